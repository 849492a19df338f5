// tb_emu_errors: what the emulator wrappers do with bad input. Run with
// +ssi_emu_config=<file> (missing, bad or good) and +x_at=<ns> (drive X on
// the emulator's clock input at that time, after it has been 0 and 1); the
// run must stop at time 0 for a bad configuration, and at the X with its
// time and pin, and otherwise print "no error" at 2 us (the 100 ns low
// phase is a T_cs violation the checker reports without stopping).

`timescale 1ns / 1ps
`default_nettype none

module tb_emu_errors;

parameter F_EMU_HZ = 50000000;

reg clk = 1'b0;
always #10 clk = ~clk;

reg sclk = 1'bx;
wire data;
integer x_at;

ssi_encoder_emu #(.F_EMU_HZ(F_EMU_HZ)) u_emu (.i_emu_clk(clk), .i_ssi_clk(sclk), .o_ssi_data(data));

initial begin
    if (!$value$plusargs("x_at=%d", x_at)) x_at = 0;
    #95 sclk = 1'b1;
    #100 sclk = 1'b0;
    #100 sclk = 1'b1;
    if (x_at > 0) begin
        #(x_at - 295) sclk = 1'bx;
    end
    #1500 $display("no error");
    $finish;
end

endmodule

`default_nettype wire
