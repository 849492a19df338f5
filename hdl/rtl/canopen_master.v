// canopen_master: CANopen master for one DS 406 encoder; the cycle-for-cycle twin of model::canopen::master::Master.
//
// What it is for
//   Boots, configures and reads one CANopen encoder (seed 003, the Leine &
//   Linde gateway note) without a processor. It sits on one can_controller:
//   waits for the encoder's boot-up (0x80 + NODE without data, the note's
//   form, or 0x700 + NODE with one byte 00h, the DS 301 form), sends the
//   SDO downloads of its parameter table one by one (expedited, size
//   indicated), checks each confirmation (60h with the same index and
//   sub-index), reports an abort (80h) with its code and stops, sends NMT
//   start (01 NODE on COB-ID 0) and then receives the position from TPDO1
//   (0x180 + NODE) or TPDO2 (0x280 + NODE, on SYNC). Connect o_can_tx to the
//   CAN transceiver's TXD and i_can_rx to its RXD (asynchronous: it passes
//   can_controller's synchroniser). Pulse i_start to begin again from
//   WAIT_BOOT (after FAILED, or to re-run the configuration).
//
// Parameters (the Rust MasterConfig field of the same name in lower case)
//   BRP, PROP_SEG, PHASE_SEG1, PHASE_SEG2, SJW, SYNC_STAGES
//                  can_controller's bit timing (MasterConfig.can)
//   NODE           the encoder's node number, 1..127
//   N_PARAMS       SDO downloads in the table, 0..8
//   PARAMk_OBJECT  entry k of MasterConfig.params: {index[15:0], sub[7:0], size[7:0]}
//                  (size 1, 2 or 4 bytes: command 2Fh, 2Bh or 23h)
//   PARAMk_VALUE   its value (little-endian on the wire)
//   BOOT_TIMEOUT   cycles to wait for the boot-up before NMT reset node (81 NODE)
//   SDO_TIMEOUT    cycles to wait for an SDO answer before sending it again
//   RETRIES        timeouts tolerated before o_node_lost (boot-up and each SDO)
//   PDO_TIMEOUT    cycles without a position before o_pos_timeout / o_pos_stale
//   SYNC_PERIOD    cycles between SYNC frames (0x80, no data) in RUN; 0 = none
//
// Timing (docs/timing/canopen.md and model/src/canopen/master.rs have the full story)
//
//   WAIT_BOOT --boot-up--> SDO_SEND --load--> SDO_WAIT --60h--> SDO_SEND (next) ... --last--> NMT_SEND --load--> RUN
//       | BOOT_TIMEOUT: 81 NODE, wait again; after RETRIES: o_node_lost, FAILED
//       |                                      | 80h: o_sdo_abort (code, index, sub), FAILED
//       |                                      | SDO_TIMEOUT: send again; after RETRIES: o_node_lost, FAILED
//   RUN: TPDO1/TPDO2 of NODE -> o_pos_valid, o_position; EMCY of NODE (8 bytes) -> o_emcy_valid;
//        boot-up of NODE -> configure again; PDO_TIMEOUT cycles without a position -> o_pos_timeout
//
//   can_controller o_rx_valid  __/‾\______   (its outputs are registers)
//   master decides               ^ this edge (state, pulses)
//   i_tx_start of the reply      ____/‾\__   one more edge: tx_start_reg
//
// Every output is a register; the pulses last one cycle.

`resetall
`timescale 1ns / 1ps
`default_nettype none

module canopen_master #(
    parameter BRP = 10,
    parameter PROP_SEG = 8,
    parameter PHASE_SEG1 = 5,
    parameter PHASE_SEG2 = 2,
    parameter SJW = 1,
    parameter SYNC_STAGES = 2,
    parameter NODE = 1,
    parameter N_PARAMS = 0,
    parameter [31:0] PARAM0_OBJECT = 32'd0,
    parameter [31:0] PARAM0_VALUE = 32'd0,
    parameter [31:0] PARAM1_OBJECT = 32'd0,
    parameter [31:0] PARAM1_VALUE = 32'd0,
    parameter [31:0] PARAM2_OBJECT = 32'd0,
    parameter [31:0] PARAM2_VALUE = 32'd0,
    parameter [31:0] PARAM3_OBJECT = 32'd0,
    parameter [31:0] PARAM3_VALUE = 32'd0,
    parameter [31:0] PARAM4_OBJECT = 32'd0,
    parameter [31:0] PARAM4_VALUE = 32'd0,
    parameter [31:0] PARAM5_OBJECT = 32'd0,
    parameter [31:0] PARAM5_VALUE = 32'd0,
    parameter [31:0] PARAM6_OBJECT = 32'd0,
    parameter [31:0] PARAM6_VALUE = 32'd0,
    parameter [31:0] PARAM7_OBJECT = 32'd0,
    parameter [31:0] PARAM7_VALUE = 32'd0,
    parameter BOOT_TIMEOUT = 400000,
    parameter SDO_TIMEOUT = 200000,
    parameter RETRIES = 2,
    parameter PDO_TIMEOUT = 600000,
    parameter SYNC_PERIOD = 0
) (
    input  wire        i_clk,
    input  wire        i_rst,

    /* Control */
    input  wire        i_start,
    output wire [2:0]  o_state,

    /* Configuration */
    output wire        o_booted,
    output wire        o_config_done,
    output wire        o_sdo_abort,
    output wire [31:0] o_abort_code,
    output wire [15:0] o_abort_index,
    output wire [7:0]  o_abort_sub,
    output wire        o_node_lost,

    /* Position */
    output wire        o_pos_valid,
    output wire [31:0] o_position,
    output wire        o_pos_timeout,
    output wire        o_pos_stale,

    /* Emergency and SYNC */
    output wire        o_emcy_valid,
    output wire [15:0] o_emcy_code,
    output wire [7:0]  o_emcy_reg,
    output wire        o_sync_sent,

    /* CAN transceiver */
    output wire        o_can_tx,
    input  wire        i_can_rx
);

// States: the same names and codes as model::canopen::master::State.
localparam [2:0]
    WAIT_BOOT = 3'd0,
    SDO_SEND  = 3'd1,
    SDO_WAIT  = 3'd2,
    NMT_SEND  = 3'd3,
    RUN       = 3'd4,
    FAILED    = 3'd5;

localparam [31:0] NODE_32 = NODE;
localparam [6:0] N = NODE_32[6:0];
localparam [31:0] N_PARAMS_32 = N_PARAMS;
localparam [3:0] N_LAST = N_PARAMS_32[3:0];
localparam [31:0] BOOT_TIMEOUT_32 = BOOT_TIMEOUT;
localparam [31:0] SDO_TIMEOUT_32 = SDO_TIMEOUT;
localparam [31:0] PDO_TIMEOUT_32 = PDO_TIMEOUT;
localparam [31:0] SYNC_PERIOD_32 = SYNC_PERIOD;
localparam [31:0] RETRIES_32 = RETRIES;
localparam [7:0] RETRIES_8 = RETRIES_32[7:0];
// COB-IDs of the pre-defined connection set (model::canopen::cob).
localparam [10:0] COB_NMT = 11'h000;
localparam [10:0] COB_SYNC = 11'h080;
localparam [28:0] COB_EMCY = {18'd0, 4'h1, N};
localparam [28:0] COB_TPDO1 = {18'd0, 4'h3, N};
localparam [28:0] COB_TPDO2 = {18'd0, 4'h5, N};
localparam [28:0] COB_SDO_TX = {18'd0, 4'hB, N};
localparam [10:0] COB_SDO_RX = {4'hC, N};
localparam [28:0] COB_NMT_ERR = {18'd0, 4'hE, N};

initial begin
    if (NODE < 1 || NODE > 127) $error("canopen_master: NODE must be 1 to 127");
    if (N_PARAMS < 0 || N_PARAMS > 8) $error("canopen_master: N_PARAMS must be 0 to 8");
    if (BOOT_TIMEOUT < 1 || SDO_TIMEOUT < 1 || PDO_TIMEOUT < 1) $error("canopen_master: timeouts must be at least 1 cycle");
    if (RETRIES < 0 || RETRIES > 255) $error("canopen_master: RETRIES must be 0 to 255");
end

/* The controller; its outputs are registers, read here as they stand before each edge. */
wire        c_tx_busy, c_tx_done, c_rx_valid, c_rx_ide, c_rx_rtr;
wire [28:0] c_rx_id;
wire [3:0]  c_rx_dlc;
wire [63:0] c_rx_data;
/* verilator lint_off UNUSEDSIGNAL */
wire        c_arb_lost, c_err_bit, c_err_stuff, c_err_crc, c_err_form, c_err_ack, c_overload;
wire [8:0]  c_tec;
wire [7:0]  c_rec;
wire [1:0]  c_err_state;
/* verilator lint_on UNUSEDSIGNAL */

reg         tx_start_reg = 1'b0, tx_start_next;
reg  [10:0] tx_id_reg = 11'd0, tx_id_next;
reg  [3:0]  tx_dlc_reg = 4'd0, tx_dlc_next;
reg  [63:0] tx_data_reg = 64'd0, tx_data_next;
// The frame loaded is a SYNC: its o_tx_done becomes o_sync_sent.
reg         tx_sync_reg = 1'b0, tx_sync_next;

can_controller #(
    .BRP(BRP),
    .PROP_SEG(PROP_SEG),
    .PHASE_SEG1(PHASE_SEG1),
    .PHASE_SEG2(PHASE_SEG2),
    .SJW(SJW),
    .SYNC_STAGES(SYNC_STAGES)
) can_inst (
    .i_clk(i_clk),
    .i_rst(i_rst),
    .i_tx_start(tx_start_reg),
    .i_tx_id(tx_id_reg),
    .i_tx_rtr(1'b0),
    .i_tx_dlc(tx_dlc_reg),
    .i_tx_data(tx_data_reg),
    .o_tx_busy(c_tx_busy),
    .o_tx_done(c_tx_done),
    .o_arb_lost(c_arb_lost),
    .i_filter_id(29'd0),
    .i_filter_mask(29'd0),
    .o_rx_valid(c_rx_valid),
    .o_rx_id(c_rx_id),
    .o_rx_ide(c_rx_ide),
    .o_rx_rtr(c_rx_rtr),
    .o_rx_dlc(c_rx_dlc),
    .o_rx_data(c_rx_data),
    .o_tec(c_tec),
    .o_rec(c_rec),
    .o_err_state(c_err_state),
    .o_err_bit(c_err_bit),
    .o_err_stuff(c_err_stuff),
    .o_err_crc(c_err_crc),
    .o_err_form(c_err_form),
    .o_err_ack(c_err_ack),
    .o_overload(c_overload),
    .o_can_tx(o_can_tx),
    .i_can_rx(i_can_rx)
);

reg  [2:0]  state_reg = WAIT_BOOT, state_next;
// The table entry being downloaded.
reg  [3:0]  k_reg = 4'd0, k_next;
// One counter times the boot-up wait, the SDO answer and the position's
// age; it saturates at 2^32 - 1 (model: Master::timer).
reg  [31:0] timer_reg = 32'd0, timer_next;
// The state machine's block below asks for the timer's restart at 0 with
// timer_clear; timer_next, sync_cnt_next and the timeouts due are worked out
// apart from it (after it): both counters change every cycle, and a simulator
// runs an always @* again whenever anything it reads changes, so the state
// machine's block reads only the flags, which change when a timeout falls due.
reg         timer_clear;
reg  [7:0]  tries_reg = 8'd0, tries_next;
reg  [31:0] sync_cnt_reg = 32'd0, sync_cnt_next;
// A SYNC is due and waits for the transmit buffer.
reg         sync_pending_reg = 1'b0, sync_pending_next;

reg         booted_reg = 1'b0, booted_next;
reg         config_done_reg = 1'b0, config_done_next;
reg         sdo_abort_reg = 1'b0, sdo_abort_next;
reg  [31:0] abort_code_reg = 32'd0, abort_code_next;
reg  [15:0] abort_index_reg = 16'd0, abort_index_next;
reg  [7:0]  abort_sub_reg = 8'd0, abort_sub_next;
reg         node_lost_reg = 1'b0, node_lost_next;
reg         pos_valid_reg = 1'b0, pos_valid_next;
reg  [31:0] position_reg = 32'd0, position_next;
reg         pos_timeout_reg = 1'b0, pos_timeout_next;
reg         pos_stale_reg = 1'b0, pos_stale_next;
reg         emcy_valid_reg = 1'b0, emcy_valid_next;
reg  [15:0] emcy_code_reg = 16'd0, emcy_code_next;
reg  [7:0]  emcy_reg_reg = 8'd0, emcy_reg_next;
reg         sync_sent_reg = 1'b0, sync_sent_next;

assign o_state = state_reg;
assign o_booted = booted_reg;
assign o_config_done = config_done_reg;
assign o_sdo_abort = sdo_abort_reg;
assign o_abort_code = abort_code_reg;
assign o_abort_index = abort_index_reg;
assign o_abort_sub = abort_sub_reg;
assign o_node_lost = node_lost_reg;
assign o_pos_valid = pos_valid_reg;
assign o_position = position_reg;
assign o_pos_timeout = pos_timeout_reg;
assign o_pos_stale = pos_stale_reg;
assign o_emcy_valid = emcy_valid_reg;
assign o_emcy_code = emcy_code_reg;
assign o_emcy_reg = emcy_reg_reg;
assign o_sync_sent = sync_sent_reg;

/* The parameter table: entry k_reg. */
reg [31:0] p_object, p_value;
always @* begin
    case (k_reg[2:0])
        3'd0: begin p_object = PARAM0_OBJECT; p_value = PARAM0_VALUE; end
        3'd1: begin p_object = PARAM1_OBJECT; p_value = PARAM1_VALUE; end
        3'd2: begin p_object = PARAM2_OBJECT; p_value = PARAM2_VALUE; end
        3'd3: begin p_object = PARAM3_OBJECT; p_value = PARAM3_VALUE; end
        3'd4: begin p_object = PARAM4_OBJECT; p_value = PARAM4_VALUE; end
        3'd5: begin p_object = PARAM5_OBJECT; p_value = PARAM5_VALUE; end
        3'd6: begin p_object = PARAM6_OBJECT; p_value = PARAM6_VALUE; end
        default: begin p_object = PARAM7_OBJECT; p_value = PARAM7_VALUE; end
    endcase
end
wire [15:0] p_index = p_object[31:16];
wire [7:0]  p_sub = p_object[15:8];
wire [7:0]  p_size = p_object[7:0];
// Expedited download, size indicated: 23h | (4 - size) << 2 (model::canopen::sdo::download).
wire [7:0]  p_command = (p_size == 8'd1) ? 8'h2F : (p_size == 8'd2) ? 8'h2B : 8'h23;
// Bytes 0..7 of the request, byte 0 in bits 63:56 (model::can::frame::pack).
wire [63:0] p_request = {p_command, p_index[7:0], p_index[15:8], p_sub, p_value[7:0], p_value[15:8], p_value[23:16], p_value[31:24]};

/* What the controller received at the last edge. */
wire [7:0] b0 = c_rx_data[63:56];
wire [7:0] b1 = c_rx_data[55:48];
wire [7:0] b2 = c_rx_data[47:40];
wire [7:0] b3 = c_rx_data[39:32];
wire [7:0] b4 = c_rx_data[31:24];
wire [7:0] b5 = c_rx_data[23:16];
wire [7:0] b6 = c_rx_data[15:8];
wire [7:0] b7 = c_rx_data[7:0];
wire rx = c_rx_valid && !c_rx_ide && !c_rx_rtr;
wire boot = rx && ((c_rx_id == COB_EMCY && c_rx_dlc == 4'd0) || (c_rx_id == COB_NMT_ERR && c_rx_dlc == 4'd1 && b0 == 8'h00));
wire sdo_ours = rx && c_rx_id == COB_SDO_TX && c_rx_dlc >= 4'd8 && {b2, b1} == p_index && b3 == p_sub;
wire pdo = rx && (c_rx_id == COB_TPDO1 || c_rx_id == COB_TPDO2) && c_rx_dlc >= 4'd4;
wire emcy = rx && c_rx_id == COB_EMCY && c_rx_dlc == 4'd8;
// The transmit buffer is empty and no request is on its way to it.
wire free = !c_tx_busy && !tx_start_reg;
wire [31:0] timer_inc = (timer_reg == 32'hFFFF_FFFF) ? timer_reg : timer_reg + 32'd1;
wire boot_timeout_due = timer_inc >= BOOT_TIMEOUT_32;
wire sdo_timeout_due = timer_inc >= SDO_TIMEOUT_32;
// The timer reaches PDO_TIMEOUT at this edge if it counts on (restarted, it
// is 0, and PDO_TIMEOUT is at least 1).
wire pdo_timeout_due = timer_inc == PDO_TIMEOUT_32;
wire sync_due = SYNC_PERIOD_32 != 32'd0 && sync_cnt_reg + 32'd1 >= SYNC_PERIOD_32;
always @* begin
    timer_next = timer_clear ? 32'd0 : timer_inc;
    // SYNC producer: counts in every state; the SYNC goes out in RUN when the buffer is free.
    sync_cnt_next = sync_cnt_reg;
    if (SYNC_PERIOD_32 != 32'd0) begin
        if (sync_due) sync_cnt_next = 32'd0;
        else sync_cnt_next = sync_cnt_reg + 32'd1;
    end
end
wire [3:0] k_inc = k_reg + 4'd1;
wire [2:0] after_boot = (N_PARAMS_32 == 32'd0) ? NMT_SEND : SDO_SEND;

always @* begin
    state_next = state_reg;
    k_next = k_reg;
    timer_clear = 1'b0;
    tries_next = tries_reg;
    sync_pending_next = sync_pending_reg;
    tx_start_next = 1'b0;
    tx_id_next = tx_id_reg;
    tx_dlc_next = tx_dlc_reg;
    tx_data_next = tx_data_reg;
    tx_sync_next = tx_sync_reg;
    booted_next = 1'b0;
    config_done_next = 1'b0;
    sdo_abort_next = 1'b0;
    abort_code_next = abort_code_reg;
    abort_index_next = abort_index_reg;
    abort_sub_next = abort_sub_reg;
    node_lost_next = 1'b0;
    pos_valid_next = 1'b0;
    position_next = position_reg;
    pos_timeout_next = 1'b0;
    pos_stale_next = pos_stale_reg;
    emcy_valid_next = 1'b0;
    emcy_code_next = emcy_code_reg;
    emcy_reg_next = emcy_reg_reg;
    sync_sent_next = 1'b0;

    if (c_tx_done && tx_sync_reg) begin
        sync_sent_next = 1'b1;
        tx_sync_next = 1'b0;
    end
    // The SYNC producer's period is over (its counter restarts above).
    if (sync_due) sync_pending_next = 1'b1;

    if (i_start) begin
        state_next = WAIT_BOOT;
        timer_clear = 1'b1;
        tries_next = 8'd0;
    end else begin
        case (state_reg)
        WAIT_BOOT: begin
            if (boot) begin
                booted_next = 1'b1;
                k_next = 4'd0;
                tries_next = 8'd0;
                state_next = after_boot;
            end else if (boot_timeout_due) begin
                timer_clear = 1'b1;
                if (tries_reg >= RETRIES_8) begin
                    node_lost_next = 1'b1;
                    state_next = FAILED;
                end else begin
                    // NMT reset node, if the buffer is free (a frame nobody acknowledges keeps it busy).
                    tries_next = tries_reg + 8'd1;
                    if (free) begin
                        tx_start_next = 1'b1;
                        tx_id_next = COB_NMT;
                        tx_dlc_next = 4'd2;
                        tx_data_next = {8'h81, 1'b0, N, 48'd0};
                        tx_sync_next = 1'b0;
                    end
                end
            end
        end
        SDO_SEND: begin
            if (free) begin
                tx_start_next = 1'b1;
                tx_id_next = COB_SDO_RX;
                tx_dlc_next = 4'd8;
                tx_data_next = p_request;
                tx_sync_next = 1'b0;
                state_next = SDO_WAIT;
                timer_clear = 1'b1;
            end else if (sdo_timeout_due) begin
                node_lost_next = 1'b1;
                state_next = FAILED;
            end
        end
        SDO_WAIT: begin
            if (boot) begin
                // The node started again: the table from entry 0, with all its retries.
                booted_next = 1'b1;
                k_next = 4'd0;
                timer_clear = 1'b1;
                tries_next = 8'd0;
                state_next = SDO_SEND;
            end else if (sdo_ours && b0 == 8'h60) begin
                tries_next = 8'd0;
                k_next = k_inc;
                state_next = (k_inc == N_LAST) ? NMT_SEND : SDO_SEND;
            end else if (sdo_ours && b0 == 8'h80) begin
                sdo_abort_next = 1'b1;
                abort_code_next = {b7, b6, b5, b4};
                abort_index_next = p_index;
                abort_sub_next = p_sub;
                state_next = FAILED;
            end else if (sdo_timeout_due) begin
                if (tries_reg >= RETRIES_8) begin
                    node_lost_next = 1'b1;
                    state_next = FAILED;
                end else begin
                    tries_next = tries_reg + 8'd1;
                    timer_clear = 1'b1;
                    state_next = SDO_SEND;
                end
            end
        end
        NMT_SEND: begin
            if (free) begin
                tx_start_next = 1'b1;
                tx_id_next = COB_NMT;
                tx_dlc_next = 4'd2;
                tx_data_next = {8'h01, 1'b0, N, 48'd0};
                tx_sync_next = 1'b0;
                state_next = RUN;
                config_done_next = 1'b1;
                pos_stale_next = 1'b0;
                timer_clear = 1'b1;
            end
        end
        RUN: begin
            if (boot) begin
                booted_next = 1'b1;
                k_next = 4'd0;
                state_next = after_boot;
            end else if (pdo) begin
                pos_valid_next = 1'b1;
                position_next = {b3, b2, b1, b0};
                pos_stale_next = 1'b0;
                timer_clear = 1'b1;
            end else if (emcy) begin
                emcy_valid_next = 1'b1;
                emcy_code_next = {b1, b0};
                emcy_reg_next = b2;
            end
            // timer_next == PDO_TIMEOUT
            if (!timer_clear && pdo_timeout_due) begin
                pos_timeout_next = 1'b1;
                pos_stale_next = 1'b1;
            end
            if ((sync_pending_reg || sync_due) && free) begin
                sync_pending_next = 1'b0;
                tx_start_next = 1'b1;
                tx_id_next = COB_SYNC;
                tx_dlc_next = 4'd0;
                tx_data_next = 64'd0;
                tx_sync_next = 1'b1;
            end
        end
        default: begin
            // FAILED: until i_start.
        end
        endcase
    end
end

// The register bank: every register takes its next value at each clock edge.
always @(posedge i_clk) begin
    state_reg <= state_next;
    k_reg <= k_next;
    tries_reg <= tries_next;
    sync_pending_reg <= sync_pending_next;
    tx_start_reg <= tx_start_next;
    tx_id_reg <= tx_id_next;
    tx_dlc_reg <= tx_dlc_next;
    tx_data_reg <= tx_data_next;
    tx_sync_reg <= tx_sync_next;
    booted_reg <= booted_next;
    config_done_reg <= config_done_next;
    sdo_abort_reg <= sdo_abort_next;
    abort_code_reg <= abort_code_next;
    abort_index_reg <= abort_index_next;
    abort_sub_reg <= abort_sub_next;
    node_lost_reg <= node_lost_next;
    pos_valid_reg <= pos_valid_next;
    position_reg <= position_next;
    pos_timeout_reg <= pos_timeout_next;
    pos_stale_reg <= pos_stale_next;
    emcy_valid_reg <= emcy_valid_next;
    emcy_code_reg <= emcy_code_next;
    emcy_reg_reg <= emcy_reg_next;
    sync_sent_reg <= sync_sent_next;
    timer_reg <= timer_next;
    sync_cnt_reg <= sync_cnt_next;

    if (i_rst) begin
        state_reg <= WAIT_BOOT;
        k_reg <= 4'd0;
        timer_reg <= 32'd0;
        tries_reg <= 8'd0;
        sync_cnt_reg <= 32'd0;
        sync_pending_reg <= 1'b0;
        tx_start_reg <= 1'b0;
        tx_id_reg <= 11'd0;
        tx_dlc_reg <= 4'd0;
        tx_data_reg <= 64'd0;
        tx_sync_reg <= 1'b0;
        booted_reg <= 1'b0;
        config_done_reg <= 1'b0;
        sdo_abort_reg <= 1'b0;
        abort_code_reg <= 32'd0;
        abort_index_reg <= 16'd0;
        abort_sub_reg <= 8'd0;
        node_lost_reg <= 1'b0;
        pos_valid_reg <= 1'b0;
        position_reg <= 32'd0;
        pos_timeout_reg <= 1'b0;
        pos_stale_reg <= 1'b0;
        emcy_valid_reg <= 1'b0;
        emcy_code_reg <= 16'd0;
        emcy_reg_reg <= 8'd0;
        sync_sent_reg <= 1'b0;
    end
end

endmodule

`resetall
