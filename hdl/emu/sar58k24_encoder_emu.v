// sar58k24_encoder_emu: one to three SAR58K24 encoders (asynchronous serial
// modes of seed 001, 3.1.1 to 3.1.6) and their cable for any testbench,
// emulated by the encoder-tb model (libcosim, cosim/src/sar58k24.rs); the
// same module name and ports in Verilator (DPI-C) and Icarus (VPI module
// emu.vpi).
//
// Line-level ports, no tristate: the host's RS-485 driver (i_line level,
// i_line_en enable; tie i_line_en low and i_line high in the modes without
// bus commands), the trigger (CLK, handshake modes) and CLR inputs (both idle
// high), and out the encoders' driver at the host's end of the cable
// (o_line level, o_line_en enable) and the resolved line level there
// (o_bus: the host's own driver, else the encoders', else high). Connect
// o_bus to the host's receiver. Clock the emulator with i_emu_clk at
// F_EMU_HZ (at least 921.6 kHz, 8 samples per bit at 115200 baud; in
// practice a clock dividing the baud rate within 0.5 %, such as 10 MHz).
//
//   host pins -> [1 emu cycle: this sample] -> cable (length_m x ns_per_m)
//     -> encoders -> cable -> [register] -> o_line, o_line_en, o_bus
//
// The configuration is a TOML file with the scenario's [sar] table (baud,
// parity, mode, [[encoders]], [cable]; a whole scenario file will do) and
// the emulator's own [random] (count, seed: random position lists) and
// [checks]: the parameter CONFIG, or, when CONFIG is "", the plusarg
// +<PLUSARG>=<file>. A missing or bad file stops the simulation at time 0
// with the file, the field and the fix.
//
// Controls (hierarchical calls, see emu_api.vh): u_emu.count(0) (frames sent
// by all encoders), u_emu.last_value(i) (the position encoder i last sent),
// u_emu.violations(0). TRANSCRIPT names a JSON file written at the end.
// Protocol violations of the host (two drivers on the line, a trigger pulse
// shorter than T2) are printed with time and rule; STOP_ON_VIOLATION = 1
// stops the run.

`default_nettype none

module sar58k24_encoder_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "sar58k24_emu_config",
    parameter F_EMU_HZ = 10000000,
    parameter TRANSCRIPT = "",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Emulator clock */
    input  wire i_emu_clk,

    /* Host side of the cable */
    input  wire i_line,
    input  wire i_line_en,
    input  wire i_trigger,
    input  wire i_clr,
    output wire o_line,
    output wire o_line_en,
    output wire o_bus
);

`include "emu_api.vh"

localparam EMU_KIND = "sar58k24";
localparam EMU_PINS = "{i_clr, i_line_en, i_line, i_trigger}";
localparam [3:0] EMU_IDLE = 4'b1011;
wire [3:0] emu_pins_in = {i_clr, i_line_en, i_line, i_trigger};

`include "emu_half_duplex.vh"

assign o_line = emu_out[0];
assign o_line_en = emu_out[1];
assign o_bus = emu_out[2];

endmodule

`default_nettype wire
