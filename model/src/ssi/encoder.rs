//! An SSI encoder as the SAR58K24 manual describes it, including what it does
//! with too many or too few clocks.

use serde::{Deserialize, Serialize};

use crate::gray::to_gray;
use crate::line::DelayLine;
use crate::{ConfigError, Result};

/// What the encoder puts on the line after its LSB while clocks keep coming.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum AfterLsb {
    /// Zeros until the monoflop expires (a 12-bit value read with 14 clocks
    /// becomes four times larger: "can exceed 1,000 degrees").
    #[default]
    Zeros,
    /// The stored value again from its MSB ("the extra clock pulses may read
    /// duplicate high-bit data"), which is what a double read relies on.
    Repeat,
}

/// The encoder's configuration, in cycles.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EncoderConfig {
    /// Resolution in bits, 1 to 64.
    pub bits: u32,
    /// Send Gray code instead of binary.
    pub gray: bool,
    /// Behaviour after the LSB.
    pub after_lsb: AfterLsb,
    /// Monoflop time `T_m`: cycles without a clock edge after which the
    /// encoder releases the line (high) and stores a new value at the next
    /// falling edge.
    pub monoflop_clocks: u64,
    /// Delay from a clock edge at the encoder to its data output changing.
    pub output_delay_clocks: u64,
}

impl EncoderConfig {
    /// Checks the configuration; field names are those of a scenario's `[encoder]` table.
    pub fn validate(&self) -> Result<()> {
        if !(1..=64).contains(&self.bits) {
            return Err(ConfigError::invalid(
                "encoder.bits",
                format!("{} bits", self.bits),
                "give 1 to 64 bits",
            ));
        }
        if self.monoflop_clocks == 0 {
            return Err(ConfigError::invalid(
                "encoder.monoflop_us",
                "zero",
                "give the encoder's T_m, e.g. 500 µs",
            ));
        }
        Ok(())
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Idle,
    Shifting,
}

/// The encoder emulator. One [`Encoder::step`] is one system-clock cycle.
#[derive(Debug, Clone)]
pub struct Encoder {
    cfg: EncoderConfig,
    position: u64,
    phase: Phase,
    last_clk: bool,
    stored: u64,
    sent: u32,
    quiet: u64,
    level: bool,
    output: DelayLine,
    reads: u64,
}

impl Encoder {
    /// An encoder at rest holding position 0.
    pub fn new(cfg: EncoderConfig) -> Result<Self> {
        cfg.validate()?;
        let output = DelayLine::new(cfg.output_delay_clocks, true);
        Ok(Encoder {
            cfg,
            position: 0,
            phase: Phase::Idle,
            last_clk: true,
            stored: 0,
            sent: 0,
            quiet: 0,
            level: true,
            output,
            reads: 0,
        })
    }

    /// The shaft moves: the position the next falling edge will store.
    pub fn set_position(&mut self, position: u64) {
        self.position = position & self.mask();
    }

    /// The position the encoder holds now.
    pub fn position(&self) -> u64 {
        self.position
    }

    /// The code word stored at the last read (Gray or binary as configured).
    pub fn stored(&self) -> u64 {
        self.stored
    }

    /// Reads begun so far (falling edges that stored a value): the hook a
    /// co-simulation uses to number its transcript entries.
    pub fn reads(&self) -> u64 {
        self.reads
    }

    /// Rising clock edges seen since the last store (bits put on the line).
    pub fn bits_sent(&self) -> u32 {
        self.sent
    }

    /// The monoflop has expired: the line is released and the next falling
    /// edge stores a new value.
    pub fn is_idle(&self) -> bool {
        self.phase == Phase::Idle
    }

    fn mask(&self) -> u64 {
        if self.cfg.bits == 64 {
            u64::MAX
        } else {
            (1u64 << self.cfg.bits) - 1
        }
    }

    /// The `k`-th bit the encoder sends after storing (0 = MSB).
    fn bit(&self, k: u32) -> bool {
        let n = self.cfg.bits;
        let index = match self.cfg.after_lsb {
            AfterLsb::Zeros if k >= n => return false,
            AfterLsb::Zeros => k,
            AfterLsb::Repeat => k % n,
        };
        (self.stored >> (n - 1 - index)) & 1 == 1
    }

    /// How many of the next steps with `clk` leave the data output and the
    /// phase as they are (fast-forward): none on a clock edge, up to the
    /// monoflop's expiry while shifting, and up to the next edge in flight
    /// on the output delay.
    pub fn quiet(&self, clk: bool) -> u64 {
        if clk != self.last_clk {
            return 0;
        }
        let phase = match self.phase {
            Phase::Idle if self.level => u64::MAX,
            Phase::Idle => 0,
            Phase::Shifting => (self.cfg.monoflop_clocks - 1).saturating_sub(self.quiet),
        };
        phase.min(self.output.quiet(self.level))
    }

    /// The data level at the encoder's pin after the last step.
    pub fn data(&self) -> bool {
        self.output.output()
    }

    /// The same as `n` steps with the last clock level, for `n` up to [`Encoder::quiet`].
    pub fn skip(&mut self, n: u64) {
        if self.phase == Phase::Shifting {
            self.quiet += n;
        }
        self.output.skip(n);
    }

    /// One cycle with the clock level at the encoder's pin; returns the data
    /// level the encoder drives onto the cable.
    pub fn step(&mut self, clk: bool) -> bool {
        let fell = self.last_clk && !clk;
        let rose = !self.last_clk && clk;
        self.last_clk = clk;
        match self.phase {
            Phase::Idle => {
                self.level = true;
                if fell {
                    self.stored = if self.cfg.gray {
                        to_gray(self.position)
                    } else {
                        self.position
                    };
                    self.phase = Phase::Shifting;
                    self.sent = 0;
                    self.quiet = 0;
                    self.reads += 1;
                }
            }
            Phase::Shifting => {
                if rose {
                    self.level = self.bit(self.sent);
                    self.sent = self.sent.saturating_add(1);
                    self.quiet = 0;
                } else if fell {
                    self.quiet = 0;
                } else {
                    self.quiet += 1;
                    if self.quiet >= self.cfg.monoflop_clocks {
                        self.phase = Phase::Idle;
                        self.level = true;
                    }
                }
            }
        }
        self.output.step(self.level)
    }
}
