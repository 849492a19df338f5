// tb_half_duplex_rules: a hand-written T-format host and ESL host (plain
// stimulus, no core, no emulator) in front of tformat_monitor and
// esl_monitor. +case=N picks what the hosts do; each case breaks one timing
// rule of seed 002 (T-format) or seed 000 (ESL) once, or none (case 0), so
// the monitors' PROTOCOL VIOLATION lines and counts show each rule firing,
// and staying silent on a clean host.
//
//   0 clean: T-format a Data ID 0 request, then a Data ID D request (CF ADF
//     CRC) 100 us later; ESL a Data ID 1 readout, then a register read (E)
//     20 us later. The encoders' receivers (i_*_rx) stay idle high.
//   1 T-format: bit 2 of the control field 600 ns (+-100 ns jitter)
//   2 T-format: 2 bits of idle line between the Data ID D request's fields
//   3 T-format: DE held 2 us after the delimiter (1.5 us allowed)
//   4 T-format: the second request 2 bits into an answer character on R
//   5 T-format: two reset requests (Data ID 7) 100 us apart (40 ms)
//   6 ESL: bit 1 of the control field 150 ns (3 % of 10 Mbps)
//   7 ESL: 1.5 bits of idle line inside the readout request
//   8 ESL: the readout request without its CRC frame
//   9 ESL: DE held 2 us after the request (1 us allowed)
//  10 ESL: Data ID B once, then the readout (B takes 8 in a row)
//  11 ESL: the second request 2 bits into an answer character on RO
//
// Plusargs: +case=N, +tformat_monitor_config=FILE, +esl_monitor_config=FILE,
// +tformat_monitor_transcript=FILE, +esl_monitor_transcript=FILE.
// Prints "violations tformat <n> esl <m>" and the transaction counts at the end.

`timescale 1ns / 1ps
`include "tformat_monitor.v"
`include "esl_monitor.v"
`default_nettype none

module tb_half_duplex_rules;

reg clk20 = 1'b0;    // 20 MHz: the T-format monitor's clock (8 cycles a bit)
reg clk80 = 1'b0;    // 80 MHz: the ESL monitor's clock (8 cycles a bit)
always #25 clk20 = ~clk20;
always #6.25 clk80 = ~clk80;

reg tf_d = 1'b1, tf_de = 1'b0, tf_r = 1'b1;
reg esl_d = 1'b1, esl_de = 1'b0, esl_r = 1'b1;

tformat_monitor #(.F_MON_HZ(20000000)) u_tf (.i_mon_clk(clk20), .i_tf_data(tf_d), .i_tf_data_oe(tf_de), .i_tf_rx(tf_r));
esl_monitor #(.F_MON_HZ(80000000)) u_esl (.i_mon_clk(clk80), .i_esl_data(esl_d), .i_esl_data_oe(esl_de), .i_esl_rx(esl_r));

integer which, kt, ke;  // one loop variable per host: they run in parallel

// One T-format field (400 ns bits) of `value`; bit `odd` (0 start .. 9
// delimiter) lasts `odd_len` ns.
task tf_field(input [7:0] value, input integer odd, input integer odd_len);
    begin
        for (kt = 0; kt < 10; kt = kt + 1) begin
            tf_d = kt == 0 ? 1'b0 : (kt == 9 ? 1'b1 : value[kt - 1]);
            #(kt == odd ? odd_len : 400);
        end
    end
endtask

// One ESL frame (100 ns bits), likewise.
task esl_field(input [7:0] value, input integer odd, input integer odd_len);
    begin
        for (ke = 0; ke < 10; ke = ke + 1) begin
            esl_d = ke == 0 ? 1'b0 : (ke == 9 ? 1'b1 : value[ke - 1]);
            #(ke == odd ? odd_len : 100);
        end
    end
endtask

// The request bytes, first field in the top byte (the test computes them
// with the model: model::tformat::frames::request, model::esl::frames::request):
// +tf_id0=<CF of Data ID 0> +tf_id7=<CF of Data ID 7> +tf_idd=<CF ADF CRC of
// a Data ID D read>, +esl_id1=<CF CRC of Data ID 1 to address 3>
// +esl_idb=<CF CRC of Data ID B> +esl_ide=<CF ADF CRC of a register read>.
reg [7:0] tf_id0, tf_id7;
reg [23:0] tf_idd, esl_ide;
reg [15:0] esl_id1, esl_idb;

initial begin
    if (!$value$plusargs("case=%d", which)) which = 0;
    if (!$value$plusargs("tf_id0=%h", tf_id0) || !$value$plusargs("tf_id7=%h", tf_id7) || !$value$plusargs("tf_idd=%h", tf_idd)
        || !$value$plusargs("esl_id1=%h", esl_id1) || !$value$plusargs("esl_idb=%h", esl_idb) || !$value$plusargs("esl_ide=%h", esl_ide))
        $fatal(1, "give +tf_id0 +tf_id7 +tf_idd +esl_id1 +esl_idb +esl_ide (hex request bytes)");
    #5000;
    fork
        begin
            // T-format: the first request.
            tf_de = 1'b1;
            tf_field(which == 5 ? tf_id7 : tf_id0, which == 1 ? 2 : -1, 600);
            #(which == 3 ? 2000 : 0);
            tf_de = 1'b0;
            if (which == 4) begin
                // An answer character on R 3 us later, and the next request 2 bits into it.
                #3000 tf_r = 1'b0;
                #400 tf_r = 1'b1;
                #400;
            end else
                #100000;
            tf_de = 1'b1;
            if (which == 5) begin
                tf_field(tf_id7, -1, 400);
            end else begin
                tf_field(tf_idd[23:16], -1, 400);
                #(which == 2 ? 800 : 0);
                tf_field(tf_idd[15:8], -1, 400);
                tf_field(tf_idd[7:0], -1, 400);
            end
            tf_de = 1'b0;
        end
        begin
            // ESL: the first request.
            esl_de = 1'b1;
            esl_field(which == 10 ? esl_idb[15:8] : esl_id1[15:8], which == 6 ? 1 : -1, 150);
            #(which == 7 ? 150 : 0);
            if (which != 8)
                esl_field(which == 10 ? esl_idb[7:0] : esl_id1[7:0], -1, 100);
            #(which == 9 ? 2000 : 0);
            esl_de = 1'b0;
            if (which == 11) begin
                #2000 esl_r = 1'b0;
                #100 esl_r = 1'b1;
                #100;
            end else
                #20000;
            esl_de = 1'b1;
            if (which == 10) begin
                esl_field(esl_id1[15:8], -1, 100);
                esl_field(esl_id1[7:0], -1, 100);
            end else begin
                esl_field(esl_ide[23:16], -1, 100);
                esl_field(esl_ide[15:8], -1, 100);
                esl_field(esl_ide[7:0], -1, 100);
            end
            esl_de = 1'b0;
        end
    join
    #50000;
    $display("violations tformat %0d esl %0d", u_tf.violations(0), u_esl.violations(0));
    $display("transactions tformat %0d esl %0d", u_tf.count(0), u_esl.count(0));
    $finish;
end

endmodule

`default_nettype wire
