// tb_ssi_master: replays golden vectors from the Rust model against ssi_master.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_ssi_master;

/* Core parameters: set per vector file from its `params:` header line */
parameter BITS = 12;
parameter CLOCKS_PER_BIT = 200;
parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2;
parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2;
parameter GRAY = 0;
parameter DOUBLE_READ = 0;
parameter WIRE_CHECK = 0;
parameter T_CS_CLOCKS = 200;
parameter PAUSE_CLOCKS = 25500;
parameter SAMPLE_DELAY = 0;

/* Harness parameters */
parameter HALF_PERIOD_FS = 10_000_000;
parameter MAX_WORDS = 1 << 22;

`include "tb_ssi_master_ports.vh"

ssi_master #(
    .BITS(BITS),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .HIGH_CLOCKS(HIGH_CLOCKS),
    .LOW_CLOCKS(LOW_CLOCKS),
    .GRAY(GRAY),
    .DOUBLE_READ(DOUBLE_READ),
    .WIRE_CHECK(WIRE_CHECK),
    .T_CS_CLOCKS(T_CS_CLOCKS),
    .PAUSE_CLOCKS(PAUSE_CLOCKS),
    .SAMPLE_DELAY(SAMPLE_DELAY)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (ssi::Master::new: clock
// high, every other output 0) at each falling edge of the reset, so a wrong
// reset value of an output register that the first cycle would overwrite
// (a pulse such as o_err_idle) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_ssi_clk, o_busy, o_done, o_err_idle, o_err_double, o_err_wire} !== 6'b100000 || o_position !== 0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "ssi_master: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
