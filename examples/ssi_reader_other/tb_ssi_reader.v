// tb_ssi_reader: ssi_reader closed-loop against encoder-tb's SSI encoder
// emulator. Copy this file, encoder.toml and the Makefile next to your own
// reader, change the instance below, and run `make SIM=icarus` or
// `make SIM=verilator`.
//
// Each read: a random position goes into the emulator, the reader is asked,
// and its value must equal what the emulator says it stored and sent.

`timescale 1ns / 1ps
`default_nettype none

module tb_ssi_reader;

reg clk = 1'b0;
always #62.5 clk = ~clk;             // 8 MHz: the reader's clock and the emulator's

reg reset_n = 1'b0;
reg read_req = 1'b0;
wire [11:0] value;
wire value_ok, sclk, sdata;

ssi_reader #(.WIDTH(12), .HALF(16), .LEAD(40), .REST(240)) dut (   // 250 kHz, T_cs 5 us, 30 us rest
    .clk(clk), .reset_n(reset_n), .read_req(read_req),
    .value(value), .value_ok(value_ok), .sclk(sclk), .sdata(sdata)
);

ssi_encoder_emu #(.CONFIG("encoder.toml"), .F_EMU_HZ(8000000), .TRANSCRIPT("build/transcript.json")) u_emu (
    .i_emu_clk(clk), .i_ssi_clk(sclk), .o_ssi_data(sdata)
);

// Random numbers that are the same in both simulators (emu_random.vh says
// why not $random).
`include "emu_random.vh"
integer reads, n, seed;
reg [63:0] position;

initial begin
    if (!$value$plusargs("reads=%d", reads)) reads = 1000;
    seed = 7;
    random_seed(seed);
    repeat (3) @(posedge clk);
    reset_n <= 1'b1;
    for (n = 0; n < reads; n = n + 1) begin
        position = random32(0) & 12'hFFF;
        u_emu.set_position(0, position);
        @(posedge clk) read_req <= 1'b1;
        @(posedge clk) read_req <= 1'b0;
        @(posedge clk);
        while (!value_ok) @(posedge clk);
        if (value !== u_emu.last_value(0) || value !== position[11:0])
            $fatal(1, "read %0d at %0t ns: reader %0d, emulator sent %0d (set %0d)", n, $time, value, u_emu.last_value(0), position);
    end
    if (u_emu.violations(0) != 0)
        $fatal(1, "the reader broke %0d timing rule(s) of SSI (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    $display("PASS ssi_reader: %0d reads equal to what the emulator sent", reads);
    $finish;
end

endmodule

`default_nettype wire
