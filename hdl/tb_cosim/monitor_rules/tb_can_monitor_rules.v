// tb_can_monitor_rules: a hand-played CAN line (plain stimulus, no core, no
// emulator) in front of can_monitor and canopen_monitor, both on the same
// pins. The line comes bit by bit from the plusarg +bits=<chars> (+n=<count>),
// written by cosim/tests/monitor.rs from the model's frames (stuffed, with
// their CRC), so each case breaks one rule once (or none):
//   '0'..'3'  one bit: TXD = bit 1 of the digit, RXD = bit 0 (3: both recessive)
//   'i' / 'I' 10 / 100 idle bits (both recessive)
//   'f' / 'n' the following bits 3 % short (a master off its bit rate) / nominal
// The monitors run at 8 MHz (125 ns), the line at 500 kbit/s (2 us, 16 monitor
// cycles per bit). Prints "violations can <n> canopen <m>" and
// "frames can <a> canopen <b>" at the end.

`timescale 1ns / 1ps
`include "can_monitor.v"
`include "canopen_monitor.v"
`default_nettype none

module tb_can_monitor_rules;

reg clk8 = 1'b0;
always #62.5 clk8 = ~clk8;

reg can_tx = 1'b1;
reg can_rx = 1'b1;

can_monitor #(.F_MON_HZ(8000000)) u_can (.i_mon_clk(clk8), .i_can_tx(can_tx), .i_can_rx(can_rx));
canopen_monitor #(.F_MON_HZ(8000000)) u_canopen (.i_mon_clk(clk8), .i_can_tx(can_tx), .i_can_rx(can_rx));

reg [8*16384-1:0] bits;
reg [7:0] c;
integer n, k, j;
real bit_ns;

task play(input t, input r);
    begin
        can_tx = t;
        can_rx = r;
        #(bit_ns);
    end
endtask

initial begin
    bits = 0;
    if (!$value$plusargs("bits=%s", bits)) bits = 0;
    if (!$value$plusargs("n=%d", n)) n = 0;
    bit_ns = 2000.0;
    #(1000);
    for (k = 0; k < n; k = k + 1) begin
        c = bits[8 * (n - 1 - k) +: 8];
        case (c)
            "0", "1", "2", "3": play(c[1], c[0]);
            "i": for (j = 0; j < 10; j = j + 1) play(1'b1, 1'b1);
            "I": for (j = 0; j < 100; j = j + 1) play(1'b1, 1'b1);
            "f": bit_ns = 1940.0;
            "n": bit_ns = 2000.0;
            default: $fatal(1, "+bits: no meaning for `%c`", c);
        endcase
    end
    for (j = 0; j < 30; j = j + 1) play(1'b1, 1'b1);
    $display("violations can %0d canopen %0d", u_can.violations(0), u_canopen.violations(0));
    $display("frames can %0d canopen %0d", u_can.count(0), u_canopen.count(0));
    $finish;
end

endmodule

`default_nettype wire
