// half_duplex_timer: the down-counter of a half-duplex host (model::half_duplex::Link's cnt): the bits of a request, the answer timeout and limit, gaps, retry and settle times.
//
// What it is for
//   One counter times every wait of a request/answer host. Its state
//   machine names a wait to load (i_load = n: CLOCKS_n cycles; 0: no load)
//   or asks for a step (i_count) and reads o_zero; it never reads the count.
//   A simulator runs an `always @*` again whenever anything it reads
//   changes: a state machine that read the count would run on every cycle
//   of every wait (docs/rtl.md, "Counters in blocks of their own").
//
// Parameters
//   CLOCKS_1 .. CLOCKS_6  the waits i_load 1 .. 6 names, in i_clk cycles,
//                         each at least 1 (i_load = 7 loads CLOCKS_6)
//
// Timing (a wait of CLOCKS_n = 3: the state machine acts in the third cycle
// after the load, as the model's `if cnt == 0 { act } else { cnt -= 1 }`)
//
//   i_load    __/ n \______________
//   i_count   _______/‾‾‾‾‾‾‾\_____
//   cnt_reg   x   | 2 | 1 | 0 | 0
//   o_zero    ‾‾‾‾\_______/‾‾‾‾‾‾‾
//
// o_zero is a register of its own (cnt_reg == 0, worked out one count
// ahead), so that the state machine's decisions start from a flop rather
// than a compare of the whole count. A load wins over a step.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module half_duplex_timer #(
    parameter [31:0] CLOCKS_1 = 1, CLOCKS_2 = 1, CLOCKS_3 = 1,
    parameter [31:0] CLOCKS_4 = 1, CLOCKS_5 = 1, CLOCKS_6 = 1
) (
    input  wire       i_clk,
    input  wire       i_rst,

    /* Requests of the state machine */
    input  wire [2:0] i_load,
    input  wire       i_count,

    /* The wait is over */
    output wire       o_zero
);

// The count each wait starts from (its cycles less one), 32 bits a wait,
// indexed by i_load (entry 0 is never loaded).
localparam [255:0] LASTS = {CLOCKS_6 - 32'd1, CLOCKS_6 - 32'd1, CLOCKS_5 - 32'd1, CLOCKS_4 - 32'd1,
                            CLOCKS_3 - 32'd1, CLOCKS_2 - 32'd1, CLOCKS_1 - 32'd1, 32'd0};
localparam [31:0] MAX12 = (CLOCKS_1 > CLOCKS_2) ? CLOCKS_1 : CLOCKS_2;
localparam [31:0] MAX34 = (CLOCKS_3 > CLOCKS_4) ? CLOCKS_3 : CLOCKS_4;
localparam [31:0] MAX56 = (CLOCKS_5 > CLOCKS_6) ? CLOCKS_5 : CLOCKS_6;
localparam [31:0] MAX = (MAX12 > MAX34) ? ((MAX12 > MAX56) ? MAX12 : MAX56) : ((MAX34 > MAX56) ? MAX34 : MAX56);
localparam integer W = $clog2(MAX + 1);

initial begin
    if (CLOCKS_1 < 1 || CLOCKS_2 < 1 || CLOCKS_3 < 1 || CLOCKS_4 < 1 || CLOCKS_5 < 1 || CLOCKS_6 < 1)
        $error("half_duplex_timer: every CLOCKS_n must be at least 1");
end

reg [W-1:0] cnt_reg = 0;
reg         zero_reg = 1'b1;

assign o_zero = zero_reg;

// One clocked block and no `always @*`: the counter steps on most cycles,
// and a simulator pays for every process it wakes.
always @(posedge i_clk) begin
    if (i_load != 3'd0) begin
        cnt_reg <= LASTS[32 * i_load +: W];
        zero_reg <= LASTS[32 * i_load +: 32] == 32'd0;
    end else if (i_count) begin
        cnt_reg <= cnt_reg - 1'b1;
        zero_reg <= cnt_reg == 1;
    end

    if (i_rst) begin
        cnt_reg <= 0;
        zero_reg <= 1'b1;
    end
end

endmodule

`resetall
