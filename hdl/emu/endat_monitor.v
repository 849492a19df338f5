// endat_monitor: a pin-level monitor and protocol checker of an EnDat 2.1 /
// 2.2 master, input-only, run by the encoder-tb library
// (cosim/src/monitor/endat.rs); the same module name and ports in Verilator
// (DPI-C) and Icarus (VPI module emu.vpi), beside or without an
// endat_encoder_emu.
//
// Connect the master's pins: its clock, its data driver's level and enable
// (D and DE of its transceiver) and the data at its receiver (R; for the
// emulator, its o_endat_data). The line at the master is D while DE is on,
// else R; for a capture of the pair alone tie i_endat_data_oe low and give
// the pair as i_endat_data_in. Clock the monitor with i_mon_clk at F_MON_HZ
// (at least 4 x the fastest EnDat clock; 8 MHz unless the configuration's
// [emulator] max_line_clock_khz says less). Each rising edge of i_mon_clk
// samples the pins. The monitor decodes every transfer with the decoder of
// `tbgen decode endat` (model/src/endat/decode.rs: mode bits, the master's
// blocks, the encoder's frames judged by the master's own check logic) and
// holds the master to the timing of seed 004 (HEIDENHAIN EnDat 2.2): f_c
// (100 kHz to 2 MHz, 8 MHz with delay compensation, the shorter phase), the
// on-off ratio (10 %), t_ST (first low phase, 2 us from 2 to 8 MHz), the send
// block (driver on only from F2, off at R8), the recovery times t_m and t_R
// before the next transfer, 30 us after an error (appendix A2), t_b > 1 ms
// after type 2.1 commands, and the delay measurement (100 to 200 kHz, at
// least three frames, before compensated transfers): the rule book
// model/src/endat/rules.rs, which endat_encoder_emu holds the master to as
// well, with the same texts. Each violation is printed with its time and
// rule:
//   PROTOCOL VIOLATION by the master on tb.u_mon.emu_show_violations at <ns> ns (emulator cycle N): t_ST (...): first low phase 0.500 us ...
// and counted (u_mon.violations(0)); STOP_ON_VIOLATION = 1 stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; the
// emulator's own file or a whole scenario will do): [monitor] pos_bits,
// delay_comp, max_clock_khz, min_clock_khz, on_off_percent, t_st_us,
// t_m_us, t_m21_us, t_r_us, round_trip_ns, t_err_us, t_b_us,
// meas_clock_khz, meas_frame_below_khz, meas_frames_min; defaults from
// [master], [encoder], [cable] and [checks] (docs/cosim.md).
//
// Queries: u_mon.count(0) (transactions seen; a delay measurement is one),
// u_mon.last_value(0) (the last position), u_mon.last_status(0, "f1" |
// "f2" | "crc_ok" | "error"). At the end of the simulation the transcript
// (every transaction as `tbgen decode endat` prints it, and every violation)
// goes to TRANSCRIPT, or to the file of +<TRANSCRIPT_PLUSARG>=<file>.

`ifndef ENDAT_MONITOR_V
`define ENDAT_MONITOR_V
`default_nettype none

module endat_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "endat_monitor_config",
    parameter F_MON_HZ = 64000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "endat_monitor_transcript",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Monitor clock */
    input wire i_mon_clk,

    /* EnDat line at the master */
    input wire i_endat_clk,
    input wire i_endat_data,
    input wire i_endat_data_oe,
    input wire i_endat_data_in
);

`include "emu_api.vh"

localparam EMU_KIND = "endat_monitor";
localparam MON_PIN_NAMES = "i_endat_clk, i_endat_data, i_endat_data_oe, i_endat_data_in";
localparam [7:0] MON_IDLE = 8'b0000_1011;
// X or Z on the master's driver enable reads as 0, the master not driving
// (a master before its reset), as endat_encoder_emu reads it (emu_pair.vh),
// and the data of a driver that is not on is not read: one warning, never a
// protocol report.
wire mon_oe = i_endat_data_oe === 1'b1;
wire mon_data = mon_oe ? i_endat_data : 1'b1;
reg mon_oe_known = 1'b0;
reg mon_oe_warned = 1'b0;
always @(posedge i_mon_clk) begin
    if (i_endat_data_oe === 1'b0 || i_endat_data_oe === 1'b1)
        mon_oe_known <= 1'b1;
    else if (mon_oe_known && !mon_oe_warned) begin
        $display("WARNING: %m: X or Z on the driver enable i_endat_data_oe at time %0t: read as 0, the master not driving",
                 $time);
        mon_oe_warned <= 1'b1;
    end
end
wire [7:0] mon_pins_now = {4'd0, i_endat_data_in, mon_oe, mon_data, i_endat_clk};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
