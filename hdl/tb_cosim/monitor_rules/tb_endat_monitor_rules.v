// tb_endat_monitor_rules: a hand-written EnDat master and a crafted encoder
// answer (plain stimulus, no core, no emulator) in front of endat_monitor.
// +case=N picks what the master does; each case breaks one timing rule of
// seed 004 (HEIDENHAIN EnDat 2.2) once (or none: case 0), so the monitor's
// PROTOCOL VIOLATION lines and count show each rule firing, and staying
// silent on a clean master. The monitor runs at 8 MHz (125 ns); the
// configuration (+endat_monitor_config) says the fastest clock is 1 MHz (case
// 1: also the monitor's limit), the encoder's output delay 0, and for cases 9
// and 10 that the master compensates the delay.
//
//   0 clean: two "send position values" 2.2 reads at 1 MHz, 31 us apart
//   1 f_c: one high and one low phase of 250 ns (the configuration: 1 MHz at most)
//   2 on-off ratio: one period of 750 ns high and 250 ns low
//   3 t_ST: a 2 MHz read with a first low phase of 250 ns (2 us)
//   4 send block: the driver on before F1 and through R8
//   5 t_m: the next read 10 us after the last clock edge (t_m 15 us)
//   6 t_R: the next read 250 ns after the line rose (500 ns)
//   7 after an error (no start bit): the next read 20 us later (30 us)
//   8 t_b: a 2.1 read (000111), the next one 500 us later (1 ms)
//   9 measurement clock: three 000111 frames at 250 kHz (100 to 200 kHz)
//  10 delay measurement: two 000111 frames at 200 kHz (at least three)
//
// Prints "violations endat <n>" at the end.

`timescale 1ns / 1ps
`include "endat_monitor.v"
`default_nettype none

module tb_endat_monitor_rules;

reg clk8 = 1'b0;     // 8 MHz: the monitor's clock (125 ns)
always #62.5 clk8 = ~clk8;

reg endat_clk = 1'b1;
reg data_out = 1'b1;
reg data_oe = 1'b0;
reg data_in = 1'b1;

endat_monitor #(.F_MON_HZ(8000000)) u_mon (
    .i_mon_clk(clk8), .i_endat_clk(endat_clk), .i_endat_data(data_out),
    .i_endat_data_oe(data_oe), .i_endat_data_in(data_in));

integer which, k;

// One transfer of 46 clocks: mode bits at F2..F7 (driver on from F2 to F8),
// the crafted encoder low from R8, a start bit at R12 (none for mode 000000),
// then low; half period `half` ns, first low `t_st` ns; clock phase `odd`
// high `odd_high` and low `odd_low` ns; `oe_late`: the driver stays on
// through R8. The line goes high again `rec` ns after the last rising edge
// (within the idle `gap` ns that follows; later, at R1 of the next transfer).
task transfer(input [5:0] mode, input integer half, input integer t_st, input integer odd,
              input integer odd_high, input integer odd_low, input integer oe_late, input integer rec, input integer gap);
    begin
        endat_clk = 1'b0;
        #(t_st);
        for (k = 1; k <= 46; k = k + 1) begin
            endat_clk = 1'b1;
            if (k == 1) data_in = 1'b1;
            if (k == 8) data_in = 1'b0;
            if (k == 9 && oe_late) data_oe = 1'b0;
            if (k == 12) data_in = (mode != 6'd0);
            if (k == 13) data_in = 1'b0;
            #(k == odd ? odd_high : half);
            if (k < 46) begin
                endat_clk = 1'b0;
                if (k + 1 >= 2 && k + 1 <= 7) begin data_oe = 1'b1; data_out = mode[7 - (k + 1)]; end
                if (k + 1 == 8) begin data_out = 1'b1; if (!oe_late) data_oe = 1'b0; end
                #(k + 1 == odd ? odd_low : half);
            end
        end
        if (rec < gap) begin
            #(rec) data_in = 1'b1;
            #(gap - rec);
        end else
            #(gap);
    end
endtask

initial begin
    if (!$value$plusargs("case=%d", which)) which = 0;
    #6250;
    case (which)
    1: begin transfer(6'b111000, 500, 500, 19, 250, 250, 0, 15000, 31000); transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000); end
    2: begin transfer(6'b111000, 500, 500, 20, 750, 250, 0, 15000, 31000); transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000); end
    3: begin transfer(6'b111000, 250, 250, 0, 0, 0, 0, 15000, 31000); transfer(6'b111000, 250, 2000, 0, 0, 0, 0, 15000, 31000); end
    4: begin
        transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000);
        data_oe = 1'b1;
        #250;
        transfer(6'b111000, 500, 500, 0, 0, 0, 1, 15000, 31000);
    end
    5: begin transfer(6'b111000, 500, 500, 0, 0, 0, 0, 5000, 10000); transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000); end
    6: begin transfer(6'b111000, 500, 500, 0, 0, 0, 0, 16000, 16250); transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000); end
    7: begin transfer(6'b000000, 500, 500, 0, 0, 0, 0, 15000, 20000); transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000); end
    8: begin transfer(6'b000111, 500, 500, 0, 0, 0, 0, 15000, 500000); transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000); end
    9: begin
        transfer(6'b000111, 2000, 2000, 0, 0, 0, 0, 15000, 1010000);
        transfer(6'b000111, 2000, 2000, 0, 0, 0, 0, 15000, 1010000);
        transfer(6'b000111, 2000, 2000, 0, 0, 0, 0, 15000, 1010000);
        transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000);
    end
    10: begin
        transfer(6'b000111, 2500, 2500, 0, 0, 0, 0, 15000, 1010000);
        transfer(6'b000111, 2500, 2500, 0, 0, 0, 0, 15000, 1010000);
        transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000);
    end
    default: begin transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000); transfer(6'b111000, 500, 500, 0, 0, 0, 0, 15000, 31000); end
    endcase
    #5000;
    $display("violations endat %0d", u_mon.violations(0));
    $finish;
end

endmodule

`default_nettype wire
