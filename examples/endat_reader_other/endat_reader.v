// endat_reader: a small EnDat 2.1 position reader written from the HEIDENHAIN
// EnDat 2.2 document (seed 004) alone, independently of encoder-tb's
// endat_master: other port names, an asynchronous active-low reset, a
// sampling point at the end of each clock low phase (endat_master samples a
// set delay after the falling edge) and its own CRC code (the seed's
// MakeCrcPos, appendix A4, as a shift register).
//
// One read: the mode command "Encoder send position values" (000111, type
// 2.1; seed 004 2.3.1.1), then the start bit, F1, POS_BITS position bits LSB
// first and the 5-bit CRC; then the clock rests high for REST cycles (seed
// 004 2.3.2: t_b > 1 ms between EnDat 2.1 cycles, which also covers the
// recovery time I t_m and, after an error, A2 4.2.1's 30 us).
//
//   ck  ‾‾\___/‾‾\__/‾‾\__ ... _/‾‾\__/‾‾\__/‾‾ ... \__/‾‾‾‾‾‾‾‾‾‾ (REST) ‾‾
//         F1  R1  F2  R2         F8                  last R
//   de  ______/‾‾‾‾‾‾‾‾ 6 mode bits ‾‾\____________________________________
//   do        M2  M1  M0 /M2 /M1 /M0   (each put at a falling edge)
//   di  (encoder) ...... low .... S F1 P0 .. Pn-1 C4..C0 (each put at a rising edge)
//                                 ^ sampled at the last cycle of the low phase
//                                   that follows (the bit put at R_k is read
//                                   just before R_(k+1))
//
// ck powers up high, as the idle line must be: a clock that starts low is a
// falling edge to the encoder.
//
// The data input passes a 2-flop synchroniser: the sample is the pin as it
// was 2 cycles before the end of the low phase, so a round trip (cable both
// ways + the encoder's output delay) up to HALF + HALF - 3 cycles is read
// correctly. This reader has no delay compensation: keep the clock at or
// below 2 MHz and the cable within that round trip.

`default_nettype none

module endat_reader #(
    parameter POS_BITS = 25,
    parameter HALF = 4,          // system clocks per clock half period
    parameter FIRST_LOW = 8,     // the first low phase F1..R1 (t_ST), system clocks
    parameter POLL_MAX = 64,     // clock periods after F1 to find the start bit
    parameter REST = 4400        // clock high after a read (> t_b), system clocks
) (
    input  wire                clk,
    input  wire                arst_n,
    input  wire                trig,        // start a read (ignored unless ready)
    output reg                 ready,       // idle: a trig now starts a read
    output reg  [POS_BITS-1:0] pos_out,
    output reg                 err1_out,    // F1 as received (1 = the encoder reports an error)
    output reg                 crc_ok,
    output reg                 got,         // one cycle: pos_out, err1_out and crc_ok are new
    output reg                 no_start,    // one cycle: no start bit within POLL_MAX periods
    output reg                 ck = 1'b1,   // idle high from power-up, before any reset
    output reg                 dout = 1'b1,    // to the transceiver's D
    output reg                 dout_en = 1'b0, // to the transceiver's DE (off from power-up, as ck is idle)
    input  wire                din          // from the transceiver's R
);

localparam [5:0] MODE = 6'b000111;          // sent left to right: M2 M1 M0 /M2 /M1 /M0
localparam S_IDLE = 3'd0, S_LOW = 3'd1, S_HIGH = 3'd2, S_REST = 3'd3;

reg [2:0] st;
reg [15:0] tmr;
reg [7:0] period;          // clock periods since F1 (1 = the first)
reg [1:0] rx_sync;
reg found;                 // start bit seen
reg [7:0] nbits;           // bits taken after the start bit
reg [POS_BITS-1:0] shreg;
reg f1_bit;
reg [3:0] crc_rx;            // the first four CRC bits (the fifth is the sample itself)
reg [4:0] lfsr;            // MakeCrcPos's ff[4..0]
reg [31:0] rest_tmr;

// One step of the seed's generator (appendix A4, MakeCrcPos) on data bit b.
function [4:0] crc_step(input [4:0] f, input b);
    reg ex;
    begin
        ex = f[4] ^ b;
        crc_step = {f[3], f[2] ^ ex, f[1], f[0] ^ ex, ex};
    end
endfunction

always @(posedge clk or negedge arst_n) begin
    if (!arst_n) begin
        st <= S_IDLE;
        ck <= 1'b1;
        dout <= 1'b1;
        dout_en <= 1'b0;
        ready <= 1'b0;
        got <= 1'b0;
        no_start <= 1'b0;
        pos_out <= {POS_BITS{1'b0}};
        err1_out <= 1'b0;
        crc_ok <= 1'b0;
        rx_sync <= 2'b11;
        tmr <= 0;
        period <= 0;
        found <= 1'b0;
        nbits <= 0;
        shreg <= {POS_BITS{1'b0}};
        f1_bit <= 1'b0;
        crc_rx <= 4'd0;
        lfsr <= 5'h1f;
        rest_tmr <= 0;
    end else begin
        rx_sync <= {rx_sync[0], din};
        got <= 1'b0;
        no_start <= 1'b0;
        case (st)
        S_IDLE: begin
            ready <= 1'b1;
            if (trig && ready) begin
                ready <= 1'b0;
                ck <= 1'b0;                        // F1: the encoder latches
                tmr <= FIRST_LOW - 1;
                period <= 1;
                found <= 1'b0;
                nbits <= 0;
                lfsr <= 5'h1f;
                st <= S_LOW;
            end
        end
        S_LOW: if (tmr != 0)
            tmr <= tmr - 1;
        else begin
            // The last cycle of a low phase: the sampling point.
            if (period >= 12 && !found) begin
                // Polling: the earliest start bit is put at R11 (10.5 periods after F1).
                if (rx_sync[1])
                    found <= 1'b1;
            end else if (found) begin
                nbits <= nbits + 1;
                if (nbits == 0) begin
                    f1_bit <= rx_sync[1];
                    lfsr <= crc_step(lfsr, rx_sync[1]);
                end else if (nbits <= POS_BITS) begin
                    shreg <= {rx_sync[1], shreg[POS_BITS-1:1]};
                    lfsr <= crc_step(lfsr, rx_sync[1]);
                end else
                    crc_rx <= {crc_rx[2:0], rx_sync[1]};
            end
            ck <= 1'b1;
            tmr <= HALF - 1;
            if (found && nbits == POS_BITS + 5) begin
                // The CRC's last bit: this rising edge is the last; publish.
                pos_out <= shreg;
                err1_out <= f1_bit;
                crc_ok <= ({crc_rx, rx_sync[1]} == ~lfsr);
                got <= 1'b1;
                rest_tmr <= REST - 1;
                st <= S_REST;
            end else if (!found && period == POLL_MAX) begin
                no_start <= 1'b1;
                rest_tmr <= REST - 1;
                st <= S_REST;
            end else
                st <= S_HIGH;
        end
        S_HIGH: if (tmr != 0)
            tmr <= tmr - 1;
        else begin
            ck <= 1'b0;                            // F(period + 1)
            tmr <= HALF - 1;
            period <= period + 1;
            // Mode bits at F2..F7; the driver off again at F8, before R8.
            if (period >= 1 && period <= 6) begin
                dout_en <= 1'b1;
                dout <= MODE[6 - period];
            end else begin
                dout_en <= 1'b0;
                dout <= 1'b1;
            end
            st <= S_LOW;
        end
        S_REST: if (rest_tmr != 0)
            rest_tmr <= rest_tmr - 1;
        else if (rx_sync[1])                       // the encoder's recovery over: line high
            st <= S_IDLE;
        default: st <= S_IDLE;
        endcase
    end
end

endmodule

`default_nettype wire
