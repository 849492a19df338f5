// tb_ssi_reader: ssi_reader closed-loop against encoder-tb's SSI encoder
// emulator. Copy this file, encoder.toml and the Makefile next to your own
// reader, change the instance below, and run `make SIM=icarus` or
// `make SIM=verilator`.
//
// Each read: a random position goes into the emulator, the reader is asked,
// and its value must equal what the emulator says it stored and sent, and
// what the pin-level monitor decoded on the line; no timing rule may be
// broken (the emulator's checks and the monitor's: T_cs, f_clk, T_m). Both
// write their JSON transcripts into build/ for `tbgen check ssi`.

`timescale 1ns / 1ps
`default_nettype none

module tb_ssi_reader;

reg clk = 1'b0;
always #62.5 clk = ~clk;             // 8 MHz: the reader's clock and the emulator's
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg reset_n = 1'b0;
reg read_req = 1'b0;
wire [11:0] value;
wire value_ok, sclk, sdata;

ssi_reader #(.WIDTH(12), .HALF(16), .LEAD(40), .REST(240)) dut (   // 250 kHz, T_cs 5 us, 30 us rest
    .clk(clk), .reset_n(reset_n), .read_req(read_req),
    .value(value), .value_ok(value_ok), .sclk(sclk), .sdata(sdata)
);

ssi_encoder_emu #(.CONFIG("encoder.toml"), .F_EMU_HZ(8000000), .TRANSCRIPT("build/transcript.json")) u_emu (
    .i_emu_clk(clk), .i_ssi_clk(sclk), .o_ssi_data(sdata)
);

// The pin-level monitor and protocol checker: it only listens.
ssi_monitor #(.CONFIG("encoder.toml"), .F_MON_HZ(8000000), .TRANSCRIPT("build/monitor.json")) u_mon (
    .i_mon_clk(clk), .i_ssi_clk(sclk), .i_ssi_data(sdata)
);

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
integer reads, n, seed;
reg [63:0] position;

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    if (!$value$plusargs("reads=%d", reads)) reads = 1000;
    seed = 7;
    random_seed(seed);
    repeat (3) @(negedge clk);
    reset_n = 1'b1;
    for (n = 0; n < reads; n = n + 1) begin
        position = random32(0) & 12'hFFF;
        u_emu.set_position(0, position);
        @(negedge clk) read_req = 1'b1;
        @(negedge clk) read_req = 1'b0;
        @(negedge clk);
        while (!value_ok) @(negedge clk);
        if (value !== u_emu.last_value(0) || value !== position[11:0])
            $fatal(1, "read %0d at %t: reader %0d, emulator sent %0d (set %0d)", n, $time, value, u_emu.last_value(0), position);
    end
    if (u_mon.count(0) != reads || u_mon.last_value(0) !== value)
        $fatal(1, "the monitor decoded %0d reads, the last position %0d; the reader read %0d", u_mon.count(0), u_mon.last_value(0), value);
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the reader broke %0d + %0d timing rule(s) of SSI (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("PASS ssi_reader: %0d reads equal to what the emulator sent", reads);
    $finish;
end

endmodule

`default_nettype wire
