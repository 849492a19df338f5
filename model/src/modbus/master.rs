//! The Modbus RTU master, cycle by cycle: the machine `hdl/rtl/modbus_master.v`
//! mirrors, on the shared `uart_rx` and `uart_tx`.
//!
//! ```text
//!  i_start   _/‾\_____________________________________________________________________
//!  o_tx_en   ______/‾‾ 01 03 00 00 00 01 84 0A ‾‾\_____________________________________
//!  i_rx      ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_01_03_02_hi_lo_crc_crc_/‾‾‾‾‾‾‾‾‾‾
//!                                     |<- device ->|                  |<- t3.5 ->|
//!  state     IDLE|SILENCE|   SEND     |   WAIT     |      RECV                  |IDLE
//!  o_done    _____________________________________________________________________/‾\_
//! ```
//! * `SILENCE` holds the request until the line has been quiet for t3.5
//!   (`T35_CLOCKS`) since the last character, in either direction, counted
//!   from the end of its stop bit on the line: `line_idle` counts from the
//!   receiver's stop-bit pulse, and the line is quiet at t3.5 plus the rest
//!   of the stop bit (`STOP_REST`, [`uart::stop_rest_clocks`]).
//! * `WAIT` ends at the answer's first start bit, or after `TIMEOUT_CLOCKS`
//!   with `o_err_timeout`.
//! * `RECV` stores up to 9 characters; t3.5 of silence ends it (measured
//!   from the receiver's stop-bit sample, half a bit before the stop bit
//!   ends). Three line faults spoil the frame, each remembered on its own:
//!   a character with a bad parity bit (`o_err_parity`), one with a low
//!   stop bit (`o_err_framing`), a silence longer than t1.5 (`T15_CLOCKS`)
//!   between two characters (`o_err_gap`). A frame that never ends (a line
//!   held low, a driver that keeps sending) is cut after `RECV_LIMIT_CHARS`
//!   character times and t3.5 (`o_err_length`).
//! * The check: every line fault seen pulses its own flag, together with
//!   `o_err_length` when the frame had fewer than 4 or more than 9
//!   characters; a frame with any of these four is not looked into
//!   further. Otherwise exactly one verdict, in this order: `o_err_crc`,
//!   `o_err_address` (not the polled station; `FF` for the query),
//!   `o_err_exception` (function | 0x80, five characters; the code on
//!   `o_exception`), `o_err_function` (not 03 / A0 / 06), `o_err_count`
//!   (byte count not 2 × registers or the length not matching it; for the
//!   address change, an answer that is not the request's echo), else `o_valid`.
//! * `i_write` is the address change (this project's reading of the
//!   manual's empty "Change the device address", `docs/timing/modbus.md`):
//!   function 06 writing `i_new_address` to holding register 0x0010 of
//!   station `i_address`; the device answers with the echo and takes the new
//!   address from the next request. A good echo pulses `o_valid` with the new
//!   address on `o_station`.

use super::frames;
use crate::ports::{Port, Ports};
use crate::uart::{self, Parity, Receiver, ReceiverConfig, Tx, TxConfig, TxIn, TxOut, TxState};
use crate::{ConfigError, Result};

/// Characters kept of an answer (the longest: 01 03 04 d d d d crc crc).
pub const MAX_CHARS: usize = 9;

/// Character times after the answer's first start bit after which `RECV` gives up.
pub const RECV_LIMIT_CHARS: u64 = 2 * MAX_CHARS as u64;

/// The master's configuration; every field is the Verilog parameter of the
/// same name in upper case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MasterConfig {
    /// System clocks per bit.
    pub clocks_per_bit: u64,
    /// The character format.
    pub parity: Parity,
    /// t1.5 in cycles.
    pub t15_clocks: u64,
    /// t3.5 in cycles.
    pub t35_clocks: u64,
    /// Cycles from the request's end to the answer's first start bit before `o_err_timeout`.
    pub timeout_clocks: u64,
}

impl MasterConfig {
    /// Checks the configuration (fields of `[modbus.master]`).
    pub fn validate(&self) -> Result<()> {
        ReceiverConfig {
            clocks_per_bit: self.clocks_per_bit,
        }
        .validate()?;
        if self.t15_clocks < self.clocks_per_bit || self.t35_clocks <= self.t15_clocks {
            return Err(ConfigError::invalid(
                "master",
                format!(
                    "t1.5 = {} and t3.5 = {} cycles",
                    self.t15_clocks, self.t35_clocks
                ),
                "give t1.5 of at least a bit and t3.5 longer than t1.5",
            ));
        }
        if self.timeout_clocks == 0 {
            return Err(ConfigError::invalid(
                "master.timeout_us",
                "0",
                "give a positive timeout",
            ));
        }
        Ok(())
    }

    /// Cycles of one character.
    pub fn char_clocks(&self) -> u64 {
        self.parity.frame_bits() as u64 * self.clocks_per_bit
    }

    /// `line_idle` at which the line has been silent for t3.5: t3.5 after the
    /// end of the last stop bit, which `line_idle` counts from the stop-bit
    /// pulse (`STOP_REST` cycles before that end).
    pub fn line_quiet_clocks(&self) -> u64 {
        self.t35_clocks + uart::stop_rest_clocks(self.clocks_per_bit)
    }
}

/// The master's states; the RTL's `localparam`s carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// Waiting for `i_start`, `i_query` or `i_write`.
    Idle = 0,
    /// Waiting for t3.5 of silence.
    Silence = 1,
    /// Sending the request.
    Send = 2,
    /// Waiting for the answer's first start bit.
    Wait = 3,
    /// Receiving the answer until t3.5 of silence.
    Recv = 4,
}

/// Inputs at one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct In {
    /// Read `i_count` registers from station `i_address` (one-cycle pulse).
    pub i_start: bool,
    /// Send the address query `FF A0 40 38` (one-cycle pulse).
    pub i_query: bool,
    /// Change station `i_address`'s address to `i_new_address` (function 06
    /// to register 0x0010; one-cycle pulse).
    pub i_write: bool,
    /// Station address.
    pub i_address: u8,
    /// The new address of `i_write` (1..247).
    pub i_new_address: u8,
    /// Registers: 1 (up to 16 bits) or 2 (17 to 32 bits).
    pub i_count: u8,
    /// The receive line.
    pub i_rx: bool,
}

impl Default for In {
    fn default() -> Self {
        In {
            i_start: false,
            i_query: false,
            i_write: false,
            i_address: 1,
            i_new_address: 1,
            i_count: 1,
            i_rx: true,
        }
    }
}

/// Registered outputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Out {
    /// Line: level driven.
    pub o_tx: bool,
    /// Line: driver enable.
    pub o_tx_en: bool,
    /// An operation is under way.
    pub o_busy: bool,
    /// One-cycle pulse at the end of an operation.
    pub o_done: bool,
    /// One-cycle pulse: a good answer; `o_value` or `o_station` holds it
    /// (the station the query returned, or the new address after `i_write`).
    pub o_valid: bool,
    /// The registers read, high first (16 or 32 bits).
    pub o_value: u32,
    /// The station address the query returned.
    pub o_station: u8,
    /// The exception code of the last exception answer.
    pub o_exception: u8,
    /// Pulse: a character of the answer had a bad parity bit.
    pub o_err_parity: bool,
    /// Pulse: a character of the answer had a low stop bit.
    pub o_err_framing: bool,
    /// Pulse: a silence longer than t1.5 inside the answer.
    pub o_err_gap: bool,
    /// Pulse: fewer than 4 or more than 9 characters, or no end within `RECV_LIMIT_CHARS`.
    pub o_err_length: bool,
    /// Pulse: CRC.
    pub o_err_crc: bool,
    /// Pulse: the answer is from another station.
    pub o_err_address: bool,
    /// Pulse: an exception answer.
    pub o_err_exception: bool,
    /// Pulse: another function code.
    pub o_err_function: bool,
    /// Pulse: the byte count or length does not match the registers asked for.
    pub o_err_count: bool,
    /// Pulse: no answer.
    pub o_err_timeout: bool,
}

impl Default for Out {
    fn default() -> Self {
        Out {
            o_tx: true,
            o_tx_en: false,
            o_busy: false,
            o_done: false,
            o_valid: false,
            o_value: 0,
            o_station: 0,
            o_exception: 0,
            o_err_parity: false,
            o_err_framing: false,
            o_err_gap: false,
            o_err_length: false,
            o_err_crc: false,
            o_err_address: false,
            o_err_exception: false,
            o_err_function: false,
            o_err_count: false,
            o_err_timeout: false,
        }
    }
}

impl Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst.copy_from_slice(&[
            self.i_start as u64,
            self.i_query as u64,
            self.i_write as u64,
            self.i_address as u64,
            self.i_new_address as u64,
            (self.i_count & 3) as u64,
            self.i_rx as u64,
        ]);
    }
}

impl Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        dst.copy_from_slice(&[
            self.o_tx as u64,
            self.o_tx_en as u64,
            self.o_busy as u64,
            self.o_done as u64,
            self.o_valid as u64,
            self.o_value as u64,
            self.o_station as u64,
            self.o_exception as u64,
            self.o_err_parity as u64,
            self.o_err_framing as u64,
            self.o_err_gap as u64,
            self.o_err_length as u64,
            self.o_err_crc as u64,
            self.o_err_address as u64,
            self.o_err_exception as u64,
            self.o_err_function as u64,
            self.o_err_count as u64,
            self.o_err_timeout as u64,
        ]);
    }
}

/// The master. One [`Master::step`] is one rising edge.
#[derive(Debug, Clone)]
pub struct Master {
    cfg: MasterConfig,
    state: State,
    rx: Receiver,
    rx_out: uart::Out,
    tx: Tx,
    tx_out: TxOut,
    tx_in: TxIn,
    tx_pending: bool,
    req: [u8; 8],
    req_len: u8,
    req_index: u8,
    op: Op,
    address: u8,
    new_address: u8,
    count: u8,
    buf: [u8; MAX_CHARS],
    nbytes: u8,
    parity_seen: bool,
    framing_seen: bool,
    gap_seen: bool,
    gap: u64,
    line_idle: u64,
    cnt: u64,
    out: Out,
}

impl Master {
    /// A master in its reset state.
    pub fn new(cfg: MasterConfig) -> Result<Self> {
        cfg.validate()?;
        Ok(Master {
            rx: Receiver::with_parity(
                ReceiverConfig {
                    clocks_per_bit: cfg.clocks_per_bit,
                },
                cfg.parity,
            )?,
            rx_out: uart::Out::default(),
            tx: Tx::new(TxConfig {
                clocks_per_bit: cfg.clocks_per_bit,
                parity: cfg.parity,
            })?,
            tx_out: TxOut::default(),
            tx_in: TxIn::default(),
            tx_pending: false,
            req: [0; 8],
            req_len: 0,
            req_index: 0,
            op: Op::Read,
            address: 0,
            new_address: 0,
            count: 1,
            buf: [0; MAX_CHARS],
            nbytes: 0,
            parity_seen: false,
            framing_seen: false,
            gap_seen: false,
            gap: 0,
            line_idle: cfg.line_quiet_clocks(),
            cnt: 0,
            state: State::Idle,
            out: Out::default(),
            cfg,
        })
    }

    /// The input ports, in vector order.
    pub fn input_ports() -> Vec<Port> {
        vec![
            Port::new("i_start", 1),
            Port::new("i_query", 1),
            Port::new("i_write", 1),
            Port::new("i_address", 8),
            Port::new("i_new_address", 8),
            Port::new("i_count", 2),
            Port::new("i_rx", 1).idle_high(),
        ]
    }

    /// The output ports, in vector order.
    pub fn output_ports() -> Vec<Port> {
        vec![
            Port::new("o_tx", 1),
            Port::new("o_tx_en", 1),
            Port::new("o_busy", 1),
            Port::new("o_done", 1),
            Port::new("o_valid", 1),
            Port::new("o_value", 32),
            Port::new("o_station", 8),
            Port::new("o_exception", 8),
            Port::new("o_err_parity", 1),
            Port::new("o_err_framing", 1),
            Port::new("o_err_gap", 1),
            Port::new("o_err_length", 1),
            Port::new("o_err_crc", 1),
            Port::new("o_err_address", 1),
            Port::new("o_err_exception", 1),
            Port::new("o_err_function", 1),
            Port::new("o_err_count", 1),
            Port::new("o_err_timeout", 1),
        ]
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        self.state
    }

    /// The characters of the last answer (at most [`MAX_CHARS`]).
    pub fn received(&self) -> &[u8] {
        &self.buf[..(self.nbytes as usize).min(MAX_CHARS)]
    }

    /// The request being or last sent.
    pub fn request(&self) -> &[u8] {
        &self.req[..self.req_len as usize]
    }

    /// How many of the next steps with `input` only run counters
    /// (fast-forward): no output or state changes, no pulse comes and no
    /// character ends. The receiver waits between two samples (or idles),
    /// the sender is idle or in the middle of a bit, and the silence,
    /// timeout, gap and limit counters are short of their ends. 0 while a
    /// pulse is up, a character is being handed to the sender, or `input`
    /// starts an operation.
    pub fn quiet(&self, input: &In) -> u64 {
        let o = &self.out;
        let pulse = o.o_done
            || o.o_valid
            || o.o_err_parity
            || o.o_err_framing
            || o.o_err_gap
            || o.o_err_length
            || o.o_err_crc
            || o.o_err_address
            || o.o_err_exception
            || o.o_err_function
            || o.o_err_count
            || o.o_err_timeout;
        let rx = self.rx_out;
        if pulse
            || rx.o_valid
            || rx.o_parity_err
            || rx.o_frame_err
            || self.tx_pending
            || self.tx_in.i_valid
        {
            return 0;
        }
        // Mid-bit of a request character: only the sender's bit timer runs
        // (the Send state waits for its busy to fall; the receiver listens
        // to a high line while the driver is on).
        if self.tx.state() != TxState::Idle {
            return if self.state == State::Send {
                self.tx.quiet().min(self.rx.quiet(&uart::In {
                    i_rx: input.i_rx || o.o_tx_en,
                }))
            } else {
                0
            };
        }
        let t35 = self.cfg.t35_clocks;
        let quiet_line = self.cfg.line_quiet_clocks();
        let fsm = match self.state {
            State::Idle if input.i_start || input.i_query || input.i_write => return 0,
            State::Idle => u64::MAX,
            State::Silence if rx.o_busy || o.o_tx_en => u64::MAX,
            State::Silence => quiet_line.saturating_sub(self.line_idle),
            State::Send => return 0,
            State::Wait if rx.o_busy => return 0,
            State::Wait => self.cnt,
            State::Recv if rx.o_busy => self.cnt,
            State::Recv => self.cnt.min(t35.saturating_sub(self.gap + 1)),
        };
        fsm.min(self.rx.quiet(&uart::In {
            i_rx: input.i_rx || o.o_tx_en,
        }))
    }

    /// The same as `n` steps with the last input, for `n` up to [`Master::quiet`].
    pub fn skip(&mut self, n: u64) {
        let rx = self.rx_out;
        match self.state {
            State::Wait => self.cnt -= n,
            State::Recv => {
                if rx.o_busy {
                    if self.nbytes > 0 && self.gap >= self.cfg.t15_clocks {
                        self.gap_seen = true;
                    }
                    self.gap = 0;
                } else {
                    self.gap += n;
                }
                self.cnt -= n;
            }
            State::Idle | State::Silence | State::Send => {}
        }
        let quiet_line = self.cfg.line_quiet_clocks();
        let stop_rest = uart::stop_rest_clocks(self.cfg.clocks_per_bit);
        if self.out.o_tx_en {
            self.line_idle = stop_rest;
        } else if rx.o_busy {
            self.line_idle = (self.line_idle + n).min(stop_rest);
        } else {
            self.line_idle = (self.line_idle + n).min(quiet_line);
        }
        self.rx.skip(n);
        self.tx.skip(n);
    }

    /// One rising edge.
    pub fn step(&mut self, input: &In) -> Out {
        let cfg = self.cfg;
        let mut next = Out {
            o_done: false,
            o_valid: false,
            o_err_parity: false,
            o_err_framing: false,
            o_err_gap: false,
            o_err_length: false,
            o_err_crc: false,
            o_err_address: false,
            o_err_exception: false,
            o_err_function: false,
            o_err_count: false,
            o_err_timeout: false,
            ..self.out
        };
        let rx = self.rx_out;
        let tx = self.tx_out;
        let mut tx_in = TxIn {
            i_valid: false,
            i_data: self.tx_in.i_data,
        };
        let char_end = rx.o_valid || rx.o_parity_err || rx.o_frame_err;
        match self.state {
            State::Idle => {
                if input.i_start || input.i_query || input.i_write {
                    // One operation per pulse; i_start wins over i_query over i_write.
                    self.op = if input.i_start {
                        Op::Read
                    } else if input.i_query {
                        Op::Query
                    } else {
                        Op::Write
                    };
                    self.address = input.i_address;
                    self.new_address = input.i_new_address;
                    self.count = input.i_count & 3;
                    let bytes = match self.op {
                        Op::Read => frames::read_request(self.address, self.count as u16),
                        Op::Query => frames::address_query(),
                        Op::Write => frames::write_request(
                            self.address,
                            frames::ADDRESS_REGISTER,
                            self.new_address as u16,
                        ),
                    };
                    self.req = [0; 8];
                    self.req[..bytes.len()].copy_from_slice(&bytes);
                    self.req_len = bytes.len() as u8;
                    self.req_index = 0;
                    self.state = State::Silence;
                    next.o_busy = true;
                }
            }
            State::Silence => {
                if self.line_idle >= cfg.line_quiet_clocks() {
                    self.state = State::Send;
                    next.o_tx_en = true;
                }
            }
            State::Send => {
                if self.tx_pending {
                    if tx.o_busy {
                        self.tx_pending = false;
                    }
                } else if !tx.o_busy {
                    if self.req_index == self.req_len {
                        next.o_tx_en = false;
                        self.state = State::Wait;
                        self.cnt = cfg.timeout_clocks - 1;
                    } else {
                        tx_in = TxIn {
                            i_valid: true,
                            i_data: self.req[self.req_index as usize],
                        };
                        self.req_index += 1;
                        self.tx_pending = true;
                    }
                }
            }
            State::Wait => {
                if rx.o_busy {
                    self.state = State::Recv;
                    self.nbytes = 0;
                    self.parity_seen = false;
                    self.framing_seen = false;
                    self.gap_seen = false;
                    self.gap = 0;
                    self.cnt = RECV_LIMIT_CHARS * cfg.char_clocks() + cfg.t35_clocks - 1;
                } else if self.cnt == 0 {
                    next.o_err_timeout = true;
                    self.finish(&mut next);
                } else {
                    self.cnt -= 1;
                }
            }
            State::Recv => {
                // The check reads the registers as they were before this edge (the RTL's `_reg`s).
                let seen = Seen {
                    parity: self.parity_seen,
                    framing: self.framing_seen,
                    gap: self.gap_seen,
                    nbytes: self.nbytes,
                };
                if char_end {
                    if (self.nbytes as usize) < MAX_CHARS {
                        self.buf[self.nbytes as usize] = rx.o_data;
                    }
                    self.nbytes = self.nbytes.saturating_add(1).min(15);
                    self.parity_seen |= rx.o_parity_err;
                    self.framing_seen |= rx.o_frame_err;
                    self.gap = 0;
                } else if rx.o_busy {
                    // A start bit: the silence before it is complete. The
                    // count runs from the cycle after the stop-bit pulse to
                    // the cycle before this one, one short of the silence on
                    // the line from the stop bit's middle: over t1.5 is a
                    // count of t1.5 or more.
                    if self.nbytes > 0 && self.gap >= cfg.t15_clocks {
                        self.gap_seen = true;
                    }
                    self.gap = 0;
                } else {
                    self.gap += 1;
                }
                if self.cnt == 0 {
                    self.check(&mut next, true, seen);
                    self.finish(&mut next);
                } else if self.gap == cfg.t35_clocks {
                    self.check(&mut next, false, seen);
                    self.finish(&mut next);
                } else {
                    self.cnt -= 1;
                }
            }
        }
        // A stop-bit pulse: the stop bit ends STOP_REST cycles later. While
        // the receiver is busy (a character, a low stop bit's line still
        // low) the silence has not begun: the count stops at STOP_REST, so
        // it runs from the later of the stop bit's end and the line's rise.
        let quiet_line = cfg.line_quiet_clocks();
        let stop_rest = uart::stop_rest_clocks(cfg.clocks_per_bit);
        if char_end {
            self.line_idle = 0;
        } else if rx.o_busy {
            self.line_idle = (self.line_idle + 1).min(stop_rest);
        } else if self.line_idle < quiet_line {
            self.line_idle += 1;
        }
        self.tx_out = self.tx.step(&self.tx_in);
        self.tx_in = tx_in;
        next.o_tx = self.tx_out.o_tx;
        self.rx_out = self.rx.step(&uart::In {
            i_rx: input.i_rx || self.out.o_tx_en,
        });
        if self.out.o_tx_en {
            // The master's own request counts as line activity for t3.5.
            self.line_idle = stop_rest;
        }
        self.out = next;
        next
    }

    fn finish(&mut self, next: &mut Out) {
        self.state = State::Idle;
        next.o_busy = false;
        next.o_done = true;
    }

    /// The verdict on a complete answer (`cut`: ended by `RECV_LIMIT_CHARS`).
    fn check(&mut self, next: &mut Out, cut: bool, seen: Seen) {
        let n = seen.nbytes as usize;
        let b = self.buf;
        next.o_err_parity = seen.parity;
        next.o_err_framing = seen.framing;
        next.o_err_gap = seen.gap;
        next.o_err_length = cut || !(4..=MAX_CHARS).contains(&n);
        if next.o_err_parity || next.o_err_framing || next.o_err_gap || next.o_err_length {
            return;
        }
        if !frames::crc_ok(&b[..n]) {
            next.o_err_crc = true;
            return;
        }
        match self.op {
            Op::Query => {
                if b[0] != frames::QUERY_ADDRESS {
                    next.o_err_address = true;
                } else if b[1] != frames::QUERY_FUNCTION {
                    next.o_err_function = true;
                } else if n != 5 {
                    next.o_err_count = true;
                } else {
                    next.o_station = b[2];
                    next.o_valid = true;
                }
            }
            _ if b[0] != self.address => next.o_err_address = true,
            Op::Read | Op::Write if b[1] == self.function() | 0x80 && n == 5 => {
                next.o_exception = b[2];
                next.o_err_exception = true;
            }
            _ if b[1] != self.function() => next.o_err_function = true,
            Op::Write => {
                // The echo: the request itself, byte for byte.
                if n != 8 || b[..6] != self.req[..6] {
                    next.o_err_count = true;
                } else {
                    next.o_station = self.new_address;
                    next.o_valid = true;
                }
            }
            Op::Read => {
                if b[2] != 2 * self.count || n != 5 + 2 * self.count as usize {
                    next.o_err_count = true;
                } else {
                    // One register: two bytes; otherwise four (the RTL's two cases).
                    let len = if self.count == 1 { 2 } else { 4 };
                    next.o_value = b[3..3 + len].iter().fold(0u32, |v, &x| (v << 8) | x as u32);
                    next.o_valid = true;
                }
            }
        }
    }

    /// The function code of the operation under way.
    fn function(&self) -> u8 {
        match self.op {
            Op::Read => frames::READ_HOLDING,
            Op::Query => frames::QUERY_FUNCTION,
            Op::Write => frames::WRITE_SINGLE,
        }
    }
}

/// The line faults and the character count of the answer so far.
#[derive(Debug, Clone, Copy)]
struct Seen {
    parity: bool,
    framing: bool,
    gap: bool,
    nbytes: u8,
}

/// The operation under way (the RTL's `op_reg`, same codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Op {
    Read = 0,
    Query = 1,
    Write = 2,
}
