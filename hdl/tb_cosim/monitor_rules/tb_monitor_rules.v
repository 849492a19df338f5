// tb_monitor_rules: a hand-written SSI master and BiSS-C master (plain
// stimulus, no core, no emulator) in front of ssi_monitor and biss_monitor.
// +case=N picks what the masters do; each case breaks one timing rule of
// seed 001 once (or none: case 0), so the monitors' PROTOCOL VIOLATION lines
// and counts show each rule firing, and staying silent on a clean master.
//
//   0 clean: two SSI reads (250 kHz, T_cs 4.5 us, 50 us apart) and two BiSS-C
//     frames (10 MHz, 20 us apart)
//   1 SSI T_cs 2.5 us          2 SSI next read 10 us after the last (T_m 20 us)
//   3 SSI one half period 1 us (500 kHz)
//   4 BiSS-C one MA high 10 ns (TMASH; its period breaks TMAS too)
//   5 BiSS-C one MA low 10 ns (TMASL, and TMAS)
//   6 BiSS-C next frame 5 us after the last MA edge (timeout 16 us)
//
// Plusargs: +case=N, +ssi_monitor_config=FILE, +biss_monitor_config=FILE.
// Prints "violations ssi <n> biss <m>" at the end.

`timescale 1ns / 1ps
`include "ssi_monitor.v"
`include "biss_monitor.v"
`default_nettype none

module tb_monitor_rules;

reg clk4 = 1'b0;     // 4 MHz: the SSI monitor's clock (250 ns)
reg clk200 = 1'b0;   // 200 MHz: the BiSS-C monitor's clock (5 ns)
always #125 clk4 = ~clk4;
always #2.5 clk200 = ~clk200;

reg ssi_clk = 1'b1;
reg ssi_data = 1'b1;
reg ma = 1'b1;
reg slo = 1'b1;

ssi_monitor #(.F_MON_HZ(4000000)) u_ssi (.i_mon_clk(clk4), .i_ssi_clk(ssi_clk), .i_ssi_data(ssi_data));
biss_monitor #(.F_MON_HZ(200000000)) u_biss (.i_mon_clk(clk200), .i_ma(ma), .i_slo(slo));

integer which, ks, kb;  // one loop variable per master: they run in parallel

// One SSI read: T_cs, then `bits` periods of 2 x `half` ns (one of them,
// `odd`, with a high phase of `odd_half` ns), the clock left high.
task ssi_read(input integer t_cs, input integer half, input integer bits, input integer odd, input integer odd_half);
    begin
        ssi_clk = 1'b0;
        #(t_cs);
        for (ks = 0; ks < bits; ks = ks + 1) begin
            ssi_clk = 1'b1;
            #(ks == odd ? odd_half : half);
            ssi_clk = 1'b0;
            #(half);
        end
        ssi_clk = 1'b1;
    end
endtask

// One BiSS-C frame of 40 MA periods of 50 + 50 ns; period `odd` has an MA
// high of `odd_high` ns and a low of `odd_low` ns. MA is left high.
task biss_frame(input integer odd, input integer odd_low, input integer odd_high);
    begin
        for (kb = 0; kb < 40; kb = kb + 1) begin
            ma = 1'b0;
            #(kb == odd ? odd_low : 50);
            ma = 1'b1;
            #(kb == odd ? odd_high : 50);
        end
    end
endtask

initial begin
    if (!$value$plusargs("case=%d", which)) which = 0;
    #10000;
    fork
        begin
            ssi_read(which == 1 ? 2500 : 4500, 2000, 12, which == 3 ? 5 : -1, 1000);
            #(which == 2 ? 10000 : 50000);
            ssi_read(4500, 2000, 12, -1, 2000);
        end
        begin
            biss_frame(which == 4 || which == 5 ? 7 : -1, which == 5 ? 10 : 50, which == 4 ? 10 : 50);
            #(which == 6 ? 5000 : 20000);
            biss_frame(-1, 50, 50);
        end
    join
    #20000;
    $display("violations ssi %0d biss %0d", u_ssi.violations(0), u_biss.violations(0));
    $finish;
end

endmodule

`default_nettype wire
