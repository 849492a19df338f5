// tb_cosim_biss_master: biss_master closed-loop against the BiSS-C slave
// emulator (hdl/emu/biss_slave_emu.v), no vectors. Each frame: every slave
// of the chain gets a random position and random error and warning bits in
// the emulator, the host starts a frame, and at each o_slave_valid the core's
// o_data, o_error and o_warning must equal what the emulator says that slave
// latched and sent (u_emu.last_value / last_status), which must equal what
// was set, with o_crc_err low; at o_done no error pulse, one latch per start.
//
// Plusargs: +biss_emu_config=<scenario.toml> (the emulator's tables),
// +transactions=N (default 1000), +seed=S, +flip_bit=K (planted failure:
// the comparison flips bit K of the core's o_data, so the run must fail).

`timescale 1fs / 1fs
`include "biss_monitor.v"
`default_nettype none

module tb_cosim_biss_master;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter SLAVES = 1;
parameter SLAVE_BITS = 16;
parameter SLAVE_CRC_WIDTH = 6;
parameter SLAVE_CRC_POLY = 3;
parameter CLOCKS_PER_BIT = 8;
parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2;
parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2;
parameter MAX_DELAY = 160;
parameter TIMEOUT_CLOCKS = 3200;
parameter CAL_FRAMES = 4;
parameter DELAY_TOL = 1;

/* Harness parameters */
parameter F_SYS_HZ = 80000000;
parameter HALF_PERIOD_FS = 6_250_000;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

// System-clock cycles simulated (for the speed figures of scripts/cosim.sh).
reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_start = 1'b0;
wire o_ma, slo;
wire o_busy, o_done, o_err_line, o_err_ack, o_err_delay, o_err_start, o_err_timeout, o_err_drift;
wire [15:0] o_delay, o_delay_mean;
wire o_slave_valid, o_crc_err, o_error, o_warning, o_cds;
wire [1:0] o_slave_index;
// Wider than the core's DATA_W; each slave's bits are masked out below.
wire [63:0] o_data;
wire o_reg_busy, o_reg_done, o_reg_err, o_reg_crc_err;
wire [7:0] o_reg_rdata;

biss_master #(
    .SLAVES(SLAVES),
    .SLAVE_BITS(SLAVE_BITS),
    .SLAVE_CRC_WIDTH(SLAVE_CRC_WIDTH),
    .SLAVE_CRC_POLY(SLAVE_CRC_POLY),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .HIGH_CLOCKS(HIGH_CLOCKS),
    .LOW_CLOCKS(LOW_CLOCKS),
    .MAX_DELAY(MAX_DELAY),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .CAL_FRAMES(CAL_FRAMES),
    .DELAY_TOL(DELAY_TOL)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .o_busy(o_busy),
    .o_done(o_done),
    .o_err_line(o_err_line),
    .o_err_ack(o_err_ack),
    .o_err_delay(o_err_delay),
    .o_err_start(o_err_start),
    .o_err_timeout(o_err_timeout),
    .o_delay(o_delay),
    .o_delay_mean(o_delay_mean),
    .o_err_drift(o_err_drift),
    .o_slave_valid(o_slave_valid),
    .o_slave_index(o_slave_index),
    .o_data(o_data),
    .o_crc_err(o_crc_err),
    .o_error(o_error),
    .o_warning(o_warning),
    .o_cds(o_cds),
    .i_reg_start(1'b0),
    .i_reg_write(1'b0),
    .i_reg_id(3'd0),
    .i_reg_addr(7'd0),
    .i_reg_wdata(8'd0),
    .o_reg_busy(o_reg_busy),
    .o_reg_done(o_reg_done),
    .o_reg_err(o_reg_err),
    .o_reg_rdata(o_reg_rdata),
    .o_reg_crc_err(o_reg_crc_err),
    .i_cmd_start(1'b0),
    .i_cmd_ids(8'd0),
    .i_cmd_code(2'd0),
    .o_ma(o_ma),
    .i_slo(slo)
);

// The emulator runs on the core's own clock here; any clock of at least
// 4 x MA would do.
biss_slave_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_ma(o_ma),
    .o_slo(slo)
);

// The pin-level monitor and protocol checker (hdl/emu/biss_monitor.v) on
// MA and SLO at the core, reading the emulator's configuration: before each
// frame it must have decoded every earlier frame with the core's values, and
// the core must break none of the seed's timing rules it checks.
// +biss_monitor_transcript=FILE writes its JSON transcript.
biss_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("biss_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_ma(o_ma),
    .i_slo(slo)
);

`include "emu_random.vh"
integer transactions, seed, flip_bit, n, i, waited, valids, bits;
reg [63:0] position [0:2];
reg error [0:2];
reg warning [0:2];
reg [63:0] core_data [0:2];
reg core_error [0:2];
reg core_warning [0:2];
reg [63:0] sent, got, mask;

// The monitor has decoded `frames` frames, the last one with the core's values.
task check_monitor(input integer frames);
    integer s;
    begin
        if (u_mon.count(0) != frames)
            $fatal(1, "at %0t: the monitor decoded %0d frames, the core made %0d", $time, u_mon.count(0), frames);
        for (s = 0; frames > 0 && s < SLAVES; s = s + 1)
            if (u_mon.last_value(s) !== core_data[s] || u_mon.last_status(s, "error") != core_error[s]
                || u_mon.last_status(s, "warning") != core_warning[s] || u_mon.last_status(s, "crc_ok") != 1)
                $fatal(1, "frame %0d at %0t: slave %0d: the monitor read %0d e%0d w%0d crc_ok %0d on the line, the core %0d e%0d w%0d",
                       frames - 1, $time, s, u_mon.last_value(s), u_mon.last_status(s, "error"), u_mon.last_status(s, "warning"),
                       u_mon.last_status(s, "crc_ok"), core_data[s], core_error[s], core_warning[s]);
    end
endtask

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    repeat (4) @(posedge clk);
    for (n = 0; n < transactions; n = n + 1) begin
        check_monitor(n);
        for (i = 0; i < SLAVES; i = i + 1) begin
            bits = (SLAVE_BITS >> (8 * i)) & 255;
            mask = (bits >= 64) ? {64{1'b1}} : ((64'd1 << bits) - 64'd1);
            position[i] = random64(0) & mask;
            error[i] = random32(0);
            warning[i] = random32(0);
            u_emu.set_position(i, position[i]);
            u_emu.set_status(i, "error", error[i]);
            u_emu.set_status(i, "warning", warning[i]);
        end
        i_start <= 1'b1;
        @(posedge clk);
        i_start <= 1'b0;
        waited = 0;
        valids = 0;
        @(posedge clk);
        while (!o_done) begin
            if (o_slave_valid) begin
                i = o_slave_index;
                bits = (SLAVE_BITS >> (8 * i)) & 255;
                mask = (bits >= 64) ? {64{1'b1}} : ((64'd1 << bits) - 64'd1);
                sent = u_emu.last_value(i);
                got = o_data & mask;
                core_data[i] = got;
                core_error[i] = o_error;
                core_warning[i] = o_warning;
                if (flip_bit >= 0) got = got ^ (64'd1 << flip_bit);
                if (i != valids)
                    $fatal(1, "frame %0d at %0t: slave %0d reported out of order (expected %0d)", n, $time, i, valids);
                if (sent !== position[i] || u_emu.last_status(i, "error") != error[i] || u_emu.last_status(i, "warning") != warning[i])
                    $fatal(1, "frame %0d at %0t: slave %0d: the emulator latched %0d e%0d w%0d, the testbench set %0d e%0d w%0d",
                           n, $time, i, sent, u_emu.last_status(i, "error"), u_emu.last_status(i, "warning"), position[i], error[i], warning[i]);
                if (got !== sent || o_crc_err !== 1'b0 || o_error !== error[i] || o_warning !== warning[i])
                    $fatal(1, "frame %0d at %0t: slave %0d: core read %0d error %b warning %b crc_err %b, the emulator sent %0d error %b warning %b",
                           n, $time, i, got, o_error, o_warning, o_crc_err, sent, error[i], warning[i]);
                valids = valids + 1;
            end
            @(posedge clk);
            waited = waited + 1;
            if (waited > 4 * TIMEOUT_CLOCKS + 200 * CLOCKS_PER_BIT)
                $fatal(1, "frame %0d: no o_done", n);
        end
        if (o_err_line || o_err_ack || o_err_delay || o_err_start || o_err_timeout || o_err_drift)
            $fatal(1, "frame %0d at %0t: error pulse line %b ack %b delay %b start %b timeout %b drift %b",
                   n, $time, o_err_line, o_err_ack, o_err_delay, o_err_start, o_err_timeout, o_err_drift);
        if (valids != SLAVES)
            $fatal(1, "frame %0d at %0t: %0d slave results, expected %0d", n, $time, valids, SLAVES);
        if (u_emu.count(0) != n + 1)
            $fatal(1, "frame %0d at %0t: the emulator counted %0d frames", n, $time, u_emu.count(0));
        while (o_busy) @(posedge clk);
    end
    repeat (4 * TIMEOUT_CLOCKS) @(posedge clk);
    check_monitor(transactions);
    if (u_mon.violations(0) != 0)
        $fatal(1, "the monitor saw %0d timing violation(s) of the seed by the core (PROTOCOL VIOLATION lines above)", u_mon.violations(0));
    if (u_emu.violations(0) != 0)
        $fatal(1, "the core broke %0d timing rule(s) of the seed (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_biss_master: %0d frames x %0d slave(s), every o_data, o_error, o_warning equal to the emulator's and to the monitor's", transactions, SLAVES);
    $finish;
end

endmodule

`default_nettype wire
