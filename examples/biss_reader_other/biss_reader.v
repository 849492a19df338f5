// biss_reader: a minimal BiSS-C reader for one slave, written from the
// SAR58K24 manual's BiSS-C section alone, independently of encoder-tb's
// biss_master: other port names, a registered request, and no line-delay
// compensation: every bit is taken at a falling MA edge. The reader finds the
// ack (first 0) and the start bit (first 1) by level, so a cable delay shifts
// the whole frame by whole MA periods and costs nothing but MA periods; its
// limit is that the bit changes must stay clear of the sampling edges. With
// 35 m at 1 MHz and a 40 MHz clock the changes land next to them, and 50 ns
// of cable jitter already makes it misread (the emulator's cable with
// `jitter_ns = 50` shows it); 20 m without jitter is well clear.
//
//   ma   ‾‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾ ... ‾\__/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//   slo  ‾‾‾‾‾‾‾‾‾‾‾‾‾\___.../‾‾\_X CDS X data X nE X nW X CRC X 0 ... /‾‾‾
//   take at each falling edge: ack (first 0), start (first 1), CDS, data
//   MSB first, nE, nW, 6 CRC bits (x^6 + x + 1, init 0, sent inverted);
//   one more MA period (the slave's 0 after the CRC), then MA stays high
//   until the slave has ended its timeout (SLO low, then high again).

`default_nettype none

module biss_reader #(
    parameter DATA_BITS = 16,
    parameter HALF = 20            // system clocks per MA half period
) (
    input  wire                 clk,
    input  wire                 reset_n,
    input  wire                 go,
    output reg  [DATA_BITS-1:0] pos,
    output reg                  n_error,
    output reg                  n_warning,
    output reg                  crc_good,
    output reg                  ready,
    output reg                  ma = 1'b1,
    input  wire                 slo
);

localparam S_IDLE = 3'd0, S_ACK = 3'd1, S_START = 3'd2, S_BITS = 3'd3, S_STOP = 3'd4, S_LOW = 3'd5, S_RELEASE = 3'd6;
localparam FRAME_BITS = 1 + DATA_BITS + 2 + 6;   // CDS, data, nE, nW, CRC

reg [2:0] st;
reg [15:0] tick;
reg [7:0] got;
reg [FRAME_BITS-1:0] frame;
reg [1:0] sync;
reg go_q;
reg [5:0] crc;
integer i;

// The CRC over data, nE and nW (MSB first), then inverted as on the wire.
function [5:0] crc6(input [DATA_BITS+1:0] bits);
    reg [5:0] c;
    reg fb;
    integer k;
    begin
        c = 6'd0;
        for (k = DATA_BITS + 1; k >= 0; k = k - 1) begin
            fb = c[5] ^ bits[k];
            c = {c[4:0], 1'b0} ^ (fb ? 6'b000011 : 6'b000000);
        end
        crc6 = ~c;
    end
endfunction

wire falling = (tick == HALF - 1) && ma;    // MA goes low at the end of this cycle

always @(posedge clk) begin
    sync <= {sync[0], slo};
    go_q <= go;
    ready <= 1'b0;
    if (!reset_n) begin
        st <= S_IDLE;
        ma <= 1'b1;
        tick <= 0;
        sync <= 2'b11;
        go_q <= 1'b0;
    end else begin
        if (st != S_IDLE && st != S_LOW && st != S_RELEASE) begin
            tick <= (tick == HALF - 1) ? 16'd0 : tick + 16'd1;
            if (tick == HALF - 1)
                ma <= ~ma;
        end
        case (st)
        S_IDLE: if (go_q && sync[1]) begin
            st <= S_ACK;
            ma <= 1'b0;
            tick <= 0;
        end
        S_ACK: if (falling && !sync[1]) st <= S_START;
        S_START: if (falling && sync[1]) begin
            st <= S_BITS;
            got <= 0;
        end
        S_BITS: if (falling) begin
            frame <= {frame[FRAME_BITS-2:0], sync[1]};
            got <= got + 8'd1;
            if (got == FRAME_BITS - 1)
                st <= S_STOP;
        end
        // One more MA period makes the slave send its 0 after the CRC; MA
        // then stays high (CDM = 0) while the slave's timeout runs.
        S_STOP: if (tick == HALF - 1 && !ma) st <= S_LOW;
        S_LOW: if (!sync[1]) st <= S_RELEASE;
        S_RELEASE: if (sync[1]) begin
            pos <= frame[FRAME_BITS-2:8];
            n_error <= frame[7];
            n_warning <= frame[6];
            crc_good <= crc6(frame[FRAME_BITS-2:6]) == frame[5:0];
            ready <= 1'b1;
            st <= S_IDLE;
        end
        default: st <= S_IDLE;
        endcase
    end
end

endmodule

`default_nettype wire
