// tb_tformat_host: replays golden vectors from the Rust model against tformat_host.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_tformat_host;

/* Core parameters: set per vector file from its `params:` header line */
parameter CLOCKS_PER_BIT = 32;
parameter TIMEOUT_CLOCKS = 1000;
parameter REPEAT_GAP_CLOCKS = 4000000;

/* Harness parameters */
parameter HALF_PERIOD_FS = 5_000_000;
parameter MAX_WORDS = 1 << 22;

`include "tb_tformat_host_ports.vh"

tformat_host #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .REPEAT_GAP_CLOCKS(REPEAT_GAP_CLOCKS)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (tformat::host::Host::new: TX idle high, every other output 0) at each
// falling edge of the reset, so a wrong reset value of an output register
// that the first cycle would overwrite (a pulse, a line level) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_tx, o_tx_en, o_busy, o_done, o_err_crc, o_err_timeout, o_err_frame, o_err_cf, o_err_comm} !== 9'b100000000
                || {o_cf, o_sf, o_abs, o_abm, o_enid, o_almc, o_adf, o_edf} !== 81'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "tformat_host: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
