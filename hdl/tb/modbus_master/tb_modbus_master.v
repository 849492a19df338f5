// tb_modbus_master: replays golden vectors from the Rust model against modbus_master.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_modbus_master;

/* Core parameters: set per vector file from its `params:` header line */
parameter CLOCKS_PER_BIT = 521;
parameter PARITY = 0;
parameter T15_CLOCKS = 7813;
parameter T35_CLOCKS = 18229;
parameter TIMEOUT_CLOCKS = 50000;

/* Harness parameters */
parameter HALF_PERIOD_FS = 50_000_000;
parameter MAX_WORDS = 1 << 22;

localparam N_IN = 7;
localparam N_OUT = 18;
localparam OUT_BITS = 63;

`include "vector_player.vh"

reg i_start = 1'b0;
reg i_query = 1'b0;
reg i_write = 1'b0;
reg [7:0] i_address = 8'd1;
reg [7:0] i_new_address = 8'd1;
reg [1:0] i_count = 2'd1;
reg i_rx = 1'b1;
wire o_tx, o_tx_en, o_busy, o_done, o_valid;
wire [31:0] o_value;
wire [7:0] o_station, o_exception;
wire o_err_parity, o_err_framing, o_err_gap, o_err_length, o_err_crc, o_err_address, o_err_exception, o_err_function, o_err_count, o_err_timeout;

// Port order = the model's modbus::Master::input_ports() / output_ports().
task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'b1;
        i_query = `IN_WORD(1) & 1'b1;
        i_write = `IN_WORD(2) & 1'b1;
        i_address = `IN_WORD(3) & 8'hFF;
        i_new_address = `IN_WORD(4) & 8'hFF;
        i_count = `IN_WORD(5) & 2'h3;
        i_rx = `IN_WORD(6) & 1'b1;
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

modbus_master #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .PARITY(PARITY),
    .T15_CLOCKS(T15_CLOCKS),
    .T35_CLOCKS(T35_CLOCKS),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .i_query(i_query),
    .i_write(i_write),
    .i_address(i_address),
    .i_new_address(i_new_address),
    .i_count(i_count),
    .o_busy(o_busy),
    .o_done(o_done),
    .o_valid(o_valid),
    .o_value(o_value),
    .o_station(o_station),
    .o_exception(o_exception),
    .o_err_parity(o_err_parity),
    .o_err_framing(o_err_framing),
    .o_err_gap(o_err_gap),
    .o_err_length(o_err_length),
    .o_err_crc(o_err_crc),
    .o_err_address(o_err_address),
    .o_err_exception(o_err_exception),
    .o_err_function(o_err_function),
    .o_err_count(o_err_count),
    .o_err_timeout(o_err_timeout),
    .o_tx(o_tx),
    .o_tx_en(o_tx_en),
    .i_rx(i_rx)
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (modbus::master::Out::default: TX idle high, every other output 0) at each
// falling edge of the reset, so a wrong reset value of an output register
// that the first cycle would overwrite (a pulse, a line level) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_tx, o_tx_en, o_busy, o_done, o_valid, o_err_parity, o_err_framing, o_err_gap, o_err_length, o_err_crc,
                 o_err_address, o_err_exception, o_err_function, o_err_count, o_err_timeout} !== 15'b100000000000000
                || o_value !== 32'd0 || o_station !== 8'd0 || o_exception !== 8'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "modbus_master: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
