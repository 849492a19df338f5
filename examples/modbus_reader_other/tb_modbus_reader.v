// tb_modbus_reader: modbus_reader closed-loop against encoder-tb's Modbus RTU
// device emulator (the SAR58K24 in its Modbus mode). Copy this file,
// device.toml and the Makefile next to your own master, change the instance
// below, and run `make SIM=icarus` or `make SIM=verilator`.
//
// Each poll: a random 32-bit position goes into the emulator, the reader
// polls station 17 with function 03 (two registers), and the position it
// took must equal what the device says it answered; the device must have
// seen and answered exactly one request per poll, and no rule of the line
// may be broken (two drivers at once, a request the device discards).
// Plusargs: +reads=N, +flip_bit=k (a planted misread: bit k of the reader's
// value flipped before the comparison, so the run must fail).

`timescale 1ns / 1ps
`default_nettype none

module tb_modbus_reader;

reg clk = 1'b0;
always #3255.208 clk = ~clk;         // 153.6 kHz = 8 x 19200 baud: the reader's clock and the emulator's
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg nreset = 1'b0;
reg poll = 1'b0;
wire [31:0] position;
wire [7:0] exception;
wire [2:0] err_code;
wire ok, err, di, de, dev_line, dev_en, bus;

modbus_reader #(.CPB(8)) dut (
    .clk(clk), .nreset(nreset), .poll(poll), .slave(8'h11), .position(position), .ok(ok), .err(err),
    .err_code(err_code), .exception(exception), .di(di), .de(de), .ro(bus)
);

modbus_device_emu #(.CONFIG("device.toml"), .F_EMU_HZ(153600), .TRANSCRIPT("build/transcript.json")) u_emu (
    .i_emu_clk(clk), .i_line(di), .i_line_en(de), .o_line(dev_line), .o_line_en(dev_en), .o_bus(bus)
);

// The pin-level monitor and protocol checker: it only listens.
modbus_monitor #(.CONFIG("device.toml"), .F_MON_HZ(153600), .TRANSCRIPT("build/monitor.json")) u_mon (
    .i_mon_clk(clk), .i_line(di), .i_line_en(de), .i_rx(bus)
);

integer reads, n, flip_bit;
reg [63:0] value, expected;

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
reg [63:0] rng;

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    random_seed(1);
    if (!$value$plusargs("reads=%d", reads)) reads = 1000;
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    repeat (3) @(negedge clk);
    nreset = 1'b1;
    for (n = 0; n < reads; n = n + 1) begin
        // t3.5 before each request is this reader's user's to keep: it
        // counts its silence from the last edge on the line, which is up to
        // 9 bits before the end of the answer's last character, and so
        // starts a request up to 91 us early after an answer whose last
        // bits are ones (the monitor's t3.5). 400 clocks from the answer's
        // last character on: 50 bits, t3.5 is 35.
        if (n > 0) repeat (400) @(negedge clk);
        rng = random64(0);
        expected = rng & 64'hFFFF_FFFF;
        u_emu.set_position(0, expected);
        @(negedge clk) poll = 1'b1;
        @(negedge clk) poll = 1'b0;
        while (!ok && !err) @(negedge clk);
        if (err)
            $fatal(1, "poll %0d at %t: the reader failed (code %0d: 1 no answer, 2 framing/noise, 3 gap, 4 CRC, 5 exception %0h, 6 header); the device answered %0h",
                   n, $realtime, err_code, exception, u_emu.last_value(0));
        value = {32'd0, position};
        if (flip_bit >= 0) value[flip_bit] = ~value[flip_bit];
        if (value !== u_emu.last_value(0) || value !== expected || u_emu.count(0) != n + 1
            || !u_emu.last_status(0, "answered"))
            $fatal(1, "poll %0d at %t: reader %0h; the device answered %0h (set %0h), %0d requests seen",
                   n, $realtime, value, u_emu.last_value(0), expected, u_emu.count(0));
    end
    if (u_mon.count(0) != reads || u_mon.last_value(0) !== value)
        $fatal(1, "the monitor decoded %0d polls, the last position %0h; the reader read %0h", u_mon.count(0), u_mon.last_value(0), value);
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the reader broke %0d + %0d rule(s) of the line (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("PASS modbus_reader: %0d reads equal to what the device answered", reads);
    $finish;
end

endmodule

`default_nettype wire
