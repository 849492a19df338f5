// biss_master: BiSS-C master for a chain of 1 to 3 slaves; the cycle-for-cycle twin of the Rust model model::biss::Master.
//
// What it is for
//   Clocks BiSS-C slaves (SAR58K24 manual, "Synchronous serial", BiSS-C) and
//   returns each slave's data, nE/nW and CRC status, measures the line delay
//   from every frame's ack, and runs register reads and writes over the
//   BiSS-C control frame (one CDM bit per frame out, one CDS bit back).
//   Connect o_ma to the MA driver (RS-485 MA+/MA-) and i_slo to the SLO
//   receiver; i_slo is asynchronous and passes a 2-flop synchroniser first.
//   Pulse i_start for one cycle while o_busy is low. Each slave's result
//   appears with a one-cycle o_slave_valid pulse (slave 0 first); o_done
//   pulses once per start with the frame's error pulses. A register access is
//   one host operation: pulse i_reg_start (with i_reg_write/_id/_addr/_wdata)
//   while o_reg_busy is low and the core runs the frames itself, back to
//   back (14 frames of CDM = 0, then the 33 frames of the control frame),
//   each with its o_slave_valid results and o_done; o_reg_done pulses with
//   o_done of the last one, with o_reg_rdata, o_reg_crc_err and o_reg_err.
//   A BiSS-C command (CTS = 0) is the same kind of operation: pulse
//   i_cmd_start with i_cmd_ids (slave-select bits, 0 = broadcast) and
//   i_cmd_code; 14 sync frames and 19 control frames; o_reg_done/o_reg_err
//   report it (i_reg_start wins a tie).
//
// Parameters (the Rust MasterConfig field of the same name in lower case;
// per-slave values packed 8 bits each, slave 0 in bits 7..0)
//   SLAVES           slaves in the chain, 1..3
//   SLAVE_BITS       data bits per slave, 1..64
//   SLAVE_CRC_WIDTH  CRC width per slave, 1..8 (BiSS-C: 6)
//   SLAVE_CRC_POLY   CRC polynomial per slave without the top term (BiSS-C x^6 + x + 1: 8'h03)
//   CLOCKS_PER_BIT   i_clk cycles per MA period, 8..4096, odd allowed (10 MHz MA needs i_clk >= 80 MHz)
//   HIGH_CLOCKS      i_clk cycles of each MA high phase; default CLOCKS_PER_BIT - CLOCKS_PER_BIT/2
//   LOW_CLOCKS       i_clk cycles of each MA low phase; default CLOCKS_PER_BIT/2
//                    HIGH_CLOCKS + LOW_CLOCKS = CLOCKS_PER_BIT. An odd period gives the high
//                    phase the extra cycle: bits are sampled by the measured delay whatever
//                    the split, frame ends and gaps are high levels (TMASH), and the seed's
//                    TMASH/TMASL > 25 ns then bind the shorter low phase (docs/timing/biss.md)
//   MAX_DELAY        longest edge-2-to-ack delay compensated, cycles, 1..65535
//   TIMEOUT_CLOCKS   longest wait for the start bit, for SLO low/high after the
//                    last clock and for a late ack, cycles (>= 2 * CLOCKS_PER_BIT)
//   CAL_FRAMES       start-up frames whose mean delay is used afterwards: 1, 2, 4, 8, 16
//   DELAY_TOL        largest departure from the mean still sampled by it, cycles (< CLOCKS_PER_BIT / 2)
//
// Timing (one slave, H = CLOCKS_PER_BIT/2, the middle of a bit cell, rounded down;
// MA is high HIGH_CLOCKS and low LOW_CLOCKS cycles); docs/timing/biss.md has the full story
//
//   o_ma   ‾‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\_ ... _/‾‾\__/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//   edge         1     2     3     4     5     6     7           n   (CDM = 0: MA stops high)
//                latch ack
//   SLO    ‾‾‾‾‾‾‾‾‾‾‾‾\_________/‾‾‾‾‾X CDS X d1  X d0  X nE ...X c0 X 0 ... 0 (t_timeout) /‾‾‾
//                      |<-t_busy->| start
//   sample             ^ack  (o_delay = cycles from edge 2 to ack at the synchroniser)
//                         ^ack + H + k * CLOCKS_PER_BIT, k = 1, 2, ... (cell middles)
//   state  IDLE| ACK      | START    | CDS | DATA      |ERR|WARN| CRC  | STOP | TIMEOUT | IDLE
//   o_slave_valid                                                  /‾\ (per slave)
//   o_done                                                                             /‾\
//
// Line-delay compensation: the delay from the second rising MA edge to the ack
// (SLO low at the synchroniser output) is measured in every frame (o_delay).
// The first CAL_FRAMES frames are sampled H + k * CLOCKS_PER_BIT cycles after
// their own ack and their delays averaged (o_delay_mean); later frames are
// sampled as if their ack had come at the mean, which takes the jitter of the
// ack edge out, unless their delay departs from the mean by more than
// DELAY_TOL: then they are sampled by their own ack and flagged (o_err_drift).
// Any cable up to MAX_DELAY is read in the middle of its bit cells. MA keeps running until the
// last CRC bit is in, then stops at the first phase boundary where it
// equals !CDM (the BiSS-C control bit is the inverted MA level in the timeout); a frame that held MA low (CDM = 1) raises it HIGH_CLOCKS cycles before o_done, so every MA high phase lasts at least HIGH_CLOCKS + 1 cycles (seed: TMASH > 25 ns).
// Errors: o_err_line (SLO low at start, refused), o_err_ack (no ack: slave
// absent, line open or stuck high), o_err_delay (ack later than MAX_DELAY),
// o_err_start (no start bit within TIMEOUT_CLOCKS), o_err_timeout (SLO not
// released); per slave o_crc_err.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module biss_master #(
    parameter SLAVES = 1,
    parameter SLAVE_BITS = 16,
    parameter SLAVE_CRC_WIDTH = 6,
    parameter SLAVE_CRC_POLY = 3,
    parameter CLOCKS_PER_BIT = 8,
    parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2,
    parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2,
    parameter MAX_DELAY = 160,
    parameter TIMEOUT_CLOCKS = 3200,
    parameter CAL_FRAMES = 4,
    parameter DELAY_TOL = 1
) (
    input  wire                  i_clk,
    input  wire                  i_rst,

    /* Host interface: frames */
    input  wire                  i_start,
    output wire                  o_busy,
    output wire                  o_done,
    output wire                  o_err_line,
    output wire                  o_err_ack,
    output wire                  o_err_delay,
    output wire                  o_err_start,
    output wire                  o_err_timeout,
    output wire [15:0]           o_delay,
    output wire [15:0]           o_delay_mean,
    output wire                  o_err_drift,

    /* Host interface: per-slave results, one slave at a time */
    output wire                  o_slave_valid,
    output wire [1:0]            o_slave_index,
    output wire [DATA_W-1:0]     o_data,
    output wire                  o_crc_err,
    output wire                  o_error,
    output wire                  o_warning,
    output wire                  o_cds,

    /* Host interface: register access over the control frame */
    input  wire                  i_reg_start,
    input  wire                  i_reg_write,
    input  wire [2:0]            i_reg_id,
    input  wire [6:0]            i_reg_addr,
    input  wire [7:0]            i_reg_wdata,
    output wire                  o_reg_busy,
    output wire                  o_reg_done,
    output wire                  o_reg_err,
    output wire [7:0]            o_reg_rdata,
    output wire                  o_reg_crc_err,

    /* Host interface: BiSS-C commands over the control frame */
    input  wire                  i_cmd_start,
    input  wire [7:0]            i_cmd_ids,
    input  wire [1:0]            i_cmd_code,

    /* BiSS line */
    output wire                  o_ma,
    input  wire                  i_slo
);

// The per-slave fields of the packed parameters, and the widest slave's data
// width, as plain constant expressions (no constant functions: Verilator's
// coverage would count a function evaluated at elaboration as uncovered code).
localparam integer BITS0 = SLAVE_BITS & 255;
localparam integer BITS1 = (SLAVE_BITS >> 8) & 255;
localparam integer BITS2 = (SLAVE_BITS >> 16) & 255;
localparam integer BITS1_USED = (SLAVES > 1) ? BITS1 : 1;
localparam integer BITS2_USED = (SLAVES > 2) ? BITS2 : 1;
localparam integer BITS01_MAX = (BITS1_USED > BITS0) ? BITS1_USED : BITS0;
localparam integer BITS012_MAX = (BITS2_USED > BITS01_MAX) ? BITS2_USED : BITS01_MAX;
localparam integer DATA_W = (BITS012_MAX > 1) ? BITS012_MAX : 1;
localparam integer HALF = CLOCKS_PER_BIT / 2; // the middle of a bit cell (rounded down), not an MA phase
localparam integer SMP_W = $clog2(2 * CLOCKS_PER_BIT);
localparam integer CAL_SHIFT = $clog2(CAL_FRAMES);
localparam integer CNT_W = $clog2(TIMEOUT_CLOCKS + 3);

localparam [31:0] HIGH_LAST_32 = HIGH_CLOCKS - 1;
localparam [31:0] LOW_LAST_32 = LOW_CLOCKS - 1;
localparam [31:0] FIRST_SAMPLE_32 = HALF + CLOCKS_PER_BIT - 1;
localparam [31:0] PERIOD_LAST_32 = CLOCKS_PER_BIT - 1;
localparam [31:0] TIMEOUT_32 = TIMEOUT_CLOCKS;
localparam [31:0] MAX_DELAY_32 = MAX_DELAY;
localparam [SMP_W-1:0] HIGH_LAST = HIGH_LAST_32[SMP_W-1:0];
localparam [SMP_W-1:0] LOW_LAST = LOW_LAST_32[SMP_W-1:0];
localparam [SMP_W-1:0] FIRST_SAMPLE = FIRST_SAMPLE_32[SMP_W-1:0];
localparam [SMP_W-1:0] PERIOD_LAST = PERIOD_LAST_32[SMP_W-1:0];
localparam [CNT_W-1:0] TIMEOUT_CNT = TIMEOUT_32[CNT_W-1:0];
localparam [15:0] MAX_DELAY_16 = MAX_DELAY_32[15:0];
localparam [15:0] FIRST_SAMPLE_16 = FIRST_SAMPLE_32[15:0];
localparam [31:0] CAL_FRAMES_32 = CAL_FRAMES;
localparam [4:0] CAL_FRAMES_5 = CAL_FRAMES_32[4:0];
localparam [31:0] DELAY_TOL_32 = DELAY_TOL;
localparam [15:0] DELAY_TOL_16 = DELAY_TOL_32[15:0];
localparam [31:0] LAST_SLAVE_32 = SLAVES - 1;
localparam [1:0] LAST_SLAVE = LAST_SLAVE_32[1:0];
localparam [31:0] BITS0_32 = BITS0;
localparam [31:0] BITS1_32 = BITS1;
localparam [31:0] BITS2_32 = BITS2;
localparam [31:0] CRCW0_32 = SLAVE_CRC_WIDTH & 255;
localparam [31:0] CRCW1_32 = (SLAVE_CRC_WIDTH >> 8) & 255;
localparam [31:0] CRCW2_32 = (SLAVE_CRC_WIDTH >> 16) & 255;
localparam [31:0] POLY0_32 = SLAVE_CRC_POLY & 255;
localparam [31:0] POLY1_32 = (SLAVE_CRC_POLY >> 8) & 255;
localparam [31:0] POLY2_32 = (SLAVE_CRC_POLY >> 16) & 255;

// Control frame (model::biss::control): 14 zeros before a start bit.
localparam [3:0] SYNC_ZEROS = 4'd14;

// States: the same names and codes as model::biss::State.
localparam [3:0]
    IDLE    = 4'd0,
    ACK     = 4'd1,
    START   = 4'd2,
    CDS     = 4'd3,
    DATA    = 4'd4,
    ERR     = 4'd5,
    WARN    = 4'd6,
    CRC     = 4'd7,
    STOP    = 4'd8,
    TIMEOUT = 4'd9,
    NOACK   = 4'd10;

initial begin
    if (SLAVES < 1 || SLAVES > 3) $error("biss_master: SLAVES must be 1..3");
    if (CLOCKS_PER_BIT < 8 || CLOCKS_PER_BIT > 4096) $error("biss_master: CLOCKS_PER_BIT must be 8..4096");
    if (HIGH_CLOCKS < 1 || LOW_CLOCKS < 1 || HIGH_CLOCKS + LOW_CLOCKS != CLOCKS_PER_BIT)
        $error("biss_master: HIGH_CLOCKS + LOW_CLOCKS must be CLOCKS_PER_BIT");
    if (MAX_DELAY < 1 || MAX_DELAY > 65535) $error("biss_master: MAX_DELAY must be 1..65535");
    if (TIMEOUT_CLOCKS < 2 * CLOCKS_PER_BIT) $error("biss_master: TIMEOUT_CLOCKS must be >= 2 * CLOCKS_PER_BIT");
    if (CAL_FRAMES != 1 && CAL_FRAMES != 2 && CAL_FRAMES != 4 && CAL_FRAMES != 8 && CAL_FRAMES != 16) $error("biss_master: CAL_FRAMES must be 1, 2, 4, 8 or 16");
    if (DELAY_TOL >= HALF) $error("biss_master: DELAY_TOL must be < CLOCKS_PER_BIT / 2");
end

// Per-slave constants of the slave being decoded (a mux over parameters).
reg [1:0] slave_reg = 2'd0, slave_next;
wire [6:0] cur_bits = (slave_reg == 2'd0) ? BITS0_32[6:0] : (slave_reg == 2'd1) ? BITS1_32[6:0] : BITS2_32[6:0];
wire [3:0] cur_crc_w = (slave_reg == 2'd0) ? CRCW0_32[3:0] : (slave_reg == 2'd1) ? CRCW1_32[3:0] : CRCW2_32[3:0];
wire [7:0] cur_poly = (slave_reg == 2'd0) ? POLY0_32[7:0] : (slave_reg == 2'd1) ? POLY1_32[7:0] : POLY2_32[7:0];
wire [7:0] cur_mask = (8'hFF >> (4'd8 - cur_crc_w));

reg [3:0]        state_reg = IDLE, state_next;
reg [CNT_W-1:0]  cnt_reg = 0, cnt_next;
// The timeout counter steps on every cycle of a wait (for the start bit, a late ack, SLO's
// release). Icarus re-runs an always @* whenever anything it reads changes, so the state
// machine's block does not read it (it would re-run every cycle): it asks for a clear or a
// step and reads the two comparisons below.
reg              cnt_clear, cnt_inc;
wire             cnt_at_timeout = cnt_reg == TIMEOUT_CNT;
wire             cnt_timed_out = cnt_reg >= TIMEOUT_CNT;
always @* begin
    if (cnt_clear) cnt_next = 0;
    else if (cnt_inc) cnt_next = cnt_reg + 1'b1;
    else cnt_next = cnt_reg;
end
reg [15:0]       delay_cnt_reg = 16'd0, delay_cnt_next;
reg [SMP_W-1:0]  smp_cnt_reg = 0, smp_cnt_next;

// MA generator: high for HIGH_CLOCKS and low for LOW_CLOCKS cycles while running;
// a stop request takes effect at the first phase boundary where MA equals its level.
reg              ma_reg = 1'b1, ma_next;
reg [SMP_W-1:0]  ma_cnt_reg = 0, ma_cnt_next;
// ma_cnt steps on every cycle of a phase: outside the state machine's block for the same
// reason as cnt. The block reads ma_cnt_zero and asks for a step or a load, naming the
// phase to load (high or low) rather than a new value signal.
reg              ma_cnt_load, ma_cnt_load_high, ma_cnt_dec;
wire             ma_cnt_zero = ma_cnt_reg == 0;
always @* begin
    if (ma_cnt_load) ma_cnt_next = ma_cnt_load_high ? HIGH_LAST : LOW_LAST;
    else if (ma_cnt_dec) ma_cnt_next = ma_cnt_reg - 1'b1;
    else ma_cnt_next = ma_cnt_reg;
end
reg              ma_run_reg = 1'b0, ma_run_next;
reg [1:0]        ma_edges_reg = 2'd0, ma_edges_next;
reg              ma_stop_reg = 1'b0, ma_stop_next;
reg              ma_stop_level_reg = 1'b1, ma_stop_level_next;

// Two-flop synchroniser: SLO comes back through the cable with an unknown delay.
reg slo_meta_reg = 1'b1;
reg slo_sync_reg = 1'b1;

reg [6:0]        bit_cnt_reg = 7'd0, bit_cnt_next;
reg [DATA_W-1:0] data_reg = 0, data_next;
// Bit-serial CRC of the current slave (stage i = bit i), preset 0 at its CDS bit.
reg [7:0]        crc_reg = 8'd0, crc_next;
reg              crc_bad_reg = 1'b0, crc_bad_next;
reg              nerr_reg = 1'b1, nerr_next;
reg              nwarn_reg = 1'b1, nwarn_next;
reg              cds_reg = 1'b0, cds_next;
reg              e_delay_reg = 1'b0, e_delay_next;
reg              e_start_reg = 1'b0, e_start_next;
// Start-up calibration: frames measured, their delay sum, the mean.
reg              e_drift_reg = 1'b0, e_drift_next;
reg [4:0]        cal_cnt_reg = 5'd0, cal_cnt_next;
reg [19:0]       cal_sum_reg = 20'd0, cal_sum_next;
reg [15:0]       delay_mean_reg = 16'd0, delay_mean_next;

// Control frame: the CDS bits (AND) and CRC status (OR) of the selected
// slaves in this frame, whether any was selected,
// frame, the CDM bit this frame carries, the count of CDM zeros sent.
reg              frame_cds_reg = 1'b0, frame_cds_next;
reg              frame_crc_bad_reg = 1'b0, frame_crc_bad_next;
reg              frame_sel_reg = 1'b0, frame_sel_next;
reg              acc_cmd_reg = 1'b0, acc_cmd_next;
reg [7:0]        acc_ids_reg = 8'd0, acc_ids_next;
reg [1:0]        acc_code_reg = 2'd0, acc_code_next;
reg              cdm_reg = 1'b0, cdm_next;
reg [3:0]        zeros_reg = 4'd0, zeros_next;
reg              reg_pending_reg = 1'b0, reg_pending_next;
reg              ctl_active_reg = 1'b0, ctl_active_next;
reg [5:0]        ctl_k_reg = 6'd0, ctl_k_next;
reg              acc_write_reg = 1'b0, acc_write_next;
reg [2:0]        acc_id_reg = 3'd0, acc_id_next;
reg [6:0]        acc_addr_reg = 7'd0, acc_addr_next;
reg [7:0]        acc_wdata_reg = 8'd0, acc_wdata_next;
reg              reg_bad_reg = 1'b0, reg_bad_next;
reg [7:0]        rdata_reg = 8'd0, rdata_next;
// CRC-4 x^4 + x + 1 (model::crc::BISS_CTRL_CRC4): sent bits, received bits.
reg [3:0]        crc4_tx_reg = 4'd0, crc4_tx_next;
reg [3:0]        crc4_rx_reg = 4'd0, crc4_rx_next;

reg              busy_reg = 1'b0, busy_next;
reg              done_reg = 1'b0, done_next;
reg              err_line_reg = 1'b0, err_line_next;
reg              err_ack_reg = 1'b0, err_ack_next;
reg              err_delay_reg = 1'b0, err_delay_next;
reg              err_start_reg = 1'b0, err_start_next;
reg              err_timeout_reg = 1'b0, err_timeout_next;
reg              err_drift_reg = 1'b0, err_drift_next;
reg [15:0]       delay_reg = 16'd0, delay_next;
reg              slave_valid_reg = 1'b0, slave_valid_next;
reg [1:0]        slave_index_reg = 2'd0, slave_index_next;
reg [DATA_W-1:0] out_data_reg = 0, out_data_next;
reg              crc_err_reg = 1'b0, crc_err_next;
reg              error_reg = 1'b0, error_next;
reg              warning_reg = 1'b0, warning_next;
reg              out_cds_reg = 1'b0, out_cds_next;
reg              reg_busy_reg = 1'b0, reg_busy_next;
reg              reg_done_reg = 1'b0, reg_done_next;
reg              reg_err_reg = 1'b0, reg_err_next;
reg [7:0]        reg_rdata_reg = 8'd0, reg_rdata_next;
reg              reg_crc_err_reg = 1'b0, reg_crc_err_next;

assign o_ma = ma_reg;
assign o_busy = busy_reg;
assign o_done = done_reg;
assign o_err_line = err_line_reg;
assign o_err_ack = err_ack_reg;
assign o_err_delay = err_delay_reg;
assign o_err_start = err_start_reg;
assign o_err_timeout = err_timeout_reg;
assign o_delay = delay_reg;
assign o_delay_mean = delay_mean_reg;
assign o_err_drift = err_drift_reg;
assign o_slave_valid = slave_valid_reg;
assign o_slave_index = slave_index_reg;
assign o_data = out_data_reg;
assign o_crc_err = crc_err_reg;
assign o_error = error_reg;
assign o_warning = warning_reg;
assign o_cds = out_cds_reg;
assign o_reg_busy = reg_busy_reg;
assign o_reg_done = reg_done_reg;
assign o_reg_err = reg_err_reg;
assign o_reg_rdata = reg_rdata_reg;
assign o_reg_crc_err = reg_crc_err_reg;

// One wider than the data so that a 1-bit slave needs no special case; the
// bit shifted out is dropped on purpose.
/* verilator lint_off UNUSEDSIGNAL */
wire [DATA_W:0] data_shifted = {data_reg, slo_sync_reg};
/* verilator lint_on UNUSEDSIGNAL */

// Calibration arithmetic: the running sum and its mean; after calibration
// the departure of this frame's delay (delay_reg, latched at the ack) from the
// mean, and the sample counter of an ack at the mean. For timing these take
// the two cycles after the ack (check, then apply), where the model does it
// all at the ack: the first sample is more than two cycles away, so the
// sample times and every output are the same.
/* verilator lint_off UNUSEDSIGNAL */
wire [19:0] cal_sum_plus = cal_sum_reg + {4'd0, delay_cnt_reg};
wire [19:0] cal_mean_wide = cal_sum_plus >> CAL_SHIFT;
wire [15:0] smp_mean_wide = FIRST_SAMPLE_16 - 16'd2 + delay_mean_reg - delay_reg;
/* verilator lint_on UNUSEDSIGNAL */
wire [15:0] delay_dev = (delay_reg >= delay_mean_reg) ? (delay_reg - delay_mean_reg) : (delay_mean_reg - delay_reg);
reg              cal_chk_reg = 1'b0, cal_chk_next;
reg              cal_apply_reg = 1'b0;
reg              cal_ok_reg = 1'b0, cal_ok_next;
reg [SMP_W-1:0]  cal_smp_reg = 0, cal_smp_next;

wire sampling = (state_reg == START) || (state_reg == CDS) || (state_reg == DATA) ||
                (state_reg == ERR) || (state_reg == WARN) || (state_reg == CRC);
wire sample = sampling && (smp_cnt_reg == 0);
// Bit sampling: once per MA period, in the middle of each arriving cell. smp_cnt steps on
// every cycle of a reception, so it is stepped here, outside the state machine's block
// (see cnt), which reads only sample and asks for a load: the first sample after the ack
// or, with smp_cnt_load_mean, the calibrated one.
reg              smp_cnt_load, smp_cnt_load_mean;
always @* begin
    smp_cnt_next = smp_cnt_reg;
    if (sampling) smp_cnt_next = (smp_cnt_reg == 0) ? PERIOD_LAST : smp_cnt_reg - 1'b1;
    if (smp_cnt_load) smp_cnt_next = smp_cnt_load_mean ? cal_smp_reg : FIRST_SAMPLE;
end
wire b = slo_sync_reg;
// The top stage of the current slave's CRC.
wire [7:0] cur_top = 8'h80 >> (4'd8 - cur_crc_w);
wire crc_msb = |(crc_reg & cur_top);

// One push of bit d into the CRC of the current slave.
function [7:0] crc_push(input [7:0] reg_value, input d, input [7:0] top, input [7:0] poly, input [7:0] mask);
    reg fb;
    begin
        fb = (|(reg_value & top)) ^ d;
        crc_push = ((reg_value << 1) & mask) ^ (fb ? poly : 8'd0);
    end
endfunction

// The CDM bit sources of control index k_next (ID MSB first at k = 2, ADR at 5, write data at 19).
wire [5:0] k_next = ctl_k_reg + 6'd1;
/* verilator lint_off UNUSEDSIGNAL */
wire [2:0] id_shifted = acc_id_reg >> (3'd4 - k_next[2:0]);
wire [6:0] addr_shifted = acc_addr_reg >> (4'd11 - k_next[3:0]);
wire [7:0] wdata_shifted = acc_wdata_reg >> (5'd26 - k_next[4:0]);
/* verilator lint_on UNUSEDSIGNAL */
wire id_bit = id_shifted[0];
wire addr_bit = addr_shifted[0];
wire wdata_bit = wdata_shifted[0];
// A register access addresses one ID (= chain position); a command selects
// by IDS bits, every slave on a broadcast.
wire ids_bit_of_slave = acc_ids_reg[{1'b0, slave_reg}];
wire addressed = ctl_active_reg && (acc_cmd_reg ? ((acc_ids_reg == 8'd0) || ids_bit_of_slave) : (acc_id_reg == {1'b0, slave_reg}));
wire ctl_cds = frame_sel_reg && frame_cds_reg;
// Command bits of index k_next: CTS = 0 at k = 1, IDS MSB first at 2, CMD at 10.
/* verilator lint_off UNUSEDSIGNAL */
wire [7:0] ids_shifted = acc_ids_reg >> (4'd9 - k_next[3:0]);
wire [1:0] code_shifted = acc_code_reg >> (4'd11 - k_next[3:0]);
/* verilator lint_on UNUSEDSIGNAL */
wire cmd_bit = (k_next == 6'd1) ? 1'b0 : (k_next <= 6'd9) ? ids_shifted[0] : code_shifted[0];

// The control CRC-4 x^4 + x + 1 advanced by one bit, with the shared LFSR
// step every core uses: one instance per bit the frame may push now.
wire [3:0] crc4_tx_one, crc4_tx_id, crc4_tx_addr, crc4_tx_wdata, crc4_rx_cds;
crc_serial #(.WIDTH(4), .POLY(4'h3)) crc4_one   (.i_crc(crc4_tx_reg), .i_bit(1'b1),          .o_crc(crc4_tx_one));
crc_serial #(.WIDTH(4), .POLY(4'h3)) crc4_id    (.i_crc(crc4_tx_reg), .i_bit(id_bit),        .o_crc(crc4_tx_id));
crc_serial #(.WIDTH(4), .POLY(4'h3)) crc4_addr  (.i_crc(crc4_tx_reg), .i_bit(addr_bit),      .o_crc(crc4_tx_addr));
crc_serial #(.WIDTH(4), .POLY(4'h3)) crc4_wdata (.i_crc(crc4_tx_reg), .i_bit(wdata_bit),     .o_crc(crc4_tx_wdata));
crc_serial #(.WIDTH(4), .POLY(4'h3)) crc4_cds   (.i_crc(crc4_rx_reg), .i_bit(ctl_cds),       .o_crc(crc4_rx_cds));
wire [3:0] crc4_tx_cmd;
crc_serial #(.WIDTH(4), .POLY(4'h3)) crc4_cmd   (.i_crc(crc4_tx_reg), .i_bit(cmd_bit),       .o_crc(crc4_tx_cmd));

reg       finish;
reg       ma_hold;
reg       frame_end;
reg       refused;
reg       fin_ack;
reg       fin_timeout;
reg       frame_ok;
reg       ctl_end;
reg       ctl_err;

always @* begin
    state_next = state_reg;
    cnt_clear = 1'b0;
    cnt_inc = 1'b0;
    delay_cnt_next = delay_cnt_reg;
    smp_cnt_load = 1'b0;
    smp_cnt_load_mean = 1'b0;
    ma_next = ma_reg;
    ma_cnt_load = 1'b0;
    ma_cnt_load_high = 1'b0;
    ma_cnt_dec = 1'b0;
    ma_run_next = ma_run_reg;
    ma_edges_next = ma_edges_reg;
    ma_stop_next = ma_stop_reg;
    ma_stop_level_next = ma_stop_level_reg;
    slave_next = slave_reg;
    bit_cnt_next = bit_cnt_reg;
    data_next = data_reg;
    crc_next = crc_reg;
    crc_bad_next = crc_bad_reg;
    nerr_next = nerr_reg;
    nwarn_next = nwarn_reg;
    cds_next = cds_reg;
    e_delay_next = e_delay_reg;
    e_start_next = e_start_reg;
    e_drift_next = e_drift_reg;
    cal_cnt_next = cal_cnt_reg;
    cal_sum_next = cal_sum_reg;
    delay_mean_next = delay_mean_reg;
    frame_cds_next = frame_cds_reg;
    frame_crc_bad_next = frame_crc_bad_reg;
    frame_sel_next = frame_sel_reg;
    acc_cmd_next = acc_cmd_reg;
    acc_ids_next = acc_ids_reg;
    acc_code_next = acc_code_reg;
    cdm_next = cdm_reg;
    zeros_next = zeros_reg;
    reg_pending_next = reg_pending_reg;
    ctl_active_next = ctl_active_reg;
    ctl_k_next = ctl_k_reg;
    acc_write_next = acc_write_reg;
    acc_id_next = acc_id_reg;
    acc_addr_next = acc_addr_reg;
    acc_wdata_next = acc_wdata_reg;
    reg_bad_next = reg_bad_reg;
    rdata_next = rdata_reg;
    crc4_tx_next = crc4_tx_reg;
    crc4_rx_next = crc4_rx_reg;
    busy_next = busy_reg;
    delay_next = delay_reg;
    slave_index_next = slave_index_reg;
    out_data_next = out_data_reg;
    crc_err_next = crc_err_reg;
    error_next = error_reg;
    warning_next = warning_reg;
    out_cds_next = out_cds_reg;
    reg_busy_next = reg_busy_reg;
    reg_rdata_next = reg_rdata_reg;
    done_next = 1'b0;
    err_line_next = 1'b0;
    err_ack_next = 1'b0;
    err_delay_next = 1'b0;
    err_start_next = 1'b0;
    err_timeout_next = 1'b0;
    err_drift_next = 1'b0;
    slave_valid_next = 1'b0;
    reg_done_next = 1'b0;
    reg_err_next = 1'b0;
    reg_crc_err_next = 1'b0;
    finish = 1'b0;
    refused = 1'b0;
    fin_ack = 1'b0;
    fin_timeout = 1'b0;
    frame_ok = 1'b0;
    ctl_end = 1'b0;
    ctl_err = 1'b0;

    // MA generator.
    if (ma_run_reg) begin
        if (ma_cnt_zero) begin
            if (ma_stop_reg && (ma_reg == ma_stop_level_reg)) begin
                ma_run_next = 1'b0;
            end else begin
                ma_next = !ma_reg;
                ma_cnt_load = 1'b1;
                ma_cnt_load_high = !ma_reg;
                if (!ma_reg) begin
                    ma_edges_next = (ma_edges_reg == 2'd2) ? 2'd2 : ma_edges_reg + 2'd1;
                    if (ma_edges_reg == 2'd1) delay_cnt_next = 16'd1;
                end
            end
        end else begin
            ma_cnt_dec = 1'b1;
        end
    end else if (!ma_cnt_zero) begin
        // Stopped: counting out the high level that ends a frame.
        ma_cnt_dec = 1'b1;
    end

    // Calibrated frames, two cycles after the ack: sample by the mean when
    // the delay is within DELAY_TOL of it, else by the own ack and flag it.
    cal_chk_next = 1'b0;
    cal_ok_next = cal_ok_reg;
    cal_smp_next = cal_smp_reg;
    if (cal_chk_reg) begin
        cal_ok_next = (delay_dev <= DELAY_TOL_16);
        cal_smp_next = smp_mean_wide[SMP_W-1:0];
    end
    if (cal_apply_reg) begin
        if (cal_ok_reg) begin
            smp_cnt_load = 1'b1;
            smp_cnt_load_mean = 1'b1;
        end
        else e_drift_next = 1'b1;
    end

    case (state_reg)
        IDLE: begin
            // A register access starts its own frames, back to back.
            if (i_start || reg_pending_reg || ctl_active_reg) begin
                if (slo_sync_reg) begin
                    state_next = ACK;
                    ma_next = 1'b0;
                    ma_cnt_load = 1'b1;
                    ma_cnt_load_high = 1'b0;
                    ma_run_next = 1'b1;
                    ma_edges_next = 2'd0;
                    ma_stop_next = 1'b0;
                    delay_cnt_next = 16'd0;
                    e_delay_next = 1'b0;
                    e_start_next = 1'b0;
                    e_drift_next = 1'b0;
                    slave_next = 2'd0;
                    frame_cds_next = 1'b1;
                    frame_sel_next = 1'b0;
                    frame_crc_bad_next = 1'b0;
                    busy_next = 1'b1;
                end else begin
                    done_next = 1'b1;
                    err_line_next = 1'b1;
                    refused = 1'b1;
                end
            end
        end
        ACK: begin
            if (ma_edges_reg == 2'd2) begin
                if (!slo_sync_reg) begin
                    state_next = START;
                    cnt_clear = 1'b1;
                    delay_next = delay_cnt_reg;
                    smp_cnt_load = 1'b1;
                    smp_cnt_load_mean = 1'b0;
                    if (cal_cnt_reg != CAL_FRAMES_5) begin
                        cal_sum_next = cal_sum_plus;
                        cal_cnt_next = cal_cnt_reg + 5'd1;
                        if (cal_cnt_reg + 5'd1 == CAL_FRAMES_5) delay_mean_next = cal_mean_wide[15:0];
                    end else begin
                        cal_chk_next = 1'b1;
                    end
                end else if (delay_cnt_reg == MAX_DELAY_16) begin
                    state_next = NOACK;
                    ma_stop_next = 1'b1;
                    ma_stop_level_next = 1'b1;
                    cnt_clear = 1'b1;
                end else begin
                    delay_cnt_next = delay_cnt_reg + 16'd1;
                end
            end
        end
        START: begin
            cnt_inc = 1'b1;
            if (sample && b) begin
                state_next = CDS;
            end else if (cnt_at_timeout) begin
                state_next = TIMEOUT;
                e_start_next = 1'b1;
                ma_stop_next = 1'b1;
                ma_stop_level_next = 1'b1;
                cnt_clear = 1'b1;
            end
        end
        CDS: begin
            if (sample) begin
                cds_next = b;
                if (addressed) begin
                    frame_cds_next = frame_cds_reg && b;
                    frame_sel_next = 1'b1;
                end
                state_next = DATA;
                bit_cnt_next = cur_bits - 7'd1;
                data_next = 0;
                crc_next = 8'd0;
            end
        end
        DATA: begin
            if (sample) begin
                data_next = data_shifted[DATA_W-1:0];
                crc_next = crc_push(crc_reg, b, cur_top, cur_poly, cur_mask);
                if (bit_cnt_reg == 0) state_next = ERR;
                else bit_cnt_next = bit_cnt_reg - 7'd1;
            end
        end
        ERR: begin
            if (sample) begin
                nerr_next = b;
                crc_next = crc_push(crc_reg, b, cur_top, cur_poly, cur_mask);
                state_next = WARN;
            end
        end
        WARN: begin
            if (sample) begin
                nwarn_next = b;
                crc_next = crc_push(crc_reg, b, cur_top, cur_poly, cur_mask);
                state_next = CRC;
                bit_cnt_next = {3'd0, cur_crc_w} - 7'd1;
                crc_bad_next = 1'b0;
            end
        end
        CRC: begin
            if (sample) begin
                // Sent inverted: the wire bit must be the complement of the remainder's MSB.
                crc_bad_next = crc_bad_reg || (b == crc_msb);
                crc_next = (crc_reg << 1) & cur_mask;
                if (bit_cnt_reg == 0) begin
                    slave_valid_next = 1'b1;
                    slave_index_next = slave_reg;
                    out_data_next = data_reg;
                    crc_err_next = crc_bad_reg || (b == crc_msb);
                    error_next = !nerr_reg;
                    warning_next = !nwarn_reg;
                    out_cds_next = cds_reg;
                    if (addressed) frame_crc_bad_next = frame_crc_bad_reg || crc_bad_reg || (b == crc_msb);
                    if (slave_reg != LAST_SLAVE) begin
                        slave_next = slave_reg + 2'd1;
                        state_next = CDS;
                    end else begin
                        state_next = STOP;
                        ma_stop_next = 1'b1;
                        ma_stop_level_next = !cdm_reg;
                        cnt_clear = 1'b1;
                    end
                end else begin
                    bit_cnt_next = bit_cnt_reg - 7'd1;
                end
            end
        end
        STOP: begin
            cnt_inc = 1'b1;
            if (!slo_sync_reg) begin
                state_next = TIMEOUT;
            end else if (cnt_timed_out) begin
                finish = 1'b1;
                fin_timeout = 1'b1;
            end
        end
        TIMEOUT: begin
            cnt_inc = 1'b1;
            if (slo_sync_reg && !ma_run_reg) begin
                finish = 1'b1;
            end else if (cnt_timed_out) begin
                finish = 1'b1;
                fin_timeout = 1'b1;
            end
        end
        NOACK: begin
            cnt_inc = 1'b1;
            if (!slo_sync_reg) begin
                e_delay_next = 1'b1;
                state_next = TIMEOUT;
            end else if (cnt_timed_out) begin
                finish = 1'b1;
                fin_ack = 1'b1;
            end
        end
        // Codes 11 to 15 are never entered (every assignment above names a
        // state); coverage counts reachable code only.
        /* verilator coverage_off */
        default: begin
            state_next = IDLE;
        end
        /* verilator coverage_on */
    endcase

    // A frame ends with MA high for at least a high phase (seed 001,
    // BiSS-C: TMASH > 25 ns), so that the next frame's first falling edge, in
    // the cycle after o_done at the earliest, never follows a short high
    // level: a frame that stopped MA low (CDM = 1) raises it first and ends
    // HIGH_CLOCKS cycles later (o_done then). (Held in its own variable rather than
    // by clearing finish: Verilator 5.006 counts no coverage in a branch that
    // clears the variable of its own condition.)
    ma_hold = finish && (!ma_reg || !ma_cnt_zero);
    frame_end = finish && !ma_hold;
    if (ma_hold && !ma_reg) begin
        ma_next = 1'b1;
        ma_cnt_load = 1'b1;
        ma_cnt_load_high = 1'b1;
    end

    if (frame_end) begin
        state_next = IDLE;
        ma_next = 1'b1;
        ma_run_next = 1'b0;
        busy_next = 1'b0;
        done_next = 1'b1;
        err_ack_next = fin_ack;
        err_delay_next = e_delay_reg;
        err_start_next = e_start_reg;
        err_timeout_next = fin_timeout;
        err_drift_next = e_drift_reg;
        frame_ok = !(fin_ack || fin_timeout || e_delay_reg || e_start_reg);
    end

    // Control-frame sequencer, at the end of every frame and at a refused
    // start: take this frame's CDS, choose the next CDM. Only frames that
    // completed count as sent.
    if (frame_end || refused) begin
        if (frame_ok) zeros_next = cdm_reg ? 4'd0 : ((zeros_reg == SYNC_ZEROS) ? SYNC_ZEROS : zeros_reg + 4'd1);
        cdm_next = 1'b0;
        if (ctl_active_reg) begin
            if (!frame_ok || frame_crc_bad_reg) begin
                ctl_end = 1'b1;
                ctl_err = 1'b1;
            end else if (acc_cmd_reg) begin
                // IDA from every selected slave, then the echo of EX.
                if (ctl_k_reg == 6'd16 && !ctl_cds) begin ctl_end = 1'b1; ctl_err = 1'b1; end
                if (ctl_k_reg == 6'd18) begin ctl_end = 1'b1; ctl_err = !ctl_cds; end
            end else begin
                case (ctl_k_reg)
                    6'd17: if (ctl_cds != !acc_write_reg) begin ctl_end = 1'b1; ctl_err = 1'b1; end
                    6'd18: if (ctl_cds != acc_write_reg) begin ctl_end = 1'b1; ctl_err = 1'b1; end
                    6'd19: begin
                        if (!ctl_cds) begin ctl_end = 1'b1; ctl_err = 1'b1; end
                        crc4_rx_next = 4'd0;
                    end
                    6'd20, 6'd21, 6'd22, 6'd23, 6'd24, 6'd25, 6'd26, 6'd27: begin
                        rdata_next = {rdata_reg[6:0], ctl_cds};
                        crc4_rx_next = crc4_rx_cds;
                    end
                    6'd28, 6'd29, 6'd30, 6'd31: begin
                        if (ctl_cds == crc4_rx_reg[3]) reg_bad_next = 1'b1;
                        crc4_rx_next = {crc4_rx_reg[2:0], 1'b0};
                    end
                    6'd32: begin
                        ctl_end = 1'b1;
                        ctl_err = reg_bad_reg || ctl_cds || (acc_write_reg && (rdata_reg != acc_wdata_reg));
                    end
                    default: begin end
                endcase
            end
            if (ctl_end) begin
                ctl_active_next = 1'b0;
                reg_done_next = 1'b1;
                reg_err_next = ctl_err;
                reg_crc_err_next = (ctl_k_reg == 6'd32) && reg_bad_reg;
                reg_rdata_next = rdata_reg;
                reg_busy_next = 1'b0;
            end else begin
                // CDM bit k_next of the access; the CRC-4 covers CTS, ID, ADR and the write data.
                ctl_k_next = k_next;
                if (k_next >= 6'd12 && k_next <= 6'd15) begin
                    // The address (or command) CRC-4, both kinds.
                    cdm_next = !crc4_tx_reg[3];
                    crc4_tx_next = {crc4_tx_reg[2:0], 1'b0};
                end else if (acc_cmd_reg) begin
                    // A command: the CRC-4 covers CTS, IDS and CMD; EX at 17.
                    case (k_next)
                        6'd1, 6'd2, 6'd3, 6'd4, 6'd5, 6'd6, 6'd7, 6'd8, 6'd9, 6'd10, 6'd11: begin
                            cdm_next = cmd_bit;
                            crc4_tx_next = crc4_tx_cmd;
                        end
                        6'd17: cdm_next = 1'b1;
                        default: cdm_next = 1'b0;
                    endcase
                end else case (k_next)
                    6'd1: begin cdm_next = 1'b1; crc4_tx_next = crc4_tx_one; end
                    6'd2, 6'd3, 6'd4: begin
                        cdm_next = id_bit;
                        crc4_tx_next = crc4_tx_id;
                    end
                    6'd5, 6'd6, 6'd7, 6'd8, 6'd9, 6'd10, 6'd11: begin
                        cdm_next = addr_bit;
                        crc4_tx_next = crc4_tx_addr;
                    end
                    6'd16: cdm_next = !acc_write_reg;
                    6'd17: cdm_next = acc_write_reg;
                    6'd18: begin cdm_next = 1'b1; crc4_tx_next = 4'd0; end
                    6'd19, 6'd20, 6'd21, 6'd22, 6'd23, 6'd24, 6'd25, 6'd26: begin
                        if (acc_write_reg) begin
                            cdm_next = wdata_bit;
                            crc4_tx_next = crc4_tx_wdata;
                        end
                    end
                    6'd27, 6'd28, 6'd29, 6'd30: begin
                        if (acc_write_reg) begin
                            cdm_next = !crc4_tx_reg[3];
                            crc4_tx_next = {crc4_tx_reg[2:0], 1'b0};
                        end
                    end
                    default: cdm_next = 1'b0;
                endcase
            end
        end else if (reg_pending_reg && !frame_ok) begin
            // A sync frame failed: the line cannot carry the access.
            reg_pending_next = 1'b0;
            reg_done_next = 1'b1;
            reg_err_next = 1'b1;
            reg_rdata_next = rdata_reg;
            reg_busy_next = 1'b0;
        end else if (reg_pending_reg && (zeros_next >= SYNC_ZEROS)) begin
            reg_pending_next = 1'b0;
            ctl_active_next = 1'b1;
            ctl_k_next = 6'd0;
            cdm_next = 1'b1;
            reg_bad_next = 1'b0;
            rdata_next = 8'd0;
            crc4_tx_next = 4'd0;
            crc4_rx_next = 4'd0;
        end
    end

    // Register requests are taken whenever no access is pending or running.
    if ((i_reg_start || i_cmd_start) && !reg_pending_reg && !ctl_active_reg) begin
        reg_pending_next = 1'b1;
        acc_cmd_next = !i_reg_start;
        acc_write_next = i_reg_start && i_reg_write;
        acc_id_next = i_reg_start ? i_reg_id : 3'd0;
        acc_addr_next = i_reg_start ? i_reg_addr : 7'd0;
        acc_wdata_next = i_reg_start ? i_reg_wdata : 8'd0;
        acc_ids_next = i_reg_start ? 8'd0 : i_cmd_ids;
        acc_code_next = i_reg_start ? 2'd0 : i_cmd_code;
        reg_busy_next = 1'b1;
    end
end

// The register bank: every register takes its next value at each clock edge.
always @(posedge i_clk) begin
    state_reg <= state_next;
    delay_cnt_reg <= delay_cnt_next;
    ma_run_reg <= ma_run_next;
    ma_edges_reg <= ma_edges_next;
    ma_stop_reg <= ma_stop_next;
    ma_stop_level_reg <= ma_stop_level_next;
    slave_reg <= slave_next;
    bit_cnt_reg <= bit_cnt_next;
    data_reg <= data_next;
    crc_reg <= crc_next;
    crc_bad_reg <= crc_bad_next;
    nerr_reg <= nerr_next;
    nwarn_reg <= nwarn_next;
    cds_reg <= cds_next;
    e_delay_reg <= e_delay_next;
    e_start_reg <= e_start_next;
    e_drift_reg <= e_drift_next;
    cal_cnt_reg <= cal_cnt_next;
    cal_sum_reg <= cal_sum_next;
    delay_mean_reg <= delay_mean_next;
    cal_chk_reg <= cal_chk_next;
    cal_ok_reg <= cal_ok_next;
    cal_smp_reg <= cal_smp_next;
    frame_cds_reg <= frame_cds_next;
    frame_crc_bad_reg <= frame_crc_bad_next;
    frame_sel_reg <= frame_sel_next;
    acc_cmd_reg <= acc_cmd_next;
    acc_ids_reg <= acc_ids_next;
    acc_code_reg <= acc_code_next;
    cdm_reg <= cdm_next;
    zeros_reg <= zeros_next;
    reg_pending_reg <= reg_pending_next;
    ctl_active_reg <= ctl_active_next;
    ctl_k_reg <= ctl_k_next;
    acc_write_reg <= acc_write_next;
    acc_id_reg <= acc_id_next;
    acc_addr_reg <= acc_addr_next;
    acc_wdata_reg <= acc_wdata_next;
    reg_bad_reg <= reg_bad_next;
    rdata_reg <= rdata_next;
    crc4_tx_reg <= crc4_tx_next;
    crc4_rx_reg <= crc4_rx_next;
    busy_reg <= busy_next;
    done_reg <= done_next;
    err_line_reg <= err_line_next;
    err_ack_reg <= err_ack_next;
    err_delay_reg <= err_delay_next;
    err_start_reg <= err_start_next;
    err_timeout_reg <= err_timeout_next;
    err_drift_reg <= err_drift_next;
    delay_reg <= delay_next;
    slave_valid_reg <= slave_valid_next;
    slave_index_reg <= slave_index_next;
    out_data_reg <= out_data_next;
    crc_err_reg <= crc_err_next;
    error_reg <= error_next;
    warning_reg <= warning_next;
    out_cds_reg <= out_cds_next;
    reg_busy_reg <= reg_busy_next;
    reg_done_reg <= reg_done_next;
    reg_err_reg <= reg_err_next;
    reg_rdata_reg <= reg_rdata_next;
    reg_crc_err_reg <= reg_crc_err_next;
    cnt_reg <= cnt_next;
    smp_cnt_reg <= smp_cnt_next;
    ma_reg <= ma_next;
    ma_cnt_reg <= ma_cnt_next;
    slo_meta_reg <= i_slo;
    slo_sync_reg <= slo_meta_reg;
    cal_apply_reg <= cal_chk_reg;

    if (i_rst) begin
        state_reg <= IDLE;
        cnt_reg <= 0;
        delay_cnt_reg <= 16'd0;
        smp_cnt_reg <= 0;
        ma_reg <= 1'b1;
        ma_cnt_reg <= 0;
        ma_run_reg <= 1'b0;
        ma_edges_reg <= 2'd0;
        ma_stop_reg <= 1'b0;
        ma_stop_level_reg <= 1'b1;
        slo_meta_reg <= 1'b1;
        slo_sync_reg <= 1'b1;
        slave_reg <= 2'd0;
        bit_cnt_reg <= 7'd0;
        data_reg <= 0;
        crc_reg <= 8'd0;
        crc_bad_reg <= 1'b0;
        nerr_reg <= 1'b1;
        nwarn_reg <= 1'b1;
        cds_reg <= 1'b0;
        e_delay_reg <= 1'b0;
        e_start_reg <= 1'b0;
        e_drift_reg <= 1'b0;
        cal_cnt_reg <= 5'd0;
        cal_sum_reg <= 20'd0;
        delay_mean_reg <= 16'd0;
        cal_chk_reg <= 1'b0;
        cal_apply_reg <= 1'b0;
        cal_ok_reg <= 1'b0;
        cal_smp_reg <= 0;
        frame_cds_reg <= 1'b0;
        frame_crc_bad_reg <= 1'b0;
        frame_sel_reg <= 1'b0;
        acc_cmd_reg <= 1'b0;
        acc_ids_reg <= 8'd0;
        acc_code_reg <= 2'd0;
        cdm_reg <= 1'b0;
        zeros_reg <= 4'd0;
        reg_pending_reg <= 1'b0;
        ctl_active_reg <= 1'b0;
        ctl_k_reg <= 6'd0;
        acc_write_reg <= 1'b0;
        acc_id_reg <= 3'd0;
        acc_addr_reg <= 7'd0;
        acc_wdata_reg <= 8'd0;
        reg_bad_reg <= 1'b0;
        rdata_reg <= 8'd0;
        crc4_tx_reg <= 4'd0;
        crc4_rx_reg <= 4'd0;
        busy_reg <= 1'b0;
        done_reg <= 1'b0;
        err_line_reg <= 1'b0;
        err_ack_reg <= 1'b0;
        err_delay_reg <= 1'b0;
        err_start_reg <= 1'b0;
        err_timeout_reg <= 1'b0;
        err_drift_reg <= 1'b0;
        delay_reg <= 16'd0;
        slave_valid_reg <= 1'b0;
        slave_index_reg <= 2'd0;
        out_data_reg <= 0;
        crc_err_reg <= 1'b0;
        error_reg <= 1'b0;
        warning_reg <= 1'b0;
        out_cds_reg <= 1'b0;
        reg_busy_reg <= 1'b0;
        reg_done_reg <= 1'b0;
        reg_err_reg <= 1'b0;
        reg_rdata_reg <= 8'd0;
        reg_crc_err_reg <= 1'b0;
    end
end

endmodule

`resetall
