// tb_cosim_canopen_master: canopen_master closed-loop against a CANopen
// DS 406 encoder on a wired-AND bus (hdl/emu/canopen_encoder_emu.v), no
// vectors. The master must boot the encoder, configure it from its
// parameter table (every SDO confirmed, no abort) and start it; then each
// transaction the testbench moves the encoder's disk to a random 25-bit
// position (u_emu.set_position), and the master must report it in
// o_position within three position PDOs, every o_position equal to the
// position of the PDO the encoder sent last (u_emu.last_value(0)), with no
// o_pos_timeout, o_sdo_abort, o_node_lost, and no error the encoder
// detects in the master's frames.
//
// Plusargs: +canopen_emu_config=<scenario.toml>, +transactions=N (default
// 1000), +seed=S, +flip_bit=K (planted failure: the comparison flips bit K
// of o_position, so the run must fail), +canopen_monitor_transcript=FILE
// (the monitor's JSON transcript).
//
// A pin-level monitor (hdl/emu/canopen_monitor.v) watches the master's TXD
// and RXD with the same configuration: at every o_pos_valid the position of
// the last PDO it decoded must equal the master's, and the master must break
// none of the CAN and CANopen rules it checks (SDO, NMT start, SYNC period).

`timescale 1fs / 1fs
`include "canopen_monitor.v"
`default_nettype none

module tb_cosim_canopen_master;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter BRP = 1;
parameter PROP_SEG = 3;
parameter PHASE_SEG1 = 2;
parameter PHASE_SEG2 = 2;
parameter SJW = 1;
parameter SYNC_STAGES = 2;
parameter NODE = 1;
parameter N_PARAMS = 0;
parameter [31:0] PARAM0_OBJECT = 32'd0;
parameter [31:0] PARAM0_VALUE = 32'd0;
parameter [31:0] PARAM1_OBJECT = 32'd0;
parameter [31:0] PARAM1_VALUE = 32'd0;
parameter [31:0] PARAM2_OBJECT = 32'd0;
parameter [31:0] PARAM2_VALUE = 32'd0;
parameter [31:0] PARAM3_OBJECT = 32'd0;
parameter [31:0] PARAM3_VALUE = 32'd0;
parameter [31:0] PARAM4_OBJECT = 32'd0;
parameter [31:0] PARAM4_VALUE = 32'd0;
parameter [31:0] PARAM5_OBJECT = 32'd0;
parameter [31:0] PARAM5_VALUE = 32'd0;
parameter [31:0] PARAM6_OBJECT = 32'd0;
parameter [31:0] PARAM6_VALUE = 32'd0;
parameter [31:0] PARAM7_OBJECT = 32'd0;
parameter [31:0] PARAM7_VALUE = 32'd0;
parameter BOOT_TIMEOUT = 8000;
parameter SDO_TIMEOUT = 4000;
parameter RETRIES = 2;
parameter PDO_TIMEOUT = 8000;
parameter SYNC_PERIOD = 0;

/* Harness parameters */
parameter F_SYS_HZ = 8000000;
parameter HALF_PERIOD_FS = 62_500_000;

localparam BIT_CLOCKS = BRP * (1 + PROP_SEG + PHASE_SEG1 + PHASE_SEG2);

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_start = 1'b0;
wire [2:0] o_state;
wire o_booted, o_config_done, o_sdo_abort, o_node_lost, o_pos_valid, o_pos_timeout, o_pos_stale;
wire o_emcy_valid, o_sync_sent;
wire [31:0] o_abort_code, o_position;
wire [15:0] o_abort_index, o_emcy_code;
wire [7:0] o_abort_sub, o_emcy_reg;
wire can_tx, can_rx;

canopen_master #(
    .BRP(BRP),
    .PROP_SEG(PROP_SEG),
    .PHASE_SEG1(PHASE_SEG1),
    .PHASE_SEG2(PHASE_SEG2),
    .SJW(SJW),
    .SYNC_STAGES(SYNC_STAGES),
    .NODE(NODE),
    .N_PARAMS(N_PARAMS),
    .PARAM0_OBJECT(PARAM0_OBJECT),
    .PARAM0_VALUE(PARAM0_VALUE),
    .PARAM1_OBJECT(PARAM1_OBJECT),
    .PARAM1_VALUE(PARAM1_VALUE),
    .PARAM2_OBJECT(PARAM2_OBJECT),
    .PARAM2_VALUE(PARAM2_VALUE),
    .PARAM3_OBJECT(PARAM3_OBJECT),
    .PARAM3_VALUE(PARAM3_VALUE),
    .PARAM4_OBJECT(PARAM4_OBJECT),
    .PARAM4_VALUE(PARAM4_VALUE),
    .PARAM5_OBJECT(PARAM5_OBJECT),
    .PARAM5_VALUE(PARAM5_VALUE),
    .PARAM6_OBJECT(PARAM6_OBJECT),
    .PARAM6_VALUE(PARAM6_VALUE),
    .PARAM7_OBJECT(PARAM7_OBJECT),
    .PARAM7_VALUE(PARAM7_VALUE),
    .BOOT_TIMEOUT(BOOT_TIMEOUT),
    .SDO_TIMEOUT(SDO_TIMEOUT),
    .RETRIES(RETRIES),
    .PDO_TIMEOUT(PDO_TIMEOUT),
    .SYNC_PERIOD(SYNC_PERIOD)
) dut (
    .i_clk(clk), .i_rst(rst), .i_start(i_start), .o_state(o_state),
    .o_booted(o_booted), .o_config_done(o_config_done), .o_sdo_abort(o_sdo_abort),
    .o_abort_code(o_abort_code), .o_abort_index(o_abort_index), .o_abort_sub(o_abort_sub),
    .o_node_lost(o_node_lost), .o_pos_valid(o_pos_valid), .o_position(o_position),
    .o_pos_timeout(o_pos_timeout), .o_pos_stale(o_pos_stale), .o_emcy_valid(o_emcy_valid),
    .o_emcy_code(o_emcy_code), .o_emcy_reg(o_emcy_reg), .o_sync_sent(o_sync_sent),
    .o_can_tx(can_tx), .i_can_rx(can_rx)
);

// The encoders' reference clock is the core's clock here.
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

// Anything that must never happen once configured.
reg bad = 1'b0;
always @(posedge clk) if (o_sdo_abort || o_node_lost || (o_pos_timeout && !rst)) bad <= 1'b1;

`include "emu_random.vh"
integer transactions, seed, flip_bit, n, pdos, waited;
reg [63:0] pos, got, sent;

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    waited = 0;
    while (!o_config_done) begin
        @(posedge clk);
        waited = waited + 1;
        if (bad || waited > (RETRIES + 1) * BOOT_TIMEOUT + (N_PARAMS + 1) * SDO_TIMEOUT)
            $fatal(1, "no o_config_done after %0d cycles (state %0d, abort %b code %h index %h sub %h)", waited, o_state, bad, o_abort_code, o_abort_index, o_abort_sub);
    end
    for (n = 0; n < transactions; n = n + 1) begin
        pos = {random32(0)} & 64'h1FF_FFFF;
        u_emu.set_position(0, pos);
        pdos = 0;
        got = ~64'd0;
        while (got != pos) begin
            @(posedge clk);
            if (bad) $fatal(1, "transaction %0d at %0t: o_sdo_abort, o_node_lost or o_pos_timeout", n, $time);
            if (o_pos_valid) begin
                got = o_position;
                // The master takes the frame at the receivers' point (EOF bit 6); the
                // encoder counts it sent at its end: wait two bits before asking.
                repeat (2 * BIT_CLOCKS) @(posedge clk);
                if (flip_bit >= 0) got = got ^ (64'd1 << flip_bit);
                sent = u_emu.last_value(0);
                if (got != sent)
                    $fatal(1, "transaction %0d at %0t: the encoder sent position %0d, the master reports %0d", n, $time, sent, got);
                if (u_mon.last_value(5) != o_position)
                    $fatal(1, "transaction %0d at %0t: the monitor decoded position %0d on the bus, the master reports %0d", n, $time, u_mon.last_value(5), o_position);
                pdos = pdos + 1;
                if (got != pos && pdos >= 3)
                    $fatal(1, "transaction %0d at %0t: position %0d set, still %0d after %0d PDOs", n, $time, pos, got, pdos);
            end
        end
    end
    if (u_mon.violations(0) != 0)
        $fatal(1, "the monitor saw %0d CAN/CANopen rule violation(s) by the master (PROTOCOL VIOLATION lines above)", u_mon.violations(0));
    if (u_emu.violations(0) != 0)
        $fatal(1, "the encoder detected %0d error(s) in the master's frames (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_canopen_master: %0d positions, each reported exactly as the encoder sent it and the monitor decoded it", transactions);
    $finish;
end

endmodule

`default_nettype wire
