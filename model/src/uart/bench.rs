//! The `uart_rx` core's own bench: a [`Transmitter`] (with baud error and
//! jitter, plus low pulses and breaks on the line) feeding a [`Receiver`].

use serde::{Deserialize, Serialize};

use super::receiver::{In, Out, Receiver, ReceiverConfig};
use super::transmitter::Transmitter;
use super::Parity;
use crate::ports::{Port, Ports};
use crate::testbench::{self, Setup, Testbench};
use crate::trace::{Layout, Sample};
use crate::{ConfigError, Result, Timebase};

/// A low pulse forced onto the line: shorter than half a bit it is a glitch
/// the receiver must reject; longer than a frame it is a break.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LowPulse {
    /// Start, µs after reset.
    pub at_us: f64,
    /// Width in ns.
    pub width_ns: f64,
}

/// Everything a scenario says about a `uart_rx` set-up (`[uart]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock in MHz.
    pub f_sys_mhz: f64,
    /// Nominal bit rate in bit/s (the receiver's).
    pub baud: f64,
    /// The sender's baud error in percent (positive = sender fast).
    pub error_percent: f64,
    /// Peak jitter of every edge the sender makes, in ns.
    pub jitter_ns: f64,
    /// Seed of the jitter.
    pub seed: u64,
    /// Bytes to send, in order (sent `repeat` times).
    pub bytes: Vec<u8>,
    /// How many times the byte list is sent.
    pub repeat: usize,
    /// Idle bits between frames (0 = back to back).
    pub gap_bits: f64,
    /// First frame's start, µs after reset.
    pub first_us: f64,
    /// Low pulses forced onto the line.
    pub low: Vec<LowPulse>,
    /// The parity bit (`PARITY`; none: 10-bit frames, the ESL and T-format
    /// default; odd or even: 11-bit frames, the SAR58K24 and Modbus option).
    pub parity: Parity,
    /// 0-based numbers of the frames (in sending order, repeats counted)
    /// whose parity bit is sent inverted (`o_parity_err`).
    pub parity_flips: Vec<usize>,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 100.0,
            baud: 10e6,
            error_percent: 0.0,
            jitter_ns: 0.0,
            seed: 1,
            bytes: vec![0x55],
            repeat: 1,
            gap_bits: 0.0,
            first_us: 0.5,
            low: Vec::new(),
            parity: Parity::None,
            parity_flips: Vec::new(),
        }
    }
}

impl BenchConfig {
    /// The receiver's configuration (the Verilog parameters).
    pub fn receiver_config(&self) -> Result<ReceiverConfig> {
        let tb = self.timebase()?;
        if self.baud.is_nan() || self.baud < 1.0 {
            return Err(ConfigError::invalid(
                "baud",
                format!("{}", self.baud),
                "give the bit rate in bit/s, e.g. 10e6",
            ));
        }
        let ratio = tb.f_sys_hz() as f64 / self.baud;
        if (ratio - ratio.round()).abs() > 1e-6 {
            return Err(ConfigError::invalid(
                "baud",
                format!("f_sys / baud = {ratio:.4} is not a whole number of clocks per bit"),
                format!(
                    "use a baud rate that divides f_sys, e.g. {} bit/s",
                    tb.f_sys_hz() as f64 / ratio.round()
                ),
            ));
        }
        let cfg = ReceiverConfig {
            clocks_per_bit: ratio.round() as u64,
        };
        cfg.validate()?;
        Ok(cfg)
    }

    fn check(&self) -> Result<()> {
        let cfg = self.receiver_config()?;
        let frames = self.bytes.len().saturating_mul(self.repeat);
        if frames > 1_000_000 {
            return Err(ConfigError::invalid(
                "repeat",
                format!(
                    "{frames} frames ({} bytes × {})",
                    self.bytes.len(),
                    self.repeat
                ),
                "send at most 1000000 frames",
            ));
        }
        if let Some(&f) = self
            .parity_flips
            .iter()
            .find(|&&f| self.parity == Parity::None || f >= frames)
        {
            return Err(ConfigError::invalid(
                "parity_flips",
                format!(
                    "frame {f} with parity {:?} and {frames} frames sent",
                    self.parity
                ),
                "set parity to odd or even and list frame numbers below the number of frames sent",
            ));
        }
        if !(-20.0..=20.0).contains(&self.error_percent) {
            return Err(ConfigError::invalid(
                "error_percent",
                format!("{}", self.error_percent),
                "give a baud error within ±20 %",
            ));
        }
        let bit_ns = 1e9 / self.baud;
        if !(0.0..=bit_ns / 4.0).contains(&self.jitter_ns) {
            return Err(ConfigError::invalid(
                "jitter_ns",
                format!("{} ns", self.jitter_ns),
                format!(
                    "give a jitter from 0 to a quarter bit ({} ns)",
                    bit_ns / 4.0
                ),
            ));
        }
        if self.bytes.is_empty() || self.repeat == 0 || self.bytes.len() * self.repeat > 1_000_000 {
            return Err(ConfigError::invalid(
                "bytes",
                "no bytes, or more than a million",
                "list 1 to 1 000 000 bytes to send",
            ));
        }
        if !(0.0..1e6).contains(&self.gap_bits) || !(0.0..1e7).contains(&self.first_us) {
            return Err(ConfigError::invalid(
                "gap_bits",
                "out of range",
                "give non-negative times",
            ));
        }
        for (i, p) in self.low.iter().enumerate() {
            if !(p.at_us >= 0.0 && p.width_ns > 0.0 && p.width_ns < 1e9) {
                return Err(ConfigError::invalid(
                    format!("low[{i}]"),
                    "bad time or width",
                    "give at_us ≥ 0 and a positive width_ns",
                ));
            }
        }
        // Refuse up front a run the vector format cannot hold (32-bit cycle stamps).
        let total = (self.first_us * 1e-6
            + frames as f64 * (self.parity.frame_bits() as f64 + self.gap_bits) / self.baud)
            * self.timebase()?.f_sys_hz() as f64
            + self
                .low
                .iter()
                .map(|p| {
                    (p.at_us * 1e-6 + p.width_ns * 1e-9)
                        * self.timebase().map_or(0.0, |t| t.f_sys_hz() as f64)
                })
                .fold(0.0, f64::max);
        if total > u32::MAX as f64 {
            return Err(ConfigError::invalid(
                "bytes",
                format!(
                    "the run takes about {total:.0} cycles, more than the {} a vector file holds",
                    u32::MAX
                ),
                "send fewer bytes, or shorter gaps",
            ));
        }
        let _ = cfg;
        Ok(())
    }
}

impl Setup for BenchConfig {
    type Bench = Bench;
    const PROTOCOL: &'static crate::protocol::Protocol = &super::descriptor::PROTOCOL;

    fn validate(&self) -> Result<()> {
        self.check()
    }

    fn timebase(&self) -> Result<Timebase> {
        Timebase::from_mhz(self.f_sys_mhz)
    }

    fn verilog_parameters(&self) -> Result<Vec<(&'static str, u64)>> {
        Ok(vec![
            ("CLOCKS_PER_BIT", self.receiver_config()?.clocks_per_bit),
            ("PARITY", self.parity.code()),
        ])
    }

    fn bench(&self) -> Result<Bench> {
        Bench::new(self)
    }
}

/// One event of the receiver, as the transcript reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// Cycle of the output pulse.
    pub cycle: u64,
    /// `byte`, `frame_error`, `parity_error` or `start_error`.
    pub kind: &'static str,
    /// The byte received (absent for a start error).
    pub received: Option<u8>,
    /// The byte the sender was sending when the frame began, if any.
    pub sent: Option<u8>,
    /// Cycle at which that byte's start bit began.
    pub sent_cycle: Option<u64>,
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.sent_cycle.unwrap_or(self.cycle), self.cycle)
    }
}

/// Sender, line and receiver.
pub struct Bench {
    receiver: Receiver,
    transmitter: Transmitter,
    lows: Vec<(u64, u64)>,
    end: u64,
    cycle: u64,
    frame_bits: u64,
    bit_cycles: u64,
    events: Vec<Transaction>,
    layout: Layout,
}

impl Bench {
    /// A bench in its reset state.
    pub fn new(cfg: &BenchConfig) -> Result<Self> {
        cfg.check()?;
        let tb = cfg.timebase()?;
        let rc = cfg.receiver_config()?;
        let mut transmitter = Transmitter::new(
            tb.period_ps(),
            cfg.baud,
            cfg.error_percent,
            cfg.jitter_ns * 1e3,
            cfg.seed,
        )
        .with_parity(cfg.parity);
        let mut at = cfg.first_us * 1e6;
        let bytes = cfg.bytes.iter().cycle().take(cfg.bytes.len() * cfg.repeat);
        for (i, &b) in bytes.enumerate() {
            if cfg.parity_flips.contains(&i) {
                let mut levels = cfg.parity.levels(b);
                levels[9] = !levels[9];
                transmitter.send_byte_levels(b, &levels, at, cfg.gap_bits);
            } else {
                transmitter.send(b, at, cfg.gap_bits);
            }
            at = 0.0;
        }
        let lows: Vec<(u64, u64)> = cfg
            .low
            .iter()
            .map(|p| {
                let start = tb.cycles_nearest_ns(p.at_us * 1e3);
                (start, start + tb.cycles_nearest_ns(p.width_ns).max(1))
            })
            .collect();
        let last_low = lows.iter().map(|l| l.1).max().unwrap_or(0);
        let idle_from = tb
            .cycles_at_least_ns(transmitter.idle_from_ps() / 1e3)
            .max(last_low);
        let end = idle_from + 3 * rc.clocks_per_bit + 16;
        let mut outputs = Receiver::output_ports();
        outputs.push(Port::new("o_parity_err", 1));
        let layout = Layout {
            inputs: Receiver::input_ports(),
            outputs,
            line: vec![Port::new("rx_line", 1)],
            decoded: vec![Port::new("state", 3), Port::new("bit_index", 3)],
        };
        Ok(Bench {
            receiver: Receiver::with_parity(rc, cfg.parity)?,
            transmitter,
            lows,
            end,
            cycle: 0,
            frame_bits: cfg.parity.frame_bits() as u64,
            bit_cycles: rc.clocks_per_bit,
            events: Vec::new(),
            layout,
        })
    }

    fn record(&mut self, out: &Out) {
        let kind = if out.o_valid {
            "byte"
        } else if out.o_frame_err {
            "frame_error"
        } else if out.o_parity_err {
            "parity_error"
        } else if out.o_start_err {
            "start_error"
        } else {
            return;
        };
        // A byte, parity or framing error comes at the stop bit, 9.5 bits
        // (10.5 with parity) after its start bit began; with a fast sender
        // the next start bit may already have begun, so the frame is the
        // latest one that started at least nine (ten) bits (and at most a
        // frame and a quarter) before the event. A start error belongs to no
        // frame.
        let bit = self.bit_cycles;
        let frame_cycles = self.frame_bits * bit;
        let sent = if kind == "start_error" {
            None
        } else {
            let window = frame_cycles + frame_cycles / 4;
            self.transmitter
                .sent()
                .iter()
                .rev()
                .find(|s| {
                    s.start_cycle + (self.frame_bits - 1) * bit <= self.cycle
                        && self.cycle - s.start_cycle <= window
                })
                .copied()
        };
        self.events.push(Transaction {
            cycle: self.cycle,
            kind,
            received: (kind != "start_error").then_some(out.o_data),
            sent: sent.map(|s| s.byte),
            sent_cycle: sent.map(|s| s.start_cycle),
        });
    }
}

impl Testbench for Bench {
    crate::compiled_here!();

    type Transaction = Transaction;

    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn step(&mut self, sample: Option<&mut Sample>) {
        let sent = self.transmitter.step();
        let forced_low = self
            .lows
            .iter()
            .any(|&(a, b)| self.cycle >= a && self.cycle < b);
        let line = sent && !forced_low;
        let input = In { i_rx: line };
        let out = self.receiver.step(&input);
        self.record(&out);
        self.cycle += 1;
        let Some(sample) = sample else { return };
        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        sample.outputs[5] = out.o_parity_err as u64;
        sample.line[0] = line as u64;
        sample.decoded[0] = self.receiver.state() as u64;
        sample.decoded[1] = self.receiver.bit_index() as u64;
    }

    fn finished(&self) -> bool {
        self.cycle >= self.end
    }

    fn quiet_cycles(&self) -> u64 {
        // Until a low pulse begins or ends ...
        let c = self.cycle;
        let lows = self
            .lows
            .iter()
            .map(|&(a, b)| {
                if c < a {
                    a - c
                } else if c < b {
                    b - c
                } else {
                    u64::MAX
                }
            })
            .min()
            .unwrap_or(u64::MAX);
        let forced_low = self.lows.iter().any(|&(a, b)| c >= a && c < b);
        // ... the sender's next edge or frame start, the receiver's next
        // sample, or the end.
        let line = self.transmitter.level() && !forced_low;
        lows.min(self.transmitter.quiet())
            .min(self.receiver.quiet(&In { i_rx: line }))
            .min(self.end.saturating_sub(c))
    }

    fn skip(&mut self, n: u64) {
        self.transmitter.skip(n);
        self.receiver.skip(n);
        self.cycle += n;
    }

    fn cycle(&self) -> u64 {
        self.cycle
    }

    fn into_transactions(self) -> Vec<Transaction> {
        self.events
    }
}
