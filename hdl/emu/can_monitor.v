// can_monitor: a pin-level monitor and protocol checker of a CAN master,
// input-only, run by the encoder-tb library (cosim/src/monitor/can.rs); the
// same module name and ports in Verilator (DPI-C) and Icarus (VPI module
// emu.vpi), beside or without a can_node_emu.
//
// Connect the master's transceiver pins: TXD as the master drives it
// (i_can_tx) and RXD, the wired-AND bus level at its receiver (i_can_rx;
// with can_node_emu, its o_can_rx). Clock the monitor with i_mon_clk at
// F_MON_HZ (at least 4 x the bit rate; the master's own clock is best).
// Each rising edge of i_mon_clk samples both pins. The monitor reads every
// frame off RXD with the decoder of `tbgen decode can`
// (model/src/can/decode.rs), tells the master's own frames (TXD dominant at
// the SOF and equal to the bus through the CRC) from the others', and holds
// the master to the CAN rule book (model/src/can/rules.rs, docs/rules.md:
// the Bosch CAN Specification 2.0, which seed 003 names): stuffing of its
// frames, its CRC, CRC delimiter / ACK delimiter / EOF recessive (and its
// own ACK slot), 3 bits of intermission before its SOF (11 recessive bits),
// its edges on the configured bit rate within the tolerance, no dominant
// TXD longer than an error flag (6 bits). Each violation is printed with its
// time and rule and counted (u_mon.violations(0)); STOP_ON_VIOLATION = 1
// stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; a
// whole scenario file will do): [can] f_sys_mhz, timing = { bit_rate_kbps,
// tq_per_bit, sample_point, sjw }; [monitor] bit_tolerance_percent,
// max_dominant_bits.
//
// Queries: u_mon.count(0) (frames seen), u_mon.last_value(field) (0 data of
// the last frame, first byte in bits 63..56; 1 its identifier; 2 its DLC;
// 3 intact frames; 4 frames the master sent), u_mon.last_status(0, "rtr" |
// "ide" | "ack" | "error" | "master"). At the end of the simulation the
// transcript (every frame as `tbgen decode can` prints it, with `sender`,
// and every violation) goes to TRANSCRIPT, or to the file of
// +<TRANSCRIPT_PLUSARG>=<file>; `tbgen check can --expect FILE <transcript>`
// compares it.

`ifndef CAN_MONITOR_V
`define CAN_MONITOR_V
`default_nettype none

module can_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "can_monitor_config",
    parameter F_MON_HZ = 10000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "can_monitor_transcript",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Monitor clock */
    input wire i_mon_clk,

    /* The master's transceiver pins */
    input wire i_can_tx,
    input wire i_can_rx
);

`include "emu_api.vh"

localparam EMU_KIND = "can_monitor";
localparam MON_PIN_NAMES = "i_can_rx, i_can_tx";
localparam [7:0] MON_IDLE = 8'b0000_0011;
wire [7:0] mon_pins_now = {6'd0, i_can_tx, i_can_rx};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
