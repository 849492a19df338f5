// tb_endat_reader: endat_reader closed-loop against encoder-tb's EnDat
// encoder emulator. Copy this file, encoder.toml and the Makefile next to
// your own master, change the instance below, and run `make SIM=icarus` or
// `make SIM=verilator`.
//
// Each read: a random position and a random F1 go into the emulator, the
// reader is asked, and what it took must equal what the emulator says it
// latched and sent, with a good CRC, and what the pin-level monitor decoded
// on the line; no timing rule may be broken (the emulator's checks and the
// monitor's: t_b, t_m, t_R, the clock, the send block). Both write their
// JSON transcripts into build/ for `tbgen check endat`.

`timescale 1ns / 1ps
`default_nettype none

module tb_endat_reader;

reg clk = 1'b0;
always #125 clk = ~clk;              // 4 MHz: the reader's clock and the emulator's
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg arst_n = 1'b0;
reg trig = 1'b0;
wire [24:0] pos;
wire ready, err1, crc_ok, got, no_start, ck, dout, dout_en, din, enc_oe;

endat_reader #(.POS_BITS(25), .HALF(4), .FIRST_LOW(8), .REST(4400)) dut (   // 500 kHz, t_b 1.1 ms
    .clk(clk), .arst_n(arst_n), .trig(trig), .ready(ready), .pos_out(pos), .err1_out(err1),
    .crc_ok(crc_ok), .got(got), .no_start(no_start), .ck(ck), .dout(dout), .dout_en(dout_en), .din(din)
);

endat_encoder_emu #(.CONFIG("encoder.toml"), .F_EMU_HZ(4000000), .TRANSCRIPT("build/transcript.json")) u_emu (
    .i_emu_clk(clk), .i_endat_clk(ck), .i_endat_data(dout), .i_endat_data_oe(dout_en),
    .o_endat_data(din), .o_endat_data_oe(enc_oe)
);

// The pin-level monitor and protocol checker: it only listens.
endat_monitor #(.CONFIG("encoder.toml"), .F_MON_HZ(4000000), .TRANSCRIPT("build/monitor.json")) u_mon (
    .i_mon_clk(clk), .i_endat_clk(ck), .i_endat_data(dout), .i_endat_data_oe(dout_en), .i_endat_data_in(din)
);

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
integer reads, n, seed, f1;
reg [63:0] position;

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    if (!$value$plusargs("reads=%d", reads)) reads = 1000;
    seed = 13;
    random_seed(seed);
    repeat (3) @(negedge clk);
    arst_n = 1'b1;
    for (n = 0; n < reads; n = n + 1) begin
        position = random32(0) & 25'h1FFFFFF;
        f1 = random32(0) & 1;
        u_emu.set_position(0, position);
        u_emu.set_status(0, "f1", f1);
        while (!ready) @(negedge clk);
        @(negedge clk) trig = 1'b1;
        @(negedge clk) trig = 1'b0;
        while (!got && !no_start) @(negedge clk);
        if (no_start || pos !== u_emu.last_value(0) || pos !== position[24:0] || !crc_ok || err1 !== f1[0])
            $fatal(1, "read %0d at %t: reader %0d F1 %b crc_ok %b no_start %b; emulator sent %0d F1 %0d",
                   n, $time, pos, err1, crc_ok, no_start, u_emu.last_value(0), f1);
        @(negedge clk);
    end
    // The monitor decodes a transfer at the next one's start or 10 us after its last edge: long since.
    if (u_mon.count(0) != reads || u_mon.last_value(0) !== pos)
        $fatal(1, "the monitor decoded %0d transfers, the last position %0d; the reader read %0d", u_mon.count(0), u_mon.last_value(0), pos);
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the reader broke %0d + %0d timing rule(s) of EnDat (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("PASS endat_reader: %0d reads equal to what the emulator sent", reads);
    $finish;
end

endmodule

`default_nettype wire
