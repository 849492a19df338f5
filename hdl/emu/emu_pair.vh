// emu_pair.vh: the body of a wrapper for a device on a half-duplex
// pair (EnDat: a clock and the data pair; T-format and ESL: the data pair
// alone). Included inside the wrapper after emu_api.vh; the wrapper declares
//   localparam EMU_KIND = "endat";
//   localparam EMU_PIN0 = "i_endat_clk"; EMU_PIN1 = "i_endat_data"; EMU_PIN2 = "i_endat_data_oe";  for messages
//   wire emu_clk_in = i_endat_clk;      the master's clock (1'b1 when there is none)
//   wire emu_data_in = i_endat_data;    the level the master's driver puts on the pair
//   wire emu_oe_in = i_endat_data_oe;   the master's driver enable
// X or Z on the driver enable reads as 0 (the master not driving: one
// warning, never a protocol report), and the data of a driver that is not on
// is not read; X or Z on the clock or on driven data holds the last level.
// and drives its outputs from emu_data_out (the device's level at the master's
// end of the cable, the fail-safe idle high while it does not drive) and
// emu_oe_out (its driver enable there), both registered. No tristate: the
// master reads emu_data_out while its own driver is off.

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

// Each input's last 0/1 level (idle: clock high, data high, driver off).
reg [2:0] pin_level = 3'b011;
reg [2:0] pin_known = 3'b000;
reg [2:0] x_reported = 3'b000;
reg emu_data_out = 1'b1;
reg emu_oe_out = 1'b0;
integer pins_out;
integer k;
reg [63:0] emu_cycle = 0;
wire [2:0] pins_now = {emu_oe_in, emu_data_in, emu_clk_in};

always @(posedge i_emu_clk) begin
    if ((^pins_now) === 1'b0 || (^pins_now) === 1'b1) begin
        // Every pin 0 or 1, as on almost every cycle: all at once (Icarus
        // runs the loop below a bit at a time).
        pin_level = pins_now;
        pin_known = 3'b111;
        x_reported = 3'b000;
    end else for (k = 0; k < 3; k = k + 1) begin
        if (pins_now[k] === 1'b0 || pins_now[k] === 1'b1) begin
            pin_level[k] = pins_now[k];
            pin_known[k] = 1'b1;
            x_reported[k] = 1'b0;
        end else if (k == 2) begin
            // X or Z on the driver enable: the master does not drive (as
            // before its reset); one warning, never a protocol report.
            pin_level[2] = 1'b0;
            if (pin_known[2] && !x_reported[2])
                $display("WARNING: %m: X or Z on the driver enable %0s at time %0t, emulator cycle %0d: read as 0, the master not driving",
                         EMU_PIN2, $time, emu_cycle);
            x_reported[2] = 1'b1;
        end else if (k == 1 && pins_now[2] !== 1'b0 && pins_now[2] !== 1'b1) begin
            // The data of a driver whose enable is X or Z is not read.
            pin_level[1] = 1'b1;
        end else if (pin_known[k] && !x_reported[k]) begin
            $display("ERROR: %m: X or Z on emulator input %0s at time %0t, emulator cycle %0d (held at %b, not read as data)",
                     k == 0 ? EMU_PIN0 : (k == 1 ? EMU_PIN1 : EMU_PIN2), $time, emu_cycle, pin_level[k]);
            x_reported[k] = 1'b1;
            if (STOP_ON_X)
                $fatal(1, "emulator input %0s is X or Z", k == 0 ? EMU_PIN0 : (k == 1 ? EMU_PIN1 : EMU_PIN2));
        end
    end
    pins_out = `EMU_STEP({29'd0, pin_level});
    if (pins_out < 0)
        emu_fail("step");
    emu_cycle = emu_cycle + 1;
    if (pins_out[7])
        emu_show_violations(STOP_ON_VIOLATION);
    emu_data_out <= pins_out[0];
    emu_oe_out <= pins_out[1];
end
