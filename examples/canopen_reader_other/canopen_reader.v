// canopen_reader: a tiny CANopen position reader on mini_can (written for
// the encoder-tb examples, independently of encoder-tb's canopen_master).
// One operation at a time: pulse `go` with `op` (and `arg`) while `ready`;
// `done` pulses with `value` when it succeeded, `failed` when the answer was
// wrong or missing (TIMEOUT clocks) or the request could not be sent.
//
//   op 0  wait for the boot-up of NODE: 0x80 + NODE without data (the
//         gateway note, seed 003 §2.2) or 0x700 + NODE with one byte 00
//         (CiA DS 301)
//   op 1  NMT start remote node: 0x000 [01 NODE]; done once sent
//   op 2  SDO upload of 6004h sub 0 (position value): 0x600 + NODE
//         [40 04 60 00 00 00 00 00]; the answer on 0x580 + NODE must be the
//         expedited 4-byte upload [43 04 60 00 v0 v1 v2 v3]; value = v (an
//         abort 80h ... fails)
//   op 3  SYNC (0x080, no data), then TPDO2 on 0x280 + NODE: value = its
//         first four bytes, low byte first
//   op 4  SAR58K24 in CAN mode (seed 001 §3.4), node arg[7:0]: the click
//         0x200 + node [80 node 00 00 00 00 00 00], answered on 0x100 + node
//         with the position, low byte first
//   op 5  SAR58K24 configuration channel 0x7E5 [arg[15:8] arg[7:0] 00 ...]:
//         `04 01` (enter) is done once sent; any other command waits for
//         the answer on 0x7E5 whose first byte is the command: value =
//         {byte 0, byte 1} (11 00, 13 00)
//
// Frames on other identifiers are ignored while an answer is awaited.

`default_nettype none

module canopen_reader #(
    parameter NODE = 5,
    parameter TIMEOUT = 40000,
    parameter CLKS_PER_BIT = 16,
    parameter SAMPLE_AT = 11,
    parameter JUMP = 3
) (
    input  wire        clk,
    input  wire        rst_n,
    input  wire        can_rxd,
    output wire        can_txd,
    input  wire        go,
    input  wire [2:0]  op,
    input  wire [15:0] arg,
    output wire        ready,
    output reg         done,
    output reg         failed,
    output reg  [31:0] value
);

localparam S_READY = 2'd0, S_SEND = 2'd1, S_WAIT = 2'd2;

reg [1:0] state;
reg [2:0] op_r;
reg [15:0] arg_r;
reg [31:0] timer;
reg send;
reg [10:0] send_id;
reg [3:0] send_len;
reg [63:0] send_bytes;
wire busy, sent, lost, tx_fail, got, got_rtr, fault;
wire [10:0] got_id;
wire [3:0] got_len;
wire [63:0] got_bytes;
wire [2:0] fault_kind;

mini_can #(.CLKS_PER_BIT(CLKS_PER_BIT), .SAMPLE_AT(SAMPLE_AT), .JUMP(JUMP)) u_can (
    .clk(clk), .rst_n(rst_n), .can_rxd(can_rxd), .can_txd(can_txd),
    .send(send), .send_id(send_id), .send_len(send_len), .send_bytes(send_bytes),
    .busy(busy), .sent(sent), .lost(lost), .tx_fail(tx_fail),
    .got(got), .got_id(got_id), .got_rtr(got_rtr), .got_len(got_len), .got_bytes(got_bytes),
    .fault(fault), .fault_kind(fault_kind)
);

assign ready = state == S_READY;

/* byte i of the received frame */
function [7:0] byte_of(input [63:0] d, input integer i);
    byte_of = d[63 - 8 * i -: 8];
endfunction

wire [31:0] le0 = {byte_of(got_bytes, 3), byte_of(got_bytes, 2), byte_of(got_bytes, 1), byte_of(got_bytes, 0)};
wire [31:0] le4 = {byte_of(got_bytes, 7), byte_of(got_bytes, 6), byte_of(got_bytes, 5), byte_of(got_bytes, 4)};
wire [6:0] node7 = NODE;

always @(posedge clk) begin
    send <= 1'b0;
    done <= 1'b0;
    failed <= 1'b0;
    if (!rst_n) begin
        state <= S_READY;
        value <= 0;
    end else case (state)
    S_READY: if (go) begin
        op_r <= op;
        arg_r <= arg;
        timer <= 0;
        send_bytes <= 0;
        case (op)
        3'd0: state <= S_WAIT;
        3'd1: begin send_id <= 11'h000; send_len <= 2; send_bytes <= {8'h01, 1'b0, node7, 48'd0}; end
        3'd2: begin send_id <= 11'h600 + NODE; send_len <= 8; send_bytes <= {32'h40046000, 32'd0}; end
        3'd3: begin send_id <= 11'h080; send_len <= 0; end
        3'd4: begin send_id <= 11'h200 + arg[7:0]; send_len <= 8; send_bytes <= {8'h80, arg[7:0], 48'd0}; end
        default: begin send_id <= 11'h7E5; send_len <= 8; send_bytes <= {arg, 48'd0}; end
        endcase
        if (op != 3'd0) begin
            send <= 1'b1;
            state <= S_SEND;
        end
    end
    S_SEND: begin
        timer <= timer + 1;
        if (tx_fail || timer == TIMEOUT) begin
            failed <= 1'b1;
            state <= S_READY;
        end else if (sent) begin
            timer <= 0;
            if (op_r == 3'd1 || (op_r == 3'd5 && arg_r[15:8] == 8'h04)) begin
                done <= 1'b1;
                state <= S_READY;
            end else
                state <= S_WAIT;
        end
    end
    default: begin                              // S_WAIT
        timer <= timer + 1;
        if (timer == TIMEOUT) begin
            failed <= 1'b1;
            state <= S_READY;
        end else if (got && !got_rtr) begin
            case (op_r)
            3'd0: if ((got_id == 11'h080 + NODE && got_len == 0) ||
                      (got_id == 11'h700 + NODE && got_len == 1 && byte_of(got_bytes, 0) == 8'h00)) begin
                done <= 1'b1;
                state <= S_READY;
            end
            3'd2: if (got_id == 11'h580 + NODE) begin
                value <= le4;
                if (got_len == 8 && got_bytes[63:32] == 32'h43046000)
                    done <= 1'b1;
                else
                    failed <= 1'b1;
                state <= S_READY;
            end
            3'd3: if (got_id == 11'h280 + NODE) begin
                value <= le0;
                if (got_len >= 4) done <= 1'b1;
                else failed <= 1'b1;
                state <= S_READY;
            end
            3'd4: if (got_id == 11'h100 + arg_r[7:0]) begin
                value <= le0;
                if (got_len >= 4) done <= 1'b1;
                else failed <= 1'b1;
                state <= S_READY;
            end
            default: if (got_id == 11'h7E5 && byte_of(got_bytes, 0) == arg_r[15:8]) begin
                value <= {16'd0, got_bytes[63:48]};
                done <= 1'b1;
                state <= S_READY;
            end
            endcase
        end
    end
    endcase
end

endmodule

`default_nettype wire
