// tb_biss_reader: biss_reader closed-loop against encoder-tb's BiSS-C slave
// emulator. Copy this file, slave.toml and the Makefile next to your own
// master, change the instance below, and run `make SIM=icarus` or
// `make SIM=verilator`.
//
// Each frame: a random position and random error and warning bits go into
// the emulator, the reader is asked, and what it took must equal what the
// emulator says it sent, with a good CRC, and what the pin-level monitor
// decoded on the line; no timing rule may be broken (the emulator's checks
// and the monitor's: TMAS, TMASH, TMASL, the timeout). Both write their
// JSON transcripts into build/ for `tbgen check biss`.

`timescale 1ns / 1ps
`default_nettype none

module tb_biss_reader;

reg clk = 1'b0;
always #12.5 clk = ~clk;             // 40 MHz: the reader's clock and the emulator's
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg reset_n = 1'b0;
reg go = 1'b0;
wire [15:0] pos;
wire n_error, n_warning, crc_good, ready, ma, slo;

biss_reader #(.DATA_BITS(16), .HALF(20)) dut (     // MA 1 MHz
    .clk(clk), .reset_n(reset_n), .go(go), .pos(pos), .n_error(n_error), .n_warning(n_warning),
    .crc_good(crc_good), .ready(ready), .ma(ma), .slo(slo)
);

biss_slave_emu #(.CONFIG("slave.toml"), .F_EMU_HZ(40000000), .TRANSCRIPT("build/transcript.json")) u_emu (
    .i_emu_clk(clk), .i_ma(ma), .o_slo(slo)
);

// The pin-level monitor and protocol checker: it only listens, on a clock
// of its own fast enough to measure TMASH and TMASL (more than 25 ns: two
// samples within 25 ns, 80 MHz).
reg mon_clk = 1'b0;
always #6.25 mon_clk = ~mon_clk;     // 80 MHz

biss_monitor #(.CONFIG("slave.toml"), .F_MON_HZ(80000000), .TRANSCRIPT("build/monitor.json")) u_mon (
    .i_mon_clk(mon_clk), .i_ma(ma), .i_slo(slo)
);

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
integer frames, n, seed, error, warning;
reg [63:0] position;

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    if (!$value$plusargs("frames=%d", frames)) frames = 1000;
    seed = 11;
    random_seed(seed);
    repeat (3) @(negedge clk);
    reset_n = 1'b1;
    for (n = 0; n < frames; n = n + 1) begin
        position = random32(0) & 16'hFFFF;
        error = random32(0) & 1;
        warning = random32(0) & 1;
        u_emu.set_position(0, position);
        u_emu.set_status(0, "error", error);
        u_emu.set_status(0, "warning", warning);
        @(negedge clk) go = 1'b1;
        @(negedge clk) go = 1'b0;
        @(negedge clk);
        while (!ready) @(negedge clk);
        if (pos !== u_emu.last_value(0) || pos !== position[15:0] || !crc_good
            || n_error !== !error || n_warning !== !warning)
            $fatal(1, "frame %0d at %t: reader %0d nE %b nW %b crc_good %b; emulator sent %0d error %0d warning %0d",
                   n, $time, pos, n_error, n_warning, crc_good, u_emu.last_value(0), error, warning);
    end
    if (u_mon.count(0) != frames || u_mon.last_value(0) !== pos)
        $fatal(1, "the monitor decoded %0d frames, the last position %0d; the reader read %0d", u_mon.count(0), u_mon.last_value(0), pos);
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the reader broke %0d + %0d timing rule(s) of BiSS-C (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("PASS biss_reader: %0d frames equal to what the emulator sent", frames);
    $finish;
end

endmodule

`default_nettype wire
