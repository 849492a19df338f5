// tformat_encoder_emu: a Tamagawa T-format encoder and its cable for any
// testbench, emulated by the encoder-tb model (libcosim, cosim/src/tformat.rs);
// the same module name and ports in Verilator (DPI-C) and Icarus (VPI module
// emu.vpi).
//
// Connect the host's transmitter and its driver enable (the transceiver's D
// and DE) to i_tf_data and i_tf_data_oe, and o_tf_data to its receiver input
// (R). No tristate: the emulator resolves the half-duplex pair itself;
// o_tf_data is the encoder's level at the host's end of the cable, the
// fail-safe idle high while the encoder does not drive, and o_tf_data_oe the
// encoder's driver enable there. Clock the emulator with i_emu_clk at
// F_EMU_HZ, a whole multiple of the bit rate (2.5 Mbps: 10, 20, 40, 80 MHz,
// at least 4 x the bit rate): the encoder samples the request at
// F_EMU_HZ / baud cycles per bit.
//
//   host pins -> [1 emu cycle: this sample] -> pair (length_m x ns_per_m)
//     -> encoder (answer_delay_us) -> pair -> [register] -> o_tf_data
//
// The configuration is a TOML file with the scenario's [tformat] device
// tables (encoder, cable, baud; a whole scenario file will do): CONFIG, or
// with CONFIG = "" the plusarg +<PLUSARG>=<file>. A missing or bad file, or
// an emulator clock too slow or no multiple of the bit rate, stops the run at
// time 0 with the file, the field and the fix.
//
// Controls (emu_api.vh): set_position(0, multi_turn << 17 | single_turn),
// set_motion(0, "[motion]..."), set_status(0, "<ALMC flag>", v) for
// over_speed, full_absolute, counting_error, counter_overflow,
// multi_turn_error, battery_error, battery_alarm (each independently),
// schedule_fault("flips = [{ answer = 7, field = 3, bit = 2 }]"), count(0)
// (answers sent), last_value(0), last_status(0, name), violations(0).
// X or Z on an input after its first 0/1 is reported with time and pin.

`default_nettype none

module tformat_encoder_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "tformat_emu_config",
    parameter F_EMU_HZ = 80000000,
    parameter TRANSCRIPT = "",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Emulator clock */
    input  wire i_emu_clk,

    /* The pair at the host's end of the cable */
    input  wire i_tf_data,
    input  wire i_tf_data_oe,
    output wire o_tf_data,
    output wire o_tf_data_oe
);

`include "emu_api.vh"

localparam EMU_KIND = "tformat";
localparam [8*24:1] EMU_PIN0 = "(none)";
localparam [8*24:1] EMU_PIN1 = "i_tf_data";
localparam [8*24:1] EMU_PIN2 = "i_tf_data_oe";
wire emu_clk_in = 1'b1;
wire emu_data_in = i_tf_data;
wire emu_oe_in = i_tf_data_oe;

`include "emu_pair.vh"

assign o_tf_data = emu_data_out;
assign o_tf_data_oe = emu_oe_out;

endmodule

`default_nettype wire
