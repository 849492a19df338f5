// tb_can_controller: replays golden vectors from the Rust model against can_controller.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_can_controller;

/* Core parameters: set per vector file from its `params:` header line */
parameter BRP = 10;
parameter PROP_SEG = 5;
parameter PHASE_SEG1 = 8;
parameter PHASE_SEG2 = 2;
parameter SJW = 1;
parameter SYNC_STAGES = 2;

/* Harness parameters */
parameter HALF_PERIOD_FS = 12_500_000;
parameter MAX_WORDS = 1 << 22;

`include "tb_can_controller_ports.vh"

can_controller #(
    .BRP(BRP),
    .PROP_SEG(PROP_SEG),
    .PHASE_SEG1(PHASE_SEG1),
    .PHASE_SEG2(PHASE_SEG2),
    .SJW(SJW),
    .SYNC_STAGES(SYNC_STAGES)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (can::Out::default: TX
// recessive, every other output 0, error active) at each falling edge of the
// reset, so a wrong reset value of an output register that the first cycle
// would overwrite (o_err_state, a pulse such as o_err_bit) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_can_tx, o_tx_busy, o_tx_done, o_arb_lost, o_rx_valid, o_rx_ide, o_rx_rtr, o_err_bit,
                 o_err_stuff, o_err_crc, o_err_form, o_err_ack, o_overload} !== 13'b1000000000000
                || o_rx_id !== 29'd0 || o_rx_dlc !== 4'd0 || o_rx_data !== 64'd0 || o_tec !== 9'd0
                || o_rec !== 8'd0 || o_err_state !== 2'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "can_controller: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
