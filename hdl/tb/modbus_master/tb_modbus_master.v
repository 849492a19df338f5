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

`include "tb_modbus_master_ports.vh"

modbus_master #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .PARITY(PARITY),
    .T15_CLOCKS(T15_CLOCKS),
    .T35_CLOCKS(T35_CLOCKS),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
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
