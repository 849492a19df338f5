// tb_cosim_modbus_master: modbus_master closed-loop against the Modbus RTU
// device emulator (hdl/emu/modbus_device_emu.v), no vectors. The emulator's
// device answers random positions ([random] in the configuration); each
// poll the master reads COUNT registers from station ADDRESS (function 03),
// and at o_done the core must have pulsed o_valid with exactly the value of
// the device's answer (u_emu.last_value), no error
// pulse, and the device must have seen and answered exactly one request.
// The second half of the polls first sets a random position of 16 x COUNT
// bits with u_emu.set_position, and the answer must carry it
// (binary, or Gray for a Gray device).
//
// A pin-level monitor (hdl/emu/modbus_monitor.v) watches the master's D, DE
// and R: before each poll it must have decoded every earlier poll with the
// registers the core read and the device answered, and the run fails on any
// timing rule it saw broken (t1.5, t3.5, character timing, turnaround,
// response timeout).
//
// Plusargs: +modbus_emu_config=<scenario.toml>, +transactions=N (default
// 1000), +seed=S (the positions set in the second half), +flip_bit=K
// (planted failure: the comparison flips bit K of the core's output, so the
// run must fail), +modbus_monitor_transcript=FILE (the monitor's JSON
// transcript).

`include "modbus_monitor.v"

`timescale 1fs / 1fs
`default_nettype none

module tb_cosim_modbus_master;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter CLOCKS_PER_BIT = 16;
parameter PARITY = 0;
parameter T15_CLOCKS = 240;
parameter T35_CLOCKS = 560;
parameter TIMEOUT_CLOCKS = 50000;

/* Harness parameters */
parameter F_SYS_HZ = 250000;
parameter HALF_PERIOD_FS = 2_000_000_000;
parameter ADDRESS = 1;
parameter COUNT = 2;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_start = 1'b0;
wire o_busy, o_done, o_valid;
wire [31:0] o_value;
wire [7:0] o_station, o_exception;
wire o_err_parity, o_err_framing, o_err_gap, o_err_length, o_err_crc, o_err_address, o_err_exception, o_err_function, o_err_count, o_err_timeout;
wire o_tx, o_tx_en, bus, dev_line, dev_line_en;

modbus_master #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT), .PARITY(PARITY), .T15_CLOCKS(T15_CLOCKS),
    .T35_CLOCKS(T35_CLOCKS), .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS)
) dut (
    .i_clk(clk), .i_rst(rst),
    .i_start(i_start), .i_query(1'b0), .i_write(1'b0), .i_address(ADDRESS[7:0]), .i_new_address(8'd0), .i_count(COUNT[1:0]),
    .o_busy(o_busy), .o_done(o_done), .o_valid(o_valid), .o_value(o_value),
    .o_station(o_station), .o_exception(o_exception),
    .o_err_parity(o_err_parity), .o_err_framing(o_err_framing), .o_err_gap(o_err_gap),
    .o_err_length(o_err_length), .o_err_crc(o_err_crc), .o_err_address(o_err_address),
    .o_err_exception(o_err_exception), .o_err_function(o_err_function),
    .o_err_count(o_err_count), .o_err_timeout(o_err_timeout),
    .o_tx(o_tx), .o_tx_en(o_tx_en), .i_rx(bus)
);

// The emulator runs on the core's clock here; any clock dividing the baud
// rate within 0.5 % would do.
modbus_device_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_line(o_tx), .i_line_en(o_tx_en),
    .o_line(dev_line), .o_line_en(dev_line_en), .o_bus(bus)
);

// The pin-level monitor and protocol checker, on the same clock.
modbus_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("modbus_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_line(o_tx), .i_line_en(o_tx_en), .i_rx(bus)
);

reg seen_valid = 1'b0, seen_err = 1'b0;
reg [31:0] got_value = 0;
always @(posedge clk) begin
    if (i_start) begin
        seen_valid <= 1'b0;
        seen_err <= 1'b0;
    end else begin
        if (o_valid) begin
            seen_valid <= 1'b1;
            got_value <= o_value;
        end
        if (o_err_parity || o_err_framing || o_err_gap || o_err_length || o_err_crc || o_err_address || o_err_exception || o_err_function || o_err_count || o_err_timeout)
            seen_err <= 1'b1;
    end
end

`include "emu_random.vh"
integer transactions, seed, flip_bit, n, waited;
reg [63:0] sent, got, count_before, position;
localparam [63:0] MASK = (64'd1 << (16 * COUNT)) - 1;

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
        i_start <= 1'b1;
        @(posedge clk);
        i_start <= 1'b0;
        waited = 0;
        @(posedge clk);
        while (!o_done) begin
            @(posedge clk);
            waited = waited + 1;
            if (waited > 2 * TIMEOUT_CLOCKS + 40 * T35_CLOCKS + 400 * CLOCKS_PER_BIT)
                $fatal(1, "poll %0d: no o_done", n);
        end
        @(posedge clk);
        sent = u_emu.last_value(0);
        got = got_value;
        if (flip_bit >= 0) got = got ^ (64'd1 << flip_bit);
        if (u_emu.count(0) != count_before + 1 || u_emu.last_status(0, "answered") != 1)
            $fatal(1, "poll %0d at %0t: the device saw %0d requests (answered: %0d)", n, $time, u_emu.count(0) - count_before, u_emu.last_status(0, "answered"));
        if (!seen_valid || seen_err || got != sent)
            $fatal(1, "poll %0d at %0t: core read %0d (valid %b, an error pulse %b), the device answered %0d",
                   n, $time, got, seen_valid, seen_err, sent);
        // The monitor decoded the same poll off the pins (the one in progress counts).
        if (u_mon.count(0) != n + 1 || u_mon.last_status(0, "valid") != 1 || u_mon.last_value(0) != got_value)
            $fatal(1, "poll %0d at %0t: the monitor decoded %0d polls, valid %0d, value %0d; the core read %0d",
                   n, $time, u_mon.count(0), u_mon.last_status(0, "valid"), u_mon.last_value(0), got_value);
        if (2 * n >= transactions && sent != position && sent != (position ^ (position >> 1)))
            $fatal(1, "poll %0d at %0t: the testbench set position %0d, the device answered %0d", n, $time, position, sent);
        while (o_busy) @(posedge clk);
    end
    if (u_emu.violations(0) != 0 || u_mon.violations(0) != 0)
        $fatal(1, "the core broke %0d rule(s) of the seed seen by the emulator, %0d seen by the monitor (PROTOCOL VIOLATION lines above)", u_emu.violations(0), u_mon.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_modbus_master: %0d polls, every o_value equal to the device's answer and to the monitor's", transactions);
    $finish;
end

endmodule

`default_nettype wire
