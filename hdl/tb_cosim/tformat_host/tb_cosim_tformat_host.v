// tb_cosim_tformat_host: tformat_host closed-loop against the T-format
// encoder emulator (hdl/emu/tformat_encoder_emu.v), no vectors. Each
// readout: a random position (17-bit ABS, 16-bit ABM) and random ALMC flags
// (each set on its own) in the emulator, then one request: Data ID 3 (ABS,
// ENID, ABM, ALMC) most of the time, every 5th Data ID 0 (ABS), every 7th
// Data ID 1 (ABM). Every 16th answer the emulator flips one data bit of one
// field after the control field (schedule_fault): the host must flag
// o_err_crc (and o_err_comm when the flipped bit is ca0 or ca1 of the status
// field). Otherwise at o_done the host's o_abs, o_abm, o_almc and o_sf
// must equal what the emulator says it sent (u_emu.last_value / last_status),
// which must equal what was set, with no error pulse; one answer per request.
//
// A pin-level monitor (hdl/emu/tformat_monitor.v) watches the host's D, DE
// and R: after every readout its decoded transaction must equal the host's
// outputs (ABS, ABM, ALMC; the CRC error of a flipped answer and no other),
// and it must see no timing violation of the seed.
//
// Plusargs: +tformat_emu_config=<scenario.toml>, +transactions=N (default
// 1000), +seed=S, +flip_bit=K (planted failure: the comparison flips bit K
// of the host's o_abs, so the run must fail), +tformat_monitor_transcript=FILE
// (the monitor's JSON transcript).

`timescale 1fs / 1fs
`include "tformat_monitor.v"
`default_nettype none

module tb_cosim_tformat_host;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter CLOCKS_PER_BIT = 32;
parameter TIMEOUT_CLOCKS = 1000;
parameter REPEAT_GAP_CLOCKS = 4000000;

/* Harness parameters */
parameter F_SYS_HZ = 80000000;
parameter HALF_PERIOD_FS = 6_250_000;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_start = 1'b0;
reg [3:0] i_data_id = 4'd3;
wire o_busy, o_done;
wire [7:0] o_cf, o_sf, o_enid, o_almc, o_adf, o_edf;
wire [16:0] o_abs;
wire [15:0] o_abm;
wire o_err_crc, o_err_timeout, o_err_frame, o_err_cf, o_err_comm;
wire tx, tx_en, rx, enc_oe;

tformat_host #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .REPEAT_GAP_CLOCKS(REPEAT_GAP_CLOCKS)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .i_data_id(i_data_id),
    .i_address(7'd0),
    .i_wdata(8'd0),
    .o_busy(o_busy),
    .o_done(o_done),
    .o_cf(o_cf),
    .o_sf(o_sf),
    .o_abs(o_abs),
    .o_abm(o_abm),
    .o_enid(o_enid),
    .o_almc(o_almc),
    .o_adf(o_adf),
    .o_edf(o_edf),
    .o_err_crc(o_err_crc),
    .o_err_timeout(o_err_timeout),
    .o_err_frame(o_err_frame),
    .o_err_cf(o_err_cf),
    .o_err_comm(o_err_comm),
    .o_tx(tx),
    .o_tx_en(tx_en),
    .i_rx(rx)
);

// The emulator on the host's own clock (a whole multiple of 2.5 Mbps).
tformat_encoder_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_tf_data(tx),
    .i_tf_data_oe(tx_en),
    .o_tf_data(rx),
    .o_tf_data_oe(enc_oe)
);

// The pin-level monitor and protocol checker, on the same clock.
tformat_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("tformat_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_tf_data(tx),
    .i_tf_data_oe(tx_en),
    .i_tf_rx(rx)
);

`include "emu_random.vh"
integer transactions, seed, flip_bit, n, waited, k, crc_errs, field, bit_i;
reg [16:0] st;
reg [15:0] mt;
reg [7:0] almc, want_sf;
reg [63:0] sent;
reg [16:0] got_abs;
reg flip;
reg [3:0] id;
reg [8*80-1:0] fault;

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    crc_errs = 0;
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    repeat (4) @(posedge clk);
    for (n = 0; n < transactions; n = n + 1) begin
        id = (n % 5) == 4 ? 4'd0 : ((n % 7) == 6 ? 4'd1 : 4'd3);
        flip = (n % 16) == 15;
        st = random32(0);
        mt = random32(0);
        almc = random32(0) & 8'hEF; // bit 4 is always 0
        u_emu.set_position(0, {mt, st});
        u_emu.set_status(0, "over_speed", almc[0]);
        u_emu.set_status(0, "full_absolute", almc[1]);
        u_emu.set_status(0, "counting_error", almc[2]);
        u_emu.set_status(0, "counter_overflow", almc[3]);
        u_emu.set_status(0, "multi_turn_error", almc[5]);
        u_emu.set_status(0, "battery_error", almc[6]);
        u_emu.set_status(0, "battery_alarm", almc[7]);
        // ea0 = CE, ea1 = ME | BE | BA (seed 002, 6.3.2)
        want_sf = {2'b00, almc[5] | almc[6] | almc[7], almc[2], 4'b0000};
        if (flip) begin
            // A data bit (1..8) of a field after CF: SF, the data or the CRC.
            field = 1 + {random32(0)} % (id == 4'd3 ? 10 : 5);
            bit_i = 1 + {random32(0)} % 8;
            $sformat(fault, "flips = [{ answer = %0d, field = %0d, bit = %0d }]", u_emu.count(0), field, bit_i);
            u_emu.schedule_fault(fault);
        end
        i_data_id <= id;
        i_start <= 1'b1;
        @(posedge clk);
        i_start <= 1'b0;
        waited = 0;
        @(posedge clk);
        while (!o_done) begin
            @(posedge clk);
            waited = waited + 1;
            if (waited > 200 * CLOCKS_PER_BIT + TIMEOUT_CLOCKS)
                $fatal(1, "readout %0d: no o_done", n);
        end
        if (u_emu.count(0) != n + 1)
            $fatal(1, "readout %0d at %0t: the emulator counted %0d answers", n, $time, u_emu.count(0));
        if (o_err_timeout || o_err_frame || o_err_cf || (o_err_comm && !flip) || (o_err_crc && !flip))
            $fatal(1, "readout %0d at %0t (Data ID %0d): error pulse crc %b timeout %b frame %b cf %b comm %b",
                   n, $time, id, o_err_crc, o_err_timeout, o_err_frame, o_err_cf, o_err_comm);
        if (flip) begin
            if (!o_err_crc)
                $fatal(1, "readout %0d at %0t: field %0d bit %0d flipped by the emulator, the host saw no CRC error", n, $time, field, bit_i);
            crc_errs = crc_errs + 1;
        end else begin
            sent = u_emu.last_value(0);
            got_abs = o_abs;
            if (flip_bit >= 0) got_abs = got_abs ^ (17'd1 << flip_bit);
            if (o_sf !== want_sf)
                $fatal(1, "readout %0d at %0t: SF %h, set alarms give %h", n, $time, o_sf, want_sf);
            if (id != 4'd1 && (sent[16:0] !== st || got_abs !== st))
                $fatal(1, "readout %0d at %0t (Data ID %0d): ABS host %0d emulator %0d set %0d", n, $time, id, got_abs, sent[16:0], st);
            if (id != 4'd0 && (sent[32:17] !== mt || o_abm !== mt))
                $fatal(1, "readout %0d at %0t (Data ID %0d): ABM host %0d emulator %0d set %0d", n, $time, id, o_abm, sent[32:17], mt);
            if (id == 4'd3) begin
                if (o_almc !== almc)
                    $fatal(1, "readout %0d at %0t: ALMC host %h set %h", n, $time, o_almc, almc);
                if (u_emu.last_status(0, "battery_alarm") != almc[7] || u_emu.last_status(0, "over_speed") != almc[0])
                    $fatal(1, "readout %0d at %0t: the emulator reports other alarms than set (%h)", n, $time, almc);
            end
        end
        // The monitor decoded the same readout off the pins.
        if (u_mon.count(0) != n + 1)
            $fatal(1, "readout %0d at %0t: the monitor decoded %0d transactions", n, $time, u_mon.count(0));
        if (u_mon.last_status(0, "crc") != flip || u_mon.last_status(0, "timeout") || u_mon.last_status(0, "frame")
            || u_mon.last_status(0, "cf_mismatch"))
            $fatal(1, "readout %0d at %0t: the monitor's errors crc %b timeout %b frame %b cf %b (flipped %b)", n, $time,
                   u_mon.last_status(0, "crc"), u_mon.last_status(0, "timeout"), u_mon.last_status(0, "frame"),
                   u_mon.last_status(0, "cf_mismatch"), flip);
        if (!flip) begin
            sent = u_mon.last_value(0);
            if ((id != 4'd1 && sent[16:0] !== got_abs) || (id != 4'd0 && sent[32:17] !== o_abm)
                || (id == 4'd3 && (u_mon.last_status(0, "battery_alarm") != o_almc[7] || u_mon.last_status(0, "over_speed") != o_almc[0]
                                   || u_mon.last_status(0, "multi_turn_error") != o_almc[5])))
                $fatal(1, "readout %0d at %0t (Data ID %0d): the monitor read ABS %0d ABM %0d on the line, the host ABS %0d ABM %0d ALMC %h",
                       n, $time, id, sent[16:0], sent[32:17], got_abs, o_abm, o_almc);
        end
        while (o_busy) @(posedge clk);
        // Request spacing: a few bits of idle line between operations.
        repeat (4 * CLOCKS_PER_BIT) @(posedge clk);
    end
    if (u_emu.violations(0) != 0)
        $fatal(1, "the host broke %0d timing rule(s) (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    if (u_mon.violations(0) != 0)
        $fatal(1, "the monitor saw %0d timing violation(s) of the seed by the host (PROTOCOL VIOLATION lines above)", u_mon.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_tformat_host: %0d readouts (%0d CRC faults flagged), every o_abs, o_abm, o_almc, o_sf equal to the emulator's and to the monitor's",
             transactions, crc_errs);
    $finish;
end

endmodule

`default_nettype wire
