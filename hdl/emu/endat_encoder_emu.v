// endat_encoder_emu: an EnDat 2.2 encoder and its cable for any testbench,
// emulated by the encoder-tb model (libcosim, cosim/src/endat.rs); the same
// module name and ports in Verilator (DPI-C) and Icarus (VPI module emu.vpi).
//
// Connect the master's clock output to i_endat_clk, its data driver's input
// and enable (the transceiver's D and DE) to i_endat_data and
// i_endat_data_oe, and o_endat_data to its receiver input (R). No tristate:
// the emulator resolves the half-duplex pair itself (cosim/src/endat.rs):
// o_endat_data is the encoder's level at the master's end of the cable, the
// fail-safe idle high while the encoder does not drive; o_endat_data_oe is
// the encoder's driver enable there (for a testbench that wants to see it).
// Clock the emulator with i_emu_clk at F_EMU_HZ, at least 4 x the fastest
// EnDat clock (32 MHz for the seed's 8 MHz; emulator.max_line_clock_khz in
// the TOML for another limit). Each rising edge of i_emu_clk samples the
// three inputs, steps the cable and the encoder once and registers the
// outputs:
//
//   master pins -> [1 emu cycle: this sample] -> clock pair / data pair (length_m x ns_per_m)
//     -> encoder (output_delay_ns) -> data pair -> [register] -> o_endat_data
//
// The configuration is a TOML file with the scenario's [endat] device
// tables (encoder, cable, faults, block_gap_clocks, positions, step, motion;
// a whole scenario file will do): CONFIG, or with CONFIG = "" the plusarg
// +<PLUSARG>=<file>. A missing or bad file stops the run at time 0 with the
// file, the field and the fix; so does an emulator clock too slow.
//
// Controls (emu_api.vh): set_position(0, p), set_motion(0, "[motion]..."),
// set_status(0, "f1" | "f2" | "warning" | "busy", v) (each independently;
// F2 comes from a separate detection unit), schedule_fault("[faults]..."),
// count(0), last_value(0), last_status(0, name), violations(0).
// X or Z on an input after its first 0/1 is reported with time and pin.

`default_nettype none

module endat_encoder_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "endat_emu_config",
    parameter F_EMU_HZ = 64000000,
    parameter TRANSCRIPT = "",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Emulator clock */
    input  wire i_emu_clk,

    /* EnDat lines at the master's end of the cable */
    input  wire i_endat_clk,
    input  wire i_endat_data,
    input  wire i_endat_data_oe,
    output wire o_endat_data,
    output wire o_endat_data_oe
);

`include "emu_api.vh"

localparam EMU_KIND = "endat";
localparam [8*24:1] EMU_PIN0 = "i_endat_clk";
localparam [8*24:1] EMU_PIN1 = "i_endat_data";
localparam [8*24:1] EMU_PIN2 = "i_endat_data_oe";
wire emu_clk_in = i_endat_clk;
wire emu_data_in = i_endat_data;
wire emu_oe_in = i_endat_data_oe;

`include "emu_pair.vh"

assign o_endat_data = emu_data_out;
assign o_endat_data_oe = emu_oe_out;

endmodule

`default_nettype wire
