// tb_can_controller_ports.vh: the ports of can_controller in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_can_controller.v after its parameters; it includes the vector player.

localparam N_IN = 8;
localparam N_OUT = 19;
localparam OUT_BITS = 129;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_tx_start = 0;
reg [10:0] i_tx_id = 0;
reg i_tx_rtr = 0;
reg [3:0] i_tx_dlc = 0;
reg [63:0] i_tx_data = 0;
reg [28:0] i_filter_id = 0;
reg [28:0] i_filter_mask = 0;
reg i_can_rx = 1;
wire o_can_tx;
wire o_tx_busy;
wire o_tx_done;
wire o_arb_lost;
wire o_rx_valid;
wire [28:0] o_rx_id;
wire o_rx_ide;
wire o_rx_rtr;
wire [3:0] o_rx_dlc;
wire [63:0] o_rx_data;
wire [8:0] o_tec;
wire [7:0] o_rec;
wire [1:0] o_err_state;
wire o_err_bit;
wire o_err_stuff;
wire o_err_crc;
wire o_err_form;
wire o_err_ack;
wire o_overload;

task apply_inputs;
    begin
        i_tx_start = `IN_WORD(0) & 1'h1;
        i_tx_id = `IN_WORD(1) & 11'h7FF;
        i_tx_rtr = `IN_WORD(2) & 1'h1;
        i_tx_dlc = `IN_WORD(3) & 4'hF;
        i_tx_data = `IN_WORD(4) & 64'hFFFFFFFFFFFFFFFF;
        i_filter_id = `IN_WORD(5) & 29'h1FFFFFFF;
        i_filter_mask = `IN_WORD(6) & 29'h1FFFFFFF;
        i_can_rx = `IN_WORD(7) & 1'h1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_can_tx,
    o_tx_busy,
    o_tx_done,
    o_arb_lost,
    o_rx_valid,
    o_rx_id,
    o_rx_ide,
    o_rx_rtr,
    o_rx_dlc,
    o_rx_data,
    o_tec,
    o_rec,
    o_err_state,
    o_err_bit,
    o_err_stuff,
    o_err_crc,
    o_err_form,
    o_err_ack,
    o_overload
};

task check_outputs;
    begin
        `CHECK(0, "o_can_tx", o_can_tx)
        `CHECK(1, "o_tx_busy", o_tx_busy)
        `CHECK(2, "o_tx_done", o_tx_done)
        `CHECK(3, "o_arb_lost", o_arb_lost)
        `CHECK(4, "o_rx_valid", o_rx_valid)
        `CHECK(5, "o_rx_id", o_rx_id)
        `CHECK(6, "o_rx_ide", o_rx_ide)
        `CHECK(7, "o_rx_rtr", o_rx_rtr)
        `CHECK(8, "o_rx_dlc", o_rx_dlc)
        `CHECK(9, "o_rx_data", o_rx_data)
        `CHECK(10, "o_tec", o_tec)
        `CHECK(11, "o_rec", o_rec)
        `CHECK(12, "o_err_state", o_err_state)
        `CHECK(13, "o_err_bit", o_err_bit)
        `CHECK(14, "o_err_stuff", o_err_stuff)
        `CHECK(15, "o_err_crc", o_err_crc)
        `CHECK(16, "o_err_form", o_err_form)
        `CHECK(17, "o_err_ack", o_err_ack)
        `CHECK(18, "o_overload", o_overload)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_tx_start(i_tx_start), \
    .i_tx_id(i_tx_id), \
    .i_tx_rtr(i_tx_rtr), \
    .i_tx_dlc(i_tx_dlc), \
    .i_tx_data(i_tx_data), \
    .i_filter_id(i_filter_id), \
    .i_filter_mask(i_filter_mask), \
    .i_can_rx(i_can_rx), \
    .o_can_tx(o_can_tx), \
    .o_tx_busy(o_tx_busy), \
    .o_tx_done(o_tx_done), \
    .o_arb_lost(o_arb_lost), \
    .o_rx_valid(o_rx_valid), \
    .o_rx_id(o_rx_id), \
    .o_rx_ide(o_rx_ide), \
    .o_rx_rtr(o_rx_rtr), \
    .o_rx_dlc(o_rx_dlc), \
    .o_rx_data(o_rx_data), \
    .o_tec(o_tec), \
    .o_rec(o_rec), \
    .o_err_state(o_err_state), \
    .o_err_bit(o_err_bit), \
    .o_err_stuff(o_err_stuff), \
    .o_err_crc(o_err_crc), \
    .o_err_form(o_err_form), \
    .o_err_ack(o_err_ack), \
    .o_overload(o_overload)
