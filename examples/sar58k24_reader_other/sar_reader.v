// sar_reader: a small SAR58K24 reader for the bus-command mode (seed 001,
// 3.1.5: "BC AA Bx" asks encoder x, which answers "FF 81 <data, high byte
// first> <checksum>"), written from the manual alone, independently of
// encoder-tb's sar_async_host: other port names, an asynchronous active-low
// reset, its own 8N1 transmitter and receiver (8 clocks per bit; the start
// bit confirmed at its middle, then one sample per bit at the middle), and
// it takes the answer's second byte either way the manual prints it.
//
//   tx_drive __/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\___________________________________________
//   tx_line  ‾‾\_BC_/\_AA_/\_Bx_/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//   rx_line  ‾‾(own echo)‾‾‾‾‾‾‾‾|<- delay ->|\_FF_/\_81_/\_hi_/ .. \_lo_/\_cs_/‾
//                                ^ answer must begin within ANSWER_TIMEOUT clocks
//                                                                 ^ got / bad
//
// Characters: start 0, 8 data bits LSB first, stop 1, no parity ("one byte is
// 10 bits ... no parity check bit"). Answer: FF, then 81 (every frame table)
// or Bx (the bus text: "the second byte of the return data is the product
// address number"): the manual contradicts itself, so both are taken; then
// DATA_BYTES data bytes, high first (2 up to 16 bits, 3 up to 24, 4 above),
// then the checksum: the low 8 bits of the sum of all the bytes before it
// (the seed's FF 81 01 7F 00: FF + 81 + 01 + 7F = 0x200).
// Seed silent, decided here: the answer must begin within ANSWER_TIMEOUT
// clocks of the command's stop bit (the manual gives no answer delay; 2 ms,
// about 20 times the 100 us such an encoder needs), and a silence of more
// than 2 characters inside the answer ends it as broken.
//
// tx_line and tx_drive power up idle (high, off): Verilator starts registers at 0.

`default_nettype none

module sar_reader #(
    parameter OVS = 8,                  // clocks per bit (153.6 kHz for 19200 baud)
    parameter DATA_BYTES = 3,           // 17 to 24 bits
    parameter ANSWER_TIMEOUT = 307,     // clocks, command's end to answer's start bit (2 ms)
    parameter GAP_LIMIT = 20 * 8        // clocks of silence that end a broken answer (2 characters)
) (
    input  wire                      clock,
    input  wire                      reset_b,      // asynchronous, active low
    input  wire                      ask,          // one pulse: read encoder `station`
    input  wire [3:0]                station,      // x of BC AA Bx
    output reg  [8*DATA_BYTES-1:0]   word,         // the position, valid with `got`
    output reg                       got,          // one pulse: a good answer
    output reg                       bad,          // one pulse: no good answer, why in `why`
    output reg  [1:0]                why,          // 0 no answer, 1 broken character or frame, 2 header, 3 checksum
    output reg                       tx_line = 1'b1,
    output reg                       tx_drive = 1'b0,
    input  wire                      rx_line
);

localparam NCHARS = DATA_BYTES + 3;
localparam P_IDLE = 3'd0, P_SEND = 3'd1, P_WAIT = 3'd2, P_RECV = 3'd3, P_CHECK = 3'd4;

reg [2:0]  phase;

// receiver
wire [7:0] rx_byte;
wire       rx_strobe, rx_broken, rx_busy;
sar_rx8 #(.OVS(OVS)) u_rx (
    .clock(clock), .reset_b(reset_b), .line(rx_line), .enable(phase == P_WAIT || phase == P_RECV),
    .data(rx_byte), .strobe(rx_strobe), .broken(rx_broken), .busy(rx_busy)
);

reg [29:0] out_bits;                 // BC AA Bx with start and stop bits, bit 0 first
reg [4:0]  out_left;
reg [15:0] t;
reg [2:0]  nchar;
reg [7:0]  sum;
reg [7:0]  head0, head1, check;
reg        broken;
reg [8*DATA_BYTES-1:0] acc;

always @(posedge clock or negedge reset_b) begin
    if (!reset_b) begin
        phase <= P_IDLE;
        tx_line <= 1'b1;
        tx_drive <= 1'b0;
        got <= 1'b0;
        bad <= 1'b0;
        why <= 2'd0;
        word <= 0;
        t <= 0;
    end else begin
        got <= 1'b0;
        bad <= 1'b0;
        case (phase)
            P_IDLE:
                if (ask) begin
                    out_bits <= {1'b1, 4'hB, station, 1'b0, 1'b1, 8'hAA, 1'b0, 1'b1, 8'hBC, 1'b0};
                    out_left <= 5'd30;
                    t <= 0;
                    tx_drive <= 1'b1;
                    phase <= P_SEND;
                end
            P_SEND: begin
                // one bit every OVS clocks; the driver is released one clock
                // after the last stop bit's full length
                tx_line <= out_bits[0];
                if (out_left == 5'd0) begin
                    tx_drive <= 1'b0;
                    tx_line <= 1'b1;
                    t <= 0;
                    nchar <= 0;
                    sum <= 8'd0;
                    broken <= 1'b0;
                    phase <= P_WAIT;
                end else if (t == OVS - 1) begin
                    t <= 0;
                    out_bits <= {1'b1, out_bits[29:1]};
                    out_left <= out_left - 1'b1;
                end else
                    t <= t + 1'b1;
            end
            P_WAIT:
                // the answer's first start bit within ANSWER_TIMEOUT
                if (rx_busy) begin
                    t <= 0;
                    phase <= P_RECV;
                end else if (t == ANSWER_TIMEOUT) begin
                    bad <= 1'b1;
                    why <= 2'd0;
                    phase <= P_IDLE;
                end else
                    t <= t + 1'b1;
            P_RECV:
                if (rx_strobe) begin
                    t <= 0;
                    if (rx_broken) broken <= 1'b1;
                    case (nchar)
                        3'd0: head0 <= rx_byte;
                        3'd1: head1 <= rx_byte;
                        default:
                            if (nchar == NCHARS - 1) check <= rx_byte;
                            else acc <= {acc[8*DATA_BYTES-9:0], rx_byte};
                    endcase
                    if (nchar != NCHARS - 1) sum <= sum + rx_byte;
                    nchar <= nchar + 1'b1;
                    if (nchar == NCHARS - 1) phase <= P_CHECK;
                end else if (rx_busy)
                    t <= 0;
                else if (t == GAP_LIMIT) begin
                    bad <= 1'b1;
                    why <= 2'd1;
                    phase <= P_IDLE;
                end else
                    t <= t + 1'b1;
            P_CHECK: begin
                phase <= P_IDLE;
                if (broken) begin
                    bad <= 1'b1; why <= 2'd1;
                end else if (head0 != 8'hFF || (head1 != 8'h81 && head1 != {4'hB, station})) begin
                    bad <= 1'b1; why <= 2'd2;
                end else if (check != sum) begin
                    bad <= 1'b1; why <= 2'd3;
                end else begin
                    word <= acc;
                    got <= 1'b1;
                end
            end
            default: phase <= P_IDLE;
        endcase
    end
end

endmodule

// sar_rx8: 8N1 receiver, OVS clocks per bit. The line passes two flops; a
// low level while idle is a start bit, confirmed low again at its middle
// (else a glitch, dropped); then each data bit and the stop bit are taken
// once, OVS clocks apart, at their middles. `strobe` pulses with each
// character, `broken` with it when the stop bit was low. `busy` is high from
// the start bit to the stop bit's middle.
module sar_rx8 #(
    parameter OVS = 8
) (
    input  wire       clock,
    input  wire       reset_b,
    input  wire       line,
    input  wire       enable,
    output reg  [7:0] data,
    output reg        strobe,
    output reg        broken,
    output wire       busy
);

reg [1:0] meta;
reg [3:0] n;             // 0 idle, 1 start, 2..9 data, 10 stop
reg [7:0] c;
reg [7:0] sh;
assign busy = (n != 4'd0);

always @(posedge clock or negedge reset_b) begin
    if (!reset_b) begin
        meta <= 2'b11;
        n <= 4'd0;
        strobe <= 1'b0;
        broken <= 1'b0;
    end else begin
        meta <= {meta[0], line};
        strobe <= 1'b0;
        if (n == 4'd0) begin
            if (enable && !meta[1]) begin
                n <= 4'd1;
                c <= 8'd1;
            end
        end else if (c == (n == 4'd1 ? OVS / 2 - 1 : OVS - 1)) begin
            c <= 8'd0;
            if (n == 4'd1)
                n <= meta[1] ? 4'd0 : 4'd2;       // the start bit's middle: still low?
            else if (n == 4'd10) begin
                data <= sh;
                broken <= !meta[1];
                strobe <= 1'b1;
                n <= 4'd0;
            end else begin
                sh <= {meta[1], sh[7:1]};
                n <= n + 1'b1;
            end
        end else
            c <= c + 1'b1;
    end
end

endmodule

`default_nettype wire
