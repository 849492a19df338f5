// tb_cosim_can_controller: can_controller closed-loop against CAN nodes on a
// wired-AND bus (hdl/emu/can_node_emu.v), no vectors. Transactions alternate:
// even ones the core sends a random standard frame (identifier, RTR, DLC
// 0..8, data), and node 0 must receive exactly it (u_emu.last_value) while
// the core pulses o_tx_done and no error; odd ones the testbench has the
// last node send a random 8-byte frame (u_emu.schedule_fault("[[send]] ..."))
// and the core must pulse o_rx_valid with exactly it. Every frame is
// acknowledged; no node may detect an error in the core's frames.
//
// Plusargs: +can_emu_config=<scenario.toml>, +transactions=N (default 1000),
// +seed=S, +flip_bit=K (planted failure: the comparison flips bit K of the
// core's data, so the run must fail), +can_monitor_transcript=FILE (the
// monitor's JSON transcript).
//
// A pin-level monitor (hdl/emu/can_monitor.v) watches the core's TXD and
// RXD, reading the same configuration: after each transaction it must have
// decoded exactly one more frame, the one the core sent (sender "master")
// or received, with its identifier, DLC and data; and the core must break
// none of the CAN rules it checks.

`timescale 1fs / 1fs
`include "can_monitor.v"
`default_nettype none

module tb_cosim_can_controller;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter BRP = 1;
parameter PROP_SEG = 3;
parameter PHASE_SEG1 = 4;
parameter PHASE_SEG2 = 2;
parameter SJW = 2;
parameter SYNC_STAGES = 2;

/* Harness parameters */
parameter F_SYS_HZ = 10000000;
parameter HALF_PERIOD_FS = 50_000_000;
parameter NODES = 2;

localparam BIT_CLOCKS = BRP * (1 + PROP_SEG + PHASE_SEG1 + PHASE_SEG2);

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_tx_start = 1'b0;
reg [10:0] i_tx_id = 0;
reg i_tx_rtr = 1'b0;
reg [3:0] i_tx_dlc = 0;
reg [63:0] i_tx_data = 0;
wire o_tx_busy, o_tx_done, o_arb_lost;
wire o_rx_valid, o_rx_ide, o_rx_rtr;
wire [28:0] o_rx_id;
wire [3:0] o_rx_dlc;
wire [63:0] o_rx_data;
wire [8:0] o_tec;
wire [7:0] o_rec;
wire [1:0] o_err_state;
wire o_err_bit, o_err_stuff, o_err_crc, o_err_form, o_err_ack, o_overload;
wire can_tx, can_rx;

can_controller #(
    .BRP(BRP), .PROP_SEG(PROP_SEG), .PHASE_SEG1(PHASE_SEG1), .PHASE_SEG2(PHASE_SEG2),
    .SJW(SJW), .SYNC_STAGES(SYNC_STAGES)
) dut (
    .i_clk(clk), .i_rst(rst),
    .i_tx_start(i_tx_start), .i_tx_id(i_tx_id), .i_tx_rtr(i_tx_rtr), .i_tx_dlc(i_tx_dlc),
    .i_tx_data(i_tx_data), .o_tx_busy(o_tx_busy), .o_tx_done(o_tx_done), .o_arb_lost(o_arb_lost),
    .i_filter_id(29'd0), .i_filter_mask(29'd0),
    .o_rx_valid(o_rx_valid), .o_rx_id(o_rx_id), .o_rx_ide(o_rx_ide), .o_rx_rtr(o_rx_rtr),
    .o_rx_dlc(o_rx_dlc), .o_rx_data(o_rx_data),
    .o_tec(o_tec), .o_rec(o_rec), .o_err_state(o_err_state),
    .o_err_bit(o_err_bit), .o_err_stuff(o_err_stuff), .o_err_crc(o_err_crc),
    .o_err_form(o_err_form), .o_err_ack(o_err_ack), .o_overload(o_overload),
    .o_can_tx(can_tx), .i_can_rx(can_rx)
);

// The nodes' reference clock is the core's clock here.
can_node_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_can_tx(can_tx),
    .o_can_rx(can_rx)
);

// The pin-level monitor and protocol checker, on the same clock.
can_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("can_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_can_tx(can_tx),
    .i_can_rx(can_rx)
);

// The monitor has decoded `frames` frames, the last one `mid`, `mdlc`, data `mdata` under `mmask`, sent by the core when `by_core`.
task check_monitor(input integer frames, input [28:0] mid, input [3:0] mdlc, input [63:0] mdata, input [63:0] mmask, input by_core);
    reg [63:0] seen;
    begin
        seen = u_mon.last_value(0) & mmask;
        if (u_mon.count(0) != frames || u_mon.last_value(1) != mid || u_mon.last_value(2) != mdlc
            || seen != (mdata & mmask) || u_mon.last_status(0, "master") != by_core || u_mon.last_status(0, "error") != 0)
            $fatal(1, "frame %0d at %0t: the monitor decoded %0d frames, the last id %h dlc %0d data %h (by the core: %0d); expected %0d frames, id %h dlc %0d data %h (by the core: %0d)",
                   frames - 1, $time, u_mon.count(0), u_mon.last_value(1), u_mon.last_value(2), seen,
                   u_mon.last_status(0, "master"), frames, mid, mdlc, mdata & mmask, by_core);
    end
endtask

reg seen_done = 1'b0, seen_rx = 1'b0, seen_err = 1'b0;
reg [63:0] rx_data = 0;
reg [28:0] rx_id = 0;
reg [3:0] rx_dlc = 0;
reg rx_rtr = 1'b0;
reg clear = 1'b0;
always @(posedge clk) begin
    if (clear) begin
        seen_done <= 1'b0;
        seen_rx <= 1'b0;
        seen_err <= 1'b0;
    end else begin
        if (o_tx_done) seen_done <= 1'b1;
        if (o_rx_valid) begin
            seen_rx <= 1'b1;
            rx_data <= o_rx_data;
            rx_id <= o_rx_id;
            rx_dlc <= o_rx_dlc;
            rx_rtr <= o_rx_rtr;
        end
        if (o_err_bit || o_err_stuff || o_err_crc || o_err_form || o_err_ack || o_arb_lost) seen_err <= 1'b1;
    end
end

`ifdef VERILATOR
string cmd;
`else
reg [8*256-1:0] cmd;
`endif

`include "emu_random.vh"
integer transactions, seed, flip_bit, n, waited, len;
reg [63:0] data, mask, got, want, count_before;
reg [10:0] id;
reg [3:0] dlc;
reg rtr;

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    // Bus integration: 11 recessive bits before the core takes part.
    repeat (20 * BIT_CLOCKS) @(posedge clk);
    for (n = 0; n < transactions; n = n + 1) begin
        id = random32(0);
        data = random64(0);
        clear <= 1'b1;
        @(posedge clk);
        clear <= 1'b0;
        count_before = u_emu.count(0);
        if (n % 2 == 0) begin
            // The core sends; node 0 receives.
            dlc = $unsigned(random32(0)) % 9;
            rtr = ($unsigned(random32(0)) % 8) == 0;
            len = (rtr || dlc == 0) ? 0 : dlc;
            mask = (len == 0) ? 64'd0 : ~(64'hFFFFFFFFFFFFFFFF >> (8 * len));
            i_tx_id <= id;
            i_tx_rtr <= rtr;
            i_tx_dlc <= dlc;
            i_tx_data <= data;
            i_tx_start <= 1'b1;
            @(posedge clk);
            i_tx_start <= 1'b0;
            waited = 0;
            while (!seen_done && !seen_err) begin
                @(posedge clk);
                waited = waited + 1;
                if (waited > 200 * BIT_CLOCKS) $fatal(1, "frame %0d: no o_tx_done", n);
            end
            repeat (2) @(posedge clk);
            got = u_emu.last_value(0) & mask;
            want = data & mask;
            if (flip_bit >= 0) got = got ^ (64'd1 << flip_bit);
            if (seen_err || u_emu.count(0) != count_before + 1 || u_emu.last_value(16) != id
                || u_emu.last_value(32) != dlc || u_emu.last_status(0, "rtr") != rtr || got != want)
                $fatal(1, "frame %0d at %0t: the core sent id %h rtr %b dlc %0d data %h; node 0 received id %h rtr %0d dlc %0d data %h (%0d frames; an error or lost arbitration: %b)",
                       n, $time, id, rtr, dlc, want, u_emu.last_value(16), u_emu.last_status(0, "rtr"),
                       u_emu.last_value(32), got, u_emu.count(0) - count_before, seen_err);
        end else begin
            // The last node sends an 8-byte frame; the core receives.
            $sformat(cmd, "[[send]]\nnode = %0d\nid = %0d\ndlc = 8\ndata = [%0d, %0d, %0d, %0d, %0d, %0d, %0d, %0d]\n",
                     NODES - 1, id, data[63:56], data[55:48], data[47:40], data[39:32],
                     data[31:24], data[23:16], data[15:8], data[7:0]);
            u_emu.schedule_fault(cmd);
            waited = 0;
            while (!seen_rx && !seen_err) begin
                @(posedge clk);
                waited = waited + 1;
                if (waited > 200 * BIT_CLOCKS) $fatal(1, "frame %0d: no o_rx_valid", n);
            end
            got = rx_data;
            if (flip_bit >= 0) got = got ^ (64'd1 << flip_bit);
            if (seen_err || rx_id != {18'd0, id} || rx_dlc != 8 || rx_rtr || got != data)
                $fatal(1, "frame %0d at %0t: node %0d sent id %h data %h; the core received id %h dlc %0d rtr %b data %h (an error: %b)",
                       n, $time, NODES - 1, id, data, rx_id, rx_dlc, rx_rtr, got, seen_err);
        end
        // The frame's end of frame and intermission.
        repeat (12 * BIT_CLOCKS) @(posedge clk);
        if (n % 2 == 0) check_monitor(n + 1, {18'd0, id}, dlc, data, mask, 1'b1);
        else check_monitor(n + 1, {18'd0, id}, 4'd8, data, ~64'd0, 1'b0);
    end
    if (u_mon.violations(0) != 0)
        $fatal(1, "the monitor saw %0d CAN rule violation(s) by the core (PROTOCOL VIOLATION lines above)", u_mon.violations(0));
    if (u_emu.violations(0) != 0)
        $fatal(1, "the nodes detected %0d error(s) in the core's frames (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_can_controller: %0d frames, each received exactly as sent, both ways, and decoded alike by the monitor", transactions);
    $finish;
end

endmodule

`default_nettype wire
