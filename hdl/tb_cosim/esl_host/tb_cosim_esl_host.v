// tb_cosim_esl_host: esl_host closed-loop against the ESL encoder emulator
// (hdl/emu/esl_encoder_emu.v), no vectors. Each operation: a random position
// (24-bit ABS, 16-bit ABM), random ALM flags (xc, mt, led, lis, overspeed,
// mem, st, uv, ov, each set on its own) and a random DD0 in the emulator,
// then one readout with a random Data ID of 1, 2, 4, 5, 6, 8, 9, A (safety
// and non-safety, Table 12). The fault set, each scheduled in the
// emulator's own tables (schedule_fault): every 16th answer one data bit of
// one field after CF1 is flipped (the host must flag o_err_crc1, o_err_crc2
// or o_err_cf); every 37th answer is cut short (the host must flag an error);
// every 29th safety answer, once the host holds a sequence reference, has
// SC1 or SC2 jump (the host must flag o_err_seq and nothing else). Otherwise
// at o_done the host's o_abs, o_abm, o_alm1, o_alm2 and o_sf must equal what
// the emulator says it sent (u_emu.last_value / last_status), which must
// equal what was set, with no error pulse; one answer per request.
//
// A pin-level monitor (hdl/emu/esl_monitor.v) watches the host's DI, DE and
// RO: after every operation it must have flagged an error exactly when the
// host did (o_err_seq as its `sequence`), and otherwise decoded the host's
// ABS, ABM and ALM1 off the line; it must see no timing violation of the
// seed.
//
// Plusargs: +esl_emu_config=<scenario.toml>, +transactions=N (default
// 1000), +seed=S, +flip_bit=K (planted failure: the comparison flips bit K
// of the host's o_abs, so the run must fail), +esl_monitor_transcript=FILE
// (the monitor's JSON transcript).

`timescale 1fs / 1fs
`include "esl_monitor.v"
`default_nettype none

module tb_cosim_esl_host;

/* Core parameters (scripts/cosim.sh: from the scenario, by cosim-params) */
parameter CLOCKS_PER_BIT = 8;
parameter TIMEOUT_CLOCKS = 400;
parameter REPEAT_GAP_CLOCKS = 3200;
parameter READ_WAIT_CLOCKS = 16000;
parameter WRITE_WAIT_CLOCKS = 480000;
parameter PAGE_WAIT_CLOCKS = 1440000;
parameter BUSY_TRIES = 3;
parameter RS_TOLERANCE = 1;
parameter BROADCAST_ADDRESS = 7;

/* Harness parameters */
parameter F_SYS_HZ = 80000000;
parameter HALF_PERIOD_FS = 6_250_000;
parameter ADDRESS = 0;

reg clk = 1'b0;
reg rst = 1'b1;
always #(HALF_PERIOD_FS) clk = ~clk;

reg [63:0] cycles = 0;
always @(posedge clk) cycles <= cycles + 1;

reg i_start = 1'b0;
reg [3:0] i_data_id = 4'd1;
wire o_busy, o_done;
wire [7:0] o_cf, o_sf, o_sf2, o_alm1, o_alm2, o_sc1, o_enid, o_temp, o_adf, o_edf;
wire [6:0] o_sc2;
wire [23:0] o_abs;
wire [15:0] o_abm, o_rs;
wire o_err_crc1, o_err_crc2, o_err_timeout, o_err_frame, o_err_cf, o_err_comm, o_err_seq, o_err_rs, o_err_busy;
wire tx, tx_en, rx, enc_oe;

esl_host #(
    .CLOCKS_PER_BIT(CLOCKS_PER_BIT),
    .TIMEOUT_CLOCKS(TIMEOUT_CLOCKS),
    .REPEAT_GAP_CLOCKS(REPEAT_GAP_CLOCKS),
    .READ_WAIT_CLOCKS(READ_WAIT_CLOCKS),
    .WRITE_WAIT_CLOCKS(WRITE_WAIT_CLOCKS),
    .PAGE_WAIT_CLOCKS(PAGE_WAIT_CLOCKS),
    .BUSY_TRIES(BUSY_TRIES),
    .RS_TOLERANCE(RS_TOLERANCE),
    .BROADCAST_ADDRESS(BROADCAST_ADDRESS)
) dut (
    .i_clk(clk),
    .i_rst(rst),
    .i_start(i_start),
    .i_data_id(i_data_id),
    .i_address(ADDRESS[2:0]),
    .i_broadcast(1'b0),
    .i_mem_address(7'd0),
    .i_wdata(8'd0),
    .o_busy(o_busy),
    .o_done(o_done),
    .o_cf(o_cf),
    .o_sf(o_sf),
    .o_sf2(o_sf2),
    .o_alm1(o_alm1),
    .o_alm2(o_alm2),
    .o_abs(o_abs),
    .o_abm(o_abm),
    .o_rs(o_rs),
    .o_sc1(o_sc1),
    .o_sc2(o_sc2),
    .o_enid(o_enid),
    .o_temp(o_temp),
    .o_adf(o_adf),
    .o_edf(o_edf),
    .o_err_crc1(o_err_crc1),
    .o_err_crc2(o_err_crc2),
    .o_err_timeout(o_err_timeout),
    .o_err_frame(o_err_frame),
    .o_err_cf(o_err_cf),
    .o_err_comm(o_err_comm),
    .o_err_seq(o_err_seq),
    .o_err_rs(o_err_rs),
    .o_err_busy(o_err_busy),
    .o_tx(tx),
    .o_tx_en(tx_en),
    .i_rx(rx)
);

// The emulator on the host's own clock.
esl_encoder_emu #(
    .F_EMU_HZ(F_SYS_HZ)
) u_emu (
    .i_emu_clk(clk),
    .i_esl_data(tx),
    .i_esl_data_oe(tx_en),
    .o_esl_data(rx),
    .o_esl_data_oe(enc_oe)
);

// The pin-level monitor and protocol checker, on the same clock.
esl_monitor #(
    .F_MON_HZ(F_SYS_HZ),
    .PLUSARG("esl_emu_config")
) u_mon (
    .i_mon_clk(clk),
    .i_esl_data(tx),
    .i_esl_data_oe(tx_en),
    .i_esl_rx(rx)
);

// Any error the monitor's decoder flagged for its last operation.
function mon_any_error(input integer unused);
    mon_any_error = u_mon.last_status(0, "crc1") | u_mon.last_status(0, "crc2") | u_mon.last_status(0, "timeout")
                  | u_mon.last_status(0, "frame") | u_mon.last_status(0, "cf_mismatch") | u_mon.last_status(0, "comm_alarm")
                  | u_mon.last_status(0, "sequence") | u_mon.last_status(0, "channel_mismatch") | u_mon.last_status(0, "busy");
endfunction

/* Table 12: fields on the line per Data ID, and what each carries */
function integer answer_fields(input [3:0] id);
    case (id)
        4'h1: answer_fields = 18;
        4'h2: answer_fields = 16;
        4'h4: answer_fields = 8;
        4'h5: answer_fields = 6;
        4'h6: answer_fields = 11;
        4'h8: answer_fields = 12;
        4'h9: answer_fields = 4;
        default: answer_fields = 8; // A
    endcase
endfunction

function [3:0] pick_id(input [2:0] r);
    case (r)
        3'd0: pick_id = 4'h1;
        3'd1: pick_id = 4'h2;
        3'd2: pick_id = 4'h4;
        3'd3: pick_id = 4'h5;
        3'd4: pick_id = 4'h6;
        3'd5: pick_id = 4'h8;
        3'd6: pick_id = 4'h9;
        default: pick_id = 4'hA;
    endcase
endfunction

`include "emu_random.vh"
integer transactions, seed, flip_bit, n, waited, field, bit_i, faults, jumps, cuts;
reg [23:0] st;
reg [15:0] mt;
reg [8:0] flags; // xc mt led lis overspeed mem st uv ov (bit 0 = xc)
reg tw;
reg [7:0] want_alm, want_sf;
reg [63:0] sent;
reg [23:0] got_abs;
reg flip, cut, jump, safety, has_abs, has_abm, has_alm, have_ref, any_err;
reg [3:0] id;
reg [8*120-1:0] fault;

initial begin
    if (!$value$plusargs("transactions=%d", transactions)) transactions = 1000;
    if (!$value$plusargs("seed=%d", seed)) seed = 1;
    random_seed(seed);
    if (!$value$plusargs("flip_bit=%d", flip_bit)) flip_bit = -1;
    faults = 0; jumps = 0; cuts = 0; have_ref = 1'b0;
    repeat (4) @(posedge clk);
    rst <= 1'b0;
    repeat (4) @(posedge clk);
    for (n = 0; n < transactions; n = n + 1) begin
        id = pick_id(random32(0));
        safety = id == 4'h1 || id == 4'h2 || id == 4'h8;
        has_abs = id == 4'h1 || id == 4'h2 || id == 4'h4 || id == 4'h5 || id == 4'h6;
        has_abm = id == 4'h1 || id == 4'h4;
        has_alm = id == 4'h1 || id == 4'h2 || id == 4'hA;
        flip = (n % 16) == 15;
        cut = !flip && (n % 37) == 36;
        jump = !flip && !cut && safety && have_ref && (n % 29) == 28;
        st = random32(0);
        mt = random32(0);
        flags = random32(0);
        tw = random32(0);
        u_emu.set_position(0, {mt, st});
        u_emu.set_status(0, "xc", flags[0]);
        u_emu.set_status(0, "mt", flags[1]);
        u_emu.set_status(0, "led", flags[2]);
        u_emu.set_status(0, "lis", flags[3]);
        u_emu.set_status(0, "overspeed", flags[4]);
        u_emu.set_status(0, "mem", flags[5]);
        u_emu.set_status(0, "st", flags[6]);
        u_emu.set_status(0, "uv", flags[7]);
        u_emu.set_status(0, "ov", flags[8]);
        u_emu.set_status(0, "temp_warning", tw);
        // ALM: xc, mt, led|lis, overspeed, mem, st, uv, ov (Table 7)
        want_alm = {flags[8], flags[7], flags[6], flags[5], flags[4], flags[2] | flags[3], flags[1], flags[0]};
        // SF: ca0, ca1, ea0 (st mem ov uv led), ea1 (mt xc lis overspeed), DD0, DD1 (ch2), DD2 ready, DD3 (Table 5)
        want_sf = {1'b0, 1'b1, 1'b0, tw,
                   flags[1] | flags[0] | flags[3] | flags[4],
                   flags[6] | flags[5] | flags[8] | flags[7] | flags[2], 2'b00};
        if (flip) begin
            field = 1 + {random32(0)} % (answer_fields(id) - 1);
            bit_i = 1 + {random32(0)} % 8;
            $sformat(fault, "flips = [{ answer = %0d, field = %0d, bit = %0d }]", u_emu.count(0), field, bit_i);
            u_emu.schedule_fault(fault);
        end
        if (cut) begin
            field = 1 + {random32(0)} % (answer_fields(id) - 1);
            $sformat(fault, "truncations = [{ answer = %0d, fields = %0d }]", u_emu.count(0), field);
            u_emu.schedule_fault(fault);
        end
        if (jump) begin
            bit_i = 1 + {random32(0)} % 2;
            $sformat(fault, "sequence_jumps = [{ answer = %0d, channel = %0d }]", u_emu.count(0), bit_i);
            u_emu.schedule_fault(fault);
        end
        i_data_id <= id;
        i_start <= 1'b1;
        @(posedge clk);
        i_start <= 1'b0;
        waited = 0;
        @(posedge clk);
        while (!o_done) begin
            @(posedge clk);
            waited = waited + 1;
            if (waited > 400 * CLOCKS_PER_BIT + TIMEOUT_CLOCKS)
                $fatal(1, "operation %0d at %0t: no o_done", n, $time);
        end
        if (u_emu.count(0) != n + 1)
            $fatal(1, "operation %0d at %0t: the emulator counted %0d answers", n, $time, u_emu.count(0));
        any_err = o_err_crc1 | o_err_crc2 | o_err_timeout | o_err_frame | o_err_cf | o_err_comm | o_err_seq | o_err_rs | o_err_busy;
        if (flip) begin
            if (!(o_err_crc1 | o_err_crc2 | o_err_cf))
                $fatal(1, "operation %0d at %0t (Data ID %h): field %0d bit %0d flipped by the emulator, the host saw no CRC or CF error", n, $time, id, field, bit_i);
            faults = faults + 1;
            have_ref = 1'b0;
        end else if (cut) begin
            if (!any_err)
                $fatal(1, "operation %0d at %0t (Data ID %h): answer cut after %0d fields, the host saw no error", n, $time, id, field);
            cuts = cuts + 1;
            have_ref = 1'b0;
        end else begin
            if (jump) begin
                if (!o_err_seq || (any_err & !o_err_seq) || o_err_crc1 || o_err_crc2)
                    $fatal(1, "operation %0d at %0t (Data ID %h): SC%0d jumped, the host flagged seq %b crc1 %b crc2 %b", n, $time, id, bit_i, o_err_seq, o_err_crc1, o_err_crc2);
                jumps = jumps + 1;
            end else if (any_err)
                $fatal(1, "operation %0d at %0t (Data ID %h): error pulse crc1 %b crc2 %b timeout %b frame %b cf %b comm %b seq %b rs %b busy %b",
                       n, $time, id, o_err_crc1, o_err_crc2, o_err_timeout, o_err_frame, o_err_cf, o_err_comm, o_err_seq, o_err_rs, o_err_busy);
            if (safety) have_ref = 1'b1;
            sent = u_emu.last_value(0);
            got_abs = o_abs;
            if (flip_bit >= 0) got_abs = got_abs ^ (24'd1 << flip_bit);
            if (o_sf !== want_sf)
                $fatal(1, "operation %0d at %0t (Data ID %h): SF %h, set flags give %h", n, $time, id, o_sf, want_sf);
            if (has_abs && (sent[23:0] !== st || got_abs !== st))
                $fatal(1, "operation %0d at %0t (Data ID %h): ABS host %h emulator %h set %h", n, $time, id, got_abs, sent[23:0], st);
            if (has_abm && (sent[39:24] !== mt || o_abm !== mt))
                $fatal(1, "operation %0d at %0t (Data ID %h): ABM host %h emulator %h set %h", n, $time, id, o_abm, sent[39:24], mt);
            if (has_alm) begin
                if (o_alm1 !== want_alm || ((id == 4'h1 || id == 4'h2 || id == 4'hA) && o_alm2 !== want_alm))
                    $fatal(1, "operation %0d at %0t (Data ID %h): ALM1 %h ALM2 %h, set flags give %h", n, $time, id, o_alm1, o_alm2, want_alm);
                if (u_emu.last_status(0, "uv") != flags[7] || u_emu.last_status(0, "xc") != flags[0])
                    $fatal(1, "operation %0d at %0t: the emulator reports other flags than set", n, $time);
            end
        end
        // The monitor decoded the same operation off the pins.
        if (u_mon.count(0) != n + 1)
            $fatal(1, "operation %0d at %0t: the monitor decoded %0d operations", n, $time, u_mon.count(0));
        if (mon_any_error(0) != any_err || u_mon.last_status(0, "sequence") != o_err_seq)
            $fatal(1, "operation %0d at %0t (Data ID %h): the monitor flagged error %b sequence %b, the host error %b seq %b",
                   n, $time, id, mon_any_error(0), u_mon.last_status(0, "sequence"), any_err, o_err_seq);
        if (!any_err) begin
            sent = u_mon.last_value(0);
            if ((has_abs && sent[23:0] !== got_abs) || (has_abm && sent[39:24] !== o_abm)
                || (has_alm && (u_mon.last_status(0, "uv") != o_alm1[6] || u_mon.last_status(0, "xc") != o_alm1[0] || u_mon.last_status(0, "ov") != o_alm1[7])))
                $fatal(1, "operation %0d at %0t (Data ID %h): the monitor read ABS %h ABM %h on the line, the host ABS %h ABM %h ALM1 %h",
                       n, $time, id, sent[23:0], sent[39:24], got_abs, o_abm, o_alm1);
        end
        while (o_busy) @(posedge clk);
        // A few bits of idle line between operations.
        repeat (4 * CLOCKS_PER_BIT) @(posedge clk);
    end
    if (u_emu.violations(0) != 0)
        $fatal(1, "the host broke %0d timing rule(s) (PROTOCOL VIOLATION lines above)", u_emu.violations(0));
    if (u_mon.violations(0) != 0)
        $fatal(1, "the monitor saw %0d timing violation(s) of the seed by the host (PROTOCOL VIOLATION lines above)", u_mon.violations(0));
    $display("cycles %0d", cycles);
    $display("PASS tb_cosim_esl_host: %0d operations (%0d bit flips, %0d cut answers, %0d sequence jumps flagged), every o_abs, o_abm, o_alm1/2, o_sf equal to the emulator's and to the monitor's",
             transactions, faults, cuts, jumps);
    $finish;
end

endmodule

`default_nettype wire
