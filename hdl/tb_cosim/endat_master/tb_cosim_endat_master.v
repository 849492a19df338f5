// tb_cosim_endat_master: endat_master closed-loop against the EnDat encoder
// emulator (hdl/emu/endat_encoder_emu.v), no vectors. Each transfer: a random
// position and random F1 and F2 (set independently: F2 comes from a separate
// detection unit) in the emulator, then one request:
//   * "send position values" 2.2 (111000), most of them;
//   * every 50th, "send position values" 2.1 (000111), where f_sys <= 16 MHz
//     (each costs t_b = 1 ms of simulated time);
//   * every 16th (not a 2.1 one), a bit of the frame flipped by the emulator
//     (schedule_fault): the core must flag o_err_crc;
//   * every 40th, six mode bits that are no command (000000): the encoder
//     answers with error handling type I (no start bit, seed 004 A2 4.2.1),
//     the core must flag o_err_timeout and the next transfer must succeed.
// At o_done the core's o_position, o_f1, o_f2 must equal what the emulator
// says it latched and sent (u_emu.last_value / last_status), which must equal
// what was set, with no other error pulse; one latch per request.
//
// Plusargs: +endat_emu_config=<scenario.toml>, +transactions=N (default 1000),
// +seed=S, +flip_bit=K (planted failure: the comparison flips bit K of the
// core's o_position, so the run must fail), +endat_monitor_transcript=FILE
// (the monitor's JSON transcript).
//
// A pin-level monitor (hdl/emu/endat_monitor.v) watches the core's clock, its
// data driver and the data at its input, reading the same configuration:
// before each transfer it must have decoded every earlier one as the core
// read it (position, F1, F2; the CRC error of a flipped frame; no start bit
// after the type I answer), and the core must break none of the seed's
// timing rules it checks.

`timescale 1fs / 1fs
`include "endat_monitor.v"
`default_nettype none

module tb_cosim_endat_master;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter POS_BITS = 25;
parameter CLOCKS_PER_BIT = 64;
parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2;
parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2;
parameter MEAS_CLOCKS_PER_BIT = 320;
parameter MEAS_HIGH_CLOCKS = MEAS_CLOCKS_PER_BIT - MEAS_CLOCKS_PER_BIT / 2;
parameter MEAS_LOW_CLOCKS = MEAS_CLOCKS_PER_BIT / 2;
parameter T_ST_CLOCKS = 32;
parameter DELAY_COMP = 0;
parameter SAMPLE_DELAY = 0;
parameter MEAS_COUNT = 4;
parameter MEAS_RETRIES = 3;
parameter DELAY_TOL = 8;
parameter DELAY_MAX = 1020;
parameter TIMEOUT_CLOCKS = 50;
parameter T_M_CLOCKS = 1952;
parameter T_B_CLOCKS = 64640;
parameter T_ERR_CLOCKS = 1952;
parameter BLOCK_GAP = 16;

/* Harness parameters */
parameter F_SYS_HZ = 64000000;
parameter HALF_PERIOD_FS = 7_812_500;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_start = 1'b0;
reg [5:0] i_mode = 6'b111000;
wire o_busy, o_done;
wire [47:0] o_position;
wire o_f1, o_f2, o_ad1_valid, o_ad2_valid;
wire [23:0] o_ad1, o_ad2;
wire [7:0] o_ack_addr;
wire [15:0] o_ack_data, o_delay;
wire o_err_crc, o_err_ad1_crc, o_err_ad2_crc, o_err_type2, o_err_type3, o_err_type4, o_err_ack;
wire o_err_timeout, o_err_absent, o_err_idle, o_err_delay, o_meas_done, o_err_meas, o_delay_valid;
wire endat_clk, data_out, data_oe, data_in, enc_oe;

endat_master #(
    .POS_BITS(POS_BITS),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .HIGH_CLOCKS(HIGH_CLOCKS),
    .LOW_CLOCKS(LOW_CLOCKS),
    .MEAS_CLOCKS_PER_BIT(MEAS_CLOCKS_PER_BIT),
    .MEAS_HIGH_CLOCKS(MEAS_HIGH_CLOCKS),
    .MEAS_LOW_CLOCKS(MEAS_LOW_CLOCKS),
    .T_ST_CLOCKS(T_ST_CLOCKS),
    .DELAY_COMP(DELAY_COMP),
    .SAMPLE_DELAY(SAMPLE_DELAY),
    .MEAS_COUNT(MEAS_COUNT),
    .MEAS_RETRIES(MEAS_RETRIES),
    .DELAY_TOL(DELAY_TOL),
    .DELAY_MAX(DELAY_MAX),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .T_M_CLOCKS(T_M_CLOCKS),
    .T_B_CLOCKS(T_B_CLOCKS),
    .T_ERR_CLOCKS(T_ERR_CLOCKS),
    .BLOCK_GAP(BLOCK_GAP)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .i_mode(i_mode),
    .i_mrs(8'd0),
    .i_param(16'd0),
    .i_cont_values(8'd0),
    .i_meas(1'b0),
    .o_busy(o_busy),
    .o_done(o_done),
    .o_position(o_position),
    .o_f1(o_f1),
    .o_f2(o_f2),
    .o_ad1(o_ad1),
    .o_ad1_valid(o_ad1_valid),
    .o_ad2(o_ad2),
    .o_ad2_valid(o_ad2_valid),
    .o_ack_addr(o_ack_addr),
    .o_ack_data(o_ack_data),
    .o_err_crc(o_err_crc),
    .o_err_ad1_crc(o_err_ad1_crc),
    .o_err_ad2_crc(o_err_ad2_crc),
    .o_err_type2(o_err_type2),
    .o_err_type3(o_err_type3),
    .o_err_type4(o_err_type4),
    .o_err_ack(o_err_ack),
    .o_err_timeout(o_err_timeout),
    .o_err_absent(o_err_absent),
    .o_err_idle(o_err_idle),
    .o_err_delay(o_err_delay),
    .o_meas_done(o_meas_done),
    .o_err_meas(o_err_meas),
    .o_delay_valid(o_delay_valid),
    .o_delay(o_delay),
    .o_endat_clk(endat_clk),
    .o_endat_data_out(data_out),
    .o_endat_data_oe(data_oe),
    .i_endat_data_in(data_in)
);

// The emulator on the core's own clock; any clock of at least 4 x the EnDat clock would do.
endat_encoder_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_endat_clk(endat_clk),
    .i_endat_data(data_out),
    .i_endat_data_oe(data_oe),
    .o_endat_data(data_in),
    .o_endat_data_oe(enc_oe)
);

// The pin-level monitor and protocol checker, on the same clock.
endat_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("endat_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_endat_clk(endat_clk),
    .i_endat_data(data_out),
    .i_endat_data_oe(data_oe),
    .i_endat_data_in(data_in)
);

`include "emu_random.vh"
integer transactions, seed, flip_bit, n, waited, flip_at, crc_errs, type1s;
integer mbase, last_kind;
reg [63:0] core_last;
reg core_f1, core_f2;

// The monitor has decoded `seen` transfers since the power-on measurement, the
// last one as the core read it: kind 0 a clean read (position, F1, F2 of a
// 2.2 frame), 1 a flipped frame bit (CRC error), 2 no start bit (type I).
task check_monitor(input integer seen, input integer kind, input is21_last);
    begin
        if (u_mon.count(0) != mbase + seen)
            $fatal(1, "at %0t: the monitor decoded %0d transfers after the power-on measurement, the core made %0d", $time, u_mon.count(0) - mbase, seen);
        if (seen > 0) begin
            if (kind == 0 && (u_mon.last_value(0) != core_last || u_mon.last_status(0, "f1") != core_f1
                              || !u_mon.last_status(0, "crc_ok")))
                $fatal(1, "transfer %0d at %0t: the monitor read %0d F1 %0d crc_ok %0d on the line, the core %0d F1 %b",
                       seen - 1, $time, u_mon.last_value(0), u_mon.last_status(0, "f1"), u_mon.last_status(0, "crc_ok"), core_last, core_f1);
            if (kind == 0 && !is21_last && u_mon.last_status(0, "f2") != core_f2)
                $fatal(1, "transfer %0d at %0t: the monitor read F2 %0d on the line, the core %b", seen - 1, $time, u_mon.last_status(0, "f2"), core_f2);
            if (kind == 1 && u_mon.last_status(0, "crc_ok"))
                $fatal(1, "transfer %0d at %0t: a frame bit flipped by the emulator, the monitor saw no CRC error", seen - 1, $time);
            if (kind == 2 && !u_mon.last_status(0, "error"))
                $fatal(1, "transfer %0d at %0t: a type I answer (no start bit), the monitor saw no error", seen - 1, $time);
        end
    end
endtask
reg [63:0] base;
integer emu_f2;
reg [63:0] position, mask, got, sent;
reg f1, f2, is21, flip, type1;
reg [8*80-1:0] fault;

// Every error pulse but the expected one.
function other_errors(input expect_crc, input expect_timeout);
    other_errors = (o_err_crc && !expect_crc) || (o_err_timeout && !expect_timeout) || o_err_ad1_crc || o_err_ad2_crc
        || o_err_type2 || o_err_type3 || o_err_type4 || o_err_ack || o_err_absent || o_err_idle || o_err_delay || o_err_meas;
endfunction

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    mask = (POS_BITS >= 64) ? {64{1'b1}} : ((64'd1 << POS_BITS) - 64'd1);
    crc_errs = 0;
    type1s = 0;
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    repeat (4) @(posedge clk);
    // With DELAY_COMP the core measures the round trip first (o_busy high).
    while (o_busy) @(posedge clk);
    // The measurement's own transfers (four at least) count as latches too.
    base = u_emu.count(0);
    mbase = u_mon.count(0);
    last_kind = 0;
    for (n = 0; n < transactions; n = n + 1) begin
        check_monitor(n, last_kind, is21);
        // A 2.1 read costs t_b = 1 ms after it: only where that is cheap (f_sys <= 16 MHz).
        is21 = (n % 50) == 49 && F_SYS_HZ <= 16000000;
        type1 = !is21 && (n % 40) == 39;
        flip = !is21 && !type1 && (n % 16) == 15;
        position = random64(0) & mask;
        f1 = random32(0);
        f2 = random32(0);
        u_emu.set_position(0, position);
        u_emu.set_status(0, "f1", f1);
        u_emu.set_status(0, "f2", f2);
        if (flip) begin
            // One bit of F1, F2, the position or the CRC (bits after the start bit).
            flip_at = {random32(0)} % (POS_BITS + 7);
            $sformat(fault, "[faults]\nflips = [{ request = %0d, bits = [%0d] }]", u_emu.count(0), flip_at);
            u_emu.schedule_fault(fault);
        end
        i_mode <= type1 ? 6'b000000 : (is21 ? 6'b000111 : 6'b111000);
        i_start <= 1'b1;
        @(posedge clk);
        i_start <= 1'b0;
        waited = 0;
        @(posedge clk);
        while (!o_done) begin
            @(posedge clk);
            waited = waited + 1;
            if (waited > 200 * CLOCKS_PER_BIT + TIMEOUT_CLOCKS * CLOCKS_PER_BIT + T_ERR_CLOCKS)
                $fatal(1, "transfer %0d: no o_done", n);
        end
        core_last = o_position & mask;
        core_f1 = o_f1;
        core_f2 = o_f2;
        last_kind = type1 ? 2 : (flip ? 1 : 0);
        if (u_emu.count(0) != base + n + 1)
            $fatal(1, "transfer %0d at %0t: the emulator counted %0d transfers after the %0d of the power-on measurement", n, $time, u_emu.count(0) - base, base);
        if (other_errors(flip, type1))
            $fatal(1, "transfer %0d at %0t: unexpected error pulse crc %b timeout %b type2 %b absent %b idle %b delay %b",
                   n, $time, o_err_crc, o_err_timeout, o_err_type2, o_err_absent, o_err_idle, o_err_delay);
        if (type1) begin
            if (!o_err_timeout)
                $fatal(1, "transfer %0d at %0t: mode 000000 (type I) without o_err_timeout", n, $time);
            type1s = type1s + 1;
        end else if (flip) begin
            if (!o_err_crc)
                $fatal(1, "transfer %0d at %0t: frame bit %0d flipped by the emulator, the core saw no CRC error", n, $time, flip_at);
            crc_errs = crc_errs + 1;
        end else begin
            sent = u_emu.last_value(0);
            got = o_position & mask;
            if (flip_bit >= 0) got = got ^ (64'd1 << flip_bit);
            // A 2.1 frame carries no F2 (ask only for 2.2: Icarus does not short-circuit calls).
            emu_f2 = !f2;
            if (!is21) emu_f2 = u_emu.last_status(0, "f2");
            if (sent !== position || u_emu.last_status(0, "f1") != f1 || emu_f2 != !f2)
                $fatal(1, "transfer %0d at %0t: the emulator latched %0d F1 %0d F2 %0d, the testbench set %0d f1 %b f2 %b",
                       n, $time, sent, u_emu.last_status(0, "f1"), emu_f2, position, f1, f2);
            if (got !== sent || o_f1 !== f1 || (!is21 && o_f2 !== !f2) || o_err_crc)
                $fatal(1, "transfer %0d at %0t (%0s): core read %0d F1 %b F2 %b crc_err %b, the emulator sent %0d F1 %b F2 %b",
                       n, $time, is21 ? "2.1" : "2.2", got, o_f1, o_f2, o_err_crc, sent, f1, !f2);
        end
        while (o_busy) @(posedge clk);
    end
    repeat (4 * CLOCKS_PER_BIT) @(posedge clk);
    check_monitor(transactions, last_kind, is21);
    if (u_mon.violations(0) != 0)
        $fatal(1, "the monitor saw %0d timing violation(s) of the seed by the core (PROTOCOL VIOLATION lines above)", u_mon.violations(0));
    if (u_emu.violations(0) != 0)
        $fatal(1, "the core broke %0d timing rule(s) of the seed (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_endat_master: %0d transfers (%0d CRC faults flagged, %0d type I answered), every o_position, o_f1, o_f2 equal to the emulator's and to the monitor's",
             transactions, crc_errs, type1s);
    $finish;
end

endmodule

`default_nettype wire
