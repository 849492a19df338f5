// can_controller_synth: can_controller behind an 8-bit register bus, for synthesis only.
//
// What it is for
//   can_controller has 271 parallel ports (a 64-bit transmit buffer, a
//   64-bit received frame, two 29-bit filter words...), more than the iCE40
//   HX8K ct256 package's user I/O, so nextpnr cannot place it alone. This
//   wrapper puts every wide port behind a byte-wide register bus, as a CPU
//   would see the controller, so that `make synth` places and routes the
//   core with its real logic (nothing is left unconnected, so yosys keeps
//   all of it) and reports its logic cells and Fmax. 26 pins. It is not
//   replayed against vectors: the core it wraps is.
//
// Registers (i_addr, byte-wide; writes with i_we, reads combinational on o_rdata)
//   0x00..0x07  W  transmit data bytes 0..7 (byte 0 sent first)
//   0x08        W  transmit id[7:0]
//   0x09        W  {rtr, dlc[3:0], id[10:8]}
//   0x0A        W  any write: i_tx_start for one cycle
//   0x0B..0x0E  W  filter id bytes 0..3 (29 bits, little-endian)
//   0x0F..0x12  W  filter mask bytes 0..3
//   0x13        W  clears the sticky event bits set in i_wdata
//   0x00..0x07  R  received data bytes 0..7
//   0x08..0x0B  R  received id bytes 0..3 (29 bits, little-endian)
//   0x0C        R  {rx_ide, rx_rtr, 2'b00, rx_dlc}
//   0x0D        R  tec[7:0]
//   0x0E        R  {tx_busy, err_state[1:0], 4'b0000, tec[8]}
//   0x0F        R  rec
//   0x10        R  sticky events {overload, err_ack, err_form, err_crc,
//                  err_stuff, err_bit, arb_lost|tx_done, rx_valid}: each
//                  one-cycle pulse of the core sets its bit (cleared by 0x13)
//   o_irq          any sticky event bit set

`resetall
`timescale 1ns / 1ps
`default_nettype none

module can_controller_synth #(
    parameter BRP = 2,
    parameter PROP_SEG = 8,
    parameter PHASE_SEG1 = 7,
    parameter PHASE_SEG2 = 4,
    parameter SJW = 1,
    parameter SYNC_STAGES = 2
) (
    input  wire       i_clk,
    input  wire       i_rst,
    input  wire       i_we,
    input  wire [4:0] i_addr,
    input  wire [7:0] i_wdata,
    output reg  [7:0] o_rdata,
    output wire       o_irq,
    output wire       o_can_tx,
    input  wire       i_can_rx
);

reg  [63:0] tx_data_reg = 64'd0;
reg  [10:0] tx_id_reg = 11'd0;
reg         tx_rtr_reg = 1'b0;
reg  [3:0]  tx_dlc_reg = 4'd0;
reg         tx_start_reg = 1'b0;
reg  [28:0] filter_id_reg = 29'd0;
reg  [28:0] filter_mask_reg = 29'd0;
reg  [7:0]  events_reg = 8'd0;

wire        tx_busy, tx_done, arb_lost, rx_valid, rx_ide, rx_rtr;
wire [28:0] rx_id;
wire [3:0]  rx_dlc;
wire [63:0] rx_data;
wire [8:0]  tec;
wire [7:0]  rec;
wire [1:0]  err_state;
wire        err_bit, err_stuff, err_crc, err_form, err_ack, overload;

can_controller #(
    .BRP(BRP),
    .PROP_SEG(PROP_SEG),
    .PHASE_SEG1(PHASE_SEG1),
    .PHASE_SEG2(PHASE_SEG2),
    .SJW(SJW),
    .SYNC_STAGES(SYNC_STAGES)
) core (
    .i_clk(i_clk),
    .i_rst(i_rst),
    .i_tx_start(tx_start_reg),
    .i_tx_id(tx_id_reg),
    .i_tx_rtr(tx_rtr_reg),
    .i_tx_dlc(tx_dlc_reg),
    .i_tx_data(tx_data_reg),
    .o_tx_busy(tx_busy),
    .o_tx_done(tx_done),
    .o_arb_lost(arb_lost),
    .i_filter_id(filter_id_reg),
    .i_filter_mask(filter_mask_reg),
    .o_rx_valid(rx_valid),
    .o_rx_id(rx_id),
    .o_rx_ide(rx_ide),
    .o_rx_rtr(rx_rtr),
    .o_rx_dlc(rx_dlc),
    .o_rx_data(rx_data),
    .o_tec(tec),
    .o_rec(rec),
    .o_err_state(err_state),
    .o_err_bit(err_bit),
    .o_err_stuff(err_stuff),
    .o_err_crc(err_crc),
    .o_err_form(err_form),
    .o_err_ack(err_ack),
    .o_overload(overload),
    .o_can_tx(o_can_tx),
    .i_can_rx(i_can_rx)
);

wire [7:0] pulses = {overload, err_ack, err_form, err_crc, err_stuff, err_bit, arb_lost | tx_done, rx_valid};
wire [31:0] rx_id_32 = {3'b000, rx_id};
assign o_irq = |events_reg;

always @* begin
    case (i_addr)
        5'h00: o_rdata = rx_data[63:56];
        5'h01: o_rdata = rx_data[55:48];
        5'h02: o_rdata = rx_data[47:40];
        5'h03: o_rdata = rx_data[39:32];
        5'h04: o_rdata = rx_data[31:24];
        5'h05: o_rdata = rx_data[23:16];
        5'h06: o_rdata = rx_data[15:8];
        5'h07: o_rdata = rx_data[7:0];
        5'h08: o_rdata = rx_id_32[7:0];
        5'h09: o_rdata = rx_id_32[15:8];
        5'h0A: o_rdata = rx_id_32[23:16];
        5'h0B: o_rdata = rx_id_32[31:24];
        5'h0C: o_rdata = {rx_ide, rx_rtr, 2'b00, rx_dlc};
        5'h0D: o_rdata = tec[7:0];
        5'h0E: o_rdata = {tx_busy, err_state, 4'b0000, tec[8]};
        5'h0F: o_rdata = rec;
        5'h10: o_rdata = events_reg;
        default: o_rdata = 8'h00;
    endcase
end

always @(posedge i_clk) begin
    tx_start_reg <= 1'b0;
    events_reg <= events_reg | pulses;
    if (i_we) begin
        case (i_addr)
            5'h00: tx_data_reg[63:56] <= i_wdata;
            5'h01: tx_data_reg[55:48] <= i_wdata;
            5'h02: tx_data_reg[47:40] <= i_wdata;
            5'h03: tx_data_reg[39:32] <= i_wdata;
            5'h04: tx_data_reg[31:24] <= i_wdata;
            5'h05: tx_data_reg[23:16] <= i_wdata;
            5'h06: tx_data_reg[15:8] <= i_wdata;
            5'h07: tx_data_reg[7:0] <= i_wdata;
            5'h08: tx_id_reg[7:0] <= i_wdata;
            5'h09: {tx_rtr_reg, tx_dlc_reg, tx_id_reg[10:8]} <= i_wdata;
            5'h0A: tx_start_reg <= 1'b1;
            5'h0B: filter_id_reg[7:0] <= i_wdata;
            5'h0C: filter_id_reg[15:8] <= i_wdata;
            5'h0D: filter_id_reg[23:16] <= i_wdata;
            5'h0E: filter_id_reg[28:24] <= i_wdata[4:0];
            5'h0F: filter_mask_reg[7:0] <= i_wdata;
            5'h10: filter_mask_reg[15:8] <= i_wdata;
            5'h11: filter_mask_reg[23:16] <= i_wdata;
            5'h12: filter_mask_reg[28:24] <= i_wdata[4:0];
            5'h13: events_reg <= (events_reg & ~i_wdata) | pulses;
            default: ;
        endcase
    end
    if (i_rst) begin
        tx_start_reg <= 1'b0;
        events_reg <= 8'd0;
    end
end

endmodule

`resetall
