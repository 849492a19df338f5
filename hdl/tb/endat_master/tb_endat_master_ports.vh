// tb_endat_master_ports.vh: the ports of endat_master in vector-file order, from the model's port lists.
// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's
// input_ports/output_ports and run
//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports
// Included by tb_endat_master.v after its parameters; it includes the vector player.

localparam N_IN = 7;
localparam N_OUT = 29;
localparam OUT_BITS = 159;

`include "vector_player.vh"

// Inputs rest at their idle level until the first record drives them.
reg i_start = 0;
reg [5:0] i_mode = 0;
reg [7:0] i_mrs = 0;
reg [15:0] i_param = 0;
reg [7:0] i_cont_values = 0;
reg i_meas = 0;
reg i_endat_data_in = 1;
wire o_endat_clk;
wire o_endat_data_out;
wire o_endat_data_oe;
wire o_busy;
wire o_done;
wire [47:0] o_position;
wire o_f1;
wire o_f2;
wire o_err_crc;
wire [23:0] o_ad1;
wire o_ad1_valid;
wire o_err_ad1_crc;
wire [23:0] o_ad2;
wire o_ad2_valid;
wire o_err_ad2_crc;
wire [7:0] o_ack_addr;
wire [15:0] o_ack_data;
wire o_err_type2;
wire o_err_type3;
wire o_err_type4;
wire o_err_ack;
wire o_err_timeout;
wire o_err_absent;
wire o_err_idle;
wire o_err_delay;
wire o_meas_done;
wire o_err_meas;
wire o_delay_valid;
wire [15:0] o_delay;

task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'h1;
        i_mode = `IN_WORD(1) & 6'h3F;
        i_mrs = `IN_WORD(2) & 8'hFF;
        i_param = `IN_WORD(3) & 16'hFFFF;
        i_cont_values = `IN_WORD(4) & 8'hFF;
        i_meas = `IN_WORD(5) & 1'h1;
        i_endat_data_in = `IN_WORD(6) & 1'h1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_endat_clk,
    o_endat_data_out,
    o_endat_data_oe,
    o_busy,
    o_done,
    o_position,
    o_f1,
    o_f2,
    o_err_crc,
    o_ad1,
    o_ad1_valid,
    o_err_ad1_crc,
    o_ad2,
    o_ad2_valid,
    o_err_ad2_crc,
    o_ack_addr,
    o_ack_data,
    o_err_type2,
    o_err_type3,
    o_err_type4,
    o_err_ack,
    o_err_timeout,
    o_err_absent,
    o_err_idle,
    o_err_delay,
    o_meas_done,
    o_err_meas,
    o_delay_valid,
    o_delay
};

task check_outputs;
    begin
        `CHECK(0, "o_endat_clk", o_endat_clk)
        `CHECK(1, "o_endat_data_out", o_endat_data_out)
        `CHECK(2, "o_endat_data_oe", o_endat_data_oe)
        `CHECK(3, "o_busy", o_busy)
        `CHECK(4, "o_done", o_done)
        `CHECK(5, "o_position", o_position)
        `CHECK(6, "o_f1", o_f1)
        `CHECK(7, "o_f2", o_f2)
        `CHECK(8, "o_err_crc", o_err_crc)
        `CHECK(9, "o_ad1", o_ad1)
        `CHECK(10, "o_ad1_valid", o_ad1_valid)
        `CHECK(11, "o_err_ad1_crc", o_err_ad1_crc)
        `CHECK(12, "o_ad2", o_ad2)
        `CHECK(13, "o_ad2_valid", o_ad2_valid)
        `CHECK(14, "o_err_ad2_crc", o_err_ad2_crc)
        `CHECK(15, "o_ack_addr", o_ack_addr)
        `CHECK(16, "o_ack_data", o_ack_data)
        `CHECK(17, "o_err_type2", o_err_type2)
        `CHECK(18, "o_err_type3", o_err_type3)
        `CHECK(19, "o_err_type4", o_err_type4)
        `CHECK(20, "o_err_ack", o_err_ack)
        `CHECK(21, "o_err_timeout", o_err_timeout)
        `CHECK(22, "o_err_absent", o_err_absent)
        `CHECK(23, "o_err_idle", o_err_idle)
        `CHECK(24, "o_err_delay", o_err_delay)
        `CHECK(25, "o_meas_done", o_meas_done)
        `CHECK(26, "o_err_meas", o_err_meas)
        `CHECK(27, "o_delay_valid", o_delay_valid)
        `CHECK(28, "o_delay", o_delay)
    end
endtask

// The instance's connections of these ports, each to its namesake.
`define DUT_PORTS \
    .i_start(i_start), \
    .i_mode(i_mode), \
    .i_mrs(i_mrs), \
    .i_param(i_param), \
    .i_cont_values(i_cont_values), \
    .i_meas(i_meas), \
    .i_endat_data_in(i_endat_data_in), \
    .o_endat_clk(o_endat_clk), \
    .o_endat_data_out(o_endat_data_out), \
    .o_endat_data_oe(o_endat_data_oe), \
    .o_busy(o_busy), \
    .o_done(o_done), \
    .o_position(o_position), \
    .o_f1(o_f1), \
    .o_f2(o_f2), \
    .o_err_crc(o_err_crc), \
    .o_ad1(o_ad1), \
    .o_ad1_valid(o_ad1_valid), \
    .o_err_ad1_crc(o_err_ad1_crc), \
    .o_ad2(o_ad2), \
    .o_ad2_valid(o_ad2_valid), \
    .o_err_ad2_crc(o_err_ad2_crc), \
    .o_ack_addr(o_ack_addr), \
    .o_ack_data(o_ack_data), \
    .o_err_type2(o_err_type2), \
    .o_err_type3(o_err_type3), \
    .o_err_type4(o_err_type4), \
    .o_err_ack(o_err_ack), \
    .o_err_timeout(o_err_timeout), \
    .o_err_absent(o_err_absent), \
    .o_err_idle(o_err_idle), \
    .o_err_delay(o_err_delay), \
    .o_meas_done(o_meas_done), \
    .o_err_meas(o_err_meas), \
    .o_delay_valid(o_delay_valid), \
    .o_delay(o_delay)
