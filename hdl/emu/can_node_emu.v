// can_node_emu: one or more CAN nodes and the wired-AND bus they share with
// the master under test, for any testbench, emulated by the encoder-tb model
// (libcosim, cosim/src/can.rs: model::can::Emulator nodes on model::can::Bus);
// the same module name and ports in Verilator (DPI-C) and Icarus (VPI module
// emu.vpi).
//
// Line-level ports, no tristate: the master's TXD in (i_can_tx, recessive
// high), the bus level at the master's RXD out (o_can_rx: the wired-AND of
// every node's TXD and the master's, each after its transceiver loop delay
// and its distance along the cable). Clock the emulator with i_emu_clk at
// F_EMU_HZ: it is the nodes' reference clock, so the configured bit timing
// must divide it (tq_per_bit quanta of whole cycles), and at least 4 x the
// bit rate.
//
//   master TXD -> [1 emu cycle: this sample] -> bus (delays) -> nodes
//     -> bus -> [register] -> o_can_rx
//
// The configuration is a TOML file with the scenario's [can] table (timing,
// ns_per_m, [dut] for the master's place, [[nodes]] with their frames; a
// whole scenario file will do): the parameter CONFIG, or the plusarg
// +<PLUSARG>=<file>. A missing or bad file stops the simulation at time 0
// with the file, the field and the fix.
//
// Controls (see emu_api.vh): u_emu.count(0) (frames node 0 received),
// u_emu.last_value(node + 16 * field) (field 0 data, 1 identifier, 2 DLC of
// the last frame the node received; 3 frames it sent), u_emu.last_status(node,
// "rtr" | "ide"), u_emu.schedule_fault("[[send]]\nnode = 0\nid = 0x123\n...")
// (a node sends a frame as soon as it is free). An error a node detects in
// the master's frames is printed as a PROTOCOL VIOLATION with its time.

`default_nettype none

module can_node_emu #(
    parameter CONFIG = "",
    parameter PLUSARG = "can_emu_config",
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

localparam EMU_KIND = "can";
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
