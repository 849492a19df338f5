// sar58k24_monitor: a pin-level monitor and protocol checker of a SAR58K24
// asynchronous-serial host (seed 001, 3.1.1 to 3.1.6: timed send,
// handshake, bus commands, with or without clear), input-only, run by the
// encoder-tb library (cosim/src/monitor/sar.rs); the same module name and
// ports in both simulators (DPI-C in Verilator, the VPI module emu.vpi in
// Icarus), beside or without a sar58k24_encoder_emu.
//
// Connect the host's pins: its RS-485 driver input D (i_line) and enable DE
// (i_line_en; tie low and i_line high in the modes without bus commands),
// its receiver's output R (i_rx: the line as the host hears it, the
// encoders' frames; with sar58k24_encoder_emu, its o_bus), its trigger (CLK)
// and CLR outputs (idle high; tie high when unused). Clock the monitor with
// i_mon_clk at F_MON_HZ (at least 8 x the baud rate; any ratio). The monitor
// decodes every command and frame with the decoder of `tbgen decode sar`
// (model/src/sar58k24/decode.rs) and holds the host to the timing:
// character timing and parity of its commands (baud rate tolerance), the
// command's characters together, DE released after the command and never
// on during an answer, the wait for the answer (or the host's timeout)
// before the next command or trigger, T2 >= 10 us of every trigger pulse,
// no trigger inside the encoder's frame, the CLR pulse width. Each violation
// is printed with its time and rule and counted (u_mon.violations(0));
// STOP_ON_VIOLATION = 1 stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; the
// emulator's own file or a whole scenario will do): the [sar] table's baud,
// parity, mode, [[encoders]] (bits, code, trigger_min_low_us,
// clr_min_low_us, command_gap_bits, answer_zeroing), [host] timeout_us,
// gap_bits, and [monitor] timeout_us, baud_tolerance_percent, release_bits,
// t2_us, clr_min_low_us, command_gap_bits.
//
// Queries: u_mon.count(0) (frames accepted), u_mon.last_value(0) (the
// position of the last frame), u_mon.last_status(0, "frame_ok" | "checksum"
// | "parity" | "frame" | "address"). At the end of the simulation the
// transcript (every event as `tbgen decode sar` prints it, and every
// violation) goes to TRANSCRIPT, or to the file of
// +<TRANSCRIPT_PLUSARG>=<file>.

`ifndef SAR58K24_MONITOR_V
`define SAR58K24_MONITOR_V
`default_nettype none

module sar58k24_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "sar58k24_monitor_config",
    parameter F_MON_HZ = 10000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "sar58k24_monitor_transcript",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Monitor clock */
    input wire i_mon_clk,

    /* The host's transceiver: D, DE, R; its trigger and CLR outputs */
    input wire i_line,
    input wire i_line_en,
    input wire i_rx,
    input wire i_trigger,
    input wire i_clr
);

`include "emu_api.vh"

localparam EMU_KIND = "sar58k24_monitor";
localparam MON_PIN_NAMES = "i_rx, i_line, i_line_en, i_trigger, i_clr";
localparam [7:0] MON_IDLE = 8'b0001_1011;
wire [7:0] mon_pins_now = {3'd0, i_clr, i_trigger, i_line_en, i_line, i_rx};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
