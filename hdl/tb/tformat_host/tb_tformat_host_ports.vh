// tb_tformat_host_ports.vh: the ports of tformat_host in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_tformat_host.v after its parameters; it includes the vector player.

localparam N_IN = 5;
localparam N_OUT = 17;
localparam OUT_BITS = 90;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_start = 0;
reg [3:0] i_data_id = 0;
reg [6:0] i_address = 0;
reg [7:0] i_wdata = 0;
reg i_rx = 1;
wire o_tx;
wire o_tx_en;
wire o_busy;
wire o_done;
wire [7:0] o_cf;
wire [7:0] o_sf;
wire [16:0] o_abs;
wire [15:0] o_abm;
wire [7:0] o_enid;
wire [7:0] o_almc;
wire [7:0] o_adf;
wire [7:0] o_edf;
wire o_err_crc;
wire o_err_timeout;
wire o_err_frame;
wire o_err_cf;
wire o_err_comm;

task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'h1;
        i_data_id = `IN_WORD(1) & 4'hF;
        i_address = `IN_WORD(2) & 7'h7F;
        i_wdata = `IN_WORD(3) & 8'hFF;
        i_rx = `IN_WORD(4) & 1'h1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_tx,
    o_tx_en,
    o_busy,
    o_done,
    o_cf,
    o_sf,
    o_abs,
    o_abm,
    o_enid,
    o_almc,
    o_adf,
    o_edf,
    o_err_crc,
    o_err_timeout,
    o_err_frame,
    o_err_cf,
    o_err_comm
};

task check_outputs;
    begin
        `CHECK(0, "o_tx", o_tx)
        `CHECK(1, "o_tx_en", o_tx_en)
        `CHECK(2, "o_busy", o_busy)
        `CHECK(3, "o_done", o_done)
        `CHECK(4, "o_cf", o_cf)
        `CHECK(5, "o_sf", o_sf)
        `CHECK(6, "o_abs", o_abs)
        `CHECK(7, "o_abm", o_abm)
        `CHECK(8, "o_enid", o_enid)
        `CHECK(9, "o_almc", o_almc)
        `CHECK(10, "o_adf", o_adf)
        `CHECK(11, "o_edf", o_edf)
        `CHECK(12, "o_err_crc", o_err_crc)
        `CHECK(13, "o_err_timeout", o_err_timeout)
        `CHECK(14, "o_err_frame", o_err_frame)
        `CHECK(15, "o_err_cf", o_err_cf)
        `CHECK(16, "o_err_comm", o_err_comm)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_start(i_start), \
    .i_data_id(i_data_id), \
    .i_address(i_address), \
    .i_wdata(i_wdata), \
    .i_rx(i_rx), \
    .o_tx(o_tx), \
    .o_tx_en(o_tx_en), \
    .o_busy(o_busy), \
    .o_done(o_done), \
    .o_cf(o_cf), \
    .o_sf(o_sf), \
    .o_abs(o_abs), \
    .o_abm(o_abm), \
    .o_enid(o_enid), \
    .o_almc(o_almc), \
    .o_adf(o_adf), \
    .o_edf(o_edf), \
    .o_err_crc(o_err_crc), \
    .o_err_timeout(o_err_timeout), \
    .o_err_frame(o_err_frame), \
    .o_err_cf(o_err_cf), \
    .o_err_comm(o_err_comm)
