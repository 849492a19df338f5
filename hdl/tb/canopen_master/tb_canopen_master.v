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

`include "tb_canopen_master_ports.vh"

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
    `DUT_PORTS
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
