// tb_esl_host_ports.vh: the ports of esl_host in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_esl_host.v after its parameters; it includes the vector player.

localparam N_IN = 7;
localparam N_OUT = 27;
localparam OUT_BITS = 156;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_start = 0;
reg [3:0] i_data_id = 0;
reg [2:0] i_address = 0;
reg i_broadcast = 0;
reg [6:0] i_mem_address = 0;
reg [7:0] i_wdata = 0;
reg i_rx = 1;
wire o_tx;
wire o_tx_en;
wire o_busy;
wire o_done;
wire [7:0] o_cf;
wire [7:0] o_sf;
wire [7:0] o_sf2;
wire [7:0] o_alm1;
wire [7:0] o_alm2;
wire [23:0] o_abs;
wire [15:0] o_abm;
wire [15:0] o_rs;
wire [7:0] o_sc1;
wire [6:0] o_sc2;
wire [7:0] o_enid;
wire [7:0] o_temp;
wire [7:0] o_adf;
wire [7:0] o_edf;
wire o_err_crc1;
wire o_err_crc2;
wire o_err_timeout;
wire o_err_frame;
wire o_err_cf;
wire o_err_comm;
wire o_err_seq;
wire o_err_rs;
wire o_err_busy;

task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'h1;
        i_data_id = `IN_WORD(1) & 4'hF;
        i_address = `IN_WORD(2) & 3'h7;
        i_broadcast = `IN_WORD(3) & 1'h1;
        i_mem_address = `IN_WORD(4) & 7'h7F;
        i_wdata = `IN_WORD(5) & 8'hFF;
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
    o_cf,
    o_sf,
    o_sf2,
    o_alm1,
    o_alm2,
    o_abs,
    o_abm,
    o_rs,
    o_sc1,
    o_sc2,
    o_enid,
    o_temp,
    o_adf,
    o_edf,
    o_err_crc1,
    o_err_crc2,
    o_err_timeout,
    o_err_frame,
    o_err_cf,
    o_err_comm,
    o_err_seq,
    o_err_rs,
    o_err_busy
};

task check_outputs;
    begin
        `CHECK(0, "o_tx", o_tx)
        `CHECK(1, "o_tx_en", o_tx_en)
        `CHECK(2, "o_busy", o_busy)
        `CHECK(3, "o_done", o_done)
        `CHECK(4, "o_cf", o_cf)
        `CHECK(5, "o_sf", o_sf)
        `CHECK(6, "o_sf2", o_sf2)
        `CHECK(7, "o_alm1", o_alm1)
        `CHECK(8, "o_alm2", o_alm2)
        `CHECK(9, "o_abs", o_abs)
        `CHECK(10, "o_abm", o_abm)
        `CHECK(11, "o_rs", o_rs)
        `CHECK(12, "o_sc1", o_sc1)
        `CHECK(13, "o_sc2", o_sc2)
        `CHECK(14, "o_enid", o_enid)
        `CHECK(15, "o_temp", o_temp)
        `CHECK(16, "o_adf", o_adf)
        `CHECK(17, "o_edf", o_edf)
        `CHECK(18, "o_err_crc1", o_err_crc1)
        `CHECK(19, "o_err_crc2", o_err_crc2)
        `CHECK(20, "o_err_timeout", o_err_timeout)
        `CHECK(21, "o_err_frame", o_err_frame)
        `CHECK(22, "o_err_cf", o_err_cf)
        `CHECK(23, "o_err_comm", o_err_comm)
        `CHECK(24, "o_err_seq", o_err_seq)
        `CHECK(25, "o_err_rs", o_err_rs)
        `CHECK(26, "o_err_busy", o_err_busy)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_start(i_start), \
    .i_data_id(i_data_id), \
    .i_address(i_address), \
    .i_broadcast(i_broadcast), \
    .i_mem_address(i_mem_address), \
    .i_wdata(i_wdata), \
    .i_rx(i_rx), \
    .o_tx(o_tx), \
    .o_tx_en(o_tx_en), \
    .o_busy(o_busy), \
    .o_done(o_done), \
    .o_cf(o_cf), \
    .o_sf(o_sf), \
    .o_sf2(o_sf2), \
    .o_alm1(o_alm1), \
    .o_alm2(o_alm2), \
    .o_abs(o_abs), \
    .o_abm(o_abm), \
    .o_rs(o_rs), \
    .o_sc1(o_sc1), \
    .o_sc2(o_sc2), \
    .o_enid(o_enid), \
    .o_temp(o_temp), \
    .o_adf(o_adf), \
    .o_edf(o_edf), \
    .o_err_crc1(o_err_crc1), \
    .o_err_crc2(o_err_crc2), \
    .o_err_timeout(o_err_timeout), \
    .o_err_frame(o_err_frame), \
    .o_err_cf(o_err_cf), \
    .o_err_comm(o_err_comm), \
    .o_err_seq(o_err_seq), \
    .o_err_rs(o_err_rs), \
    .o_err_busy(o_err_busy)
