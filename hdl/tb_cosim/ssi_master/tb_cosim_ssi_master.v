// tb_cosim_ssi_master: ssi_master closed-loop against the SSI encoder
// emulator (hdl/emu/ssi_encoder_emu.v), no vectors. Each read: a random
// position is set in the emulator, the host starts a read, and at o_done the
// core's o_position must equal what the emulator says it stored and sent
// (u_emu.last_value), which must equal the position set; no error pulse, and
// the emulator must have counted exactly one read per start.
//
// Plusargs: +ssi_emu_config=<scenario.toml> (the emulator's tables),
// +transactions=N (default 1000), +seed=S, +flip_bit=K (planted failure:
// the comparison flips bit K of the core's output, so the run must fail),
// +ssi_monitor_transcript=FILE (the monitor's JSON transcript).
//
// A pin-level monitor (hdl/emu/ssi_monitor.v) watches the core's clock and
// the data at its input, reading the same configuration: before each read
// it must have decoded every earlier read with the core's value, and the
// core must break none of the seed's timing rules it checks.

`timescale 1fs / 1fs
`include "ssi_monitor.v"
`default_nettype none

module tb_cosim_ssi_master;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter BITS = 12;
parameter CLOCKS_PER_BIT = 200;
parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2;
parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2;
parameter GRAY = 0;
parameter DOUBLE_READ = 0;
parameter WIRE_CHECK = 0;
parameter T_CS_CLOCKS = 200;
parameter PAUSE_CLOCKS = 25500;
parameter SAMPLE_DELAY = 0;

/* Harness parameters */
parameter F_SYS_HZ = 50000000;
parameter HALF_PERIOD_FS = 10_000_000;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

// System-clock cycles simulated (for the speed figures of scripts/cosim.sh).
reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_start = 1'b0;
wire o_ssi_clk, ssi_data;
wire o_busy, o_done, o_err_idle, o_err_double, o_err_wire;
wire [BITS-1:0] o_position;

ssi_master #(
    .BITS(BITS),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .HIGH_CLOCKS(HIGH_CLOCKS),
    .LOW_CLOCKS(LOW_CLOCKS),
    .GRAY(GRAY),
    .DOUBLE_READ(DOUBLE_READ),
    .WIRE_CHECK(WIRE_CHECK),
    .T_CS_CLOCKS(T_CS_CLOCKS),
    .PAUSE_CLOCKS(PAUSE_CLOCKS),
    .SAMPLE_DELAY(SAMPLE_DELAY)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .o_busy(o_busy),
    .o_done(o_done),
    .o_position(o_position),
    .o_err_idle(o_err_idle),
    .o_err_double(o_err_double),
    .o_err_wire(o_err_wire),
    .o_ssi_clk(o_ssi_clk),
    .i_ssi_data(ssi_data)
);

// The emulator runs on the core's own clock here; any clock of at least
// 4 x the SSI clock would do.
ssi_encoder_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_ssi_clk(o_ssi_clk),
    .o_ssi_data(ssi_data)
);

// The pin-level monitor and protocol checker, on the same clock.
ssi_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("ssi_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_ssi_clk(o_ssi_clk),
    .i_ssi_data(ssi_data)
);

`include "emu_random.vh"
integer transactions, seed, flip_bit, n, waited;
reg [63:0] position, sent, got, mask, core_last;

// The monitor has decoded `reads` reads, the last one the core's `value`.
task check_monitor(input integer reads, input [63:0] value);
    begin
        if (u_mon.count(0) != reads)
            $fatal(1, "at %0t: the monitor decoded %0d reads, the core made %0d", $time, u_mon.count(0), reads);
        if (reads > 0 && u_mon.last_value(0) != value)
            $fatal(1, "read %0d at %0t: the monitor read %0d on the line, the core %0d", reads - 1, $time, u_mon.last_value(0), value);
    end
endtask

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    mask = (BITS >= 64) ? {64{1'b1}} : ((64'd1 << BITS) - 64'd1);
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    repeat (4) @(posedge clk);
    for (n = 0; n < transactions; n = n + 1) begin
        check_monitor(n, core_last);
        position = random64(0) & mask;
        u_emu.set_position(0, position);
        i_start <= 1'b1;
        @(posedge clk);
        i_start <= 1'b0;
        waited = 0;
        @(posedge clk);
        while (!o_done) begin
            @(posedge clk);
            waited = waited + 1;
            if (waited > 4 * PAUSE_CLOCKS + 8 * BITS * CLOCKS_PER_BIT + 100000)
                $fatal(1, "read %0d: no o_done", n);
        end
        sent = u_emu.last_value(0);
        got = o_position;
        core_last = o_position;
        if (flip_bit >= 0) got = got ^ (64'd1 << flip_bit);
        if (u_emu.count(0) != n + 1)
            $fatal(1, "read %0d at %0t: the emulator counted %0d reads", n, $time, u_emu.count(0));
        if (sent != position)
            $fatal(1, "read %0d at %0t: the emulator stored %0d, the testbench set %0d", n, $time, sent, position);
        if (got != sent || o_err_idle || o_err_double || o_err_wire)
            $fatal(1, "read %0d at %0t: core read %0d (errors idle %b double %b wire %b), the emulator sent %0d",
                   n, $time, got, o_err_idle, o_err_double, o_err_wire, sent);
        while (o_busy) @(posedge clk);
    end
    repeat (4 * CLOCKS_PER_BIT) @(posedge clk);
    check_monitor(transactions, core_last);
    if (u_mon.violations(0) != 0)
        $fatal(1, "the monitor saw %0d timing violation(s) of the seed by the core (PROTOCOL VIOLATION lines above)", u_mon.violations(0));
    if (u_emu.violations(0) != 0)
        $fatal(1, "the core broke %0d timing rule(s) of the seed (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_ssi_master: %0d reads, every o_position equal to the emulator's and to the monitor's", transactions);
    $finish;
end

endmodule

`default_nettype wire
