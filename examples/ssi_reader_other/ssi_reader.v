// ssi_reader: a small SSI position reader written from the SAR58K24 manual's
// SSI section alone, independently of encoder-tb's ssi_master: other port
// names, an active-low reset, a registered request (one cycle more latency)
// and a different sampling point (the end of each low phase, where
// ssi_master samples just after the falling edge).
//
//   sclk  ‾‾‾‾\______/‾‾‾\___/‾‾‾\___/ ... ‾‾‾\___/‾‾‾‾‾‾‾‾‾‾‾‾‾ (REST) ‾‾
//              LEAD    HALF HALF            ^ sample at the last cycle of
//              ^ the encoder stores          each low phase (bit k put on
//                                            the line by rising edge k)
//
// sclk powers up high: a clock line that starts low (Verilator starts every
// register at 0) is a falling edge to the encoder, which stores a value and
// answers a read nobody asked for.
//
// The data input passes a 2-flop synchroniser, so the sample is the pin as
// it was 2 cycles before the end of the low phase.

`default_nettype none

module ssi_reader #(
    parameter WIDTH = 12,
    parameter HALF = 8,       // system clocks per clock half period
    parameter LEAD = 16,      // first low phase (T_cs), system clocks
    parameter REST = 2000     // clock-high rest after a read (> the encoder's monoflop)
) (
    input  wire             clk,
    input  wire             reset_n,
    input  wire             read_req,
    output reg  [WIDTH-1:0] value,
    output reg              value_ok,
    output reg              sclk = 1'b1,   // idle high from power-up, before any reset
    input  wire             sdata
);

localparam IDLE = 2'd0, LOW = 2'd1, HIGH = 2'd2, WAIT = 2'd3;

reg [1:0] phase;
reg [31:0] timer;
reg [7:0] bitno;
reg [WIDTH-1:0] shift;
reg req_q;
reg [1:0] sync;

always @(posedge clk) begin
    if (!reset_n) begin
        phase <= IDLE;
        sclk <= 1'b1;
        value <= {WIDTH{1'b0}};
        value_ok <= 1'b0;
        req_q <= 1'b0;
        sync <= 2'b11;
        timer <= 0;
        bitno <= 0;
        shift <= {WIDTH{1'b0}};
    end else begin
        sync <= {sync[0], sdata};
        req_q <= read_req;
        value_ok <= 1'b0;
        case (phase)
        IDLE: if (req_q) begin
            sclk <= 1'b0;
            timer <= LEAD - 1;
            bitno <= 0;
            phase <= LOW;
        end
        LOW: if (timer == 0) begin
            // End of a low phase: every low phase but the first carries a bit.
            if (bitno != 0)
                shift <= {shift[WIDTH-2:0], sync[1]};
            if (bitno == WIDTH) begin
                sclk <= 1'b1;
                timer <= REST - 1;
                phase <= WAIT;
            end else begin
                sclk <= 1'b1;
                timer <= HALF - 1;
                phase <= HIGH;
            end
        end else
            timer <= timer - 1;
        HIGH: if (timer == 0) begin
            sclk <= 1'b0;
            timer <= HALF - 1;
            bitno <= bitno + 1;
            phase <= LOW;
        end else
            timer <= timer - 1;
        WAIT: if (timer == 0) begin
            value <= shift;
            value_ok <= 1'b1;
            phase <= IDLE;
        end else
            timer <= timer - 1;
        endcase
    end
end

endmodule

`default_nettype wire
