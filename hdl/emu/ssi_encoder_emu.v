// ssi_encoder_emu: an SSI encoder and its cable for any testbench, emulated by
// the encoder-tb model (libcosim, cosim/src/ssi.rs); the same module name and
// ports in Verilator (DPI-C) and Icarus (VPI module emu.vpi).
//
// Connect the master's SSI clock to i_ssi_clk and o_ssi_data to the master's
// data input; clock the emulator with i_emu_clk at F_EMU_HZ (any clock of the
// testbench, at least 4 x the fastest SSI clock: 1 MHz for the seed's
// 250 kHz, more with `emulator.max_line_clock_khz`). Each rising edge of
// i_emu_clk samples i_ssi_clk, steps the cable and the encoder once and
// registers the data the encoder's answer has at the master's end of the
// cable:
//
//   master pin -> [1 emu cycle: this sample] -> cable (length_m x ns_per_m)
//     -> encoder (output_delay_ns) -> cable -> [register] -> o_ssi_data
//
// The configuration is a TOML file with the scenario's [encoder], [cable] and
// [fault] tables (a whole scenario file will do): the parameter CONFIG, or,
// when CONFIG is "", the plusarg +<PLUSARG>=<file>. A missing or bad file
// stops the simulation at time 0 with the file, the field and the fix.
//
// X or Z on i_ssi_clk before its first 0/1 (reset) is ignored (the clock is
// taken as idle high); after it, it is reported with time and pin and never
// read as data (STOP_ON_X = 1 stops the run, 0 holds the last level).
//
// Controls for the testbench (hierarchical calls, see emu_api.vh):
//   u_emu.set_position(0, value); u_emu.schedule_fault("fault = { level = false, from_read = 3 }");
//   u_emu.count(0) (reads begun), u_emu.last_value(0) (position stored at the last read)
// TRANSCRIPT names a JSON file written at the end of the simulation.
//
// The emulator also checks the master: every timing rule of the seed it
// breaks (limits in the TOML's [checks] table) is printed as
// "PROTOCOL VIOLATION by the master on ... at <ns> (emulator cycle N): <rule>: <measured>"
// and counted (u_emu.violations(0)); STOP_ON_VIOLATION = 1 stops the run.
// The rules are the rule book of docs/rules.md, the monitor's too. The
// emulator expects i_ssi_clk idle high before the first read: until it has seen
// it high (a master holding reset with it at 0 from time 0), the device sees
// it idle and nothing is checked.

`default_nettype none

module ssi_encoder_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "ssi_emu_config",
    parameter F_EMU_HZ = 50000000,
    parameter TRANSCRIPT = "",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Emulator clock */
    input  wire i_emu_clk,

    /* SSI line at the master's end of the cable */
    input  wire i_ssi_clk,
    output wire o_ssi_data
);

`include "emu_api.vh"

localparam EMU_KIND = "ssi";
localparam EMU_PIN = "i_ssi_clk";
wire emu_line_in = i_ssi_clk;

`include "emu_clocked.vh"

assign o_ssi_data = emu_line_out;

endmodule

`default_nettype wire
