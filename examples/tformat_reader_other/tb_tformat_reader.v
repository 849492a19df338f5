// tb_tformat_reader: tformat_reader closed-loop against encoder-tb's
// T-format encoder emulator. Copy this file, encoder.toml and the Makefile
// next to your own host, change the instance below, and run `make
// SIM=icarus` or `make SIM=verilator`.
//
// Each read: a random single-turn and multi-turn position and random ALMC
// flags go into the emulator, the reader asks for Data ID 3 (every fourth
// read Data ID 0), and what it took must equal what the emulator says it
// sent, and what the pin-level monitor decoded on the line; no timing rule
// may be broken (the emulator's checks and the monitor's: character timing,
// turnaround, request spacing). Both write their JSON transcripts into
// build/ for `tbgen check tformat`.

`timescale 1ns / 1ps
`default_nettype none

module tb_tformat_reader;

reg clk = 1'b0;
always #25 clk = ~clk;               // 20 MHz: the reader's clock and the emulator's
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg nreset = 1'b0;
reg go = 1'b0;
reg [3:0] id = 4'd3;
wire [16:0] st;
wire [15:0] mt;
wire [7:0] almc, sf;
wire [2:0] why;
wire idle, fresh, bad, tx, tx_en, rx, enc_oe;

tformat_reader #(.BIT(8), .TIMEOUT(400)) dut (     // 2.5 Mbps, 20 us timeout
    .sys_clk(clk), .nreset(nreset), .go(go), .id(id), .idle(idle), .single_turn(st), .multi_turn(mt),
    .alarms(almc), .status(sf), .fresh(fresh), .bad(bad), .why(why), .tx(tx), .tx_en(tx_en), .rx(rx)
);

tformat_encoder_emu #(.CONFIG("encoder.toml"), .F_EMU_HZ(20000000), .TRANSCRIPT("build/transcript.json")) u_emu (
    .i_emu_clk(clk), .i_tf_data(tx), .i_tf_data_oe(tx_en), .o_tf_data(rx), .o_tf_data_oe(enc_oe)
);

// The pin-level monitor and protocol checker: it only listens.
tformat_monitor #(.CONFIG("encoder.toml"), .F_MON_HZ(20000000), .TRANSCRIPT("build/monitor.json")) u_mon (
    .i_mon_clk(clk), .i_tf_data(tx), .i_tf_data_oe(tx_en), .i_tf_rx(rx)
);

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
integer reads, n, seed, k;
reg [16:0] want_st;
reg [15:0] want_mt;
reg [7:0] want_almc;

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    if (!$value$plusargs("reads=%d", reads)) reads = 1000;
    seed = 17;
    random_seed(seed);
    repeat (3) @(negedge clk);
    nreset = 1'b1;
    for (n = 0; n < reads; n = n + 1) begin
        want_st = random32(0);
        want_mt = random32(0);
        want_almc = random32(0) & 8'hEF;           // bit 4 is always 0 (Table 3)
        u_emu.set_position(0, {want_mt, want_st});
        u_emu.set_status(0, "over_speed", want_almc[0]);
        u_emu.set_status(0, "full_absolute", want_almc[1]);
        u_emu.set_status(0, "counting_error", want_almc[2]);
        u_emu.set_status(0, "counter_overflow", want_almc[3]);
        u_emu.set_status(0, "multi_turn_error", want_almc[5]);
        u_emu.set_status(0, "battery_error", want_almc[6]);
        u_emu.set_status(0, "battery_alarm", want_almc[7]);
        while (!idle) @(negedge clk);
        repeat (20) @(negedge clk);                 // 1 us between the answer's end and the next request
        id = (n % 4 == 3) ? 4'd0 : 4'd3;
        @(negedge clk) go = 1'b1;
        @(negedge clk) go = 1'b0;
        while (!fresh && !bad) @(negedge clk);
        // last_value: ABM << 17 | ABS of the last answer, ABS alone when it carried no ABM (Data ID 0).
        if (bad || st !== want_st || u_emu.last_value(0) !== (id == 4'd3 ? {want_mt, want_st} : want_st)
            || (id == 4'd3 && (mt !== want_mt || almc !== want_almc)))
            $fatal(1, "read %0d (Data ID %0d) at %t: reader ABS %0d ABM %0d ALMC %h bad %b (why %0d); emulator sent ABS %0d ABM %0d ALMC %h",
                   n, id, $time, st, mt, almc, bad, why, want_st, want_mt, want_almc);
        @(negedge clk);
    end
    if (u_mon.count(0) != reads || u_mon.last_value(0) !== {mt, st})   // both hold ABM through a Data ID 0 answer
        $fatal(1, "the monitor decoded %0d readouts, the last ABM << 17 | ABS %0d; the reader read %0d", u_mon.count(0), u_mon.last_value(0), {mt, st});
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the reader broke %0d + %0d timing rule(s) of T-format (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("PASS tformat_reader: %0d reads equal to what the emulator sent", reads);
    $finish;
end

endmodule

`default_nettype wire
