// can_controller: CAN 2.0 controller (ISO 11898-1 classical CAN); the cycle-for-cycle twin of model::can::Controller.
//
// What it is for
//   One transmit buffer (standard frames, data or remote) sent with
//   arbitration and automatic retransmission; reception of standard and
//   extended frames with an ID/mask acceptance filter; ACK; error detection
//   (bit, stuff, CRC, form, ACK), active and passive error flags, overload
//   frames recognised; TEC/REC with error-active, error-passive and bus-off,
//   recovery after 128 x 11 recessive bits. Connect o_can_tx to the
//   transceiver's TXD and i_can_rx to its RXD (asynchronous: it passes a
//   SYNC_STAGES-flop synchroniser). Pulse i_tx_start with i_tx_* while
//   o_tx_busy is low; o_tx_done pulses when the frame was sent and
//   acknowledged. o_rx_valid pulses with o_rx_* holding an accepted frame
//   (the filter accepts when ((id ^ i_filter_id) & i_filter_mask) == 0;
//   standard identifiers are 11-bit values, extended ones 29-bit).
//
// Parameters (the Rust ControllerConfig / BitTiming field of the same name in lower case)
//   BRP          f_sys cycles per time quantum
//   PROP_SEG     propagation segment, quanta (1..8)
//   PHASE_SEG1   phase segment 1, quanta (1..8)
//   PHASE_SEG2   phase segment 2, quanta (2..8)
//   SJW          synchronisation jump width, quanta (1..4, <= both phase segments)
//   SYNC_STAGES  flops of the i_can_rx synchroniser (2 or 3)
//   bit rate = f_sys / (BRP * (1 + PROP_SEG + PHASE_SEG1 + PHASE_SEG2)); 10 kbit/s to 1 Mbit/s
//
// Timing (docs/timing/can.md and model/src/can/ have the full story)
//
//   bit      |SYNC|PROP_SEG|PHASE_SEG1  ^sample   |PHASE_SEG2|
//   engine   reads the bus at the sample point, decides the next bit
//   o_can_tx <------------------ bit n ----------------------->< bit n+1
//   pulses   one cycle after the sample point that detects them
//
//   frame    SOF ID(11) RTR IDE r0 DLC(4) DATA CRC(15) | CRC-del ACK ACK-del EOF(7) IFS(3)
//   state    FRAME (stuffed) ....................... | CRC_DELIM ACK_SLOT ACK_DELIM EOF INTERMISSION
//   errors   ERR_FLAG (6) -> ERR_WAIT (until recessive) -> ERR_DELIM (7) -> INTERMISSION
//
// Hard synchronisation in IDLE, SUSPEND and the third intermission bit;
// resynchronisation on recessive-to-dominant edges after a recessive sample,
// once between sample points, by at most SJW, not while sending dominant.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module can_controller #(
    parameter BRP = 10,
    parameter PROP_SEG = 5,
    parameter PHASE_SEG1 = 8,
    parameter PHASE_SEG2 = 2,
    parameter SJW = 1,
    parameter SYNC_STAGES = 2
) (
    input  wire        i_clk,
    input  wire        i_rst,

    /* Transmit buffer */
    input  wire        i_tx_start,
    input  wire [10:0] i_tx_id,
    input  wire        i_tx_rtr,
    input  wire [3:0]  i_tx_dlc,
    input  wire [63:0] i_tx_data,
    output wire        o_tx_busy,
    output wire        o_tx_done,
    output wire        o_arb_lost,

    /* Acceptance filter */
    input  wire [28:0] i_filter_id,
    input  wire [28:0] i_filter_mask,

    /* Received frame (valid with o_rx_valid, held until the next) */
    output wire        o_rx_valid,
    output wire [28:0] o_rx_id,
    output wire        o_rx_ide,
    output wire        o_rx_rtr,
    output wire [3:0]  o_rx_dlc,
    output wire [63:0] o_rx_data,

    /* Fault confinement */
    output wire [8:0]  o_tec,
    output wire [7:0]  o_rec,
    output wire [1:0]  o_err_state,

    /* Error pulses */
    output wire        o_err_bit,
    output wire        o_err_stuff,
    output wire        o_err_crc,
    output wire        o_err_form,
    output wire        o_err_ack,
    output wire        o_overload,

    /* CAN transceiver */
    output wire        o_can_tx,
    input  wire        i_can_rx
);

localparam integer TSEG1 = PROP_SEG + PHASE_SEG1;
localparam integer NTQ = 1 + TSEG1 + PHASE_SEG2;
localparam [31:0] BRP_LAST_32 = BRP - 1;
localparam [31:0] TSEG1_32 = TSEG1;
localparam [31:0] LAST_TQ_32 = NTQ - 1;
localparam [31:0] SJW_32 = SJW;
localparam [9:0] BRP_LAST = BRP_LAST_32[9:0];
localparam [5:0] TSEG1_6 = TSEG1_32[5:0];
localparam [5:0] LAST_TQ_6 = LAST_TQ_32[5:0];
localparam [5:0] SJW_6 = SJW_32[5:0];
// REC after a successful reception from above 127 (model::can::controller::REC_RESTORE).
localparam [7:0] REC_RESTORE = 8'd119;

// States: the same names and codes as model::can::State.
localparam [3:0]
    INTEGRATE    = 4'd0,
    IDLE         = 4'd1,
    FRAME        = 4'd2,
    CRC_DELIM    = 4'd3,
    ACK_SLOT     = 4'd4,
    ACK_DELIM    = 4'd5,
    EOF          = 4'd6,
    INTERMISSION = 4'd7,
    SUSPEND      = 4'd8,
    ERR_FLAG     = 4'd9,
    OVL_FLAG     = 4'd10,
    ERR_WAIT     = 4'd11,
    ERR_DELIM    = 4'd12,
    BUS_OFF      = 4'd13;

// Error kinds of one sample point.
localparam [2:0] E_NONE = 3'd0, E_BIT = 3'd1, E_STUFF = 3'd2, E_CRC = 3'd3, E_FORM = 3'd4, E_ACK = 3'd5;

initial begin
    if (BRP < 1 || BRP > 1024) $error("can_controller: BRP must be 1 to 1024");
    if (PROP_SEG < 1 || PROP_SEG > 8 || PHASE_SEG1 < 1 || PHASE_SEG1 > 8) $error("can_controller: PROP_SEG and PHASE_SEG1 must be 1 to 8");
    if (PHASE_SEG2 < 2 || PHASE_SEG2 > 8) $error("can_controller: PHASE_SEG2 must be 2 to 8");
    if (SJW < 1 || SJW > 4 || SJW > PHASE_SEG1 || SJW > PHASE_SEG2) $error("can_controller: SJW must be 1 to 4 and at most both phase segments");
    if (NTQ < 8 || NTQ > 25) $error("can_controller: 8 to 25 quanta per bit");
    if (SYNC_STAGES < 2 || SYNC_STAGES > 3) $error("can_controller: SYNC_STAGES must be 2 or 3");
end

/* Input synchroniser: i_can_rx is asynchronous to i_clk. */
reg [2:0] sync_reg = 3'b111;
wire      rx = sync_reg[SYNC_STAGES-1];
reg       rx_prev_reg = 1'b1;
reg       last_sample_reg = 1'b1;

/* Bit clock */
reg [9:0] pre_cnt_reg = 10'd0, pre_cnt_next;
reg [5:0] tq_cnt_reg = 6'd0, tq_cnt_next;
reg [5:0] ext_reg = 6'd0, ext_next;
reg       short_reg = 1'b0, short_next;
reg       synced_reg = 1'b0, synced_next;

/* Protocol engine */
reg [3:0]  state_reg = INTEGRATE, state_next;
reg [3:0]  bit_cnt_reg = 4'd0, bit_cnt_next;
reg [6:0]  bo_seq_reg = 7'd0, bo_seq_next;
reg [6:0]  pos_reg = 7'd0, pos_next;
reg [2:0]  stuff_cnt_reg = 3'd0, stuff_cnt_next;
reg        last_bit_reg = 1'b1, last_bit_next;
reg [14:0] crc_reg = 15'd0, crc_next;
reg        crc_bad_reg = 1'b0, crc_bad_next;
reg [28:0] rx_id_reg = 29'd0, rx_id_next;
reg        rx_ide_reg = 1'b0, rx_ide_next;
reg        rx_rtr_reg = 1'b0, rx_rtr_next;
reg [3:0]  rx_dlc_reg = 4'd0, rx_dlc_next;
reg [63:0] rx_data_reg = 64'd0, rx_data_next;
reg [10:0] tx_id_reg = 11'd0, tx_id_next;
reg        tx_rtr_reg = 1'b0, tx_rtr_next;
reg [3:0]  tx_dlc_reg = 4'd0, tx_dlc_next;
reg [63:0] tx_data_reg = 64'd0, tx_data_next;
reg        tx_pending_reg = 1'b0, tx_pending_next;
reg        tx_active_reg = 1'b0, tx_active_next;
// The level decided at the sample point for the next bit.
reg        tx_bit_reg = 1'b1, tx_bit_next;
reg        flag_passive_reg = 1'b0, flag_passive_next;
reg        flag_ovl_reg = 1'b0, flag_ovl_next;
// An error-passive transmitter's ACK error costs 8 only if a dominant bit
// follows in its passive flag (fault confinement rule 3, exception 1).
reg        ack_pass_reg = 1'b0, ack_pass_next;
reg [2:0]  dom_cnt_reg = 3'd0, dom_cnt_next;
reg        suspend_needed_reg = 1'b0, suspend_needed_next;
reg [8:0]  tec_reg = 9'd0, tec_next;
reg [7:0]  rec_reg = 8'd0, rec_next;

/* Outputs */
reg        can_tx_reg = 1'b1, can_tx_next;
reg        tx_done_reg = 1'b0, tx_done_next;
reg        arb_lost_reg = 1'b0, arb_lost_next;
reg        rx_valid_reg = 1'b0, rx_valid_next;
reg [28:0] o_rx_id_reg = 29'd0, o_rx_id_next;
reg        o_rx_ide_reg = 1'b0, o_rx_ide_next;
reg        o_rx_rtr_reg = 1'b0, o_rx_rtr_next;
reg [3:0]  o_rx_dlc_reg = 4'd0, o_rx_dlc_next;
reg [63:0] o_rx_data_reg = 64'd0, o_rx_data_next;
reg [1:0]  err_state_reg = 2'd0, err_state_next;
reg        err_bit_reg = 1'b0, err_bit_next;
reg        err_stuff_reg = 1'b0, err_stuff_next;
reg        err_crc_reg = 1'b0, err_crc_next;
reg        err_form_reg = 1'b0, err_form_next;
reg        err_ack_reg = 1'b0, err_ack_next;
reg        overload_reg = 1'b0, overload_next;

assign o_can_tx = can_tx_reg;
assign o_tx_busy = tx_pending_reg;
assign o_tx_done = tx_done_reg;
assign o_arb_lost = arb_lost_reg;
assign o_rx_valid = rx_valid_reg;
assign o_rx_id = o_rx_id_reg;
assign o_rx_ide = o_rx_ide_reg;
assign o_rx_rtr = o_rx_rtr_reg;
assign o_rx_dlc = o_rx_dlc_reg;
assign o_rx_data = o_rx_data_reg;
assign o_tec = tec_reg;
assign o_rec = rec_reg;
assign o_err_state = err_state_reg;
assign o_err_bit = err_bit_reg;
assign o_err_stuff = err_stuff_reg;
assign o_err_crc = err_crc_reg;
assign o_err_form = err_form_reg;
assign o_err_ack = err_ack_reg;
assign o_overload = overload_reg;

/* CRC-15 (model::crc::CAN_CRC15) of the bit read at this sample point. */
wire [14:0] crc_step;
crc_serial #(
    .WIDTH(15),
    .POLY(15'h4599)
) crc_inst (
    .i_crc(crc_reg),
    .i_bit(rx),
    .o_crc(crc_step)
);

// Field boundaries of the frame being received (destuffed positions,
// model::can::frame): data from 19 (standard) or 39 (extended), min(DLC, 8)
// bytes unless remote, then 15 CRC bits.
function [6:0] data_start;
    input ide;
    data_start = ide ? 7'd39 : 7'd19;
endfunction

function [6:0] crc_start;
    input ide;
    input rtr;
    input [3:0] dlc;
    reg [3:0] n;
    begin
        n = rtr ? 4'd0 : (dlc > 4'd8 ? 4'd8 : dlc);
        crc_start = data_start(ide) + {n, 3'b000};
    end
endfunction

// The bit a standard-frame transmitter sends at destuffed position pos
// (CRC positions: the top of the CRC register).
function header_bit;
    input [6:0] pos;
    input [10:0] id;
    input rtr;
    input [3:0] dlc;
    input [63:0] data;
    input crc_msb;
    reg [6:0] cs;
    reg [5:0] k;
    begin
        cs = crc_start(1'b0, rtr, dlc);
        k = pos[5:0] - 6'd19;
        // pos >= 1: SOF (position 0) is decided apart, when the frame begins.
        if (pos <= 7'd11) header_bit = id[4'd11 - pos[3:0]];
        else if (pos == 7'd12) header_bit = rtr;
        else if (pos <= 7'd14) header_bit = 1'b0;
        else if (pos <= 7'd18) header_bit = dlc[2'd2 - pos[1:0]];
        else if (pos < cs) header_bit = data[6'd63 - k];
        else header_bit = crc_msb;
    end
endfunction

/* Bit clock, this cycle */
wire edge_seen = rx_prev_reg && !rx && last_sample_reg && !synced_reg;
wire hard_ok = (state_reg == IDLE) || (state_reg == SUSPEND) || (state_reg == INTERMISSION && bit_cnt_reg == 4'd2);
wire resync_ok = can_tx_reg;
reg  restart;
reg  sample;
reg  load_tx;
reg  [5:0] left;
reg  [5:0] end_tq;
// The last cycle of a time quantum.
wire tq_end = (pre_cnt_reg == BRP_LAST);

// The prescaler counts in a block of its own: it changes every cycle, and a
// simulator runs an always @* again whenever anything it reads changes, so
// the block below sees only tq_end and runs once per time quantum, not every
// cycle (Icarus spent most of a CAN replay re-running it).
always @* begin
    if (restart) begin
        // This cycle is the first of SYNC_SEG.
        if (BRP == 1) pre_cnt_next = 10'd0;
        else pre_cnt_next = 10'd1;
    end else if (tq_end) begin
        pre_cnt_next = 10'd0;
    end else begin
        pre_cnt_next = pre_cnt_reg + 10'd1;
    end
end

always @* begin
    tq_cnt_next = tq_cnt_reg;
    ext_next = ext_reg;
    short_next = short_reg;
    synced_next = synced_reg;
    restart = 1'b0;
    sample = 1'b0;
    load_tx = 1'b0;
    left = 6'd0;
    end_tq = 6'd0;
    if (edge_seen && hard_ok) begin
        restart = 1'b1;
    end else if (edge_seen && resync_ok && tq_cnt_reg != 6'd0) begin
        synced_next = 1'b1;
        if (tq_cnt_reg <= TSEG1_6 + ext_reg) begin
            // Late edge: lengthen PHASE_SEG1 by min(e, SJW).
            ext_next = (tq_cnt_reg < SJW_6) ? tq_cnt_reg : SJW_6;
        end else begin
            // Early edge: the quanta left in the bit, this one included.
            left = LAST_TQ_6 + ext_reg - tq_cnt_reg + 6'd1;
            if (left <= SJW_6) restart = 1'b1;
            else short_next = 1'b1;
        end
    end
    if (restart) begin
        // This cycle is the first of SYNC_SEG.
        ext_next = 6'd0;
        short_next = 1'b0;
        synced_next = 1'b1;
        load_tx = 1'b1;
        if (BRP == 1) tq_cnt_next = 6'd1;
        else tq_cnt_next = 6'd0;
    end else begin
        end_tq = LAST_TQ_6 + ext_next - (short_next ? SJW_6 : 6'd0);
        if (tq_end) begin
            sample = (tq_cnt_reg == TSEG1_6 + ext_next);
            load_tx = (tq_cnt_reg == end_tq);
            if (load_tx) begin
                tq_cnt_next = 6'd0;
                ext_next = 6'd0;
                short_next = 1'b0;
            end else begin
                tq_cnt_next = tq_cnt_reg + 6'd1;
            end
        end
        if (sample) synced_next = 1'b0;
    end
end

/* Protocol engine, at the sample point */
wire       b = rx;
wire       sent = can_tx_reg;
wire       passive_now = (tec_reg > 9'd127) || (rec_reg > 8'd127);
wire [6:0] cs_now = crc_start(rx_ide_reg, rx_rtr_reg, rx_dlc_reg);
wire [6:0] ds_now = data_start(rx_ide_reg);
wire [5:0] data_k = pos_reg[5:0] - ds_now[5:0];
wire [6:0] arb_end = 7'd12;
wire       accepted = (((rx_id_reg ^ i_filter_id) & i_filter_mask) == 29'd0);
reg  [2:0] e_kind;
reg        e_exempt;
reg        e_flag_bit;
reg        go_bus_off;
reg        go_sof;
reg        sof_join;
reg        go_idle;
reg        go_inter;
reg        go_ovl;
reg        go_flag_done;
reg  [8:0] rec_sum;
reg  [6:0] cs_n;
reg  [6:0] ds_n;

always @* begin
    state_next = state_reg;
    bit_cnt_next = bit_cnt_reg;
    bo_seq_next = bo_seq_reg;
    pos_next = pos_reg;
    stuff_cnt_next = stuff_cnt_reg;
    last_bit_next = last_bit_reg;
    crc_next = crc_reg;
    crc_bad_next = crc_bad_reg;
    rx_id_next = rx_id_reg;
    rx_ide_next = rx_ide_reg;
    rx_rtr_next = rx_rtr_reg;
    rx_dlc_next = rx_dlc_reg;
    rx_data_next = rx_data_reg;
    tx_id_next = tx_id_reg;
    tx_rtr_next = tx_rtr_reg;
    tx_dlc_next = tx_dlc_reg;
    tx_data_next = tx_data_reg;
    tx_pending_next = tx_pending_reg;
    tx_active_next = tx_active_reg;
    tx_bit_next = tx_bit_reg;
    flag_passive_next = flag_passive_reg;
    flag_ovl_next = flag_ovl_reg;
    ack_pass_next = ack_pass_reg;
    dom_cnt_next = dom_cnt_reg;
    suspend_needed_next = suspend_needed_reg;
    tec_next = tec_reg;
    rec_next = rec_reg;
    can_tx_next = can_tx_reg;
    tx_done_next = 1'b0;
    arb_lost_next = 1'b0;
    rx_valid_next = 1'b0;
    o_rx_id_next = o_rx_id_reg;
    o_rx_ide_next = o_rx_ide_reg;
    o_rx_rtr_next = o_rx_rtr_reg;
    o_rx_dlc_next = o_rx_dlc_reg;
    o_rx_data_next = o_rx_data_reg;
    err_bit_next = 1'b0;
    err_stuff_next = 1'b0;
    err_crc_next = 1'b0;
    err_form_next = 1'b0;
    err_ack_next = 1'b0;
    overload_next = 1'b0;
    e_kind = E_NONE;
    e_exempt = 1'b0;
    e_flag_bit = 1'b0;
    go_bus_off = 1'b0;
    go_sof = 1'b0;
    sof_join = 1'b0;
    go_idle = 1'b0;
    go_inter = 1'b0;
    go_ovl = 1'b0;
    go_flag_done = 1'b0;
    rec_sum = 9'd0;
    cs_n = 7'd0;
    ds_n = 7'd0;

    if (sample) begin
        case (state_reg)
            INTEGRATE: begin
                if (!b) bit_cnt_next = 4'd0;
                else if (bit_cnt_reg == 4'd10) begin
                    bit_cnt_next = 4'd0;
                    go_idle = 1'b1;
                end else bit_cnt_next = bit_cnt_reg + 4'd1;
            end
            BUS_OFF: begin
                if (!b) bit_cnt_next = 4'd0;
                else if (bit_cnt_reg == 4'd10) begin
                    bit_cnt_next = 4'd0;
                    if (bo_seq_reg == 7'd127) begin
                        bo_seq_next = 7'd0;
                        tec_next = 9'd0;
                        rec_next = 8'd0;
                        go_idle = 1'b1;
                    end else bo_seq_next = bo_seq_reg + 7'd1;
                end else bit_cnt_next = bit_cnt_reg + 4'd1;
            end
            IDLE: begin
                if (!b) begin
                    go_sof = 1'b1;
                    sof_join = tx_pending_reg;
                end else if (tx_pending_reg) go_idle = 1'b1;
            end
            SUSPEND: begin
                if (!b) go_sof = 1'b1;
                else if (bit_cnt_reg == 4'd7) go_idle = 1'b1;
                else bit_cnt_next = bit_cnt_reg + 4'd1;
            end
            INTERMISSION: begin
                if (!b && bit_cnt_reg < 4'd2) go_ovl = 1'b1;
                else if (!b) begin
                    suspend_needed_next = 1'b0;
                    go_sof = 1'b1;
                    sof_join = tx_pending_reg;
                end else if (bit_cnt_reg == 4'd2) begin
                    if (suspend_needed_reg) begin
                        suspend_needed_next = 1'b0;
                        state_next = SUSPEND;
                        bit_cnt_next = 4'd0;
                        tx_bit_next = 1'b1;
                    end else go_idle = 1'b1;
                end else bit_cnt_next = bit_cnt_reg + 4'd1;
            end
            FRAME: begin
                if (stuff_cnt_reg == 3'd5) begin
                    if (b == last_bit_reg) begin
                        // Rule 3 exception 2: a recessive stuff bit in arbitration read dominant,
                        // "located before the RTR bit": the bit before it (pos_reg - 1) is not RTR.
                        e_kind = E_STUFF;
                        e_exempt = tx_active_reg && pos_reg >= 7'd2 && pos_reg <= arb_end && sent && !b;
                    end else begin
                        stuff_cnt_next = 3'd1;
                        last_bit_next = b;
                    end
                end else begin
                    if (tx_active_reg && sent != b) begin
                        if (pos_reg >= 7'd1 && pos_reg <= arb_end && sent && !b) begin
                            tx_active_next = 1'b0;
                            arb_lost_next = 1'b1;
                        end else begin
                            e_kind = E_BIT;
                        end
                    end
                    if (e_kind == E_NONE) begin
                        if (pos_reg < ds_now || pos_reg < cs_now) begin
                            crc_next = crc_step;
                        end else begin
                            if (b != crc_reg[14]) crc_bad_next = 1'b1;
                            crc_next = {crc_reg[13:0], 1'b0};
                        end
                        if (pos_reg >= 7'd1 && pos_reg <= 7'd11) rx_id_next = {rx_id_reg[27:0], b};
                        else if (pos_reg == 7'd12) rx_rtr_next = b;
                        else if (pos_reg == 7'd13) rx_ide_next = b;
                        else if (rx_ide_reg && pos_reg >= 7'd14 && pos_reg <= 7'd31) rx_id_next = {rx_id_reg[27:0], b};
                        else if (rx_ide_reg && pos_reg == 7'd32) rx_rtr_next = b;
                        else if (!rx_ide_reg && pos_reg >= 7'd15 && pos_reg <= 7'd18) rx_dlc_next = {rx_dlc_reg[2:0], b};
                        else if (rx_ide_reg && pos_reg >= 7'd35 && pos_reg <= 7'd38) rx_dlc_next = {rx_dlc_reg[2:0], b};
                        else if (pos_reg >= ds_now && pos_reg < cs_now) rx_data_next[6'd63 - data_k] = b;
                        if (b == last_bit_reg) stuff_cnt_next = stuff_cnt_reg + 3'd1;
                        else begin
                            stuff_cnt_next = 3'd1;
                            last_bit_next = b;
                        end
                        pos_next = pos_reg + 7'd1;
                    end
                end
                if (e_kind == E_NONE) begin
                    cs_n = crc_start(rx_ide_next, rx_rtr_next, rx_dlc_next);
                    ds_n = data_start(rx_ide_next);
                    if (pos_next >= ds_n && pos_next == cs_n + 7'd15 && stuff_cnt_next != 3'd5) begin
                        state_next = CRC_DELIM;
                        tx_bit_next = 1'b1;
                    end else if (!tx_active_next) begin
                        tx_bit_next = 1'b1;
                    end else if (stuff_cnt_next == 3'd5) begin
                        tx_bit_next = !last_bit_next;
                    end else begin
                        tx_bit_next = header_bit(pos_next, tx_id_reg, tx_rtr_reg, tx_dlc_reg, tx_data_reg, crc_next[14]);
                    end
                end
            end
            CRC_DELIM: begin
                if (!b) e_kind = E_FORM;
                else begin
                    state_next = ACK_SLOT;
                    tx_bit_next = tx_active_reg || crc_bad_reg;
                end
            end
            ACK_SLOT: begin
                if (tx_active_reg && b) e_kind = E_ACK;
                else if (!tx_active_reg && !sent && b) e_kind = E_BIT;
                else begin
                    // Rule 8: received without error up to the ACK slot and the ACK bit sent.
                    if (!tx_active_reg && !sent) begin
                        if (rec_reg > 8'd127) rec_next = REC_RESTORE;
                        else if (rec_reg != 8'd0) rec_next = rec_reg - 8'd1;
                    end
                    state_next = ACK_DELIM;
                    tx_bit_next = 1'b1;
                end
            end
            ACK_DELIM: begin
                if (!b) e_kind = E_FORM;
                else if (crc_bad_reg && !tx_active_reg) e_kind = E_CRC;
                else begin
                    state_next = EOF;
                    bit_cnt_next = 4'd0;
                end
            end
            EOF: begin
                if (!b && !(bit_cnt_reg == 4'd6 && !tx_active_reg)) e_kind = E_FORM;
                else begin
                    if (bit_cnt_reg == 4'd5 && !tx_active_reg) begin
                        // The receiver's frame is valid at the last but one EOF bit.
                        if (accepted) begin
                            rx_valid_next = 1'b1;
                            o_rx_id_next = rx_id_reg;
                            o_rx_ide_next = rx_ide_reg;
                            o_rx_rtr_next = rx_rtr_reg;
                            o_rx_dlc_next = rx_dlc_reg;
                            o_rx_data_next = rx_data_reg;
                        end
                    end
                    if (bit_cnt_reg == 4'd6) begin
                        if (tx_active_reg) begin
                            tx_done_next = 1'b1;
                            tx_pending_next = 1'b0;
                            if (tec_reg != 9'd0) tec_next = tec_reg - 9'd1;
                        end
                        go_inter = 1'b1;
                        // A receiver's last EOF bit dominant: overload.
                        go_ovl = !b;
                    end else bit_cnt_next = bit_cnt_reg + 4'd1;
                end
            end
            ERR_FLAG: begin
                if (flag_passive_reg) begin
                    if (!b && ack_pass_reg) begin
                        ack_pass_next = 1'b0;
                        tec_next = tec_reg + 9'd8;
                        if (tec_next > 9'd255) go_bus_off = 1'b1;
                    end
                    // Six equal consecutive bits complete a passive flag.
                    if (go_bus_off) ;
                    else if (bit_cnt_reg == 4'd0 || b != last_bit_reg) begin
                        bit_cnt_next = 4'd1;
                        last_bit_next = b;
                    end else if (bit_cnt_reg == 4'd5) begin
                        bit_cnt_next = 4'd6;
                        ack_pass_next = 1'b0;
                        go_flag_done = 1'b1;
                    end else bit_cnt_next = bit_cnt_reg + 4'd1;
                end else if (b) e_flag_bit = 1'b1;
                else if (bit_cnt_reg == 4'd5) go_flag_done = 1'b1;
                else bit_cnt_next = bit_cnt_reg + 4'd1;
            end
            OVL_FLAG: begin
                if (b) e_flag_bit = 1'b1;
                else if (bit_cnt_reg == 4'd5) go_flag_done = 1'b1;
                else bit_cnt_next = bit_cnt_reg + 4'd1;
            end
            ERR_WAIT: begin
                if (b) begin
                    state_next = ERR_DELIM;
                    bit_cnt_next = 4'd0;
                end else begin
                    if (bit_cnt_reg == 4'd0 && !flag_ovl_reg && !tx_active_reg) begin
                        rec_sum = {1'b0, rec_next} + 9'd8;
                        rec_next = rec_sum[8] ? 8'd255 : rec_sum[7:0];
                    end
                    bit_cnt_next = 4'd1;
                    if (dom_cnt_reg == 3'd7) begin
                        dom_cnt_next = 3'd0;
                        if (tx_active_reg) begin
                            tec_next = tec_reg + 9'd8;
                            if (tec_next > 9'd255) go_bus_off = 1'b1;
                        end else begin
                            rec_sum = {1'b0, rec_next} + 9'd8;
                            rec_next = rec_sum[8] ? 8'd255 : rec_sum[7:0];
                        end
                    end else dom_cnt_next = dom_cnt_reg + 3'd1;
                end
            end
            ERR_DELIM: begin
                if (!b && bit_cnt_reg == 4'd6) begin
                    go_ovl = 1'b1;
                end else if (!b) e_kind = E_FORM;
                else if (bit_cnt_reg == 4'd6) go_inter = 1'b1;
                else bit_cnt_next = bit_cnt_reg + 4'd1;
            end
            // Codes 14 and 15 are never entered; coverage counts reachable code only.
            /* verilator coverage_off */
            default: begin
                state_next = INTEGRATE;
                bit_cnt_next = 4'd0;
            end
            /* verilator coverage_on */
        endcase

        /* Actions shared by several states, in the model's order */
        if (go_inter) begin
            // A transmitter stays one until the bus is idle.
            suspend_needed_next = tx_active_next && ((tec_next > 9'd127) || (rec_next > 8'd127));
            state_next = INTERMISSION;
            bit_cnt_next = 4'd0;
            tx_bit_next = 1'b1;
        end
        if (go_ovl) begin
            overload_next = 1'b1;
            state_next = OVL_FLAG;
            bit_cnt_next = 4'd0;
            flag_ovl_next = 1'b1;
            tx_bit_next = 1'b0;
        end
        if (go_flag_done) begin
            state_next = ERR_WAIT;
            bit_cnt_next = 4'd0;
            dom_cnt_next = 3'd0;
            tx_bit_next = 1'b1;
        end
        if (go_sof || (go_idle && tx_pending_reg)) begin
            // begin_frame: SOF read (position 0 consumed) or about to be sent.
            state_next = FRAME;
            pos_next = 7'd1;
            stuff_cnt_next = 3'd1;
            last_bit_next = 1'b0;
            crc_next = 15'd0;
            crc_bad_next = 1'b0;
            rx_id_next = 29'd0;
            rx_ide_next = 1'b0;
            rx_rtr_next = 1'b0;
            rx_dlc_next = 4'd0;
            rx_data_next = 64'd0;
            if (go_sof) begin
                tx_active_next = sof_join;
                tx_bit_next = sof_join ? tx_id_reg[10] : 1'b1;
            end else begin
                // Send SOF in the next bit.
                tx_active_next = 1'b1;
                pos_next = 7'd0;
                stuff_cnt_next = 3'd0;
                last_bit_next = 1'b1;
                tx_bit_next = 1'b0;
            end
        end else if (go_idle) begin
            // The bus is idle: the transmitter of the last frame is one no more.
            state_next = IDLE;
            tx_active_next = 1'b0;
            tx_bit_next = 1'b1;
        end
        if (e_kind != E_NONE || e_flag_bit) begin
            if (e_flag_bit) begin
                err_bit_next = 1'b1;
                if (tx_active_reg) tec_next = tec_reg + 9'd8;
                else begin
                    rec_sum = {1'b0, rec_reg} + 9'd8;
                    rec_next = rec_sum[8] ? 8'd255 : rec_sum[7:0];
                end
            end else begin
                err_bit_next = (e_kind == E_BIT);
                err_stuff_next = (e_kind == E_STUFF);
                err_crc_next = (e_kind == E_CRC);
                err_form_next = (e_kind == E_FORM);
                err_ack_next = (e_kind == E_ACK);
                ack_pass_next = 1'b0;
                if (tx_active_reg) begin
                    if (e_kind == E_ACK && passive_now) ack_pass_next = 1'b1;
                    else if (!e_exempt) tec_next = tec_reg + 9'd8;
                end else begin
                    rec_sum = {1'b0, rec_reg} + 9'd1;
                    rec_next = rec_sum[8] ? 8'd255 : rec_sum[7:0];
                end
            end
            // start_flag: passive only if error-passive before this error (rule 9).
            if (tec_next > 9'd255) go_bus_off = 1'b1;
            else begin
                state_next = ERR_FLAG;
                bit_cnt_next = 4'd0;
                flag_ovl_next = 1'b0;
                flag_passive_next = passive_now;
                tx_bit_next = passive_now;
            end
        end
        if (go_bus_off) begin
            state_next = BUS_OFF;
            bit_cnt_next = 4'd0;
            bo_seq_next = 7'd0;
            tx_active_next = 1'b0;
            tx_bit_next = 1'b1;
        end
    end

    if (i_tx_start && !tx_pending_reg) begin
        tx_id_next = i_tx_id;
        tx_rtr_next = i_tx_rtr;
        tx_dlc_next = i_tx_dlc;
        tx_data_next = i_tx_data;
        tx_pending_next = 1'b1;
    end
    if (load_tx) can_tx_next = tx_bit_next;
    if (state_next == BUS_OFF) err_state_next = 2'd2;
    else if ((tec_next > 9'd127) || (rec_next > 8'd127)) err_state_next = 2'd1;
    else err_state_next = 2'd0;
end

// The register bank: every register takes its next value at each clock edge.
always @(posedge i_clk) begin
    ext_reg <= ext_next;
    short_reg <= short_next;
    synced_reg <= synced_next;
    state_reg <= state_next;
    bit_cnt_reg <= bit_cnt_next;
    bo_seq_reg <= bo_seq_next;
    pos_reg <= pos_next;
    stuff_cnt_reg <= stuff_cnt_next;
    last_bit_reg <= last_bit_next;
    crc_reg <= crc_next;
    crc_bad_reg <= crc_bad_next;
    rx_id_reg <= rx_id_next;
    rx_ide_reg <= rx_ide_next;
    rx_rtr_reg <= rx_rtr_next;
    rx_dlc_reg <= rx_dlc_next;
    rx_data_reg <= rx_data_next;
    tx_id_reg <= tx_id_next;
    tx_rtr_reg <= tx_rtr_next;
    tx_dlc_reg <= tx_dlc_next;
    tx_data_reg <= tx_data_next;
    tx_pending_reg <= tx_pending_next;
    tx_active_reg <= tx_active_next;
    tx_bit_reg <= tx_bit_next;
    flag_passive_reg <= flag_passive_next;
    flag_ovl_reg <= flag_ovl_next;
    ack_pass_reg <= ack_pass_next;
    dom_cnt_reg <= dom_cnt_next;
    suspend_needed_reg <= suspend_needed_next;
    tec_reg <= tec_next;
    rec_reg <= rec_next;
    can_tx_reg <= can_tx_next;
    tx_done_reg <= tx_done_next;
    arb_lost_reg <= arb_lost_next;
    rx_valid_reg <= rx_valid_next;
    o_rx_id_reg <= o_rx_id_next;
    o_rx_ide_reg <= o_rx_ide_next;
    o_rx_rtr_reg <= o_rx_rtr_next;
    o_rx_dlc_reg <= o_rx_dlc_next;
    o_rx_data_reg <= o_rx_data_next;
    err_state_reg <= err_state_next;
    err_bit_reg <= err_bit_next;
    err_stuff_reg <= err_stuff_next;
    err_crc_reg <= err_crc_next;
    err_form_reg <= err_form_next;
    err_ack_reg <= err_ack_next;
    overload_reg <= overload_next;
    sync_reg <= {sync_reg[1:0], i_can_rx};
    rx_prev_reg <= rx;
    if (sample) last_sample_reg <= rx;
    pre_cnt_reg <= pre_cnt_next;
    tq_cnt_reg <= tq_cnt_next;

    if (i_rst) begin
        sync_reg <= 3'b111;
        rx_prev_reg <= 1'b1;
        last_sample_reg <= 1'b1;
        pre_cnt_reg <= 10'd0;
        tq_cnt_reg <= 6'd0;
        ext_reg <= 6'd0;
        short_reg <= 1'b0;
        synced_reg <= 1'b0;
        state_reg <= INTEGRATE;
        bit_cnt_reg <= 4'd0;
        bo_seq_reg <= 7'd0;
        pos_reg <= 7'd0;
        stuff_cnt_reg <= 3'd0;
        last_bit_reg <= 1'b1;
        crc_reg <= 15'd0;
        crc_bad_reg <= 1'b0;
        rx_id_reg <= 29'd0;
        rx_ide_reg <= 1'b0;
        rx_rtr_reg <= 1'b0;
        rx_dlc_reg <= 4'd0;
        rx_data_reg <= 64'd0;
        tx_id_reg <= 11'd0;
        tx_rtr_reg <= 1'b0;
        tx_dlc_reg <= 4'd0;
        tx_data_reg <= 64'd0;
        tx_pending_reg <= 1'b0;
        tx_active_reg <= 1'b0;
        tx_bit_reg <= 1'b1;
        flag_passive_reg <= 1'b0;
        flag_ovl_reg <= 1'b0;
        ack_pass_reg <= 1'b0;
        dom_cnt_reg <= 3'd0;
        suspend_needed_reg <= 1'b0;
        tec_reg <= 9'd0;
        rec_reg <= 8'd0;
        can_tx_reg <= 1'b1;
        tx_done_reg <= 1'b0;
        arb_lost_reg <= 1'b0;
        rx_valid_reg <= 1'b0;
        o_rx_id_reg <= 29'd0;
        o_rx_ide_reg <= 1'b0;
        o_rx_rtr_reg <= 1'b0;
        o_rx_dlc_reg <= 4'd0;
        o_rx_data_reg <= 64'd0;
        err_state_reg <= 2'd0;
        err_bit_reg <= 1'b0;
        err_stuff_reg <= 1'b0;
        err_crc_reg <= 1'b0;
        err_form_reg <= 1'b0;
        err_ack_reg <= 1'b0;
        overload_reg <= 1'b0;
    end
end

endmodule

`resetall
