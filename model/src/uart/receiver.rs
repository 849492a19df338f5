//! The frame receiver, cycle for cycle the same machine as `hdl/rtl/uart_rx.v`.

use super::Parity;
use crate::ports::{Port, Ports};
use crate::{ConfigError, Result};

/// The receiver's configuration; `clocks_per_bit` is the Verilog `CLOCKS_PER_BIT`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReceiverConfig {
    /// System clocks per bit (f_sys / baud), at least 6.
    pub clocks_per_bit: u64,
}

impl ReceiverConfig {
    /// Checks the configuration.
    pub fn validate(&self) -> Result<()> {
        if !(6..=65_535).contains(&self.clocks_per_bit) {
            return Err(ConfigError::invalid(
                "baud",
                format!("f_sys / baud = {} clocks per bit", self.clocks_per_bit),
                "give f_sys at least 6 times the baud rate (10 Mbps wants 60 MHz or more) and at most 65535 times",
            ));
        }
        Ok(())
    }
}

/// The receiver's states; the RTL's `localparam`s carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// Line high, waiting for a start bit.
    Idle = 0,
    /// Half a bit to the middle of the start bit.
    Start = 1,
    /// Eight data bits.
    Data = 2,
    /// The stop bit.
    Stop = 3,
    /// After a framing error: waiting for the line to go high.
    Recover = 4,
    /// The parity bit (only with a [`Parity`] other than `None`); `PARITY_BIT` in the RTL.
    ParityBit = 5,
}

/// Inputs at one rising edge of the system clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct In {
    /// The receive line (RS-485 receiver output), asynchronous.
    pub i_rx: bool,
}

/// Registered outputs after one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Out {
    /// The last byte received (valid with `o_valid`, and with `o_frame_err`).
    pub o_data: u8,
    /// One-cycle pulse: a byte with a good stop bit.
    pub o_valid: bool,
    /// One-cycle pulse: the stop bit was 0.
    pub o_frame_err: bool,
    /// One-cycle pulse: a low pulse too short to be a start bit.
    pub o_start_err: bool,
    /// A frame is being received.
    pub o_busy: bool,
    /// One-cycle pulse at the stop-bit sample: the stop bit was 1 but the
    /// parity bit was wrong (never set with [`Parity::None`]). Not one of the
    /// `uart_rx` core's ports unless its `PARITY` parameter is not 0; the
    /// 10-bit cores' vectors leave it out.
    pub o_parity_err: bool,
}

impl Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_rx as u64;
    }
}

impl Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.o_data as u64;
        dst[1] = self.o_valid as u64;
        dst[2] = self.o_frame_err as u64;
        dst[3] = self.o_start_err as u64;
        dst[4] = self.o_busy as u64;
    }
}

/// Cycles from the step that sees a character's stop-bit pulse
/// (`o_valid`, `o_parity_err`, `o_frame_err`, one cycle after the receiver
/// raised it) to the first cycle after that stop bit on the line, for a
/// sender at the nominal rate: the stop bit ends `frame_bits` bits after the
/// start edge, the sample is `⌊C/2⌋` into it, and the start edge reached the
/// receiver's state machine two synchroniser flops late and its pulse is
/// read one cycle after it rose, so `C − ⌊C/2⌋ − 3`.
pub fn stop_rest_clocks(clocks_per_bit: u64) -> u64 {
    clocks_per_bit - clocks_per_bit / 2 - 3
}

/// The receiver. One [`Receiver::step`] is one rising edge of the system clock.
#[derive(Debug, Clone)]
pub struct Receiver {
    cfg: ReceiverConfig,
    state: State,
    cnt: u64,
    bit_index: u8,
    shift: u8,
    rx_meta: bool,
    rx_sync: bool,
    parity: Parity,
    parity_ok: bool,
    out: Out,
}

impl Receiver {
    /// A receiver in its reset state.
    pub fn new(cfg: ReceiverConfig) -> Result<Self> {
        cfg.validate()?;
        Receiver::with_parity(cfg, Parity::None)
    }

    /// A receiver of frames with a parity bit after the data (11 bits:
    /// start, 8 data LSB first, parity, stop); `Parity::None` is [`Receiver::new`].
    pub fn with_parity(cfg: ReceiverConfig, parity: Parity) -> Result<Self> {
        cfg.validate()?;
        Ok(Receiver {
            cfg,
            state: State::Idle,
            cnt: 0,
            bit_index: 0,
            shift: 0,
            rx_meta: true,
            rx_sync: true,
            parity,
            parity_ok: true,
            out: Out::default(),
        })
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        self.state
    }

    /// The data bit being received (0..7).
    pub fn bit_index(&self) -> u8 {
        self.bit_index
    }

    /// The input ports, in vector order.
    pub fn input_ports() -> Vec<Port> {
        vec![Port::new("i_rx", 1).idle_high()]
    }

    /// The output ports, in vector order.
    pub fn output_ports() -> Vec<Port> {
        vec![
            Port::new("o_data", 8),
            Port::new("o_valid", 1),
            Port::new("o_frame_err", 1),
            Port::new("o_start_err", 1),
            Port::new("o_busy", 1),
        ]
    }

    /// How many of the next steps with `input` only run the bit counter
    /// (fast-forward): idle on a high line, between two samples of a
    /// character, or waiting in recovery on a low one. 0 while a pulse is
    /// up or `input` is new (not the last step's). Between two samples an
    /// edge may still be on its way through the synchroniser: nothing reads
    /// it before the next sample, and [`Receiver::skip`] moves it on. Idle
    /// and recovery read the synchroniser every cycle, so there it must
    /// have settled.
    pub fn quiet(&self, input: &In) -> u64 {
        let o = &self.out;
        if o.o_valid
            || o.o_frame_err
            || o.o_start_err
            || o.o_parity_err
            || self.rx_meta != input.i_rx
        {
            return 0;
        }
        match self.state {
            State::Idle | State::Recover
                if self.rx_sync == input.i_rx && input.i_rx == (self.state == State::Idle) =>
            {
                u64::MAX
            }
            State::Idle | State::Recover => 0,
            State::Start | State::Data | State::ParityBit | State::Stop => self.cnt,
        }
    }

    /// The same as `n` steps with the last input, for `n` up to [`Receiver::quiet`].
    pub fn skip(&mut self, n: u64) {
        if matches!(
            self.state,
            State::Start | State::Data | State::ParityBit | State::Stop
        ) {
            self.cnt -= n;
        }
        if n > 0 {
            // The synchroniser's second stage takes the first's, which holds the input.
            self.rx_sync = self.rx_meta;
        }
    }

    /// One rising edge of the system clock.
    pub fn step(&mut self, input: &In) -> Out {
        let bit = self.cfg.clocks_per_bit;
        let half = bit / 2;
        let mut next = Out {
            o_valid: false,
            o_frame_err: false,
            o_start_err: false,
            o_parity_err: false,
            ..self.out
        };
        let mut state = self.state;
        let mut cnt = self.cnt;
        let sample = self.rx_sync;
        match self.state {
            State::Idle => {
                if !sample {
                    state = State::Start;
                    cnt = half - 1;
                    next.o_busy = true;
                }
            }
            State::Start => {
                if self.cnt == 0 {
                    if sample {
                        state = State::Idle;
                        next.o_busy = false;
                        next.o_start_err = true;
                    } else {
                        state = State::Data;
                        cnt = bit - 1;
                        self.bit_index = 0;
                        self.parity_ok = true;
                    }
                } else {
                    cnt -= 1;
                }
            }
            State::Data => {
                if self.cnt == 0 {
                    self.shift = (self.shift >> 1) | ((sample as u8) << 7);
                    cnt = bit - 1;
                    if self.bit_index == 7 {
                        state = if self.parity == Parity::None {
                            State::Stop
                        } else {
                            State::ParityBit
                        };
                    } else {
                        self.bit_index += 1;
                    }
                } else {
                    cnt -= 1;
                }
            }
            State::ParityBit => {
                if self.cnt == 0 {
                    self.parity_ok = self.parity.bit(self.shift) == sample;
                    state = State::Stop;
                    cnt = bit - 1;
                } else {
                    cnt -= 1;
                }
            }
            State::Stop => {
                if self.cnt == 0 {
                    next.o_data = self.shift;
                    if sample {
                        state = State::Idle;
                        next.o_busy = false;
                        next.o_valid = self.parity_ok;
                        next.o_parity_err = !self.parity_ok;
                    } else {
                        state = State::Recover;
                        next.o_frame_err = true;
                    }
                } else {
                    cnt -= 1;
                }
            }
            State::Recover => {
                if sample {
                    state = State::Idle;
                    next.o_busy = false;
                }
            }
        }
        self.state = state;
        self.cnt = cnt;
        self.rx_sync = self.rx_meta;
        self.rx_meta = input.i_rx;
        self.out = next;
        next
    }
}
