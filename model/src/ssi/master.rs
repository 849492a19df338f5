//! The SSI reader, cycle for cycle the same machine as `hdl/rtl/ssi_master.v`.

use crate::ports::{Port, Ports};
use crate::{ConfigError, Result};

/// Synchroniser depth on `i_ssi_data` (fixed, as in the RTL).
pub const SYNC_STAGES: u64 = 2;

/// The reader's configuration, in cycles; each field is the Verilog parameter
/// of the same name in upper case.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MasterConfig {
    /// Data bits per read, 1 to 64 (`BITS`).
    pub bits: u32,
    /// System clocks per SSI clock period, at least 8 (`CLOCKS_PER_BIT`).
    pub clocks_per_bit: u64,
    /// System clocks of each clock-high phase (`HIGH_CLOCKS`); with
    /// `low_clocks` it makes up the period. An odd period gives the high
    /// phase the extra cycle ([`crate::time::BitClock`]).
    pub high_clocks: u64,
    /// System clocks of each clock-low phase, in which the bit is captured (`LOW_CLOCKS`).
    pub low_clocks: u64,
    /// Decode Gray to binary (`GRAY`).
    pub gray: bool,
    /// Read the value twice in one transfer and compare (`DOUBLE_READ`).
    pub double_read: bool,
    /// Clock one bit past the LSB and require it to be 0 (`WIRE_CHECK`).
    pub wire_check: bool,
    /// Length of the first low phase, the encoder's `T_cs` (`T_CS_CLOCKS`).
    pub t_cs_clocks: u64,
    /// Clock-high pause after a read before the next may start (`PAUSE_CLOCKS`).
    pub pause_clocks: u64,
    /// Extra cycles between a falling edge and the level it samples (`SAMPLE_DELAY`).
    pub sample_delay: u64,
}

impl MasterConfig {
    /// Checks the configuration; field names are those of a scenario's `[master]` table.
    pub fn validate(&self) -> Result<()> {
        if !(1..=64).contains(&self.bits) {
            return Err(ConfigError::invalid(
                "master.bits",
                format!("{} bits", self.bits),
                "read 1 to 64 bits",
            ));
        }
        if self.clocks_per_bit < 8 {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!("the SSI clock is f_sys / {}", self.clocks_per_bit),
                "make f_sys at least 8 times the SSI clock",
            ));
        }
        if self.high_clocks + self.low_clocks != self.clocks_per_bit
            || self.high_clocks == 0
            || self.low_clocks == 0
        {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!(
                    "phases of {} + {} cycles for a period of {}",
                    self.high_clocks, self.low_clocks, self.clocks_per_bit
                ),
                "give high and low phases that make up the period",
            ));
        }
        let low = self.low_clocks;
        if SYNC_STAGES + self.sample_delay > low - 1 {
            return Err(ConfigError::invalid(
                "master.sample_delay_ns",
                format!(
                    "a sample {} cycles after the falling edge falls outside the {}-cycle low phase",
                    SYNC_STAGES + self.sample_delay,
                    low
                ),
                "lower sample_delay_ns or the SSI clock frequency",
            ));
        }
        if self.t_cs_clocks < low {
            return Err(ConfigError::invalid(
                "master.t_cs_us",
                format!(
                    "{} cycles is shorter than a low phase of the SSI clock ({} cycles)",
                    self.t_cs_clocks, low
                ),
                "give T_cs of at least half the SSI clock period",
            ));
        }
        if self.pause_clocks == 0 {
            return Err(ConfigError::invalid(
                "master.pause_us",
                "no pause",
                "pause at least the encoder's monoflop time T_m",
            ));
        }
        if self.double_read && self.wire_check {
            return Err(ConfigError::invalid(
                "master.wire_check",
                "double read and wire check both set",
                "choose one: a repeating encoder has no 0 after its LSB",
            ));
        }
        Ok(())
    }

    /// Bits sampled in one read: the value, its copy, the wire-check bit.
    pub fn sampled_bits(&self) -> u32 {
        self.bits * if self.double_read { 2 } else { 1 } + self.wire_check as u32
    }

    /// Cycles from the accepted start to `o_done` (inclusive of the done cycle's edge).
    pub fn read_cycles(&self) -> u64 {
        self.t_cs_clocks + self.sampled_bits() as u64 * self.clocks_per_bit
    }

    /// The `cnt` value of the low-phase cycle that captures the synchronised bit.
    fn capture_count(&self) -> u64 {
        self.low_clocks - SYNC_STAGES - self.sample_delay
    }
}

/// The reader's states; the RTL's `localparam`s carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// Clock high, waiting for `i_start`.
    Idle = 0,
    /// First low phase: the encoder stores its value (`T_cs`).
    Latch = 1,
    /// Clock high half period.
    High = 2,
    /// Clock low half period; one bit is captured in it.
    Low = 3,
    /// Clock high while the encoder's monoflop runs out.
    Pause = 4,
}

/// Inputs sampled at one rising edge of the system clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct In {
    /// Host: start one read (one-cycle pulse; ignored while busy).
    pub i_start: bool,
    /// Line: the encoder's data as it arrives at the master's receiver.
    pub i_ssi_data: bool,
}

/// Registered outputs after one rising edge of the system clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Out {
    /// Line: the SSI clock to the encoder.
    pub o_ssi_clk: bool,
    /// Host: a read or its pause is under way.
    pub o_busy: bool,
    /// Host: one-cycle pulse at the end of a read, or of a refused start.
    pub o_done: bool,
    /// Host: the position of the last read, binary, `BITS` wide.
    pub o_position: u64,
    /// Status pulse with `o_done`: the data line was low when the start came
    /// (encoder still in its monoflop time, or line stuck low); nothing was read.
    pub o_err_idle: bool,
    /// Status pulse with `o_done`: the two copies of a double read differ.
    pub o_err_double: bool,
    /// Status pulse with `o_done`: the bit after the LSB was 1 (line stuck high or broken).
    pub o_err_wire: bool,
}

impl Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_start as u64;
        dst[1] = self.i_ssi_data as u64;
    }
}

impl Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.o_ssi_clk as u64;
        dst[1] = self.o_busy as u64;
        dst[2] = self.o_done as u64;
        dst[3] = self.o_position;
        dst[4] = self.o_err_idle as u64;
        dst[5] = self.o_err_double as u64;
        dst[6] = self.o_err_wire as u64;
    }
}

/// The SSI reader. One [`Master::step`] is one rising edge of the system clock.
#[derive(Debug, Clone)]
pub struct Master {
    cfg: MasterConfig,
    // Constants of the configuration, worked out once (the RTL's localparams).
    high: u64,
    low: u64,
    mask: u64,
    capture_at: u64,
    sampled: u32,
    state: State,
    cnt: u64,
    bit_count: u32,
    data_meta: bool,
    data_sync: bool,
    gray_last: bool,
    data: u64,
    copy: u64,
    wire_bad: bool,
    raw: u128,
    out: Out,
}

impl Master {
    /// A reader in its reset state.
    pub fn new(cfg: MasterConfig) -> Result<Self> {
        cfg.validate()?;
        Ok(Master {
            high: cfg.high_clocks,
            low: cfg.low_clocks,
            mask: if cfg.bits == 64 {
                u64::MAX
            } else {
                (1u64 << cfg.bits) - 1
            },
            capture_at: cfg.capture_count(),
            sampled: cfg.sampled_bits(),
            cfg,
            state: State::Idle,
            cnt: 0,
            bit_count: 0,
            data_meta: true,
            data_sync: true,
            gray_last: false,
            data: 0,
            copy: 0,
            wire_bad: false,
            raw: 0,
            out: Out {
                o_ssi_clk: true,
                ..Out::default()
            },
        })
    }

    /// The configuration.
    pub fn config(&self) -> &MasterConfig {
        &self.cfg
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        self.state
    }

    /// Bits captured so far in the current read.
    pub fn bit_count(&self) -> u32 {
        self.bit_count
    }

    /// The raw bits captured in the current (or last) read, first bit in the
    /// most significant position of the `sampled_bits()` used.
    pub fn raw_bits(&self) -> u128 {
        self.raw
    }

    /// The input ports, in vector order.
    pub fn input_ports(&self) -> Vec<Port> {
        vec![
            Port::new("i_start", 1),
            Port::new("i_ssi_data", 1).idle_high(),
        ]
    }

    /// The output ports, in vector order.
    pub fn output_ports(&self) -> Vec<Port> {
        vec![
            Port::new("o_ssi_clk", 1),
            Port::new("o_busy", 1),
            Port::new("o_done", 1),
            Port::new("o_position", self.cfg.bits).width_from("BITS"),
            Port::new("o_err_idle", 1),
            Port::new("o_err_double", 1),
            Port::new("o_err_wire", 1),
        ]
    }

    /// One rising edge of the system clock: every register takes its next
    /// value, computed from the registers' present values and `input`.
    pub fn step(&mut self, input: &In) -> Out {
        // Fast path, the same result as the full step below: in most cycles
        // a counter runs down (or the reader idles without a start), no
        // pulse is left to clear, and only the counter and the synchroniser
        // move. `make test` proves the equivalence: vectors are unchanged.
        let o = &self.out;
        let no_pulse = !(o.o_done || o.o_err_idle || o.o_err_double || o.o_err_wire);
        let counting = self.state != State::Idle
            && self.cnt > 0
            && !(self.state == State::Low && self.cnt == self.capture_at);
        let idling = self.state == State::Idle && !input.i_start;
        if no_pulse && (counting || idling) {
            if counting {
                self.cnt -= 1;
            }
            self.data_sync = self.data_meta;
            self.data_meta = input.i_ssi_data;
            return self.out;
        }
        let mut next = Out {
            o_done: false,
            o_err_idle: false,
            o_err_double: false,
            o_err_wire: false,
            ..self.out
        };
        let mut state = self.state;
        let mut cnt = self.cnt;
        match self.state {
            State::Idle => {
                if input.i_start {
                    if self.data_sync {
                        state = State::Latch;
                        cnt = self.cfg.t_cs_clocks - 1;
                        next.o_ssi_clk = false;
                        next.o_busy = true;
                        self.bit_count = 0;
                        self.data = 0;
                        self.copy = 0;
                        self.wire_bad = false;
                        self.gray_last = false;
                        self.raw = 0;
                    } else {
                        next.o_done = true;
                        next.o_err_idle = true;
                    }
                }
            }
            State::Latch | State::High => {
                if self.cnt == 0 {
                    state = if self.state == State::Latch {
                        State::High
                    } else {
                        State::Low
                    };
                    next.o_ssi_clk = self.state == State::Latch;
                    cnt = if self.state == State::Latch {
                        self.high - 1
                    } else {
                        self.low - 1
                    };
                } else {
                    cnt -= 1;
                }
            }
            State::Low => {
                if self.cnt == self.capture_at {
                    self.capture(self.data_sync);
                }
                if self.cnt == 0 {
                    next.o_ssi_clk = true;
                    if self.bit_count == self.sampled {
                        state = State::Pause;
                        cnt = self.cfg.pause_clocks - 1;
                        next.o_done = true;
                        next.o_position = self.data;
                        next.o_err_double = self.cfg.double_read && self.data != self.copy;
                        next.o_err_wire = self.wire_bad;
                    } else {
                        state = State::High;
                        cnt = self.high - 1;
                    }
                } else {
                    cnt -= 1;
                }
            }
            State::Pause => {
                if self.cnt == 0 {
                    state = State::Idle;
                    next.o_busy = false;
                } else {
                    cnt -= 1;
                }
            }
        }
        self.state = state;
        self.cnt = cnt;
        self.data_sync = self.data_meta;
        self.data_meta = input.i_ssi_data;
        self.out = next;
        next
    }

    /// How many of the next steps with `input` only run a counter down:
    /// no output, state or bit count changes (fast-forward). 0 while a
    /// pulse is up, the synchroniser has not settled, or an edge is due.
    pub fn quiet(&self, input: &In) -> u64 {
        let o = &self.out;
        if o.o_done
            || o.o_err_idle
            || o.o_err_double
            || o.o_err_wire
            || self.data_meta != input.i_ssi_data
            || self.data_sync != input.i_ssi_data
        {
            return 0;
        }
        match self.state {
            State::Idle if input.i_start => 0,
            State::Idle => u64::MAX,
            State::Low if self.cnt > self.capture_at => self.cnt - self.capture_at,
            State::Low if self.cnt == self.capture_at => 0,
            State::Latch | State::High | State::Low | State::Pause => self.cnt,
        }
    }

    /// The same as `n` steps with the last input, for `n` up to [`Master::quiet`].
    pub fn skip(&mut self, n: u64) {
        if self.state != State::Idle {
            self.cnt -= n;
        }
    }

    /// Shifts one sampled bit into the value, its copy or the wire check.
    fn capture(&mut self, bit: bool) {
        let mask = self.mask;
        let k = self.bit_count;
        let bits = self.cfg.bits;
        self.raw = (self.raw << 1) | bit as u128;
        // Serial Gray decoding restarts at the MSB of each copy.
        let previous = if k == 0 || k == bits {
            false
        } else {
            self.gray_last
        };
        let binary = if self.cfg.gray { previous ^ bit } else { bit };
        if k < bits {
            self.data = ((self.data << 1) | binary as u64) & mask;
            self.gray_last = binary;
        } else if self.cfg.double_read {
            self.copy = ((self.copy << 1) | binary as u64) & mask;
            self.gray_last = binary;
        } else {
            self.wire_bad = bit;
        }
        self.bit_count += 1;
    }
}
