// esl_encoder_emu: QS35 ESL encoders (one, or a daisy chain on one bus) and
// their cable for any testbench, emulated by the encoder-tb model (libcosim,
// cosim/src/esl.rs); the same module name and ports in Verilator (DPI-C) and
// Icarus (VPI module emu.vpi).
//
// Connect the host's transmitter and its driver enable (the RS-485
// transceiver's DI and DE) to i_esl_data and i_esl_data_oe, and o_esl_data to
// its receiver output (RO). No tristate: the emulator resolves the
// half-duplex pair itself; o_esl_data is the encoders' level at the host's
// end of the cable, the fail-safe idle high while no encoder drives, and
// o_esl_data_oe their driver enable there. ESL has no clock line: the body
// is emu_pair.vh (shared with EnDat and T-format) with the clock input tied
// high. Clock the emulator with i_emu_clk at F_EMU_HZ, at least 4 x the bit
// rate (40 MHz at the seed's 10 Mbps); the encoders sample the request at
// F_EMU_HZ / baud cycles per bit (8 at 80 MHz).
//
//   host pins -> [1 emu cycle: this sample] -> pair (length_m x ns_per_m)
//     -> encoders (answer_delay_us) -> pair -> [register] -> o_esl_data
//
// The configuration is a TOML file with the scenario's [esl] device tables
// ([[encoders]], [cable], baud, broadcast_address, [checks]; a whole
// scenario file will do): CONFIG, or with CONFIG = "" the plusarg
// +<PLUSARG>=<file>. A missing or bad file, or an emulator clock too slow,
// stops the run at time 0 with the file, the field (or the minimum) and the
// fix.
//
// Controls (emu_api.vh), device = the encoder's place in [[encoders]]:
// set_position(d, multi_turn << 24 | single_turn), set_motion(d, "[motion]..."),
// set_status(d, name, v) for the ALM flags xc, mt, led, lis, overspeed, mem,
// st, uv, ov and temp_warning (DD0), each independently (EA0/EA1 follow),
// schedule_fault("device = 0\nflips = [{ answer = 7, field = 3, bit = 2 }]")
// (also truncations, sequence_jumps, foreign_address_answers, rs_offset),
// count(0) (answers sent by all encoders), last_value(d), last_status(d,
// name) (also ea0, ea1, ready), violations(0): the host's turnaround,
// character timing and request spacing (cosim/src/esl.rs).
// X or Z on an input after its first 0/1 is reported with time and pin.

`default_nettype none

module esl_encoder_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "esl_emu_config",
    parameter F_EMU_HZ = 80000000,
    parameter TRANSCRIPT = "",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Emulator clock */
    input  wire i_emu_clk,

    /* The pair at the host's end of the cable */
    input  wire i_esl_data,
    input  wire i_esl_data_oe,
    output wire o_esl_data,
    output wire o_esl_data_oe
);

`include "emu_api.vh"

localparam EMU_KIND = "esl";
localparam [8*24:1] EMU_PIN0 = "(none)";
localparam [8*24:1] EMU_PIN1 = "i_esl_data";
localparam [8*24:1] EMU_PIN2 = "i_esl_data_oe";
wire emu_clk_in = 1'b1;
wire emu_data_in = i_esl_data;
wire emu_oe_in = i_esl_data_oe;

`include "emu_pair.vh"

assign o_esl_data = emu_data_out;
assign o_esl_data_oe = emu_oe_out;

endmodule

`default_nettype wire
