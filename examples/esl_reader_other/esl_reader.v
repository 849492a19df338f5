// esl_reader: a small ESL position reader (non-safety position read, Data
// ID 4) written from the QS35 ESL specification alone (seed 000),
// independently of encoder-tb's esl_host: other port names, an active-low
// reset, a registered request, 6 clocks per bit (60 MHz for 10 Mbps) with a
// 3-sample majority vote around the middle of each bit, its own CRC-8 code
// (it checks the residue of the whole answer, CRC field included, instead of
// comparing a computed CRC), and it reports as soon as the 8th field of the
// answer has arrived instead of waiting for the end of the frame set.
//
//   txd_en  __/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\______________________________________
//   txd     ‾‾\_ RCF _/\_ CRC8 _/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//   rxd     ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_CF_/\_SF_/\_ABS0.._/\_ABM1_/\_CRC_/‾‾
//                                 |<-2 us->|               8 fields      ^ done/fail
//            (answer must start within REPLY_TIMEOUT clocks of the request's end)
//
// Frames: start 0, 8 data bits LSB first, stop 1 (seed Table 1, Figure 7).
// Request: RCF = EAD0..2 (bits 0..2), CC0..CC3 = Data ID (bits 3..6), parity
// (bit 7) making CC0..CC3 + parity odd (Table 3), then the CRC-8 frame of the
// RCF (Figure 1: "add CRC frame requirement to Command Frame").
// Answer to Data ID 4 (Table 12): CF, SF, ABS0, ABS1, ABS2, ABM0, ABM1, CRC1.
// CRC-8: X^8 + X^5 + X^3 + X^2 + X + 1 (the seed's 8'h97 is this generator
// with its x^8 term dropped), initial value 0, over the data bits of every
// field before the CRC, "transmitted from LSB first". Read here as the
// reflected register (bit i of the register = coefficient of x^(7-i)), bits in
// line order; then the whole answer, CRC field included, leaves 0 in it.
// The seed gives no worked example: this is the reading in which a message
// followed by its CRC is a codeword, as for Modbus.
// Checked in the answer: every start and stop bit, CF equal to the request's
// RCF, SF's CA0/CA1 (the encoder found no parity or stop-bit error in the
// request), the CRC. EA0/EA1 (encoder errors) are reported, not failures.
//
// txd and txd_en power up idle (high, off): Verilator starts registers at 0.

`default_nettype none

module esl_reader #(
    parameter BIT_CLKS = 6,          // system clocks per bit (60 MHz / 10 Mbps); 6 or more
    parameter REPLY_TIMEOUT = 300,   // clocks from the request's end to the answer's start bit (5 us)
    parameter QUIET_CLKS = 120       // idle receiver before the next request may go (20 bits)
) (
    input  wire        clk,
    input  wire        rst_n,
    input  wire        trigger,      // one pulse: read the position
    input  wire [2:0]  enc_addr,
    output reg  [23:0] angle,        // ABS: single-turn count
    output reg  [15:0] turns,        // ABM: multi-turn count
    output reg  [7:0]  status,       // SF
    output reg         fresh,        // one pulse: angle, turns, status are new and good
    output reg         fail,         // one pulse: the read failed, why in fail_why
    output reg  [2:0]  fail_why,     // 1 timeout, 2 start/stop bit, 3 CRC, 4 CF echo, 5 CA0/CA1
    output reg         txd = 1'b1,   // to the RS-485 transceiver's DI
    output reg         txd_en = 1'b0,// to its DE
    input  wire        rxd           // from its RO
);

localparam [3:0] DATA_ID = 4'h4;
localparam NFIELDS = 8;

localparam S_IDLE = 3'd0, S_LOAD = 3'd1, S_SEND = 3'd2, S_WAIT = 3'd3,
           S_FIELD = 3'd4, S_NEXT = 3'd5, S_QUIET = 3'd6;

// CRC-8 of seed 000, reflected register, one bit in line order.
function [7:0] crc8_bit(input [7:0] c, input b);
    crc8_bit = (c[0] ^ b) ? ((c >> 1) ^ 8'hF4) : (c >> 1);   // 0xF4 = 0x2F bit-reversed
endfunction

function [7:0] crc8_byte(input [7:0] c, input [7:0] d);
    integer k;
    reg [7:0] r;
    begin
        r = c;
        for (k = 0; k < 8; k = k + 1)
            r = crc8_bit(r, d[k]);
        crc8_byte = r;
    end
endfunction

reg [2:0] st = S_IDLE;
reg       trig_q;
reg       pending;               // a trigger waits here while a read or the quiet time runs
reg [2:0] rx_sync = 3'b111;       // 2-flop synchroniser and the previous level
wire      rx = rx_sync[1];
wire      rx_fall = rx_sync[2] & ~rx_sync[1];

reg [19:0] shreg;                 // request: 2 frames, bit 0 first
reg [4:0]  nbits;
reg [15:0] tmr;
reg [3:0]  bitno;                 // 0 start, 1..8 data, 9 stop
reg [1:0]  votes;                 // ones among the 3 samples of this bit
reg [7:0]  rbyte;
reg [3:0]  nfield;
reg [7:0]  crc;
reg        bad_frame;
reg [7:0]  cf_sent;
reg [7:0]  f [0:NFIELDS-1];

wire [7:0] rcf = {~^DATA_ID, DATA_ID, enc_addr};
wire       majority = (votes >= 2'd2);

always @(posedge clk) begin
    rx_sync <= {rx_sync[1:0], rxd};
    trig_q  <= trigger;
    if (trig_q) pending <= 1'b1;
    fresh   <= 1'b0;
    fail    <= 1'b0;
    if (!rst_n) begin
        st <= S_IDLE;
        txd <= 1'b1;
        txd_en <= 1'b0;
        trig_q <= 1'b0;
        pending <= 1'b0;
        rx_sync <= 3'b111;
    end else case (st)
        S_IDLE:
            if (pending) begin
                pending <= trig_q;
                st <= S_LOAD;
            end
        S_LOAD: begin
            cf_sent <= rcf;
            shreg <= {1'b1, crc8_byte(8'h00, rcf), 1'b0, 1'b1, rcf, 1'b0};
            nbits <= 5'd20;
            tmr <= BIT_CLKS - 1;
            txd_en <= 1'b1;
            txd <= 1'b0;          // start bit of the RCF from the next cycle on
            st <= S_SEND;
        end
        S_SEND:
            if (tmr != 0) tmr <= tmr - 1'b1;
            else begin
                tmr <= BIT_CLKS - 1;
                shreg <= {1'b1, shreg[19:1]};
                nbits <= nbits - 1'b1;
                if (nbits == 5'd1) begin
                    txd_en <= 1'b0;
                    txd <= 1'b1;
                    tmr <= 16'd0;
                    nfield <= 4'd0;
                    crc <= 8'h00;
                    bad_frame <= 1'b0;
                    st <= S_WAIT;
                end else
                    txd <= shreg[1];
            end
        S_WAIT:
            if (rx_fall) begin
                tmr <= 16'd0;
                bitno <= 4'd0;
                votes <= 2'd0;
                st <= S_FIELD;
            end else if (tmr == REPLY_TIMEOUT) begin
                fail <= 1'b1;
                fail_why <= 3'd1;
                tmr <= 16'd0;
                st <= S_QUIET;
            end else
                tmr <= tmr + 1'b1;
        S_FIELD: begin
            // tmr = 0 two cycles after the start edge was seen, and rx is the
            // line as it was 2 cycles before: tmr = k samples the line about
            // k + 1 cycles after the bit's edge. Three samples, tmr =
            // BIT_CLKS/2 - 3 .. BIT_CLKS/2 - 1 (1 to 3 cycles into a 6-cycle
            // bit, around its middle), then the majority at BIT_CLKS/2.
            if (tmr == BIT_CLKS - 1) tmr <= 16'd0; else tmr <= tmr + 1'b1;
            if (tmr >= BIT_CLKS / 2 - 3 && tmr <= BIT_CLKS / 2 - 1)
                votes <= votes + rx;
            if (tmr == BIT_CLKS / 2) begin
                votes <= 2'd0;
                bitno <= bitno + 1'b1;
                if (bitno == 4'd0 && majority) bad_frame <= 1'b1;
                if (bitno >= 4'd1 && bitno <= 4'd8) begin
                    rbyte <= {majority, rbyte[7:1]};
                    crc <= crc8_bit(crc, majority);
                end
                if (bitno == 4'd9) begin
                    if (!majority) bad_frame <= 1'b1;
                    f[nfield] <= rbyte;
                    nfield <= nfield + 1'b1;
                    tmr <= 16'd0;
                    st <= S_NEXT;
                end
            end
        end
        S_NEXT:
            if (nfield == NFIELDS) begin
                tmr <= 16'd0;
                st <= S_QUIET;
                if (bad_frame) begin
                    fail <= 1'b1; fail_why <= 3'd2;
                end else if (crc != 8'h00) begin
                    fail <= 1'b1; fail_why <= 3'd3;
                end else if (f[0] != cf_sent) begin
                    fail <= 1'b1; fail_why <= 3'd4;
                end else if (f[1][1:0] != 2'b00) begin
                    fail <= 1'b1; fail_why <= 3'd5;
                end else begin
                    status <= f[1];
                    angle <= {f[4], f[3], f[2]};
                    turns <= {f[6], f[5]};
                    fresh <= 1'b1;
                end
            end else if (!rx) begin
                // the next start bit (by level: its edge may have come in the
                // cycle that decided the stop bit, with a fast encoder)
                tmr <= 16'd0;
                bitno <= 4'd0;
                votes <= 2'd0;
                st <= S_FIELD;
            end else if (tmr == 3 * BIT_CLKS) begin
                // the frame set ended early
                fail <= 1'b1;
                fail_why <= 3'd2;
                tmr <= 16'd0;
                st <= S_QUIET;
            end else
                tmr <= tmr + 1'b1;
        S_QUIET:
            // a request only after the line has been idle QUIET_CLKS
            if (!rx) tmr <= 16'd0;
            else if (tmr == QUIET_CLKS) st <= S_IDLE;
            else tmr <= tmr + 1'b1;
        default: st <= S_IDLE;
    endcase
end

endmodule

`default_nettype wire
