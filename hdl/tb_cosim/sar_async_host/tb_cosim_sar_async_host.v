// tb_cosim_sar_async_host: sar_async_host closed-loop against the SAR58K24
// encoder emulator (hdl/emu/sar58k24_encoder_emu.v), no vectors. The
// emulator's encoders read random positions ([random] in the configuration);
// each operation the host starts a read (the next frame when timed, a
// trigger pulse in the handshake modes, BC AA Bx on the bus) and at o_done
// the core must have pulsed o_valid with exactly the position the emulator
// says it sent (u_emu.last_value), no error pulse, and in the handshake and
// bus modes the emulator must have sent exactly one frame per read. The
// second half of the reads first sets a random position of BITS bits with
// u_emu.set_position (the testbench owns the shaft from then on),
// and the frame must carry exactly that position.
//
// A pin-level monitor (hdl/emu/sar58k24_monitor.v) watches the host's D, DE,
// R, trigger and CLR: at each o_done it must have decoded one frame per
// read with the position the core read and the emulator sent, and the run
// fails on any timing rule it saw broken (character timing, command gap,
// turnaround, answer wait, T2).
//
// Plusargs: +sar58k24_emu_config=<scenario.toml>, +transactions=N (default
// 1000), +seed=S (the positions set in the second half),
// +flip_bit=K (planted failure: the comparison flips bit K of the core's
// output, so the run must fail), +sar58k24_monitor_transcript=FILE (the
// monitor's JSON transcript).

`include "sar58k24_monitor.v"

`timescale 1fs / 1fs
`default_nettype none

module tb_cosim_sar_async_host;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter MODE = 4;
parameter BITS = 16;
parameter GRAY = 0;
parameter PARITY = 0;
parameter TAG_ADDRESS = 1;
parameter ZERO_ANSWER = 1;
parameter CLOCKS_PER_BIT = 87;
parameter GAP_CLOCKS = 1305;
parameter STALE_CLOCKS = 0;
parameter TIMEOUT_CLOCKS = 50000;
parameter TRIGGER_LOW_CLOCKS = 100;
parameter CLR_LOW_CLOCKS = 200;

/* Harness parameters */
parameter F_SYS_HZ = 10000000;
parameter HALF_PERIOD_FS = 50_000_000;
parameter ADDRESS = 1;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_start = 1'b0;
wire o_busy, o_done, o_valid;
wire [31:0] o_position;
wire o_err_checksum, o_err_parity, o_err_frame, o_err_address, o_err_timeout, o_err_stale;
wire o_tx, o_tx_en, o_trigger, o_clr, bus;
wire enc_line, enc_line_en;

sar_async_host #(
    .MODE(MODE), .BITS(BITS), .GRAY(GRAY), .PARITY(PARITY), .TAG_ADDRESS(TAG_ADDRESS),
    .ZERO_ANSWER(ZERO_ANSWER), .CLOCKS_PER_BIT(CLOCKS_PER_BIT), .GAP_CLOCKS(GAP_CLOCKS),
    .STALE_CLOCKS(STALE_CLOCKS), .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .TRIGGER_LOW_CLOCKS(TRIGGER_LOW_CLOCKS), .CLR_LOW_CLOCKS(CLR_LOW_CLOCKS)
) dut (
    .i_clk(clk), .i_rst(rst),
    .i_start(i_start), .i_zero(1'b0), .i_address(ADDRESS[3:0]),
    .o_busy(o_busy), .o_done(o_done), .o_valid(o_valid), .o_position(o_position),
    .o_err_checksum(o_err_checksum), .o_err_parity(o_err_parity), .o_err_frame(o_err_frame),
    .o_err_address(o_err_address), .o_err_timeout(o_err_timeout), .o_err_stale(o_err_stale),
    .o_tx(o_tx), .o_tx_en(o_tx_en), .o_trigger(o_trigger), .o_clr(o_clr), .i_rx(bus)
);

// The emulator runs on the core's clock here; any clock dividing the baud
// rate within 0.5 % would do.
sar58k24_encoder_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_line(o_tx), .i_line_en(o_tx_en), .i_trigger(o_trigger), .i_clr(o_clr),
    .o_line(enc_line), .o_line_en(enc_line_en), .o_bus(bus)
);

// The pin-level monitor and protocol checker, on the same clock.
sar58k24_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("sar58k24_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_line(o_tx), .i_line_en(o_tx_en), .i_rx(bus), .i_trigger(o_trigger), .i_clr(o_clr)
);

// Each error pulse and the position at o_valid, caught between start and done.
reg seen_valid = 1'b0, seen_err = 1'b0;
reg [31:0] got_position = 0;
always @(posedge clk) begin
    if (i_start) begin
        seen_valid <= 1'b0;
        seen_err <= 1'b0;
    end else begin
        if (o_valid) begin
            seen_valid <= 1'b1;
            got_position <= o_position;
        end
        if (o_err_checksum || o_err_parity || o_err_frame || o_err_address || o_err_timeout || o_err_stale)
            seen_err <= 1'b1;
    end
end

localparam COUNTED = (MODE >= 2);
`include "emu_random.vh"
integer transactions, seed, flip_bit, n, waited;
reg [63:0] sent, got, count_before, position, mon_before;
localparam [63:0] MASK = (64'd1 << BITS) - 1;

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    repeat (4) @(posedge clk);
    for (n = 0; n < transactions; n = n + 1) begin
        if (2 * n >= transactions) begin
            position = random64(0) & MASK;
            u_emu.set_position(0, position);
        end
        count_before = u_emu.count(0);
        mon_before = u_mon.count(0);
        i_start <= 1'b1;
        @(posedge clk);
        i_start <= 1'b0;
        waited = 0;
        @(posedge clk);
        while (!o_done) begin
            @(posedge clk);
            waited = waited + 1;
            if (waited > 2 * TIMEOUT_CLOCKS + 100000)
                $fatal(1, "read %0d: no o_done", n);
        end
        @(posedge clk);
        sent = u_emu.last_value(0);
        got = got_position;
        if (flip_bit >= 0) got = got ^ (64'd1 << flip_bit);
        if (COUNTED && u_emu.count(0) != count_before + 1)
            $fatal(1, "read %0d at %0t: the emulator sent %0d frames for one read", n, $time, u_emu.count(0) - count_before);
        if (!seen_valid || seen_err || got != sent)
            $fatal(1, "read %0d at %0t: core read %0d (valid %b, an error pulse %b), the emulator sent %0d",
                   n, $time, got, seen_valid, seen_err, sent);
        // The monitor decoded the same frame off the pins.
        if ((COUNTED ? u_mon.count(0) != mon_before + 1 : u_mon.count(0) <= mon_before) || u_mon.last_value(0) != got_position)
            $fatal(1, "read %0d at %0t: the monitor decoded %0d frames, the last %0d; the core read %0d",
                   n, $time, u_mon.count(0) - mon_before, u_mon.last_value(0), got_position);
        if (2 * n >= transactions && sent != position)
            $fatal(1, "read %0d at %0t: the testbench set position %0d, the encoder sent %0d", n, $time, position, sent);
        while (o_busy) @(posedge clk);
        // The host's o_done comes in the middle of the last stop bit, while
        // the encoder still drives its line: a host that starts the next
        // command at once overlaps it (the emulator reports two drivers).
        // Wait the rest of that bit and the cable, as a bus master should.
        repeat (2 * CLOCKS_PER_BIT) @(posedge clk);
    end
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the core broke %0d rule(s) of the seed seen by the emulator, %0d seen by the monitor (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_sar_async_host: %0d reads, every o_position equal to the emulator's and to the monitor's", transactions);
    $finish;
end

endmodule

`default_nettype wire
