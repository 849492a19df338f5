// modbus_device_emu: one to three Modbus RTU devices (the SAR58K24 in its
// seventh mode, seed 001, 3.1.7) and their cable for any testbench, emulated
// by the encoder-tb model (libcosim, cosim/src/modbus.rs); the same module
// name and ports in Verilator (DPI-C) and Icarus (VPI module emu.vpi).
//
// Line-level ports, no tristate: the master's RS-485 driver (i_line level,
// i_line_en enable) in; the devices' driver at the master's end of the cable
// (o_line level, o_line_en enable) and the resolved line level there (o_bus:
// the master's own driver, else the devices', else high) out. Connect o_bus
// to the master's receiver. Clock the emulator with i_emu_clk at F_EMU_HZ (at
// least 921.6 kHz; in practice a clock dividing the baud rate within 0.5 %).
//
//   master pins -> [1 emu cycle: this sample] -> cable -> devices -> cable
//     -> [register] -> o_line, o_line_en, o_bus
//
// The configuration is a TOML file with the scenario's [modbus] table (baud,
// parity, [master] for t1.5/t3.5, [[devices]], [cable]; a whole scenario
// file will do) and the emulator's own [random] and [checks]: the parameter
// CONFIG or the plusarg +<PLUSARG>=<file>. A missing or bad file stops the
// simulation at time 0 with the file, the field and the fix.
//
// Controls (see emu_api.vh): u_emu.count(0) (requests device 0 saw),
// u_emu.last_value(i) (the value of device i's last function-03 answer),
// u_emu.last_status(i, "answered" | "discarded" | "exception"),
// u_emu.violations(0). Violations of the master (two drivers at once, a
// request the device discards) are printed with time and rule.

`default_nettype none

module modbus_device_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "modbus_emu_config",
    parameter F_EMU_HZ = 10000000,
    parameter TRANSCRIPT = "",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Emulator clock */
    input  wire i_emu_clk,

    /* Master side of the cable */
    input  wire i_line,
    input  wire i_line_en,
    output wire o_line,
    output wire o_line_en,
    output wire o_bus
);

`include "emu_api.vh"

localparam EMU_KIND = "modbus";
localparam EMU_PINS = "{i_line_en, i_line}";
localparam [3:0] EMU_IDLE = 4'b1011;
wire [3:0] emu_pins_in = {1'b1, i_line_en, i_line, 1'b1};

`include "emu_half_duplex.vh"

assign o_line = emu_out[0];
assign o_line_en = emu_out[1];
assign o_bus = emu_out[2];

endmodule

`default_nettype wire
