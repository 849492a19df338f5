// canopen_monitor: a pin-level monitor and protocol checker of a CANopen
// master (DS 301 / DS 406, seed 003) or of a master of SAR58K24 encoders in
// their CAN mode (seed 001 §3.4), input-only, run by the encoder-tb library
// (cosim/src/monitor/canopen.rs); the same module name and ports in both
// simulators (DPI-C in Verilator, the VPI module emu.vpi in Icarus), beside
// or without a canopen_encoder_emu.
//
// Connect the master's TXD (i_can_tx) and RXD (i_can_rx; with
// canopen_encoder_emu, its o_can_rx); clock it with i_mon_clk at F_MON_HZ
// (at least 4 x the bit rate). It checks everything can_monitor checks and,
// on the frames it reads as `tbgen decode canopen` does, the master's
// CANopen sequence: one SDO request outstanding per node until its answer
// or the SDO timeout; no second NMT start of a started node; node guarding
// at the guard time the master wrote (100Ch), and no guarding of a node
// with a heartbeat (1017h); the SYNC period when one is configured; a
// SAR58K24 command only after the answer to the previous one (or its
// timeout). Each violation is printed with its time and rule and counted
// (u_mon.violations(0)); STOP_ON_VIOLATION = 1 stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; a
// whole scenario file will do): [canopen] f_sys_mhz, bit_rate_kbps,
// tq_per_bit, sample_point, sjw, [canopen.master] sdo_timeout_us,
// sync_period_us, [[canopen.encoders]], [[canopen.sar]]; [monitor]
// bit_tolerance_percent, max_dominant_bits, sdo_timeout_us, sync_period_us,
// guard_time_ms, guard_tolerance_percent, sar_answer_timeout_us.
//
// Queries: as can_monitor, and u_mon.last_value(5): the position (bytes 0..3
// little endian) of the last TPDO1/TPDO2 another node sent. At the end of
// the simulation the transcript (every frame as `tbgen decode canopen`
// prints it, with `sender`, and every violation) goes to TRANSCRIPT, or to
// the file of +<TRANSCRIPT_PLUSARG>=<file>.

`ifndef CANOPEN_MONITOR_V
`define CANOPEN_MONITOR_V
`default_nettype none

module canopen_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "canopen_monitor_config",
    parameter F_MON_HZ = 10000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "canopen_monitor_transcript",
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

localparam EMU_KIND = "canopen_monitor";
localparam MON_PIN_NAMES = "i_can_rx, i_can_tx";
localparam [7:0] MON_IDLE = 8'b0000_0011;
wire [7:0] mon_pins_now = {6'd0, i_can_tx, i_can_rx};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
