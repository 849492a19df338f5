// esl_monitor: a pin-level monitor and protocol checker of an ESL host,
// input-only, run by the encoder-tb library (cosim/src/monitor/esl.rs); the
// same module name and ports in Verilator (DPI-C) and Icarus (VPI module
// emu.vpi), beside or without an esl_encoder_emu.
//
// Connect the host's half-duplex RS-485 transceiver as the host drives it:
// its driver input DI (i_esl_data), its driver enable DE (i_esl_data_oe) and
// the receiver's output RO (i_esl_rx: the bus as the host hears it; with
// esl_encoder_emu, its o_esl_data). Clock the monitor with i_mon_clk at
// F_MON_HZ (at least 4 x the bit rate, 40 MHz at 10 Mbps; any ratio). Each
// rising edge of i_mon_clk samples the three pins. The monitor decodes every
// operation with the decoder of `tbgen decode esl` (model/src/esl/decode.rs)
// and holds the host to the seed's timing (seed 000, QS35 ESL Safety
// protocol): character timing of its requests (10 Mbps within 3 %, 10-bit
// frames back to back, the frame count of the Data ID), turnaround (DE off
// soon after the request, never on while an encoder answers) and request
// spacing per encoder address (B, C, D 8 times in a row within the repeat
// window, EEPROM reads 200 us and writes 6 ms apart, 18 ms after a page
// change). Each violation is printed with its time and rule and counted
// (u_mon.violations(0)); STOP_ON_VIOLATION = 1 stops the run.
//
// Configuration: a TOML file (CONFIG, or the plusarg +<PLUSARG>=<file>; the
// emulator's own file or a whole scenario will do): baud, [[encoders]]
// address, repeat_window_us, eeprom_read_us, eeprom_write_us,
// page_change_us; [host] broadcast_address, busy_tries, rs_tolerance;
// [checks] bit_tolerance_percent; [monitor] the same and max_gap_bits,
// release_us.
//
// Queries: u_mon.count(0) (operations seen; B, C, D's eight requests are
// one), u_mon.last_value(0) (abm << 24 | abs after the last operation),
// u_mon.last_status(0, "crc1" | "crc2" | "timeout" | "frame" | "cf_mismatch"
// | "comm_alarm" | "sequence" | "channel_mismatch" | "busy" | an ALM flag
// name). At the end of the simulation the transcript (every operation as
// `tbgen decode esl` prints it, and every violation) goes to TRANSCRIPT, or
// to the file of +<TRANSCRIPT_PLUSARG>=<file>.

`ifndef ESL_MONITOR_V
`define ESL_MONITOR_V
`default_nettype none

module esl_monitor #(
    parameter CONFIG = "",
    parameter PLUSARG = "esl_monitor_config",
    parameter F_MON_HZ = 80000000,
    parameter TRANSCRIPT = "",
    parameter TRANSCRIPT_PLUSARG = "esl_monitor_transcript",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Monitor clock */
    input wire i_mon_clk,

    /* The host's transceiver: DI, DE, RO */
    input wire i_esl_data,
    input wire i_esl_data_oe,
    input wire i_esl_rx
);

`include "emu_api.vh"

localparam EMU_KIND = "esl_monitor";
localparam MON_PIN_NAMES = "i_esl_rx, i_esl_data, i_esl_data_oe";
localparam [7:0] MON_IDLE = 8'b0000_0011;
wire [7:0] mon_pins_now = {5'd0, i_esl_data_oe, i_esl_data, i_esl_rx};

`include "emu_monitor.vh"

endmodule

`default_nettype wire
`endif
