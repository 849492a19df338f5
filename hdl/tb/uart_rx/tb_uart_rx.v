// tb_uart_rx: replays golden vectors from the Rust model against uart_rx.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_uart_rx;

/* Core parameters: set per vector file from its `params:` header line */
parameter CLOCKS_PER_BIT = 10;
parameter PARITY = 0;

/* Harness parameters */
parameter HALF_PERIOD_FS = 5_000_000;
parameter MAX_WORDS = 1 << 22;

`include "tb_uart_rx_ports.vh"

uart_rx #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .PARITY(PARITY)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (uart::Receiver::new:
// Out::default(), every output 0) at each falling edge of the reset, so a
// wrong reset value of an output register that the first cycle would
// overwrite (a pulse such as o_frame_err) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_valid, o_frame_err, o_start_err, o_busy, o_parity_err} !== 5'b00000 || o_data !== 8'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "uart_rx: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
