// uart_rx: 10-bit frame receiver (start 0, 8 bits LSB first, stop 1) for ESL and T-format, with an optional parity bit (SAR58K24, Modbus); twin of model::uart::Receiver.
//
// What it is for
//   The receive half of the RS-485 frame protocols: ESL at 10 Mbps (seed 000)
//   and Tamagawa T-format at 2.5 Mbps (seed 002). Connect i_rx to the RS-485
//   receiver output (asynchronous: it passes a 2-flop synchroniser first).
//   Each frame ends with one pulse: o_valid (good stop bit, o_data holds the
//   byte), o_frame_err (stop bit 0; o_data holds what was shifted in), or, for
//   a low pulse shorter than half a bit, o_start_err.
//
// Parameters
//   CLOCKS_PER_BIT  i_clk cycles per bit = f_sys / baud, 6..65535
//                   (100 MHz / 10 Mbps = 10; 100 MHz / 2.5 Mbps = 40)
//   PARITY          0 none (10-bit frames, the default), 1 odd, 2 even: a
//                   parity bit follows d7 (state PARITY_BIT, built only with
//                   parity: generate block g_parity) and the stop bit is
//                   bit 10; a wrong parity bit with a good stop bit gives
//                   o_parity_err instead of o_valid. With PARITY = 0 the
//                   machine is exactly the 10-bit one and o_parity_err stays 0.
//
// Timing (HALF = CLOCKS_PER_BIT / 2); docs/timing/uart_rx.md has the tolerance derivation
//
//   i_rx      ‾‾‾‾‾\_____ start _____X  d0  X  d1  X ... X  d7  X‾‾‾ stop ‾‾‾‾
//   state     IDLE | START (HALF) |  DATA (8 x CLOCKS_PER_BIT)  | STOP | IDLE
//   samples                      ^ mid start  ^ mid d0 ...  ^ mid d7    ^ mid stop
//   o_valid   _____________________________________________________________/‾\_
//
// Sample k (0 = start, 9 = stop) reads the pin HALF + k*CLOCKS_PER_BIT + u
// cycles after the true start edge, u in [0,1). Every sample lies inside its
// bit for a sender baud error from -(1 - 9C/(HALF+9C)) to (10C/(HALF+9C+1) - 1):
// -5.26 % .. +4.17 % at CLOCKS_PER_BIT = 10, less jitter. After a good stop
// bit the receiver is idle at mid-stop-bit, in time for a start bit that
// follows with no gap. After a framing error it waits for the line to go high.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module uart_rx #(
    parameter CLOCKS_PER_BIT = 10,
    parameter PARITY = 0
) (
    input  wire       i_clk,
    input  wire       i_rst,

    /* Line */
    input  wire       i_rx,

    /* Received data */
    output wire [7:0] o_data,
    output wire       o_valid,

    /* Status (one-cycle pulses) */
    output wire       o_frame_err,
    output wire       o_start_err,
    output wire       o_busy,
    output wire       o_parity_err
);

localparam integer CNT_W = $clog2(CLOCKS_PER_BIT);
localparam [31:0] BIT_LAST_32 = CLOCKS_PER_BIT - 1;
localparam [31:0] HALF_LAST_32 = CLOCKS_PER_BIT / 2 - 1;
localparam [CNT_W-1:0] BIT_LAST = BIT_LAST_32[CNT_W-1:0];
localparam [CNT_W-1:0] HALF_LAST = HALF_LAST_32[CNT_W-1:0];

// States: the same names and codes as model::uart::State.
localparam [2:0]
    IDLE    = 3'd0,
    START   = 3'd1,
    DATA    = 3'd2,
    STOP    = 3'd3,
    RECOVER = 3'd4,
    PARITY_BIT = 3'd5;

initial begin
    if (CLOCKS_PER_BIT < 6 || CLOCKS_PER_BIT > 65535) $error("uart_rx: CLOCKS_PER_BIT must be 6..65535");
    if (PARITY < 0 || PARITY > 2) $error("uart_rx: PARITY must be 0 (none), 1 (odd) or 2 (even)");
end

reg [2:0]       state_reg = IDLE, state_next;
reg [CNT_W-1:0] cnt_reg = 0, cnt_next;
// The bit counter steps on every cycle of a character. Icarus re-runs an always @*
// whenever anything it reads changes, so the state machine's block does not read it (it
// would re-run every cycle): it asks for a load or a step and reads cnt_zero.
reg             cnt_load_half, cnt_load_bit, cnt_dec;
wire            cnt_zero = cnt_reg == 0;
always @* begin
    if (cnt_load_half) cnt_next = HALF_LAST;
    else if (cnt_load_bit) cnt_next = BIT_LAST;
    else if (cnt_dec) cnt_next = cnt_reg - 1'b1;
    else cnt_next = cnt_reg;
end
reg [2:0]       bit_index_reg = 3'd0, bit_index_next;
reg [7:0]       shift_reg = 8'd0, shift_next;

// Two-flop synchroniser: the line comes from another device's clock.
reg rx_meta_reg = 1'b1;
reg rx_sync_reg = 1'b1;

reg [7:0] data_reg = 8'd0, data_next;
reg       valid_reg = 1'b0, valid_next;
reg       frame_err_reg = 1'b0, frame_err_next;
reg       start_err_reg = 1'b0, start_err_next;
reg       busy_reg = 1'b0, busy_next;
reg       parity_ok_reg = 1'b1, parity_ok_next;
reg       parity_err_reg = 1'b0, parity_err_next;

// The parity bit stage: what state PARITY_BIT does, built only with
// PARITY != 0, so that a receiver without parity (ESL, T-format) has no
// parity line that could never run. In PARITY_BIT the counter runs down one
// bit (g_parity asks for the step or the reload, like the state machine); at
// mid parity bit the bit is checked and the machine goes to STOP.
// Toggle coverage counts g_parity's own registers, not these: without
// parity they are constants and would count as bits that never toggle.
/* verilator coverage_off */
wire [2:0]       parity_state_next;
wire             parity_cnt_load, parity_cnt_dec;
wire             parity_ok_sampled;
/* verilator coverage_on */

generate
if (PARITY != 0) begin : g_parity
    reg [2:0]       state_n;
    reg             load_n, dec_n;
    reg             ok_n;

    // The parity bit expected after shift: odd parity makes the count of ones odd.
    localparam PARITY_ODD = (PARITY == 1);
    wire parity_expected = (^shift_reg) ^ PARITY_ODD;

    always @* begin
        state_n = state_reg;
        load_n = 1'b0;
        dec_n = 1'b0;
        ok_n = parity_ok_reg;
        if (state_reg == PARITY_BIT) begin
            if (cnt_zero) begin
                ok_n = (rx_sync_reg == parity_expected);
                state_n = STOP;
                load_n = 1'b1;
            end else begin
                dec_n = 1'b1;
            end
        end
    end

    assign parity_state_next = state_n;
    assign parity_cnt_load = load_n;
    assign parity_cnt_dec = dec_n;
    assign parity_ok_sampled = ok_n;
end else begin : g_no_parity
    // Never read: without parity the state is never PARITY_BIT.
    assign parity_state_next = IDLE;
    assign parity_cnt_load = 1'b0;
    assign parity_cnt_dec = 1'b0;
    assign parity_ok_sampled = 1'b1;
end
endgenerate

assign o_data = data_reg;
assign o_valid = valid_reg;
assign o_frame_err = frame_err_reg;
assign o_start_err = start_err_reg;
assign o_busy = busy_reg;
assign o_parity_err = parity_err_reg;

always @* begin
    state_next = state_reg;
    cnt_load_half = 1'b0;
    cnt_load_bit = 1'b0;
    cnt_dec = 1'b0;
    bit_index_next = bit_index_reg;
    shift_next = shift_reg;
    data_next = data_reg;
    busy_next = busy_reg;
    valid_next = 1'b0;
    frame_err_next = 1'b0;
    start_err_next = 1'b0;
    parity_ok_next = parity_ok_reg;
    parity_err_next = 1'b0;

    case (state_reg)
        IDLE: begin
            if (!rx_sync_reg) begin
                state_next = START;
                cnt_load_half = 1'b1;
                busy_next = 1'b1;
            end
        end
        START: begin
            if (cnt_zero) begin
                if (rx_sync_reg) begin
                    // The line went back high before mid-bit: a glitch.
                    state_next = IDLE;
                    busy_next = 1'b0;
                    start_err_next = 1'b1;
                end else begin
                    state_next = DATA;
                    cnt_load_bit = 1'b1;
                    bit_index_next = 3'd0;
                    parity_ok_next = 1'b1;
                end
            end else begin
                cnt_dec = 1'b1;
            end
        end
        DATA: begin
            if (cnt_zero) begin
                shift_next = {rx_sync_reg, shift_reg[7:1]};
                cnt_load_bit = 1'b1;
                if (bit_index_reg == 3'd7) begin
                    state_next = (PARITY == 0) ? STOP : PARITY_BIT;
                end else begin
                    bit_index_next = bit_index_reg + 1'b1;
                end
            end else begin
                cnt_dec = 1'b1;
            end
        end
        STOP: begin
            if (cnt_zero) begin
                data_next = shift_reg;
                if (rx_sync_reg) begin
                    state_next = IDLE;
                    busy_next = 1'b0;
                    valid_next = parity_ok_reg;
                    parity_err_next = !parity_ok_reg;
                end else begin
                    state_next = RECOVER;
                    frame_err_next = 1'b1;
                end
            end else begin
                cnt_dec = 1'b1;
            end
        end
        RECOVER: begin
            if (rx_sync_reg) begin
                state_next = IDLE;
                busy_next = 1'b0;
            end
        end
        // Without parity no state assigns PARITY_BIT (DATA goes to STOP), and
        // codes 6 and 7 are never entered: coverage counts reachable code
        // only. With parity, the PARITY_BIT arm's work is g_parity's, where
        // coverage counts it.
        /* verilator coverage_off */
        PARITY_BIT: begin
            state_next = parity_state_next;
            cnt_load_bit = parity_cnt_load;
            cnt_dec = parity_cnt_dec;
            parity_ok_next = parity_ok_sampled;
        end
        default: begin
            state_next = IDLE;
        end
        /* verilator coverage_on */
    endcase
end

// The register bank: every register takes its next value at each clock edge.
always @(posedge i_clk) begin
    state_reg <= state_next;
    bit_index_reg <= bit_index_next;
    shift_reg <= shift_next;
    data_reg <= data_next;
    valid_reg <= valid_next;
    frame_err_reg <= frame_err_next;
    start_err_reg <= start_err_next;
    busy_reg <= busy_next;
    parity_ok_reg <= parity_ok_next;
    parity_err_reg <= parity_err_next;
    cnt_reg <= cnt_next;
    rx_meta_reg <= i_rx;
    rx_sync_reg <= rx_meta_reg;

    if (i_rst) begin
        state_reg <= IDLE;
        cnt_reg <= 0;
        bit_index_reg <= 3'd0;
        shift_reg <= 8'd0;
        data_reg <= 8'd0;
        valid_reg <= 1'b0;
        frame_err_reg <= 1'b0;
        start_err_reg <= 1'b0;
        busy_reg <= 1'b0;
        parity_ok_reg <= 1'b1;
        parity_err_reg <= 1'b0;
        rx_meta_reg <= 1'b1;
        rx_sync_reg <= 1'b1;
    end
end

endmodule

`resetall
