//! Host, half-duplex RS-485 bus and one or more encoders (a daisy chain),
//! stepped together, with a host script of operations and line faults.
//! Implements [`Setup`]/[`Testbench`] for `tbgen` (core `esl_host`).

use serde::{Deserialize, Serialize};

use super::encoder::{Encoder, EncoderConfig, EncoderSettings};
use super::frames::{self, DataId};
use super::host::{Host, HostConfig, In, Out};
use crate::line::{CableConfig, Drive, HalfDuplexLine};
use crate::ports::{Port, Ports};
use crate::testbench::{self, Setup, Testbench};
use crate::trace::{Layout, Sample};
use crate::uart;
use crate::{ConfigError, Result, Timebase};

/// The host's settings in a scenario's units (`[esl.host]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HostSettings {
    /// Answer timeout after the request, µs (the answer comes 2 µs after it).
    pub timeout_us: f64,
    /// Interval between the 8 requests of B, C, D, µs (seed: typ. 40 µs).
    pub repeat_gap_us: f64,
    /// Wait before repeating a memory read answered busy, µs (seed: 200 µs).
    pub read_wait_us: f64,
    /// Wait after an accepted EEPROM write, µs (seed: 6 ms).
    pub write_wait_us: f64,
    /// Wait after a page change, µs (seed: 18 ms).
    pub page_wait_us: f64,
    /// Requests a memory access may take while busy.
    pub busy_tries: u64,
    /// Largest RS difference from channel 1, in RS LSBs.
    pub rs_tolerance: u64,
    /// The broadcast address (a chain that uses broadcast gives its encoders the others).
    pub broadcast_address: u8,
}

impl Default for HostSettings {
    fn default() -> Self {
        HostSettings {
            timeout_us: 5.0,
            repeat_gap_us: 40.0,
            read_wait_us: 200.0,
            write_wait_us: 6_000.0,
            page_wait_us: 18_000.0,
            busy_tries: 3,
            rs_tolerance: 1,
            broadcast_address: 7,
        }
    }
}

/// One host operation (`[[esl.ops]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Operation {
    /// The Data ID code (Table 3; others are sent as asked, to see that no
    /// encoder acknowledges them).
    pub data_id: u8,
    /// Encoder address 0..7.
    #[serde(default)]
    pub address: u8,
    /// Send to every encoder at the broadcast address (no answer expected).
    #[serde(default)]
    pub broadcast: bool,
    /// Memory address (E, F).
    #[serde(default)]
    pub mem_address: u8,
    /// Data to write (F).
    #[serde(default)]
    pub data: u8,
    /// Idle time before the operation, µs.
    #[serde(default = "default_gap")]
    pub gap_us: f64,
}

fn default_gap() -> f64 {
    2.0
}

/// One bit of one request inverted on the line at the encoders' end
/// (`[[esl.request_flips]]`): wrong parity, bad stop bit, CRC errors.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RequestFlip {
    /// Which request on the line (0 = the first the host sends).
    pub request: usize,
    /// Which field (0 = CF).
    pub field: usize,
    /// Which of its 10 bits: 0 start, 1..8 data, 9 stop.
    pub bit: u8,
}

/// A second driver that pulls the line low for a while (`[[esl.intruders]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Intruder {
    /// Start, µs after the start of the run.
    pub at_us: f64,
    /// Length, µs.
    pub length_us: f64,
}

/// Everything a scenario says about an ESL set-up (`[esl]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock in MHz.
    pub f_sys_mhz: f64,
    /// Bit rate in bit/s (seed: 10 Mbps).
    pub baud: f64,
    /// The host.
    pub host: HostSettings,
    /// The encoders on the bus (one: point to point).
    pub encoders: Vec<EncoderSettings>,
    /// The cable.
    pub cable: CableConfig,
    /// Faults: request bits inverted on the line.
    pub request_flips: Vec<RequestFlip>,
    /// Faults: a second driver on the line.
    pub intruders: Vec<Intruder>,
    /// What the host does, in order.
    pub ops: Vec<Operation>,
    /// The whole list of operations is run this many times (long benches).
    pub repeat_ops: usize,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 80.0,
            baud: 10e6,
            host: HostSettings::default(),
            encoders: vec![EncoderSettings::default()],
            cable: CableConfig {
                length_m: 10.0,
                ..CableConfig::default()
            },
            request_flips: Vec::new(),
            intruders: Vec::new(),
            ops: vec![Operation {
                data_id: 1,
                address: 0,
                broadcast: false,
                mem_address: 0,
                data: 0,
                gap_us: 2.0,
            }],
            repeat_ops: 1,
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
                "use a baud rate that divides f_sys (10 Mbps at 80 MHz)",
            ));
        }
        Ok(ratio.round() as u64)
    }

    /// The host's configuration in cycles (the Verilog parameters).
    pub fn host_config(&self) -> Result<HostConfig> {
        let tb = self.timebase()?;
        let h = &self.host;
        for (f, v) in [
            ("host.timeout_us", h.timeout_us),
            ("host.repeat_gap_us", h.repeat_gap_us),
            ("host.read_wait_us", h.read_wait_us),
            ("host.write_wait_us", h.write_wait_us),
            ("host.page_wait_us", h.page_wait_us),
        ] {
            if !(v > 0.0 && v < 1e6) {
                return Err(ConfigError::invalid(
                    f,
                    format!("{v}"),
                    "give a positive time in µs",
                ));
            }
        }
        let cfg = HostConfig {
            clocks_per_bit: self.clocks_per_bit()?,
            timeout_clocks: tb.cycles_at_least_ns(h.timeout_us * 1e3),
            repeat_gap_clocks: tb.cycles_at_least_ns(h.repeat_gap_us * 1e3),
            read_wait_clocks: tb.cycles_at_least_ns(h.read_wait_us * 1e3),
            write_wait_clocks: tb.cycles_at_least_ns(h.write_wait_us * 1e3),
            page_wait_clocks: tb.cycles_at_least_ns(h.page_wait_us * 1e3),
            busy_tries: h.busy_tries,
            rs_tolerance: h.rs_tolerance,
            broadcast_address: u64::from(h.broadcast_address),
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// The configuration in cycles of encoder `i`.
    pub fn encoder_config(&self, i: usize) -> Result<EncoderConfig> {
        let tb = self.timebase()?;
        let e = self.encoders.get(i).ok_or_else(|| {
            ConfigError::invalid(
                "encoders",
                "no such encoder",
                "list at least one [[esl.encoders]]",
            )
        })?;
        let p = format!("encoders[{i}]");
        for (f, v) in [
            ("answer_delay_us", e.answer_delay_us),
            ("eeprom_read_us", e.eeprom_read_us),
            ("eeprom_write_us", e.eeprom_write_us),
            ("page_change_us", e.page_change_us),
            ("repeat_window_us", e.repeat_window_us),
        ] {
            if !(0.0..1e6).contains(&v) {
                return Err(ConfigError::invalid(
                    format!("{p}.{f}"),
                    format!("{v}"),
                    "give a non-negative time in µs below 1 s",
                ));
            }
        }
        if !(-20.0..=20.0).contains(&e.baud_error_percent) {
            return Err(ConfigError::invalid(
                format!("{p}.baud_error_percent"),
                format!("{}", e.baud_error_percent),
                "give −20 to +20 %",
            ));
        }
        if e.address > 7 || e.enid_mt_bytes > 3 || e.single_turn > 0xFF_FFFF {
            return Err(ConfigError::invalid(
                p,
                "address above 7, enid_mt_bytes above 3 or single_turn above 24 bits",
                "give address 0..7, enid_mt_bytes 0..3, single_turn < 2^24",
            ));
        }
        for (k, m) in e.memory.iter().enumerate() {
            if m.page > 15 || usize::from(m.address) + m.data.len() > 0x7F {
                return Err(ConfigError::invalid(
                    format!("{p}.memory[{k}]"),
                    "page above 15 or data past address 0x7E",
                    "give page 0..15 and keep address + len(data) ≤ 0x7F",
                ));
            }
        }
        for (k, f) in e.flips.iter().enumerate() {
            if f.bit > 9 || f.field >= 18 {
                return Err(ConfigError::invalid(
                    format!("{p}.flips[{k}]"),
                    "field above 17 or bit above 9",
                    "give field 0..17 and bit 0..9 (0 start, 1..8 data, 9 stop)",
                ));
            }
        }
        for (k, j) in e.sequence_jumps.iter().enumerate() {
            if !(1..=2).contains(&j.channel) {
                return Err(ConfigError::invalid(
                    format!("{p}.sequence_jumps[{k}].channel"),
                    format!("{}", j.channel),
                    "give channel 1 or 2",
                ));
            }
        }
        let bit = tb.f_sys_hz() as f64 / self.baud;
        Ok(EncoderConfig {
            bit_cycles: bit / (1.0 + e.baud_error_percent / 100.0),
            answer_delay: tb.cycles_nearest_ns(e.answer_delay_us * 1e3),
            eeprom_read: tb.cycles_at_least_ns(e.eeprom_read_us * 1e3),
            eeprom_write: tb.cycles_at_least_ns(e.eeprom_write_us * 1e3),
            page_change: tb.cycles_at_least_ns(e.page_change_us * 1e3),
            repeat_window: tb.cycles_at_least_ns(e.repeat_window_us * 1e3),
            broadcast_address: Some(self.host.broadcast_address)
                .filter(|_| self.ops.iter().any(|o| o.broadcast)),
            settings: e.clone(),
        })
    }

    fn check(&self) -> Result<()> {
        self.cable.validate("cable")?;
        if self.repeat_ops == 0 || self.ops.len().saturating_mul(self.repeat_ops) > 1_000_000 {
            return Err(ConfigError::invalid(
                "repeat_ops",
                format!("{}", self.repeat_ops),
                "give 1 or more, at most 1 000 000 operations in all",
            ));
        }
        self.host_config()?;
        if self.encoders.is_empty() || self.encoders.len() > 8 {
            return Err(ConfigError::invalid(
                "encoders",
                format!("{} encoders", self.encoders.len()),
                "list 1 to 8 [[esl.encoders]]",
            ));
        }
        for i in 0..self.encoders.len() {
            self.encoder_config(i)?;
            if self.encoders[..i]
                .iter()
                .any(|e| e.address == self.encoders[i].address)
            {
                return Err(ConfigError::invalid(
                    format!("encoders[{i}].address"),
                    "used twice",
                    "give every encoder on the bus its own address",
                ));
            }
        }
        if self.ops.is_empty() || self.ops.len() > 100_000 {
            return Err(ConfigError::invalid(
                "ops",
                format!("{} operations", self.ops.len()),
                "list 1 to 100 000 operations",
            ));
        }
        for (i, op) in self.ops.iter().enumerate() {
            let range = [
                (
                    "data_id",
                    op.data_id as f64 > 15.0,
                    format!("{:#X} is above 0xF", op.data_id),
                    "give a Data ID from 0 to 0xF",
                ),
                (
                    "address",
                    op.address > 7,
                    format!("{} is above 7", op.address),
                    "give an encoder address from 0 to 7",
                ),
                (
                    "mem_address",
                    op.mem_address > 0x7F,
                    format!("{:#X} is above 0x7F", op.mem_address),
                    "give a memory address from 0 to 0x7F",
                ),
                (
                    "gap_us",
                    !(0.0..1e6).contains(&op.gap_us),
                    format!("{} µs", op.gap_us),
                    "give a gap from 0 to 1 s in µs",
                ),
            ];
            if let Some((field, _, problem, fix)) = range.into_iter().find(|r| r.1) {
                return Err(ConfigError::invalid(
                    format!("ops[{i}].{field}"),
                    problem,
                    fix,
                ));
            }
            if op.broadcast && DataId::from_code(op.data_id).is_some_and(|d| d.is_memory()) {
                return Err(ConfigError::invalid(
                    format!("ops[{i}].broadcast"),
                    "memory access in broadcast",
                    "seed 000: memory read and write only point to point; address one encoder",
                ));
            }
        }
        if self.ops.iter().any(|o| o.broadcast)
            && self
                .encoders
                .iter()
                .any(|e| e.address == self.host.broadcast_address)
        {
            return Err(ConfigError::invalid(
                "host.broadcast_address",
                "an encoder has this address",
                "keep the broadcast address free on a chain that uses broadcast",
            ));
        }
        for (i, f) in self.request_flips.iter().enumerate() {
            if f.bit > 9 || f.field > 3 {
                return Err(ConfigError::invalid(
                    format!("request_flips[{i}]"),
                    "field above 3 or bit above 9",
                    "give field 0..3 and bit 0..9",
                ));
            }
        }
        for (i, r) in self.intruders.iter().enumerate() {
            if !(r.at_us >= 0.0 && r.length_us > 0.0 && r.at_us + r.length_us < 1e6) {
                return Err(ConfigError::invalid(
                    format!("intruders[{i}]"),
                    "bad time",
                    "give at_us ≥ 0 and length_us > 0",
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
            ("READ_WAIT_CLOCKS", h.read_wait_clocks),
            ("WRITE_WAIT_CLOCKS", h.write_wait_clocks),
            ("PAGE_WAIT_CLOCKS", h.page_wait_clocks),
            ("BUSY_TRIES", h.busy_tries),
            ("RS_TOLERANCE", h.rs_tolerance),
            ("BROADCAST_ADDRESS", h.broadcast_address),
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
    /// The encoder address (the broadcast address for a broadcast).
    pub address: u8,
    /// Sent to every encoder.
    pub broadcast: bool,
    /// Requests this operation put on the line (8 for B, C, D; more for busy memory).
    pub requests: usize,
    /// The last request frame set the host sent.
    pub sent: Vec<u8>,
    /// The last answer frame set the host received.
    pub received: Vec<u8>,
    /// Every request frame set the host drove (8 for B, C, D; more for a
    /// busy memory access), as the characters on the line at the host's pins
    /// while its driver was on, read by a receiver that is never deaf: the
    /// request the host sent, with any bit a fault inverted. What an
    /// independent decoder of the line must find.
    pub wire_requests: Vec<Vec<u8>>,
    /// For each of `wire_requests`, every character on the line at the
    /// host's pins after it up to the next request (or the end of the run),
    /// as received, a low stop bit included (the value is what the data
    /// samples read): the answer, the rest of an answer whose framing the
    /// host lost, anything another driver sent.
    pub wire_answers: Vec<Vec<u8>>,
    /// CF1.
    pub cf: u8,
    /// SF1.
    pub sf: u8,
    /// SF2.
    pub sf2: u8,
    /// ALM1.
    pub alm1: u8,
    /// ALM2.
    pub alm2: u8,
    /// Single-turn.
    pub abs: u32,
    /// Multi-turn.
    pub abm: u16,
    /// Redundant single-turn (channel 2).
    pub rs: u16,
    /// SC1.
    pub sc1: u8,
    /// SC2.
    pub sc2: u8,
    /// ENID.
    pub enid: u8,
    /// Temperature (two's complement °C).
    pub temp: u8,
    /// ADF (busy in bit 0).
    pub adf: u8,
    /// EDF.
    pub edf: u8,
    /// What the host flagged: `crc1`, `crc2`, `timeout`, `frame`,
    /// `cf_mismatch`, `comm_alarm`, `sequence`, `channel_mismatch`, `busy`.
    pub errors: Vec<&'static str>,
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.start_cycle, self.done_cycle)
    }
}

/// The error names of the transcript, in the order of the host's error outputs.
pub fn error_names(out: &Out) -> Vec<&'static str> {
    [
        (out.o_err_crc1, "crc1"),
        (out.o_err_crc2, "crc2"),
        (out.o_err_timeout, "timeout"),
        (out.o_err_frame, "frame"),
        (out.o_err_cf, "cf_mismatch"),
        (out.o_err_comm, "comm_alarm"),
        (out.o_err_seq, "sequence"),
        (out.o_err_rs, "channel_mismatch"),
        (out.o_err_busy, "busy"),
    ]
    .into_iter()
    .filter_map(|(f, n)| f.then_some(n))
    .collect()
}

/// Host, bus and encoders.
pub struct Bench {
    cfg: BenchConfig,
    host: Host,
    encoders: Vec<Encoder>,
    line: HalfDuplexLine,
    at_host: bool,
    encoder_drive: Drive,
    bus_contention: u64,
    intruders: Vec<(u64, u64)>,
    requests_sent: usize,
    last_tx_en: bool,
    request_bit: (usize, u64),
    /// A receiver on the line at the host's pins that listens all the time
    /// (the host's own is deaf while it drives): the wire bytes of the
    /// transcript.
    /// Every character on the wire at the host, for the transcript.
    wire_tap: uart::WireTap,
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
    clocks_per_bit: u64,
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
        let encoders = (0..cfg.encoders.len())
            .map(|i| cfg.encoder_config(i).map(Encoder::new))
            .collect::<Result<Vec<_>>>()?;
        let intruders = cfg
            .intruders
            .iter()
            .map(|r| {
                (
                    tb.cycles_nearest_ns(r.at_us * 1e3),
                    tb.cycles_nearest_ns((r.at_us + r.length_us) * 1e3),
                )
            })
            .collect();
        Ok(Bench {
            host: Host::new(cfg.host_config()?)?,
            encoders,
            line: HalfDuplexLine::new(cfg.cable.delay_cycles(&tb), true),
            at_host: true,
            encoder_drive: Drive::default(),
            bus_contention: 0,
            intruders,
            requests_sent: 0,
            last_tx_en: false,
            request_bit: (0, 0),
            wire_tap: uart::WireTap::new(cfg.clocks_per_bit()?)?,
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
            clocks_per_bit: cfg.clocks_per_bit()?,
            tb,
            layout,
            cfg: BenchConfig {
                ops: cfg
                    .ops
                    .iter()
                    .cycle()
                    .take(cfg.ops.len() * cfg.repeat_ops)
                    .cloned()
                    .collect(),
                ..cfg.clone()
            },
        })
    }

    /// Cycles the RS-485 pair had two drivers on (host and bus, or two on the bus).
    pub fn contention_cycles(&self) -> u64 {
        self.line.contention_cycles() + self.bus_contention
    }

    /// The encoders (for tests that look inside them).
    pub fn encoders(&self) -> &[Encoder] {
        &self.encoders
    }

    /// The operations finished so far.
    pub fn transactions(&self) -> &[Transaction] {
        &self.transactions
    }

    /// The host (for tests that look inside it).
    pub fn host(&self) -> &Host {
        &self.host
    }

    /// What the encoders' side drives onto the line this cycle (an
    /// intruder pulls it low).
    fn bus_drive(&self) -> Drive {
        if self
            .intruders
            .iter()
            .any(|&(a, b)| (a..b).contains(&self.cycle))
        {
            Drive {
                enable: true,
                level: false,
            }
        } else {
            self.encoder_drive
        }
    }

    /// The level the host drives after the request-flip faults.
    fn host_drive(&mut self, out: &Out) -> Drive {
        if out.o_tx_en && !self.last_tx_en {
            self.request_bit = (self.requests_sent, self.cycle);
            self.requests_sent += 1;
        }
        self.last_tx_en = out.o_tx_en;
        let mut level = out.o_tx;
        if out.o_tx_en {
            let (request, from) = self.request_bit;
            let bit = ((self.cycle - from) / self.clocks_per_bit) as usize;
            if self
                .cfg
                .request_flips
                .iter()
                .any(|f| f.request == request && f.field * 10 + usize::from(f.bit) == bit)
            {
                level = !level;
            }
        }
        Drive {
            enable: out.o_tx_en,
            level,
        }
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
                i_broadcast: op.broadcast,
                i_mem_address: op.mem_address,
                i_wdata: op.data,
                i_rx: self.at_host,
            };
            self.open = Some(Transaction {
                index: self.next_op,
                start_cycle: self.cycle,
                done_cycle: 0,
                data_id: op.data_id,
                address: if op.broadcast {
                    self.cfg.host.broadcast_address
                } else {
                    op.address
                },
                broadcast: op.broadcast,
                requests: self.requests_sent,
                sent: Vec::new(),
                received: Vec::new(),
                wire_requests: Vec::new(),
                wire_answers: Vec::new(),
                cf: 0,
                sf: 0,
                sf2: 0,
                alm1: 0,
                alm2: 0,
                abs: 0,
                abm: 0,
                rs: 0,
                sc1: 0,
                sc2: 0,
                enid: 0,
                temp: 0,
                adf: 0,
                edf: 0,
                errors: Vec::new(),
            });
            self.waiting = true;
        }
        let out = self.host.step(&input);
        let host_drive = self.host_drive(&out);
        self.record_wire(input.i_rx, &out);
        let intruding = self
            .intruders
            .iter()
            .any(|&(a, b)| (a..b).contains(&self.cycle));
        let mut bus = self.encoder_drive;
        if intruding {
            if bus.enable {
                self.bus_contention += 1;
            }
            bus = Drive {
                enable: true,
                level: false,
            };
        }
        let (at_host, at_encoder) = self.line.step(host_drive, bus);
        // Two drivers on a bus: a low wins (the stronger pull in a fight is not modelled).
        let (mut enabled, mut level) = (0, true);
        for e in &mut self.encoders {
            let d = e.step(at_encoder.level);
            if d.enable {
                enabled += 1;
                level &= d.level;
            }
        }
        if enabled > 1 {
            self.bus_contention += 1;
        }
        self.encoder_drive = Drive {
            enable: enabled > 0,
            level,
        };
        self.at_host = at_host.level;
        if out.o_done {
            if let Some(mut t) = self.open.take() {
                t.done_cycle = self.cycle;
                t.requests = self.requests_sent - t.requests;
                t.sent = self.host.request().to_vec();
                t.received = self.host.fields().to_vec();
                t.cf = out.o_cf;
                t.sf = out.o_sf;
                t.sf2 = out.o_sf2;
                t.alm1 = out.o_alm1;
                t.alm2 = out.o_alm2;
                t.abs = out.o_abs;
                t.abm = out.o_abm;
                t.rs = out.o_rs;
                t.sc1 = out.o_sc1;
                t.sc2 = out.o_sc2;
                t.enid = out.o_enid;
                t.temp = out.o_temp;
                t.adf = out.o_adf;
                t.edf = out.o_edf;
                t.errors = error_names(&out);
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
        // The cycle after a start shows its pulse falling; a flipped
        // request bit depends on the cycle.
        let out = &self.last_out;
        if host == 0 || input != self.last_in || (out.o_tx_en && !self.cfg.request_flips.is_empty())
        {
            return 0;
        }
        // The parts most often busy first: most calls in a frame end at
        // the first 0, before the line and the encoders are looked at.
        let mut q = host.min(self.host.quiet(&input));
        if q == 0 {
            return 0;
        }
        q = q.min(self.wire_tap.quiet(input.i_rx, out.o_tx_en));
        let host_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        let bus = self.bus_drive();
        q = q.min(self.line.quiet(host_drive, bus));
        if q == 0 {
            return 0;
        }
        let at_encoder = self.line.sensed(host_drive, bus).1.level;
        for e in &self.encoders {
            q = q.min(e.quiet(at_encoder));
        }
        // Not across the start or end of an intruder.
        for &(a, b) in &self.intruders {
            let until = if self.cycle < a {
                a - self.cycle
            } else {
                b.saturating_sub(self.cycle)
            };
            if until > 0 {
                q = q.min(until);
            }
        }
        q
    }

    fn skip(&mut self, n: u64) {
        let out = self.last_out;
        let host_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        let bus = self.bus_drive();
        if self
            .intruders
            .iter()
            .any(|&(a, b)| (a..b).contains(&self.cycle))
            && self.encoder_drive.enable
        {
            self.bus_contention += n;
        }
        if self.encoders.iter().filter(|e| e.drive().enable).count() > 1 {
            self.bus_contention += n;
        }
        self.host.skip(n);
        self.wire_tap.skip(n);
        self.line.skip(n, host_drive, bus);
        for e in &mut self.encoders {
            e.skip(n);
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

/// The request a host puts on the line for one operation (for documentation and decoders).
pub fn request_for(op: &Operation, broadcast_address: u8) -> Vec<u8> {
    let address = if op.broadcast {
        broadcast_address
    } else {
        op.address
    };
    frames::request(address, op.data_id, op.mem_address, op.data)
}
