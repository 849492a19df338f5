// tb_cosim_sar58k24_can: the SAR58K24 in its CAN mode (seed 001 §3.4)
// closed-loop, no vectors. The master is our can_controller with a command
// sequencer in this testbench; the SAR58K24 (and, in a mixed
// configuration, DS 406 encoders) is emulated on a wired-AND bus by
// hdl/emu/canopen_encoder_emu.v (one wrapper carries both device kinds).
//
// Each transaction is one command and its answers, the first six one of
// each kind, then chosen at random (of 40: 3 zeros, 3 directions, a start,
// a timed send, a configuration, the rest clicks):
//   80 NN       click: one position (a random raw position set before)
//   20 NN       zero: acknowledged 20 00; the next positions count from here
//   22 NN / 23  direction: acknowledged 22 00 (toggle reading) or 22/23 00
//               (SAR_DIRECTION_CODES = 1: 22 forward, 23 reverse)
//   01 NN       start: a position at once and every SAR_CYCLE_MS; two of
//               them (new random positions between), then stopped by 31 NN TT
//   31 NN TT    timed send TT times a second: the first timed position, then
//               the same bytes stop it (acknowledged 31 00 both times)
//   7E5         04 01 enter configuration (no answer), 11 <node> (11 00),
//               13 00 <code> with a random code 00/02/03 (13 00), then the
//               bus's own code again, a power cycle (u_emu.set_status(dev,
//               "power", 0/1)): from then on the commands go to the new node
// Every frame the SAR58K24 sends is checked three ways: the identifier and
// data the controller received (o_rx_id, o_rx_data) equal the frame the
// emulator says it sent last (u_emu.last_value(dev + 16 x 5 / 4)), the
// number of frames received from it equals the number it sent, and a
// position equals the testbench's own prediction from the raw position,
// the zero and the direction (and u_emu.last_value(dev)). No error flag, no
// frame the emulated devices find in error, no answer missing or extra.
//
// Plusargs: +canopen_emu_config=<scenario.toml>, +transactions=N (default
// 1000), +seed=S, +flip_bit=K (planted failure: the comparison flips bit K
// of the received data, so the run must fail with "core read"),
// +canopen_monitor_transcript=FILE (the monitor's JSON transcript).
//
// A pin-level monitor (hdl/emu/canopen_monitor.v) watches the controller's
// TXD and RXD with the same configuration: each answer the core read must
// be the last frame the monitor decoded (identifier and data), and the
// command sequence must break none of the CAN rules and SAR58K24 command
// rules it checks (a command only after the answer to the previous one).

`timescale 1fs / 1fs
`include "canopen_monitor.v"
`default_nettype none

module tb_cosim_sar58k24_can;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params sar58k24_can) */
parameter BRP = 1;
parameter PROP_SEG = 8;
parameter PHASE_SEG1 = 5;
parameter PHASE_SEG2 = 2;
parameter SJW = 1;
parameter SYNC_STAGES = 2;

/* Harness parameters (the scenario's first [[canopen.sar]]) */
parameter F_SYS_HZ = 4000000;
parameter HALF_PERIOD_FS = 125_000_000;
parameter SAR_DEVICE = 0;
parameter SAR_NODE = 32;
parameter SAR_BITS = 14;
parameter SAR_ANSWER_BASE = 256;
parameter SAR_CYCLE_MS = 2;
parameter SAR_DIRECTION_CODES = 0;
parameter SAR_RATE_CODE = 3;

localparam BIT_CLOCKS = BRP * (1 + PROP_SEG + PHASE_SEG1 + PHASE_SEG2);
localparam [11:0] CONFIG_ID = 12'h7E5;
localparam [63:0] MASK = (64'd1 << SAR_BITS) - 1;
localparam integer MS_CLOCKS = F_SYS_HZ / 1000;
// One command and its answer: two 8-byte frames of at most 135 bits each and their spaces.
localparam integer ANSWER_CLOCKS = 400 * BIT_CLOCKS;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_tx_start = 1'b0;
reg [10:0] i_tx_id = 0;
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
    .i_tx_start(i_tx_start), .i_tx_id(i_tx_id), .i_tx_rtr(1'b0), .i_tx_dlc(4'd8),
    .i_tx_data(i_tx_data), .o_tx_busy(o_tx_busy), .o_tx_done(o_tx_done), .o_arb_lost(o_arb_lost),
    .i_filter_id(29'd0), .i_filter_mask(29'd0),
    .o_rx_valid(o_rx_valid), .o_rx_id(o_rx_id), .o_rx_ide(o_rx_ide), .o_rx_rtr(o_rx_rtr),
    .o_rx_dlc(o_rx_dlc), .o_rx_data(o_rx_data),
    .o_tec(o_tec), .o_rec(o_rec), .o_err_state(o_err_state),
    .o_err_bit(o_err_bit), .o_err_stuff(o_err_stuff), .o_err_crc(o_err_crc),
    .o_err_form(o_err_form), .o_err_ack(o_err_ack), .o_overload(o_overload),
    .o_can_tx(can_tx), .i_can_rx(can_rx)
);

// The devices' reference clock is the controller's clock here.
canopen_encoder_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_can_tx(can_tx),
    .o_can_rx(can_rx)
);

// The pin-level monitor and protocol checker, on the same clock.
canopen_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("canopen_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_can_tx(can_tx),
    .i_can_rx(can_rx)
);

// The node in use, and the identifiers of the SAR58K24's frames.
reg [7:0] node = SAR_NODE;
wire [11:0] answer_id = SAR_ANSWER_BASE + node;

// Frames from the SAR58K24 (its answer identifier, or 0x7E5: the controller
// does not receive its own frames), queued; other devices' frames counted.
reg [11:0] q_id [0:7];
reg [63:0] q_data [0:7];
reg [3:0] q_dlc [0:7];
reg [2:0] q_head = 0, q_tail = 0;
reg [3:0] q_count = 0;
reg q_pop = 1'b0;
reg [31:0] others = 0;
reg bad = 1'b0;
always @(posedge clk) begin
    if (o_rx_valid && !o_rx_ide && (o_rx_id[11:0] == answer_id || o_rx_id[11:0] == CONFIG_ID)) begin
        q_id[q_tail] <= o_rx_id[11:0];
        q_data[q_tail] <= o_rx_data;
        q_dlc[q_tail] <= o_rx_dlc;
        q_tail <= q_tail + 1;
    end else if (o_rx_valid) begin
        others <= others + 1;
        $display("a frame of another device at %0t: %h [%h]", $time, o_rx_id, o_rx_data);
    end
    if (q_pop) q_head <= q_head + 1;
    q_count <= q_count + (o_rx_valid && !o_rx_ide && (o_rx_id[11:0] == answer_id || o_rx_id[11:0] == CONFIG_ID)) - q_pop;
    if (o_err_bit || o_err_stuff || o_err_crc || o_err_form || o_err_ack) bad <= 1'b1;
end

`ifdef VERILATOR
string cmd;
`else
reg [8*64-1:0] cmd;
`endif

integer transactions, seed, flip_bit, n, waited, heard, r, k, positions;
reg [63:0] raw, zero, got_data, read_data, want, sent_data, sent_id, p;
reg [11:0] got_id;
reg [3:0] got_dlc;
reg reverse;
reg [7:0] tt, new_node, code;

// The position the SAR58K24 must send now: the raw count less the zero, negated when reversed.
function [63:0] expected(input dummy);
    reg [63:0] q;
    begin
        q = (raw - zero) & MASK;
        expected = reverse ? ((MASK + 1 - q) & MASK) : q;
    end
endfunction

// An answer's data as the controller presents it (D0 in bits 63..56).
function [63:0] frame_of_position(input [63:0] v);
    frame_of_position = {v[7:0], v[15:8], v[23:16], v[31:24], 32'd0};
endfunction

function [63:0] ack_of(input [7:0] c);
    ack_of = {c, 56'd0};
endfunction

// Sends id with data D0 D1 D2 0 0 0 0 0; waits for o_tx_done (it retries after a lost arbitration).
task send(input [10:0] id, input [7:0] d0, input [7:0] d1, input [7:0] d2);
    begin
        while (o_tx_busy) @(posedge clk);
        i_tx_id <= id;
        i_tx_data <= {d0, d1, d2, 40'd0};
        i_tx_start <= 1'b1;
        @(posedge clk);
        i_tx_start <= 1'b0;
        waited = 0;
        while (!o_tx_done) begin
            @(posedge clk);
            waited = waited + 1;
            if (bad || waited > ANSWER_CLOCKS)
                $fatal(1, "transaction %0d at %0t: the command %h %h %h %h was not sent (error flag: %b)", n, $time, id, d0, d1, d2, bad);
        end
    end
endtask

// Waits (at most `limit` cycles) until a frame of the SAR58K24 is queued.
task wait_frame(input [11:0] want_id, input integer limit);
    begin
        waited = 0;
        while (q_count == 0) begin
            @(posedge clk);
            waited = waited + 1;
            if (bad) $fatal(1, "transaction %0d at %0t: an error flag of the controller", n, $time);
            if (waited > limit) $fatal(1, "transaction %0d at %0t: no answer on %h within %0d cycles", n, $time, want_id, limit);
        end
    end
endtask

// Takes the next frame of the SAR58K24 (within `limit` cycles) and checks it
// against the frame the emulator sent last and against `want_data` on `want_id`.
task expect_frame(input [11:0] want_id, input [63:0] want_data, input is_position, input integer limit);
    begin
        wait_frame(want_id, limit);
        got_id = q_id[q_head];
        got_data = q_data[q_head];
        read_data = q_data[q_head];
        got_dlc = q_dlc[q_head];
        q_pop <= 1'b1;
        @(posedge clk);
        q_pop <= 1'b0;
        heard = heard + 1;
        // The controller takes the frame at EOF bit 6; the emulated node counts it sent at its end.
        repeat (3 * BIT_CLOCKS) @(posedge clk);
        if (flip_bit >= 0) got_data = got_data ^ (64'd1 << flip_bit);
        sent_data = u_emu.last_value(SAR_DEVICE + 16 * 4);
        sent_id = u_emu.last_value(SAR_DEVICE + 16 * 5);
        if (got_id != sent_id[11:0] || got_data != sent_data || got_dlc != 8)
            $fatal(1, "transaction %0d at %0t: the SAR58K24 sent %h [%h]; the core read %h [%h] dlc %0d", n, $time, sent_id, sent_data, got_id, got_data, got_dlc);
        if (u_emu.last_value(SAR_DEVICE + 16) != heard)
            $fatal(1, "transaction %0d at %0t: the SAR58K24 sent %0d frames, the core read %0d", n, $time, u_emu.last_value(SAR_DEVICE + 16), heard);
        if (u_mon.last_value(1) != got_id || u_mon.last_value(0) != read_data || u_mon.last_status(0, "master"))
            $fatal(1, "transaction %0d at %0t: the monitor decoded %h [%h] last (by the core: %0d); the core read %h [%h]", n, $time, u_mon.last_value(1), u_mon.last_value(0), u_mon.last_status(0, "master"), got_id, read_data);
        if (got_id != want_id || got_data != want_data)
            $fatal(1, "transaction %0d at %0t: expected %h [%h]; the core read %h [%h]", n, $time, want_id, want_data, got_id, got_data);
        if (is_position && u_emu.last_value(SAR_DEVICE) != expected(0))
            $fatal(1, "transaction %0d at %0t: the emulator says position %0d, the testbench expects %0d", n, $time, u_emu.last_value(SAR_DEVICE), expected(0));
        positions = positions + is_position;
    end
endtask

// A position answer: possibly a timed one that was already on its way.
task expect_position(input integer limit);
    expect_frame(answer_id, frame_of_position(expected(0)), 1'b1, limit);
endtask

// Stops self-sending (start or timed send) with 31 NN TT; a position sent
// before the stop took effect is accepted (and checked) before the 31 00.
task stop_sending;
    begin
        // A position whose frame has the acknowledgement's bytes (49: 31 00 ..) would be ambiguous.
        if (frame_of_position(expected(0)) == ack_of(8'h31)) begin
            raw = (raw + 1) & MASK;
            u_emu.set_position(SAR_DEVICE, raw);
        end
        send(11'h200 + node, 8'h31, node, tt);
        wait_frame(answer_id, ANSWER_CLOCKS);
        if (q_data[q_head] != ack_of(8'h31)) expect_position(ANSWER_CLOCKS);
        expect_frame(answer_id, ack_of(8'h31), 1'b0, ANSWER_CLOCKS);
        if (u_emu.last_status(SAR_DEVICE, "sending"))
            $fatal(1, "transaction %0d at %0t: the SAR58K24 still sends after 31 %h %h", n, $time, node, tt);
    end
endtask

integer configs, clicks, zeros, directions, starts, timed;

// The testbench's own random numbers (a 64-bit LCG, upper half: the same
// sequence in both simulators and evenly spread over the command mix).
reg [63:0] rng;
task next_rand;
    rng = rng * 64'd6364136223846793005 + 64'd1442695040888963407;
endtask

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    heard = 0; positions = 0;
    configs = 0; clicks = 0; zeros = 0; directions = 0; starts = 0; timed = 0;
    raw = 0; zero = 0; reverse = 1'b0; tt = 0;
    rng = seed;
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    // Bus integration (11 recessive bits) and any boot-up of a DS 406 encoder.
    repeat (200 * BIT_CLOCKS) @(posedge clk);
    for (n = 0; n < transactions; n = n + 1) begin
        next_rand;
        r = rng[63:40] % 40;
        // The first six: every command once (click, zero, direction, start, timed send, configuration).
        case (n)
            0: r = 9;
            1: r = 0;
            2: r = 3;
            3: r = 6;
            4: r = 7;
            5: r = 8;
            default: ;
        endcase
        next_rand;
        raw = rng[63:32] & MASK;
        u_emu.set_position(SAR_DEVICE, raw);
        if (r < 3) begin
            // Zero ("centered", ⑥).
            send(11'h200 + node, 8'h20, node, 8'h00);
            expect_frame(answer_id, ack_of(8'h20), 1'b0, ANSWER_CLOCKS);
            // The zero is taken on the unreversed count: raw now reads 0.
            zero = raw;
            zeros = zeros + 1;
        end else if (r < 6) begin
            // Direction (④ ⑤).
            next_rand;
            code = (SAR_DIRECTION_CODES && rng[63]) ? 8'h23 : 8'h22;
            send(11'h200 + node, code, node, 8'h00);
            expect_frame(answer_id, ack_of(code), 1'b0, ANSWER_CLOCKS);
            reverse = SAR_DIRECTION_CODES ? (code == 8'h23) : !reverse;
            if (u_emu.last_status(SAR_DEVICE, "reversed") != reverse)
                $fatal(1, "transaction %0d: the emulator's direction is not the testbench's", n);
            directions = directions + 1;
        end else if (r == 6) begin
            // Start (①): a position at once, then every cycle; stopped by 31 NN TT.
            send(11'h200 + node, 8'h01, node, 8'h00);
            expect_position(ANSWER_CLOCKS);
            for (k = 0; k < 2; k = k + 1) begin
                next_rand;
                raw = rng[63:32] & MASK;
                u_emu.set_position(SAR_DEVICE, raw);
                expect_position(SAR_CYCLE_MS * MS_CLOCKS + ANSWER_CLOCKS);
            end
            next_rand;
            tt = 8'd200 + rng[63:40] % 56;
            stop_sending;
            starts = starts + 1;
        end else if (r == 7) begin
            // Timed send TT times a second (⑦) and its stop (⑧).
            next_rand;
            tt = 8'd200 + rng[63:40] % 56;
            send(11'h200 + node, 8'h31, node, tt);
            expect_frame(answer_id, ack_of(8'h31), 1'b0, ANSWER_CLOCKS);
            expect_position(F_SYS_HZ / tt + ANSWER_CLOCKS);
            stop_sending;
            timed = timed + 1;
        end else if (r == 8) begin
            // The configuration channel 0x7E5 (② ③) and a power cycle.
            send(CONFIG_ID, 8'h04, 8'h01, 8'h00);
            repeat (3 * BIT_CLOCKS) @(posedge clk);
            if (!u_emu.last_status(SAR_DEVICE, "config_mode"))
                $fatal(1, "transaction %0d at %0t: 04 01 on 0x7E5 did not enter configuration mode", n, $time);
            next_rand;
            new_node = 8'h10 + rng[63:40] % 8'h70;
            send(CONFIG_ID, 8'h11, new_node, 8'h00);
            expect_frame(CONFIG_ID, ack_of(8'h11), 1'b0, ANSWER_CLOCKS);
            if (u_emu.last_value(SAR_DEVICE + 16 * 6) != new_node)
                $fatal(1, "transaction %0d: node %h set, the emulator will use %h", n, new_node, u_emu.last_value(SAR_DEVICE + 16 * 6));
            next_rand;
            code = (rng[63:40] % 3 == 0) ? 8'h00 : (rng[63:40] % 3 == 1) ? 8'h02 : 8'h03;
            send(CONFIG_ID, 8'h13, 8'h00, code);
            expect_frame(CONFIG_ID, ack_of(8'h13), 1'b0, ANSWER_CLOCKS);
            if (u_emu.last_value(SAR_DEVICE + 16 * 7) != (code == 0 ? 1000 : code == 2 ? 500 : 250))
                $fatal(1, "transaction %0d: bit rate code %h set, the emulator will use %0d kbit/s", n, code, u_emu.last_value(SAR_DEVICE + 16 * 7));
            if (code != SAR_RATE_CODE) begin
                // Back to the bus's own rate before the power cycle (the controller's rate is fixed).
                send(CONFIG_ID, 8'h13, 8'h00, SAR_RATE_CODE);
                expect_frame(CONFIG_ID, ack_of(8'h13), 1'b0, ANSWER_CLOCKS);
            end
            u_emu.set_status(SAR_DEVICE, "power", 0);
            repeat (20 * BIT_CLOCKS) @(posedge clk);
            u_emu.set_status(SAR_DEVICE, "power", 1);
            repeat (20 * BIT_CLOCKS) @(posedge clk);
            if (u_emu.last_value(SAR_DEVICE + 16 * 2) != new_node)
                $fatal(1, "transaction %0d: after the power cycle the SAR58K24 is node %h, not %h", n, u_emu.last_value(SAR_DEVICE + 16 * 2), new_node);
            node = new_node;
            configs = configs + 1;
        end else begin
            // Click (①): one position.
            send(11'h200 + node, 8'h80, node, 8'h00);
            expect_position(ANSWER_CLOCKS);
            clicks = clicks + 1;
        end
        // Nothing else may come.
        if (q_count != 0)
            $fatal(1, "transaction %0d at %0t: an extra frame %h [%h] from the SAR58K24", n, $time, q_id[q_head], q_data[q_head]);
    end
    repeat (20 * BIT_CLOCKS) @(posedge clk);
    if (q_count != 0 || u_emu.last_value(SAR_DEVICE + 16) != heard)
        $fatal(1, "at the end: the SAR58K24 sent %0d frames, the core read %0d", u_emu.last_value(SAR_DEVICE + 16), heard);
    if (u_mon.violations(0) != 0)
        $fatal(1, "the monitor saw %0d CAN or SAR58K24 command rule violation(s) by the core (PROTOCOL VIOLATION lines above)", u_mon.violations(0));
    if (u_emu.violations(0) != 0)
        $fatal(1, "the emulated devices detected %0d error(s) in the core's frames (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    $display("cycles %0d", cycles);
    $display("commands: %0d clicks, %0d zeros, %0d directions, %0d starts, %0d timed sends, %0d configurations; %0d positions; %0d frames of other devices",
             clicks, zeros, directions, starts, timed, configs, positions, others);
    $display("PASS tb_cosim_sar58k24_can: %0d commands, every answer of the SAR58K24 read exactly as it sent it (%0d frames)", transactions, heard);
    $finish;
end

endmodule

`default_nettype wire
