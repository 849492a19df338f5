// endat_master_formal: the EnDat master's clock rules on the unchanged core.
//
// What it checks (seed 004, EnDat 2.2 D297403; model/src/endat/rules.rs), in
// cycles of i_clk at the core's configuration, watched on o_endat_clk with
// counters of this harness (none of the core's); any command on i_mode, any
// encoder on the data line:
//   t_st               the first low phase of a frame lasts at least
//                      T_ST_CLOCKS (t_ST: the encoder's send block off)
//   clock_low          every later low phase of a frame lasts LOW_CLOCKS
//   clock_high         every high phase inside a frame lasts HIGH_CLOCKS, so
//                      the period and the on-off ratio are the configured ones
//   recovery           a frame starts only after the clock has been high for at
//                      least the shortest pause of the rule book, min(t_m, t_b,
//                      the wait after an error) = min(T_M_CLOCKS, T_B_CLOCKS,
//                      T_ERR_CLOCKS), since the previous frame's last rising edge
//   clock_at_rest      the clock is low only while o_busy is high
//
// Not yet here: the pause per command type (t_b after type 2.1, t_m after
// 2.2), the clock counts per mode, the send block and the CRC check. The
// delay measurement is not driven (DELAY_COMP = 0, i_meas low): its slower
// clock is a rule of its own (MEAS_CLOCK).
//
// The core's registers start from any value (the script drops their initial
// values): reset in the first cycle is what defines them. The probe_* wires
// serve only the helper invariants (inv_*) of the induction.

`default_nettype none

module endat_master_formal #(
    parameter POS_BITS = 2,
    parameter CLOCKS_PER_BIT = 8,
    parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2,
    parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2,
    parameter MEAS_CLOCKS_PER_BIT = 16,
    parameter T_ST_CLOCKS = 6,
    parameter TIMEOUT_CLOCKS = 8,
    parameter T_M_CLOCKS = 12,
    parameter T_B_CLOCKS = 20,
    parameter T_ERR_CLOCKS = 14,
    parameter BLOCK_GAP = 2
) (
    input wire        i_clk,
    input wire        i_start,
    input wire [5:0]  i_mode,
    input wire [7:0]  i_mrs,
    input wire [15:0] i_param,
    input wire [7:0]  i_cont_values,
    input wire        i_endat_data_in
);

localparam integer T_MIN_AB = (T_M_CLOCKS < T_B_CLOCKS) ? T_M_CLOCKS : T_B_CLOCKS;
localparam integer T_MIN = (T_ERR_CLOCKS < T_MIN_AB) ? T_ERR_CLOCKS : T_MIN_AB;
localparam integer LEN_MAX = HIGH_CLOCKS + T_B_CLOCKS + T_M_CLOCKS + T_ERR_CLOCKS;

reg f_past = 1'b0;
always @(posedge i_clk) f_past <= 1'b1;
wire i_rst = !f_past;

wire o_busy, o_endat_clk;
/* verilator lint_off UNUSEDSIGNAL */
wire [47:0] o_position;
wire [23:0] o_ad1, o_ad2;
wire [7:0] o_ack_addr;
wire [15:0] o_ack_data, o_delay;
wire o_done, o_f1, o_f2, o_ad1_valid, o_ad2_valid, o_err_crc, o_err_ad1_crc, o_err_ad2_crc, o_err_type2,
     o_err_type3, o_err_type4, o_err_ack, o_err_timeout, o_err_absent, o_err_idle, o_err_delay, o_meas_done,
     o_err_meas, o_delay_valid, o_endat_data_out, o_endat_data_oe;
/* verilator lint_on UNUSEDSIGNAL */

endat_master #(
    .POS_BITS(POS_BITS), .CLOCKS_PER_BIT(CLOCKS_PER_BIT), .HIGH_CLOCKS(HIGH_CLOCKS), .LOW_CLOCKS(LOW_CLOCKS),
    .MEAS_CLOCKS_PER_BIT(MEAS_CLOCKS_PER_BIT), .T_ST_CLOCKS(T_ST_CLOCKS), .DELAY_COMP(0), .SAMPLE_DELAY(0),
    .DELAY_TOL(1), .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS), .T_M_CLOCKS(T_M_CLOCKS), .T_B_CLOCKS(T_B_CLOCKS),
    .T_ERR_CLOCKS(T_ERR_CLOCKS), .BLOCK_GAP(BLOCK_GAP)
) dut (
    .i_clk(i_clk), .i_rst(i_rst), .i_start(i_start), .i_mode(i_mode), .i_mrs(i_mrs), .i_param(i_param),
    .i_cont_values(i_cont_values), .i_meas(1'b0), .o_busy(o_busy), .o_done(o_done),
    .o_position(o_position), .o_f1(o_f1), .o_f2(o_f2), .o_ad1(o_ad1), .o_ad1_valid(o_ad1_valid),
    .o_ad2(o_ad2), .o_ad2_valid(o_ad2_valid), .o_ack_addr(o_ack_addr), .o_ack_data(o_ack_data),
    .o_err_crc(o_err_crc), .o_err_ad1_crc(o_err_ad1_crc), .o_err_ad2_crc(o_err_ad2_crc),
    .o_err_type2(o_err_type2), .o_err_type3(o_err_type3), .o_err_type4(o_err_type4), .o_err_ack(o_err_ack),
    .o_err_timeout(o_err_timeout), .o_err_absent(o_err_absent), .o_err_idle(o_err_idle),
    .o_err_delay(o_err_delay), .o_meas_done(o_meas_done), .o_err_meas(o_err_meas),
    .o_delay_valid(o_delay_valid), .o_delay(o_delay),
    .o_endat_clk(o_endat_clk), .o_endat_data_out(o_endat_data_out), .o_endat_data_oe(o_endat_data_oe),
    .i_endat_data_in(i_endat_data_in)
);

/* The clock as the encoder sees it */
// Each *_now is this cycle's value, its *_q the previous cycle's.
reg                         clk_q = 1'b1;
reg [$clog2(LEN_MAX+1)-1:0] len_q = LEN_MAX;
reg                         in_frame_q = 1'b0;
reg                         had_frame = 1'b0;   // a frame has ended since reset
reg                         rose_in_frame_q = 1'b0;
wire fell = clk_q && !o_endat_clk;
wire rose = !clk_q && o_endat_clk;
wire [$clog2(LEN_MAX+1)-1:0] len_now = (fell || rose) ? 1 : (len_q == LEN_MAX) ? len_q : len_q + 1'b1;
// A frame: from a falling edge after rest until a high phase outlasts HIGH_CLOCKS.
wire in_frame_now = fell || (in_frame_q && !(o_endat_clk && len_now > HIGH_CLOCKS));
wire frame_over = in_frame_q && !in_frame_now;
wire rose_in_frame_now = (fell && !in_frame_q) ? 1'b0 : (rose_in_frame_q || rose);
always @(posedge i_clk) begin
    // Before reset the outputs are not the core's own: the clock is taken at rest.
    clk_q <= i_rst || o_endat_clk;
    len_q <= i_rst ? LEN_MAX : len_now;
    in_frame_q <= !i_rst && in_frame_now;
    rose_in_frame_q <= !i_rst && rose_in_frame_now;
    if (frame_over) had_frame <= 1'b1;
end

always @* if (f_past) begin
    if (rose && !rose_in_frame_q) t_st: assert (len_q >= T_ST_CLOCKS);
    if (rose && rose_in_frame_q) clock_low: assert (len_q == LOW_CLOCKS);
    if (fell && in_frame_q) clock_high: assert (len_q == HIGH_CLOCKS);
    if (fell && !in_frame_q && had_frame) recovery: assert (len_q >= T_MIN);
    if (!o_endat_clk) clock_at_rest: assert (o_busy);
end

/* Helper invariants (k-induction): the harness's view against the core's registers */
localparam integer MAX_A = (T_B_CLOCKS > T_M_CLOCKS) ? T_B_CLOCKS : T_M_CLOCKS;
localparam integer MAX_B = (T_ERR_CLOCKS > T_ST_CLOCKS) ? T_ERR_CLOCKS : T_ST_CLOCKS;
localparam integer MAX_C = (MAX_A > MAX_B) ? MAX_A : MAX_B;
localparam integer CNT_MAX = (MAX_C > MEAS_CLOCKS_PER_BIT) ? MAX_C : MEAS_CLOCKS_PER_BIT;
localparam integer CNT_W = $clog2(CNT_MAX + 1);
(* keep *) wire [2:0]       probe_state;
(* keep *) wire [CNT_W-1:0] probe_cnt;
(* keep *) wire             probe_meas_on;
(* keep *) wire             probe_meas_frame;
always @* if (f_past) begin
    inv_len: assert (len_q <= LEN_MAX && !probe_meas_on && !probe_meas_frame && o_busy == (probe_state != 3'd0));
    case (probe_state)
    3'd0: inv_idle: assert (o_endat_clk && !in_frame_now && (!had_frame || len_now >= T_MIN));
    3'd1: inv_first: assert (!o_endat_clk && in_frame_now && !rose_in_frame_now && len_now + probe_cnt == T_ST_CLOCKS);
    3'd2: inv_high: assert (o_endat_clk && in_frame_now && rose_in_frame_now && len_now + probe_cnt == HIGH_CLOCKS);
    3'd3: inv_low: assert (!o_endat_clk && in_frame_now && rose_in_frame_now && len_now + probe_cnt == LOW_CLOCKS);
    3'd4: inv_pause: assert (o_endat_clk && len_now + probe_cnt >= HIGH_CLOCKS + T_MIN
                             && in_frame_now == (len_now <= HIGH_CLOCKS) && (in_frame_now || rose_in_frame_q || had_frame));
    default: inv_state: assert (0);
    endcase
end

endmodule
