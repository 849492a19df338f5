// half_duplex_rx: the answer receiver of a half-duplex host (ESL, T-format, SAR58K24, Modbus): uart_rx, deaf while the host drives the line; model::half_duplex::Link's rx.
//
// What it is for
//   A host on a two-wire RS-485 line hears its own request through its
//   receiver. Feeding the receiver a high line while the host's driver is on
//   keeps the request out of the answer, with no character to discard
//   afterwards and no race at the turnaround. Connect i_tx_en to the host's
//   registered driver enable (the o_tx_en it drives) and i_rx to the RS-485
//   receiver output (RO); the outputs are uart_rx's registers, read by the
//   host as they stand before each edge.
//
// Parameters
//   CLOCKS_PER_BIT  i_clk cycles per bit (uart_rx: 6..65535)
//   PARITY          0 none (ESL, T-format: 10-bit frames, o_parity_err stays
//                   0), 1 odd, 2 even (SAR58K24, Modbus)
//
// Timing
//
//   i_tx_en   _/‾‾‾ request ‾‾‾\______________________________________
//   i_rx      ‾\_ own request _/‾‾‾‾‾‾‾‾‾\_ answer characters _/‾‾‾‾‾‾
//   heard     ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_ answer characters _/‾‾‾‾‾‾
//   o_busy    ____________________________/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\______
//
// A glitch shorter than half a bit (uart_rx's o_start_err) is neither a
// character nor an answer to any of these hosts: it is not passed on.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module half_duplex_rx #(
    parameter CLOCKS_PER_BIT = 8,
    parameter PARITY = 0
) (
    input  wire       i_clk,
    input  wire       i_rst,

    /* RS-485 line */
    input  wire       i_tx_en,
    input  wire       i_rx,

    /* Received characters (one-cycle pulses) */
    output wire [7:0] o_data,
    output wire       o_valid,
    output wire       o_frame_err,
    output wire       o_parity_err,
    output wire       o_busy
);

/* verilator lint_off UNUSEDSIGNAL */
wire start_err;
/* verilator lint_on UNUSEDSIGNAL */

uart_rx #(.CLOCKS_PER_BIT(CLOCKS_PER_BIT), .PARITY(PARITY)) rx_inst (
    .i_clk(i_clk), .i_rst(i_rst), .i_rx(i_rx | i_tx_en),
    .o_data(o_data), .o_valid(o_valid), .o_frame_err(o_frame_err), .o_start_err(start_err),
    .o_busy(o_busy), .o_parity_err(o_parity_err)
);

endmodule

`resetall
