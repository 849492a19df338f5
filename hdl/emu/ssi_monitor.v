// ssi_monitor: a pin-level monitor and protocol checker of an SSI master,
// input-only, run by the encoder-tb library (cosim/src/monitor/ssi.rs); the
// same module name and ports in Verilator (DPI-C) and Icarus (VPI module
// emu.vpi), beside or without an ssi_encoder_emu.
//
// Connect the master's SSI clock and the data at its receiver; clock the
// monitor with i_mon_clk at F_MON_HZ (at least 4 x the fastest SSI clock).
// Each rising edge of i_mon_clk samples both pins. The monitor decodes every
// read with the decoder of `tbgen decode ssi` (model/src/ssi/decode.rs) and
// holds the master to the seed's timing (seed 001, SAR58K24 manual, SSI (2)):
// T_cs > 4 us, 100 kHz < f_clk < 250 kHz, T_m (the encoder's monoflop)
// before the next read. Each violation is printed with its time and rule:
//   PROTOCOL VIOLATION by the master on tb.u_mon.emu_show_violations at <ns> ns (emulator cycle N): T_cs (...): first low phase 2.500 us
// and counted (u_mon.violations(0)); STOP_ON_VIOLATION = 1 stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; the
// emulator's own file or a whole scenario will do): [monitor] bits, code,
// double_read, wire_check, t_m_us (default: the [master] table's, else the
// [encoder]'s), [checks] t_cs_min_us, min_clock_khz, max_clock_khz. An empty
// file reads the seed's encoder (12 bits binary, T_m 500 us).
//
// Queries: u_mon.count(0) (reads seen), u_mon.last_value(0) (the last read's
// position), u_mon.last_status(0, "error"). At the end of the simulation the
// transcript (every read as `tbgen decode ssi` prints it, and every
// violation) goes to TRANSCRIPT, or to the file of +<TRANSCRIPT_PLUSARG>=<file>;
// `tbgen check ssi --expect FILE <transcript>` compares it.

`ifndef SSI_MONITOR_V
`define SSI_MONITOR_V
`default_nettype none

module ssi_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "ssi_monitor_config",
    parameter F_MON_HZ = 50000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "ssi_monitor_transcript",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Monitor clock */
    input wire i_mon_clk,

    /* SSI line at the master */
    input wire i_ssi_clk,
    input wire i_ssi_data
);

`include "emu_api.vh"

localparam EMU_KIND = "ssi_monitor";
localparam MON_PIN_NAMES = "i_ssi_clk, i_ssi_data";
localparam [7:0] MON_IDLE = 8'b0000_0011;
wire [7:0] mon_pins_now = {6'd0, i_ssi_data, i_ssi_clk};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
