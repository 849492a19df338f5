// modbus_reader: a small Modbus RTU poller of an encoder's position (seed 001,
// 3.1.7: function 03, two registers from address 0x0000, the 32-bit position
// high byte first), written from the manual alone, independently of
// encoder-tb's modbus_master: other port names (an RS-485 transceiver's DI,
// DE, RO), a synchronous active-low reset, its own UART (8 clocks per bit,
// three samples around each bit's middle, a character whose three samples
// disagree is noise) and its own CRC-16 code, bit-serial beside the UART in
// both directions (the request's CRC is the register after its 6th byte; an
// answer is good when the register is 0 after its own CRC bytes). It reports
// as soon as the 9th character has arrived, and keeps the 3.5-character
// silence only before its next request.
//
//   de   _/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_____________________________________________
//   di   ‾‾\_ a _/\_03_/ .. \_crc_/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//   ro   (own echo) ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾|<-device's t3.5 + delay->|\_a_/\_03_/\_04_/..\_crc_/‾‾
//        |<- t3.5 of silence before ->|                                      ^ ok / err
//
// Request: a 03 00 00 00 02 CRClo CRChi. Answer: a 03 04 b3 b2 b1 b0 CRClo
// CRChi; an exception a 83 code CRClo CRChi is reported as such. CRC-16:
// register FFFF, each data bit LSB first: shift right, XOR A001 when the bit
// out differs from the data bit (the seed's steps 1 to 8, one bit at a time);
// low byte first on the line. Characters 8N1, no parity (factory setting).
// Seed silent or Modbus-spec readings, decided here: the silences count
// 11-bit characters (a Modbus character is 11 bits; on a 10-bit line that is
// the longer, safe side): t3.5 = 38.5 bits before a request, a gap over
// t1.5 = 16.5 bits inside the answer is an error; the answer must begin
// within REPLY_TIMEOUT clocks of the request's end.
//
// di and de power up idle (high, off): Verilator starts registers at 0.

`default_nettype none

module modbus_reader #(
    parameter CPB = 8,                     // clocks per bit (153.6 kHz for 19200 baud)
    parameter T35 = 308,                   // 38.5 bits of CPB
    parameter T15 = 132,                   // 16.5 bits of CPB
    parameter REPLY_TIMEOUT = 3072         // clocks (20 ms at 153.6 kHz)
) (
    input  wire        clk,
    input  wire        nreset,             // synchronous, active low
    input  wire        poll,               // one pulse: read the position of `slave`
    input  wire [7:0]  slave,
    output reg  [31:0] position,
    output reg         ok,                 // one pulse: position is new and good
    output reg         err,                // one pulse: the poll failed, why in err_code
    output reg  [2:0]  err_code,           // 1 no answer, 2 framing or noise, 3 gap, 4 CRC, 5 exception, 6 wrong address/function/count
    output reg  [7:0]  exception,
    output reg         di = 1'b1,
    output reg         de = 1'b0,
    input  wire        ro
);

localparam W_SILENT = 3'd0, W_READY = 3'd1, W_SEND = 3'd2, W_REPLY = 3'd3, W_CHAR = 3'd4, W_BETWEEN = 3'd5, W_JUDGE = 3'd6;

reg [2:0]  w = W_SILENT;
reg [2:0]  ro_s = 3'b111;
wire       line = ro_s[2];                 // synchronised: the pin as it was 2 to 3 clocks ago
reg        want;
reg [15:0] quiet;                          // clocks the line has been high (saturating)
reg [15:0] k;
reg [15:0] crc;
reg [7:0]  tx_byte;
reg [3:0]  tx_bit;                         // 0 start, 1..8 data, 9 stop
reg [3:0]  nbyte;
reg [3:0]  rx_bit;
reg [2:0]  s3;                             // the three samples of the bit
reg [7:0]  rx_byte;
reg        spoiled;
reg [7:0]  r [0:8];

function [15:0] crc_step(input [15:0] c, input b);
    crc_step = (c[0] ^ b) ? ((c >> 1) ^ 16'hA001) : (c >> 1);
endfunction

// the request's bytes before the CRC
function [7:0] req_byte(input [3:0] i, input [7:0] a);
    case (i)
        4'd0: req_byte = a;
        4'd1: req_byte = 8'h03;
        4'd5: req_byte = 8'h02;
        default: req_byte = 8'h00;
    endcase
endfunction

wire vote = (s3[0] & s3[1]) | (s3[1] & s3[2]) | (s3[0] & s3[2]);

always @(posedge clk) begin
    ro_s <= {ro_s[1:0], ro};
    ok <= 1'b0;
    err <= 1'b0;
    if (poll) want <= 1'b1;
    // silence on the line, either direction (our own driver included)
    if (de || !line) quiet <= 16'd0;
    else if (quiet != 16'hFFFF) quiet <= quiet + 1'b1;
    if (!nreset) begin
        w <= W_SILENT;
        di <= 1'b1;
        de <= 1'b0;
        want <= 1'b0;
        quiet <= 16'd0;
        ro_s <= 3'b111;
    end else case (w)
        W_SILENT:
            if (quiet >= T35) w <= W_READY;
        W_READY:
            if (!line) w <= W_SILENT;               // someone talks: wait for silence again
            else if (want || poll) begin
                want <= 1'b0;
                de <= 1'b1;
                crc <= 16'hFFFF;
                nbyte <= 4'd0;
                tx_byte <= slave;
                tx_bit <= 4'd0;
                k <= 16'd0;
                w <= W_SEND;
            end
        W_SEND: begin
            // bit tx_bit of character nbyte, CPB clocks each (shown one clock
            // after it is chosen; the driver goes off one clock after the
            // last stop bit's CPB clocks)
            di <= (tx_bit == 4'd0) ? 1'b0 : (tx_bit == 4'd9) ? 1'b1 : tx_byte[tx_bit - 1];
            if (k == CPB - 1) begin
                k <= 16'd0;
                if (tx_bit >= 4'd1 && tx_bit <= 4'd8 && nbyte < 4'd6)
                    crc <= crc_step(crc, tx_byte[tx_bit - 1]);
                if (tx_bit != 4'd9)
                    tx_bit <= tx_bit + 1'b1;
                else begin
                    tx_bit <= 4'd0;
                    nbyte <= nbyte + 1'b1;
                    case (nbyte)
                        4'd5: tx_byte <= crc[7:0];
                        4'd6: tx_byte <= crc[15:8];
                        default: tx_byte <= req_byte(nbyte + 1'b1, slave);
                    endcase
                    if (nbyte == 4'd7) begin
                        crc <= 16'hFFFF;
                        spoiled <= 1'b0;
                        nbyte <= 4'd0;
                        w <= W_REPLY;
                    end
                end
            end else
                k <= k + 1'b1;
        end
        W_REPLY: begin
            de <= 1'b0;
            di <= 1'b1;
            if (!line) begin
                k <= 16'd1;
                rx_bit <= 4'd0;
                w <= W_CHAR;
            end else if (k == REPLY_TIMEOUT) begin
                err <= 1'b1;
                err_code <= 3'd1;
                w <= W_SILENT;
            end else
                k <= k + 1'b1;
        end
        W_CHAR: begin
            // k counts from the cycle the start bit was seen (k = 1 there): the
            // samples at k = 8n + 2, 3, 4 see the line 2 to 5 clocks into bit n
            k <= (k == CPB - 1) ? 16'd0 : k + 1'b1;
            if (k == CPB / 2 - 2) s3[0] <= line;
            if (k == CPB / 2 - 1) s3[1] <= line;
            if (k == CPB / 2)     s3[2] <= line;
            if (k == CPB / 2 + 1) begin
                if (s3 != 3'b000 && s3 != 3'b111) spoiled <= 1'b1;   // noise
                rx_bit <= rx_bit + 1'b1;
                if (rx_bit == 4'd0 && vote) spoiled <= 1'b1;
                if (rx_bit >= 4'd1 && rx_bit <= 4'd8) begin
                    rx_byte <= {vote, rx_byte[7:1]};
                    crc <= crc_step(crc, vote);
                end
                if (rx_bit == 4'd9) begin
                    if (!vote) spoiled <= 1'b1;             // framing
                    if (nbyte <= 4'd8) r[nbyte] <= rx_byte;
                    nbyte <= nbyte + 1'b1;
                    k <= 16'd0;
                    w <= W_BETWEEN;
                end
            end
        end
        W_BETWEEN:
            if (nbyte == 4'd9 || (nbyte == 4'd5 && r[1] == 8'h83))
                w <= W_JUDGE;
            else if (!line) begin
                k <= 16'd1;
                rx_bit <= 4'd0;
                w <= W_CHAR;
            end else if (k == T15) begin
                err <= 1'b1;
                err_code <= spoiled ? 3'd2 : 3'd3;
                w <= W_SILENT;
            end else
                k <= k + 1'b1;
        W_JUDGE: begin
            w <= W_SILENT;
            if (spoiled) begin
                err <= 1'b1; err_code <= 3'd2;
            end else if (crc != 16'h0000) begin
                err <= 1'b1; err_code <= 3'd4;
            end else if (r[0] != slave) begin
                err <= 1'b1; err_code <= 3'd6;
            end else if (r[1] == 8'h83) begin
                err <= 1'b1; err_code <= 3'd5; exception <= r[2];
            end else if (r[1] != 8'h03 || r[2] != 8'h04) begin
                err <= 1'b1; err_code <= 3'd6;
            end else begin
                position <= {r[3], r[4], r[5], r[6]};
                ok <= 1'b1;
            end
        end
        default: w <= W_SILENT;
    endcase
end

endmodule

`default_nettype wire
