//! The request/answer skeleton of the half-duplex hosts (ESL, T-format):
//! the request sender, the turnaround, the answer receiver with its timeout
//! and end-of-answer rule, the driver enable, the gap between the requests
//! of one operation, the quiet wait after a flawed answer and the settle
//! time after it. [`Link`] is that machine; a protocol's host keeps only
//! its frames, Data IDs and checks, and names the skeleton's [`State`]s
//! with its own state enum (the codes its RTL's `localparam`s carry).
//!
//! ```text
//!  o_tx_en  _/‾‾ request ‾‾\____________________________________________________
//!  line     ‾\_ fields __/‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_ answer fields _/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//!  state    IDLE| SEND   |     WAIT     |       RECV      |1 bit| GAP, QUIET, SETTLE or IDLE
//!                        |<- timeout -->|
//! ```
//!
//! * `SEND` drives each field as start 0, eight data bits LSB first, stop 1,
//!   back to back, `clocks_per_bit` cycles a bit; the driver enable is on
//!   from the first start bit to the end of the last stop bit.
//! * The receiver is deaf while the driver is on (it hears a high line), so
//!   the host never reads its own request.
//! * `WAIT` ends at the answer's first start bit, or after `timeout_clocks`
//!   ([`End::Timeout`]). `RECV` keeps every field and ends when the receiver
//!   has been idle one bit after a field ([`End::Answer`]), or, with an
//!   answer limit, that many bits after the answer began ([`End::Overlong`]).
//! * At an [`End`] the protocol checks the answer and says what comes next
//!   ([`Link::then`]): the same request again after a wait (a busy answer),
//!   the next of the operation's repeats after `repeat_gap_clocks`, or the
//!   end of the operation: at once, after a settle time, or, after a flawed
//!   answer, once the receiver has been idle [`QUIET_BITS`] (so that the
//!   next request cannot land on the rest of an answer whose framing was
//!   lost), at most the quiet limit if there is one.

pub mod watch;

use crate::uart::{self, Receiver, ReceiverConfig};
use crate::Result;

/// Bit times of idle receiver that end `QUIET`: two fields, longer than any
/// run of ones inside an answer (a stop bit, a start bit turned 1, eight
/// data ones and a stop bit).
pub const QUIET_BITS: u64 = 20;

/// The most fields a request has (control field, address, data, CRC).
pub const MAX_REQUEST: usize = 4;

/// Bits of one field on the line: start, eight data bits, stop.
const FIELD_BITS: u64 = 10;

/// The skeleton's timing, in cycles of the system clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LinkConfig {
    /// System clocks per bit.
    pub clocks_per_bit: u64,
    /// Cycles from the end of the request to the answer's start bit before
    /// the host gives up.
    pub timeout_clocks: u64,
    /// Cycles from the end of one answer to the next request of the same
    /// operation.
    pub repeat_gap_clocks: u64,
    /// Bit times from the answer's first start bit after which reception
    /// ends ([`End::Overlong`]); `None`: the answer ends only on idle line.
    pub answer_limit_bits: Option<u64>,
    /// Bit times after which `QUIET` ends the operation even if the line has
    /// not fallen quiet; `None`: it waits for the quiet line.
    pub quiet_limit_bits: Option<u64>,
}

impl LinkConfig {
    /// A skeleton of these times without an answer or quiet limit.
    pub fn new(clocks_per_bit: u64, timeout_clocks: u64, repeat_gap_clocks: u64) -> Self {
        LinkConfig {
            clocks_per_bit,
            timeout_clocks,
            repeat_gap_clocks,
            answer_limit_bits: None,
            quiet_limit_bits: None,
        }
    }
}

/// The skeleton's states, with the codes of `hdl/rtl/esl_host.v`'s
/// `localparam`s (ESL's host states are these). A host whose core numbers
/// them otherwise names them with its own enum (T-format's core has no
/// `SETTLE` and numbers `QUIET` 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// Waiting for `i_start`.
    Idle = 0,
    /// Driving the request.
    Send = 1,
    /// Driver off, waiting for the answer's start bit.
    Wait = 2,
    /// Receiving the answer's fields.
    Recv = 3,
    /// Between two requests of one operation (repeated commands, a busy
    /// answer).
    Gap = 4,
    /// After an accepted answer, a time the operation still holds (an
    /// EEPROM write or page change time).
    Settle = 5,
    /// After a flawed answer: waiting for the line to fall quiet, so that
    /// the next request cannot land on the rest of an answer.
    Quiet = 6,
}

/// How an answer (or the wait for it) ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum End {
    /// A bit time of idle line followed the answer's last field.
    Answer,
    /// No start bit came within the timeout.
    Timeout,
    /// The answer went on past the answer limit.
    Overlong,
}

/// What one step gives the protocol.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Event {
    /// Nothing for the protocol.
    None,
    /// A field of the answer arrived (also kept in the field registers).
    Field(u8),
    /// The answer ended: the protocol checks it and calls [`Link::then`]
    /// in the same step.
    End(End),
}

/// What follows a checked answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Then {
    /// Send the same request again after this many cycles (at least 1),
    /// not counted as one of the operation's repeats (a busy answer).
    Retry(u64),
    /// The next repeat, if any is left; else the end of the operation:
    /// after `QUIET` if `flawed`, else after `settle` cycles (0: at once).
    Checked {
        /// The answer could not be trusted.
        flawed: bool,
        /// Cycles the operation still holds after an accepted answer.
        settle: u64,
    },
}

/// The skeleton's registered outputs after one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Line {
    /// The level driven.
    pub o_tx: bool,
    /// The RS-485 driver enable.
    pub o_tx_en: bool,
    /// An operation is under way.
    pub o_busy: bool,
    /// One-cycle pulse at the end of an operation.
    pub o_done: bool,
}

/// The skeleton of one host with room for `MAX_FIELDS` answer fields. One
/// [`Link::step`] is one rising edge of the system clock.
#[derive(Debug, Clone)]
pub struct Link<const MAX_FIELDS: usize> {
    cfg: LinkConfig,
    state: State,
    rx: Receiver,
    /// The receiver's registered outputs, as the RTL's FSM sees them: the
    /// values after the previous edge.
    rx_out: uart::Out,
    req: [u8; MAX_REQUEST],
    req_len: u8,
    /// The request's bits still to send, next in bit 0, and how many.
    shift: u64,
    bits_left: u8,
    cnt: u64,
    idle: u64,
    repeats_left: u8,
    fields: [u8; MAX_FIELDS],
    count: u8,
    frame_err: bool,
    line: Line,
}

impl<const MAX_FIELDS: usize> Link<MAX_FIELDS> {
    /// A skeleton in its reset state (the caller has checked `cfg`'s times).
    pub fn new(cfg: LinkConfig) -> Result<Self> {
        Ok(Link {
            cfg,
            state: State::Idle,
            rx: Receiver::new(ReceiverConfig {
                clocks_per_bit: cfg.clocks_per_bit,
            })?,
            rx_out: uart::Out::default(),
            req: [0; MAX_REQUEST],
            req_len: 0,
            shift: 0,
            bits_left: 0,
            cnt: 0,
            idle: 0,
            repeats_left: 0,
            fields: [0; MAX_FIELDS],
            count: 0,
            frame_err: false,
            line: Line {
                o_tx: true,
                o_tx_en: false,
                o_busy: false,
                o_done: false,
            },
        })
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        self.state
    }

    /// The line outputs after the last step (or [`Link::start`], [`Link::then`]).
    pub fn line(&self) -> Line {
        self.line
    }

    /// The request being sent (or last sent).
    pub fn request(&self) -> &[u8] {
        &self.req[..usize::from(self.req_len)]
    }

    /// Fields received in the current answer: the first `MAX_FIELDS` of them.
    pub fn fields(&self) -> &[u8] {
        &self.fields[..usize::from(self.count).min(MAX_FIELDS)]
    }

    /// Every field register: those past the current answer's last field
    /// hold an older answer's, as the core's registers do.
    pub fn registers(&self) -> &[u8; MAX_FIELDS] {
        &self.fields
    }

    /// Fields in the current answer; it stops at `MAX_FIELDS + 1` (more
    /// than any answer has).
    pub fn count(&self) -> usize {
        usize::from(self.count)
    }

    /// A field of the current answer had a framing error.
    pub fn frame_err(&self) -> bool {
        self.frame_err
    }

    /// Starts an operation from `Idle`: sends `request` (at most
    /// [`MAX_REQUEST`] fields), `repeats` times (at least 1) in all. Called
    /// after [`Link::step`] in the step whose input starts it, as the RTL's
    /// `IDLE` does at that edge.
    pub fn start(&mut self, request: &[u8], repeats: u8) {
        self.req = [0; MAX_REQUEST];
        self.req[..request.len()].copy_from_slice(request);
        self.req_len = request.len() as u8;
        self.repeats_left = repeats;
        self.line.o_busy = true;
        self.begin_send();
    }

    /// How many of the next steps with `i_rx` only run counters
    /// (fast-forward): idle, a bit of the request, the answer timeout, the
    /// answer limit, the gap, the settle time or the quiet wait counting,
    /// with the receiver between samples or idle. 0 on `o_done` or a
    /// `start` (the protocol's start input).
    pub fn quiet(&self, i_rx: bool, start: bool) -> u64 {
        if self.line.o_done || start {
            return 0;
        }
        let rx_in = uart::In {
            i_rx: i_rx || self.line.o_tx_en,
        };
        let busy = self.rx_out.o_busy;
        let c = self.cfg.clocks_per_bit;
        let limit = if self.counting() { self.cnt } else { u64::MAX };
        let state = match self.state {
            State::Idle => u64::MAX,
            State::Send | State::Gap | State::Settle => self.cnt,
            State::Wait if busy => 0,
            State::Wait => self.cnt,
            State::Recv | State::Quiet if busy => limit,
            State::Recv => limit.min((c - 1).saturating_sub(self.idle)),
            State::Quiet => limit.min((QUIET_BITS * c - 1).saturating_sub(self.idle)),
        };
        state.min(self.rx.quiet(&rx_in))
    }

    /// The same as `n` steps with the last input, for `n` up to [`Link::quiet`].
    pub fn skip(&mut self, n: u64) {
        if self.counting() {
            self.cnt -= n;
        }
        if matches!(self.state, State::Recv | State::Quiet) {
            self.idle = if self.rx_out.o_busy { 0 } else { self.idle + n };
        }
        self.rx.skip(n);
    }

    /// One rising edge of the system clock, with `i_rx` the RS-485
    /// receiver's output. After [`Event::End`] the caller must call
    /// [`Link::then`] before the next step.
    pub fn step(&mut self, i_rx: bool) -> Event {
        let c = self.cfg.clocks_per_bit;
        let rx = self.rx_out;
        // The receiver listens only while the driver is off (the enable
        // registered at the previous edge).
        let rx_in = uart::In {
            i_rx: i_rx || self.line.o_tx_en,
        };
        self.line.o_done = false;
        let mut event = Event::None;
        match self.state {
            State::Idle => {}
            State::Send => {
                if self.cnt == 0 {
                    if self.bits_left == 0 {
                        self.line.o_tx_en = false;
                        self.line.o_tx = true;
                        self.state = State::Wait;
                        self.cnt = self.cfg.timeout_clocks - 1;
                        self.count = 0;
                        self.frame_err = false;
                    } else {
                        self.line.o_tx = self.shift & 1 == 1;
                        self.shift >>= 1;
                        self.bits_left -= 1;
                        self.cnt = c - 1;
                    }
                } else {
                    self.cnt -= 1;
                }
            }
            State::Wait => {
                if rx.o_busy {
                    self.state = State::Recv;
                    self.idle = 0;
                    if let Some(bits) = self.cfg.answer_limit_bits {
                        self.cnt = bits * c - 1;
                    }
                } else if self.cnt == 0 {
                    event = Event::End(End::Timeout);
                } else {
                    self.cnt -= 1;
                }
            }
            State::Recv if self.counting() && self.cnt == 0 => {
                event = Event::End(End::Overlong);
            }
            State::Recv => {
                if self.counting() {
                    self.cnt -= 1;
                }
                if rx.o_valid || rx.o_frame_err {
                    if usize::from(self.count) < MAX_FIELDS {
                        self.fields[usize::from(self.count)] = rx.o_data;
                    }
                    self.count = (self.count + 1).min(MAX_FIELDS as u8 + 1);
                    self.frame_err |= rx.o_frame_err;
                    self.idle = 0;
                    event = Event::Field(rx.o_data);
                } else if !rx.o_busy {
                    self.idle += 1;
                    if self.idle == c {
                        event = Event::End(End::Answer);
                    }
                } else {
                    self.idle = 0;
                }
            }
            State::Gap => {
                if self.cnt == 0 {
                    self.begin_send();
                } else {
                    self.cnt -= 1;
                }
            }
            State::Settle => {
                if self.cnt == 0 {
                    self.done();
                } else {
                    self.cnt -= 1;
                }
            }
            State::Quiet => {
                if rx.o_busy {
                    self.idle = 0;
                } else {
                    self.idle += 1;
                }
                if self.idle == QUIET_BITS * c || (self.counting() && self.cnt == 0) {
                    self.done();
                } else if self.counting() {
                    self.cnt -= 1;
                }
            }
        }
        self.rx_out = self.rx.step(&rx_in);
        event
    }

    /// What follows the answer the last step ended.
    pub fn then(&mut self, then: Then) {
        match then {
            Then::Retry(cycles) => {
                self.state = State::Gap;
                self.cnt = cycles - 1;
            }
            Then::Checked { flawed, settle } => {
                self.repeats_left -= 1;
                if self.repeats_left > 0 {
                    self.state = State::Gap;
                    self.cnt = self.cfg.repeat_gap_clocks - 1;
                } else if flawed {
                    self.state = State::Quiet;
                    self.idle = 0;
                    if let Some(bits) = self.cfg.quiet_limit_bits {
                        self.cnt = bits * self.cfg.clocks_per_bit - 1;
                    }
                } else if settle > 0 {
                    self.state = State::Settle;
                    self.cnt = settle - 1;
                } else {
                    self.done();
                }
            }
        }
    }

    /// The counter runs in this state: always in the timed states, in
    /// `RECV` and `QUIET` only under their limits.
    fn counting(&self) -> bool {
        match self.state {
            State::Idle => false,
            State::Send | State::Wait | State::Gap | State::Settle => true,
            State::Recv => self.cfg.answer_limit_bits.is_some(),
            State::Quiet => self.cfg.quiet_limit_bits.is_some(),
        }
    }

    /// Drives the request's first start bit and loads the rest.
    fn begin_send(&mut self) {
        let bits = self.request().iter().rev().fold(0u64, |acc, &b| {
            (acc << FIELD_BITS) | (1 << 9) | (u64::from(b) << 1)
        });
        self.state = State::Send;
        self.shift = bits >> 1;
        self.bits_left = (FIELD_BITS as u8) * self.req_len - 1;
        self.cnt = self.cfg.clocks_per_bit - 1;
        self.line.o_tx_en = true;
        self.line.o_tx = bits & 1 == 1;
    }

    fn done(&mut self) {
        self.state = State::Idle;
        self.line.o_busy = false;
        self.line.o_done = true;
    }
}

/// A protocol on the skeleton: its ports, its requests and its checks. A
/// protocol's host is [`Host`] of it.
pub trait Protocol<const MAX_FIELDS: usize> {
    /// The host's inputs at one rising edge.
    type In;
    /// The host's registered outputs after one rising edge.
    type Out: Copy + Default + std::fmt::Debug;
    /// The start input (`i_start`) and the line input (`i_rx`) of `input`.
    fn pins(input: &Self::In) -> (bool, bool);
    /// Writes the skeleton's line outputs into `out`.
    fn drive(out: &mut Self::Out, line: Line);
    /// Latches the operation `input` asks for and clears the errors in
    /// `next`; returns the request and how many times to send it.
    fn start(&mut self, input: &Self::In, next: &mut Self::Out) -> (Vec<u8>, u8);
    /// A field of the answer arrived.
    fn field(&mut self, _byte: u8) {}
    /// The answer (or the wait for it) ended: checks it, publishes it in
    /// `next` and says what follows.
    fn finish(&mut self, link: &Link<MAX_FIELDS>, next: &mut Self::Out, end: End) -> Then;
}

/// The `pins` and `drive` of a [`Protocol`] whose `In` and `Out` carry
/// the ports every half-duplex host has, under their Verilog names:
/// `i_start`, `i_rx`; `o_tx`, `o_tx_en`, `o_busy`, `o_done`.
macro_rules! line_ports {
    () => {
        fn pins(input: &In) -> (bool, bool) {
            (input.i_start, input.i_rx)
        }

        fn drive(out: &mut Out, line: $crate::half_duplex::Line) {
            out.o_tx = line.o_tx;
            out.o_tx_en = line.o_tx_en;
            out.o_busy = line.o_busy;
            out.o_done = line.o_done;
        }
    };
}
pub(crate) use line_ports;

/// A half-duplex host: the skeleton and a protocol's side of it. One
/// [`Host::step`] is one rising edge of the system clock.
#[derive(Debug, Clone)]
pub struct Host<P: Protocol<MAX_FIELDS>, const MAX_FIELDS: usize> {
    link: Link<MAX_FIELDS>,
    protocol: P,
    out: P::Out,
}

impl<P: Protocol<MAX_FIELDS>, const MAX_FIELDS: usize> Host<P, MAX_FIELDS> {
    /// A host in its reset state on a skeleton of `cfg` (the caller has
    /// checked its times).
    pub fn with(cfg: LinkConfig, protocol: P) -> Result<Self> {
        let link = Link::new(cfg)?;
        let mut out = P::Out::default();
        P::drive(&mut out, link.line());
        Ok(Host {
            link,
            protocol,
            out,
        })
    }

    /// The skeleton.
    pub fn link(&self) -> &Link<MAX_FIELDS> {
        &self.link
    }

    /// The protocol's side.
    pub fn protocol(&self) -> &P {
        &self.protocol
    }

    /// How many of the next steps with `input` only run counters
    /// (fast-forward); see [`Link::quiet`].
    pub fn quiet(&self, input: &P::In) -> u64 {
        let (i_start, i_rx) = P::pins(input);
        self.link.quiet(i_rx, i_start)
    }

    /// The same as `n` steps with the last input, for `n` up to [`Host::quiet`].
    pub fn skip(&mut self, n: u64) {
        self.link.skip(n);
    }

    /// One rising edge of the system clock.
    pub fn step(&mut self, input: &P::In) -> P::Out {
        let (i_start, i_rx) = P::pins(input);
        // A start counts only in `Idle` at this edge, not in the step that
        // ends an operation.
        let start = i_start && self.link.state() == State::Idle;
        let mut next = self.out;
        match self.link.step(i_rx) {
            Event::None => {}
            Event::Field(byte) => self.protocol.field(byte),
            Event::End(end) => {
                let then = self.protocol.finish(&self.link, &mut next, end);
                self.link.then(then);
            }
        }
        if start {
            let (request, repeats) = self.protocol.start(input, &mut next);
            self.link.start(&request, repeats);
        }
        P::drive(&mut next, self.link.line());
        self.out = next;
        next
    }
}
