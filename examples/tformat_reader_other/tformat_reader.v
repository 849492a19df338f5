// tformat_reader: a small Tamagawa T-format reader written from the Smart
// Abs TS5669 N127 specification (seed 002) alone, independently of
// encoder-tb's tformat_host: other port names, a synchronous active-low
// reset, a registered request (one cycle more latency), its own receiver
// (it re-aligns on every start bit and takes each bit by a majority of three
// samples around its middle; tformat_host takes one sample) and its own
// checks.
//
// One read: a request of Data ID 0 or 3 (one control field), the driver
// released at the end of its delimiter, then the answer (seed 002 6.2.1,
// Table 2): CF SF ABS0 ABS1 ABS2 CRC (ID 0) or CF SF ABS0 ABS1 ABS2 ENID ABM0
// ABM1 ABM2 ALMC CRC (ID 3), each field a start bit 0, 8 bits LSB first and
// a delimiter 1 (6.3). Checked: the answer begins within TIMEOUT cycles of
// the request's end; every start bit and delimiter; the field count of the
// Data ID; CF equal to the request's; SF's communication alarms ca0 and ca1
// clear; the CRC (6.3.4: G(X) = X^8 + 1 over every field but the CRC without
// start bits and delimiters, i.e. the XOR of those bytes, bit by bit). The
// answer ends when no start bit follows a delimiter within two bit times
// (7.2).
//
//   tx_en ___/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_________________________________________
//   tx    ‾‾‾\_S_c0..c7_/‾D‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//   rx    ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾ ~3 us ‾‾\_S_CF_D_S_SF_D_ ... _S_CRC_D‾‾‾‾‾
//
// The control field (Figure 4 is lost in the seed's text): bits 0..2 the
// sink code 010, bits 3..6 the Data ID cc0..cc3, bit 7 the parity cc4 (the
// XOR of cc0..cc3, as Table 1 gives it): Data ID 0 is 0x02, 3 is 0x1A. The
// status field: bit 6 ca0, bit 7 ca1 (Figure 5 is lost too; encoder-tb's
// reading, docs/timing/tformat.md).
//
// rx passes a 2-flop synchroniser first.

`default_nettype none

module tformat_reader #(
    parameter BIT = 8,             // system clocks per bit (20 MHz / 2.5 Mbps)
    parameter TIMEOUT = 400        // cycles from the request's end to the answer's start bit
) (
    input  wire        sys_clk,
    input  wire        nreset,        // synchronous, active low
    input  wire        go,            // start a read of Data ID `id`
    input  wire [3:0]  id,            // 0 or 3
    output reg         idle,
    output reg  [16:0] single_turn,
    output reg  [15:0] multi_turn,    // Data ID 3 only
    output reg  [7:0]  alarms,        // ALMC, Data ID 3 only
    output reg  [7:0]  status,        // SF
    output reg         fresh,         // one cycle: a good answer, the outputs above are new
    output reg         bad,           // one cycle: an answer failed a check, or none came
    output reg  [2:0]  why,           // with bad: 1 timeout, 2 framing, 3 field count, 4 CF, 5 SF alarm, 6 CRC
    output reg         tx = 1'b1,     // to the transceiver's D (idle high)
    output reg         tx_en = 1'b0,  // to the transceiver's DE (off from power-up)
    input  wire        rx             // from the transceiver's R
);

localparam P_IDLE = 3'd0, P_SEND = 3'd1, P_WAIT = 3'd2, P_BITS = 3'd3, P_GAP = 3'd4, P_CHECK = 3'd5;

reg [2:0] ph;
reg go_q;
reg [3:0] id_q;
reg [1:0] rx_s;
reg [15:0] cnt;
reg [3:0] bitn;             // bit of the field: 0 start, 1..8 data, 9 delimiter
reg [9:0] txsr;
reg [2:0] votes;
reg [7:0] byte_sr;
reg [3:0] nfields;
reg [7:0] f [0:10];
reg [7:0] xsum;             // XOR of every field so far
reg framing;
reg rx_prev;

wire [7:0] cf_req = {^id_q, id_q, 3'b010};
wire [3:0] want = (id_q == 4'd3) ? 4'd11 : 4'd6;
wire fall = rx_prev && !rx_s[1];
wire maj = (votes[0] & votes[1]) | (votes[1] & votes[2]) | (votes[0] & votes[2]);

integer i;

always @(posedge sys_clk) begin
    if (!nreset) begin
        ph <= P_IDLE;
        go_q <= 1'b0;
        id_q <= 4'd0;
        rx_s <= 2'b11;
        rx_prev <= 1'b1;
        tx <= 1'b1;
        tx_en <= 1'b0;
        idle <= 1'b0;
        fresh <= 1'b0;
        bad <= 1'b0;
        why <= 3'd0;
        cnt <= 0;
        bitn <= 0;
        txsr <= 10'h3ff;
        votes <= 3'b111;
        byte_sr <= 8'd0;
        nfields <= 0;
        xsum <= 8'd0;
        framing <= 1'b0;
        single_turn <= 17'd0;
        multi_turn <= 16'd0;
        alarms <= 8'd0;
        status <= 8'd0;
        for (i = 0; i < 11; i = i + 1)
            f[i] <= 8'd0;
    end else begin
        rx_s <= {rx_s[0], rx};
        rx_prev <= rx_s[1];
        go_q <= go;
        fresh <= 1'b0;
        bad <= 1'b0;
        case (ph)
        P_IDLE: begin
            idle <= 1'b1;
            if (go_q && idle) begin
                idle <= 1'b0;
                txsr <= {1'b1, cf_req, 1'b0};      // delimiter, CF LSB first, start
                tx_en <= 1'b1;
                tx <= 1'b0;
                cnt <= BIT - 1;
                bitn <= 0;
                ph <= P_SEND;
            end else
                id_q <= id;
        end
        P_SEND: if (cnt != 0)
            cnt <= cnt - 1;
        else if (bitn == 9) begin
            tx_en <= 1'b0;                         // the end of the delimiter: release the line
            tx <= 1'b1;
            cnt <= TIMEOUT;
            nfields <= 0;
            xsum <= 8'd0;
            framing <= 1'b0;
            ph <= P_WAIT;
        end else begin
            bitn <= bitn + 1;
            tx <= txsr[bitn + 1];
            cnt <= BIT - 1;
        end
        P_WAIT, P_GAP: if (fall) begin
            // A start bit: re-align on it; its middle is BIT/2 cycles on.
            bitn <= 0;
            cnt <= 1;
            ph <= P_BITS;
        end else if (cnt == 0) begin
            if (ph == P_WAIT) begin
                bad <= 1'b1;
                why <= 3'd1;
                ph <= P_IDLE;
            end else
                ph <= P_CHECK;
        end else
            cnt <= cnt - 1;
        P_BITS: begin
            // cnt: cycles since the bit's edge was seen (1 on the first cycle after it).
            if (cnt == BIT - 1) begin
                cnt <= 0;
                bitn <= bitn + 1;
            end else
                cnt <= cnt + 1;
            if (cnt == BIT / 2 - 1) votes[0] <= rx_s[1];
            if (cnt == BIT / 2)     votes[1] <= rx_s[1];
            if (cnt == BIT / 2 + 1) votes[2] <= rx_s[1];
            if (cnt == BIT / 2 + 2) begin
                // The bit's value, after its three votes.
                if (bitn == 0 && maj)
                    framing <= 1'b1;
                else if (bitn >= 1 && bitn <= 8)
                    byte_sr <= {maj, byte_sr[7:1]};
                if (bitn == 9) begin
                    if (!maj)
                        framing <= 1'b1;
                    if (nfields < 11)
                        f[nfields] <= byte_sr;
                    xsum <= xsum ^ byte_sr;
                    nfields <= nfields + 1;
                    cnt <= 2 * BIT;                // the next start bit, or the end (7.2)
                    ph <= P_GAP;
                end
            end
        end
        P_CHECK: begin
            ph <= P_IDLE;
            if (framing) begin
                bad <= 1'b1; why <= 3'd2;
            end else if (nfields != want) begin
                bad <= 1'b1; why <= 3'd3;
            end else if (f[0] != cf_req) begin
                bad <= 1'b1; why <= 3'd4;
            end else if (f[1][7:6] != 2'b00) begin
                bad <= 1'b1; why <= 3'd5;
            end else if (xsum != 8'd0) begin
                // The XOR of all fields, the CRC included, is 0 when the CRC holds.
                bad <= 1'b1; why <= 3'd6;
            end else begin
                fresh <= 1'b1;
                status <= f[1];
                single_turn <= {f[4][0], f[3], f[2]};
                if (id_q == 4'd3) begin
                    multi_turn <= {f[7], f[6]};
                    alarms <= f[9];
                end
            end
        end
        default: ph <= P_IDLE;
        endcase
    end
end

endmodule

`default_nettype wire
