// biss_slave_emu: a chain of one to three BiSS-C slaves and its cable for any
// testbench, emulated by the encoder-tb model (libcosim, cosim/src/biss.rs);
// the same module name and ports in Verilator (DPI-C) and Icarus (VPI module
// emu.vpi).
//
// Connect the master's MA to i_ma and o_slo to the master's SLO input; clock
// the emulator with i_emu_clk at F_EMU_HZ (at least 4 x the fastest MA: 40 MHz
// for the seed's 10 MHz, less with `emulator.max_line_clock_khz`). Each rising
// edge of i_emu_clk samples i_ma, steps the cable and the chain once and
// registers SLO as it arrives at the master's end of the cable:
//
//   master pin -> [1 emu cycle: this sample] -> cable (length_m x ns_per_m)
//     -> slaves (output_delay_ns of the first) -> cable -> [register] -> o_slo
//
// The configuration is a TOML file with the scenario's [[slaves]], [cable],
// [[flips]], [stuck] and [delay_step] tables (a whole scenario file will do):
// the parameter CONFIG, or, when CONFIG is "", the plusarg +<PLUSARG>=<file>.
// A missing or bad file stops the simulation at time 0 with file, field, fix.
//
// X or Z on i_ma before its first 0/1 (reset) is ignored (MA is taken as idle
// high); after it, it is reported with time and pin and never read as data
// (STOP_ON_X = 1 stops the run, 0 holds the last level).
//
// Controls for the testbench (hierarchical calls, see emu_api.vh):
//   u_emu.set_position(slave, value); u_emu.set_status(slave, "error", 1);
//   u_emu.set_status(slave, "warning", 0); u_emu.schedule_fault("flips = [{ frame = 7, bits = [0] }]");
//   u_emu.count(0) (frames latched), u_emu.last_value(slave), u_emu.last_status(slave, "error")
// TRANSCRIPT names a JSON file written at the end of the simulation.
//
// The emulator also checks the master: every timing rule of the seed it
// breaks (limits in the TOML's [checks] table) is printed as
// "PROTOCOL VIOLATION by the master on ... at <ns> (emulator cycle N): <rule>: <measured>"
// and counted (u_emu.violations(0)); STOP_ON_VIOLATION = 1 stops the run.
// The rules are the rule book of docs/rules.md, the monitor's too. The
// emulator expects i_ma idle high before the first frame: until it has seen
// it high (a master holding reset with it at 0 from time 0), the device sees
// it idle and nothing is checked.

`default_nettype none

module biss_slave_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "biss_emu_config",
    parameter F_EMU_HZ = 80000000,
    parameter TRANSCRIPT = "",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Emulator clock */
    input  wire i_emu_clk,

    /* BiSS-C line at the master's end of the cable */
    input  wire i_ma,
    output wire o_slo
);

`include "emu_api.vh"

localparam EMU_KIND = "biss";
localparam EMU_PIN = "i_ma";
wire emu_line_in = i_ma;

`include "emu_clocked.vh"

assign o_slo = emu_line_out;

endmodule

`default_nettype wire
