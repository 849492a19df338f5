// tb_biss_master: replays golden vectors from the Rust model against biss_master.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_biss_master;

/* Core parameters: set per vector file from its `params:` header line */
parameter SLAVES = 1;
parameter SLAVE_BITS = 16;
parameter SLAVE_CRC_WIDTH = 6;
parameter SLAVE_CRC_POLY = 3;
parameter CLOCKS_PER_BIT = 8;
parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2;
parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2;
parameter MAX_DELAY = 160;
parameter TIMEOUT_CLOCKS = 3200;
parameter CAL_FRAMES = 4;
parameter DELAY_TOL = 1;

/* Harness parameters */
parameter HALF_PERIOD_FS = 6_250_000;
parameter MAX_WORDS = 1 << 22;

function integer field8(input integer packed_values, input integer index);
    begin
        field8 = (packed_values >> (8 * index)) & 255;
    end
endfunction

function integer max_bits(input integer packed_values, input integer count);
    integer k;
    begin
        max_bits = 1;
        for (k = 0; k < count; k = k + 1)
            if (field8(packed_values, k) > max_bits) max_bits = field8(packed_values, k);
    end
endfunction

localparam integer DATA_W = max_bits(SLAVE_BITS, SLAVES);
localparam N_IN = 10;
localparam N_OUT = 23;
localparam OUT_BITS = 60 + DATA_W;

`include "vector_player.vh"

reg i_start = 1'b0;
reg i_slo = 1'b1;
reg i_reg_start = 1'b0;
reg i_reg_write = 1'b0;
reg [2:0] i_reg_id = 3'd0;
reg [6:0] i_reg_addr = 7'd0;
reg [7:0] i_reg_wdata = 8'd0;
reg i_cmd_start = 1'b0;
reg [7:0] i_cmd_ids = 8'd0;
reg [1:0] i_cmd_code = 2'd0;
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

// Port order = the model's biss::Master::input_ports() / output_ports().
task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'b1;
        i_slo = `IN_WORD(1) & 1'b1;
        i_reg_start = `IN_WORD(2) & 1'b1;
        i_reg_write = `IN_WORD(3) & 1'b1;
        i_reg_id = `IN_WORD(4) & 3'h7;
        i_reg_addr = `IN_WORD(5) & 7'h7F;
        i_reg_wdata = `IN_WORD(6) & 8'hFF;
        i_cmd_start = `IN_WORD(7) & 1'b1;
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

biss_master #(
    .SLAVES(SLAVES),
    .SLAVE_BITS(SLAVE_BITS),
    .SLAVE_CRC_WIDTH(SLAVE_CRC_WIDTH),
    .SLAVE_CRC_POLY(SLAVE_CRC_POLY),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .HIGH_CLOCKS(HIGH_CLOCKS),
    .LOW_CLOCKS(LOW_CLOCKS),
    .MAX_DELAY(MAX_DELAY),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .CAL_FRAMES(CAL_FRAMES),
    .DELAY_TOL(DELAY_TOL)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .o_busy(o_busy),
    .o_done(o_done),
    .o_err_line(o_err_line),
    .o_err_ack(o_err_ack),
    .o_err_delay(o_err_delay),
    .o_err_start(o_err_start),
    .o_err_timeout(o_err_timeout),
    .o_delay(o_delay),
    .o_delay_mean(o_delay_mean),
    .o_err_drift(o_err_drift),
    .o_slave_valid(o_slave_valid),
    .o_slave_index(o_slave_index),
    .o_data(o_data),
    .o_crc_err(o_crc_err),
    .o_error(o_error),
    .o_warning(o_warning),
    .o_cds(o_cds),
    .i_reg_start(i_reg_start),
    .i_reg_write(i_reg_write),
    .i_reg_id(i_reg_id),
    .i_reg_addr(i_reg_addr),
    .i_reg_wdata(i_reg_wdata),
    .o_reg_busy(o_reg_busy),
    .o_reg_done(o_reg_done),
    .o_reg_err(o_reg_err),
    .o_reg_rdata(o_reg_rdata),
    .o_reg_crc_err(o_reg_crc_err),
    .i_cmd_start(i_cmd_start),
    .i_cmd_ids(i_cmd_ids),
    .i_cmd_code(i_cmd_code),
    .o_ma(o_ma),
    .i_slo(i_slo)
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (biss::Master::new: MA
// high, every other output 0) at each falling edge of the reset, so a wrong
// reset value of an output register that the first cycle would overwrite
// (a pulse such as o_done or o_err_timeout) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_ma, o_busy, o_done, o_err_line, o_err_ack, o_err_delay, o_err_start, o_err_timeout,
                 o_slave_valid, o_crc_err, o_error, o_warning, o_cds, o_reg_busy, o_reg_done, o_reg_err,
                 o_reg_crc_err, o_err_drift} !== 18'b100000000000000000
                || o_delay !== 16'd0 || o_slave_index !== 2'd0 || o_data !== 0 || o_reg_rdata !== 8'd0 || o_delay_mean !== 16'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "biss_master: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
