// ssi_master_formal: the SSI master's seed rules and status outputs, proven on the unchanged core.
//
// What it checks (seed 001, SAR58K24 manual, SSI (2): "T_cs > 4µs;
// 100kHz < f_clk < 250kHz; T_m > 500µs"; model/src/ssi/rules.rs), each in
// cycles of i_clk at the core's configuration, watched on o_ssi_clk alone
// with counters of this harness (none of the core's):
//   t_cs               the first low phase of a read lasts at least T_CS_CLOCKS
//   clock_low          every later low phase lasts LOW_CLOCKS
//   clock_high         every high phase inside a read lasts HIGH_CLOCKS, so each
//                      period (rising edge to rising edge) is CLOCKS_PER_BIT
//   t_m                a read starts only after the clock has been high for at
//                      least PAUSE_CLOCKS since the previous read's last edge
//   clock_count        no read has more than SAMPLED + 1 rising edges (the
//                      first ends T_cs, each later one a sampled bit's low phase)
//   clock_count_end    a read ends (the clock rests high) after exactly
//                      SAMPLED + 1 rising edges
//   clock_at_rest      the clock is low only while o_busy is high
//   done_pulse         o_done is a one-cycle pulse (back to back only for a new
//                      start) and only for a start taken
//   done_once          a start is taken only once the previous one's o_done came
//   busy_done          o_busy is low only once the start's o_done has come
//   err_with_done      every error pulse comes with o_done
//   err_idle           a start is refused (o_err_idle) exactly when the
//                      synchronised data line was low
//   err_idle_no_clock  a refused start moves no clock and leaves o_busy low
//   position           o_position is the word on the pin at the sampling
//                      instants, Gray-decoded here by a formula of this harness
//   double_read        o_err_double exactly when the two copies on the pin differ
//   double_read_off    no o_err_double without DOUBLE_READ
//   wire_check         o_err_wire exactly when the bit after the LSB was 1
//   wire_check_off     no o_err_wire without WIRE_CHECK
//   no_x               (the no_x task) two copies of the core started from any
//                      state agree on every output from the cycle after reset on
//
// The core's registers start from any value (the script drops their initial
// values): reset in the first cycle is what defines them. Later resets are
// not driven: the seed rules hold between reads, and a reset mid-read cuts a
// read short by design.
//
// The probe_* wires are tied to the core's registers by the script (yosys
// `connect` after `flatten`), so that the core stays free of formal code; they
// serve only the helper assertions (inv_*) that make k-induction close, which
// are proven like the rest.

`default_nettype none

module ssi_master_formal #(
    parameter BITS = 3,
    parameter CLOCKS_PER_BIT = 8,
    parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2,
    parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2,
    parameter GRAY = 0,
    parameter DOUBLE_READ = 0,
    parameter WIRE_CHECK = 0,
    parameter T_CS_CLOCKS = 5,
    parameter PAUSE_CLOCKS = 12,
    parameter SAMPLE_DELAY = 1
) (
    input wire i_clk,
    input wire i_start,
    input wire i_ssi_data
);

localparam integer SAMPLED = BITS * ((DOUBLE_READ != 0) ? 2 : 1) + ((WIRE_CHECK != 0) ? 1 : 0);
// The harness's phase counter saturates past the longest phase it judges.
localparam integer LEN_MAX = PAUSE_CLOCKS + T_CS_CLOCKS + CLOCKS_PER_BIT;

initial begin
    // The sampling instant below is the pin level in the first cycle the clock reads low.
    if (SAMPLE_DELAY != 1) $error("ssi_master_formal: written for SAMPLE_DELAY = 1");
end

// Reset in the first cycle only.
reg f_past = 1'b0;
always @(posedge i_clk) f_past <= 1'b1;
wire i_rst = !f_past;

wire            o_busy, o_done, o_err_idle, o_err_double, o_err_wire, o_ssi_clk;
wire [BITS-1:0] o_position;

ssi_master #(
    .BITS(BITS), .CLOCKS_PER_BIT(CLOCKS_PER_BIT), .HIGH_CLOCKS(HIGH_CLOCKS), .LOW_CLOCKS(LOW_CLOCKS),
    .GRAY(GRAY), .DOUBLE_READ(DOUBLE_READ), .WIRE_CHECK(WIRE_CHECK), .T_CS_CLOCKS(T_CS_CLOCKS),
    .PAUSE_CLOCKS(PAUSE_CLOCKS), .SAMPLE_DELAY(SAMPLE_DELAY)
) dut (
    .i_clk(i_clk), .i_rst(i_rst),
    .i_start(i_start), .o_busy(o_busy), .o_done(o_done), .o_position(o_position),
    .o_err_idle(o_err_idle), .o_err_double(o_err_double), .o_err_wire(o_err_wire),
    .o_ssi_clk(o_ssi_clk), .i_ssi_data(i_ssi_data)
);

`ifdef TWIN
// A second copy on the same inputs: its registers start from other values.
wire            t_busy, t_done, t_err_idle, t_err_double, t_err_wire, t_ssi_clk;
wire [BITS-1:0] t_position;
ssi_master #(
    .BITS(BITS), .CLOCKS_PER_BIT(CLOCKS_PER_BIT), .HIGH_CLOCKS(HIGH_CLOCKS), .LOW_CLOCKS(LOW_CLOCKS),
    .GRAY(GRAY), .DOUBLE_READ(DOUBLE_READ), .WIRE_CHECK(WIRE_CHECK), .T_CS_CLOCKS(T_CS_CLOCKS),
    .PAUSE_CLOCKS(PAUSE_CLOCKS), .SAMPLE_DELAY(SAMPLE_DELAY)
) twin (
    .i_clk(i_clk), .i_rst(i_rst),
    .i_start(i_start), .o_busy(t_busy), .o_done(t_done), .o_position(t_position),
    .o_err_idle(t_err_idle), .o_err_double(t_err_double), .o_err_wire(t_err_wire),
    .o_ssi_clk(t_ssi_clk), .i_ssi_data(i_ssi_data)
);
always @* if (f_past) begin
    no_x: assert ({o_busy, o_done, o_err_idle, o_err_double, o_err_wire, o_ssi_clk, o_position}
               == {t_busy, t_done, t_err_idle, t_err_double, t_err_wire, t_ssi_clk, t_position});
end
`else

/* The clock as the encoder sees it */
// Each *_now is this cycle's value, its *_q the previous cycle's.
reg                          clk_q = 1'b1;
reg [$clog2(LEN_MAX+1)-1:0]  len_q = 0;
reg                          in_read_q = 1'b0;
reg                          had_read = 1'b0;   // a read has ended since reset (T_m applies from then on)
reg [7:0]                    rises_q = 0;
wire fell = clk_q && !o_ssi_clk;
wire rose = !clk_q && o_ssi_clk;
// Cycles o_ssi_clk has held its level, this one included (saturating).
wire [$clog2(LEN_MAX+1)-1:0] len_now = (fell || rose) ? 1 : (len_q == LEN_MAX) ? len_q : len_q + 1'b1;
// A read: from a falling edge after rest until a high phase outlasts HIGH_CLOCKS.
wire in_read_now = fell || (in_read_q && !(o_ssi_clk && len_now > HIGH_CLOCKS));
wire read_over = in_read_q && !in_read_now;
wire [7:0] rises_now = (fell && !in_read_q) ? 8'd0 : rises_q + rose;

always @(posedge i_clk) begin
    // The core's outputs before reset are not its own: the clock is taken idle then.
    clk_q <= i_rst || o_ssi_clk;
    len_q <= i_rst ? 0 : len_now;
    in_read_q <= !i_rst && in_read_now;
    rises_q <= i_rst ? 8'd0 : rises_now;
    if (read_over) had_read <= 1'b1;
end

always @* if (f_past) begin
    if (fell && !in_read_q && had_read) t_m: assert (len_q >= PAUSE_CLOCKS);
    if (fell && in_read_q) clock_high: assert (len_q == HIGH_CLOCKS);
    if (rose && rises_q == 0) t_cs: assert (len_q >= T_CS_CLOCKS);
    if (rose && rises_q != 0) clock_low: assert (len_q == LOW_CLOCKS);
    if (rose) clock_count: assert (in_read_q && rises_q <= SAMPLED);
    if (read_over) clock_count_end: assert (rises_q == SAMPLED + 1);
    if (!o_ssi_clk) clock_at_rest: assert (o_busy);
end

/* Host interface */
reg  done_q = 1'b0;
reg  pending = 1'b0;     // a start taken, its o_done not yet seen
reg  start_q = 1'b0;     // a start was taken in the previous cycle
reg  data_d1 = 1'b1, data_d2 = 1'b1, data_low_q = 1'b0;
wire start_taken = f_past && i_start && !o_busy;
always @(posedge i_clk) begin
    done_q <= !i_rst && o_done;
    if (start_taken) pending <= 1'b1;
    else if (o_done) pending <= 1'b0;
    start_q <= start_taken;
    // The synchroniser reads the line idle (high) through reset.
    data_d1 <= i_rst || i_ssi_data;
    data_d2 <= i_rst || data_d1;
    // The level the core's two-flop synchroniser shows in the cycle of the start.
    data_low_q <= !data_d2;
end

always @* if (f_past) begin
    // One cycle per start: back to back only for a start taken in between.
    done_pulse: assert ((!(o_done && done_q) || start_q) && (!o_done || pending));
    if (start_taken) done_once: assert (!pending || o_done);
    if (!o_busy && !start_q) busy_done: assert (!pending);
    err_with_done: assert (!(o_err_idle || o_err_double || o_err_wire) || o_done);
    err_idle: assert (o_err_idle == (start_q && data_low_q));
    if (o_err_idle) err_idle_no_clock: assert (o_ssi_clk && !o_busy);
end

/* The word on the pin */
// The bit of each data low phase is the pin level in the first cycle the
// clock reads low (SAMPLE_DELAY = 1 edge after the falling edge).
reg [SAMPLED-1:0] word = 0;
always @(posedge i_clk) begin
    if (fell && !in_read_q) word <= 0;
    else if (fell) word <= {word[SAMPLED-2:0], i_ssi_data};
end
wire [BITS-1:0] first_copy = word[SAMPLED-1 -: BITS];
// Gray to binary: bit i is the XOR of the Gray bits from the MSB down to i.
reg [BITS-1:0] first_binary;
integer i;
always @* begin
    for (i = 0; i < BITS; i = i + 1) first_binary[i] = ^(first_copy >> i);
end

always @* if (f_past && o_done && !o_err_idle) begin
    position: assert (o_position == ((GRAY != 0) ? first_binary : first_copy));
    if (DOUBLE_READ != 0) double_read: assert (o_err_double == (first_copy != word[BITS-1:0]));
    else double_read_off: assert (!o_err_double);
    if (WIRE_CHECK != 0) wire_check: assert (o_err_wire == word[0]);
    else wire_check_off: assert (!o_err_wire);
end
/* Helper invariants (k-induction): the harness's view against the core's registers */
localparam integer PHASE_MAX = (HIGH_CLOCKS > LOW_CLOCKS) ? HIGH_CLOCKS : LOW_CLOCKS;
localparam integer CNT_MAX = (PAUSE_CLOCKS > T_CS_CLOCKS) ? ((PAUSE_CLOCKS > PHASE_MAX) ? PAUSE_CLOCKS : PHASE_MAX)
                                                         : ((T_CS_CLOCKS > PHASE_MAX) ? T_CS_CLOCKS : PHASE_MAX);
localparam integer CNT_W = $clog2(CNT_MAX + 1);
localparam integer CAPTURE_AT = LOW_CLOCKS - 2 - SAMPLE_DELAY;
(* keep *) wire [2:0]       probe_state;
(* keep *) wire [CNT_W-1:0] probe_cnt;
(* keep *) wire [7:0]       probe_bits;
(* keep *) wire             probe_sync;
(* keep *) wire             probe_meta;
(* keep *) wire             probe_wire_bad;
always @* if (f_past) begin
    inv_sync: assert (probe_sync == data_d2 && probe_meta == data_d1);
    if (WIRE_CHECK == 0) inv_wire: assert (!probe_wire_bad);
    case (probe_state)
    3'd0: inv_idle: assert (o_ssi_clk && !o_busy && !in_read_now && (!pending || (o_done && o_err_idle)));
    3'd1: inv_latch: assert (!o_ssi_clk && o_busy && in_read_now && rises_now == 0 && probe_bits == 0 && pending
                             && !o_done && len_now + probe_cnt == T_CS_CLOCKS);
    3'd2: inv_high: assert (o_ssi_clk && o_busy && in_read_now && rises_now == probe_bits + 1 && probe_bits < SAMPLED
                            && pending && !o_done && len_now + probe_cnt == HIGH_CLOCKS);
    3'd3: inv_low: assert (!o_ssi_clk && o_busy && in_read_now && pending && !o_done && len_now + probe_cnt == LOW_CLOCKS
                           && probe_bits + (probe_cnt >= CAPTURE_AT) == rises_now && rises_now <= SAMPLED);
    3'd4: inv_pause: assert (o_ssi_clk && o_busy && len_now + probe_cnt == PAUSE_CLOCKS
                             && in_read_now == (len_now <= HIGH_CLOCKS) && (!in_read_now || rises_now == SAMPLED + 1)
                             && (!pending || o_done) && !start_q && (o_done == (len_now == 1)));
    default: inv_state: assert (0);
    endcase
end

`endif

endmodule
