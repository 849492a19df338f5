// biss_master_formal: the BiSS-C master's seed rules, status outputs and CRC check, on the unchanged core.
//
// What it checks (seed 001, SAR58K24 manual, BiSS-C: "TMAS: The allowed clock
// cycle is >100ns", "TMASH: High level duration >25ns", "TMASL: Low level
// duration >25ns", "Timeout: Biss timeout 16µs"; model/src/biss/rules.rs), in
// cycles of i_clk at the core's configuration, watched on o_ma and i_slo with
// counters and a CRC of this harness (none of the core's); the slave is any
// input sequence on i_slo:
//   tmas               every MA period (rising edge to rising edge) lasts at
//                      least CLOCKS_PER_BIT
//   tmash              every MA high phase lasts at least HIGH_CLOCKS
//   tmasl              every MA low phase lasts at least LOW_CLOCKS
//   timeout_start      a frame starts (MA falls from rest) only when the
//                      synchronised SLO was high: the slave's timeout is over
//   timeout_done       a frame that ends without a line, ack or timeout error
//                      ends with SLO high (the master waited for the timeout)
//   ma_at_rest         MA is low only while o_busy is high
//   done_pulse         o_done is a one-cycle pulse (back to back only for a
//                      new start) and only for a start taken
//   done_once          a start is taken only once the previous one's o_done came
//   busy_done          o_busy is low only from the start's o_done on
//   err_with_done      every frame error pulse comes with o_done
//   err_line           a start is refused (o_err_line, MA at rest) exactly
//                      when the synchronised SLO was low
//   valid_pulse        o_slave_valid is a one-cycle pulse, inside a frame
//   data               o_data is the slave's data bits as sampled after the
//                      start and CDS bits, o_cds the CDS bit
//   error_warning      o_error and o_warning are the inverted nE and nW bits
//   crc_err            o_crc_err exactly when the received CRC differs from
//                      the inverted CRC-6 (x^6 + x + 1, preset 0) of the
//                      data, nE and nW bits, computed here by long division
//   no_x               (the no_x task) two copies of the core started from any
//                      state agree on every output from the cycle after reset on
//
// The bits are the synchronised SLO at the core's own sampling instants
// (probe_sample): where a bit is sampled is the delay compensation's
// business (o_delay, proven by the vectors and closed loops); what the core
// makes of the sampled bits is checked here against this harness's fields.
// Register accesses and commands are not driven (i_reg_start, i_cmd_start
// low): they start only after 14 sync frames, beyond a bounded run's reach.
// One slave, SLAVE_BITS data bits.
//
// The core's registers start from any value (the script drops their initial
// values): reset in the first cycle is what defines them.

`default_nettype none

module biss_master_formal #(
    parameter SLAVE_BITS = 2,
    parameter SLAVE_CRC_WIDTH = 6,
    parameter SLAVE_CRC_POLY = 3,
    parameter CLOCKS_PER_BIT = 8,
    parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2,
    parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2,
    parameter MAX_DELAY = 4,
    parameter TIMEOUT_CLOCKS = 16,
    parameter CAL_FRAMES = 1,
    parameter DELAY_TOL = 1
) (
    input wire i_clk,
    input wire i_start,
    input wire i_slo
);

// The BiSS-C CRC-6 generator x^6 + x + 1, with its top term (seed: BiSS-C).
localparam [6:0] GEN = 7'b1000011;
localparam integer LEN_MAX = 4 * CLOCKS_PER_BIT;

initial begin
    if (SLAVE_CRC_WIDTH != 6 || SLAVE_CRC_POLY != 3) $error("biss_master_formal: written for the BiSS-C CRC-6");
end

reg f_past = 1'b0;
always @(posedge i_clk) f_past <= 1'b1;
wire i_rst = !f_past;

wire o_busy, o_done, o_err_line, o_err_ack, o_err_delay, o_err_start, o_err_timeout, o_err_drift;
wire [15:0] o_delay, o_delay_mean;
wire o_slave_valid, o_crc_err, o_error, o_warning, o_cds, o_ma;
wire [1:0] o_slave_index;
wire [SLAVE_BITS-1:0] o_data;
wire o_reg_busy, o_reg_done, o_reg_err, o_reg_crc_err;
wire [7:0] o_reg_rdata;

biss_master #(
    .SLAVES(1), .SLAVE_BITS(SLAVE_BITS), .SLAVE_CRC_WIDTH(SLAVE_CRC_WIDTH), .SLAVE_CRC_POLY(SLAVE_CRC_POLY),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT), .HIGH_CLOCKS(HIGH_CLOCKS), .LOW_CLOCKS(LOW_CLOCKS), .MAX_DELAY(MAX_DELAY),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS), .CAL_FRAMES(CAL_FRAMES), .DELAY_TOL(DELAY_TOL)
) dut (
    .i_clk(i_clk), .i_rst(i_rst), .i_start(i_start), .o_busy(o_busy), .o_done(o_done),
    .o_err_line(o_err_line), .o_err_ack(o_err_ack), .o_err_delay(o_err_delay), .o_err_start(o_err_start),
    .o_err_timeout(o_err_timeout), .o_delay(o_delay), .o_delay_mean(o_delay_mean), .o_err_drift(o_err_drift),
    .o_slave_valid(o_slave_valid), .o_slave_index(o_slave_index), .o_data(o_data), .o_crc_err(o_crc_err),
    .o_error(o_error), .o_warning(o_warning), .o_cds(o_cds),
    .i_reg_start(1'b0), .i_reg_write(1'b0), .i_reg_id(3'd0), .i_reg_addr(7'd0), .i_reg_wdata(8'd0),
    .o_reg_busy(o_reg_busy), .o_reg_done(o_reg_done), .o_reg_err(o_reg_err), .o_reg_rdata(o_reg_rdata),
    .o_reg_crc_err(o_reg_crc_err), .i_cmd_start(1'b0), .i_cmd_ids(8'd0), .i_cmd_code(2'd0),
    .o_ma(o_ma), .i_slo(i_slo)
);

wire [SLAVE_BITS+90:0] outs = {o_busy, o_done, o_err_line, o_err_ack, o_err_delay, o_err_start, o_err_timeout,
    o_err_drift, o_delay, o_delay_mean, o_slave_valid, o_crc_err, o_error, o_warning, o_cds, o_ma, o_slave_index,
    o_data, o_reg_busy, o_reg_done, o_reg_err, o_reg_crc_err, o_reg_rdata};

`ifdef TWIN
wire t_busy, t_done, t_err_line, t_err_ack, t_err_delay, t_err_start, t_err_timeout, t_err_drift;
wire [15:0] t_delay, t_delay_mean;
wire t_slave_valid, t_crc_err, t_error, t_warning, t_cds, t_ma;
wire [1:0] t_slave_index;
wire [SLAVE_BITS-1:0] t_data;
wire t_reg_busy, t_reg_done, t_reg_err, t_reg_crc_err;
wire [7:0] t_reg_rdata;
biss_master #(
    .SLAVES(1), .SLAVE_BITS(SLAVE_BITS), .SLAVE_CRC_WIDTH(SLAVE_CRC_WIDTH), .SLAVE_CRC_POLY(SLAVE_CRC_POLY),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT), .HIGH_CLOCKS(HIGH_CLOCKS), .LOW_CLOCKS(LOW_CLOCKS), .MAX_DELAY(MAX_DELAY),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS), .CAL_FRAMES(CAL_FRAMES), .DELAY_TOL(DELAY_TOL)
) twin (
    .i_clk(i_clk), .i_rst(i_rst), .i_start(i_start), .o_busy(t_busy), .o_done(t_done),
    .o_err_line(t_err_line), .o_err_ack(t_err_ack), .o_err_delay(t_err_delay), .o_err_start(t_err_start),
    .o_err_timeout(t_err_timeout), .o_delay(t_delay), .o_delay_mean(t_delay_mean), .o_err_drift(t_err_drift),
    .o_slave_valid(t_slave_valid), .o_slave_index(t_slave_index), .o_data(t_data), .o_crc_err(t_crc_err),
    .o_error(t_error), .o_warning(t_warning), .o_cds(t_cds),
    .i_reg_start(1'b0), .i_reg_write(1'b0), .i_reg_id(3'd0), .i_reg_addr(7'd0), .i_reg_wdata(8'd0),
    .o_reg_busy(t_reg_busy), .o_reg_done(t_reg_done), .o_reg_err(t_reg_err), .o_reg_rdata(t_reg_rdata),
    .o_reg_crc_err(t_reg_crc_err), .i_cmd_start(1'b0), .i_cmd_ids(8'd0), .i_cmd_code(2'd0),
    .o_ma(t_ma), .i_slo(i_slo)
);
wire [SLAVE_BITS+90:0] t_outs = {t_busy, t_done, t_err_line, t_err_ack, t_err_delay, t_err_start, t_err_timeout,
    t_err_drift, t_delay, t_delay_mean, t_slave_valid, t_crc_err, t_error, t_warning, t_cds, t_ma, t_slave_index,
    t_data, t_reg_busy, t_reg_done, t_reg_err, t_reg_crc_err, t_reg_rdata};
always @* if (f_past) no_x: assert (outs == t_outs);
`else

/* MA as the slave sees it */
// Each *_now is this cycle's value, its *_q the previous cycle's.
reg ma_q = 1'b1;
reg [$clog2(LEN_MAX+1)-1:0] len_q = 0;
// The last high phase's length: with the low phase after it, one period.
reg [$clog2(LEN_MAX+1)-1:0] last_high = LEN_MAX;
wire ma_fell = ma_q && !o_ma;
wire ma_rose = !ma_q && o_ma;
// Cycles MA has held its level, this one included (saturating).
wire [$clog2(LEN_MAX+1)-1:0] len_now = (ma_fell || ma_rose) ? 1 : (len_q == LEN_MAX) ? len_q : len_q + 1'b1;
always @(posedge i_clk) begin
    // Before reset the outputs are not the core's own: MA is taken at rest then.
    ma_q <= i_rst || o_ma;
    len_q <= i_rst ? LEN_MAX : len_now;
    if (i_rst) last_high <= LEN_MAX;
    else if (ma_fell) last_high <= len_q;
end

/* SLO as the core's two-flop synchroniser shows it (idle high through reset) */
reg slo_d1 = 1'b1, slo_d2 = 1'b1, slo_d2_q = 1'b1;
always @(posedge i_clk) begin
    slo_d1 <= i_rst || i_slo;
    slo_d2 <= i_rst || slo_d1;
    slo_d2_q <= i_rst || slo_d2;
end

/* Host interface */
reg busy_q = 1'b0, done_q = 1'b0, valid_q = 1'b0, pending = 1'b0, start_q = 1'b0;
wire start_taken = f_past && i_start && !o_busy;
always @(posedge i_clk) begin
    busy_q <= !i_rst && o_busy;
    done_q <= !i_rst && o_done;
    valid_q <= !i_rst && o_slave_valid;
    if (start_taken) pending <= 1'b1;
    else if (o_done) pending <= 1'b0;
    start_q <= start_taken;
end

always @* if (f_past) begin
    if (ma_rose) tmasl: assert (len_q >= LOW_CLOCKS);
    if (ma_fell) tmash: assert (len_q >= HIGH_CLOCKS);
    if (ma_rose) tmas: assert (last_high + len_q >= CLOCKS_PER_BIT);
    if (ma_fell && !busy_q) timeout_start: assert (slo_d2_q);
    if (!o_ma) ma_at_rest: assert (o_busy);
end

/* Helper invariants (k-induction): the harness's view against the core's registers */
localparam integer SMP_W = $clog2(2 * CLOCKS_PER_BIT);
localparam integer CNT_W = $clog2(TIMEOUT_CLOCKS + 3);
(* keep *) wire [3:0]       probe_state;
(* keep *) wire [SMP_W-1:0] probe_ma_cnt;
(* keep *) wire             probe_ma_run;
(* keep *) wire             probe_ma_stop;
(* keep *) wire [CNT_W-1:0] probe_cnt;
(* keep *) wire             probe_slo_sync;
(* keep *) wire             probe_slo_meta;
`ifndef BOUNDED
// Only for the induction: a bounded run needs none, and its first failure
// should be a rule's.
always @* if (f_past) begin
    inv_sync: assert (probe_slo_sync == slo_d2 && probe_slo_meta == slo_d1);
    inv_last_high: assert (last_high >= HIGH_CLOCKS && last_high <= LEN_MAX && len_q <= LEN_MAX);
    // The MA generator: a running phase ends when its count does; a stopped
    // level has lasted at least its phase.
    inv_ma_len: assert (probe_ma_run ? (len_now + probe_ma_cnt == (o_ma ? HIGH_CLOCKS : LOW_CLOCKS))
                                     : (len_now + probe_ma_cnt >= (o_ma ? HIGH_CLOCKS : LOW_CLOCKS)));
    if (!probe_ma_run && probe_ma_cnt != 0) inv_ma_hold: assert (o_ma && probe_ma_cnt < HIGH_CLOCKS);
    inv_state: assert (probe_state <= 4'd10);
    if (probe_state == 4'd0) inv_idle: assert (!probe_ma_run && probe_ma_cnt == 0 && o_ma && !o_busy);
    // ACK to CRC: MA runs; STOP, TIMEOUT, NOACK: a stop is asked, and MA
    // keeps running at most one period into the timeout count.
    if (probe_state >= 4'd1 && probe_state <= 4'd7) inv_running: assert (probe_ma_run && !probe_ma_stop && o_busy);
    if (probe_state >= 4'd8) inv_stopping: assert (probe_ma_stop && o_busy && (!probe_ma_run || probe_cnt <= CLOCKS_PER_BIT));
end
`endif

`ifndef MA_ONLY
always @* if (f_past) begin
    if (o_done && !(o_err_line || o_err_ack || o_err_timeout)) timeout_done: assert (slo_d2_q);
    done_pulse: assert ((!(o_done && done_q) || start_q) && (!o_done || pending));
    if (start_taken) done_once: assert (!pending || o_done);
    if (!o_busy && !start_q) busy_done: assert (!pending || o_done);
    err_with_done: assert (!(o_err_line || o_err_ack || o_err_delay || o_err_start || o_err_timeout || o_err_drift) || o_done);
    err_line: assert (o_err_line == (start_q && !slo_d2_q) && (!o_err_line || (o_ma && !o_busy)));
    valid_pulse: assert (!(o_slave_valid && valid_q) && (!o_slave_valid || (o_busy && pending)));
end

/* The slave's fields, at the core's sampling instants */
(* keep *) wire probe_sample;
localparam integer FIELDS = 1 + SLAVE_BITS + 2 + 6;   // CDS, data, nE, nW, CRC
reg [FIELDS-1:0] bits = 0;
reg              started = 1'b0;                        // the start bit was sampled
always @(posedge i_clk) begin
    if (o_busy && !busy_q) begin
        started <= 1'b0;
        bits <= 0;
    end else if (f_past && probe_sample) begin
        if (!started) started <= slo_d2;
        else bits <= {bits[FIELDS-2:0], slo_d2};
    end
end
wire                  cds_bit = bits[FIELDS-1];
wire [SLAVE_BITS-1:0] data_bits = bits[FIELDS-2 -: SLAVE_BITS];
wire                  ne_bit = bits[7];
wire                  nw_bit = bits[6];
wire [5:0]            crc_bits = bits[5:0];
// CRC-6 by long division: the data, nE and nW bits followed by six zeros,
// divided by GEN bit by bit (the augmented message; the core computes it
// directly, bit by bit without the zeros).
wire [SLAVE_BITS+7:0] message = {data_bits, ne_bit, nw_bit, 6'd0};
reg  [6:0] rem;
integer k;
always @* begin
    rem = 7'd0;
    for (k = SLAVE_BITS + 7; k >= 0; k = k - 1) begin
        rem = {rem[5:0], message[k]};
        if (rem[6]) rem = rem ^ GEN;
    end
end

always @* if (f_past && o_slave_valid) begin
    data: assert (o_data == data_bits && o_cds == cds_bit);
    error_warning: assert (o_error == !ne_bit && o_warning == !nw_bit);
    crc_err: assert (o_crc_err == (crc_bits != ~rem[5:0]));
end
`endif
`endif

endmodule
