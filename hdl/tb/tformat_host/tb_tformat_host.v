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

localparam N_IN = 5;
localparam N_OUT = 17;
localparam OUT_BITS = 90;

`include "vector_player.vh"

reg i_start = 1'b0;
reg [3:0] i_data_id = 4'd0;
reg [6:0] i_address = 7'd0;
reg [7:0] i_wdata = 8'd0;
reg i_rx = 1'b1;
wire o_tx, o_tx_en, o_busy, o_done;
wire [7:0] o_cf, o_sf, o_enid, o_almc, o_adf, o_edf;
wire [16:0] o_abs;
wire [15:0] o_abm;
wire o_err_crc, o_err_timeout, o_err_frame, o_err_cf, o_err_comm;

// Port order = the model's tformat::Host::input_ports() / output_ports().
task apply_inputs;
    begin
        i_start = `IN_WORD(0) & 1'b1;
        i_data_id = `IN_WORD(1) & 4'hF;
        i_address = `IN_WORD(2) & 7'h7F;
        i_wdata = `IN_WORD(3) & 8'hFF;
        i_rx = `IN_WORD(4) & 1'b1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_tx,
    o_tx_en,
    o_busy,
    o_done,
    o_cf,
    o_sf,
    o_abs,
    o_abm,
    o_enid,
    o_almc,
    o_adf,
    o_edf,
    o_err_crc,
    o_err_timeout,
    o_err_frame,
    o_err_cf,
    o_err_comm
};

task check_outputs;
    begin
        `CHECK(0, "o_tx", o_tx)
        `CHECK(1, "o_tx_en", o_tx_en)
        `CHECK(2, "o_busy", o_busy)
        `CHECK(3, "o_done", o_done)
        `CHECK(4, "o_cf", o_cf)
        `CHECK(5, "o_sf", o_sf)
        `CHECK(6, "o_abs", o_abs)
        `CHECK(7, "o_abm", o_abm)
        `CHECK(8, "o_enid", o_enid)
        `CHECK(9, "o_almc", o_almc)
        `CHECK(10, "o_adf", o_adf)
        `CHECK(11, "o_edf", o_edf)
        `CHECK(12, "o_err_crc", o_err_crc)
        `CHECK(13, "o_err_timeout", o_err_timeout)
        `CHECK(14, "o_err_frame", o_err_frame)
        `CHECK(15, "o_err_cf", o_err_cf)
        `CHECK(16, "o_err_comm", o_err_comm)
    end
endtask

tformat_host #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .REPEAT_GAP_CLOCKS(REPEAT_GAP_CLOCKS)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .i_data_id(i_data_id),
    .i_address(i_address),
    .i_wdata(i_wdata),
    .o_busy(o_busy),
    .o_done(o_done),
    .o_cf(o_cf),
    .o_sf(o_sf),
    .o_abs(o_abs),
    .o_abm(o_abm),
    .o_enid(o_enid),
    .o_almc(o_almc),
    .o_adf(o_adf),
    .o_edf(o_edf),
    .o_err_crc(o_err_crc),
    .o_err_timeout(o_err_timeout),
    .o_err_frame(o_err_frame),
    .o_err_cf(o_err_cf),
    .o_err_comm(o_err_comm),
    .o_tx(o_tx),
    .o_tx_en(o_tx_en),
    .i_rx(i_rx)
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
