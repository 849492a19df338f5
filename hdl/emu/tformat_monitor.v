// tformat_monitor: a pin-level monitor and protocol checker of a Tamagawa
// T-format host, input-only, run by the encoder-tb library
// (cosim/src/monitor/tformat.rs); the same module name and ports in both
// simulators (DPI-C in Verilator, the VPI module emu.vpi in Icarus), beside
// or without a tformat_encoder_emu.
//
// Connect the host's half-duplex RS-485 transceiver as the host drives it:
// its driver input D (i_tf_data), its driver enable DE (i_tf_data_oe) and the
// receiver's output R (i_tf_rx: the line as the host hears it; with
// tformat_encoder_emu, its o_tf_data). Clock the monitor with i_mon_clk at
// F_MON_HZ (at least 4 x the bit rate, 10 MHz at 2.5 Mbps; any ratio). Each
// rising edge of i_mon_clk samples the three pins. The monitor decodes every
// transaction with the decoder of `tbgen decode tformat`
// (model/src/tformat/decode.rs) and holds the host to the seed's timing
// (seed 002, Tamagawa TS5669 N127): character timing of its requests (2.5
// Mbps, +-100 ns jitter, 10-bit fields, fields back to back, the field count
// of the Data ID), turnaround (DE off soon after the request's last
// delimiter, never on while the encoder answers) and the reset sequence (10
// requests of 7, 8 or C, 40 ms apart). Each violation is printed with its
// time and rule and counted (u_mon.violations(0)); STOP_ON_VIOLATION = 1
// stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; the
// emulator's own file or a whole scenario will do): baud, [host] timeout_us,
// [encoder] reset_interval_us, [monitor] timeout_us, jitter_ns, max_gap_bits,
// release_us, reset_interval_us.
//
// Queries: u_mon.count(0) (transactions seen; a reset's ten requests are
// one), u_mon.last_value(0) (abm << 17 | abs after the last transaction),
// u_mon.last_status(0, "crc" | "timeout" | "frame" | "cf_mismatch" |
// "comm_alarm" | an ALMC flag name). At the end of the simulation the
// transcript (every transaction as `tbgen decode tformat` prints it, and
// every violation) goes to TRANSCRIPT, or to the file of
// +<TRANSCRIPT_PLUSARG>=<file>.

`ifndef TFORMAT_MONITOR_V
`define TFORMAT_MONITOR_V
`default_nettype none

module tformat_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "tformat_monitor_config",
    parameter F_MON_HZ = 80000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "tformat_monitor_transcript",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Monitor clock */
    input wire i_mon_clk,

    /* The host's transceiver: D, DE, R */
    input wire i_tf_data,
    input wire i_tf_data_oe,
    input wire i_tf_rx
);

`include "emu_api.vh"

localparam EMU_KIND = "tformat_monitor";
localparam MON_PIN_NAMES = "i_tf_rx, i_tf_data, i_tf_data_oe";
localparam [7:0] MON_IDLE = 8'b0000_0011;
wire [7:0] mon_pins_now = {5'd0, i_tf_data_oe, i_tf_data, i_tf_rx};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
