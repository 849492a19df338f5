// tb_canopen_master: replays golden vectors from the Rust model against canopen_master.
`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_canopen_master;

/* Core parameters: set per vector file from its `params:` header line */
parameter BRP = 10;
parameter PROP_SEG = 8;
parameter PHASE_SEG1 = 5;
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
parameter BOOT_TIMEOUT = 400000;
parameter SDO_TIMEOUT = 200000;
parameter RETRIES = 2;
parameter PDO_TIMEOUT = 600000;
parameter SYNC_PERIOD = 0;

/* Harness parameters */
parameter HALF_PERIOD_FS = 12_500_000;
parameter MAX_WORDS = 1 << 22;

localparam N_IN = 2;
localparam N_OUT = 17;
localparam OUT_BITS = 125;

`include "vector_player.vh"

reg i_start = 1'b0;
reg i_can_rx = 1'b1;
wire o_can_tx;
wire [2:0] o_state;
wire o_booted;
wire o_config_done;
wire o_sdo_abort;
wire [31:0] o_abort_code;
wire [15:0] o_abort_index;
wire [7:0] o_abort_sub;
wire o_node_lost;
wire o_pos_valid;
wire [31:0] o_position;
wire o_pos_timeout;
wire o_pos_stale;
wire o_emcy_valid;
wire [15:0] o_emcy_code;
wire [7:0] o_emcy_reg;
wire o_sync_sent;

// Port order = the model's canopen::master::Master::input_ports() / output_ports().
task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'b1;
        i_can_rx = `IN_WORD(1) & 1'b1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_can_tx,
    o_state,
    o_booted,
    o_config_done,
    o_sdo_abort,
    o_abort_code,
    o_abort_index,
    o_abort_sub,
    o_node_lost,
    o_pos_valid,
    o_position,
    o_pos_timeout,
    o_pos_stale,
    o_emcy_valid,
    o_emcy_code,
    o_emcy_reg,
    o_sync_sent
};

task check_outputs;
    begin
        `CHECK(0, "o_can_tx", o_can_tx)
        `CHECK(1, "o_state", o_state)
        `CHECK(2, "o_booted", o_booted)
        `CHECK(3, "o_config_done", o_config_done)
        `CHECK(4, "o_sdo_abort", o_sdo_abort)
        `CHECK(5, "o_abort_code", o_abort_code)
        `CHECK(6, "o_abort_index", o_abort_index)
        `CHECK(7, "o_abort_sub", o_abort_sub)
        `CHECK(8, "o_node_lost", o_node_lost)
        `CHECK(9, "o_pos_valid", o_pos_valid)
        `CHECK(10, "o_position", o_position)
        `CHECK(11, "o_pos_timeout", o_pos_timeout)
        `CHECK(12, "o_pos_stale", o_pos_stale)
        `CHECK(13, "o_emcy_valid", o_emcy_valid)
        `CHECK(14, "o_emcy_code", o_emcy_code)
        `CHECK(15, "o_emcy_reg", o_emcy_reg)
        `CHECK(16, "o_sync_sent", o_sync_sent)
    end
endtask

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
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .o_can_tx(o_can_tx),
    .o_state(o_state),
    .o_booted(o_booted),
    .o_config_done(o_config_done),
    .o_sdo_abort(o_sdo_abort),
    .o_abort_code(o_abort_code),
    .o_abort_index(o_abort_index),
    .o_abort_sub(o_abort_sub),
    .o_node_lost(o_node_lost),
    .o_pos_valid(o_pos_valid),
    .o_position(o_position),
    .o_pos_timeout(o_pos_timeout),
    .o_pos_stale(o_pos_stale),
    .o_emcy_valid(o_emcy_valid),
    .o_emcy_code(o_emcy_code),
    .o_emcy_reg(o_emcy_reg),
    .o_sync_sent(o_sync_sent),
    .i_can_rx(i_can_rx)
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (canopen::master::Master::new:
// TX recessive, state WAIT_BOOT, every other output 0) at each falling edge
// of the reset, so a wrong reset value of an output register that the first
// cycle would overwrite (a pulse such as o_sdo_abort) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_can_tx, o_booted, o_config_done, o_sdo_abort, o_node_lost, o_pos_valid, o_pos_timeout,
                 o_pos_stale, o_emcy_valid, o_sync_sent} !== 10'b1000000000
                || o_state !== 3'd0 || o_abort_code !== 32'd0 || o_abort_index !== 16'd0
                || o_abort_sub !== 8'd0 || o_position !== 32'd0 || o_emcy_code !== 16'd0 || o_emcy_reg !== 8'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "canopen_master: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
