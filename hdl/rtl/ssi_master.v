// ssi_master: SSI reader for absolute encoders; the cycle-for-cycle twin of the Rust model model::ssi::Master.
//
// What it is for
//   Clocks an SSI encoder (SAR58K24 manual, "Synchronous serial") and returns
//   its position. Connect o_ssi_clk to the clock driver (RS-485 C+/C-) and
//   i_ssi_data to the data receiver (D+/D-); i_ssi_data is asynchronous and
//   passes a 2-flop synchroniser first. Pulse i_start for one cycle while
//   o_busy is low; o_done pulses once per start with o_position and the
//   error pulses valid in the same cycle.
//
// Parameters (the Rust MasterConfig field of the same name in lower case)
//   BITS            data bits per read, 1..64
//   CLOCKS_PER_BIT  i_clk cycles per SSI clock period, >= 8 (odd is allowed)
//   HIGH_CLOCKS     i_clk cycles of each clock-high phase; default CLOCKS_PER_BIT - CLOCKS_PER_BIT/2
//   LOW_CLOCKS      i_clk cycles of each clock-low phase (the capture phase); default CLOCKS_PER_BIT/2
//                   HIGH_CLOCKS + LOW_CLOCKS = CLOCKS_PER_BIT. An odd period gives the high
//                   phase the extra cycle: the bit leaves the encoder at a rising edge and is
//                   captured 2 + SAMPLE_DELAY cycles after the next falling edge, so the cable's
//                   round trip is budgeted in the high phase (docs/timing/ssi.md, "Odd dividers")
//   GRAY            1: the encoder sends Gray code; o_position is binary
//   DOUBLE_READ     1: clock 2*BITS bits and flag o_err_double if the copies differ
//   WIRE_CHECK      1: clock one bit past the LSB and flag o_err_wire unless it is 0
//                   (DOUBLE_READ and WIRE_CHECK exclude each other)
//   T_CS_CLOCKS     length of the first low phase (the encoder's T_cs), >= LOW_CLOCKS
//   PAUSE_CLOCKS    clock-high pause after each read, >= the encoder's monoflop time T_m
//   SAMPLE_DELAY    cycles between a falling edge and the pin level it samples (long cables);
//                   2 + SAMPLE_DELAY must be below LOW_CLOCKS
//
// Timing (n = 3 bits, no options, H = HIGH_CLOCKS, L = LOW_CLOCKS); docs/timing/ssi.md has the full story
//
//   o_ssi_clk ‾‾‾‾‾\________/‾‾‾‾\____/‾‾‾‾\____/‾‾‾‾\____/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//   state     IDLE | LATCH  |HIGH|LOW |HIGH|LOW |HIGH|LOW | PAUSE      | IDLE
//                  |<-T_CS->|<H >|<L >|
//   data      ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾X MSB    X b1     X LSB    X 0 ...(T_m)../‾‾‾‾‾
//   capture                       ^ fall 2 + 2 + SAMPLE_DELAY (MSB)
//   o_done    ___________________________________________/‾\__________________
//
// A start while the synchronised data line is low (encoder still in its
// monoflop time, or the line stuck low) is refused: o_done and o_err_idle
// pulse in the next cycle and the clock does not move.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module ssi_master #(
    parameter BITS = 12,
    parameter CLOCKS_PER_BIT = 200,
    parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2,
    parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2,
    parameter GRAY = 0,
    parameter DOUBLE_READ = 0,
    parameter WIRE_CHECK = 0,
    parameter T_CS_CLOCKS = 200,
    parameter PAUSE_CLOCKS = 25500,
    parameter SAMPLE_DELAY = 0
) (
    input  wire            i_clk,
    input  wire            i_rst,

    /* Host interface */
    input  wire            i_start,
    output wire            o_busy,
    output wire            o_done,
    output wire [BITS-1:0] o_position,

    /* Status (one-cycle pulses with o_done) */
    output wire            o_err_idle,
    output wire            o_err_double,
    output wire            o_err_wire,

    /* SSI line */
    output wire            o_ssi_clk,
    input  wire            i_ssi_data
);

localparam integer PHASE_MAX = (HIGH_CLOCKS > LOW_CLOCKS) ? HIGH_CLOCKS : LOW_CLOCKS; // the longer phase
localparam integer SAMPLED = BITS * ((DOUBLE_READ != 0) ? 2 : 1) + ((WIRE_CHECK != 0) ? 1 : 0);
localparam integer CNT_MAX = (PAUSE_CLOCKS > T_CS_CLOCKS) ? ((PAUSE_CLOCKS > PHASE_MAX) ? PAUSE_CLOCKS : PHASE_MAX)
                                                         : ((T_CS_CLOCKS > PHASE_MAX) ? T_CS_CLOCKS : PHASE_MAX);
localparam integer CNT_W = $clog2(CNT_MAX + 1);

// 32-bit forms of the counter constants, cut to the counter's width below.
localparam [31:0] HIGH_LAST_32 = HIGH_CLOCKS - 1;
localparam [31:0] LOW_LAST_32 = LOW_CLOCKS - 1;
localparam [31:0] T_CS_LAST_32 = T_CS_CLOCKS - 1;
localparam [31:0] PAUSE_LAST_32 = PAUSE_CLOCKS - 1;
// The low-phase count at which the synchronised level is the pin level
// SAMPLE_DELAY cycles after the falling edge (2 cycles of synchroniser).
localparam [31:0] CAPTURE_AT_32 = LOW_CLOCKS - 2 - SAMPLE_DELAY;
localparam [31:0] SAMPLED_32 = SAMPLED;
localparam [31:0] BITS_32 = BITS;

localparam [CNT_W-1:0] HIGH_LAST = HIGH_LAST_32[CNT_W-1:0];
localparam [CNT_W-1:0] LOW_LAST = LOW_LAST_32[CNT_W-1:0];
localparam [CNT_W-1:0] T_CS_LAST = T_CS_LAST_32[CNT_W-1:0];
localparam [CNT_W-1:0] PAUSE_LAST = PAUSE_LAST_32[CNT_W-1:0];
localparam [CNT_W-1:0] CAPTURE_AT = CAPTURE_AT_32[CNT_W-1:0];
localparam [7:0] SAMPLED_BITS = SAMPLED_32[7:0];
localparam [7:0] VALUE_BITS = BITS_32[7:0];

// States: the same names and codes as model::ssi::State.
localparam [2:0]
    IDLE  = 3'd0,
    LATCH = 3'd1,
    HIGH  = 3'd2,
    LOW   = 3'd3,
    PAUSE = 3'd4;

initial begin
    if (BITS < 1 || BITS > 64) $error("ssi_master: BITS must be 1..64");
    if (CLOCKS_PER_BIT < 8) $error("ssi_master: CLOCKS_PER_BIT must be >= 8");
    if (HIGH_CLOCKS < 1 || LOW_CLOCKS < 1 || HIGH_CLOCKS + LOW_CLOCKS != CLOCKS_PER_BIT)
        $error("ssi_master: HIGH_CLOCKS + LOW_CLOCKS must be CLOCKS_PER_BIT");
    if (2 + SAMPLE_DELAY > LOW_CLOCKS - 1) $error("ssi_master: 2 + SAMPLE_DELAY must be below LOW_CLOCKS");
    if (T_CS_CLOCKS < LOW_CLOCKS) $error("ssi_master: T_CS_CLOCKS must be at least LOW_CLOCKS");
    if ((DOUBLE_READ != 0) && (WIRE_CHECK != 0)) $error("ssi_master: DOUBLE_READ and WIRE_CHECK exclude each other");
end

reg [2:0]       state_reg = IDLE, state_next;
reg [CNT_W-1:0] cnt_reg = 0, cnt_next;
// The phase counter steps on every cycle of a read and of the pause. Icarus re-runs an
// always @* whenever anything it reads changes, so the state machine's block does not
// read it (it would re-run every cycle): it asks for a load or a step and reads cnt_zero
// and cnt_capture. A load names its value by a code (the value stays here), not a new
// counter-wide signal whose top bits would never toggle.
localparam [1:0] LOAD_T_CS = 2'd0, LOAD_HIGH = 2'd1, LOAD_LOW = 2'd2, LOAD_PAUSE = 2'd3;
reg             cnt_load, cnt_dec;
reg [1:0]       cnt_load_sel;
wire            cnt_zero = cnt_reg == 0;
wire            cnt_capture = cnt_reg == CAPTURE_AT;
always @* begin
    if (cnt_load) begin
        case (cnt_load_sel)
            LOAD_T_CS: cnt_next = T_CS_LAST;
            LOAD_HIGH: cnt_next = HIGH_LAST;
            LOAD_LOW: cnt_next = LOW_LAST;
            default: cnt_next = PAUSE_LAST; // LOAD_PAUSE
        endcase
    end else if (cnt_dec) begin
        cnt_next = cnt_reg - 1'b1;
    end else begin
        cnt_next = cnt_reg;
    end
end
reg [7:0]       bit_count_reg = 0, bit_count_next;

// Two-flop synchroniser: i_ssi_data comes from the encoder's clock domain
// (our clock, delayed by the cable by an unknown fraction of a cycle).
reg data_meta_reg = 1'b1;
reg data_sync_reg = 1'b1;

// Serial Gray decoding: each binary bit is the previous binary bit XOR the
// Gray bit, MSB first, so no wide XOR tree is needed at the end.
reg            gray_last_reg = 1'b0, gray_last_next;
reg [BITS-1:0] data_reg = 0, data_next;
reg [BITS-1:0] copy_reg = 0, copy_next;
reg            wire_bad_reg = 1'b0, wire_bad_next;

reg            ssi_clk_reg = 1'b1, ssi_clk_next;
reg            busy_reg = 1'b0, busy_next;
reg            done_reg = 1'b0, done_next;
reg [BITS-1:0] position_reg = 0, position_next;
reg            err_idle_reg = 1'b0, err_idle_next;
reg            err_double_reg = 1'b0, err_double_next;
reg            err_wire_reg = 1'b0, err_wire_next;

assign o_ssi_clk = ssi_clk_reg;
assign o_busy = busy_reg;
assign o_done = done_reg;
assign o_position = position_reg;
assign o_err_idle = err_idle_reg;
assign o_err_double = err_double_reg;
assign o_err_wire = err_wire_reg;

// The bit captured in this cycle, decoded from Gray if need be.
wire capture_gray_restart = (bit_count_reg == 8'd0) || (bit_count_reg == VALUE_BITS);
wire capture_binary = (GRAY != 0) ? ((capture_gray_restart ? 1'b0 : gray_last_reg) ^ data_sync_reg) : data_sync_reg;
// One bit wider than the value so that BITS = 1 needs no special case; the
// top bit (the one shifted out) is dropped on purpose.
/* verilator lint_off UNUSEDSIGNAL */
wire [BITS:0] data_shifted = {data_reg, capture_binary};
wire [BITS:0] copy_shifted = {copy_reg, capture_binary};
/* verilator lint_on UNUSEDSIGNAL */

always @* begin
    state_next = state_reg;
    cnt_load = 1'b0;
    cnt_load_sel = LOAD_T_CS;
    cnt_dec = 1'b0;
    bit_count_next = bit_count_reg;
    gray_last_next = gray_last_reg;
    data_next = data_reg;
    copy_next = copy_reg;
    wire_bad_next = wire_bad_reg;
    ssi_clk_next = ssi_clk_reg;
    busy_next = busy_reg;
    position_next = position_reg;
    done_next = 1'b0;
    err_idle_next = 1'b0;
    err_double_next = 1'b0;
    err_wire_next = 1'b0;

    case (state_reg)
        IDLE: begin
            if (i_start) begin
                if (data_sync_reg) begin
                    state_next = LATCH;
                    cnt_load = 1'b1;
                    cnt_load_sel = LOAD_T_CS;
                    ssi_clk_next = 1'b0;
                    busy_next = 1'b1;
                    bit_count_next = 8'd0;
                    data_next = 0;
                    copy_next = 0;
                    wire_bad_next = 1'b0;
                    gray_last_next = 1'b0;
                end else begin
                    done_next = 1'b1;
                    err_idle_next = 1'b1;
                end
            end
        end
        LATCH, HIGH: begin
            if (cnt_zero) begin
                state_next = (state_reg == LATCH) ? HIGH : LOW;
                ssi_clk_next = (state_reg == LATCH);
                cnt_load = 1'b1;
                cnt_load_sel = (state_reg == LATCH) ? LOAD_HIGH : LOAD_LOW;
            end else begin
                cnt_dec = 1'b1;
            end
        end
        LOW: begin
            if (cnt_capture) begin
                if (bit_count_reg < VALUE_BITS) begin
                    data_next = data_shifted[BITS-1:0];
                    gray_last_next = capture_binary;
                end else if (DOUBLE_READ != 0) begin
                    copy_next = copy_shifted[BITS-1:0];
                    gray_last_next = capture_binary;
                end else begin
                    wire_bad_next = data_sync_reg;
                end
                bit_count_next = bit_count_reg + 1'b1;
            end
            if (cnt_zero) begin
                ssi_clk_next = 1'b1;
                if (bit_count_next == SAMPLED_BITS) begin
                    state_next = PAUSE;
                    cnt_load = 1'b1;
                    cnt_load_sel = LOAD_PAUSE;
                    done_next = 1'b1;
                    position_next = data_next;
                    err_double_next = (DOUBLE_READ != 0) && (data_next != copy_next);
                    err_wire_next = wire_bad_next;
                end else begin
                    state_next = HIGH;
                    cnt_load = 1'b1;
                    cnt_load_sel = LOAD_HIGH;
                end
            end else begin
                cnt_dec = 1'b1;
            end
        end
        PAUSE: begin
            if (cnt_zero) begin
                state_next = IDLE;
                busy_next = 1'b0;
            end else begin
                cnt_dec = 1'b1;
            end
        end
        // Codes 5 to 7 are never entered (every assignment above names a
        // state); coverage counts reachable code only.
        /* verilator coverage_off */
        default: begin
            state_next = IDLE;
        end
        /* verilator coverage_on */
    endcase
end

// The register bank: every register takes its next value at each clock edge.
always @(posedge i_clk) begin
    state_reg <= state_next;
    bit_count_reg <= bit_count_next;
    gray_last_reg <= gray_last_next;
    data_reg <= data_next;
    copy_reg <= copy_next;
    wire_bad_reg <= wire_bad_next;
    ssi_clk_reg <= ssi_clk_next;
    busy_reg <= busy_next;
    done_reg <= done_next;
    position_reg <= position_next;
    err_idle_reg <= err_idle_next;
    err_double_reg <= err_double_next;
    err_wire_reg <= err_wire_next;
    cnt_reg <= cnt_next;
    data_meta_reg <= i_ssi_data;
    data_sync_reg <= data_meta_reg;

    if (i_rst) begin
        state_reg <= IDLE;
        cnt_reg <= 0;
        bit_count_reg <= 8'd0;
        gray_last_reg <= 1'b0;
        data_reg <= 0;
        copy_reg <= 0;
        wire_bad_reg <= 1'b0;
        ssi_clk_reg <= 1'b1;
        busy_reg <= 1'b0;
        done_reg <= 1'b0;
        position_reg <= 0;
        err_idle_reg <= 1'b0;
        err_double_reg <= 1'b0;
        err_wire_reg <= 1'b0;
        data_meta_reg <= 1'b1;
        data_sync_reg <= 1'b1;
    end
end

endmodule

`resetall
