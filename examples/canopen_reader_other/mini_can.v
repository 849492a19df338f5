// mini_can: a small classic CAN controller (CAN 2.0A, standard 11-bit
// identifiers), written for the encoder-tb examples from the public
// descriptions of ISO 11898-1 only, independently of encoder-tb's own
// can_controller (other ports, active-low reset, another bit-timing scheme,
// its own CRC-15 and destuffing).
//
// Implements
//   * bit timing by clock cycles, no prescaler or time quanta: a bit is
//     CLKS_PER_BIT clocks, the bus is sampled once at clock SAMPLE_AT of the
//     bit (0 = its first clock), and a resynchronisation moves the bit by at
//     most JUMP clocks. Hard synchronisation on a falling edge while the bus
//     is idle or in intermission; resynchronisation only on a falling edge
//     after a recessive sample, never on an edge while this node drives
//     dominant, and a transmitter never lengthens a bit (no resync on a late
//     edge).
//   * transmit of data frames (11-bit identifier, 0 to 8 bytes), with bit
//     monitoring, arbitration loss detection (a recessive identifier or RTR
//     bit read dominant: `lost` pulses, the controller becomes a receiver for
//     the rest of that frame and sends its frame again once the bus is free)
//     and the ACK check (`sent` pulses at the 7th bit of EOF).
//   * receive of data and remote frames with destuffing (a sixth equal bit
//     is a stuff error), CRC-15 check (the received CRC shifted through the
//     same register must leave 0), form checks of the delimiters and EOF,
//     and the ACK slot driven dominant for every frame received correctly
//     (`got` pulses at the 6th bit of EOF, the receivers' point of validity).
//   * bus integration: after reset and after any error the controller waits
//     for 11 recessive bits before it takes part again.
//
// Omits (deliberately, to stay small; say so if you reuse it)
//   * error frames: an error is reported on `fault`/`fault_kind` and the
//     controller falls silent until 11 recessive bits have passed; it sends
//     no error flag (a receiver with a CRC error only withholds its ACK), so
//     it keeps no error counters and has no error-passive or bus-off state.
//   * overload frames: a dominant bit in intermission is taken as a start of
//     frame.
//   * extended (29-bit) frames: a frame with IDE = 1 is skipped silently (no
//     ACK); remote frames are received but not sent.
//   * automatic retransmission after an error: a frame whose transmission
//     failed (bit or ACK error) is dropped with `tx_fail`; only a lost
//     arbitration is retried.
//
// Timing (CLKS_PER_BIT = 16, SAMPLE_AT = 11):
//
//   clock in bit  0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 | 0 ...
//   can_txd       ^ changes one clock after clock 0   |
//   sample                               ^ clock 11 (68.75 %), on can_rxd after 2 flops
//
// can_rxd goes through two flip-flops, so the sample at clock SAMPLE_AT sees
// the pin as it was two clocks earlier; with the transceiver's and the
// cable's delays the round trip must stay below SAMPLE_AT - 3 clocks.

`default_nettype none

module mini_can #(
    parameter CLKS_PER_BIT = 16,
    parameter SAMPLE_AT = 11,
    parameter JUMP = 3
) (
    input  wire        clk,
    input  wire        rst_n,          // synchronous, active low
    /* transceiver */
    input  wire        can_rxd,
    output reg         can_txd,
    /* transmit request: taken when `busy` is low */
    input  wire        send,
    input  wire [10:0] send_id,
    input  wire [3:0]  send_len,
    input  wire [63:0] send_bytes,     // byte 0 in [63:56]
    output wire        busy,
    output reg         sent,
    output reg         lost,
    output reg         tx_fail,
    /* received frames */
    output reg         got,
    output reg  [10:0] got_id,
    output reg         got_rtr,
    output reg  [3:0]  got_len,
    output reg  [63:0] got_bytes,      // byte 0 in [63:56]
    output reg         fault,
    output reg  [2:0]  fault_kind      // 1 bit, 2 stuff, 3 CRC, 4 form, 5 ACK
);

localparam CW = $clog2(CLKS_PER_BIT + 1);

/* modes and frame fields */
localparam M_INTEG = 2'd0, M_IDLE = 2'd1, M_FRAME = 2'd2, M_INTER = 2'd3;
localparam F_HEAD = 3'd0, F_DATA = 3'd1, F_CRC = 3'd2, F_CDEL = 3'd3,
           F_ACK = 3'd4, F_ADEL = 3'd5, F_EOF = 3'd6;
localparam E_BIT = 3'd1, E_STUFF = 3'd2, E_CRC = 3'd3, E_FORM = 3'd4, E_ACK = 3'd5;

reg rx_meta = 1'b1, rx_s = 1'b1, rx_d = 1'b1;
reg [CW-1:0] cnt;
reg [1:0] mode;
reg [2:0] fld;
reg [6:0] k;              // bit within the field (or recessive bits counted)
reg [2:0] run;            // equal bits in a row (stuffing)
reg last;                 // the last bit sampled
reg [14:0] crc;
reg [82:0] tx_sr;         // SOF, identifier, RTR, IDE, r0, DLC, data
reg txing, pend, ack_go;
reg [10:0] req_id;
reg [3:0] req_len;
reg [63:0] req_bytes;
reg [10:0] id_r;
reg rtr_r;
reg [3:0] len_r;
reg [63:0] data_r;
reg [6:0] data_bits;

assign busy = pend;

/* edges on the synchronised line */
wire fall = rx_d & ~rx_s;
wire hard = fall && mode != M_FRAME;
wire may_resync = fall && mode == M_FRAME && last && can_txd;
wire late = may_resync && cnt != 0 && cnt <= SAMPLE_AT && !txing;
wire early = may_resync && cnt > SAMPLE_AT;
wire early_now = early && (CLKS_PER_BIT - cnt) <= JUMP;
wire [CW:0] late_to = cnt + 1 - ((cnt < JUMP) ? cnt : JUMP);
wire [CW:0] early_to = cnt + 1 + JUMP;
wire bstart = (cnt == 0 && !hard && !early_now) || early_now;
wire smp = cnt == SAMPLE_AT && !late && !hard;
wire b = rx_s;

/* CRC-15, x^15 + x^14 + x^10 + x^8 + x^7 + x^4 + x^3 + 1, from 0 */
function [14:0] crc_step(input [14:0] c, input bit_in);
    crc_step = {c[13:0], 1'b0} ^ ((bit_in ^ c[14]) ? 15'h4599 : 15'h0000);
endfunction

wire stuff_zone = fld <= F_CDEL;

task start_frame(input as_tx);
    begin
        mode <= M_FRAME;
        fld <= F_HEAD;
        k <= 0;
        run <= 0;
        crc <= 0;
        data_r <= 0;
        ack_go <= 1'b0;
        txing <= as_tx;
        if (as_tx) begin
            can_txd <= 1'b0;
            tx_sr <= {1'b0, req_id, 3'b000, req_len, req_bytes};
        end
    end
endtask

task fail_with(input [2:0] kind);
    begin
        fault <= 1'b1;
        fault_kind <= kind;
        if (txing) begin
            tx_fail <= 1'b1;
            pend <= 1'b0;
        end
        txing <= 1'b0;
        ack_go <= 1'b0;
        can_txd <= 1'b1;
        mode <= M_INTEG;
        k <= 0;
    end
endtask

always @(posedge clk) begin
    rx_meta <= can_rxd;
    rx_s <= rx_meta;
    rx_d <= rx_s;
    sent <= 1'b0;
    lost <= 1'b0;
    tx_fail <= 1'b0;
    got <= 1'b0;
    fault <= 1'b0;
    if (!rst_n) begin
        can_txd <= 1'b1;
        cnt <= 0;
        mode <= M_INTEG;
        fld <= F_HEAD;
        k <= 0;
        run <= 0;
        last <= 1'b1;
        crc <= 0;
        txing <= 1'b0;
        pend <= 1'b0;
        ack_go <= 1'b0;
        fault_kind <= 0;
        got_id <= 0;
        got_rtr <= 1'b0;
        got_len <= 0;
        got_bytes <= 0;
    end else begin
        if (send && !pend) begin
            pend <= 1'b1;
            req_id <= send_id;
            req_len <= send_len;
            req_bytes <= send_bytes;
        end

        /* bit timing */
        if (hard || early_now)
            cnt <= 1;
        else if (late)
            cnt <= late_to[CW-1:0];
        else if (early)
            cnt <= (early_to >= CLKS_PER_BIT) ? 0 : early_to[CW-1:0];
        else
            cnt <= (cnt == CLKS_PER_BIT - 1) ? 0 : cnt + 1;

        if (hard && (mode == M_IDLE || mode == M_INTER)) begin
            start_frame(pend);            // someone's SOF: receive it, or join with ours
        end else if (bstart) begin
            /* the bit that goes out now */
            if (mode == M_IDLE && pend)
                start_frame(1'b1);
            else if (mode == M_FRAME && txing) begin
                if (stuff_zone && run == 5)
                    can_txd <= ~last;
                else case (fld)
                    F_HEAD, F_DATA: can_txd <= tx_sr[82];
                    F_CRC: can_txd <= crc[14];
                    default: can_txd <= 1'b1;
                endcase
            end else if (mode == M_FRAME && fld == F_ACK && ack_go) begin
                can_txd <= 1'b0;
                ack_go <= 1'b0;
            end else
                can_txd <= 1'b1;
        end else if (smp) begin
            last <= b;
            case (mode)
            M_INTEG: begin
                if (!b)
                    k <= 0;
                else if (k == 10) begin
                    mode <= M_IDLE;
                    k <= 0;
                end else
                    k <= k + 1;
            end
            M_INTER: begin
                if (k == 2) begin
                    mode <= M_IDLE;
                    k <= 0;
                end else
                    k <= k + 1;
            end
            M_FRAME: begin
                if (stuff_zone && run == 5) begin
                    /* a stuff bit: must differ from the five before it */
                    if (b == last)
                        fail_with(txing ? E_BIT : E_STUFF);
                    else
                        run <= 1;
                end else if (txing && b != can_txd && fld == F_HEAD && k >= 1 && k <= 12 && can_txd) begin
                    /* arbitration lost: go on as a receiver, send again later */
                    txing <= 1'b0;
                    lost <= 1'b1;
                    run <= (b == last && run != 0) ? run + 1 : 1;
                    crc <= crc_step(crc, b);
                    if (k <= 11) id_r <= {id_r[9:0], b};
                    else rtr_r <= b;
                    k <= k + 1;
                end else if (txing && b != can_txd && fld != F_ACK) begin
                    fail_with(E_BIT);
                end else if (txing && fld == F_ACK && b) begin
                    fail_with(E_ACK);
                end else begin
                    if (stuff_zone)
                        run <= (b == last && run != 0) ? run + 1 : 1;
                    case (fld)
                    F_HEAD: begin
                        crc <= crc_step(crc, b);
                        tx_sr <= {tx_sr[81:0], 1'b0};
                        if (k == 0 && b)
                            fail_with(E_FORM);          // cannot happen after a falling edge
                        if (k >= 1 && k <= 11) id_r <= {id_r[9:0], b};
                        if (k == 12) rtr_r <= b;
                        if (k >= 15) len_r <= {len_r[2:0], b};
                        if (k == 13 && b) begin
                            mode <= M_INTEG;         // extended frame: not ours
                            k <= 0;
                        end else if (k == 18) begin
                            k <= 0;
                            fld <= (n_bytes_next(len_r, b) != 0) ? F_DATA : F_CRC;
                            data_bits <= {n_bytes_next(len_r, b), 3'b000} - 1;
                        end else
                            k <= k + 1;
                    end
                    F_DATA: begin
                        crc <= crc_step(crc, b);
                        tx_sr <= {tx_sr[81:0], 1'b0};
                        data_r[63 - k[5:0]] <= b;
                        if (k == data_bits) begin
                            k <= 0;
                            fld <= F_CRC;
                        end else
                            k <= k + 1;
                    end
                    F_CRC: begin
                        crc <= crc_step(crc, b);
                        if (k == 14) begin
                            k <= 0;
                            fld <= F_CDEL;
                        end else
                            k <= k + 1;
                    end
                    F_CDEL: begin
                        if (!b)
                            fail_with(E_FORM);
                        else if (!txing && crc != 0)
                            fail_with(E_CRC);
                        else begin
                            ack_go <= !txing;
                            fld <= F_ACK;
                        end
                    end
                    F_ACK: fld <= F_ADEL;
                    F_ADEL: begin
                        if (!b)
                            fail_with(E_FORM);
                        else begin
                            fld <= F_EOF;
                            k <= 0;
                        end
                    end
                    default: begin              // F_EOF
                        if (!b && !(k == 6 && !txing))
                            fail_with(E_FORM);
                        else begin
                            if (!txing && k == 5) begin
                                got <= 1'b1;
                                got_id <= id_r;
                                got_rtr <= rtr_r;
                                got_len <= len_r;
                                got_bytes <= data_r;
                            end
                            if (k == 6) begin
                                if (txing) begin
                                    sent <= 1'b1;
                                    pend <= 1'b0;
                                    txing <= 1'b0;
                                end
                                mode <= M_INTER;
                                k <= 0;
                            end else
                                k <= k + 1;
                        end
                    end
                    endcase
                end
            end
            default: ;                          // M_IDLE: wait for an edge or a request
            endcase
        end
    end
end

/* data bytes of the frame whose last DLC bit is `b` (RTR known already) */
function [3:0] n_bytes_next(input [3:0] len_sofar, input b_in);
    reg [3:0] dlc;
    begin
        dlc = {len_sofar[2:0], b_in};
        n_bytes_next = rtr_r ? 4'd0 : ((dlc > 4'd8) ? 4'd8 : dlc);
    end
endfunction

endmodule

`default_nettype wire
