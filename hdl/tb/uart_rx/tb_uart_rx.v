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

localparam N_IN = 1;
localparam N_OUT = 6;
localparam OUT_BITS = 13;

`include "vector_player.vh"

reg i_rx = 1'b1;
wire [7:0] o_data;
wire o_valid;
wire o_frame_err;
wire o_start_err;
wire o_busy;
wire o_parity_err;

// Port order = the model's uart::Receiver::input_ports() / output_ports(), then o_parity_err (uart::Bench).
task apply_inputs;
    begin
        i_rx = `IN_WORD(0) & 1'b1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_data,
    o_valid,
    o_frame_err,
    o_start_err,
    o_busy,
    o_parity_err
};

task check_outputs;
    begin
        `CHECK(0, "o_data", o_data)
        `CHECK(1, "o_valid", o_valid)
        `CHECK(2, "o_frame_err", o_frame_err)
        `CHECK(3, "o_start_err", o_start_err)
        `CHECK(4, "o_busy", o_busy)
        `CHECK(5, "o_parity_err", o_parity_err)
    end
endtask

uart_rx #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .PARITY(PARITY)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_rx(i_rx),
    .o_data(o_data),
    .o_valid(o_valid),
    .o_frame_err(o_frame_err),
    .o_start_err(o_start_err),
    .o_busy(o_busy),
    .o_parity_err(o_parity_err)
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
