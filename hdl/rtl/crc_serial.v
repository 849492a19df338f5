// crc_serial: one step of the bit-serial CRC LFSR every core uses (model::crc::BitSerial).
//
// Stage i of i_crc is the coefficient of x^i. Per bit d: fb = stage[WIDTH-1] ^ d,
// shift every stage up by one (stage 0 takes 0), then XOR POLY in if fb. The
// preset (INIT), reflection and output XOR of an algorithm belong to the user.
// Combinational: chain instances for several bits per cycle.
//
// Parameters
//   WIDTH  register width (EnDat: 5)
//   POLY   generator in normal notation without the x^WIDTH term (EnDat: 5'h0B)

`resetall
`timescale 1ns / 1ps
`default_nettype none

module crc_serial #(
    parameter WIDTH = 5,
    parameter [WIDTH-1:0] POLY = 5'h0B
) (
    input  wire [WIDTH-1:0] i_crc,
    input  wire             i_bit,
    output wire [WIDTH-1:0] o_crc
);

wire fb = i_crc[WIDTH-1] ^ i_bit;
assign o_crc = {i_crc[WIDTH-2:0], 1'b0} ^ (fb ? POLY : {WIDTH{1'b0}});

endmodule

`resetall
