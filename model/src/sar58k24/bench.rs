//! Host, cable and one to three SAR58K24 emulators, stepped together, with a
//! host script of operations. Implements [`Setup`]/[`Testbench`] for `tbgen`
//! (core `sar_async_host`, scenario table `[sar]`).

use serde::{Deserialize, Serialize};

use super::encoder::{
    Encoder, EncoderConfig, EncoderIn, EncoderSettings, Mode, OutputCode, SentFrame,
};
use super::host::{Host, HostConfig, In, Out};
use crate::angle::angle_deg;
use crate::line::{CableConfig, DelayLine, Drive, HalfDuplexLine};
use crate::ports::{Port, Ports};
use crate::testbench::{self, Setup, Testbench};
use crate::trace::{Layout, Sample};
pub use crate::uart::SecondDriver;
use crate::uart::{self, Parity};
use crate::{ConfigError, Result, Timebase};

/// The host's settings in a scenario's units (`[sar.host]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HostSettings {
    /// Answer timeout from entering `WAIT`, µs.
    pub timeout_us: f64,
    /// Idle bit times after a character that end a frame (15 = 1.5 characters).
    pub gap_bits: f64,
    /// Timed modes: refresh periods without a valid frame that flag stale data (0: off).
    pub stale_periods: f64,
    /// Low time of the trigger pulse, µs (T2 ≥ 10 µs).
    pub trigger_low_us: f64,
    /// Low time of the CLR pulse, µs.
    pub clr_low_us: f64,
}

impl Default for HostSettings {
    fn default() -> Self {
        HostSettings {
            timeout_us: 5000.0,
            gap_bits: 15.0,
            stale_periods: 3.0,
            trigger_low_us: 10.0,
            clr_low_us: 20.0,
        }
    }
}

/// What one host operation does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OpKind {
    /// The next frame (timed), a trigger pulse (handshake) or `BC AA Bx` (bus).
    Read,
    /// CLR pulse (clear modes) or `BC AA Cx` (bus + clear).
    Zero,
}

/// One host operation (`[[sar.ops]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Operation {
    /// What to do.
    pub op: OpKind,
    /// Bus address x.
    #[serde(default)]
    pub address: u8,
    /// Idle time before the operation, µs.
    #[serde(default = "default_gap")]
    pub gap_us: f64,
    /// How many times the operation is done, each after its gap (a run of
    /// timed reads is "listen to the next N frames").
    #[serde(default = "default_repeat")]
    pub repeat: u32,
}

fn default_gap() -> f64 {
    100.0
}

fn default_repeat() -> u32 {
    1
}

/// Everything a scenario says about a SAR58K24 asynchronous set-up (`[sar]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock, MHz.
    pub f_sys_mhz: f64,
    /// Baud rate (2.4: 2400 to 115200).
    pub baud: f64,
    /// Parity ("according to customer requirements"; none by default).
    pub parity: Parity,
    /// The mode of every encoder.
    pub mode: Mode,
    /// The host.
    pub host: HostSettings,
    /// The encoders: one, or up to three on a bus.
    pub encoders: Vec<EncoderSettings>,
    /// The cable.
    pub cable: CableConfig,
    /// What the host does.
    pub ops: Vec<Operation>,
    /// Other drivers on the line.
    pub second_drivers: Vec<SecondDriver>,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 10.0,
            baud: 115_200.0,
            parity: Parity::None,
            mode: Mode::TimedSend,
            host: HostSettings::default(),
            encoders: vec![EncoderSettings::default()],
            cable: CableConfig {
                length_m: 10.0,
                ..CableConfig::default()
            },
            ops: vec![Operation {
                op: OpKind::Read,
                address: 1,
                gap_us: 0.0,
                repeat: 2,
            }],
            second_drivers: Vec::new(),
        }
    }
}

/// The seven baud rates the manual lists, and what a host at `f_sys`
/// divides them to: (baud, clocks per bit, error in percent).
pub fn divider(f_sys_hz: u64, baud: f64) -> (u64, f64) {
    let c = (f_sys_hz as f64 / baud).round().max(1.0) as u64;
    let actual = f_sys_hz as f64 / c as f64;
    (c, (actual / baud - 1.0) * 100.0)
}

impl BenchConfig {
    /// The host's clocks per bit, refused when the rounding costs more than 0.5 %.
    pub fn clocks_per_bit(&self) -> Result<u64> {
        let tb = self.timebase()?;
        if !(300.0..=10e6).contains(&self.baud) {
            return Err(ConfigError::invalid(
                "baud",
                format!("{}", self.baud),
                "give a baud rate such as 2400, 9600, 19200 or 115200",
            ));
        }
        let (c, err) = divider(tb.f_sys_hz(), self.baud);
        if err.abs() > 0.5 {
            return Err(ConfigError::invalid(
                "baud",
                format!(
                    "f_sys / baud = {:.3}, rounded to {c} clocks per bit, is {err:+.2} % off",
                    tb.f_sys_hz() as f64 / self.baud
                ),
                "raise f_sys_mhz or pick a clock that divides the baud rate within 0.5 %",
            ));
        }
        Ok(c)
    }

    fn refresh_hz(&self) -> f64 {
        self.encoders.first().map_or(100.0, |e| e.refresh_hz)
    }

    /// The host's configuration in cycles (the Verilog parameters).
    pub fn host_config(&self) -> Result<HostConfig> {
        let tb = self.timebase()?;
        let h = &self.host;
        for (f, v) in [
            ("host.timeout_us", h.timeout_us),
            ("host.trigger_low_us", h.trigger_low_us),
            ("host.clr_low_us", h.clr_low_us),
        ] {
            if !(v > 0.0 && v < 1e7) {
                return Err(ConfigError::invalid(
                    f,
                    format!("{v}"),
                    "give a positive time in µs",
                ));
            }
        }
        if !(1.0..=1000.0).contains(&h.gap_bits) || !(0.0..=1000.0).contains(&h.stale_periods) {
            return Err(ConfigError::invalid(
                "host.gap_bits",
                format!("gap_bits {} stale_periods {}", h.gap_bits, h.stale_periods),
                "give gap_bits 1 to 1000 and stale_periods 0 to 1000",
            ));
        }
        let e = self.encoders.first().cloned().unwrap_or_default();
        let c = self.clocks_per_bit()?;
        let stale_clocks = if self.mode.is_timed() && h.stale_periods > 0.0 {
            tb.cycles_at_least_ns(h.stale_periods * 1e9 / self.refresh_hz())
        } else {
            0
        };
        let cfg = HostConfig {
            mode: self.mode,
            bits: e.bits,
            gray: e.code == OutputCode::Gray,
            parity: self.parity,
            tag_address: e.answer_tag == super::frames::AnswerTag::Address,
            zero_answer: e.answer_zeroing,
            clocks_per_bit: c,
            gap_clocks: (h.gap_bits * c as f64).round() as u64,
            stale_clocks,
            timeout_clocks: tb.cycles_at_least_ns(h.timeout_us * 1e3),
            trigger_low_clocks: tb.cycles_at_least_ns(h.trigger_low_us * 1e3),
            clr_low_clocks: tb.cycles_at_least_ns(h.clr_low_us * 1e3),
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// Encoder `i`'s configuration in cycles.
    pub fn encoder_config(&self, i: usize) -> Result<EncoderConfig> {
        let tb = self.timebase()?;
        let e = &self.encoders[i];
        e.validate(self.mode, self.baud, self.parity)
            .map_err(|err| prefix(err, i))?;
        Ok(EncoderConfig {
            mode: self.mode,
            parity: self.parity,
            period_ps: tb.period_ps(),
            baud: self.baud,
            clocks_per_bit: self.clocks_per_bit()?,
            refresh_clocks: tb.cycles_nearest_ns(1e9 / e.refresh_hz.max(1.0)),
            acquisition_clocks: tb.cycles_nearest_ns(e.acquisition_us * 1e3),
            trigger_min_low: tb.cycles_at_least_ns(e.trigger_min_low_us * 1e3),
            clr_min_low: tb.cycles_at_least_ns(e.clr_min_low_us * 1e3),
            answer_delay: tb.cycles_nearest_ns(e.answer_delay_us * 1e3),
            command_gap: (e.command_gap_bits * self.clocks_per_bit()? as f64).round() as u64,
            settings: e.clone(),
        })
    }

    /// The operations with their repeats written out.
    pub fn expanded_ops(&self) -> Vec<Operation> {
        self.ops
            .iter()
            .flat_map(|op| {
                std::iter::repeat_n(
                    Operation {
                        repeat: 1,
                        ..op.clone()
                    },
                    op.repeat as usize,
                )
            })
            .collect()
    }

    fn check(&self) -> Result<()> {
        self.cable.validate("cable")?;
        let max = if self.mode.is_bus() { 3 } else { 1 };
        if self.encoders.is_empty() || self.encoders.len() > max {
            return Err(ConfigError::invalid(
                "encoders",
                format!("{} encoders in mode {:?}", self.encoders.len(), self.mode),
                "give one encoder, or one to three in the bus modes (each its own address)",
            ));
        }
        for i in 0..self.encoders.len() {
            self.encoder_config(i)?;
            let e = &self.encoders[i];
            let first = &self.encoders[0];
            if e.bits != first.bits
                || e.code != first.code
                || e.answer_tag != first.answer_tag
                || e.answer_zeroing != first.answer_zeroing
            {
                return Err(ConfigError::invalid(
                    format!("encoders[{i}]"),
                    "resolution, code, answer tag or zeroing answer differs from encoders[0]",
                    "give every encoder on one host the same format",
                ));
            }
            if self.encoders[..i].iter().any(|o| o.address == e.address) {
                return Err(ConfigError::invalid(
                    format!("encoders[{i}].address"),
                    format!("address {} used twice", e.address),
                    "give each encoder on the bus its own address",
                ));
            }
        }
        self.host_config()?;
        if self.ops.is_empty() || self.ops.len() > 100_000 {
            return Err(ConfigError::invalid(
                "ops",
                format!("{} operations", self.ops.len()),
                "list 1 to 100 000 operations",
            ));
        }
        for (i, op) in self.ops.iter().enumerate() {
            let usable = match op.op {
                OpKind::Read => true,
                OpKind::Zero => self.mode.has_clr() || self.mode == Mode::BusClear,
            };
            if !usable
                || op.address > 15
                || !(0.0..1e8).contains(&op.gap_us)
                || !(1..=100_000).contains(&op.repeat)
            {
                return Err(ConfigError::invalid(
                    format!("ops[{i}]"),
                    format!("{:?} in mode {:?} (address {}, gap {} µs, repeat {})", op.op, self.mode, op.address, op.gap_us, op.repeat),
                    "zero needs a clear mode or bus_clear; address 0..15, gap_us ≥ 0, repeat 1 to 100 000",
                ));
            }
        }
        for (i, d) in self.second_drivers.iter().enumerate() {
            d.validate(i)?;
        }
        Ok(())
    }
}

/// Renames `encoder.x` to `encoders[i].x` in an encoder's error.
fn prefix(err: ConfigError, i: usize) -> ConfigError {
    let ConfigError::Invalid {
        field,
        problem,
        fix,
    } = err;
    ConfigError::invalid(
        field.replacen("encoder.", &format!("encoders[{i}]."), 1),
        problem,
        fix,
    )
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
        let h = self.host_config()?;
        Ok(vec![
            ("MODE", h.mode.code()),
            ("BITS", h.bits as u64),
            ("GRAY", h.gray as u64),
            ("PARITY", h.parity.code()),
            ("TAG_ADDRESS", h.tag_address as u64),
            ("ZERO_ANSWER", h.zero_answer as u64),
            ("CLOCKS_PER_BIT", h.clocks_per_bit),
            ("GAP_CLOCKS", h.gap_clocks),
            ("STALE_CLOCKS", h.stale_clocks),
            ("TIMEOUT_CLOCKS", h.timeout_clocks),
            ("TRIGGER_LOW_CLOCKS", h.trigger_low_clocks),
            ("CLR_LOW_CLOCKS", h.clr_low_clocks),
        ])
    }

    fn bench(&self) -> Result<Bench> {
        Bench::new(self)
    }
}

/// One host operation as the transcript reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based operation number.
    pub index: usize,
    /// `read` or `zero`.
    pub op: OpKind,
    /// Bus address.
    pub address: u8,
    /// Cycle the operation began.
    pub start_cycle: u64,
    /// Cycle it ended (`o_done`, or the end of the listening window).
    pub done_cycle: u64,
    /// The position the operation ended with (`o_valid` with `o_done`).
    pub position: Option<u32>,
    /// Every position the host accepted from the operation's start to the
    /// next operation's (frames between operations included).
    pub positions: Vec<u32>,
    /// Their angles, `360° × a / 2^n` cut to four decimals.
    pub angles_deg: Vec<f64>,
    /// Every error pulse in the window, in order: `checksum`, `parity`,
    /// `frame`, `address`, `timeout`, `stale`.
    pub errors: Vec<&'static str>,
    /// The host's commands as on the wire at its pins (one list per
    /// command; one empty list for an operation that sends none).
    pub wire_requests: Vec<Vec<u8>>,
    /// Every character on the wire at the host after each command (or from
    /// the operation's start), up to the next operation, as received.
    pub wire_answers: Vec<Vec<u8>>,
    /// The frames the encoders meant to send in the window (before faults).
    pub encoder_frames: Vec<Vec<u8>>,
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.start_cycle, self.done_cycle)
    }
}

/// Host, cable and encoders.
pub struct Bench {
    cfg: BenchConfig,
    ops: Vec<Operation>,
    host: Host,
    encoders: Vec<Encoder>,
    line: HalfDuplexLine,
    trigger_line: DelayLine,
    clr_line: DelayLine,
    drivers: Vec<(u64, Vec<bool>)>,
    wire_tap: uart::WireTap,
    at_host: bool,
    encoder_drive: Drive,
    /// Encoders driving in the last step.
    encoders_on: usize,
    encoder_contention: u64,
    fault_contention: u64,
    next_op: usize,
    start_at: u64,
    last_out: Out,
    cycle: u64,
    end: Option<u64>,
    open: Option<Transaction>,
    transactions: Vec<Transaction>,
    tb: Timebase,
    layout: Layout,
}

impl Bench {
    /// A bench in its reset state.
    pub fn new(cfg: &BenchConfig) -> Result<Self> {
        cfg.check()?;
        let tb = cfg.timebase()?;
        let c = cfg.clocks_per_bit()?;
        let delay = cfg.cable.delay_cycles(&tb);
        let layout = Layout {
            inputs: Host::input_ports(),
            outputs: Host::output_ports(),
            line: vec![
                Port::new("tx_en_host", 1),
                Port::new("tx_en_encoder", 1),
                Port::new("line_at_host", 1),
                Port::new("line_at_encoder", 1),
                Port::new("trigger_at_encoder", 1),
                Port::new("clr_at_encoder", 1),
            ],
            decoded: vec![
                Port::new("state", 3),
                Port::new("count", 4),
                Port::new("synced", 1),
            ],
        };
        let encoders = (0..cfg.encoders.len())
            .map(|i| Encoder::new(cfg.encoder_config(i)?))
            .collect::<Result<Vec<_>>>()?;
        let drivers = cfg
            .second_drivers
            .iter()
            .map(|d| d.cycle_levels(&tb, cfg.parity, c))
            .collect();
        Ok(Bench {
            host: Host::new(cfg.host_config()?)?,
            encoders,
            line: HalfDuplexLine::new(delay, true),
            trigger_line: DelayLine::new(delay, true),
            clr_line: DelayLine::new(delay, true),
            drivers,
            wire_tap: uart::WireTap::with_parity(c, cfg.parity)?,
            at_host: true,
            encoder_drive: Drive::default(),
            encoders_on: 0,
            encoder_contention: 0,
            fault_contention: 0,
            next_op: 0,
            start_at: tb.cycles_at_least_ns(cfg.ops[0].gap_us * 1e3),
            ops: cfg.expanded_ops(),
            last_out: Out::default(),
            cycle: 0,
            end: None,
            open: None,
            transactions: Vec::new(),
            tb,
            layout,
            cfg: cfg.clone(),
        })
    }

    /// Cycles the host and an encoder (or two encoders) drove together.
    pub fn contention_cycles(&self) -> u64 {
        self.line.contention_cycles() + self.encoder_contention
    }

    /// Cycles a second driver overlapped the host or an encoder.
    pub fn fault_contention_cycles(&self) -> u64 {
        self.fault_contention
    }

    /// The emulators.
    pub fn encoders(&self) -> &[Encoder] {
        &self.encoders
    }

    fn open_transaction(&mut self) {
        let op = self.ops[self.next_op].clone();
        let sends =
            self.cfg.mode.is_bus() && (op.op == OpKind::Read || self.cfg.mode == Mode::BusClear);
        self.open = Some(Transaction {
            index: self.next_op,
            op: op.op,
            address: op.address,
            start_cycle: self.cycle,
            done_cycle: 0,
            position: None,
            positions: Vec::new(),
            angles_deg: Vec::new(),
            errors: Vec::new(),
            wire_requests: if sends { Vec::new() } else { vec![Vec::new()] },
            wire_answers: if sends { Vec::new() } else { vec![Vec::new()] },
            encoder_frames: Vec::new(),
        });
    }

    fn close_transaction(&mut self, out: &Out) {
        if let Some(mut t) = self.open.take() {
            t.done_cycle = self.cycle;
            if out.o_valid {
                t.position = Some(out.o_position);
            }
            let sent: Vec<&SentFrame> = self
                .encoders
                .iter()
                .flat_map(|e| e.sent().iter())
                .filter(|f| f.cycle >= t.start_cycle && f.cycle <= t.done_cycle)
                .collect();
            t.encoder_frames = sent.iter().map(|f| f.bytes.clone()).collect();
            self.transactions.push(t);
        }
        self.next_op += 1;
        if self.next_op == self.ops.len() {
            self.end = Some(self.cycle + 16);
        } else {
            self.start_at = self.cycle
                + self
                    .tb
                    .cycles_at_least_ns(self.ops[self.next_op].gap_us * 1e3);
        }
    }
}

impl Testbench for Bench {
    crate::compiled_here!();

    type Transaction = Transaction;

    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn step(&mut self, sample: Option<&mut Sample>) {
        let mut input = In {
            i_rx: self.at_host,
            ..In::default()
        };
        if self.open.is_none()
            && self.end.is_none()
            && self.cycle >= self.start_at
            && !self.last_out.o_busy
        {
            let op = self.ops[self.next_op].clone();
            input.i_start = op.op == OpKind::Read;
            input.i_zero = op.op == OpKind::Zero;
            input.i_address = op.address;
            self.open_transaction();
        }
        let out = self.host.step(&input);
        let host_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        {
            let t = self.open.as_mut().or(self.transactions.last_mut());
            self.wire_tap.step(
                input.i_rx,
                out.o_tx_en,
                t.map(|t| (&mut t.wire_requests, &mut t.wire_answers)),
            );
        }
        let (mut at_host, mut at_encoder) = self.line.step(host_drive, self.encoder_drive);
        let now = self.cycle;
        for (from, levels) in &self.drivers {
            if (*from..*from + levels.len() as u64).contains(&now) {
                let level = levels[(now - from) as usize];
                at_host.level = level;
                at_encoder.level = level;
                if host_drive.enable || self.encoder_drive.enable {
                    self.fault_contention += 1;
                }
            }
        }
        let trigger = self.trigger_line.step(out.o_trigger);
        let clr = self.clr_line.step(out.o_clr);
        let enc_in = EncoderIn {
            rx: at_encoder.level,
            trigger,
            clr,
        };
        let drives: Vec<Drive> = self.encoders.iter_mut().map(|e| e.step(&enc_in)).collect();
        let on: Vec<&Drive> = drives.iter().filter(|d| d.enable).collect();
        if on.len() > 1 {
            self.encoder_contention += 1;
        }
        self.encoders_on = on.len();
        self.encoder_drive = on.first().map_or(
            Drive {
                enable: false,
                level: true,
            },
            |d| **d,
        );
        self.at_host = at_host.level;
        if let Some(t) = self.open.as_mut().or(self.transactions.last_mut()) {
            if out.o_valid {
                t.positions.push(out.o_position);
                t.angles_deg
                    .push(angle_deg(out.o_position as u64, self.cfg.encoders[0].bits));
            }
            for (flag, name) in [
                (out.o_err_checksum, "checksum"),
                (out.o_err_parity, "parity"),
                (out.o_err_frame, "frame"),
                (out.o_err_address, "address"),
                (out.o_err_timeout, "timeout"),
                (out.o_err_stale, "stale"),
            ] {
                if flag {
                    t.errors.push(name);
                }
            }
        }
        if out.o_done && self.open.is_some() {
            self.close_transaction(&out);
        }
        self.last_out = out;
        self.cycle += 1;
        let Some(sample) = sample else { return };
        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        sample.line.copy_from_slice(&[
            host_drive.enable as u64,
            self.encoder_drive.enable as u64,
            at_host.level as u64,
            at_encoder.level as u64,
            trigger as u64,
            clr as u64,
        ]);
        sample.decoded.copy_from_slice(&[
            self.host.state() as u64,
            self.host.count() as u64,
            self.host.synced() as u64,
        ]);
    }

    fn finished(&self) -> bool {
        self.end.is_some_and(|e| self.cycle >= e)
    }

    fn quiet_cycles(&self) -> u64 {
        let c = self.cycle;
        // The cycle after a start shows its pulse falling.
        let just_started = self.open.as_ref().is_some_and(|t| t.start_cycle + 1 == c);
        let q = uart::bench_quiet(
            c,
            self.end,
            self.open.is_some() || self.last_out.o_busy,
            self.start_at,
            just_started,
            &self.drivers,
        );
        if q == 0 {
            return 0;
        }
        let out = &self.last_out;
        let input = In {
            i_rx: self.at_host,
            ..In::default()
        };
        let host_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        let (near, far) = self.line.sensed(host_drive, self.encoder_drive);
        // The level a second driver left at the near end gives way to the line's.
        if near.level != self.at_host {
            return 0;
        }
        let at_encoder = far.level;
        let enc_in = EncoderIn {
            rx: at_encoder,
            trigger: self.trigger_line.output(),
            clr: self.clr_line.output(),
        };
        let encoders = self
            .encoders
            .iter()
            .map(|e| e.quiet(&enc_in))
            .min()
            .unwrap_or(u64::MAX);
        q.min(self.host.quiet(&input))
            .min(self.wire_tap.quiet(input.i_rx, out.o_tx_en))
            .min(self.line.quiet(host_drive, self.encoder_drive))
            .min(self.trigger_line.quiet(out.o_trigger))
            .min(self.clr_line.quiet(out.o_clr))
            .min(encoders)
    }

    fn skip(&mut self, n: u64) {
        let out = self.last_out;
        let host_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        self.host.skip(n);
        self.wire_tap.skip(n);
        self.line.skip(n, host_drive, self.encoder_drive);
        self.trigger_line.skip(n);
        self.clr_line.skip(n);
        for e in &mut self.encoders {
            e.skip(n);
        }
        if self.encoders_on > 1 {
            self.encoder_contention += n;
        }
        self.cycle += n;
    }

    fn cycle(&self) -> u64 {
        self.cycle
    }

    fn into_transactions(self) -> Vec<Transaction> {
        self.transactions
    }
}
