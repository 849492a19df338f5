// tb_uart_rx_ports.vh: the ports of uart_rx in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_uart_rx.v after its parameters; it includes the vector player.

localparam N_IN = 1;
localparam N_OUT = 6;
localparam OUT_BITS = 13;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_rx = 1;
wire [7:0] o_data;
wire o_valid;
wire o_frame_err;
wire o_start_err;
wire o_busy;
wire o_parity_err;

task apply_inputs;
    begin
        i_rx = `IN_WORD(0) & 1'h1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_data,
    o_valid,
    o_frame_err,
    o_start_err,
    o_busy,
    o_parity_err
};

task check_outputs;
    begin
        `CHECK(0, "o_data", o_data)
        `CHECK(1, "o_valid", o_valid)
        `CHECK(2, "o_frame_err", o_frame_err)
        `CHECK(3, "o_start_err", o_start_err)
        `CHECK(4, "o_busy", o_busy)
        `CHECK(5, "o_parity_err", o_parity_err)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_rx(i_rx), \
    .o_data(o_data), \
    .o_valid(o_valid), \
    .o_frame_err(o_frame_err), \
    .o_start_err(o_start_err), \
    .o_busy(o_busy), \
    .o_parity_err(o_parity_err)
