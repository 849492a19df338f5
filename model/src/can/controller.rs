//! The CAN controller, cycle by cycle: the machine `hdl/rtl/can_controller.v`
//! mirrors (same ports, parameters, state names and codes).
//!
//! One f_sys cycle per [`Controller::step`]: the input synchroniser
//! (`SYNC_STAGES` flops), the bit clock ([`BitClock`]), and at each sample
//! point the protocol engine ([`Controller::on_sample`]); the transmit level
//! decided at the sample point goes out at the start of the next bit.
//!
//! ```text
//!  bit n:   |SYNC|PROP|PS1   ^ sample: engine reads bit n, decides bit n+1 |PS2|
//!  o_can_tx  <------------ bit n ------------------------------------------->< bit n+1
//!  pulses (o_rx_valid, o_tx_done, o_err_*) last the f_sys cycle after the sample point
//! ```
//! States: `INTEGRATE` (11 recessive bits after reset), `IDLE`, `FRAME`
//! (SOF through the CRC sequence, stuffed), `CRC_DELIM`, `ACK_SLOT`,
//! `ACK_DELIM`, `EOF`, `INTERMISSION`, `SUSPEND` (8 bits after an
//! error-passive transmitter's frame), `ERR_FLAG`, `OVL_FLAG`, `ERR_WAIT`
//! (after a flag, until the bus is recessive), `ERR_DELIM` (7 more recessive
//! bits), `BUS_OFF` (128 × 11 recessive bits).
//!
//! Error confinement (ISO 11898-1 fault confinement rules, as numbered in the
//! Bosch CAN 2.0 specification, part A §7 / part B §8):
//! 1. a receiver's error: REC + 1 (a bit error in its own active error or
//!    overload flag: + 8, rule 5);
//! 2. a receiver reading dominant as the first bit after its error flag: REC + 8;
//! 3. a transmitter sending an error flag: TEC + 8, except an error-passive
//!    transmitter's ACK error when no dominant bit follows in its passive
//!    flag, and a stuff error in arbitration on a recessive stuff bit read
//!    dominant;
//! 4. a transmitter's bit error in its active error or overload flag: TEC + 8;
//! 6. 8 consecutive dominant bits after a flag (the 14th after an active
//!    flag, the 8th after a passive one), and each further 8: TEC or REC + 8;
//! 7. a successful transmission: TEC − 1; 8. a successful reception (no
//!    error up to the ACK slot and the ACK bit sent): REC − 1 at the ACK
//!    slot, or back to [`REC_RESTORE`] from above 127;
//! 9. error-passive above 127, but the error that makes a node
//!    error-passive is still signalled with an active flag.
//!
//! The node is the transmitter (`tx_active`) from its SOF until the bus is
//! idle (or it loses arbitration): through the error, overload and
//! intermission fields after its frame, and an error-passive node's
//! suspend. Bus-off above 255 (TEC); bus-off ends after 128 sequences of 11
//! recessive bits with both counters 0. `docs/timing/can.md` quotes each rule.

use super::frame::{arbitration_end, data_len, data_start, header_bit};
use super::timing::{BitClock, BitTiming};
use crate::crc::CAN_CRC15;
use crate::{ConfigError, Port, Result};

/// REC after a successful reception from above 127 (ISO 11898-1: "a value
/// between 119 and 127"; the lowest is chosen).
pub const REC_RESTORE: u16 = 119;

/// The controller's configuration; each field is the Verilog parameter of
/// the same name in upper case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ControllerConfig {
    /// Bit timing (BRP, PROP_SEG, PHASE_SEG1, PHASE_SEG2, SJW).
    pub timing: BitTiming,
    /// Flops of the `i_can_rx` synchroniser (2 or 3).
    pub sync_stages: u32,
}

impl ControllerConfig {
    /// Checks the configuration.
    pub fn validate(&self) -> Result<()> {
        self.timing.validate()?;
        if !(2..=3).contains(&self.sync_stages) {
            return Err(ConfigError::invalid(
                "sync_stages",
                format!("{}", self.sync_stages),
                "give 2 or 3 synchroniser flops",
            ));
        }
        Ok(())
    }
}

/// The engine's states; the RTL's `localparam`s carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "SCREAMING_SNAKE_CASE")]
pub enum State {
    /// After reset: waiting for 11 recessive bits.
    Integrate = 0,
    /// Bus idle.
    Idle = 1,
    /// SOF through the CRC sequence (the stuffed part).
    Frame = 2,
    /// CRC delimiter.
    CrcDelim = 3,
    /// ACK slot.
    AckSlot = 4,
    /// ACK delimiter.
    AckDelim = 5,
    /// End of frame, 7 bits.
    Eof = 6,
    /// Intermission, 3 bits.
    Intermission = 7,
    /// Suspend transmission, 8 bits (error-passive transmitter).
    Suspend = 8,
    /// Sending an error flag (active: dominant; passive: recessive until 6 equal bits).
    ErrFlag = 9,
    /// Sending an overload flag.
    OvlFlag = 10,
    /// After a flag, recessive, waiting for a recessive bit.
    ErrWait = 11,
    /// Error or overload delimiter, 7 more recessive bits.
    ErrDelim = 12,
    /// Bus-off.
    BusOff = 13,
}

/// Error states on `o_err_state`.
pub const ERROR_ACTIVE: u8 = 0;
/// Error-passive.
pub const ERROR_PASSIVE: u8 = 1;
/// Bus-off.
pub const BUS_OFF: u8 = 2;

/// Inputs at one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct In {
    /// Load the transmit buffer (one-cycle pulse; ignored while `o_tx_busy`).
    pub i_tx_start: bool,
    /// Standard identifier to send.
    pub i_tx_id: u16,
    /// Send a remote frame.
    pub i_tx_rtr: bool,
    /// DLC to send.
    pub i_tx_dlc: u8,
    /// Data to send, byte 0 in bits 63..56.
    pub i_tx_data: u64,
    /// Acceptance filter: identifier (11-bit for standard, 29-bit for extended frames).
    pub i_filter_id: u32,
    /// Acceptance filter: identifier bits that must match.
    pub i_filter_mask: u32,
    /// CAN transceiver receive output (asynchronous).
    pub i_can_rx: bool,
}

impl Default for In {
    fn default() -> Self {
        In {
            i_tx_start: false,
            i_tx_id: 0,
            i_tx_rtr: false,
            i_tx_dlc: 0,
            i_tx_data: 0,
            i_filter_id: 0,
            i_filter_mask: 0,
            i_can_rx: true,
        }
    }
}

/// Registered outputs after one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Out {
    /// CAN transceiver transmit input (1 = recessive).
    pub o_can_tx: bool,
    /// A frame waits in the transmit buffer or is being sent.
    pub o_tx_busy: bool,
    /// The buffered frame was sent and acknowledged (pulse).
    pub o_tx_done: bool,
    /// Arbitration lost; the frame will be sent again (pulse).
    pub o_arb_lost: bool,
    /// A frame passed the acceptance filter (pulse); `o_rx_*` hold it.
    pub o_rx_valid: bool,
    /// Received identifier.
    pub o_rx_id: u32,
    /// Received frame is extended.
    pub o_rx_ide: bool,
    /// Received frame is a remote frame.
    pub o_rx_rtr: bool,
    /// Received DLC.
    pub o_rx_dlc: u8,
    /// Received data, byte 0 in bits 63..56.
    pub o_rx_data: u64,
    /// Transmit error counter.
    pub o_tec: u16,
    /// Receive error counter.
    pub o_rec: u16,
    /// 0 error-active, 1 error-passive, 2 bus-off.
    pub o_err_state: u8,
    /// Bit error detected (pulse).
    pub o_err_bit: bool,
    /// Stuff error detected (pulse).
    pub o_err_stuff: bool,
    /// CRC error detected (pulse).
    pub o_err_crc: bool,
    /// Form error detected (pulse).
    pub o_err_form: bool,
    /// ACK error detected (pulse).
    pub o_err_ack: bool,
    /// Overload condition detected, overload flag follows (pulse).
    pub o_overload: bool,
}

impl Default for Out {
    fn default() -> Self {
        Out {
            o_can_tx: true,
            o_tx_busy: false,
            o_tx_done: false,
            o_arb_lost: false,
            o_rx_valid: false,
            o_rx_id: 0,
            o_rx_ide: false,
            o_rx_rtr: false,
            o_rx_dlc: 0,
            o_rx_data: 0,
            o_tec: 0,
            o_rec: 0,
            o_err_state: 0,
            o_err_bit: false,
            o_err_stuff: false,
            o_err_crc: false,
            o_err_form: false,
            o_err_ack: false,
            o_overload: false,
        }
    }
}

/// The kinds of error a node detects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    /// Sent one level, read the other.
    Bit,
    /// Six equal bits in the stuffed part.
    Stuff,
    /// CRC sequence mismatch.
    Crc,
    /// A fixed-form bit dominant.
    Form,
    /// No dominant ACK slot.
    Ack,
}

/// The frame in the transmit buffer (the model also sends extended frames,
/// for the node emulator; the RTL's buffer holds standard frames).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TxBuffer {
    /// Identifier.
    pub id: u32,
    /// Extended.
    pub ide: bool,
    /// Remote.
    pub rtr: bool,
    /// DLC.
    pub dlc: u8,
    /// Data, byte 0 in bits 63..56.
    pub data: u64,
}

/// The last frame the engine saw end (model-only view, for transcripts).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Seen {
    /// Identifier, extended flag, remote flag, DLC, data as received.
    pub id: u32,
    /// Extended.
    pub ide: bool,
    /// Remote.
    pub rtr: bool,
    /// DLC.
    pub dlc: u8,
    /// Data.
    pub data: u64,
    /// The CRC sequence as received.
    pub crc: u16,
    /// The ACK slot was dominant.
    pub ack: bool,
}

/// The controller.
#[derive(Debug, Clone)]
pub struct Controller {
    cfg: ControllerConfig,
    sync: [bool; 3],
    rx_prev: bool,
    last_sample: bool,
    clock: BitClock,
    state: State,
    bit_cnt: u32,
    bo_seq: u32,
    pos: u32,
    stuff_cnt: u32,
    last_bit: bool,
    crc: u16,
    crc_bad: bool,
    rx_crc: u16,
    rx_ack: bool,
    rx_id: u32,
    rx_ide: bool,
    rx_rtr: bool,
    rx_dlc: u8,
    rx_data: u64,
    tx: TxBuffer,
    tx_pending: bool,
    tx_active: bool,
    tx_bit: bool,
    flag_passive: bool,
    flag_ovl: bool,
    ack_pass: bool,
    dom_cnt: u32,
    suspend_needed: bool,
    tec: u16,
    rec: u16,
    out: Out,
    /// Model-only: the frame that last reached the end of its CRC sequence.
    seen: Seen,
    /// Model-only: a listener that drives nothing (a bus monitor).
    listen_only: bool,
    /// Model-only: never acknowledges (a faulty node of the emulator).
    no_ack: bool,
}

impl Controller {
    /// A controller in its reset state.
    pub fn new(cfg: ControllerConfig) -> Result<Self> {
        cfg.validate()?;
        Ok(Controller {
            cfg,
            sync: [true; 3],
            rx_prev: true,
            last_sample: true,
            clock: BitClock::default(),
            state: State::Integrate,
            bit_cnt: 0,
            bo_seq: 0,
            pos: 0,
            stuff_cnt: 0,
            last_bit: true,
            crc: 0,
            crc_bad: false,
            rx_crc: 0,
            rx_ack: false,
            rx_id: 0,
            rx_ide: false,
            rx_rtr: false,
            rx_dlc: 0,
            rx_data: 0,
            tx: TxBuffer::default(),
            tx_pending: false,
            tx_active: false,
            tx_bit: true,
            flag_passive: false,
            flag_ovl: false,
            ack_pass: false,
            dom_cnt: 0,
            suspend_needed: false,
            tec: 0,
            rec: 0,
            out: Out::default(),
            seen: Seen::default(),
            listen_only: false,
            no_ack: false,
        })
    }

    /// The input ports, in vector order (the Verilog port names).
    pub fn input_ports() -> Vec<Port> {
        vec![
            Port::new("i_tx_start", 1),
            Port::new("i_tx_id", 11),
            Port::new("i_tx_rtr", 1),
            Port::new("i_tx_dlc", 4),
            Port::new("i_tx_data", 64),
            Port::new("i_filter_id", 29),
            Port::new("i_filter_mask", 29),
            Port::new("i_can_rx", 1).idle_high(),
        ]
    }

    /// The output ports, in vector order (the Verilog port names).
    pub fn output_ports() -> Vec<Port> {
        vec![
            Port::new("o_can_tx", 1),
            Port::new("o_tx_busy", 1),
            Port::new("o_tx_done", 1),
            Port::new("o_arb_lost", 1),
            Port::new("o_rx_valid", 1),
            Port::new("o_rx_id", 29),
            Port::new("o_rx_ide", 1),
            Port::new("o_rx_rtr", 1),
            Port::new("o_rx_dlc", 4),
            Port::new("o_rx_data", 64),
            Port::new("o_tec", 9),
            Port::new("o_rec", 8),
            Port::new("o_err_state", 2),
            Port::new("o_err_bit", 1),
            Port::new("o_err_stuff", 1),
            Port::new("o_err_crc", 1),
            Port::new("o_err_form", 1),
            Port::new("o_err_ack", 1),
            Port::new("o_overload", 1),
        ]
    }

    /// The engine's state.
    pub fn state(&self) -> State {
        self.state
    }

    /// The bit clock's registers.
    pub fn clock(&self) -> &BitClock {
        &self.clock
    }

    /// The configuration.
    pub fn config(&self) -> &ControllerConfig {
        &self.cfg
    }

    /// The last frame whose CRC sequence ended, with its ACK slot once that passed.
    pub fn seen(&self) -> Seen {
        self.seen
    }

    /// Whether this node is the transmitter of the frame on the bus.
    pub fn transmitting(&self) -> bool {
        self.tx_active
    }

    /// Destuffed position within the frame (in `FRAME`).
    pub fn pos(&self) -> u32 {
        self.pos
    }

    /// Loads the transmit buffer directly (model-only: extended frames for
    /// the node emulator). Returns false while a frame is pending.
    pub fn load(&mut self, f: TxBuffer) -> bool {
        if self.tx_pending {
            return false;
        }
        self.tx = f;
        self.tx_pending = true;
        self.out.o_tx_busy = true;
        true
    }

    /// Makes this controller a listener (model-only: the bench's bus
    /// monitor): it reads every bit as if it had sent it, and after an
    /// error waits for 11 recessive bits (bus integration), so it follows
    /// the bus through any error frame without errors of its own making.
    pub fn set_listen_only(&mut self) {
        self.listen_only = true;
    }

    /// Makes this controller leave every ACK slot recessive (model-only:
    /// the emulator's `ack = false` fault).
    pub fn set_no_ack(&mut self) {
        self.no_ack = true;
    }

    /// The outputs as they stand.
    pub fn out(&self) -> Out {
        self.out
    }

    /// How many of the next cycles, with `i_can_rx` held at `rx` and no
    /// `i_tx_start`, change nothing but the bit clock's counters. None while
    /// `rx` is still on its way through the synchroniser (an edge may come)
    /// or a pulse stands (it falls in the next cycle). Otherwise:
    /// - any number in bus idle with nothing to send and a recessive line,
    ///   the transmitter sending recessive: each sample point then reads
    ///   recessive and does nothing;
    /// - in any other state, the cycles before the bit clock's next sample
    ///   point ([`BitClock::cycles_to_sample`]), or before the bit end if
    ///   that comes first and loads a level other than the one sent
    ///   ([`BitClock::cycles_to_event`]): in between only `pre_cnt`/`tq_cnt`
    ///   count (and restart at a bit end), as no edge can come.
    pub fn quiet(&self, rx: bool) -> u64 {
        let n = self.cfg.sync_stages as usize;
        if rx != self.rx_prev || self.sync[..n].iter().any(|&s| s != rx) {
            return 0;
        }
        self.quiet_crossing(rx)
    }

    /// [`Controller::quiet`], but a level on its way through the
    /// synchroniser counts as quiet too, up to the cycle it leaves it: the
    /// cycles before one whose step reads at the synchroniser's output a
    /// level other than the last (where an edge may come). Each cycle
    /// before it only shifts the synchroniser and counts the bit clock
    /// ([`Controller::skip_crossing`]).
    pub fn quiet_crossing(&self, rx: bool) -> u64 {
        let n = self.cfg.sync_stages as usize;
        let o = &self.out;
        let pulse = o.o_tx_done
            || o.o_arb_lost
            || o.o_rx_valid
            || o.o_err_bit
            || o.o_err_stuff
            || o.o_err_crc
            || o.o_err_form
            || o.o_err_ack
            || o.o_overload;
        if pulse {
            return 0;
        }
        // The step k cycles from now reads sync[n - 1 - k] (k < n), then `rx`.
        let crossing = match (0..n).find(|&k| self.sync[n - 1 - k] != self.rx_prev) {
            Some(k) => k as u64,
            None if rx != self.rx_prev => n as u64,
            None => u64::MAX,
        };
        if crossing == u64::MAX
            && self.state == State::Idle
            && rx
            && !self.tx_pending
            && self.tx_bit
            && o.o_can_tx
            && !o.o_tx_busy
        {
            u64::MAX
        } else if self.tx_bit == o.o_can_tx {
            // The bit end loads the level already sent: only the counters restart.
            crossing.min(self.clock.cycles_to_sample(&self.cfg.timing))
        } else {
            crossing.min(self.clock.cycles_to_event(&self.cfg.timing))
        }
    }

    /// Advances `n` cycles, at most [`Controller::quiet`]: only the bit clock runs.
    pub fn skip(&mut self, n: u64) {
        self.clock.skip(&self.cfg.timing, n);
    }

    /// Advances `n` cycles with `i_can_rx` held at `rx`, at most
    /// [`Controller::quiet_crossing`]: the bit clock runs and `rx` moves
    /// `n` flops into the synchroniser.
    pub fn skip_crossing(&mut self, n: u64, rx: bool) {
        self.clock.skip(&self.cfg.timing, n);
        let stages = self.cfg.sync_stages as usize;
        let k = (n as usize).min(stages);
        self.sync.copy_within(0..stages - k, k);
        self.sync[..k].fill(rx);
    }

    /// One f_sys cycle.
    pub fn step(&mut self, i: &In) -> Out {
        let n = self.cfg.sync_stages as usize;
        let rx = self.sync[n - 1];
        for k in (1..n).rev() {
            self.sync[k] = self.sync[k - 1];
        }
        self.sync[0] = i.i_can_rx;
        let edge = self.rx_prev && !rx && self.last_sample;
        let hard = matches!(self.state, State::Idle | State::Suspend)
            || (self.state == State::Intermission && self.bit_cnt == 2);
        let resync = self.out.o_can_tx;
        let tick = self.clock.step(&self.cfg.timing, edge, hard, resync);
        let o = &mut self.out;
        o.o_tx_done = false;
        o.o_arb_lost = false;
        o.o_rx_valid = false;
        o.o_err_bit = false;
        o.o_err_stuff = false;
        o.o_err_crc = false;
        o.o_err_form = false;
        o.o_err_ack = false;
        o.o_overload = false;
        let load = i.i_tx_start && !self.tx_pending;
        if tick.sample {
            self.on_sample(rx, i);
            self.last_sample = rx;
        }
        if load {
            self.tx = TxBuffer {
                id: i.i_tx_id as u32 & 0x7FF,
                ide: false,
                rtr: i.i_tx_rtr,
                dlc: i.i_tx_dlc & 0xF,
                data: i.i_tx_data,
            };
            self.tx_pending = true;
        }
        if tick.load_tx {
            self.out.o_can_tx = self.tx_bit;
        }
        self.rx_prev = rx;
        self.out.o_tx_busy = self.tx_pending;
        self.out.o_tec = self.tec;
        self.out.o_rec = self.rec;
        self.out.o_err_state = if self.state == State::BusOff {
            BUS_OFF
        } else if self.tec > 127 || self.rec > 127 {
            ERROR_PASSIVE
        } else {
            ERROR_ACTIVE
        };
        self.out
    }

    fn passive(&self) -> bool {
        self.tec > 127 || self.rec > 127
    }

    /// Rule 8: REC − 1 from 1..=127, [`REC_RESTORE`] from above 127.
    fn rec_success(&mut self) {
        if self.rec > 127 {
            self.rec = REC_RESTORE;
        } else if self.rec > 0 {
            self.rec -= 1;
        }
    }

    fn add_rec(&mut self, n: u16) {
        self.rec = (self.rec + n).min(255);
    }

    /// Starts a frame at SOF (position 0 just read dominant).
    fn begin_frame(&mut self, transmitter: bool) {
        self.state = State::Frame;
        self.pos = 1;
        self.stuff_cnt = 1;
        self.last_bit = false;
        self.crc = 0;
        self.crc_bad = false;
        self.rx_crc = 0;
        self.rx_id = 0;
        self.rx_ide = false;
        self.rx_rtr = false;
        self.rx_dlc = 0;
        self.rx_data = 0;
        self.tx_active = transmitter;
    }

    /// Decides to send SOF in the next bit.
    fn start_tx(&mut self) {
        self.begin_frame(true);
        self.pos = 0;
        self.stuff_cnt = 0;
        self.last_bit = true;
    }

    /// The bit the transmitter sends next in `FRAME`.
    fn frame_tx_bit(&self) -> bool {
        if !self.tx_active {
            return true;
        }
        if self.stuff_cnt == 5 {
            return !self.last_bit;
        }
        let t = &self.tx;
        header_bit(t.id, t.ide, t.rtr, t.dlc, t.data, self.pos).unwrap_or(self.crc & 0x4000 != 0)
    }

    fn crc_start(&self) -> u32 {
        data_start(self.rx_ide) + 8 * data_len(self.rx_dlc, self.rx_rtr) as u32
    }

    /// An error detected at this sample point: pulse, counters, then an
    /// error flag from the next bit (or bus-off).
    fn error(&mut self, kind: ErrorKind, tec_exempt: bool) {
        let was_passive = self.passive();
        match kind {
            ErrorKind::Bit => self.out.o_err_bit = true,
            ErrorKind::Stuff => self.out.o_err_stuff = true,
            ErrorKind::Crc => self.out.o_err_crc = true,
            ErrorKind::Form => self.out.o_err_form = true,
            ErrorKind::Ack => self.out.o_err_ack = true,
        }
        self.ack_pass = false;
        if self.tx_active {
            if kind == ErrorKind::Ack && self.passive() {
                self.ack_pass = true;
            } else if !tec_exempt {
                self.tec += 8;
            }
        } else {
            self.add_rec(1);
        }
        self.start_flag(was_passive);
    }

    /// Starts an error flag in the next bit (bus-off instead when TEC > 255):
    /// passive if the node was error-passive before this error (rule 9: the
    /// error that makes a node error-passive is still signalled actively).
    fn start_flag(&mut self, was_passive: bool) {
        if self.listen_only {
            // A listener sends no flag: it waits for 11 recessive bits, the
            // end of any error frame and intermission, and then for SOF.
            self.state = State::Integrate;
            self.bit_cnt = 0;
            return;
        }
        if self.tec > 255 {
            self.enter_bus_off();
            return;
        }
        self.state = State::ErrFlag;
        self.bit_cnt = 0;
        self.flag_ovl = false;
        self.flag_passive = was_passive;
        self.tx_bit = self.flag_passive;
    }

    fn enter_bus_off(&mut self) {
        self.state = State::BusOff;
        self.bit_cnt = 0;
        self.bo_seq = 0;
        self.tx_active = false;
        self.tx_bit = true;
    }

    fn start_overload(&mut self) {
        self.out.o_overload = true;
        self.state = State::OvlFlag;
        self.bit_cnt = 0;
        self.flag_ovl = true;
        self.tx_bit = false;
    }

    /// End of a frame, error or overload frame: intermission from the next
    /// bit. A transmitter stays one through it ("until the bus is idle").
    fn enter_intermission(&mut self) {
        self.suspend_needed = self.tx_active && self.passive();
        self.state = State::Intermission;
        self.bit_cnt = 0;
        self.tx_bit = true;
    }

    /// After intermission or suspend: send SOF next if a frame waits.
    fn enter_idle(&mut self) {
        if self.tx_pending {
            self.start_tx();
            self.tx_bit = false;
        } else {
            // The bus is idle: the transmitter of the last frame is one no more.
            self.tx_active = false;
            self.state = State::Idle;
            self.tx_bit = true;
        }
    }

    /// A dominant bit read as SOF (idle, suspend, third intermission bit).
    fn sof_received(&mut self, may_join: bool) {
        let join = may_join && self.tx_pending;
        self.begin_frame(join);
        self.tx_bit = self.frame_tx_bit();
    }

    /// The protocol engine at one sample point: `b` is the bus level read.
    pub fn on_sample(&mut self, b: bool, i: &In) {
        let sent = if self.listen_only {
            b
        } else {
            self.out.o_can_tx
        };
        match self.state {
            State::Integrate => {
                if !b {
                    self.bit_cnt = 0;
                } else if self.bit_cnt == 10 {
                    self.bit_cnt = 0;
                    self.enter_idle();
                } else {
                    self.bit_cnt += 1;
                }
            }
            State::BusOff => {
                if !b {
                    self.bit_cnt = 0;
                } else if self.bit_cnt == 10 {
                    self.bit_cnt = 0;
                    if self.bo_seq == 127 {
                        self.bo_seq = 0;
                        self.tec = 0;
                        self.rec = 0;
                        self.enter_idle();
                    } else {
                        self.bo_seq += 1;
                    }
                } else {
                    self.bit_cnt += 1;
                }
            }
            State::Idle => {
                if !b {
                    self.sof_received(true);
                } else if self.tx_pending {
                    self.enter_idle();
                }
            }
            State::Suspend => {
                if !b {
                    self.sof_received(false);
                } else if self.bit_cnt == 7 {
                    self.enter_idle();
                } else {
                    self.bit_cnt += 1;
                }
            }
            State::Intermission => {
                if !b && self.bit_cnt < 2 {
                    self.start_overload();
                } else if !b {
                    self.suspend_needed = false;
                    self.sof_received(true);
                } else if self.bit_cnt == 2 {
                    if self.suspend_needed {
                        self.suspend_needed = false;
                        self.state = State::Suspend;
                        self.bit_cnt = 0;
                        self.tx_bit = true;
                    } else {
                        self.enter_idle();
                    }
                } else {
                    self.bit_cnt += 1;
                }
            }
            State::Frame => self.frame_bit(b, sent),
            State::CrcDelim => {
                if !b {
                    self.error(ErrorKind::Form, false);
                } else {
                    self.state = State::AckSlot;
                    self.tx_bit = self.tx_active || self.crc_bad || self.no_ack;
                }
            }
            State::AckSlot => {
                self.rx_ack = !b;
                self.seen.ack = !b;
                if self.tx_active && b {
                    self.error(ErrorKind::Ack, false);
                } else if !self.tx_active && !sent && b {
                    self.error(ErrorKind::Bit, false);
                } else {
                    if !self.tx_active && !sent {
                        // Rule 8: received without error up to the ACK slot
                        // and the ACK bit sent (dominant, read back dominant).
                        self.rec_success();
                    }
                    self.state = State::AckDelim;
                    self.tx_bit = true;
                }
            }
            State::AckDelim => {
                if !b {
                    self.error(ErrorKind::Form, false);
                } else if self.crc_bad && !self.tx_active {
                    self.error(ErrorKind::Crc, false);
                } else {
                    self.state = State::Eof;
                    self.bit_cnt = 0;
                }
            }
            State::Eof => {
                let last = self.bit_cnt == 6;
                if !b && (!last || self.tx_active) {
                    self.error(ErrorKind::Form, false);
                    return;
                }
                if self.bit_cnt == 5 && !self.tx_active {
                    // The receiver's frame is valid at the last but one EOF bit.
                    if (self.rx_id ^ i.i_filter_id) & i.i_filter_mask & 0x1FFF_FFFF == 0 {
                        let o = &mut self.out;
                        o.o_rx_valid = true;
                        o.o_rx_id = self.rx_id;
                        o.o_rx_ide = self.rx_ide;
                        o.o_rx_rtr = self.rx_rtr;
                        o.o_rx_dlc = self.rx_dlc;
                        o.o_rx_data = self.rx_data;
                    }
                }
                if last {
                    if self.tx_active {
                        self.out.o_tx_done = true;
                        self.tx_pending = false;
                        self.tec = self.tec.saturating_sub(1);
                    }
                    if !b {
                        // A receiver's last EOF bit dominant: overload.
                        self.enter_intermission();
                        self.start_overload();
                    } else {
                        self.enter_intermission();
                    }
                } else {
                    self.bit_cnt += 1;
                }
            }
            State::ErrFlag => {
                if self.flag_passive {
                    if !b && self.ack_pass {
                        self.ack_pass = false;
                        self.tec += 8;
                        if self.tec > 255 {
                            self.enter_bus_off();
                            return;
                        }
                    }
                    // Six equal consecutive bits complete a passive flag.
                    if self.bit_cnt == 0 || b != self.last_bit {
                        self.bit_cnt = 1;
                    } else {
                        self.bit_cnt += 1;
                    }
                    self.last_bit = b;
                    if self.bit_cnt == 6 {
                        self.ack_pass = false;
                        self.flag_done();
                    }
                } else if b {
                    self.flag_bit_error();
                } else if self.bit_cnt == 5 {
                    self.flag_done();
                } else {
                    self.bit_cnt += 1;
                }
            }
            State::OvlFlag => {
                if b {
                    self.flag_bit_error();
                } else if self.bit_cnt == 5 {
                    self.flag_done();
                } else {
                    self.bit_cnt += 1;
                }
            }
            State::ErrWait => {
                if b {
                    self.state = State::ErrDelim;
                    self.bit_cnt = 0;
                } else {
                    if self.bit_cnt == 0 && !self.flag_ovl && !self.tx_active {
                        self.add_rec(8);
                    }
                    self.bit_cnt = 1;
                    if self.dom_cnt == 7 {
                        self.dom_cnt = 0;
                        if self.tx_active {
                            self.tec += 8;
                            if self.tec > 255 {
                                self.enter_bus_off();
                            }
                        } else {
                            self.add_rec(8);
                        }
                    } else {
                        self.dom_cnt += 1;
                    }
                }
            }
            State::ErrDelim => {
                if !b && self.bit_cnt == 6 {
                    self.start_overload();
                } else if !b {
                    self.error(ErrorKind::Form, false);
                } else if self.bit_cnt == 6 {
                    self.enter_intermission();
                } else {
                    self.bit_cnt += 1;
                }
            }
        }
    }

    /// A bit error in an active error flag or an overload flag: + 8, a new error flag.
    fn flag_bit_error(&mut self) {
        let was_passive = self.passive();
        self.out.o_err_bit = true;
        if self.tx_active {
            self.tec += 8;
        } else {
            self.add_rec(8);
        }
        self.start_flag(was_passive);
    }

    fn flag_done(&mut self) {
        self.state = State::ErrWait;
        self.bit_cnt = 0;
        self.dom_cnt = 0;
        self.tx_bit = true;
    }

    /// One bit of the stuffed part.
    fn frame_bit(&mut self, b: bool, sent: bool) {
        if self.stuff_cnt == 5 {
            if b == self.last_bit {
                // Rule 3 exception 2: a recessive stuff bit in arbitration read
                // dominant, "whereby the STUFFBIT is located before the RTR bit":
                // the bit before it (at `pos - 1`) is an identifier bit (or SRR,
                // IDE), not RTR, so `pos` is at most RTR's position.
                let arb = self.pos >= 2 && self.pos <= arbitration_end(self.tx.ide);
                let exempt = self.tx_active && arb && sent && !b;
                self.error(ErrorKind::Stuff, exempt);
                return;
            }
            self.stuff_cnt = 1;
            self.last_bit = b;
        } else {
            if self.tx_active && sent != b {
                let arb = self.pos >= 1 && self.pos <= arbitration_end(self.tx.ide);
                if arb && sent && !b {
                    self.tx_active = false;
                    self.out.o_arb_lost = true;
                } else {
                    self.error(ErrorKind::Bit, false);
                    return;
                }
            }
            let p = self.pos;
            let crc_start = self.crc_start();
            let ds = data_start(self.rx_ide);
            if p < ds || p < crc_start {
                self.crc = crc_step(self.crc, b);
            } else {
                if b != (self.crc & 0x4000 != 0) {
                    self.crc_bad = true;
                }
                self.crc = (self.crc << 1) & 0x7FFF;
                self.rx_crc = (self.rx_crc << 1) | b as u16;
            }
            match p {
                1..=11 => self.rx_id = (self.rx_id << 1) | b as u32,
                12 => self.rx_rtr = b,
                13 => self.rx_ide = b,
                14..=31 if self.rx_ide => self.rx_id = (self.rx_id << 1) | b as u32,
                32 if self.rx_ide => self.rx_rtr = b,
                15..=18 if !self.rx_ide => self.rx_dlc = (self.rx_dlc << 1) | b as u8,
                35..=38 if self.rx_ide => self.rx_dlc = (self.rx_dlc << 1) | b as u8,
                _ if p >= ds && p < crc_start => self.rx_data |= (b as u64) << (63 - (p - ds)),
                _ => {}
            }
            if b == self.last_bit {
                self.stuff_cnt += 1;
            } else {
                self.stuff_cnt = 1;
                self.last_bit = b;
            }
            self.pos += 1;
        }
        let ds = data_start(self.rx_ide);
        if self.pos >= ds && self.pos == self.crc_start() + 15 && self.stuff_cnt != 5 {
            self.seen = Seen {
                id: self.rx_id,
                ide: self.rx_ide,
                rtr: self.rx_rtr,
                dlc: self.rx_dlc,
                data: self.rx_data,
                crc: self.rx_crc,
                ack: false,
            };
            self.state = State::CrcDelim;
            self.tx_bit = true;
        } else {
            self.tx_bit = self.frame_tx_bit();
        }
    }
}

/// One step of the CAN CRC-15 register (what `crc_serial` computes in the RTL).
pub fn crc_step(crc: u16, b: bool) -> u16 {
    let fb = (crc & 0x4000 != 0) ^ b;
    let r = (crc << 1) & 0x7FFF;
    if fb {
        r ^ CAN_CRC15.poly as u16
    } else {
        r
    }
}

impl crate::Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_tx_start as u64;
        dst[1] = (self.i_tx_id & 0x7FF) as u64;
        dst[2] = self.i_tx_rtr as u64;
        dst[3] = (self.i_tx_dlc & 0xF) as u64;
        dst[4] = self.i_tx_data;
        dst[5] = (self.i_filter_id & 0x1FFF_FFFF) as u64;
        dst[6] = (self.i_filter_mask & 0x1FFF_FFFF) as u64;
        dst[7] = self.i_can_rx as u64;
    }
}

impl crate::Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.o_can_tx as u64;
        dst[1] = self.o_tx_busy as u64;
        dst[2] = self.o_tx_done as u64;
        dst[3] = self.o_arb_lost as u64;
        dst[4] = self.o_rx_valid as u64;
        dst[5] = self.o_rx_id as u64;
        dst[6] = self.o_rx_ide as u64;
        dst[7] = self.o_rx_rtr as u64;
        dst[8] = self.o_rx_dlc as u64;
        dst[9] = self.o_rx_data;
        dst[10] = self.o_tec as u64 & 0x1FF;
        dst[11] = self.o_rec as u64;
        dst[12] = self.o_err_state as u64;
        dst[13] = self.o_err_bit as u64;
        dst[14] = self.o_err_stuff as u64;
        dst[15] = self.o_err_crc as u64;
        dst[16] = self.o_err_form as u64;
        dst[17] = self.o_err_ack as u64;
        dst[18] = self.o_overload as u64;
    }
}
