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

localparam N_IN = 8;
localparam N_OUT = 19;
localparam OUT_BITS = 129;

`include "vector_player.vh"

reg i_tx_start = 1'b0;
reg [10:0] i_tx_id = 11'd0;
reg i_tx_rtr = 1'b0;
reg [3:0] i_tx_dlc = 4'd0;
reg [63:0] i_tx_data = 64'd0;
reg [28:0] i_filter_id = 29'd0;
reg [28:0] i_filter_mask = 29'd0;
reg i_can_rx = 1'b1;
wire o_can_tx, o_tx_busy, o_tx_done, o_arb_lost, o_rx_valid, o_rx_ide, o_rx_rtr;
wire [28:0] o_rx_id;
wire [3:0] o_rx_dlc;
wire [63:0] o_rx_data;
wire [8:0] o_tec;
wire [7:0] o_rec;
wire [1:0] o_err_state;
wire o_err_bit, o_err_stuff, o_err_crc, o_err_form, o_err_ack, o_overload;

// Port order = the model's can::Controller::input_ports() / output_ports().
task apply_inputs;
    begin
        i_tx_start = `IN_WORD(0) & 1'b1;
        i_tx_id = `IN_WORD(1) & 11'h7FF;
        i_tx_rtr = `IN_WORD(2) & 1'b1;
        i_tx_dlc = `IN_WORD(3) & 4'hF;
        i_tx_data = `IN_WORD(4);
        i_filter_id = `IN_WORD(5) & 29'h1FFF_FFFF;
        i_filter_mask = `IN_WORD(6) & 29'h1FFF_FFFF;
        i_can_rx = `IN_WORD(7) & 1'b1;
    end
endtask

// Every output in one vector, in check_outputs' order: the player runs
// check_outputs again only when this or the expected record changes.
wire [OUT_BITS-1:0] all_outputs = {
    o_can_tx,
    o_tx_busy,
    o_tx_done,
    o_arb_lost,
    o_rx_valid,
    o_rx_id,
    o_rx_ide,
    o_rx_rtr,
    o_rx_dlc,
    o_rx_data,
    o_tec,
    o_rec,
    o_err_state,
    o_err_bit,
    o_err_stuff,
    o_err_crc,
    o_err_form,
    o_err_ack,
    o_overload
};

task check_outputs;
    begin
        `CHECK(0, "o_can_tx", o_can_tx)
        `CHECK(1, "o_tx_busy", o_tx_busy)
        `CHECK(2, "o_tx_done", o_tx_done)
        `CHECK(3, "o_arb_lost", o_arb_lost)
        `CHECK(4, "o_rx_valid", o_rx_valid)
        `CHECK(5, "o_rx_id", o_rx_id)
        `CHECK(6, "o_rx_ide", o_rx_ide)
        `CHECK(7, "o_rx_rtr", o_rx_rtr)
        `CHECK(8, "o_rx_dlc", o_rx_dlc)
        `CHECK(9, "o_rx_data", o_rx_data)
        `CHECK(10, "o_tec", o_tec)
        `CHECK(11, "o_rec", o_rec)
        `CHECK(12, "o_err_state", o_err_state)
        `CHECK(13, "o_err_bit", o_err_bit)
        `CHECK(14, "o_err_stuff", o_err_stuff)
        `CHECK(15, "o_err_crc", o_err_crc)
        `CHECK(16, "o_err_form", o_err_form)
        `CHECK(17, "o_err_ack", o_err_ack)
        `CHECK(18, "o_overload", o_overload)
    end
endtask

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
    .i_tx_start(i_tx_start),
    .i_tx_id(i_tx_id),
    .i_tx_rtr(i_tx_rtr),
    .i_tx_dlc(i_tx_dlc),
    .i_tx_data(i_tx_data),
    .o_tx_busy(o_tx_busy),
    .o_tx_done(o_tx_done),
    .o_arb_lost(o_arb_lost),
    .i_filter_id(i_filter_id),
    .i_filter_mask(i_filter_mask),
    .o_rx_valid(o_rx_valid),
    .o_rx_id(o_rx_id),
    .o_rx_ide(o_rx_ide),
    .o_rx_rtr(o_rx_rtr),
    .o_rx_dlc(o_rx_dlc),
    .o_rx_data(o_rx_data),
    .o_tec(o_tec),
    .o_rec(o_rec),
    .o_err_state(o_err_state),
    .o_err_bit(o_err_bit),
    .o_err_stuff(o_err_stuff),
    .o_err_crc(o_err_crc),
    .o_err_form(o_err_form),
    .o_err_ack(o_err_ack),
    .o_overload(o_overload),
    .o_can_tx(o_can_tx),
    .i_can_rx(i_can_rx)
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
