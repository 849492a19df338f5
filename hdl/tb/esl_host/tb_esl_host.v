// tb_esl_host: replays golden vectors from the Rust model against esl_host.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_esl_host;

/* Core parameters: set per vector file from its `params:` header line */
parameter CLOCKS_PER_BIT = 8;
parameter TIMEOUT_CLOCKS = 400;
parameter REPEAT_GAP_CLOCKS = 3200;
parameter READ_WAIT_CLOCKS = 16000;
parameter WRITE_WAIT_CLOCKS = 480000;
parameter PAGE_WAIT_CLOCKS = 1440000;
parameter BUSY_TRIES = 3;
parameter RS_TOLERANCE = 1;
parameter BROADCAST_ADDRESS = 7;

/* Harness parameters */
parameter HALF_PERIOD_FS = 5_000_000;
parameter MAX_WORDS = 1 << 22;

`include "tb_esl_host_ports.vh"

esl_host #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .REPEAT_GAP_CLOCKS(REPEAT_GAP_CLOCKS),
    .READ_WAIT_CLOCKS(READ_WAIT_CLOCKS),
    .WRITE_WAIT_CLOCKS(WRITE_WAIT_CLOCKS),
    .PAGE_WAIT_CLOCKS(PAGE_WAIT_CLOCKS),
    .BUSY_TRIES(BUSY_TRIES),
    .RS_TOLERANCE(RS_TOLERANCE),
    .BROADCAST_ADDRESS(BROADCAST_ADDRESS)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (esl::host::Host::new: TX idle high, every other output 0) at each
// falling edge of the reset, so a wrong reset value of an output register
// that the first cycle would overwrite (a pulse, a line level) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_tx, o_tx_en, o_busy, o_done, o_err_crc1, o_err_crc2, o_err_timeout, o_err_frame, o_err_cf,
                 o_err_comm, o_err_seq, o_err_rs, o_err_busy} !== 13'b1000000000000
                || {o_cf, o_sf, o_sf2, o_alm1, o_alm2, o_abs, o_abm, o_rs, o_sc1, o_sc2, o_enid, o_temp, o_adf, o_edf} !== 143'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "esl_host: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
