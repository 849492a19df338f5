// tb_sar_async_host: replays golden vectors from the Rust model against sar_async_host.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_sar_async_host;

/* Core parameters: set per vector file from its `params:` header line */
parameter MODE = 0;
parameter BITS = 14;
parameter GRAY = 0;
parameter PARITY = 0;
parameter TAG_ADDRESS = 1;
parameter ZERO_ANSWER = 1;
parameter CLOCKS_PER_BIT = 87;
parameter GAP_CLOCKS = 1305;
parameter STALE_CLOCKS = 0;
parameter TIMEOUT_CLOCKS = 50000;
parameter TRIGGER_LOW_CLOCKS = 100;
parameter CLR_LOW_CLOCKS = 200;

/* Harness parameters */
parameter HALF_PERIOD_FS = 50_000_000;
parameter MAX_WORDS = 1 << 22;

`include "tb_sar_async_host_ports.vh"

sar_async_host #(
    .MODE(MODE),
    .BITS(BITS),
    .GRAY(GRAY),
    .PARITY(PARITY),
    .TAG_ADDRESS(TAG_ADDRESS),
    .ZERO_ANSWER(ZERO_ANSWER),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .GAP_CLOCKS(GAP_CLOCKS),
    .STALE_CLOCKS(STALE_CLOCKS),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .TRIGGER_LOW_CLOCKS(TRIGGER_LOW_CLOCKS),
    .CLR_LOW_CLOCKS(CLR_LOW_CLOCKS)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (sar58k24::host::Out::default: TX idle high, o_trigger and o_clr high, every other output 0) at each
// falling edge of the reset, so a wrong reset value of an output register
// that the first cycle would overwrite (a pulse, a line level) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_tx, o_tx_en, o_trigger, o_clr, o_busy, o_done, o_valid, o_err_checksum, o_err_parity, o_err_frame,
                 o_err_address, o_err_timeout, o_err_stale} !== 13'b1011000000000 || o_position !== 32'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "sar_async_host: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
