// emu_clocked.vh: the body of a wrapper for a device with one line in (the
// master's clock: SSI clock, BiSS-C MA, EnDat clock) and one data line out.
// Included inside the wrapper after emu_api.vh; the wrapper declares
//   localparam EMU_KIND = "ssi";       the library's emulator name
//   localparam EMU_PIN = "i_ssi_clk";  the input's name, for messages
//   wire emu_line_in = i_ssi_clk;      the master's line
// and drives its output from emu_line_out (registered, idle high).

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

// The input level last seen as 0 or 1 (idle high before reset ends).
reg line_level = 1'b1;
reg line_known = 1'b0;
reg x_reported = 1'b0;
reg emu_line_out = 1'b1;
integer pins_out;
reg [63:0] emu_cycle = 0;

always @(posedge i_emu_clk) begin
    if (emu_line_in === 1'b0 || emu_line_in === 1'b1) begin
        line_level = emu_line_in;
        line_known = 1'b1;
        x_reported = 1'b0;
    end else if (line_known && !x_reported) begin
        $display("ERROR: %m: X or Z on emulator input %0s at time %0t, emulator cycle %0d (held at %b, not read as data)",
                 EMU_PIN, $time, emu_cycle, line_level);
        x_reported = 1'b1;
        if (STOP_ON_X)
            $fatal(1, "emulator input %0s is X or Z", EMU_PIN);
    end
    pins_out = `EMU_STEP({31'd0, line_level});
    if (pins_out < 0)
        emu_fail("step");
    emu_cycle = emu_cycle + 1;
    if (pins_out[7])
        emu_show_violations(STOP_ON_VIOLATION);
    emu_line_out <= pins_out[0];
end
