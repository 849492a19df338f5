// tb_sar_reader: sar_reader closed-loop against encoder-tb's SAR58K24
// encoder emulator in bus-command mode. Copy this file, encoder.toml and the
// Makefile next to your own master, change the instance below, and run
// `make SIM=icarus` or `make SIM=verilator`.
//
// Each read: a random 24-bit position goes into the emulator, the reader
// sends BC AA B5, and the position it took from the answer must equal what
// the emulator says it sent; no rule of the line may be broken (two drivers
// at once). Plusargs: +reads=N, +flip_bit=k (a planted misread: bit k of the
// reader's value flipped before the comparison, so the run must fail).

`timescale 1ns / 1ps
`default_nettype none

module tb_sar_reader;

reg clock = 1'b0;
always #3255.208 clock = ~clock;     // 153.6 kHz = 8 x 19200 baud: the reader's clock and the emulator's
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg reset_b = 1'b0;
reg ask = 1'b0;
wire [23:0] word;
wire got, bad, tx_line, tx_drive, line_out, line_en, bus;
wire [1:0] why;

sar_reader #(.OVS(8), .DATA_BYTES(3)) dut (
    .clock(clock), .reset_b(reset_b), .ask(ask), .station(4'd5), .word(word), .got(got), .bad(bad), .why(why),
    .tx_line(tx_line), .tx_drive(tx_drive), .rx_line(bus)
);

// The handshake and clear inputs are unused in the bus mode: held idle high.
sar58k24_encoder_emu #(.CONFIG("encoder.toml"), .F_EMU_HZ(153600), .TRANSCRIPT("build/transcript.json")) u_emu (
    .i_emu_clk(clock), .i_line(tx_line), .i_line_en(tx_drive), .i_trigger(1'b1), .i_clr(1'b1),
    .o_line(line_out), .o_line_en(line_en), .o_bus(bus)
);

// The pin-level monitor and protocol checker: it only listens.
sar58k24_monitor #(.CONFIG("encoder.toml"), .F_MON_HZ(153600), .TRANSCRIPT("build/monitor.json")) u_mon (
    .i_mon_clk(clock), .i_line(tx_line), .i_line_en(tx_drive), .i_rx(bus), .i_trigger(1'b1), .i_clr(1'b1)
);

integer reads, n, flip_bit;
reg [63:0] position, value;

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
reg [63:0] rng;

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    random_seed(1);
    if (!$value$plusargs("reads=%d", reads)) reads = 1000;
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    #1000 reset_b = 1'b1;
    for (n = 0; n < reads; n = n + 1) begin
        rng = random64(0);
        position = rng & 64'hFF_FFFF;
        u_emu.set_position(0, position);
        @(negedge clock) ask = 1'b1;
        @(negedge clock) ask = 1'b0;
        @(negedge clock);
        while (!got && !bad) @(negedge clock);
        if (bad)
            $fatal(1, "read %0d at %t: the reader found no good answer (why %0d: 0 none, 1 broken, 2 header, 3 checksum); the emulator sent %0d",
                   n, $realtime, why, u_emu.last_value(0));
        value = {40'd0, word};
        if (flip_bit >= 0) value[flip_bit] = ~value[flip_bit];
        if (value !== u_emu.last_value(0) || value !== position)
            $fatal(1, "read %0d at %t: reader %0d; the emulator sent %0d, set %0d",
                   n, $realtime, value, u_emu.last_value(0), position);
        // the next command one character time after the answer
        repeat (80) @(negedge clock);
    end
    if (u_emu.count(0) != reads)
        $fatal(1, "the emulator sent %0d frames, expected %0d", u_emu.count(0), reads);
    if (u_mon.count(0) != reads || u_mon.last_value(0) !== value)
        $fatal(1, "the monitor decoded %0d reads, the last position %0d; the reader read %0d", u_mon.count(0), u_mon.last_value(0), value);
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the reader broke %0d + %0d rule(s) of the line (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("PASS sar_reader: %0d reads equal to what the emulator sent", reads);
    $finish;
end

endmodule

`default_nettype wire
