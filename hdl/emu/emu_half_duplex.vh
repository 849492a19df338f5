// emu_half_duplex.vh: the body of a wrapper for a device on a half-duplex
// line (SAR58K24, Modbus RTU): several master pins in, the device's driver
// (level and enable) and the resolved line level at the master's end out.
// Included inside the wrapper after emu_api.vh; the wrapper declares
//   localparam EMU_KIND = "modbus";            the library's emulator name
//   localparam EMU_PINS = "{i_clr, i_line_en, i_line, i_trigger}";  names, for messages
//   localparam [3:0] EMU_IDLE = 4'b1011;       each input's level before reset
//   wire [3:0] emu_pins_in = {...};            the master's pins (library bit order)
// and drives its outputs from emu_out[0] (the device's driver level at the
// master's end), emu_out[1] (its enable there) and emu_out[2] (the resolved
// line level: the master's own driver, else the device's, else high),
// registered. X or Z on the driver enable (bit 2) reads as not driving, and
// the driver's level is then not read: one warning, never a protocol report;
// X or Z on another pin holds its last level (an error, STOP_ON_X).

`EMU_STR config_path;

initial begin
    config_path = CONFIG;
    if (CONFIG == "") begin
        if (!$value$plusargs({PLUSARG, "=%s"}, config_path))
            config_path = "";
    end
    emu_start(EMU_KIND, config_path, F_EMU_HZ, TRANSCRIPT);
end

`ifdef VERILATOR
final if (TRANSCRIPT != "" && emu_handle > 0)
    if (emu_write_transcript(emu_handle, TRANSCRIPT) < 0)
        $display("ERROR: %m: %0s", emu_last_error());
`endif

// The inputs last seen as 0 or 1 (their idle levels before reset ends).
reg [3:0] pins_level = EMU_IDLE;
reg pins_known = 1'b0;
reg x_reported = 1'b0;
reg [2:0] emu_out = 3'b101;
integer pins_out;
integer k;
reg [63:0] emu_cycle = 0;

always @(posedge i_emu_clk) begin
    if ((^emu_pins_in) === 1'b0 || (^emu_pins_in) === 1'b1) begin
        pins_level = emu_pins_in;
        pins_known = 1'b1;
        x_reported = 1'b0;
    end else begin
        for (k = 0; k < 4; k = k + 1)
            if (emu_pins_in[k] === 1'b0 || emu_pins_in[k] === 1'b1)
                pins_level[k] = emu_pins_in[k];
        // X or Z on the driver enable (bit 2) reads as not driving (as
        // before the master's reset), and the level of that driver (bit 1)
        // is then not read: one warning, never a protocol report.
        if (emu_pins_in[2] !== 1'b0 && emu_pins_in[2] !== 1'b1
                && ((^{emu_pins_in[3], emu_pins_in[0]}) === 1'b0 || (^{emu_pins_in[3], emu_pins_in[0]}) === 1'b1)) begin
            pins_level[2] = 1'b0;
            if (emu_pins_in[1] !== 1'b0 && emu_pins_in[1] !== 1'b1)
                pins_level[1] = EMU_IDLE[1];
            if (pins_known && !x_reported)
                $display("WARNING: %m: X or Z on the driver enable of %0s = %b at time %0t, emulator cycle %0d: read as not driving",
                         EMU_PINS, emu_pins_in, $time, emu_cycle);
            x_reported = 1'b1;
        end else if (pins_known && !x_reported) begin
            $display("ERROR: %m: X or Z on emulator input %0s = %b at time %0t, emulator cycle %0d (held at %b, not read as data)",
                     EMU_PINS, emu_pins_in, $time, emu_cycle, pins_level);
            x_reported = 1'b1;
            if (STOP_ON_X)
                $fatal(1, "emulator input %0s is X or Z", EMU_PINS);
        end
    end
    pins_out = `EMU_STEP({28'd0, pins_level});
    if (pins_out < 0)
        emu_fail("step");
    emu_cycle = emu_cycle + 1;
    if (pins_out[7])
        emu_show_violations(STOP_ON_VIOLATION);
    emu_out <= pins_out[2:0];
end
