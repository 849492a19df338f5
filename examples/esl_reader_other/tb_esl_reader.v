// tb_esl_reader: esl_reader closed-loop against encoder-tb's ESL encoder
// emulator. Copy this file, encoder.toml and the Makefile next to your own
// master, change the instance below, and run `make SIM=icarus` or
// `make SIM=verilator`.
//
// Each read: a random 40-bit position (24-bit single turn, 16-bit multi
// turn) and random alarm flags go into the emulator, the reader is asked
// (Data ID 4), and what it took must equal what the emulator says it sent;
// SF's EA0/EA1/DD0 must follow the flags (seed 000, Table 5); no timing rule
// may be broken. Plusargs: +reads=N, +flip_bit=k (a planted misread: bit k
// of the reader's value flipped before the comparison, so the run must
// fail), +wire_flip=n (the emulator flips a data bit of answer n on the
// line: the reader must refuse that answer, so the run must fail).

`timescale 1ns / 1ps
`default_nettype none

module tb_esl_reader;

reg clk = 1'b0;
always #8.333 clk = ~clk;           // 60 MHz: the reader's clock and the emulator's
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg rst_n = 1'b0;
reg trigger = 1'b0;
wire [23:0] angle;
wire [15:0] turns;
wire [7:0] status;
wire fresh, fail, txd, txd_en, rxd, rx_en;
wire [2:0] fail_why;

esl_reader #(.BIT_CLKS(6)) dut (
    .clk(clk), .rst_n(rst_n), .trigger(trigger), .enc_addr(3'd6),
    .angle(angle), .turns(turns), .status(status), .fresh(fresh), .fail(fail), .fail_why(fail_why),
    .txd(txd), .txd_en(txd_en), .rxd(rxd)
);

esl_encoder_emu #(.CONFIG("encoder.toml"), .F_EMU_HZ(60000000), .TRANSCRIPT("build/transcript.json")) u_emu (
    .i_emu_clk(clk), .i_esl_data(txd), .i_esl_data_oe(txd_en), .o_esl_data(rxd), .o_esl_data_oe(rx_en)
);

// The pin-level monitor and protocol checker: it only listens.
esl_monitor #(.CONFIG("encoder.toml"), .F_MON_HZ(60000000), .TRANSCRIPT("build/monitor.json")) u_mon (
    .i_mon_clk(clk), .i_esl_data(txd), .i_esl_data_oe(txd_en), .i_esl_rx(rxd)
);

integer reads, n, flip_bit, wire_flip;
reg [63:0] position, got;
reg [9:0] alm;                      // xc mt led lis overspeed mem st uv ov temp_warning
reg ea0, ea1;
reg [8*64-1:0] fault;

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
reg [63:0] rng;

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    random_seed(1);
    if (!$value$plusargs("reads=%d", reads)) reads = 1000;
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    if (!$value$plusargs("wire_flip=%d", wire_flip)) wire_flip = -1;
    if (wire_flip >= 0) begin
        // answer n (from 0), field 3 (ABS1: CF is field 0), bit 3 (data bit 2; bit 0 is the start bit)
        $sformat(fault, "flips = [{ answer = %0d, field = 3, bit = 3 }]", wire_flip);
        u_emu.schedule_fault(fault);
    end
    repeat (3) @(negedge clk);
    rst_n = 1'b1;
    for (n = 0; n < reads; n = n + 1) begin
        rng = random64(0);
        position = rng & 64'hFF_FFFF_FFFF;
        alm = rng[63:54];
        u_emu.set_position(0, position);
        u_emu.set_status(0, "xc", alm[0]);
        u_emu.set_status(0, "mt", alm[1]);
        u_emu.set_status(0, "led", alm[2]);
        u_emu.set_status(0, "lis", alm[3]);
        u_emu.set_status(0, "overspeed", alm[4]);
        u_emu.set_status(0, "mem", alm[5]);
        u_emu.set_status(0, "st", alm[6]);
        u_emu.set_status(0, "uv", alm[7]);
        u_emu.set_status(0, "ov", alm[8]);
        u_emu.set_status(0, "temp_warning", alm[9]);
        ea0 = alm[6] | alm[5] | alm[8] | alm[7] | alm[2];    // ST MEM OV UV LED: safety error
        ea1 = alm[1] | alm[0] | alm[3] | alm[4];             // MT XC LIS OVSP: non-safety error
        @(negedge clk) trigger = 1'b1;
        @(negedge clk) trigger = 1'b0;
        while (!fresh && !fail) @(negedge clk);
        if (fail)
            $fatal(1, "read %0d at %t: the reader failed (why %0d: 1 timeout, 2 frame, 3 CRC, 4 CF, 5 CA); the emulator sent %0h",
                   n, $realtime, fail_why, u_emu.last_value(0));
        got = {24'd0, turns, angle};
        if (flip_bit >= 0) got[flip_bit] = ~got[flip_bit];
        if (got !== u_emu.last_value(0) || got !== position || status[2] !== ea0 || status[3] !== ea1
            || status[4] !== alm[9])
            $fatal(1, "read %0d at %t: reader %0h SF %b; emulator sent %0h, set %0h, EA0 %b EA1 %b DD0 %b",
                   n, $realtime, got, status, u_emu.last_value(0), position, ea0, ea1, alm[9]);
    end
    if (u_emu.count(0) != reads)
        $fatal(1, "the emulator answered %0d requests, expected %0d", u_emu.count(0), reads);
    if (u_mon.count(0) != reads || u_mon.last_value(0) !== got)
        $fatal(1, "the monitor decoded %0d readouts, the last position %0h; the reader read %0h", u_mon.count(0), u_mon.last_value(0), got);
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the reader broke %0d + %0d timing rule(s) of ESL (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("PASS esl_reader: %0d reads equal to what the emulator sent", reads);
    $finish;
end

endmodule

`default_nettype wire
