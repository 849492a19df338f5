// tb_endat_master: replays golden vectors from the Rust model against endat_master.
//
// The bidirectional data line is modelled at the master's pins: o_endat_data_out and
// o_endat_data_oe are compared with the model's, and i_endat_data_in is the level the
// model's HalfDuplexLine delivered to the master's receiver (its own driver included).

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_endat_master;

/* Core parameters: set per vector file from its `params:` header line */
parameter POS_BITS = 25;
parameter CLOCKS_PER_BIT = 64;
parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2;
parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2;
parameter MEAS_CLOCKS_PER_BIT = 320;
parameter MEAS_HIGH_CLOCKS = MEAS_CLOCKS_PER_BIT - MEAS_CLOCKS_PER_BIT / 2;
parameter MEAS_LOW_CLOCKS = MEAS_CLOCKS_PER_BIT / 2;
parameter T_ST_CLOCKS = 32;
parameter DELAY_COMP = 0;
parameter SAMPLE_DELAY = 0;
parameter MEAS_COUNT = 4;
parameter MEAS_RETRIES = 3;
parameter DELAY_TOL = 8;
parameter DELAY_MAX = 1020;
parameter TIMEOUT_CLOCKS = 50;
parameter T_M_CLOCKS = 1952;
parameter T_B_CLOCKS = 64640;
parameter T_ERR_CLOCKS = 1952;
parameter BLOCK_GAP = 16;

/* Harness parameters */
parameter HALF_PERIOD_FS = 7_812_500;
parameter MAX_WORDS = 1 << 22;

`include "tb_endat_master_ports.vh"

endat_master #(
    .POS_BITS(POS_BITS),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .HIGH_CLOCKS(HIGH_CLOCKS),
    .LOW_CLOCKS(LOW_CLOCKS),
    .MEAS_CLOCKS_PER_BIT(MEAS_CLOCKS_PER_BIT),
    .MEAS_HIGH_CLOCKS(MEAS_HIGH_CLOCKS),
    .MEAS_LOW_CLOCKS(MEAS_LOW_CLOCKS),
    .T_ST_CLOCKS(T_ST_CLOCKS),
    .DELAY_COMP(DELAY_COMP),
    .SAMPLE_DELAY(SAMPLE_DELAY),
    .MEAS_COUNT(MEAS_COUNT),
    .MEAS_RETRIES(MEAS_RETRIES),
    .DELAY_TOL(DELAY_TOL),
    .DELAY_MAX(DELAY_MAX),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .T_M_CLOCKS(T_M_CLOCKS),
    .T_B_CLOCKS(T_B_CLOCKS),
    .T_ERR_CLOCKS(T_ERR_CLOCKS),
    .BLOCK_GAP(BLOCK_GAP)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (endat::master::Master::new:
// clock high, o_f2 high, o_busy = DELAY_COMP, o_delay = 2 + SAMPLE_DELAY,
// every other output 0) at each falling edge of the reset, so a wrong reset
// value of an output register that the first cycle would overwrite (a pulse,
// a line level) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_endat_clk, o_endat_data_out, o_endat_data_oe, o_done, o_f1, o_f2, o_err_crc, o_ad1_valid, o_err_ad1_crc,
                 o_ad2_valid, o_err_ad2_crc, o_err_type2, o_err_type3, o_err_type4, o_err_ack, o_err_timeout,
                 o_err_absent, o_err_idle, o_err_delay, o_meas_done, o_err_meas, o_delay_valid} !== 22'b1000010000000000000000
                || o_busy !== (DELAY_COMP != 0) || o_delay !== 2 + SAMPLE_DELAY
                || o_position !== 48'd0 || o_ad1 !== 24'd0 || o_ad2 !== 24'd0 || o_ack_addr !== 8'd0 || o_ack_data !== 16'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "endat_master: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
