// tb_canopen_master_ports.vh: the ports of canopen_master in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_canopen_master.v after its parameters; it includes the vector player.

localparam N_IN = 2;
localparam N_OUT = 17;
localparam OUT_BITS = 125;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_start = 0;
reg i_can_rx = 1;
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

task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'h1;
        i_can_rx = `IN_WORD(1) & 1'h1;
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

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_start(i_start), \
    .i_can_rx(i_can_rx), \
    .o_can_tx(o_can_tx), \
    .o_state(o_state), \
    .o_booted(o_booted), \
    .o_config_done(o_config_done), \
    .o_sdo_abort(o_sdo_abort), \
    .o_abort_code(o_abort_code), \
    .o_abort_index(o_abort_index), \
    .o_abort_sub(o_abort_sub), \
    .o_node_lost(o_node_lost), \
    .o_pos_valid(o_pos_valid), \
    .o_position(o_position), \
    .o_pos_timeout(o_pos_timeout), \
    .o_pos_stale(o_pos_stale), \
    .o_emcy_valid(o_emcy_valid), \
    .o_emcy_code(o_emcy_code), \
    .o_emcy_reg(o_emcy_reg), \
    .o_sync_sent(o_sync_sent)
