// half_duplex_tx: the request sender of a half-duplex host that sends whole characters (SAR58K24 bus commands, Modbus RTU): uart_tx and the RS-485 driver enable.
//
// What it is for
//   Sends a request one character at a time, back to back, with the driver
//   enable on from before the first start bit to the end of the last stop
//   bit. The host turns the driver on (i_drive), offers each character
//   (i_valid with i_data) while o_ready is high, and turns the driver off
//   (i_release) at the first o_ready after the last one: the end of that
//   character's stop bit. Connect o_tx and o_tx_en to the RS-485 driver (DI,
//   DE) and o_tx_en to half_duplex_rx's i_tx_en.
//
// Parameters
//   CLOCKS_PER_BIT  i_clk cycles per bit (uart_tx: 2..1048576)
//   PARITY          0 none (10-bit characters), 1 odd, 2 even (11 bits)
//
// Timing (a request of two characters)
//
//   i_drive   _/‾\___________________________________________________
//   o_tx_en   ___/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\___
//   i_valid   _____/‾\____________________/‾\_______________________
//   o_tx      ‾‾‾‾‾‾‾‾‾\_ character 1 _/‾‾‾\_ character 2 _/‾‾‾‾‾‾‾
//   o_ready   ‾‾‾‾‾‾‾\_______________/‾‾‾‾\________________/‾‾‾‾‾‾
//   i_release _________________________________________________/‾\___
//
// o_ready is low from an offer until uart_tx has taken the character and
// sent its stop bit (pending_reg covers the cycle before uart_tx's o_busy
// rises), so the host never offers a character uart_tx would drop.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module half_duplex_tx #(
    parameter CLOCKS_PER_BIT = 10,
    parameter PARITY = 0
) (
    input  wire       i_clk,
    input  wire       i_rst,

    /* Request */
    input  wire       i_drive,
    input  wire       i_release,
    input  wire       i_valid,
    input  wire [7:0] i_data,
    output wire       o_ready,

    /* RS-485 line */
    output wire       o_tx,
    output wire       o_tx_en
);

reg       tx_en_reg = 1'b0;
reg       valid_reg = 1'b0;
reg [7:0] data_reg = 8'd0;
// An offered character uart_tx has not taken yet (its o_busy has not risen).
reg       pending_reg = 1'b0;
wire      tx_busy;

uart_tx #(.CLOCKS_PER_BIT(CLOCKS_PER_BIT), .PARITY(PARITY)) tx_inst (
    .i_clk(i_clk), .i_rst(i_rst), .i_valid(valid_reg), .i_data(data_reg),
    .o_tx(o_tx), .o_busy(tx_busy)
);

assign o_ready = !pending_reg && !tx_busy;
assign o_tx_en = tx_en_reg;

// One clocked block and no `always @*`: a simulator pays for every process
// it wakes.
always @(posedge i_clk) begin
    if (i_drive) tx_en_reg <= 1'b1;
    else if (i_release) tx_en_reg <= 1'b0;
    valid_reg <= i_valid;
    if (i_valid) begin
        data_reg <= i_data;
        pending_reg <= 1'b1;
    end else if (tx_busy) begin
        pending_reg <= 1'b0;
    end

    if (i_rst) begin
        tx_en_reg <= 1'b0;
        valid_reg <= 1'b0;
        data_reg <= 8'd0;
        pending_reg <= 1'b0;
    end
end

endmodule

`resetall
