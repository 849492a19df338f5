// tb_modbus_master_ports.vh: the ports of modbus_master in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_modbus_master.v after its parameters; it includes the vector player.

localparam N_IN = 7;
localparam N_OUT = 18;
localparam OUT_BITS = 63;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_start = 0;
reg i_query = 0;
reg i_write = 0;
reg [7:0] i_address = 0;
reg [7:0] i_new_address = 0;
reg [1:0] i_count = 0;
reg i_rx = 1;
wire o_tx;
wire o_tx_en;
wire o_busy;
wire o_done;
wire o_valid;
wire [31:0] o_value;
wire [7:0] o_station;
wire [7:0] o_exception;
wire o_err_parity;
wire o_err_framing;
wire o_err_gap;
wire o_err_length;
wire o_err_crc;
wire o_err_address;
wire o_err_exception;
wire o_err_function;
wire o_err_count;
wire o_err_timeout;

task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'h1;
        i_query = `IN_WORD(1) & 1'h1;
        i_write = `IN_WORD(2) & 1'h1;
        i_address = `IN_WORD(3) & 8'hFF;
        i_new_address = `IN_WORD(4) & 8'hFF;
        i_count = `IN_WORD(5) & 2'h3;
        i_rx = `IN_WORD(6) & 1'h1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_tx,
    o_tx_en,
    o_busy,
    o_done,
    o_valid,
    o_value,
    o_station,
    o_exception,
    o_err_parity,
    o_err_framing,
    o_err_gap,
    o_err_length,
    o_err_crc,
    o_err_address,
    o_err_exception,
    o_err_function,
    o_err_count,
    o_err_timeout
};

task check_outputs;
    begin
        `CHECK(0, "o_tx", o_tx)
        `CHECK(1, "o_tx_en", o_tx_en)
        `CHECK(2, "o_busy", o_busy)
        `CHECK(3, "o_done", o_done)
        `CHECK(4, "o_valid", o_valid)
        `CHECK(5, "o_value", o_value)
        `CHECK(6, "o_station", o_station)
        `CHECK(7, "o_exception", o_exception)
        `CHECK(8, "o_err_parity", o_err_parity)
        `CHECK(9, "o_err_framing", o_err_framing)
        `CHECK(10, "o_err_gap", o_err_gap)
        `CHECK(11, "o_err_length", o_err_length)
        `CHECK(12, "o_err_crc", o_err_crc)
        `CHECK(13, "o_err_address", o_err_address)
        `CHECK(14, "o_err_exception", o_err_exception)
        `CHECK(15, "o_err_function", o_err_function)
        `CHECK(16, "o_err_count", o_err_count)
        `CHECK(17, "o_err_timeout", o_err_timeout)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_start(i_start), \
    .i_query(i_query), \
    .i_write(i_write), \
    .i_address(i_address), \
    .i_new_address(i_new_address), \
    .i_count(i_count), \
    .i_rx(i_rx), \
    .o_tx(o_tx), \
    .o_tx_en(o_tx_en), \
    .o_busy(o_busy), \
    .o_done(o_done), \
    .o_valid(o_valid), \
    .o_value(o_value), \
    .o_station(o_station), \
    .o_exception(o_exception), \
    .o_err_parity(o_err_parity), \
    .o_err_framing(o_err_framing), \
    .o_err_gap(o_err_gap), \
    .o_err_length(o_err_length), \
    .o_err_crc(o_err_crc), \
    .o_err_address(o_err_address), \
    .o_err_exception(o_err_exception), \
    .o_err_function(o_err_function), \
    .o_err_count(o_err_count), \
    .o_err_timeout(o_err_timeout)
