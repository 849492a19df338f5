// tb_wrapper_x: X or Z on an input of a monitor (emu_monitor.vh) or of an
// emulator with a clock, data and enable line (emu_pair.vh) is reported with
// time, pin and cycle, and stops the run. Both wrappers take every input at
// once while all are 0 or 1, and look at each pin only when one is not:
// this bench drives each path. Icarus only (Verilator is two-state: no X
// reaches a wrapper there).
//
//   +x_on=none|monitor|pair  which wrapper sees X on its data input at
//                            +x_at=<ns> (default 500); with none, the run
//                            prints "no error" at 2 us
//   +ssi_monitor_config=<toml>  +endat_emu_config=<toml>

`timescale 1ns / 1ps
`include "ssi_monitor.v"
`include "endat_encoder_emu.v"
`default_nettype none

module tb_wrapper_x;

reg clk = 1'b0;
always #10 clk = ~clk;

// Idle lines: the clocks high, the data high, the master's driver off.
reg ssi_clk = 1'b1;
reg ssi_data = 1'b1;
reg endat_clk = 1'b1;
reg endat_data = 1'b1;
wire endat_data_out, endat_data_oe;
integer x_at;
reg [8*8-1:0] x_on;

ssi_monitor #(.F_MON_HZ(50000000)) u_mon (.i_mon_clk(clk), .i_ssi_clk(ssi_clk), .i_ssi_data(ssi_data));

endat_encoder_emu #(.F_EMU_HZ(50000000)) u_emu (
    .i_emu_clk(clk),
    .i_endat_clk(endat_clk),
    .i_endat_data(endat_data),
    .i_endat_data_oe(1'b0),
    .o_endat_data(endat_data_out),
    .o_endat_data_oe(endat_data_oe)
);

initial begin
    if (!$value$plusargs("x_at=%d", x_at)) x_at = 500;
    if (!$value$plusargs("x_on=%s", x_on)) x_on = "none";
    #(x_at);
    if (x_on == "monitor") ssi_data = 1'bx;
    if (x_on == "pair") endat_data = 1'bz;
    #(2000 - x_at) $display("no error");
    $finish;
end

endmodule

`default_nettype wire
