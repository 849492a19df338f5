// emu_monitor.vh: the body of a pin-level monitor (hdl/emu/<proto>_monitor.v):
// input-only, it samples the master's line pins on each rising edge of
// i_mon_clk and hands them to the monitor of the library (cosim/src/monitor/),
// which decodes the transactions and checks the master's timing. Included
// inside the monitor module after emu_api.vh; the module declares
//   localparam EMU_KIND = "ssi_monitor";            the library's monitor name
//   localparam MON_PIN_NAMES = "i_ssi_clk, i_ssi_data";  pin 0, 1, ... for messages
//   localparam [7:0] MON_IDLE = 8'b011;              each pin's level before reset ends
//   wire [7:0] mon_pins_now = {6'd0, i_ssi_data, i_ssi_clk};
// and the parameters CONFIG, PLUSARG, F_MON_HZ, TRANSCRIPT, TRANSCRIPT_PLUSARG,
// STOP_ON_X and STOP_ON_VIOLATION.

`EMU_STR config_path;
`EMU_STR transcript_path;

initial begin
    config_path = CONFIG;
    if (CONFIG == "") begin
        if (!$value$plusargs({PLUSARG, "=%s"}, config_path))
            config_path = "";
    end
    transcript_path = TRANSCRIPT;
    if (TRANSCRIPT == "") begin
        if (!$value$plusargs({TRANSCRIPT_PLUSARG, "=%s"}, transcript_path))
            transcript_path = "";
    end
    emu_start(EMU_KIND, config_path, F_MON_HZ, transcript_path);
end

`ifdef VERILATOR
final if (transcript_path != "" && emu_handle > 0)
    if (emu_write_transcript(emu_handle, transcript_path) < 0)
        $display("ERROR: %m: %0s", emu_last_error());
`endif

// Each input's last 0/1 level (the line's idle level before the first).
reg [7:0] pin_level = MON_IDLE;
reg [7:0] pin_known = 8'd0;
reg [7:0] x_reported = 8'd0;
integer pins_out;
integer k;
reg [63:0] mon_cycle = 0;

always @(posedge i_mon_clk) begin
    if ((^mon_pins_now) === 1'b0 || (^mon_pins_now) === 1'b1) begin
        // Every pin 0 or 1, as on almost every cycle: all at once (the
        // loop below, a bit at a time, was most of a closed loop's time in
        // Icarus).
        pin_level = mon_pins_now;
        pin_known = 8'hff;
        x_reported = 8'd0;
    end else for (k = 0; k < 8; k = k + 1) begin
        if (mon_pins_now[k] === 1'b0 || mon_pins_now[k] === 1'b1) begin
            pin_level[k] = mon_pins_now[k];
            pin_known[k] = 1'b1;
            x_reported[k] = 1'b0;
        end else if (pin_known[k] && !x_reported[k]) begin
            $display("ERROR: %m: X or Z on monitor input %0d of (%0s) at time %0t, monitor cycle %0d (held at %b, not read as data)",
                     k, MON_PIN_NAMES, $time, mon_cycle, pin_level[k]);
            x_reported[k] = 1'b1;
            if (STOP_ON_X)
                $fatal(1, "monitor input %0d of (%0s) is X or Z", k, MON_PIN_NAMES);
        end
    end
    pins_out = `EMU_STEP({24'd0, pin_level});
    if (pins_out < 0)
        emu_fail("step");
    mon_cycle = mon_cycle + 1;
    if (pins_out[7])
        emu_show_violations(STOP_ON_VIOLATION);
end
