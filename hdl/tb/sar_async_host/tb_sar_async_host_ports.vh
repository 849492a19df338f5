// tb_sar_async_host_ports.vh: the ports of sar_async_host in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_sar_async_host.v after its parameters; it includes the vector player.

localparam N_IN = 4;
localparam N_OUT = 14;
localparam OUT_BITS = 45;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_start = 0;
reg i_zero = 0;
reg [3:0] i_address = 0;
reg i_rx = 1;
wire o_tx;
wire o_tx_en;
wire o_trigger;
wire o_clr;
wire o_busy;
wire o_done;
wire o_valid;
wire [31:0] o_position;
wire o_err_checksum;
wire o_err_parity;
wire o_err_frame;
wire o_err_address;
wire o_err_timeout;
wire o_err_stale;

task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'h1;
        i_zero = `IN_WORD(1) & 1'h1;
        i_address = `IN_WORD(2) & 4'hF;
        i_rx = `IN_WORD(3) & 1'h1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_tx,
    o_tx_en,
    o_trigger,
    o_clr,
    o_busy,
    o_done,
    o_valid,
    o_position,
    o_err_checksum,
    o_err_parity,
    o_err_frame,
    o_err_address,
    o_err_timeout,
    o_err_stale
};

task check_outputs;
    begin
        `CHECK(0, "o_tx", o_tx)
        `CHECK(1, "o_tx_en", o_tx_en)
        `CHECK(2, "o_trigger", o_trigger)
        `CHECK(3, "o_clr", o_clr)
        `CHECK(4, "o_busy", o_busy)
        `CHECK(5, "o_done", o_done)
        `CHECK(6, "o_valid", o_valid)
        `CHECK(7, "o_position", o_position)
        `CHECK(8, "o_err_checksum", o_err_checksum)
        `CHECK(9, "o_err_parity", o_err_parity)
        `CHECK(10, "o_err_frame", o_err_frame)
        `CHECK(11, "o_err_address", o_err_address)
        `CHECK(12, "o_err_timeout", o_err_timeout)
        `CHECK(13, "o_err_stale", o_err_stale)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_start(i_start), \
    .i_zero(i_zero), \
    .i_address(i_address), \
    .i_rx(i_rx), \
    .o_tx(o_tx), \
    .o_tx_en(o_tx_en), \
    .o_trigger(o_trigger), \
    .o_clr(o_clr), \
    .o_busy(o_busy), \
    .o_done(o_done), \
    .o_valid(o_valid), \
    .o_position(o_position), \
    .o_err_checksum(o_err_checksum), \
    .o_err_parity(o_err_parity), \
    .o_err_frame(o_err_frame), \
    .o_err_address(o_err_address), \
    .o_err_timeout(o_err_timeout), \
    .o_err_stale(o_err_stale)
