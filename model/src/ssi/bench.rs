//! A whole SSI set-up: host, reader, cable and encoder, stepped together.
//!
//! Each cycle `c`:
//! 1. the host decides `i_start`; the reader's data input is the level that
//!    left the cable at the master's end in the previous cycle;
//! 2. the reader steps and drives its clock;
//! 3. the clock crosses the cable (its delay, 0 cycles for no cable);
//! 4. the encoder steps with the clock at its pin and drives its data;
//! 5. the data crosses the cable back; the master sees it in cycle `c + 1`.
//!
//! So even with no cable one cycle passes between the encoder's output and
//! the reader's pin, which is what a registered transceiver interface gives.

use serde::{Deserialize, Serialize};

use super::encoder::{AfterLsb, Encoder, EncoderConfig};
use super::master::{In, Master, MasterConfig, Out};
use super::Code;
use crate::angle::angle_deg;
use crate::line::{CableConfig, DelayLine};
use crate::ports::{Port, Ports};
use crate::testbench::{self, Setup, Testbench};
use crate::time::BitClock;
use crate::trace::{Layout, Sample};
use crate::{ConfigError, Result, Timebase};

/// The reader's settings in a scenario file's units (`[master]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MasterSettings {
    /// Clocks to read (`BITS`).
    pub bits: u32,
    /// SSI clock frequency in kHz (the seed's encoder: 100 to 250 kHz); f_sys divided by a whole number of at least 8, odd allowed (the high phase takes the extra cycle).
    pub clock_khz: f64,
    /// `binary` or `gray`.
    pub code: Code,
    /// Read twice and compare.
    pub double_read: bool,
    /// Clock one extra bit and require 0.
    pub wire_check: bool,
    /// First low phase in µs (the seed's `T_cs > 4 µs`).
    pub t_cs_us: f64,
    /// Clock-high pause after each read in µs (at least the encoder's `T_m`).
    pub pause_us: f64,
    /// Sampling delay after each falling edge in ns, for long cables.
    pub sample_delay_ns: f64,
}

impl Default for MasterSettings {
    fn default() -> Self {
        MasterSettings {
            bits: 12,
            clock_khz: 250.0,
            code: Code::Binary,
            double_read: false,
            wire_check: false,
            t_cs_us: 4.0,
            pause_us: 510.0,
            sample_delay_ns: 0.0,
        }
    }
}

/// The encoder's settings in a scenario file's units (`[encoder]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderSettings {
    /// Resolution in bits.
    pub bits: u32,
    /// `binary` or `gray`.
    pub code: Code,
    /// `zeros` or `repeat`.
    pub after_lsb: AfterLsb,
    /// Monoflop time `T_m` in µs (the seed: `T_m > 500 µs`).
    pub monoflop_us: f64,
    /// Clock edge to data output in ns.
    pub output_delay_ns: f64,
}

impl Default for EncoderSettings {
    fn default() -> Self {
        EncoderSettings {
            bits: 12,
            code: Code::Binary,
            after_lsb: AfterLsb::Zeros,
            monoflop_us: 500.0,
            output_delay_ns: 100.0,
        }
    }
}

/// When the host asks for reads (`[host]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HostSettings {
    /// The first start, in µs after reset.
    pub first_start_us: f64,
    /// Idle time between the end of one read's pause and the next start, µs.
    pub gap_us: f64,
}

impl Default for HostSettings {
    fn default() -> Self {
        HostSettings {
            first_start_us: 1.0,
            gap_us: 2.0,
        }
    }
}

/// A data line held at one level from a given read on (`[fault]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StuckFault {
    /// The level the line is stuck at at the master's receiver: `true` = high.
    pub level: bool,
    /// The first read (0-based) that sees the fault.
    pub from_read: usize,
}

/// Everything a scenario says about an SSI set-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock in MHz.
    pub f_sys_mhz: f64,
    /// The reader.
    pub master: MasterSettings,
    /// The encoder.
    pub encoder: EncoderSettings,
    /// The cable.
    pub cable: CableConfig,
    /// The host.
    pub host: HostSettings,
    /// Positions the encoder holds at successive reads (cycled if `reads` is larger).
    pub positions: Vec<u64>,
    /// Number of reads (default: one per listed position).
    pub reads: Option<usize>,
    /// Counts the shaft moves between successive reads (added to the listed positions).
    pub step: u64,
    /// An optional stuck data line.
    pub fault: Option<StuckFault>,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 50.0,
            master: MasterSettings::default(),
            encoder: EncoderSettings::default(),
            cable: CableConfig::default(),
            host: HostSettings::default(),
            positions: vec![0],
            reads: None,
            step: 0,
            fault: None,
        }
    }
}

impl BenchConfig {
    /// The seed's example set-up: a 12-bit binary encoder read at 250 kHz
    /// through 10 m of cable, holding 495 (SAR58K24 manual, SSI section (4)).
    pub fn seed_example() -> Self {
        BenchConfig {
            positions: vec![495],
            cable: CableConfig {
                length_m: 10.0,
                ..CableConfig::default()
            },
            ..BenchConfig::default()
        }
    }

    /// The reader's configuration in cycles (the Verilog parameters).
    pub fn master_config(&self) -> Result<MasterConfig> {
        let tb = self.timebase()?;
        let m = &self.master;
        if m.clock_khz.is_nan() || m.clock_khz <= 0.0 {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                "not a positive frequency",
                "give the SSI clock in kHz, e.g. 250",
            ));
        }
        for (field, value) in [
            ("master.t_cs_us", m.t_cs_us),
            ("master.pause_us", m.pause_us),
            ("master.sample_delay_ns", m.sample_delay_ns),
        ] {
            if !(0.0..1e7).contains(&value) {
                return Err(ConfigError::invalid(
                    field,
                    format!("{value}"),
                    "give a non-negative time",
                ));
            }
        }
        let clock = tb.divider(m.clock_khz * 1e3, "master.clock_khz", 8)?;
        let cfg = MasterConfig {
            bits: m.bits,
            clocks_per_bit: clock.period,
            high_clocks: clock.high,
            low_clocks: clock.low,
            gray: m.code == Code::Gray,
            double_read: m.double_read,
            wire_check: m.wire_check,
            t_cs_clocks: tb.cycles_at_least_ns(m.t_cs_us * 1e3),
            pause_clocks: tb.cycles_at_least_ns(m.pause_us * 1e3),
            sample_delay: tb.cycles_nearest_ns(m.sample_delay_ns),
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// The encoder's configuration in cycles.
    pub fn encoder_config(&self) -> Result<EncoderConfig> {
        let tb = self.timebase()?;
        let e = &self.encoder;
        for (field, value) in [
            ("encoder.monoflop_us", e.monoflop_us),
            ("encoder.output_delay_ns", e.output_delay_ns),
        ] {
            if !(0.0..1e7).contains(&value) {
                return Err(ConfigError::invalid(
                    field,
                    format!("{value}"),
                    "give a non-negative time",
                ));
            }
        }
        let cfg = EncoderConfig {
            bits: e.bits,
            gray: e.code == Code::Gray,
            after_lsb: e.after_lsb,
            monoflop_clocks: tb.cycles_at_least_ns(e.monoflop_us * 1e3),
            output_delay_clocks: tb.cycles_nearest_ns(e.output_delay_ns),
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// The number of reads the host makes.
    pub fn read_count(&self) -> usize {
        self.reads.unwrap_or(self.positions.len())
    }

    /// The position the encoder holds at read `k`.
    pub fn position_at(&self, k: usize) -> u64 {
        let listed = if self.positions.is_empty() {
            0
        } else {
            self.positions[k % self.positions.len()]
        };
        listed.wrapping_add((k as u64).wrapping_mul(self.step))
    }

    /// The Verilog parameters of `ssi_master` for this set-up, in the order the
    /// vector header lists them.
    fn parameters(&self) -> Result<Vec<(&'static str, u64)>> {
        let c = self.master_config()?;
        let mut p = vec![
            ("BITS", c.bits as u64),
            ("CLOCKS_PER_BIT", c.clocks_per_bit),
        ];
        p.extend(BitClock::parameters(
            c.high_clocks,
            c.low_clocks,
            ["HIGH_CLOCKS", "LOW_CLOCKS"],
        ));
        p.extend([
            ("GRAY", c.gray as u64),
            ("DOUBLE_READ", c.double_read as u64),
            ("WIRE_CHECK", c.wire_check as u64),
            ("T_CS_CLOCKS", c.t_cs_clocks),
            ("PAUSE_CLOCKS", c.pause_clocks),
            ("SAMPLE_DELAY", c.sample_delay),
        ]);
        Ok(p)
    }

    /// Checks everything; the error names the scenario field.
    fn check(&self) -> Result<()> {
        self.cable.validate("cable")?;
        self.master_config()?;
        self.encoder_config()?;
        if self.read_count() == 0 {
            return Err(ConfigError::invalid(
                "reads",
                "no reads",
                "list at least one position or set reads",
            ));
        }
        if self.read_count() > 10_000_000 {
            return Err(ConfigError::invalid(
                "reads",
                format!("{} reads", self.read_count()),
                "ask for at most 10 million reads",
            ));
        }
        let limit = if self.encoder.bits == 64 {
            u64::MAX
        } else {
            (1u64 << self.encoder.bits) - 1
        };
        if let Some((i, p)) = self.positions.iter().enumerate().find(|(_, p)| **p > limit) {
            return Err(ConfigError::invalid(
                format!("positions[{i}]"),
                format!("{p} does not fit a {}-bit encoder", self.encoder.bits),
                format!("give positions from 0 to {limit}"),
            ));
        }
        for (field, us) in [
            ("host.first_start_us", self.host.first_start_us),
            ("host.gap_us", self.host.gap_us),
        ] {
            if !(0.0..1e7).contains(&us) {
                return Err(ConfigError::invalid(
                    field,
                    format!("{us}"),
                    "give a non-negative time in µs",
                ));
            }
        }
        // Refuse up front a run the vector format cannot hold, rather than
        // simulate for minutes and fail at the end.
        let tb = self.timebase()?;
        let m = self.master_config()?;
        let per_read =
            m.read_cycles() + m.pause_clocks + tb.cycles_at_least_ns(self.host.gap_us * 1e3) + 4;
        let total = (self.read_count() as u128) * per_read as u128
            + tb.cycles_at_least_ns(self.host.first_start_us * 1e3) as u128;
        if total > MAX_CYCLES as u128 {
            return Err(ConfigError::invalid(
                "reads",
                format!("{} reads take about {total} cycles, more than the {MAX_CYCLES} a vector file holds", self.read_count()),
                "ask for fewer reads, or shorter pauses and gaps",
            ));
        }
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
        self.parameters()
    }

    fn bench(&self) -> Result<Bench> {
        Bench::new(self)
    }
}

/// One read as the transcript reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based read number.
    pub index: usize,
    /// Cycle of the host's start pulse.
    pub start_cycle: u64,
    /// Cycle of `o_done`.
    pub done_cycle: u64,
    /// The position the encoder held when the read began.
    pub encoder_position: u64,
    /// The code word the encoder stored (Gray or binary), as bits MSB first.
    pub sent_bits: String,
    /// The bits the reader sampled, in order.
    pub received_bits: String,
    /// The decoded position, absent when nothing was read.
    pub position: Option<u64>,
    /// `360° × position / 2^bits` with the reader's bit count, as the seed computes it.
    pub angle_deg: Option<f64>,
    /// Errors the reader flagged: `line_not_idle`, `double_read_mismatch`, `wire_check_failed`.
    pub errors: Vec<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Host {
    WaitUntil(u64),
    WaitDone,
    WaitIdle,
    Finished(u64),
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.start_cycle, self.done_cycle)
    }
}

/// Host, reader, cable and encoder.
pub struct Bench {
    cfg: BenchConfig,
    master: Master,
    encoder: Encoder,
    clk_line: DelayLine,
    data_line: DelayLine,
    data_at_master: bool,
    host: Host,
    gap_clocks: u64,
    next_read: usize,
    stuck: Option<bool>,
    cycle: u64,
    last_out: Out,
    open: Option<Transaction>,
    transactions: Vec<Transaction>,
    layout: Layout,
}

/// The longest run a vector file can hold (its cycle stamps are 32 bits).
pub const MAX_CYCLES: u64 = u32::MAX as u64;

/// Cycles the bench keeps running after the last read, so the waves show the idle line.
const TAIL_CYCLES: u64 = 16;

impl Bench {
    /// A bench in its reset state.
    pub fn new(cfg: &BenchConfig) -> Result<Self> {
        cfg.check()?;
        let tb = cfg.timebase()?;
        let master = Master::new(cfg.master_config()?)?;
        let encoder = Encoder::new(cfg.encoder_config()?)?;
        let (clk_line, data_line) = cfg.cable.lines(&tb, true);
        let bits = master.config().bits;
        let layout = Layout {
            inputs: master.input_ports(),
            outputs: master.output_ports(),
            line: vec![
                Port::new("ssi_clk_master", 1),
                Port::new("ssi_clk_encoder", 1),
                Port::new("ssi_data_encoder", 1),
                Port::new("ssi_data_master", 1),
            ],
            decoded: vec![
                Port::new("state", 3),
                Port::new("bit_count", 8),
                Port::new("encoder_position", cfg.encoder.bits),
                Port::new("position", bits),
            ],
        };
        Ok(Bench {
            master,
            encoder,
            clk_line,
            data_line,
            data_at_master: true,
            host: Host::WaitUntil(tb.cycles_at_least_ns(cfg.host.first_start_us * 1e3)),
            gap_clocks: tb.cycles_at_least_ns(cfg.host.gap_us * 1e3),
            next_read: 0,
            stuck: None,
            cycle: 0,
            last_out: Out {
                o_ssi_clk: true,
                ..Out::default()
            },
            open: None,
            transactions: Vec::new(),
            layout,
            cfg: cfg.clone(),
        }
        .with_fault_applied())
    }

    fn with_fault_applied(mut self) -> Self {
        self.apply_fault_before(0);
        self
    }

    /// Runs to the end with nothing recorded.
    pub fn run_to_end(self) -> testbench::Run<Transaction> {
        testbench::run_to_end(self)
    }
}

impl Testbench for Bench {
    crate::compiled_here!();

    type Transaction = Transaction;

    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn finished(&self) -> bool {
        matches!(self.host, Host::Finished(end) if self.cycle >= end)
    }

    fn cycle(&self) -> u64 {
        self.cycle
    }

    fn into_transactions(self) -> Vec<Transaction> {
        self.transactions
    }

    /// One system-clock cycle of the whole set-up.
    fn step(&mut self, sample: Option<&mut Sample>) {
        let start = self.host_decides();
        let pin = self.stuck.unwrap_or(self.data_at_master);
        let input = In {
            i_start: start,
            i_ssi_data: pin,
        };
        let out = self.master.step(&input);
        let clk_at_encoder = self.clk_line.step(out.o_ssi_clk);
        let data_from_encoder = self.encoder.step(clk_at_encoder);
        self.data_at_master = self.data_line.step(data_from_encoder);
        self.host_observes(&out);
        self.last_out = out;
        self.cycle += 1;
        let Some(sample) = sample else { return };

        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        sample.line[0] = out.o_ssi_clk as u64;
        sample.line[1] = clk_at_encoder as u64;
        sample.line[2] = data_from_encoder as u64;
        sample.line[3] = pin as u64;
        sample.decoded[0] = self.master.state() as u64;
        sample.decoded[1] = self.master.bit_count() as u64;
        sample.decoded[2] = self.encoder.position();
        sample.decoded[3] = out.o_position;
    }

    fn quiet_cycles(&self) -> u64 {
        let host = match self.host {
            Host::WaitUntil(at) if self.cycle < at => at - self.cycle,
            Host::WaitUntil(_) | Host::WaitIdle if !self.last_out.o_busy => 0,
            Host::WaitUntil(_) | Host::WaitIdle | Host::WaitDone => u64::MAX,
            Host::Finished(end) => end.saturating_sub(self.cycle),
        };
        // The cycle after a start pulse shows `i_start` falling.
        let just_started = matches!(&self.open, Some(t) if t.start_cycle + 1 == self.cycle);
        if host == 0 || just_started {
            return 0;
        }
        let pin = self.stuck.unwrap_or(self.data_at_master);
        host.min(self.master.quiet(&In {
            i_start: false,
            i_ssi_data: pin,
        }))
        .min(self.clk_line.quiet(self.last_out.o_ssi_clk))
        .min(self.encoder.quiet(self.clk_line.output()))
        .min(self.data_line.quiet(self.encoder.data()))
    }

    fn skip(&mut self, n: u64) {
        self.master.skip(n);
        self.clk_line.skip(n);
        self.encoder.skip(n);
        self.data_line.skip(n);
        self.cycle += n;
    }
}

impl Bench {
    fn host_decides(&mut self) -> bool {
        match self.host {
            Host::WaitUntil(at) if self.cycle >= at && !self.last_out.o_busy => {
                let k = self.next_read;
                let position = self.cfg.position_at(k);
                self.encoder.set_position(position);
                self.open = Some(Transaction {
                    index: k,
                    start_cycle: self.cycle,
                    done_cycle: 0,
                    encoder_position: self.encoder.position(),
                    sent_bits: String::new(),
                    received_bits: String::new(),
                    position: None,
                    angle_deg: None,
                    errors: Vec::new(),
                });
                self.next_read += 1;
                self.host = Host::WaitDone;
                true
            }
            _ => false,
        }
    }

    fn host_observes(&mut self, out: &Out) {
        match self.host {
            Host::WaitDone if out.o_done => {
                self.close_transaction(out);
                self.host = Host::WaitIdle;
            }
            Host::WaitIdle if !out.o_busy => {
                self.apply_fault_before(self.next_read);
                self.host = if self.next_read < self.cfg.read_count() {
                    Host::WaitUntil(self.cycle + self.gap_clocks)
                } else {
                    Host::Finished(self.cycle + TAIL_CYCLES)
                };
            }
            _ => {}
        }
    }

    /// A stuck line appears while the line is idle before read `k`, so the
    /// reader meets it with the same history a real break would give.
    fn apply_fault_before(&mut self, k: usize) {
        if let Some(fault) = &self.cfg.fault {
            if k >= fault.from_read {
                self.stuck = Some(fault.level);
            }
        }
    }

    fn close_transaction(&mut self, out: &Out) {
        let Some(mut t) = self.open.take() else {
            return;
        };
        let mc = self.master.config();
        t.done_cycle = self.cycle;
        if out.o_err_idle {
            t.errors.push("line_not_idle".into());
        } else {
            let n = self.cfg.encoder.bits;
            t.sent_bits = crate::bits::string_of(self.encoder.stored() as u128, n);
            t.received_bits = crate::bits::string_of(self.master.raw_bits(), mc.sampled_bits());
            t.position = Some(out.o_position);
            t.angle_deg = Some(angle_deg(out.o_position, mc.bits));
            if out.o_err_double {
                t.errors.push("double_read_mismatch".into());
            }
            if out.o_err_wire {
                t.errors.push("wire_check_failed".into());
            }
        }
        self.transactions.push(t);
    }
}
