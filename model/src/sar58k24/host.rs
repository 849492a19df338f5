//! The SAR58K24 asynchronous host, cycle by cycle: the machine
//! `hdl/rtl/sar_async_host.v` mirrors, on the shared `uart_rx` and `uart_tx`.
//!
//! Two parts run side by side every cycle:
//!
//! * the **frame finder** listens in every mode. Each received character
//!   shifts into a window of the last `L` bytes (`L` = 5, 6 or 7 for 16, 24,
//!   32 bits). `count` is the number of characters since the last frame
//!   boundary: a frame accepted, an idle gap longer than `GAP_CLOCKS`, a
//!   parity or framing error. A window is a frame when `count ≥ L`, it starts
//!   `FF <tag>` and its last byte is the low byte of the sum of the others.
//!   While `synced` (after a boundary that was a frame or a gap), the
//!   `L`-th character must close a frame: if it does not, the host flags why
//!   (`o_err_address`: `FF Bx` of another encoder; `o_err_frame`: not
//!   `FF <tag>`; `o_err_checksum`) and hunts: it slides the window one byte
//!   at a time and takes the first window that is a frame. An `FF 81`
//!   inside the data cannot fool it while it is synced (it never looks
//!   there), and when hunting a false `FF 81` must also carry a matching
//!   checksum at the right distance (1 in 256) to be taken. A gap with
//!   `0 < count < L` while synced is a truncated frame (`o_err_frame`).
//! * the **operation FSM** drives the trigger pulse (handshake), the CLR
//!   pulse (clear modes), or a bus command (`BC AA Bx`, `BC AA Cx`), then
//!   waits for the first frame event (a frame, or an error the finder
//!   flags) or `TIMEOUT_CLOCKS`. In the timed modes a read (`i_start`) only
//!   waits: "the next frame event", so a user (and the transcript) gets one
//!   `o_done` per position asked for.
//!
//! ```text
//!  handshake:  o_trigger ‾‾‾\__ TRIGGER_LOW __/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾
//!              i_rx      ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_FF_/\_81_/\_hi_/\_lo_/\_cs_/‾‾‾‾‾
//!                           |<------ T3 ------->|                      o_valid ^
//!              state     IDLE| TRIGGER          | WAIT (TIMEOUT_CLOCKS)        |IDLE
//!  bus:        o_tx_en   _/‾ BC AA Bx ‾\______________________________________________
//!              i_rx      ‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_FF_/\_Bx_/\_hi_/\_lo_/\_cs_/‾‾‾‾‾
//!              state     IDLE| SEND      | WAIT                                 |IDLE
//!  stale:      no frame for STALE_CLOCKS cycles gives o_err_stale, and again every STALE_CLOCKS.
//! ```

use super::encoder::Mode;
use super::frames;
use crate::gray::from_gray;
use crate::ports::{Port, Ports};
use crate::uart::{self, Parity, Receiver, ReceiverConfig, Tx, TxConfig, TxIn, TxOut};
use crate::{ConfigError, Result};

/// The host's configuration; every field is the Verilog parameter of the
/// same name in upper case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HostConfig {
    /// The mode (`MODE` 0..5).
    pub mode: Mode,
    /// Resolution (`BITS`, 10..32).
    pub bits: u32,
    /// The data is Gray coded (`GRAY`).
    pub gray: bool,
    /// The character format (`PARITY` 0 none, 1 odd, 2 even).
    pub parity: Parity,
    /// Bus answers carry `Bx` as second byte (`TAG_ADDRESS`), else `81`.
    pub tag_address: bool,
    /// A zeroing command is answered (`ZERO_ANSWER`).
    pub zero_answer: bool,
    /// System clocks per bit.
    pub clocks_per_bit: u64,
    /// Idle cycles after a character that end a frame (1.5 characters).
    pub gap_clocks: u64,
    /// Cycles without a frame that flag stale data (0: never).
    pub stale_clocks: u64,
    /// Cycles from entering `WAIT` to `o_err_timeout`.
    pub timeout_clocks: u64,
    /// Low time of the trigger pulse (T2 ≥ 10 µs).
    pub trigger_low_clocks: u64,
    /// Low time of the CLR pulse.
    pub clr_low_clocks: u64,
}

impl HostConfig {
    /// Checks the configuration; field names are those of `[sar.host]`.
    pub fn validate(&self) -> Result<()> {
        ReceiverConfig {
            clocks_per_bit: self.clocks_per_bit,
        }
        .validate()?;
        if !(10..=32).contains(&self.bits) {
            return Err(ConfigError::invalid(
                "encoder.bits",
                format!("{}", self.bits),
                "give 10 to 32 bits",
            ));
        }
        if self.gap_clocks < self.clocks_per_bit {
            return Err(ConfigError::invalid(
                "host.gap_bits",
                "shorter than one bit",
                "give at least 1 bit time (the default is 15, 1.5 characters)",
            ));
        }
        if self.timeout_clocks == 0 || self.trigger_low_clocks == 0 || self.clr_low_clocks == 0 {
            return Err(ConfigError::invalid(
                "host",
                "a zero timeout, trigger or CLR width",
                "give positive times",
            ));
        }
        Ok(())
    }

    /// Bytes in a frame.
    pub fn frame_len(&self) -> usize {
        frames::frame_len(self.bits)
    }
}

/// The host's states; the RTL's `localparam`s carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// No operation (frames are still found in every state).
    Idle = 0,
    /// Driving the trigger low (first, held high, until the stop bit of the
    /// last character received has ended).
    Trigger = 1,
    /// Driving CLR low.
    Clr = 2,
    /// Sending a bus command.
    Send = 3,
    /// Waiting for the answer.
    Wait = 4,
}

/// Inputs at one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct In {
    /// Start a read: wait for the next frame (timed), trigger pulse
    /// (handshake) or `BC AA Bx` (bus). One-cycle pulse.
    pub i_start: bool,
    /// Start a zeroing: CLR pulse or `BC AA Cx`. One-cycle pulse.
    pub i_zero: bool,
    /// The bus address x.
    pub i_address: u8,
    /// The receive line.
    pub i_rx: bool,
}

impl Default for In {
    fn default() -> Self {
        In {
            i_start: false,
            i_zero: false,
            i_address: 0,
            i_rx: true,
        }
    }
}

/// Registered outputs after one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Out {
    /// Line: the level driven (bus commands).
    pub o_tx: bool,
    /// Line: the RS-485 driver enable.
    pub o_tx_en: bool,
    /// The trigger output (CLK), idle high.
    pub o_trigger: bool,
    /// The CLR output, idle high.
    pub o_clr: bool,
    /// An operation is under way.
    pub o_busy: bool,
    /// One-cycle pulse: an operation ended.
    pub o_done: bool,
    /// One-cycle pulse: a frame was accepted, `o_position` holds it.
    pub o_valid: bool,
    /// The last accepted position (binary).
    pub o_position: u32,
    /// One-cycle pulse: a frame's checksum was wrong.
    pub o_err_checksum: bool,
    /// One-cycle pulse: a character's parity bit was wrong.
    pub o_err_parity: bool,
    /// One-cycle pulse: a framing error, a truncated frame, or no `FF <tag>` where a frame must start.
    pub o_err_frame: bool,
    /// One-cycle pulse: a frame tagged for another bus address.
    pub o_err_address: bool,
    /// One-cycle pulse: no answer within the timeout.
    pub o_err_timeout: bool,
    /// One-cycle pulse: no frame for `STALE_CLOCKS`.
    pub o_err_stale: bool,
}

impl Default for Out {
    fn default() -> Self {
        Out {
            o_tx: true,
            o_tx_en: false,
            o_trigger: true,
            o_clr: true,
            o_busy: false,
            o_done: false,
            o_valid: false,
            o_position: 0,
            o_err_checksum: false,
            o_err_parity: false,
            o_err_frame: false,
            o_err_address: false,
            o_err_timeout: false,
            o_err_stale: false,
        }
    }
}

impl Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst.copy_from_slice(&[
            self.i_start as u64,
            self.i_zero as u64,
            (self.i_address & 0xF) as u64,
            self.i_rx as u64,
        ]);
    }
}

impl Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        dst.copy_from_slice(&[
            self.o_tx as u64,
            self.o_tx_en as u64,
            self.o_trigger as u64,
            self.o_clr as u64,
            self.o_busy as u64,
            self.o_done as u64,
            self.o_valid as u64,
            self.o_position as u64,
            self.o_err_checksum as u64,
            self.o_err_parity as u64,
            self.o_err_frame as u64,
            self.o_err_address as u64,
            self.o_err_timeout as u64,
            self.o_err_stale as u64,
        ]);
    }
}

/// The host. One [`Host::step`] is one rising edge of the system clock.
#[derive(Debug, Clone)]
pub struct Host {
    cfg: HostConfig,
    state: State,
    rx: Receiver,
    rx_out: uart::Out,
    tx: Tx,
    tx_out: TxOut,
    tx_in: TxIn,
    tx_pending: bool,
    /// The command being sent and the next byte's index.
    cmd: [u8; 3],
    cmd_index: u8,
    /// The operation expects an answer.
    expect_answer: bool,
    tag: u8,
    window: u64,
    count: u8,
    synced: bool,
    idle: u64,
    stale: u64,
    cnt: u64,
    /// Steps until the stop bit of the last character received has ended
    /// on the line (loaded at its stop-bit pulse): a trigger falls only at
    /// 0, outside the frame ("T1-T3: Data transmission time").
    stop_left: u64,
    out: Out,
}

impl Host {
    /// A host in its reset state.
    pub fn new(cfg: HostConfig) -> Result<Self> {
        cfg.validate()?;
        Ok(Host {
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
            cmd: [0; 3],
            cmd_index: 0,
            expect_answer: false,
            tag: frames::TAG_81,
            window: 0,
            count: 0,
            synced: true,
            idle: 0,
            stale: 0,
            cnt: 0,
            stop_left: 0,
            state: State::Idle,
            out: Out::default(),
            cfg,
        })
    }

    /// The input ports, in vector order (the Verilog port names).
    pub fn input_ports() -> Vec<Port> {
        vec![
            Port::new("i_start", 1),
            Port::new("i_zero", 1),
            Port::new("i_address", 4),
            Port::new("i_rx", 1).idle_high(),
        ]
    }

    /// The output ports, in vector order (the Verilog port names).
    pub fn output_ports() -> Vec<Port> {
        vec![
            Port::new("o_tx", 1),
            Port::new("o_tx_en", 1),
            Port::new("o_trigger", 1),
            Port::new("o_clr", 1),
            Port::new("o_busy", 1),
            Port::new("o_done", 1),
            Port::new("o_valid", 1),
            Port::new("o_position", 32),
            Port::new("o_err_checksum", 1),
            Port::new("o_err_parity", 1),
            Port::new("o_err_frame", 1),
            Port::new("o_err_address", 1),
            Port::new("o_err_timeout", 1),
            Port::new("o_err_stale", 1),
        ]
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        self.state
    }

    /// Characters since the last frame boundary (saturates at `L + 1`).
    pub fn count(&self) -> u8 {
        self.count
    }

    /// The finder is synced (the next `L`-th character must close a frame).
    pub fn synced(&self) -> bool {
        self.synced
    }

    fn window_byte(&self, j: usize) -> u8 {
        let l = self.cfg.frame_len();
        (self.window >> (8 * (l - 1 - j))) as u8
    }

    /// How many of the next steps with `input` only run counters
    /// (fast-forward): no output, state or character count changes and no
    /// pulse comes. The receiver waits between two samples (or idles), the
    /// sender is idle, the frame gap, stale and state counters are short of
    /// their ends. 0 while a pulse is up, a command is being sent, or
    /// `input` starts an operation.
    pub fn quiet(&self, input: &In) -> u64 {
        let o = &self.out;
        let pulse = o.o_done
            || o.o_valid
            || o.o_err_checksum
            || o.o_err_parity
            || o.o_err_frame
            || o.o_err_address
            || o.o_err_timeout
            || o.o_err_stale;
        let rx = self.rx_out;
        if pulse
            || rx.o_valid
            || rx.o_parity_err
            || rx.o_frame_err
            || self.tx_pending
            || self.tx_in.i_valid
            || self.tx.state() != uart::TxState::Idle
        {
            return 0;
        }
        let cfg = self.cfg;
        let fsm = match self.state {
            State::Idle if input.i_start || input.i_zero => return 0,
            State::Idle => u64::MAX,
            // Waiting for the last stop bit to end before the trigger falls.
            State::Trigger if o.o_trigger => self.stop_left,
            State::Trigger | State::Clr | State::Wait => self.cnt,
            State::Send => return 0,
        };
        let gap = if !rx.o_busy && self.count != 0 {
            cfg.gap_clocks.saturating_sub(self.idle + 1)
        } else {
            u64::MAX
        };
        let stale = if cfg.stale_clocks != 0 {
            cfg.stale_clocks.saturating_sub(self.stale + 1)
        } else {
            u64::MAX
        };
        let line = uart::In {
            i_rx: input.i_rx || o.o_tx_en,
        };
        fsm.min(gap).min(stale).min(self.rx.quiet(&line))
    }

    /// The same as `n` steps with the last input, for `n` up to [`Host::quiet`].
    pub fn skip(&mut self, n: u64) {
        if !self.rx_out.o_busy && self.count != 0 {
            self.idle += n;
        }
        if self.cfg.stale_clocks != 0 {
            self.stale += n;
        }
        if self.state == State::Trigger && self.out.o_trigger {
            // quiet() stops short of the step that reads 0.
        } else if matches!(self.state, State::Trigger | State::Clr | State::Wait) {
            self.cnt -= n;
        }
        self.stop_left = self.stop_left.saturating_sub(n);
        self.rx.skip(n);
    }

    /// One rising edge of the system clock.
    pub fn step(&mut self, input: &In) -> Out {
        let cfg = self.cfg;
        let l = cfg.frame_len();
        let mut next = Out {
            o_done: false,
            o_valid: false,
            o_err_checksum: false,
            o_err_parity: false,
            o_err_frame: false,
            o_err_address: false,
            o_err_timeout: false,
            o_err_stale: false,
            ..self.out
        };
        let rx = self.rx_out;
        let tx = self.tx_out;
        let mut tx_in = TxIn {
            i_valid: false,
            i_data: self.tx_in.i_data,
        };

        // Frame finder.
        let mut event = false;
        let mut accepted = false;
        if rx.o_valid {
            let mask = if l == 8 {
                u64::MAX
            } else {
                (1u64 << (8 * l)) - 1
            };
            self.window = ((self.window << 8) | rx.o_data as u64) & mask;
            let count = (self.count + 1).min(l as u8 + 1);
            let sum = (0..l - 1).fold(0u8, |s, j| s.wrapping_add(self.window_byte(j)));
            let (b0, b1, cs) = (
                self.window_byte(0),
                self.window_byte(1),
                self.window_byte(l - 1),
            );
            let header_ok = b0 == frames::SYNC && b1 == self.tag;
            if count as usize >= l && header_ok && sum == cs {
                let data = (2..l - 1).fold(0u64, |v, j| (v << 8) | self.window_byte(j) as u64);
                let data = data & ((1u64 << cfg.bits) - 1);
                next.o_position = if cfg.gray { from_gray(data) } else { data } as u32;
                next.o_valid = true;
                accepted = true;
                event = true;
                self.count = 0;
                self.synced = true;
                self.stale = 0;
            } else {
                if count as usize == l && self.synced {
                    event = true;
                    self.synced = false;
                    if b0 == frames::SYNC
                        && b1 & 0xF0 == 0xB0
                        && cfg.mode.is_bus()
                        && cfg.tag_address
                        && b1 != self.tag
                    {
                        next.o_err_address = true;
                    } else if !header_ok {
                        next.o_err_frame = true;
                    } else {
                        next.o_err_checksum = true;
                    }
                }
                self.count = count;
            }
            self.idle = 0;
        } else if rx.o_parity_err || rx.o_frame_err {
            next.o_err_parity = rx.o_parity_err;
            next.o_err_frame = rx.o_frame_err;
            event = true;
            self.count = 0;
            self.synced = false;
            self.idle = 0;
        } else if rx.o_busy {
            self.idle = 0;
        } else if self.count != 0 {
            self.idle += 1;
            if self.idle == cfg.gap_clocks {
                if self.synced && (self.count as usize) < l {
                    next.o_err_frame = true;
                    event = true;
                }
                self.count = 0;
                self.synced = true;
            }
        }
        if cfg.stale_clocks != 0 && !accepted {
            if self.stale + 1 == cfg.stale_clocks {
                next.o_err_stale = true;
                self.stale = 0;
            } else {
                self.stale += 1;
            }
        }

        // Operation FSM.
        match self.state {
            State::Idle => {
                let bus_zero = input.i_zero && cfg.mode == Mode::BusClear;
                if input.i_start && cfg.mode.is_timed() {
                    // Timed modes: a read is "the next frame event".
                    self.state = State::Wait;
                    self.cnt = cfg.timeout_clocks - 1;
                    next.o_busy = true;
                } else if input.i_start && cfg.mode.is_handshake() {
                    self.state = State::Trigger;
                    self.cnt = cfg.trigger_low_clocks - 1;
                    // Not inside the last frame's stop bit: the trigger
                    // falls once it has ended.
                    next.o_trigger = self.stop_left != 0;
                    next.o_busy = true;
                } else if (input.i_start && cfg.mode.is_bus()) || bus_zero {
                    let a = input.i_address & 0xF;
                    self.cmd = if input.i_start {
                        frames::read_command(a)
                    } else {
                        frames::zero_command(a)
                    };
                    self.expect_answer = input.i_start || cfg.zero_answer;
                    self.tag = if cfg.tag_address {
                        0xB0 | a
                    } else {
                        frames::TAG_81
                    };
                    self.cmd_index = 0;
                    self.state = State::Send;
                    next.o_tx_en = true;
                    next.o_busy = true;
                } else if input.i_zero && cfg.mode.has_clr() {
                    self.state = State::Clr;
                    self.cnt = cfg.clr_low_clocks - 1;
                    next.o_clr = false;
                    next.o_busy = true;
                }
            }
            State::Trigger => {
                if self.out.o_trigger {
                    next.o_trigger = self.stop_left != 0;
                } else if self.cnt == 0 {
                    next.o_trigger = true;
                    self.state = State::Wait;
                    self.cnt = cfg.timeout_clocks - 1;
                } else {
                    self.cnt -= 1;
                }
            }
            State::Clr => {
                if self.cnt == 0 {
                    next.o_clr = true;
                    self.state = State::Idle;
                    next.o_busy = false;
                    next.o_done = true;
                } else {
                    self.cnt -= 1;
                }
            }
            State::Send => {
                if self.tx_pending {
                    if tx.o_busy {
                        self.tx_pending = false;
                    }
                } else if !tx.o_busy {
                    if self.cmd_index == 3 {
                        next.o_tx_en = false;
                        if self.expect_answer {
                            self.state = State::Wait;
                            self.cnt = cfg.timeout_clocks - 1;
                        } else {
                            self.state = State::Idle;
                            next.o_busy = false;
                            next.o_done = true;
                        }
                    } else {
                        tx_in = TxIn {
                            i_valid: true,
                            i_data: self.cmd[self.cmd_index as usize],
                        };
                        self.cmd_index += 1;
                        self.tx_pending = true;
                    }
                }
            }
            State::Wait => {
                if event {
                    self.state = State::Idle;
                    next.o_busy = false;
                    next.o_done = true;
                } else if self.cnt == 0 {
                    next.o_err_timeout = true;
                    self.state = State::Idle;
                    next.o_busy = false;
                    next.o_done = true;
                } else {
                    self.cnt -= 1;
                }
            }
        }

        // A stop-bit pulse: that stop bit ends STOP_REST steps later; the
        // count is read one step after it is loaded, so it is loaded one less.
        if rx.o_valid || rx.o_parity_err || rx.o_frame_err {
            self.stop_left = uart::stop_rest_clocks(cfg.clocks_per_bit).saturating_sub(1);
        } else {
            self.stop_left = self.stop_left.saturating_sub(1);
        }

        // The receiver hears the line only while the driver is off; the
        // sender takes the byte registered in the previous cycle.
        self.tx_out = self.tx.step(&self.tx_in);
        self.tx_in = tx_in;
        next.o_tx = self.tx_out.o_tx;
        self.rx_out = self.rx.step(&uart::In {
            i_rx: input.i_rx || self.out.o_tx_en,
        });
        self.out = next;
        next
    }
}
