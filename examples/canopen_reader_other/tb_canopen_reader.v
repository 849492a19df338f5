// tb_canopen_reader: canopen_reader (mini_can and a tiny sequencer, a master
// encoder-tb did not write) closed-loop against encoder-tb's CANopen
// emulator: one DS 406 encoder and one SAR58K24 in CAN mode on a wired-AND
// bus (canopen.toml). Copy this file, canopen.toml and the Makefile next to
// your own master, change the instance, and run `make SIM=icarus` or
// `make SIM=verilator`.
//
// The reader waits for the encoder's boot-up, clicks the SAR58K24 once (the
// manual's example: 47 26 = 9799 on 0x120, seed 001 §3.4), reads the position by an SDO
// upload of 6004h in PRE-OPERATIONAL, starts the node (NMT), then each
// transaction sets a random position in the emulator and reads it back: an
// SDO upload of 6004h, a SYNC answered by TPDO2, or a click of the
// SAR58K24 (its 14-bit position on 0x100 + node). Every value must equal the
// position set and what the emulator says it sent. Half way, the SAR58K24 is
// given a new node on its configuration channel 0x7E5 (04 01, 11 <node>,
// answered 11 00), power-cycled, and clicked at the new node from then on.
//
// Plusargs: +reads=N (default 100), +seed=S, +flip_bit=K (a planted misread:
// bit K of every value is flipped before the comparison, so the run fails).

`timescale 1ns / 1ps
`default_nettype none

module tb_canopen_reader;

localparam CLKS_PER_BIT = 16;        // 4 MHz / 250 kbit/s
reg clk = 1'b0;
always #125 clk = ~clk;              // 4 MHz: the reader's clock and the emulator's
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg rst_n = 1'b0;
reg go = 1'b0;
reg [2:0] op = 0;
reg [15:0] arg = 0;
wire ready, done, failed, txd, rxd;
wire [31:0] value;

canopen_reader #(.NODE(5), .TIMEOUT(40000), .CLKS_PER_BIT(CLKS_PER_BIT), .SAMPLE_AT(11), .JUMP(3)) dut (
    .clk(clk), .rst_n(rst_n), .can_rxd(rxd), .can_txd(txd),
    .go(go), .op(op), .arg(arg), .ready(ready), .done(done), .failed(failed), .value(value)
);

canopen_encoder_emu #(.CONFIG("canopen.toml"), .F_EMU_HZ(4000000), .TRANSCRIPT("build/canopen_transcript.json")) u_emu (
    .i_emu_clk(clk), .i_can_tx(txd), .o_can_rx(rxd)
);

// The pin-level monitor and protocol checker: it only listens.
canopen_monitor #(.CONFIG("canopen.toml"), .F_MON_HZ(4000000), .TRANSCRIPT("build/canopen_monitor.json")) u_mon (
    .i_mon_clk(clk), .i_can_tx(txd), .i_can_rx(rxd)
);

/* the controller's own error and arbitration reports */
integer faults = 0, losses = 0;
always @(posedge clk) begin
    if (dut.u_can.fault) begin
        faults = faults + 1;
        $display("reader: CAN error kind %0d at %t", dut.u_can.fault_kind, $realtime);
    end
    if (dut.u_can.lost) losses = losses + 1;
end

integer reads, n, seed, flip_bit, sar_node, new_node, sdo, pdo, clicks;
reg [31:0] p, got;

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
reg [31:0] r1, r2;

task run_op(input [2:0] o, input [15:0] a);
    begin
        while (!ready) @(negedge clk);
        op = o;
        arg = a;
        go = 1'b1;
        @(negedge clk) go = 1'b0;
        @(negedge clk);
        while (!done && !failed) @(negedge clk);
        if (failed)
            $fatal(1, "op %0d (arg %h) failed at %t", o, a, $realtime);
        got = value;
        if (flip_bit >= 0) got = got ^ (32'd1 << flip_bit);
        // The reader takes a frame at EOF bit 6, the emulator counts it at its end.
        repeat (2 * CLKS_PER_BIT) @(negedge clk);
    end
endtask

task check(input [31:0] want, input [63:0] sent, input [8*16-1:0] what);
    begin
        if (got !== want || {32'd0, got} !== sent)
            $fatal(1, "read %0d (%0s) at %t: reader %0d, position set %0d, emulator sent %0d", n, what, $realtime, got, want, sent);
    end
endtask

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    if (!$value$plusargs("reads=%d", reads)) reads = 100;
    if (!$value$plusargs("seed=%d", seed)) seed = 11;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    sar_node = 8'h20;
    sdo = 0; pdo = 0; clicks = 0;
    repeat (4) @(negedge clk);
    rst_n = 1'b1;
    run_op(0, 0);                                       // boot-up on 0x85, no data
    if (u_emu.last_value(32) != 127 || u_emu.last_value(80) != 11'h085)
        $fatal(1, "after the boot-up: NMT state %0d, last frame %h", u_emu.last_value(32), u_emu.last_value(80));
    run_op(4, 16'h0020);                                // seed 001 §3.4: 80 20 on 0x220, 47 26 on 0x120
    if (got !== 32'd9799 || u_emu.last_value(1 + 16 * 5) != 11'h120 || u_emu.last_value(1 + 16 * 4) != 64'h4726_0000_0000_0000)
        $fatal(1, "the manual's example: reader %0d, the SAR58K24 sent %h [%h] (want 9799, 120 [4726000000000000])", got, u_emu.last_value(1 + 16 * 5), u_emu.last_value(1 + 16 * 4));
    for (n = 0; n < reads; n = n + 1) begin
        if (n == 1) begin
            run_op(1, 0);                               // NMT start 01 05
            if (!u_emu.last_status(0, "operational"))
                $fatal(1, "the encoder is not OPERATIONAL after NMT start");
        end
        if (n == reads / 2 && n > 0) begin              // SAR58K24: a new node from the next power-on
            r1 = random32(0);
            new_node = 8'h10 + (r1 % 8'h70);
            if (new_node == sar_node) new_node = new_node ^ 1;
            run_op(5, 16'h0401);
            run_op(5, {8'h11, new_node[7:0]});
            if (value !== 32'h1100 || u_emu.last_value(1 + 16 * 6) != new_node)
                $fatal(1, "configuration: answer %h, node from the next power-on %0d (want 11 00, %0d)", value, u_emu.last_value(1 + 16 * 6), new_node);
            u_emu.set_status(1, "power", 0);
            repeat (20 * CLKS_PER_BIT) @(negedge clk);
            u_emu.set_status(1, "power", 1);
            repeat (20 * CLKS_PER_BIT) @(negedge clk);
            if (u_emu.last_value(1 + 16 * 2) != new_node)
                $fatal(1, "the SAR58K24 is at node %0d after the power cycle, not %0d", u_emu.last_value(1 + 16 * 2), new_node);
            sar_node = new_node;
        end
        if (n == 0 || n % 3 == 0) begin                 // SDO upload of 6004h
            r1 = random32(0);
            p = r1 & 32'h1FF_FFFF;
            u_emu.set_position(0, p);
            run_op(2, 0);
            if (u_emu.last_value(16 * 5) != 11'h585 ||
                u_emu.last_value(16 * 4) != {32'h43046000, p[7:0], p[15:8], p[23:16], p[31:24]})
                $fatal(1, "read %0d: the encoder's last frame %h [%h] is not the SDO answer of %0d", n, u_emu.last_value(16 * 5), u_emu.last_value(16 * 4), p);
            check(p, {32'd0, p}, "SDO 6004h");     // the frame itself carried p (above)
            sdo = sdo + 1;
        end else if (n % 3 == 1) begin                  // SYNC, TPDO2
            r1 = random32(0);
            p = r1 & 32'h1FF_FFFF;
            u_emu.set_position(0, p);
            run_op(3, 0);
            check(p, u_emu.last_value(0), "TPDO2");
            pdo = pdo + 1;
        end else begin                                  // SAR58K24 click
            r1 = random32(0);
            p = r1 & 32'h3FFF;
            u_emu.set_position(1, p);
            run_op(4, sar_node[15:0]);
            check(p, u_emu.last_value(1), "SAR58K24 click");
            clicks = clicks + 1;
        end
    end
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the emulator saw %0d and the monitor %0d error(s) in the reader's frames (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    if (faults != 0)
        $fatal(1, "the reader reported %0d CAN error(s)", faults);
    $display("PASS canopen_reader: %0d reads equal to what the emulator sent (%0d SDO uploads of 6004h, %0d TPDO2 after SYNC, %0d SAR58K24 clicks; SAR58K24 moved to node 0x%h on 0x7E5; %0d arbitration losses)",
             reads, sdo, pdo, clicks, sar_node[7:0], losses);
    $finish;
end

endmodule

`default_nettype wire
