// tb_biss_master_ports.vh: the ports of biss_master in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_biss_master.v after its parameters; it includes the vector player.

localparam N_IN = 10;
localparam N_OUT = 23;
localparam OUT_BITS = 60 + DATA_W;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_start = 0;
reg i_slo = 1;
reg i_reg_start = 0;
reg i_reg_write = 0;
reg [2:0] i_reg_id = 0;
reg [6:0] i_reg_addr = 0;
reg [7:0] i_reg_wdata = 0;
reg i_cmd_start = 0;
reg [7:0] i_cmd_ids = 0;
reg [1:0] i_cmd_code = 0;
wire o_ma;
wire o_busy;
wire o_done;
wire o_err_line;
wire o_err_ack;
wire o_err_delay;
wire o_err_start;
wire o_err_timeout;
wire [15:0] o_delay;
wire o_slave_valid;
wire [1:0] o_slave_index;
wire [DATA_W-1:0] o_data;
wire o_crc_err;
wire o_error;
wire o_warning;
wire o_cds;
wire o_reg_busy;
wire o_reg_done;
wire o_reg_err;
wire [7:0] o_reg_rdata;
wire o_reg_crc_err;
wire [15:0] o_delay_mean;
wire o_err_drift;

task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'h1;
        i_slo = `IN_WORD(1) & 1'h1;
        i_reg_start = `IN_WORD(2) & 1'h1;
        i_reg_write = `IN_WORD(3) & 1'h1;
        i_reg_id = `IN_WORD(4) & 3'h7;
        i_reg_addr = `IN_WORD(5) & 7'h7F;
        i_reg_wdata = `IN_WORD(6) & 8'hFF;
        i_cmd_start = `IN_WORD(7) & 1'h1;
        i_cmd_ids = `IN_WORD(8) & 8'hFF;
        i_cmd_code = `IN_WORD(9) & 2'h3;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_ma,
    o_busy,
    o_done,
    o_err_line,
    o_err_ack,
    o_err_delay,
    o_err_start,
    o_err_timeout,
    o_delay,
    o_slave_valid,
    o_slave_index,
    o_data,
    o_crc_err,
    o_error,
    o_warning,
    o_cds,
    o_reg_busy,
    o_reg_done,
    o_reg_err,
    o_reg_rdata,
    o_reg_crc_err,
    o_delay_mean,
    o_err_drift
};

task check_outputs;
    begin
        `CHECK(0, "o_ma", o_ma)
        `CHECK(1, "o_busy", o_busy)
        `CHECK(2, "o_done", o_done)
        `CHECK(3, "o_err_line", o_err_line)
        `CHECK(4, "o_err_ack", o_err_ack)
        `CHECK(5, "o_err_delay", o_err_delay)
        `CHECK(6, "o_err_start", o_err_start)
        `CHECK(7, "o_err_timeout", o_err_timeout)
        `CHECK(8, "o_delay", o_delay)
        `CHECK(9, "o_slave_valid", o_slave_valid)
        `CHECK(10, "o_slave_index", o_slave_index)
        `CHECK(11, "o_data", o_data)
        `CHECK(12, "o_crc_err", o_crc_err)
        `CHECK(13, "o_error", o_error)
        `CHECK(14, "o_warning", o_warning)
        `CHECK(15, "o_cds", o_cds)
        `CHECK(16, "o_reg_busy", o_reg_busy)
        `CHECK(17, "o_reg_done", o_reg_done)
        `CHECK(18, "o_reg_err", o_reg_err)
        `CHECK(19, "o_reg_rdata", o_reg_rdata)
        `CHECK(20, "o_reg_crc_err", o_reg_crc_err)
        `CHECK(21, "o_delay_mean", o_delay_mean)
        `CHECK(22, "o_err_drift", o_err_drift)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_start(i_start), \
    .i_slo(i_slo), \
    .i_reg_start(i_reg_start), \
    .i_reg_write(i_reg_write), \
    .i_reg_id(i_reg_id), \
    .i_reg_addr(i_reg_addr), \
    .i_reg_wdata(i_reg_wdata), \
    .i_cmd_start(i_cmd_start), \
    .i_cmd_ids(i_cmd_ids), \
    .i_cmd_code(i_cmd_code), \
    .o_ma(o_ma), \
    .o_busy(o_busy), \
    .o_done(o_done), \
    .o_err_line(o_err_line), \
    .o_err_ack(o_err_ack), \
    .o_err_delay(o_err_delay), \
    .o_err_start(o_err_start), \
    .o_err_timeout(o_err_timeout), \
    .o_delay(o_delay), \
    .o_slave_valid(o_slave_valid), \
    .o_slave_index(o_slave_index), \
    .o_data(o_data), \
    .o_crc_err(o_crc_err), \
    .o_error(o_error), \
    .o_warning(o_warning), \
    .o_cds(o_cds), \
    .o_reg_busy(o_reg_busy), \
    .o_reg_done(o_reg_done), \
    .o_reg_err(o_reg_err), \
    .o_reg_rdata(o_reg_rdata), \
    .o_reg_crc_err(o_reg_crc_err), \
    .o_delay_mean(o_delay_mean), \
    .o_err_drift(o_err_drift)
