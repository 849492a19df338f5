// tb_ssi_master_ports.vh: the ports of ssi_master in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_ssi_master.v after its parameters; it includes the vector player.

localparam N_IN = 2;
localparam N_OUT = 7;
localparam OUT_BITS = 6 + BITS;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_start = 0;
reg i_ssi_data = 1;
wire o_ssi_clk;
wire o_busy;
wire o_done;
wire [BITS-1:0] o_position;
wire o_err_idle;
wire o_err_double;
wire o_err_wire;

task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'h1;
        i_ssi_data = `IN_WORD(1) & 1'h1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_ssi_clk,
    o_busy,
    o_done,
    o_position,
    o_err_idle,
    o_err_double,
    o_err_wire
};

task check_outputs;
    begin
        `CHECK(0, "o_ssi_clk", o_ssi_clk)
        `CHECK(1, "o_busy", o_busy)
        `CHECK(2, "o_done", o_done)
        `CHECK(3, "o_position", o_position)
        `CHECK(4, "o_err_idle", o_err_idle)
        `CHECK(5, "o_err_double", o_err_double)
        `CHECK(6, "o_err_wire", o_err_wire)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_start(i_start), \
    .i_ssi_data(i_ssi_data), \
    .o_ssi_clk(o_ssi_clk), \
    .o_busy(o_busy), \
    .o_done(o_done), \
    .o_position(o_position), \
    .o_err_idle(o_err_idle), \
    .o_err_double(o_err_double), \
    .o_err_wire(o_err_wire)
