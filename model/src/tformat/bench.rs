//! Host, half-duplex RS-485 pair and encoder, stepped together, with a host
//! script of operations. Implements [`Setup`]/[`Testbench`] so that `tbgen`
//! can drive it as soon as the `tformat_host` core exists.

use serde::{Deserialize, Serialize};

use super::encoder::{Encoder, EncoderConfig, EncoderSettings};
use super::frames::DataId;
use super::host::{Host, HostConfig, In, Out};
use crate::line::{CableConfig, Drive, HalfDuplexLine};
use crate::ports::{Port, Ports};
use crate::testbench::{self, Setup, Testbench};
use crate::trace::{Layout, Sample};
use crate::uart;
use crate::{ConfigError, Result, Timebase};

/// The host's settings in a scenario's units (`[tformat.host]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HostSettings {
    /// Answer timeout after the request, µs.
    pub timeout_us: f64,
    /// Interval between the ten reset requests, µs (seed: ≥ 40 ms).
    pub repeat_gap_us: f64,
}

impl Default for HostSettings {
    fn default() -> Self {
        HostSettings {
            timeout_us: 10.0,
            repeat_gap_us: 40_000.0,
        }
    }
}

/// One host operation (`[[tformat.ops]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Operation {
    /// The Data ID code: 0, 1, 2, 3, 6, 7, 8, 0xC or 0xD (others are sent as
    /// asked, to see the encoder's Table 5 answer).
    pub data_id: u8,
    /// EEPROM address (6, D).
    #[serde(default)]
    pub address: u8,
    /// EEPROM data (6).
    #[serde(default)]
    pub data: u8,
    /// Idle time before the operation, µs.
    #[serde(default = "default_gap")]
    pub gap_us: f64,
}

fn default_gap() -> f64 {
    5.0
}

/// A fault on the RS-485 pair (`[[tformat.line_faults]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LineFault {
    /// What happens: `stuck_low` or `stuck_high` (a shorted pair, a failed
    /// transceiver), or `second_driver` (another device sends `bytes`).
    pub kind: LineFaultKind,
    /// Start, µs after reset.
    pub at_us: f64,
    /// How long a stuck line lasts, µs (a second driver lasts its bytes).
    #[serde(default)]
    pub width_us: f64,
    /// What a second driver sends, as 10-bit fields at the nominal rate.
    #[serde(default)]
    pub bytes: Vec<u8>,
}

/// The kinds of [`LineFault`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum LineFaultKind {
    /// The pair reads low at both ends.
    StuckLow,
    /// The pair reads high at both ends.
    StuckHigh,
    /// A third device drives; both receivers hear it (it is assumed the
    /// stronger driver), and the cycles it overlaps host or encoder count as
    /// contention.
    SecondDriver,
}

/// Everything a scenario says about a T-format set-up (`[tformat]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock in MHz.
    pub f_sys_mhz: f64,
    /// Bit rate in bit/s (seed: 2.5 Mbps).
    pub baud: f64,
    /// The host.
    pub host: HostSettings,
    /// The encoder.
    pub encoder: EncoderSettings,
    /// The cable.
    pub cable: CableConfig,
    /// What the host does, in order.
    pub ops: Vec<Operation>,
    /// Faults on the pair.
    pub line_faults: Vec<LineFault>,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 80.0,
            baud: 2.5e6,
            host: HostSettings::default(),
            encoder: EncoderSettings::default(),
            cable: CableConfig {
                length_m: 10.0,
                ..CableConfig::default()
            },
            ops: vec![Operation {
                data_id: 0,
                address: 0,
                data: 0,
                gap_us: 5.0,
            }],
            line_faults: Vec::new(),
        }
    }
}

impl BenchConfig {
    fn clocks_per_bit(&self) -> Result<u64> {
        let tb = self.timebase()?;
        let ratio = tb.f_sys_hz() as f64 / self.baud;
        if !(ratio.is_finite() && (ratio - ratio.round()).abs() < 1e-6) {
            return Err(ConfigError::invalid(
                "baud",
                format!("f_sys / baud = {ratio}"),
                "use a baud rate that divides f_sys (2.5 Mbps at 100 MHz)",
            ));
        }
        Ok(ratio.round() as u64)
    }

    /// The host's configuration in cycles (the Verilog parameters).
    pub fn host_config(&self) -> Result<HostConfig> {
        let tb = self.timebase()?;
        for (f, v) in [
            ("host.timeout_us", self.host.timeout_us),
            ("host.repeat_gap_us", self.host.repeat_gap_us),
        ] {
            if !(v > 0.0 && v < 1e7) {
                return Err(ConfigError::invalid(
                    f,
                    format!("{v}"),
                    "give a positive time in µs",
                ));
            }
        }
        let cfg = HostConfig {
            clocks_per_bit: self.clocks_per_bit()?,
            timeout_clocks: tb.cycles_at_least_ns(self.host.timeout_us * 1e3),
            repeat_gap_clocks: tb.cycles_at_least_ns(self.host.repeat_gap_us * 1e3),
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// The encoder's configuration in cycles.
    pub fn encoder_config(&self) -> Result<EncoderConfig> {
        let tb = self.timebase()?;
        let clocks_per_bit = self.clocks_per_bit()?;
        let e = &self.encoder;
        for (f, v) in [
            ("encoder.answer_delay_us", e.answer_delay_us),
            ("encoder.eeprom_write_us", e.eeprom_write_us),
            ("encoder.reset_interval_us", e.reset_interval_us),
        ] {
            if !(0.0..1e7).contains(&v) {
                return Err(ConfigError::invalid(
                    f,
                    format!("{v}"),
                    "give a non-negative time in µs",
                ));
            }
        }
        if !(-10.0..=10.0).contains(&e.baud_error_percent) {
            return Err(ConfigError::invalid(
                "encoder.baud_error_percent",
                format!("{}", e.baud_error_percent),
                "give the answer's bit rate error within ±10 %",
            ));
        }
        let quarter_bit_ns = 1e9 / self.baud / 4.0;
        if !(0.0..=quarter_bit_ns).contains(&e.jitter_ns) {
            return Err(ConfigError::invalid(
                "encoder.jitter_ns",
                format!("{} ns", e.jitter_ns),
                format!("give a jitter from 0 to a quarter bit ({quarter_bit_ns} ns)"),
            ));
        }
        Ok(EncoderConfig {
            clocks_per_bit,
            answer_bit_clocks: clocks_per_bit as f64 / (1.0 + e.baud_error_percent / 100.0),
            jitter_clocks: e.jitter_ns * 1e3 / tb.period_ps() as f64,
            answer_delay: tb.cycles_nearest_ns(e.answer_delay_us * 1e3),
            eeprom_write: tb.cycles_at_least_ns(e.eeprom_write_us * 1e3),
            reset_interval: tb.cycles_at_least_ns(e.reset_interval_us * 1e3),
            settings: e.clone(),
        })
    }

    fn check(&self) -> Result<()> {
        self.cable.validate("cable")?;
        self.host_config()?;
        self.encoder_config()?;
        if self.ops.is_empty() || self.ops.len() > 100_000 {
            return Err(ConfigError::invalid(
                "ops",
                format!("{} operations", self.ops.len()),
                "list 1 to 100 000 operations",
            ));
        }
        for (i, f) in self.encoder.flips.iter().enumerate() {
            if f.bit > 9 || f.field >= 11 {
                return Err(ConfigError::invalid(
                    format!("encoder.flips[{i}]"),
                    "field above 10 or bit above 9",
                    "give field 0..10 and bit 0..9 (0 start, 1..8 data, 9 delimiter)",
                ));
            }
        }
        for (i, f) in self.line_faults.iter().enumerate() {
            let stuck = f.kind != LineFaultKind::SecondDriver;
            if !(0.0..1e7).contains(&f.at_us)
                || !(0.0..1e7).contains(&f.width_us)
                || (stuck && f.width_us <= 0.0)
                || (!stuck && !(1..=1000).contains(&f.bytes.len()))
            {
                return Err(ConfigError::invalid(
                    format!("line_faults[{i}]"),
                    "bad time, width or bytes",
                    "give at_us ≥ 0; a stuck line a positive width_us; a second driver 1 to 1000 bytes",
                ));
            }
        }
        if let Some(t) = &self.encoder.truncate {
            if t.bits == 0 || t.bits > 110 {
                return Err(ConfigError::invalid(
                    "encoder.truncate.bits",
                    format!("{}", t.bits),
                    "give 1 to 110 bits (an answer has at most 11 fields of 10)",
                ));
            }
        }
        for (i, op) in self.ops.iter().enumerate() {
            if op.data_id > 0xF {
                return Err(ConfigError::invalid(
                    format!("ops[{i}].data_id"),
                    format!("{:#X} is above 0xF", op.data_id),
                    "give a Data ID from 0 to 0xF",
                ));
            }
            if op.address > 0x7F {
                return Err(ConfigError::invalid(
                    format!("ops[{i}].address"),
                    format!("{} is above 127", op.address),
                    "give an EEPROM address from 0 to 127",
                ));
            }
            if !(0.0..1e7).contains(&op.gap_us) {
                return Err(ConfigError::invalid(
                    format!("ops[{i}].gap_us"),
                    format!("{} µs", op.gap_us),
                    "give a gap from 0 to 10 s in µs",
                ));
            }
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
        let h = self.host_config()?;
        Ok(vec![
            ("CLOCKS_PER_BIT", h.clocks_per_bit),
            ("TIMEOUT_CLOCKS", h.timeout_clocks),
            ("REPEAT_GAP_CLOCKS", h.repeat_gap_clocks),
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
    /// Cycle of the start pulse.
    pub start_cycle: u64,
    /// Cycle of `o_done`.
    pub done_cycle: u64,
    /// The Data ID code asked for.
    pub data_id: u8,
    /// The request fields the host sent (the last of them, for a reset sent ten times).
    pub sent: Vec<u8>,
    /// The answer fields the host received (the last answer, for a reset).
    pub received: Vec<u8>,
    /// Every request frame set the host drove (ten for a reset), as the
    /// characters on the line at the host's pins while its driver was on,
    /// read by a receiver that is never deaf: the request the host sent,
    /// unless another driver overrode it. What an independent decoder of the
    /// line must find.
    pub wire_requests: Vec<Vec<u8>>,
    /// For each of `wire_requests`, every character on the line at the
    /// host's pins after it up to the next request (or the end of the run),
    /// as received, a low stop bit included (the value is what the data
    /// samples read): the answer, the rest of an answer whose framing the
    /// host lost, anything another driver sent.
    pub wire_answers: Vec<Vec<u8>>,
    /// Decoded single-turn data (17 bits).
    pub abs: u32,
    /// Decoded multi-turn data (16 bits).
    pub abm: u16,
    /// Decoded status field.
    pub sf: u8,
    /// Decoded ENID.
    pub enid: u8,
    /// Decoded ALMC.
    pub almc: u8,
    /// Decoded EEPROM fields (ADF with its busy bit, EDF).
    pub adf: u8,
    /// EEPROM data field.
    pub edf: u8,
    /// What the host flagged: `crc`, `timeout`, `frame`, `cf_mismatch`, `comm_alarm`.
    pub errors: Vec<&'static str>,
    /// The encoder's single-turn and multi-turn values when the answer was sent.
    pub encoder_position: (u32, u16),
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.start_cycle, self.done_cycle)
    }
}

/// Host, line and encoder.
pub struct Bench {
    cfg: BenchConfig,
    host: Host,
    encoder: Encoder,
    line: HalfDuplexLine,
    /// The faults as cycle windows: (first cycle, end cycle, kind, levels of a second driver per cycle offset).
    faults: Vec<FaultWindow>,
    fault_contention: u64,
    /// A receiver on the line at the host's pins that listens all the time
    /// (the host's own is deaf while it drives): the wire bytes of the
    /// transcript.
    /// Every character on the wire at the host, for the transcript.
    wire_tap: uart::WireTap,
    at_host: bool,
    encoder_drive: Drive,
    next_op: usize,
    start_at: u64,
    waiting: bool,
    last_in: In,
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
        let layout = Layout {
            inputs: Host::input_ports(),
            outputs: Host::output_ports(),
            line: vec![
                Port::new("tx_en_host", 1),
                Port::new("tx_en_encoder", 1),
                Port::new("line_at_host", 1),
                Port::new("line_at_encoder", 1),
            ],
            decoded: vec![Port::new("state", 3)],
        };
        Ok(Bench {
            host: Host::new(cfg.host_config()?)?,
            encoder: Encoder::new(cfg.encoder_config()?),
            line: HalfDuplexLine::new(cfg.cable.delay_cycles(&tb), true),
            faults: fault_windows(cfg, &tb)?,
            fault_contention: 0,
            wire_tap: uart::WireTap::new(cfg.clocks_per_bit()?)?,
            at_host: true,
            encoder_drive: Drive::default(),
            next_op: 0,
            start_at: tb.cycles_at_least_ns(cfg.ops[0].gap_us * 1e3),
            waiting: false,
            last_in: In {
                i_rx: true,
                ..In::default()
            },
            last_out: Out {
                o_tx: true,
                ..Out::default()
            },
            cycle: 0,
            end: None,
            open: None,
            transactions: Vec::new(),
            tb,
            layout,
            cfg: cfg.clone(),
        })
    }

    /// Cycles the RS-485 pair had two drivers on (host and encoder).
    pub fn contention_cycles(&self) -> u64 {
        self.line.contention_cycles()
    }

    /// Cycles a second driver overlapped the host's or the encoder's driver.
    pub fn fault_contention_cycles(&self) -> u64 {
        self.fault_contention
    }

    /// The level a line fault forces this cycle, if any.
    fn forced_level(&mut self, host_drives: bool) -> Option<bool> {
        let now = self.cycle;
        let (from, _, kind, levels) = self
            .faults
            .iter()
            .find(|(from, to, _, _)| (*from..*to).contains(&now))?;
        let level = match kind {
            LineFaultKind::StuckLow => false,
            LineFaultKind::StuckHigh => true,
            LineFaultKind::SecondDriver => levels[(now - from) as usize],
        };
        if *kind == LineFaultKind::SecondDriver && (host_drives || self.encoder_drive.enable) {
            self.fault_contention += 1;
        }
        Some(level)
    }

    /// Feeds the always-listening receiver the host's input and files each
    /// character it completes: a request character if it began while the
    /// host drove, else an answer character of the latest request.
    fn record_wire(&mut self, line: bool, out: &Out) {
        let latest = match self.open.as_mut() {
            Some(t) => Some(t),
            None => self.transactions.last_mut(),
        };
        self.wire_tap.step(
            line,
            out.o_tx_en,
            latest.map(|t| (&mut t.wire_requests, &mut t.wire_answers)),
        );
    }

    /// The encoder emulator (for tests that look inside it).
    pub fn encoder(&self) -> &Encoder {
        &self.encoder
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
        if !self.waiting
            && self.end.is_none()
            && self.cycle >= self.start_at
            && !self.last_out.o_busy
        {
            let op = &self.cfg.ops[self.next_op];
            input = In {
                i_start: true,
                i_data_id: op.data_id,
                i_address: op.address,
                i_wdata: op.data,
                i_rx: self.at_host,
            };
            let sent = match DataId::from_code(op.data_id) {
                Some(id) => super::frames::request(id, op.address, op.data),
                None => vec![super::frames::control_field_for_code(op.data_id)],
            };
            self.open = Some(Transaction {
                index: self.next_op,
                start_cycle: self.cycle,
                done_cycle: 0,
                data_id: op.data_id,
                sent,
                received: Vec::new(),
                wire_requests: Vec::new(),
                wire_answers: Vec::new(),
                abs: 0,
                abm: 0,
                sf: 0,
                enid: 0,
                almc: 0,
                adf: 0,
                edf: 0,
                errors: Vec::new(),
                encoder_position: (0, 0),
            });
            self.waiting = true;
        }
        let out = self.host.step(&input);
        let host_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        self.record_wire(input.i_rx, &out);
        let (mut at_host, mut at_encoder) = self.line.step(host_drive, self.encoder_drive);
        if let Some(level) = self.forced_level(host_drive.enable) {
            at_host.level = level;
            at_encoder.level = level;
        }
        self.encoder_drive = self.encoder.step(at_encoder.level);
        self.at_host = at_host.level;
        if out.o_done {
            if let Some(mut t) = self.open.take() {
                t.done_cycle = self.cycle;
                t.received = self.host.fields().to_vec();
                t.abs = out.o_abs;
                t.abm = out.o_abm;
                t.sf = out.o_sf;
                t.enid = out.o_enid;
                t.almc = out.o_almc;
                t.adf = out.o_adf;
                t.edf = out.o_edf;
                for (flag, name) in [
                    (out.o_err_crc, "crc"),
                    (out.o_err_timeout, "timeout"),
                    (out.o_err_frame, "frame"),
                    (out.o_err_cf, "cf_mismatch"),
                    (out.o_err_comm, "comm_alarm"),
                ] {
                    if flag {
                        t.errors.push(name);
                    }
                }
                t.encoder_position = (self.encoder.single_turn(), self.encoder.multi_turn());
                self.transactions.push(t);
            }
            self.waiting = false;
            self.next_op += 1;
            if self.next_op == self.cfg.ops.len() {
                self.end = Some(self.cycle + 16);
            } else {
                self.start_at = self.cycle
                    + self
                        .tb
                        .cycles_at_least_ns(self.cfg.ops[self.next_op].gap_us * 1e3);
            }
        }
        self.last_in = input;
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
        ]);
        sample.decoded[0] = self.host.state() as u64;
    }

    fn finished(&self) -> bool {
        self.end.is_some_and(|e| self.cycle >= e)
    }

    fn quiet_cycles(&self) -> u64 {
        let host = match self.end {
            Some(end) => end.saturating_sub(self.cycle),
            None if self.waiting => u64::MAX,
            None if self.cycle < self.start_at => self.start_at - self.cycle,
            None if self.last_out.o_busy => u64::MAX,
            None => 0,
        };
        let input = In {
            i_rx: self.at_host,
            ..In::default()
        };
        // The cycle after a start shows its pulse falling.
        if host == 0 || input != self.last_in {
            return 0;
        }
        // Not across the start or end of a line fault, nor within a second
        // driver's (its level changes by the cycle), nor on the cycle after
        // one of them.
        let mut faults = u64::MAX;
        for &(from, to, kind, _) in &self.faults {
            if self.cycle < from {
                faults = faults.min(from - self.cycle);
            } else if self.cycle == from || self.cycle == to {
                faults = 0; // the forcing starts or ends: the line changes
            } else if self.cycle < to {
                faults = faults.min(if kind == LineFaultKind::SecondDriver {
                    0
                } else {
                    to - self.cycle
                });
            }
        }
        let out = &self.last_out;
        let host_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        host.min(faults)
            .min(self.host.quiet(&input))
            .min(self.wire_tap.quiet(input.i_rx, out.o_tx_en))
            .min(self.line.quiet(host_drive, self.encoder_drive))
            .min(self.encoder.quiet())
    }

    fn skip(&mut self, n: u64) {
        let out = self.last_out;
        self.host.skip(n);
        self.wire_tap.skip(n);
        self.line.skip(
            n,
            Drive {
                enable: out.o_tx_en,
                level: out.o_tx,
            },
            self.encoder_drive,
        );
        self.encoder.skip(n);
        self.cycle += n;
    }

    fn cycle(&self) -> u64 {
        self.cycle
    }

    fn into_transactions(self) -> Vec<Transaction> {
        self.transactions
    }
}

/// A line fault as a cycle window: its first cycle, the cycle after its
/// last, its kind, and a second driver's levels cycle by cycle (read only
/// for a second driver).
type FaultWindow = (u64, u64, LineFaultKind, Vec<bool>);

/// The line faults as cycle windows.
fn fault_windows(cfg: &BenchConfig, tb: &Timebase) -> Result<Vec<FaultWindow>> {
    let c = cfg.clocks_per_bit()?;
    Ok(cfg
        .line_faults
        .iter()
        .map(|f| {
            let from = tb.cycles_nearest_ns(f.at_us * 1e3);
            let levels: Vec<bool> = f
                .bytes
                .iter()
                .flat_map(|&b| super::encoder::frame_bits(b))
                .flat_map(|bit| std::iter::repeat_n(bit, c as usize))
                .collect();
            let len = if f.kind == LineFaultKind::SecondDriver {
                levels.len() as u64
            } else {
                tb.cycles_nearest_ns(f.width_us * 1e3).max(1)
            };
            (from, from + len, f.kind, levels)
        })
        .collect())
}
