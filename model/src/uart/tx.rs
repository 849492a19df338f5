//! The character sender, cycle for cycle the same machine as
//! `hdl/rtl/uart_tx.v`: start bit 0, 8 data bits LSB first, an optional
//! parity bit, stop bit 1; every bit lasts `CLOCKS_PER_BIT` cycles.
//!
//! ```text
//!  i_valid  _/‾\______________________________________________________
//!  o_tx     ‾‾‾\___start___X d0 X d1 X ... X d7 X (par) X‾‾‾ stop ‾‾‾‾‾‾
//!  o_busy   ___/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\___
//!  state    IDLE|                        SEND                    |IDLE
//! ```
//! `i_valid` is taken in `IDLE` only; the start bit is on `o_tx` from the
//! edge that takes it, and `o_busy` falls at the end of the stop bit, so a
//! byte offered in the cycle `o_busy` is seen low follows after one idle
//! cycle.

use super::Parity;
use crate::ports::{Port, Ports};
use crate::{ConfigError, Result};

/// The sender's configuration (`CLOCKS_PER_BIT`, `PARITY`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TxConfig {
    /// System clocks per bit.
    pub clocks_per_bit: u64,
    /// The parity bit, if any.
    pub parity: Parity,
}

impl TxConfig {
    /// Checks the configuration.
    pub fn validate(&self) -> Result<()> {
        if !(2..=1 << 20).contains(&self.clocks_per_bit) {
            return Err(ConfigError::invalid(
                "baud",
                format!("{} clocks per bit", self.clocks_per_bit),
                "give f_sys at least twice the baud rate and at most 2^20 times",
            ));
        }
        Ok(())
    }
}

/// The sender's states (the RTL's `localparam`s).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TxState {
    /// Waiting for `i_valid`.
    Idle = 0,
    /// Shifting a character out.
    Send = 1,
}

/// Inputs at one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TxIn {
    /// Send `i_data` (taken in `IDLE` only).
    pub i_valid: bool,
    /// The byte.
    pub i_data: u8,
}

/// Registered outputs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TxOut {
    /// The line level.
    pub o_tx: bool,
    /// A character is on the line.
    pub o_busy: bool,
}

impl Default for TxOut {
    fn default() -> Self {
        TxOut {
            o_tx: true,
            o_busy: false,
        }
    }
}

impl Ports for TxIn {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_valid as u64;
        dst[1] = self.i_data as u64;
    }
}

impl Ports for TxOut {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.o_tx as u64;
        dst[1] = self.o_busy as u64;
    }
}

/// The sender. One [`Tx::step`] is one rising edge.
#[derive(Debug, Clone)]
pub struct Tx {
    cfg: TxConfig,
    state: TxState,
    shift: u16,
    bits_left: u8,
    cnt: u64,
    out: TxOut,
}

impl Tx {
    /// A sender in its reset state.
    pub fn new(cfg: TxConfig) -> Result<Self> {
        cfg.validate()?;
        Ok(Tx {
            cfg,
            state: TxState::Idle,
            shift: 0,
            bits_left: 0,
            cnt: 0,
            out: TxOut::default(),
        })
    }

    /// The input ports, in vector order.
    pub fn input_ports() -> Vec<Port> {
        vec![Port::new("i_valid", 1), Port::new("i_data", 8)]
    }

    /// The output ports, in vector order.
    pub fn output_ports() -> Vec<Port> {
        vec![Port::new("o_tx", 1), Port::new("o_busy", 1)]
    }

    /// The state after the last step.
    pub fn state(&self) -> TxState {
        self.state
    }

    /// The outputs after the last step.
    pub fn out(&self) -> TxOut {
        self.out
    }

    /// How many of the next steps with `i_valid` low only count down the
    /// bit timer (fast-forward): mid-bit while sending, no output changes
    /// until the bit ends; `u64::MAX` when idle (the caller caps it where
    /// `i_valid` may rise).
    pub fn quiet(&self) -> u64 {
        match self.state {
            TxState::Idle => u64::MAX,
            TxState::Send => self.cnt,
        }
    }

    /// The same as `n` steps with `i_valid` low, for `n` up to [`Tx::quiet`].
    pub fn skip(&mut self, n: u64) {
        if self.state == TxState::Send {
            self.cnt -= n;
        }
    }

    /// One rising edge.
    pub fn step(&mut self, input: &TxIn) -> TxOut {
        let mut next = self.out;
        match self.state {
            TxState::Idle => {
                if input.i_valid {
                    let levels = self.cfg.parity.levels(input.i_data);
                    self.shift = levels
                        .iter()
                        .rev()
                        .fold(0u16, |acc, &b| (acc << 1) | b as u16);
                    self.bits_left = levels.len() as u8 - 1;
                    self.cnt = self.cfg.clocks_per_bit - 1;
                    self.state = TxState::Send;
                    next.o_tx = self.shift & 1 == 1;
                    next.o_busy = true;
                }
            }
            TxState::Send => {
                if self.cnt != 0 {
                    self.cnt -= 1;
                } else if self.bits_left == 0 {
                    self.state = TxState::Idle;
                    next.o_busy = false;
                    next.o_tx = true;
                } else {
                    self.shift >>= 1;
                    self.bits_left -= 1;
                    self.cnt = self.cfg.clocks_per_bit - 1;
                    next.o_tx = self.shift & 1 == 1;
                }
            }
        }
        self.out = next;
        next
    }
}
