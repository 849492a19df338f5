// tb_probe: replays one rule probe (cosim/src/probe/, exported by
// `tbgen probes --out DIR`) into a protocol's emulator and monitor wrappers
// (hdl/emu/), as the library's own run of the probe steps them, and leaves
// their transcripts for `tbgen probes --check DIR --sim <simulator>` to
// judge with the library's verdict. One testbench for every protocol: the
// wrappers come from the kit's generated include (DIR/<kind>/probe_wiring.vh,
// derived from the wrappers' own pin lists), the monitor's pins from the
// kit's wiring table, evaluated here. hdl/tb_probe/run.sh builds and runs it.
//
// Run in a probe's folder's <simulator>/ subfolder, it reads
//   ../stimulus.mem  the master's pins, runs of emulator cycles: one 64-bit
//                    word a run, {cycles[63:32], unknown[31:16], levels[15:0]};
//                    the pins of `unknown` are X for the run (a master in
//                    reset before it drives them), a zero word ends
//   ../monitor.mem   the kit's wiring table: a byte per monitor pin, the
//                    source's kind in the high nibble (0 a master pin, 1 an
//                    emulator pin, 2 the half-duplex bus, 3 a wired-AND bus
//                    of a master pin and the emulator's data), the pin low
//   ../probe.toml    the configuration of both wrappers
// and writes emulator.json and monitor.json (the wrappers' transcripts).
//
// Timing, as `cosim::probe::run` has it: on each rising edge of the emulator
// clock both wrappers sample; the emulator sees the master's pins of this
// cycle, the monitor the same pins and the emulator's answer of the cycle
// before (its registered outputs), wired by the table. The master's pins for
// the next cycle are set with the edge (nonblocking), so every wrapper
// samples this cycle's.
//
// Four-state and two-state: in Icarus (and cocotb) an unknown pin is X until
// the probe's `unknown_ps`; the wrappers read X or Z on a driver enable as
// not driving. Verilator is two-state: run.sh builds with --x-assign 0, so
// an X this testbench drives is 0 there, the level the library reads an
// unknown pin as; the probe still runs, without the X path.

`timescale 1ps / 1ps
`default_nettype none

module tb_probe;

/* Harness parameters (run.sh: from the export's manifest) */
parameter F_HZ = 200000000;
parameter STIM_DEPTH = 1024;
// The clock's half period only spaces the edges for waveforms: the wrappers
// count emulator cycles at F_HZ, not simulation time.
localparam [63:0] HALF_PS = 64'd500000000000 / F_HZ;

localparam CONFIG = "../probe.toml";
localparam EMU_TRANSCRIPT = "emulator.json";
localparam MON_TRANSCRIPT = "monitor.json";

reg clk = 1'b0;
always #(HALF_PS) clk = ~clk;

reg [63:0] stim [0:STIM_DEPTH-1];
reg [7:0] table_mem [0:7];
reg [63:0] sources;

// The master's pins in the emulator's input layout, X where unknown.
function [15:0] pins(input [63:0] w);
    pins = (w[15:0] & ~w[31:16]) | ({16{1'bx}} & w[31:16]);
endfunction

reg [15:0] master;
wire [3:0] answer;
wire [7:0] mon_pins;

// One monitor pin from its source (cosim::probe::Src, the byte
// tbgen probes writes): a master pin, an emulator pin, the half-duplex bus
// at the master's receiver, or the wired-AND CAN bus.
function src_level(input [7:0] s, input [15:0] m, input [3:0] a);
    case (s[7:4])
        4'd0: src_level = m[s[3:0]];
        4'd1: src_level = a[s[1:0]];
        // The bus and the wired-AND are the testbench's, not a wrapper's
        // input: an unknown master pin in them reads as 0, as the library's
        // run reads it (an enable X or Z: not driving), so that they carry
        // no X the master did not put on a wrapper's own pin.
        4'd2: src_level = (a[1] === 1'b1) ? a[0] : ((m[2] === 1'b1) ? m[1] : 1'b1);
        4'd3: src_level = (m[s[3:0]] === 1'b1) & a[0];
        default: src_level = 1'bx;
    endcase
endfunction

genvar gi;
generate
    for (gi = 0; gi < 8; gi = gi + 1) begin : g_mon
        assign mon_pins[gi] = src_level(sources[8*gi +: 8], master, answer);
    end
endgenerate

`include "probe_wiring.vh"

integer seg = 0;
integer k;
reg [31:0] left = 0;
reg done = 1'b0;

initial begin
    for (k = 0; k < 8; k = k + 1)
        table_mem[k] = 8'hff;
    $readmemh("../stimulus.mem", stim);
    $readmemh("../monitor.mem", table_mem);
    for (k = 0; k < 8; k = k + 1)
        sources[8*k +: 8] = table_mem[k];
    master = pins(stim[0]);
    left = stim[0][63:32];
    if (left == 0)
        $fatal(1, "tb_probe: ../stimulus.mem is empty or missing");
end

// After this edge's sample: the next cycle's pins, or the end after the
// last run (at the falling edge, once every wrapper has taken this sample).
always @(posedge clk) begin
    left = left - 1;
    if (left == 0) begin
        seg = seg + 1;
        if (seg >= STIM_DEPTH || stim[seg][63:32] == 0) begin
            done <= 1'b1;
        end else begin
            master <= pins(stim[seg]);
            left = stim[seg][63:32];
        end
    end
end

always @(negedge clk)
    if (done)
        $finish;

endmodule

`default_nettype wire
