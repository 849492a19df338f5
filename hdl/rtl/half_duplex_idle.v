// half_duplex_idle: the idle-line counter of a half-duplex host (model::half_duplex::Link's idle): the end of an answer, and the quiet line after a flawed one.
//
// What it is for
//   Counts the cycles the receiver has been idle. In RECV, one bit time of
//   idle line after a field ends the answer; in QUIET (after a flawed
//   answer) QUIET_BITS bit times end the wait, longer than any run of ones
//   inside an answer, so that the next request cannot land on the rest of an
//   answer whose framing was lost. The state machine asks for a clear
//   (i_clear: a field, a busy receiver, the start of RECV or QUIET) or a
//   step (i_count) and reads the two flags, never the count.
//
// Parameters
//   CLOCKS_PER_BIT  i_clk cycles per bit
//
// Outputs (registers, compared one count ahead)
//   o_answer_end  the count is CLOCKS_PER_BIT - 1: a step now completes one
//                 bit time of idle line
//   o_quiet       the count is QUIET_BITS * CLOCKS_PER_BIT - 1: a step now
//                 completes the quiet wait
//
// Timing (CLOCKS_PER_BIT = 4, the receiver idle after a field)
//
//   i_clear       _/‾\_____________________
//   i_count       ___/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\______
//   idle_reg      x  | 0 | 1 | 2 | 3 | 4
//   o_answer_end  ___________________/‾‾‾\_   (the state machine ends the answer here)
//
// The flags are registered with the count (a step sets each to the count
// before it compared with its constant less one), so that the end of an
// answer reaches the state machine and the result enables from a flop, not
// through the adder's carry chain. A clear wins over a step.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module half_duplex_idle #(
    parameter CLOCKS_PER_BIT = 8
) (
    input  wire i_clk,
    input  wire i_rst,

    /* Requests of the state machine */
    input  wire i_clear,
    input  wire i_count,

    /* The line has been idle */
    output wire o_answer_end,
    output wire o_quiet
);

// model::half_duplex::QUIET_BITS: two fields, longer than any run of ones
// inside an answer (a stop bit, a start bit turned 1, eight data ones and a
// stop bit).
localparam integer QUIET_BITS = 20;
localparam integer QUIET_CLOCKS = QUIET_BITS * CLOCKS_PER_BIT;
localparam integer W = $clog2(QUIET_CLOCKS + 1);
localparam [31:0] END_LAST_32 = CLOCKS_PER_BIT - 1;
localparam [31:0] QUIET_LAST_32 = QUIET_CLOCKS - 1;
localparam [W-1:0] END_LAST = END_LAST_32[W-1:0];
localparam [W-1:0] QUIET_LAST = QUIET_LAST_32[W-1:0];

reg [W-1:0] idle_reg = 0;
reg         answer_end_reg = 1'b0;
reg         quiet_reg = 1'b0;

assign o_answer_end = answer_end_reg;
assign o_quiet = quiet_reg;

// One clocked block and no `always @*`: the count steps on most cycles,
// and a simulator pays for every process it wakes. Each flag is its count
// compared with a constant; a count compares its value before the step.
always @(posedge i_clk) begin
    if (i_clear) begin
        idle_reg <= 0;
        answer_end_reg <= END_LAST == 0;
        quiet_reg <= QUIET_LAST == 0;
    end else if (i_count) begin
        idle_reg <= idle_reg + 1'b1;
        answer_end_reg <= idle_reg == END_LAST - 1'b1;
        quiet_reg <= idle_reg == QUIET_LAST - 1'b1;
    end

    if (i_rst) begin
        idle_reg <= 0;
        answer_end_reg <= 1'b0;
        quiet_reg <= 1'b0;
    end
end

endmodule

`resetall
