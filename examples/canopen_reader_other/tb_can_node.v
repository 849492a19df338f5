// tb_can_node: mini_can (a CAN controller encoder-tb did not write)
// closed-loop against encoder-tb's CAN node emulator (can_node_emu,
// node.toml): each transaction is one of
//   0  the controller sends a random data frame (identifier, 0 to 8 bytes);
//      the node must have received exactly it
//   1  the node sends a random data frame (u_emu.schedule_fault "[[send]]");
//      the controller must receive exactly it
//   2  arbitration: the node sends two frames; while the first is on the bus
//      the controller asks to send its own, so its frame and the node's
//      second start together after the intermission. The lower identifier
//      must win, the controller must report `lost` exactly when its
//      identifier is the higher one, and all three frames must arrive whole
// and the controller must report no CAN error.
//
// Plusargs: +reads=N (default 100), +seed=S, +flip_bit=K (a planted misread:
// bit K of every data field read is flipped before the comparison), +glitch
// (bit 20 of the node's first frame inverted on the way to the controller:
// its CRC or stuff check must report it, so the run fails).

`timescale 1ns / 1ps
`default_nettype none

module tb_can_node;

localparam CLKS_PER_BIT = 32;        // 4 MHz / 125 kbit/s
reg clk = 1'b0;
always #125 clk = ~clk;
// The stimulus below drives and samples on the falling edge, the reader
// and the emulator work on the rising one: no race between them, the same
// cycles in Icarus and Verilator (a non-blocking assignment in an initial
// block is not: Verilator warns INITIALDLY and runs it a cycle apart).

reg rst_n = 1'b0;
reg send = 1'b0;
reg [10:0] send_id = 0;
reg [3:0] send_len = 0;
reg [63:0] send_bytes = 0;
wire txd, rxd, busy, sent, lost, tx_fail, got, got_rtr, fault;
wire [10:0] got_id;
wire [3:0] got_len;
wire [63:0] got_bytes;
wire [2:0] fault_kind;

reg glitch = 1'b0;                   // +glitch: one bit inverted at the controller's RXD
mini_can #(.CLKS_PER_BIT(CLKS_PER_BIT), .SAMPLE_AT(22), .JUMP(5)) dut (
    .clk(clk), .rst_n(rst_n), .can_rxd(rxd ^ glitch), .can_txd(txd),
    .send(send), .send_id(send_id), .send_len(send_len), .send_bytes(send_bytes),
    .busy(busy), .sent(sent), .lost(lost), .tx_fail(tx_fail),
    .got(got), .got_id(got_id), .got_rtr(got_rtr), .got_len(got_len), .got_bytes(got_bytes),
    .fault(fault), .fault_kind(fault_kind)
);

can_node_emu #(.CONFIG("node.toml"), .F_EMU_HZ(4000000), .TRANSCRIPT("build/can_node_transcript.json")) u_emu (
    .i_emu_clk(clk), .i_can_tx(txd), .o_can_rx(rxd)
);

// The pin-level monitor and protocol checker: it only listens.
can_monitor #(.CONFIG("node.toml"), .F_MON_HZ(4000000), .TRANSCRIPT("build/can_monitor.json")) u_mon (
    .i_mon_clk(clk), .i_can_tx(txd), .i_can_rx(rxd)
);

/* what the controller received, in order; its reports */
reg [10:0] rx_id [0:3];
reg [3:0] rx_len [0:3];
reg [63:0] rx_data [0:3];
integer rx_n = 0, sent_n = 0, lost_n = 0, faults = 0, flip_bit;
always @(posedge clk) begin
    if (got) begin
        rx_id[rx_n % 4] <= got_id;
        rx_len[rx_n % 4] <= got_len;
        rx_data[rx_n % 4] <= (flip_bit >= 0) ? got_bytes ^ (64'd1 << flip_bit) : got_bytes;
        rx_n <= rx_n + 1;
        if (got_rtr) $fatal(1, "a remote frame at %t", $realtime);
    end
    if (sent) sent_n <= sent_n + 1;
    if (lost) lost_n <= lost_n + 1;
    if (fault || tx_fail) begin
        faults = faults + 1;
        $display("controller: CAN error kind %0d (tx_fail %b) at %t", fault_kind, tx_fail, $realtime);
    end
end

`ifdef VERILATOR
`define TB_STR string
`else
`define TB_STR reg [8*256-1:0]
`endif
`TB_STR cmd, cmd2;

integer reads, n, seed, len, i, waited, rx_before, sent_before, lost_before, wins, losses;
reg [10:0] id, id2;
reg [3:0] dlc, dlc2;
reg [63:0] data, data2, mask;

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
reg [31:0] r1, r2;

/* a random frame: identifier, DLC 0..8, data left-aligned (byte 0 in [63:56]) */
task random_frame(output [10:0] f_id, output [3:0] f_len, output [63:0] f_data);
    begin
        r1 = random32(0);
        f_id = r1[10:0];
        r1 = random32(0);
        f_len = r1 % 9;
        mask = (f_len == 0) ? 64'd0 : ~64'd0 << (64 - 8 * f_len);
        r1 = random32(0);
        r2 = random32(0);
        f_data = {r1, r2} & mask;
    end
endtask

/* the TOML of a frame node 0 sends */
task frame_toml(output `TB_STR s, input [10:0] f_id, input [3:0] f_len, input [63:0] f_data);
    reg [7:0] d0, d1, d2, d3, d4, d5, d6, d7;
    begin
        {d0, d1, d2, d3, d4, d5, d6, d7} = f_data;
        case (f_len)
        0: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 0\ndata = []\n", f_id);
        1: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 1\ndata = [%0d]\n", f_id, d0);
        2: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 2\ndata = [%0d, %0d]\n", f_id, d0, d1);
        3: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 3\ndata = [%0d, %0d, %0d]\n", f_id, d0, d1, d2);
        4: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 4\ndata = [%0d, %0d, %0d, %0d]\n", f_id, d0, d1, d2, d3);
        5: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 5\ndata = [%0d, %0d, %0d, %0d, %0d]\n", f_id, d0, d1, d2, d3, d4);
        6: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 6\ndata = [%0d, %0d, %0d, %0d, %0d, %0d]\n", f_id, d0, d1, d2, d3, d4, d5);
        7: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 7\ndata = [%0d, %0d, %0d, %0d, %0d, %0d, %0d]\n", f_id, d0, d1, d2, d3, d4, d5, d6);
        default: $sformat(s, "[[send]]\nnode = 0\nid = %0d\ndlc = 8\ndata = [%0d, %0d, %0d, %0d, %0d, %0d, %0d, %0d]\n", f_id, d0, d1, d2, d3, d4, d5, d6, d7);
        endcase
    end
endtask

task wait_for(input integer what, input integer target);    // 0: rx_n, 1: sent_n
    begin
        waited = 0;
        while ((what == 0 ? rx_n : sent_n) < target) begin
            @(negedge clk);
            waited = waited + 1;
            if (waited > 400 * CLKS_PER_BIT)
                $fatal(1, "transaction %0d: no %0s within 400 bits (at %t)", n, what == 0 ? "frame received" : "frame sent", $realtime);
        end
        repeat (2 * CLKS_PER_BIT) @(negedge clk);      // the node counts a frame at its end
    end
endtask

task request(input [10:0] f_id, input [3:0] f_len, input [63:0] f_data);
    begin
        while (busy) @(negedge clk);
        send_id = f_id;
        send_len = f_len;
        send_bytes = f_data;
        send = 1'b1;
        @(negedge clk) send = 1'b0;
    end
endtask

/* node 0 received exactly this frame last */
task node_got(input [10:0] f_id, input [3:0] f_len, input [63:0] f_data);
    reg [63:0] d;
    begin
        d = u_emu.last_value(0);                           // byte 0 in [63:56]
        if (flip_bit >= 0) d = d ^ (64'd1 << flip_bit);
        if (u_emu.last_value(16) != f_id || u_emu.last_value(32) != f_len || d !== f_data)
            $fatal(1, "transaction %0d at %t: controller sent %h [%0d] %h, node received %h [%0d] %h", n, $realtime,
                   f_id, f_len, f_data, u_emu.last_value(16), u_emu.last_value(32), d);
    end
endtask

/* the controller received exactly this frame as its k-th */
task ctrl_got(input integer k, input [10:0] f_id, input [3:0] f_len, input [63:0] f_data);
    begin
        if (rx_id[k % 4] != f_id || rx_len[k % 4] != f_len || rx_data[k % 4] !== f_data)
            $fatal(1, "transaction %0d at %t: node sent %h [%0d] %h, controller received %h [%0d] %h", n, $realtime,
                   f_id, f_len, f_data, rx_id[k % 4], rx_len[k % 4], rx_data[k % 4]);
    end
endtask

initial begin
    $timeformat(-9, 3, " ns", 0);    // %t in ns, whatever the simulator's precision
    if (!$value$plusargs("reads=%d", reads)) reads = 100;
    if (!$value$plusargs("seed=%d", seed)) seed = 3;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    wins = 0; losses = 0;
    repeat (4) @(negedge clk);
    rst_n = 1'b1;
    repeat (12 * CLKS_PER_BIT) @(negedge clk);          // bus integration: 11 recessive bits
    for (n = 0; n < reads; n = n + 1) begin
        rx_before = rx_n; sent_before = sent_n; lost_before = lost_n;
        case (n % 3)
        0: begin
            random_frame(id, dlc, data);
            request(id, dlc, data);
            wait_for(1, sent_before + 1);
            node_got(id, dlc, data);
        end
        1: begin
            random_frame(id, dlc, data);
            frame_toml(cmd, id, dlc, data);
            u_emu.schedule_fault(cmd);
            if (n == 1 && $test$plusargs("glitch")) begin
                while (rxd) @(negedge clk);
                repeat (20 * CLKS_PER_BIT) @(negedge clk);
                glitch = 1'b1;
                repeat (CLKS_PER_BIT) @(negedge clk);
                glitch = 1'b0;
            end
            wait_for(0, rx_before + 1);
            ctrl_got(rx_before, id, dlc, data);
        end
        default: begin
            random_frame(id, dlc, data);                // the node's first frame
            random_frame(id2, dlc2, data2);             // its second, against ours
            frame_toml(cmd, id, dlc, data);
            frame_toml(cmd2, id2, dlc2, data2);
            u_emu.schedule_fault(cmd);
            u_emu.schedule_fault(cmd2);
            random_frame(send_id, send_len, send_bytes);
            if (send_id == id2) send_id = send_id ^ 11'h001;
            // ours is asked for once the node's first frame is on the bus
            while (rxd) @(negedge clk);
            repeat (4 * CLKS_PER_BIT) @(negedge clk);   // past its SOF: not joined, waits for the bus
            request(send_id, send_len, send_bytes);
            wait_for(0, rx_before + 2);
            wait_for(1, sent_before + 1);
            ctrl_got(rx_before, id, dlc, data);
            ctrl_got(rx_before + 1, id2, dlc2, data2);
            node_got(send_id, send_len, send_bytes);
            if ((lost_n - lost_before) != (send_id > id2 ? 1 : 0))
                $fatal(1, "transaction %0d: identifiers %h (controller) and %h (node): %0d arbitration losses reported", n, send_id, id2, lost_n - lost_before);
            if (send_id > id2) losses = losses + 1; else wins = wins + 1;
        end
        endcase
    end
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the node saw %0d and the monitor %0d error(s) in the controller's frames (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    if (faults != 0)
        $fatal(1, "the controller reported %0d CAN error(s)", faults);
    $display("PASS mini_can: %0d transactions with can_node_emu equal on both sides (%0d arbitrations won, %0d lost and resent)", reads, wins, losses);
    $finish;
end

endmodule

`default_nettype wire
