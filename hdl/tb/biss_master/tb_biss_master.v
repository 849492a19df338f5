// tb_biss_master: replays golden vectors from the Rust model against biss_master.

`timescale 1fs / 1fs
`default_nettype none

// Coverage (make coverage, make test) counts the core in hdl/rtl, never this
// testbench: instrumenting the replay loop made a replay about 5x slower.
/* verilator coverage_off */
module tb_biss_master;

/* Core parameters: set per vector file from its `params:` header line */
parameter SLAVES = 1;
parameter SLAVE_BITS = 16;
parameter SLAVE_CRC_WIDTH = 6;
parameter SLAVE_CRC_POLY = 3;
parameter CLOCKS_PER_BIT = 8;
parameter HIGH_CLOCKS = CLOCKS_PER_BIT - CLOCKS_PER_BIT / 2;
parameter LOW_CLOCKS = CLOCKS_PER_BIT / 2;
parameter MAX_DELAY = 160;
parameter TIMEOUT_CLOCKS = 3200;
parameter CAL_FRAMES = 4;
parameter DELAY_TOL = 1;

/* Harness parameters */
parameter HALF_PERIOD_FS = 6_250_000;
parameter MAX_WORDS = 1 << 22;

function integer field8(input integer packed_values, input integer index);
    begin
        field8 = (packed_values >> (8 * index)) & 255;
    end
endfunction

function integer max_bits(input integer packed_values, input integer count);
    integer k;
    begin
        max_bits = 1;
        for (k = 0; k < count; k = k + 1)
            if (field8(packed_values, k) > max_bits) max_bits = field8(packed_values, k);
    end
endfunction

localparam integer DATA_W = max_bits(SLAVE_BITS, SLAVES);

`include "tb_biss_master_ports.vh"

biss_master #(
    .SLAVES(SLAVES),
    .SLAVE_BITS(SLAVE_BITS),
    .SLAVE_CRC_WIDTH(SLAVE_CRC_WIDTH),
    .SLAVE_CRC_POLY(SLAVE_CRC_POLY),
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .HIGH_CLOCKS(HIGH_CLOCKS),
    .LOW_CLOCKS(LOW_CLOCKS),
    .MAX_DELAY(MAX_DELAY),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .CAL_FRAMES(CAL_FRAMES),
    .DELAY_TOL(DELAY_TOL)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    `DUT_PORTS
);

// While reset is held the player compares nothing (vector_player.vh): here
// every output is held to the model's reset state (biss::Master::new: MA
// high, every other output 0) at each falling edge of the reset, so a wrong
// reset value of an output register that the first cycle would overwrite
// (a pulse such as o_done or o_err_timeout) is still caught.
always begin
    // Parked once reset is released: no cost per cycle after it.
    wait (rst);
    @(negedge clk);
    if (rst && ({o_ma, o_busy, o_done, o_err_line, o_err_ack, o_err_delay, o_err_start, o_err_timeout,
                 o_slave_valid, o_crc_err, o_error, o_warning, o_cds, o_reg_busy, o_reg_done, o_reg_err,
                 o_reg_crc_err, o_err_drift} !== 18'b100000000000000000
                || o_delay !== 16'd0 || o_slave_index !== 2'd0 || o_data !== 0 || o_reg_rdata !== 8'd0 || o_delay_mean !== 16'd0)) begin
        $display("MISMATCH in reset: outputs differ from the model's reset state");
        $fatal(1, "biss_master: an output is not at its reset value while i_rst is high");
    end
end

endmodule

`default_nettype wire
