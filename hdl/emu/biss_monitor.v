// biss_monitor: a pin-level monitor and protocol checker of a BiSS-C master,
// input-only, run by the encoder-tb library (cosim/src/monitor/biss.rs); the
// same module name and ports in Verilator (DPI-C) and Icarus (VPI module
// emu.vpi), beside or without a biss_slave_emu.
//
// Connect MA as the master drives it and SLO at the master's receiver; clock
// the monitor with i_mon_clk at F_MON_HZ (at least 4 x the fastest MA). Each
// rising edge of i_mon_clk samples both pins. The monitor decodes every frame
// with the decoder of `tbgen decode biss` (model/src/biss/decode.rs: data,
// nE, nW, CRC, control frames) and holds the master to the seed's timing
// (seed 001, SAR58K24 manual, BiSS-C timing): TMAS > 100 ns, TMASH > 25 ns,
// TMASL > 25 ns within every frame, and the BiSS timeout (16 us) with SLO
// high before the next frame. Each violation is printed with its time and
// rule and counted (u_mon.violations(0)); STOP_ON_VIOLATION = 1 stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; the
// emulator's own file or a whole scenario will do): [[slaves]] bits,
// crc_width, crc_poly, timeout_us; [checks] min_tmas_ns; [monitor]
// min_tmas_ns, min_tmash_ns, min_tmasl_ns, timeout_us.
//
// Queries: u_mon.count(0) (frames seen), u_mon.last_value(i) (slave i's
// position in the last frame), u_mon.last_status(i, "error" | "warning" |
// "crc_ok"). At the end of the simulation the transcript (every frame as
// `tbgen decode biss` prints it, and every violation) goes to TRANSCRIPT, or
// to the file of +<TRANSCRIPT_PLUSARG>=<file>.

`ifndef BISS_MONITOR_V
`define BISS_MONITOR_V
`default_nettype none

module biss_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "biss_monitor_config",
    parameter F_MON_HZ = 80000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "biss_monitor_transcript",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Monitor clock */
    input wire i_mon_clk,

    /* BiSS-C line at the master */
    input wire i_ma,
    input wire i_slo
);

`include "emu_api.vh"

localparam EMU_KIND = "biss_monitor";
localparam MON_PIN_NAMES = "i_ma, i_slo";
localparam [7:0] MON_IDLE = 8'b0000_0011;
wire [7:0] mon_pins_now = {6'd0, i_slo, i_ma};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
