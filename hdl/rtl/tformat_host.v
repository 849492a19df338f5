// tformat_host: Tamagawa T-format host (2.5 Mbps half-duplex RS-485); the cycle-for-cycle twin of model::tformat::Host.
//
// What it is for
//   Sends one T-format request (seed 002: Data ID 0, 1, 2, 3 readouts; 6
//   EEPROM write; D EEPROM read; 7, 8, C resets, sent ten times as one
//   operation) and receives and checks the Smart Abs answer. Connect o_tx and
//   o_tx_en to an RS-485 driver (DI, DE) and i_rx to its receiver (RO); the
//   receive path is deaf while o_tx_en is high. Pulse i_start with
//   i_data_id, i_address, i_wdata while o_busy is low; o_done pulses at the
//   end with every result and error output valid (they hold until the next
//   operation).
//
// Parameters (the Rust HostConfig field of the same name in lower case)
//   CLOCKS_PER_BIT     i_clk cycles per bit: f_sys / 2.5 Mbps (32 at 80 MHz)
//   TIMEOUT_CLOCKS     cycles after the request before a missing answer is
//                      flagged (the encoder answers after 3 us typ.)
//   REPEAT_GAP_CLOCKS  cycles from one answer to the next of the ten reset
//                      requests (the seed asks for 40 ms or more between requests)
//
// Timing (Data ID 0); docs/timing/tformat.md and model/src/tformat/mod.rs have the full story
//
//   o_tx_en     _/‾‾‾ CF ‾‾\________________________________________________
//   line        ‾\_request_/‾‾‾‾‾‾‾‾‾‾‾\_CF_/\_SF_/\_ABS0..2_/\_CRC_/‾‾‾‾‾‾‾‾‾‾‾
//                          |<-- 3 us -->|<-- 6 fields back to back -->|
//   state       IDLE| SEND |    WAIT    |            RECV             |1 bit|IDLE
//   (after a flawed answer: QUIET until the receiver has been idle 20 bits, at most 120 bits, then o_done;
//    RECV ends with a framing error 120 bits after the answer's first start bit)
//   o_done      _______________________________________________________________/‾\_
//
// Checks at the end of each answer: CRC (the XOR of all fields, CRC
// included, is 0: G(X) = X^8 + 1), the number of fields the request asks for,
// framing, the answer's control field against the request's, and the
// communication alarms ca0/ca1 of the status field. A frame set ends when
// the line stays idle for one bit after a delimiter (seed 002, 7.2).

`resetall
`timescale 1ns / 1ps
`default_nettype none

module tformat_host #(
    parameter CLOCKS_PER_BIT = 32,
    parameter TIMEOUT_CLOCKS = 1000,
    parameter REPEAT_GAP_CLOCKS = 4000000
) (
    input  wire        i_clk,
    input  wire        i_rst,

    /* Host interface */
    input  wire        i_start,
    input  wire [3:0]  i_data_id,
    input  wire [6:0]  i_address,
    input  wire [7:0]  i_wdata,
    output wire        o_busy,
    output wire        o_done,

    /* Results (valid with o_done) */
    output wire [7:0]  o_cf,
    output wire [7:0]  o_sf,
    output wire [16:0] o_abs,
    output wire [15:0] o_abm,
    output wire [7:0]  o_enid,
    output wire [7:0]  o_almc,
    output wire [7:0]  o_adf,
    output wire [7:0]  o_edf,

    /* Status (valid with o_done) */
    output wire        o_err_crc,
    output wire        o_err_timeout,
    output wire        o_err_frame,
    output wire        o_err_cf,
    output wire        o_err_comm,

    /* RS-485 line */
    output wire        o_tx,
    output wire        o_tx_en,
    input  wire        i_rx
);

// The counter also bounds RECV and QUIET: 120 bit times each
// (model::tformat::ANSWER_LIMIT_BITS, QUIET_LIMIT_BITS: the longest answer
// and one field more), so a stuck line or a second driver cannot hang the host.
localparam integer LIMIT_CLOCKS = 120 * CLOCKS_PER_BIT;

// Sink code in bits 0..2 of every control field (model::tformat::frames::SINK_CODE).
localparam [2:0] SINK_CODE = 3'b010;

// States: the same names and codes as model::tformat::State.
localparam [2:0]
    IDLE = 3'd0,
    SEND = 3'd1,
    WAIT = 3'd2,
    RECV = 3'd3,
    GAP  = 3'd4,
    QUIET = 3'd5;

initial begin
    if (CLOCKS_PER_BIT < 6) $error("tformat_host: CLOCKS_PER_BIT must be at least 6");
    if (TIMEOUT_CLOCKS < CLOCKS_PER_BIT) $error("tformat_host: TIMEOUT_CLOCKS must be at least one bit");
    if (REPEAT_GAP_CLOCKS < 20 * CLOCKS_PER_BIT) $error("tformat_host: REPEAT_GAP_CLOCKS must be at least 20 bits");
end

/* The skeleton's receiver (half_duplex_rx): its outputs are registers,
   read here as they stand before each edge. */
wire [7:0] rx_data;
wire       rx_valid;
wire       rx_frame_err;
wire       rx_busy;
/* verilator lint_off UNUSEDSIGNAL */
wire       rx_parity_err; // always 0: 10-bit frames (PARITY = 0)
/* verilator lint_on UNUSEDSIGNAL */
reg        tx_en_reg = 1'b0, tx_en_next;

half_duplex_rx #(.CLOCKS_PER_BIT(CLOCKS_PER_BIT)) rx_inst (
    .i_clk(i_clk), .i_rst(i_rst), .i_tx_en(tx_en_reg), .i_rx(i_rx),
    .o_data(rx_data), .o_valid(rx_valid), .o_frame_err(rx_frame_err), .o_parity_err(rx_parity_err), .o_busy(rx_busy)
);

reg [2:0]        state_reg = IDLE, state_next;
reg [3:0]        id_reg = 4'd0, id_next;
// The request as it goes on the line, first bit in bit 0 (start, data LSB
// first, delimiter per field; at most 4 fields). Shifting it out keeps the
// path to o_tx one flop long, instead of a bit counter and two muxes.
reg [7:0]        req_cf_reg = 8'd0, req_cf_next;
reg [39:0]       req_bits_reg = 40'd0, req_bits_next;
reg [5:0]        req_nbits_reg = 6'd0, req_nbits_next;
reg [39:0]       shift_reg = 40'd0, shift_next;
reg [5:0]        bits_left_reg = 6'd0, bits_left_next;
/* The skeleton's two counters (half_duplex_timer: every bit and wait, the
   answer and quiet limits; half_duplex_idle: the receiver's idle time in
   RECV and QUIET). The state machine asks for a load or a step and reads
   their registered flags cnt_zero, idle_end and idle_quiet. A load wins
   over a step (RECV steps on every cycle; an answer's end may load the
   limit or the gap in the same cycle). */
localparam [2:0] LOAD_NONE = 3'd0, LOAD_BIT = 3'd1, LOAD_TIMEOUT = 3'd2, LOAD_LIMIT = 3'd3, LOAD_GAP = 3'd4;
// Requests: load the wait cnt_load names (LOAD_NONE: none), or count down;
// clear the idle count, or count it up.
reg [2:0]        cnt_load;
reg              cnt_dec, idle_clear, idle_count;
wire             cnt_zero, idle_end, idle_quiet;

half_duplex_timer #(
    .CLOCKS_1(CLOCKS_PER_BIT), .CLOCKS_2(TIMEOUT_CLOCKS), .CLOCKS_3(LIMIT_CLOCKS), .CLOCKS_4(REPEAT_GAP_CLOCKS)
) cnt_inst (
    .i_clk(i_clk), .i_rst(i_rst), .i_load(cnt_load), .i_count(cnt_dec), .o_zero(cnt_zero)
);

half_duplex_idle #(.CLOCKS_PER_BIT(CLOCKS_PER_BIT)) idle_inst (
    .i_clk(i_clk), .i_rst(i_rst), .i_clear(idle_clear), .i_count(idle_count),
    .o_answer_end(idle_end), .o_quiet(idle_quiet)
);

reg [3:0]        repeats_reg = 4'd0, repeats_next;
reg [7:0]        count_reg = 8'd0, count_next;
reg [7:0]        crc_reg = 8'd0, crc_next;
reg              frame_bad_reg = 1'b0, frame_bad_next;

// The answer's fields, CF first (Data ID 3 has eleven). Only what the
// results need is stored: of ABS2 (f4) its one valid bit (17-bit data);
// ABM2 (f8, always 0) and the CRC (f10) count only through the running XOR.
reg [7:0] f0_reg = 8'd0, f1_reg = 8'd0, f2_reg = 8'd0, f3_reg = 8'd0, f5_reg = 8'd0;
reg [7:0] f6_reg = 8'd0, f7_reg = 8'd0, f9_reg = 8'd0;
reg       f4_bit0_reg = 1'b0;
reg       store;

reg        tx_reg = 1'b1, tx_next;
reg        busy_reg = 1'b0, busy_next;
reg        done_reg = 1'b0, done_next;
reg [7:0]  cf_reg = 8'd0, cf_next;
reg [7:0]  sf_reg = 8'd0, sf_next;
reg [16:0] abs_reg = 17'd0, abs_next;
reg [15:0] abm_reg = 16'd0, abm_next;
reg [7:0]  enid_reg = 8'd0, enid_next;
reg [7:0]  almc_reg = 8'd0, almc_next;
reg [7:0]  adf_reg = 8'd0, adf_next;
reg [7:0]  edf_reg = 8'd0, edf_next;
reg        err_crc_reg = 1'b0, err_crc_next;
reg        err_timeout_reg = 1'b0, err_timeout_next;
reg        err_frame_reg = 1'b0, err_frame_next;
reg        err_cf_reg = 1'b0, err_cf_next;
reg        err_comm_reg = 1'b0, err_comm_next;

assign o_tx = tx_reg;
assign o_tx_en = tx_en_reg;
assign o_busy = busy_reg;
assign o_done = done_reg;
assign o_cf = cf_reg;
assign o_sf = sf_reg;
assign o_abs = abs_reg;
assign o_abm = abm_reg;
assign o_enid = enid_reg;
assign o_almc = almc_reg;
assign o_adf = adf_reg;
assign o_edf = edf_reg;
assign o_err_crc = err_crc_reg;
assign o_err_timeout = err_timeout_reg;
assign o_err_frame = err_frame_reg;
assign o_err_cf = err_cf_reg;
assign o_err_comm = err_comm_reg;

// The request built from the host inputs: control field (sink code, Data
// ID, even parity over cc0..cc4), and for 6 and D the EEPROM fields and CRC.
wire [7:0] start_cf = {^i_data_id, i_data_id, SINK_CODE};
wire [7:0] start_adf = {1'b0, i_address};
wire       start_is_reset = (i_data_id == 4'h7) || (i_data_id == 4'h8) || (i_data_id == 4'hC);

// The request's fields with start bits and delimiters, for the shift register.
wire [7:0]  wr_crc = start_cf ^ start_adf ^ i_wdata;
wire [7:0]  rd_crc = start_cf ^ start_adf;
wire [39:0] start_bits_write = {1'b1, wr_crc, 1'b0, 1'b1, i_wdata, 1'b0, 1'b1, start_adf, 1'b0, 1'b1, start_cf, 1'b0};
wire [39:0] start_bits_read = {10'b11_1111_1111, 1'b1, rd_crc, 1'b0, 1'b1, start_adf, 1'b0, 1'b1, start_cf, 1'b0};
wire [39:0] start_bits_one = {30'h3FFF_FFFF, 1'b1, start_cf, 1'b0};

// End-of-answer checks, from the fields as they stand.
wire [3:0] answer_code = f0_reg[6:3];
wire       answer_is_eeprom = (answer_code == 4'h6) || (answer_code == 4'hD);
reg  [7:0] expected_fields;

always @* begin
    case (id_reg)
        4'h0, 4'h1, 4'h7, 4'h8, 4'hC: expected_fields = 8'd6;
        4'h2, 4'h6, 4'hD: expected_fields = 8'd4;
        default: expected_fields = 8'd11;
    endcase
end

reg finish;
reg finish_timeout;

// The checks of one answer, from the fields and running XOR as they stand.
// `timeout_now` is the WAIT state's timeout, from registers only.
wire timeout_now = (state_reg == WAIT) && !rx_busy && cnt_zero;
wire crc_bad = !timeout_now && crc_reg != 8'd0;
// RECV has run 120 bit times: the answer is over, whatever holds the line.
wire too_long = (state_reg == RECV) && cnt_zero;
wire frame_bad = !timeout_now && (frame_bad_reg || too_long || count_reg != expected_fields);
wire cf_bad = !timeout_now && f0_reg != req_cf_reg;

always @* begin
    state_next = state_reg;
    id_next = id_reg;
    req_cf_next = req_cf_reg;
    req_bits_next = req_bits_reg;
    req_nbits_next = req_nbits_reg;
    shift_next = shift_reg;
    bits_left_next = bits_left_reg;
    cnt_load = LOAD_NONE;
    cnt_dec = 1'b0;
    idle_clear = 1'b0;
    idle_count = 1'b0;
    repeats_next = repeats_reg;
    count_next = count_reg;
    crc_next = crc_reg;
    frame_bad_next = frame_bad_reg;
    store = 1'b0;
    tx_next = tx_reg;
    tx_en_next = tx_en_reg;
    busy_next = busy_reg;
    done_next = 1'b0;
    cf_next = cf_reg;
    sf_next = sf_reg;
    abs_next = abs_reg;
    abm_next = abm_reg;
    enid_next = enid_reg;
    almc_next = almc_reg;
    adf_next = adf_reg;
    edf_next = edf_reg;
    err_crc_next = err_crc_reg;
    err_timeout_next = err_timeout_reg;
    err_frame_next = err_frame_reg;
    err_cf_next = err_cf_reg;
    err_comm_next = err_comm_reg;
    finish = 1'b0;
    finish_timeout = 1'b0;

    case (state_reg)
        IDLE: begin
            if (i_start) begin
                id_next = i_data_id;
                req_cf_next = start_cf;
                if (i_data_id == 4'h6) begin
                    req_bits_next = start_bits_write;
                    req_nbits_next = 6'd40;
                end else if (i_data_id == 4'hD) begin
                    req_bits_next = start_bits_read;
                    req_nbits_next = 6'd30;
                end else begin
                    req_bits_next = start_bits_one;
                    req_nbits_next = 6'd10;
                end
                repeats_next = start_is_reset ? 4'd10 : 4'd1;
                frame_bad_next = 1'b0;
                busy_next = 1'b1;
                err_crc_next = 1'b0;
                err_timeout_next = 1'b0;
                err_frame_next = 1'b0;
                err_cf_next = 1'b0;
                err_comm_next = 1'b0;
                // The first start bit now; the rest from the shift register.
                state_next = SEND;
                shift_next = req_bits_next >> 1;
                bits_left_next = req_nbits_next - 1'b1;
                cnt_load = LOAD_BIT;
                tx_en_next = 1'b1;
                tx_next = 1'b0;
            end
        end
        SEND: begin
            if (cnt_zero) begin
                if (bits_left_reg == 6'd0) begin
                    tx_en_next = 1'b0;
                    tx_next = 1'b1;
                    state_next = WAIT;
                    cnt_load = LOAD_TIMEOUT;
                    count_next = 8'd0;
                    crc_next = 8'd0;
                end else begin
                    tx_next = shift_reg[0];
                    shift_next = shift_reg >> 1;
                    bits_left_next = bits_left_reg - 1'b1;
                    cnt_load = LOAD_BIT;
                end
            end else begin
                cnt_dec = 1'b1;
            end
        end
        WAIT: begin
            if (rx_busy) begin
                state_next = RECV;
                idle_clear = 1'b1;
                cnt_load = LOAD_LIMIT;
            end else if (cnt_zero) begin
                finish = 1'b1;
                finish_timeout = 1'b1;
            end else begin
                cnt_dec = 1'b1;
            end
        end
        RECV: begin
            cnt_dec = 1'b1;
            if (too_long) begin
                finish = 1'b1;
            end else if (rx_valid || rx_frame_err) begin
                store = (count_reg < 8'd11);
                count_next = (count_reg == 8'hFF) ? count_reg : count_reg + 1'b1;
                crc_next = crc_reg ^ rx_data;
                frame_bad_next = frame_bad_reg | rx_frame_err;
                idle_clear = 1'b1;
            end else if (!rx_busy) begin
                idle_count = 1'b1;
                if (idle_end) begin
                    finish = 1'b1;
                end
            end else begin
                idle_clear = 1'b1;
            end
        end
        GAP: begin
            if (cnt_zero) begin
                state_next = SEND;
                shift_next = req_bits_reg >> 1;
                bits_left_next = req_nbits_reg - 1'b1;
                cnt_load = LOAD_BIT;
                tx_en_next = 1'b1;
                tx_next = req_bits_reg[0];
            end else begin
                cnt_dec = 1'b1;
            end
        end
        QUIET: begin
            // After a flawed answer: wait until the line has been quiet for
            // two fields, so the next request cannot land on the rest of an
            // answer whose framing was lost.
            // A line that never falls quiet (stuck low, a second driver)
            // ends QUIET after 120 bit times: the errors are flagged already.
            if (rx_busy) begin
                idle_clear = 1'b1;
            end else begin
                idle_count = 1'b1;
            end
            if ((!rx_busy && idle_quiet) || cnt_zero) begin
                state_next = IDLE;
                busy_next = 1'b0;
                done_next = 1'b1;
            end else begin
                cnt_dec = 1'b1;
            end
        end
        // Codes 6 and 7 are never entered (no state assigns them); coverage counts reachable code only.
        /* verilator coverage_off */
        default: begin
            state_next = IDLE;
        end
        /* verilator coverage_on */
    endcase

    if (finish) begin
        if (!finish_timeout) begin
            cf_next = f0_reg;
            if (answer_is_eeprom) begin
                adf_next = f1_reg;
                edf_next = f2_reg;
            end else begin
                sf_next = f1_reg;
                case (answer_code)
                    4'h1: abm_next = {f3_reg, f2_reg};
                    4'h2: enid_next = f2_reg;
                    4'h3: begin
                        abs_next = {f4_bit0_reg, f3_reg, f2_reg};
                        enid_next = f5_reg;
                        abm_next = {f7_reg, f6_reg};
                        almc_next = f9_reg;
                    end
                    default: abs_next = {f4_bit0_reg, f3_reg, f2_reg};
                endcase
            end
        end
        err_timeout_next = err_timeout_reg | finish_timeout;
        err_crc_next = err_crc_reg | crc_bad;
        err_frame_next = err_frame_reg | frame_bad;
        err_cf_next = err_cf_reg | cf_bad;
        err_comm_next = err_comm_reg | (!finish_timeout && !answer_is_eeprom && f1_reg[7:6] != 2'b00);
        frame_bad_next = 1'b0;
        repeats_next = repeats_reg - 1'b1;
        if (repeats_reg == 4'd1 && (finish_timeout || crc_bad || frame_bad || cf_bad)) begin
            state_next = QUIET;
            idle_clear = 1'b1;
            cnt_load = LOAD_LIMIT;
        end else if (repeats_reg == 4'd1) begin
            state_next = IDLE;
            busy_next = 1'b0;
            done_next = 1'b1;
        end else begin
            state_next = GAP;
            cnt_load = LOAD_GAP;
        end
    end
end

// The register bank: every register takes its next value at each clock edge.
always @(posedge i_clk) begin
    state_reg <= state_next;
    id_reg <= id_next;
    req_cf_reg <= req_cf_next;
    req_bits_reg <= req_bits_next;
    req_nbits_reg <= req_nbits_next;
    shift_reg <= shift_next;
    bits_left_reg <= bits_left_next;
    repeats_reg <= repeats_next;
    count_reg <= count_next;
    crc_reg <= crc_next;
    frame_bad_reg <= frame_bad_next;
    tx_reg <= tx_next;
    tx_en_reg <= tx_en_next;
    busy_reg <= busy_next;
    done_reg <= done_next;
    cf_reg <= cf_next;
    sf_reg <= sf_next;
    abs_reg <= abs_next;
    abm_reg <= abm_next;
    enid_reg <= enid_next;
    almc_reg <= almc_next;
    adf_reg <= adf_next;
    edf_reg <= edf_next;
    err_crc_reg <= err_crc_next;
    err_timeout_reg <= err_timeout_next;
    err_frame_reg <= err_frame_next;
    err_cf_reg <= err_cf_next;
    err_comm_reg <= err_comm_next;
    if (store) begin
        case (count_reg[3:0])
            4'd0: f0_reg <= rx_data;
            4'd1: f1_reg <= rx_data;
            4'd2: f2_reg <= rx_data;
            4'd3: f3_reg <= rx_data;
            4'd4: f4_bit0_reg <= rx_data[0];
            4'd5: f5_reg <= rx_data;
            4'd6: f6_reg <= rx_data;
            4'd7: f7_reg <= rx_data;
            4'd9: f9_reg <= rx_data;
            default: ;
        endcase
    end

    if (i_rst) begin
        state_reg <= IDLE;
        id_reg <= 4'd0;
        req_cf_reg <= 8'd0;
        req_bits_reg <= 40'd0;
        req_nbits_reg <= 6'd0;
        shift_reg <= 40'd0;
        bits_left_reg <= 6'd0;
        repeats_reg <= 4'd0;
        count_reg <= 8'd0;
        crc_reg <= 8'd0;
        frame_bad_reg <= 1'b0;
        tx_reg <= 1'b1;
        tx_en_reg <= 1'b0;
        busy_reg <= 1'b0;
        done_reg <= 1'b0;
        cf_reg <= 8'd0;
        sf_reg <= 8'd0;
        abs_reg <= 17'd0;
        abm_reg <= 16'd0;
        enid_reg <= 8'd0;
        almc_reg <= 8'd0;
        adf_reg <= 8'd0;
        edf_reg <= 8'd0;
        err_crc_reg <= 1'b0;
        err_timeout_reg <= 1'b0;
        err_frame_reg <= 1'b0;
        err_cf_reg <= 1'b0;
        err_comm_reg <= 1'b0;
        f0_reg <= 8'd0;
        f1_reg <= 8'd0;
        f2_reg <= 8'd0;
        f3_reg <= 8'd0;
        f4_bit0_reg <= 1'b0;
        f5_reg <= 8'd0;
        f6_reg <= 8'd0;
        f7_reg <= 8'd0;
        f9_reg <= 8'd0;
    end
end

endmodule

`resetall
