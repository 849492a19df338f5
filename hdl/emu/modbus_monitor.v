// modbus_monitor: a pin-level monitor and protocol checker of a Modbus RTU
// master (seed 001, 3.1.7, the SAR58K24's seventh mode), input-only, run by
// the encoder-tb library (cosim/src/monitor/modbus.rs); the same module
// name and ports in both simulators (DPI-C in Verilator, the VPI module
// emu.vpi in Icarus), beside or without a modbus_device_emu.
//
// Connect the master's half-duplex RS-485 transceiver as the master drives
// it: its driver input D (i_line), its driver enable DE (i_line_en) and the
// receiver's output R (i_rx: the line as the master hears it; with
// modbus_device_emu, its o_bus). Clock the monitor with i_mon_clk at
// F_MON_HZ (at least 8 x the baud rate; any ratio). Each rising edge of
// i_mon_clk samples the three pins. The monitor decodes every poll with the
// decoder of `tbgen decode modbus` (model/src/modbus/decode.rs) and holds
// the master to the timing: character timing and parity of its requests
// (baud rate tolerance), at most t1.5 of silence inside a request, t3.5 of
// silence before it, DE released after the request and never on during an
// answer, and the response timeout before the next request. Each violation
// is printed with its time and rule and counted (u_mon.violations(0));
// STOP_ON_VIOLATION = 1 stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; the
// emulator's own file or a whole scenario will do): the [modbus] table's
// baud, parity, [[devices]] gray, [master] timeout_us, and [monitor]
// timeout_us, baud_tolerance_percent, release_bits.
//
// Queries: u_mon.count(0) (polls seen, the one in progress included),
// u_mon.last_value(0) (the registers of the last poll), u_mon.last_status(0,
// "valid" | "parity" | "framing" | "gap" | "length" | "crc" | "address" |
// "exception" | "function" | "count" | "timeout"). At the end of the
// simulation the transcript (every poll as `tbgen decode modbus` prints it,
// and every violation) goes to TRANSCRIPT, or to the file of
// +<TRANSCRIPT_PLUSARG>=<file>.

`ifndef MODBUS_MONITOR_V
`define MODBUS_MONITOR_V
`default_nettype none

module modbus_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "modbus_monitor_config",
    parameter F_MON_HZ = 10000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "modbus_monitor_transcript",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Monitor clock */
    input wire i_mon_clk,

    /* The master's transceiver: D, DE, R */
    input wire i_line,
    input wire i_line_en,
    input wire i_rx
);

`include "emu_api.vh"

localparam EMU_KIND = "modbus_monitor";
localparam MON_PIN_NAMES = "i_rx, i_line, i_line_en";
localparam [7:0] MON_IDLE = 8'b0000_0011;
wire [7:0] mon_pins_now = {5'd0, i_line_en, i_line, i_rx};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
