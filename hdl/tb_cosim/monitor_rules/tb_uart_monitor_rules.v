// tb_uart_monitor_rules: a hand-written Modbus RTU master and SAR58K24 bus
// host, with hand-written answers on their receivers (plain stimulus, no
// core, no emulator), in front of modbus_monitor and sar58k24_monitor.
// +case=N picks what they do; each case breaks one timing rule once, or none
// (case 0). Both lines run at 15625 baud (64 us bits) on a 1 MHz monitor
// clock; Modbus with even parity (t1.5 = 1056 us, t3.5 = 2464 us), the
// SAR58K24 without; both answer timeouts 5000 us (the test's TOML).
//
//   0 clean: Modbus 01 03 00 00 00 02 C4 0B, the answer 01 03 04 <4 bytes>
//     <CRC> 3000 us later, the same request 3000 us after it; SAR58K24
//     BC AA B1, the answer FF B1 <4 bytes> <sum> 200 us later, BC AA B1
//     again 2000 us after it, a 20 us trigger pulse and a 20 us CLR pulse.
//   1 Modbus: bit 3 of the third request character 80 us (a 64 us bit)
//   2 Modbus: the parity bit of the third request character wrong
//   3 Modbus: 1200 us of silence between the fourth and fifth characters
//   4 Modbus: the second request 1000 us after the answer (t3.5)
//   5 Modbus: DE held 500 us after the first request
//   6 Modbus: DE on 2 bits into the answer's last character
//   7 Modbus: the first request to station 9 (no answer), the next 3000 us later
//   8 SAR: bit 3 of AA 80 us
//   9 SAR: 1200 us between BC and AA (the encoder's 15 bits: 960 us)
//  10 SAR: DE held 500 us after the first command
//  11 SAR: DE on 2 bits into the answer's last character
//  12 SAR: the first command to encoder 2 (no answer), the next 3000 us later
//  13 SAR: a trigger pulse of 5 us (T2 >= 10 us)
//  14 SAR: the trigger's falling edge inside a character of the answer
//
// Plusargs: +case=N, +modbus_monitor_config=FILE, +sar58k24_monitor_config=FILE,
// +modbus_monitor_transcript=FILE, +sar58k24_monitor_transcript=FILE.
// Prints "violations modbus <n> sar <m>" at the end.

`timescale 1ns / 1ps
`include "modbus_monitor.v"
`include "sar58k24_monitor.v"
`default_nettype none

module tb_uart_monitor_rules;

reg clk = 1'b0;
always #500 clk = ~clk;

reg mb_d = 1'b1, mb_de = 1'b0, mb_r = 1'b1;
reg s_d = 1'b1, s_de = 1'b0, s_r = 1'b1, s_trig = 1'b1, s_clr = 1'b1;

modbus_monitor #(.F_MON_HZ(1000000)) u_mb (.i_mon_clk(clk), .i_line(mb_d), .i_line_en(mb_de), .i_rx(mb_r));
sar58k24_monitor #(.F_MON_HZ(1000000)) u_sar (.i_mon_clk(clk), .i_line(s_d), .i_line_en(s_de), .i_rx(s_r), .i_trigger(s_trig), .i_clr(s_clr));

integer which, km, ks;
localparam integer BIT = 64000;

function [15:0] crc16(input [63:0] bytes, input integer n);
    integer i, j;
    reg [15:0] c;
    begin
        c = 16'hFFFF;
        for (i = 0; i < n; i = i + 1) begin
            c = c ^ {8'd0, bytes[8 * (n - 1 - i) +: 8]};
            for (j = 0; j < 8; j = j + 1)
                c = c[0] ? (c >> 1) ^ 16'hA001 : c >> 1;
        end
        crc16 = c;
    end
endfunction

// One Modbus character (even parity) on `mb_d` (host) or `mb_r` (answer);
// bit `odd` (0 start .. 10 stop) lasts `odd_len`, `flip` inverts the parity bit.
task mb_char(input [7:0] v, input host, input integer odd, input integer odd_len, input flip);
    reg l;
    begin
        for (km = 0; km < 11; km = km + 1) begin
            l = km == 0 ? 1'b0 : (km <= 8 ? v[km - 1] : (km == 9 ? ((^v) ^ flip) : 1'b1));
            if (host) mb_d = l; else mb_r = l;
            #(km == odd ? odd_len : BIT);
        end
    end
endtask

task s_char(input [7:0] v, input host, input integer odd, input integer odd_len);
    reg l;
    begin
        for (ks = 0; ks < 10; ks = ks + 1) begin
            l = ks == 0 ? 1'b0 : (ks <= 8 ? v[ks - 1] : 1'b1);
            if (host) s_d = l; else s_r = l;
            #(ks == odd ? odd_len : BIT);
        end
    end
endtask

reg [63:0] req;
reg [15:0] c;
reg [7:0] sum;
integer i, is;  // one loop variable per host: they run in parallel

// The Modbus master: request 1, answer, request 2, answer.
task mb_request(input [7:0] station, input integer bad_char, input integer gap_at, input integer hold);
    begin
        req = {station, 8'h03, 8'h00, 8'h00, 8'h00, 8'h02, 16'h0};
        c = crc16(req[63:16], 6);
        req[15:0] = {c[7:0], c[15:8]};
        mb_de = 1'b1;
        #(BIT);
        for (i = 0; i < 8; i = i + 1) begin
            if (i == 4 && gap_at) #(1200000);
            mb_char(req[8 * (7 - i) +: 8], 1'b1, (i == 2 && bad_char == 1) ? 4 : -1, 80000, i == 2 && bad_char == 2);
        end
        #(hold);
        mb_de = 1'b0;
    end
endtask

task mb_answer(input integer de_inside);
    begin
        req = {8'h01, 8'h03, 8'h04, 8'h12, 8'h34, 8'h56, 8'h78, 8'h00};
        c = crc16(req[63:8], 7);
        for (i = 0; i < 9; i = i + 1) begin
            if (i == 8 && de_inside) begin
                // 0xFF: after the start bit the line is high, so only the
                // switch-on is wrong; DE on for the third bit (inline, no fork).
                for (km = 0; km < 11; km = km + 1) begin
                    mb_r = km == 0 ? 1'b0 : 1'b1;
                    mb_de = km == 2;
                    #(BIT);
                end
            end else
                mb_char(i < 7 ? req[8 * (7 - i) +: 8] : (i == 7 ? c[7:0] : c[15:8]), 1'b0, -1, 0, 1'b0);
        end
    end
endtask

task sar_command(input [3:0] addr, input integer bad, input integer gap, input integer hold);
    begin
        s_de = 1'b1;
        #(BIT);
        s_char(8'hBC, 1'b1, -1, 0);
        if (gap) #(1200000);
        s_char(8'hAA, 1'b1, bad ? 4 : -1, 80000);
        s_char({4'hB, addr}, 1'b1, -1, 0);
        #(hold);
        s_de = 1'b0;
    end
endtask

task sar_answer(input integer de_inside, input integer trig_inside);
    reg [7:0] b;
    begin
        sum = 8'hFF + 8'hB1 + 8'h01 + 8'h02 + 8'h03 + 8'h04;
        for (is = 0; is < 7; is = is + 1) begin
            b = is == 0 ? 8'hFF : (is == 1 ? 8'hB1 : (is == 6 ? sum : is - 1));
            if (is == 6 && (de_inside || trig_inside)) begin
                // DE on (or the trigger low) for the third bit of the last character.
                for (ks = 0; ks < 10; ks = ks + 1) begin
                    s_r = ks == 0 ? 1'b0 : (ks <= 8 ? b[ks - 1] : 1'b1);
                    if (de_inside) s_de = ks == 2; else s_trig = ks != 2;
                    #(BIT);
                end
            end else
                s_char(b, 1'b0, -1, 0);
        end
    end
endtask

initial begin
    if (!$value$plusargs("case=%d", which)) which = 0;
    #(10 * BIT);
    fork
        begin
            mb_request(which == 7 ? 8'd9 : 8'd1, which == 1 ? 1 : (which == 2 ? 2 : 0), which == 3, which == 5 ? 500000 : 0);
            if (which != 7) begin
                #(3000000);
                mb_answer(which == 6);
            end
            #(which == 4 ? 1000000 : 3000000);
            mb_request(8'd1, 0, 0, 0);
            #(3000000);
            mb_answer(0);
            #(4000000);
        end
        begin
            sar_command(which == 12 ? 4'd2 : 4'd1, which == 8, which == 9, which == 10 ? 500000 : 0);
            if (which != 12) begin
                #(200000);
                sar_answer(which == 11, which == 14);
            end
            #(which == 12 ? 3000000 : 2000000);
            s_trig = 1'b0;
            #(which == 13 ? 5000 : 20000);
            s_trig = 1'b1;
            #(1000000);
            s_clr = 1'b0;
            #(20000);
            s_clr = 1'b1;
            #(1000000);
            sar_command(4'd1, 0, 0, 0);
            #(200000);
            sar_answer(0, 0);
            #(4000000);
        end
    join
    $display("violations modbus %0d sar %0d", u_mb.violations(0), u_sar.violations(0));
    $display("transactions modbus %0d sar %0d", u_mb.count(0), u_sar.count(0));
    $finish;
end

endmodule

`default_nettype wire
