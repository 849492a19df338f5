// canopen_encoder_emu: one or more CANopen DS 406 encoders (the Leine &
// Linde gateway of seed 003) and/or SAR58K24 encoders in their CAN mode
// (seed 001 §3.4) and the wired-AND bus they share with the master under
// test, for any testbench, emulated by the encoder-tb model (libcosim,
// cosim/src/canopen.rs: model::canopen::EncoderNode and
// DeviceNode<SarCan> on model::can::Bus); the same module name and ports
// in both simulators: DPI-C in Verilator, the VPI module emu.vpi in Icarus.
// (A comment line must not begin with the simulator's name: Verilator reads
// such a line as one of its directives.)
//
// Line-level ports, no tristate: the master's TXD in (i_can_tx, recessive
// high), the bus level at the master's RXD out (o_can_rx: the wired-AND of
// every encoder's TXD and the master's, each after its transceiver loop
// delay and its distance along the cable). Clock the emulator with
// i_emu_clk at F_EMU_HZ: it is the encoders' reference clock, so the
// configured bit timing must divide it, and at least 4 x the bit rate.
//
//   master TXD -> [1 emu cycle: this sample] -> bus (delays) -> encoders
//     -> bus -> [register] -> o_can_rx
//
// Each encoder boots after power-on (boot-up on 0x80 + node without data, or
// the DS 301 form), answers SDO on 0x580 + node, follows NMT, sends TPDO1
// by its cyclic timer (6200h) and TPDO2 on SYNC, and emergencies on alarms.
//
// The configuration is a TOML file with the scenario's [canopen] table
// (bit timing, ns_per_m, [master] for the master's place, [[encoders]] with
// their [encoders.encoder], [[sar]] with their [sar.encoder]; a whole
// scenario file will do): the parameter
// CONFIG, or the plusarg +<PLUSARG>=<file>. A missing or bad file stops the
// simulation at time 0 with the file, the field and the fix.
//
// A SAR58K24 answers its own commands on 0x200 + node (01 start, 80 click,
// 20 zero, 22 direction, 31 NN TT timed send and its stop) on 0x100 + node
// (or 0x180 + node, answer_base) and the configuration channel 0x7E5 (04 01
// enter, 11 <node>, 13 00 <code>), effective after u_emu.set_status(k,
// "power", 0) and (k, "power", 1). Devices: the [[encoders]] first, then
// the [[sar]]; u_emu.last_value(k + 16 * field) as docs/cosim.md lists.
//
// Controls (see emu_api.vh): u_emu.count(0) (TPDOs encoder 0 sent),
// u_emu.last_value(k) (the position of encoder k's last TPDO; k + 16 its
// frames sent; k + 32 its NMT state), u_emu.set_position(k, raw) (moves its
// disk), u_emu.set_status(k, "alarm", 1) (an emergency),
// u_emu.last_status(k, "operational"). An error an encoder detects in the
// master's frames is printed as a PROTOCOL VIOLATION with its time.

`default_nettype none

module canopen_encoder_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "canopen_emu_config",
    parameter F_EMU_HZ = 10000000,
    parameter TRANSCRIPT = "",
    parameter STOP_ON_X = 1,
    parameter STOP_ON_VIOLATION = 0
) (
    /* Emulator clock */
    input  wire i_emu_clk,

    /* The master's transceiver pins */
    input  wire i_can_tx,
    output wire o_can_rx
);

`include "emu_api.vh"

localparam EMU_KIND = "canopen";
localparam EMU_PINS = "i_can_tx";
localparam [3:0] EMU_IDLE = 4'b1011;
wire [3:0] emu_pins_in = {1'b1, 1'b0, i_can_tx, 1'b1};

`include "emu_half_duplex.vh"

assign o_can_rx = emu_out[0];
// A CAN node has no separate driver enable: the wired-AND bus level is
// emu_out[0]; the half-duplex body's other two outputs are not wired out.
wire unused_emu_out = |emu_out[2:1];

endmodule

`default_nettype wire
