//! Master, half-duplex RS-485 pair and one to three SAR58K24 devices in
//! Modbus mode, stepped together with a script of polls. Implements
//! [`Setup`]/[`Testbench`] for `tbgen` (core `modbus_master`, table `[modbus]`).

use serde::{Deserialize, Serialize};

use super::device::{Device, DeviceConfig, DeviceSettings};
use super::frames;
use super::master::{In, Master, MasterConfig, Out};
use crate::angle::angle_deg;
use crate::gray::from_gray;
use crate::line::{CableConfig, Drive, HalfDuplexLine};
use crate::ports::{Port, Ports};
use crate::testbench::{self, Setup, Testbench};
use crate::trace::{Layout, Sample};
pub use crate::uart::SecondDriver;
use crate::uart::{self, Parity};
use crate::{ConfigError, Result, Timebase};

/// The master's settings in a scenario's units (`[modbus.master]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MasterSettings {
    /// From the request's end to the answer's first start bit, µs.
    pub timeout_us: f64,
}

impl Default for MasterSettings {
    fn default() -> Self {
        MasterSettings { timeout_us: 5000.0 }
    }
}

/// What a poll does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum OpKind {
    /// Function 03 from register 0.
    Read,
    /// The address query `FF A0 40 38`.
    Query,
    /// The address change: station `address` becomes `new_address`
    /// (function 06 to register 0x0010, this project's reading).
    SetAddress,
}

/// One poll (`[[modbus.ops]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Operation {
    /// Read or query.
    pub op: OpKind,
    /// Station address.
    #[serde(default = "default_address")]
    pub address: u8,
    /// Registers (1 or 2; 0 and 3 are sent as asked, to see the exception).
    #[serde(default = "default_count")]
    pub count: u8,
    /// Idle time before the poll, µs.
    #[serde(default)]
    pub gap_us: f64,
    /// `set_address`: the station's new address (1..247).
    #[serde(default)]
    pub new_address: u8,
}

fn default_address() -> u8 {
    1
}

fn default_count() -> u8 {
    1
}

/// Everything a scenario says about a Modbus set-up (`[modbus]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock, MHz.
    pub f_sys_mhz: f64,
    /// Baud (factory default 19200).
    pub baud: f64,
    /// Parity (factory default none).
    pub parity: Parity,
    /// The master.
    pub master: MasterSettings,
    /// The devices (1 to 3 on the bus).
    pub devices: Vec<DeviceSettings>,
    /// The cable.
    pub cable: CableConfig,
    /// The polls.
    pub ops: Vec<Operation>,
    /// Other drivers.
    pub second_drivers: Vec<SecondDriver>,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 10.0,
            baud: 19_200.0,
            parity: Parity::None,
            master: MasterSettings::default(),
            devices: vec![DeviceSettings::default()],
            cable: CableConfig {
                length_m: 10.0,
                ..CableConfig::default()
            },
            ops: vec![Operation {
                op: OpKind::Read,
                address: 1,
                count: 1,
                gap_us: 0.0,
                new_address: 0,
            }],
            second_drivers: Vec::new(),
        }
    }
}

impl BenchConfig {
    /// Clocks per bit, refused when rounding costs more than 0.5 %.
    pub fn clocks_per_bit(&self) -> Result<u64> {
        let tb = self.timebase()?;
        if !(300.0..=10e6).contains(&self.baud) {
            return Err(ConfigError::invalid(
                "baud",
                format!("{}", self.baud),
                "give a baud rate such as 9600, 19200 or 115200",
            ));
        }
        let c = (tb.f_sys_hz() as f64 / self.baud).round().max(1.0) as u64;
        let err = (tb.f_sys_hz() as f64 / c as f64 / self.baud - 1.0) * 100.0;
        if err.abs() > 0.5 {
            return Err(ConfigError::invalid(
                "baud",
                format!("{c} clocks per bit are {err:+.2} % off"),
                "raise f_sys_mhz or pick a clock that divides the baud rate within 0.5 %",
            ));
        }
        Ok(c)
    }

    /// The master's configuration in cycles (the Verilog parameters).
    pub fn master_config(&self) -> Result<MasterConfig> {
        let tb = self.timebase()?;
        if !(self.master.timeout_us > 0.0 && self.master.timeout_us < 1e7) {
            return Err(ConfigError::invalid(
                "master.timeout_us",
                format!("{}", self.master.timeout_us),
                "give a positive time in µs",
            ));
        }
        let fb = self.parity.frame_bits();
        let cfg = MasterConfig {
            clocks_per_bit: self.clocks_per_bit()?,
            parity: self.parity,
            t15_clocks: tb.cycles_nearest_ns(frames::t15_seconds(self.baud, fb) * 1e9),
            t35_clocks: tb.cycles_nearest_ns(frames::t35_seconds(self.baud, fb) * 1e9),
            timeout_clocks: tb.cycles_at_least_ns(self.master.timeout_us * 1e3),
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// Device `i`'s configuration in cycles (it keeps the same t1.5 and t3.5).
    pub fn device_config(&self, i: usize) -> Result<DeviceConfig> {
        let tb = self.timebase()?;
        let m = self.master_config()?;
        let d = &self.devices[i];
        d.validate(self.parity).map_err(|e| {
            let ConfigError::Invalid {
                field,
                problem,
                fix,
            } = e;
            ConfigError::invalid(
                field.replacen("device.", &format!("devices[{i}]."), 1),
                problem,
                fix,
            )
        })?;
        Ok(DeviceConfig {
            period_ps: tb.period_ps(),
            baud: self.baud,
            parity: self.parity,
            clocks_per_bit: m.clocks_per_bit,
            t15: m.t15_clocks,
            t35: m.t35_clocks,
            answer_delay: tb.cycles_nearest_ns(d.answer_delay_us * 1e3),
            settings: d.clone(),
        })
    }

    fn check(&self) -> Result<()> {
        self.cable.validate("cable")?;
        self.master_config()?;
        if self.devices.is_empty() || self.devices.len() > 3 {
            return Err(ConfigError::invalid(
                "devices",
                format!("{} devices", self.devices.len()),
                "give 1 to 3 devices",
            ));
        }
        for i in 0..self.devices.len() {
            self.device_config(i)?;
        }
        if self.ops.is_empty() || self.ops.len() > 100_000 {
            return Err(ConfigError::invalid(
                "ops",
                format!("{} polls", self.ops.len()),
                "list 1 to 100 000 polls",
            ));
        }
        for (i, op) in self.ops.iter().enumerate() {
            if op.count > 3 || !(0.0..1e8).contains(&op.gap_us) {
                return Err(ConfigError::invalid(
                    format!("ops[{i}]"),
                    format!("count {}, gap {} µs", op.count, op.gap_us),
                    "give count 0 to 3 (1 or 2 are valid reads) and gap_us ≥ 0",
                ));
            }
            if op.op == OpKind::SetAddress && !(1..=247).contains(&op.new_address) {
                return Err(ConfigError::invalid(
                    format!("ops[{i}].new_address"),
                    format!("{}", op.new_address),
                    "give the station's new address, 1 to 247",
                ));
            }
        }
        for (i, d) in self.second_drivers.iter().enumerate() {
            d.validate(i)?;
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
        let m = self.master_config()?;
        Ok(vec![
            ("CLOCKS_PER_BIT", m.clocks_per_bit),
            ("PARITY", m.parity.code()),
            ("T15_CLOCKS", m.t15_clocks),
            ("T35_CLOCKS", m.t35_clocks),
            ("TIMEOUT_CLOCKS", m.timeout_clocks),
        ])
    }

    fn bench(&self) -> Result<Bench> {
        Bench::new(self)
    }
}

/// One poll as the transcript reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based poll number.
    pub index: usize,
    /// Read or query.
    pub op: OpKind,
    /// Station polled.
    pub address: u8,
    /// Registers asked for.
    pub count: u8,
    /// Cycle of the start pulse.
    pub start_cycle: u64,
    /// Cycle of `o_done`.
    pub done_cycle: u64,
    /// The request the master built.
    pub request: Vec<u8>,
    /// The answer characters the master kept.
    pub received: Vec<u8>,
    /// The registers read (binary after Gray decoding when the devices send Gray).
    pub value: Option<u32>,
    /// Its angle for the first device's resolution.
    pub angle_deg: Option<f64>,
    /// The station the query returned, or the new address a good address change confirmed.
    pub station: Option<u8>,
    /// The exception code, if the answer was one.
    pub exception: Option<u8>,
    /// What the master flagged: `parity`, `framing`, `gap`, `length`, `crc`,
    /// `address`, `exception`, `function`, `count`, `timeout`.
    pub errors: Vec<&'static str>,
    /// The requests on the wire at the master's pins.
    pub wire_requests: Vec<Vec<u8>>,
    /// Every character on the wire after each request.
    pub wire_answers: Vec<Vec<u8>>,
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.start_cycle, self.done_cycle)
    }
}

/// Master, cable and devices.
pub struct Bench {
    cfg: BenchConfig,
    master: Master,
    devices: Vec<Device>,
    line: HalfDuplexLine,
    drivers: Vec<(u64, Vec<bool>)>,
    wire_tap: uart::WireTap,
    at_master: bool,
    device_drive: Drive,
    /// Devices driving in the last step.
    devices_on: usize,
    device_contention: u64,
    fault_contention: u64,
    next_op: usize,
    start_at: u64,
    waiting: bool,
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
        let layout = Layout {
            inputs: Master::input_ports(),
            outputs: Master::output_ports(),
            line: vec![
                Port::new("tx_en_master", 1),
                Port::new("tx_en_device", 1),
                Port::new("line_at_master", 1),
                Port::new("line_at_device", 1),
                Port::new("tx_device", 1),
            ],
            decoded: vec![Port::new("state", 3)],
        };
        let devices = (0..cfg.devices.len())
            .map(|i| Device::new(cfg.device_config(i)?))
            .collect::<Result<Vec<_>>>()?;
        let drivers = cfg
            .second_drivers
            .iter()
            .map(|d| d.cycle_levels(&tb, cfg.parity, c))
            .collect();
        Ok(Bench {
            master: Master::new(cfg.master_config()?)?,
            devices,
            line: HalfDuplexLine::new(cfg.cable.delay_cycles(&tb), true),
            drivers,
            wire_tap: uart::WireTap::with_parity(c, cfg.parity)?,
            at_master: true,
            device_drive: Drive::default(),
            devices_on: 0,
            device_contention: 0,
            fault_contention: 0,
            next_op: 0,
            start_at: tb.cycles_at_least_ns(cfg.ops[0].gap_us * 1e3),
            waiting: false,
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

    /// Cycles two drivers (master and a device, or two devices) were on together.
    pub fn contention_cycles(&self) -> u64 {
        self.line.contention_cycles() + self.device_contention
    }

    /// Cycles a second driver overlapped the master or a device.
    pub fn fault_contention_cycles(&self) -> u64 {
        self.fault_contention
    }

    /// The devices.
    pub fn devices(&self) -> &[Device] {
        &self.devices
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
            i_rx: self.at_master,
            ..In::default()
        };
        if !self.waiting
            && self.end.is_none()
            && self.cycle >= self.start_at
            && !self.last_out.o_busy
        {
            let op = self.cfg.ops[self.next_op].clone();
            input = In {
                i_start: op.op == OpKind::Read,
                i_query: op.op == OpKind::Query,
                i_write: op.op == OpKind::SetAddress,
                i_address: op.address,
                i_new_address: op.new_address,
                i_count: op.count,
                i_rx: self.at_master,
            };
            self.open = Some(Transaction {
                index: self.next_op,
                op: op.op,
                address: op.address,
                count: op.count,
                start_cycle: self.cycle,
                done_cycle: 0,
                request: Vec::new(),
                received: Vec::new(),
                value: None,
                angle_deg: None,
                station: None,
                exception: None,
                errors: Vec::new(),
                wire_requests: Vec::new(),
                wire_answers: Vec::new(),
            });
            self.waiting = true;
        }
        let out = self.master.step(&input);
        let master_drive = Drive {
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
        let (mut at_master, mut at_device) = self.line.step(master_drive, self.device_drive);
        let now = self.cycle;
        for (from, levels) in &self.drivers {
            if (*from..*from + levels.len() as u64).contains(&now) {
                let level = levels[(now - from) as usize];
                at_master.level = level;
                at_device.level = level;
                if master_drive.enable || self.device_drive.enable {
                    self.fault_contention += 1;
                }
            }
        }
        let drives: Vec<Drive> = self
            .devices
            .iter_mut()
            .map(|d| d.step(at_device.level))
            .collect();
        let on: Vec<&Drive> = drives.iter().filter(|d| d.enable).collect();
        if on.len() > 1 {
            self.device_contention += 1;
        }
        self.devices_on = on.len();
        self.device_drive = on.first().map_or(
            Drive {
                enable: false,
                level: true,
            },
            |d| **d,
        );
        self.at_master = at_master.level;
        if out.o_done {
            if let Some(mut t) = self.open.take() {
                t.done_cycle = self.cycle;
                t.request = self.master.request().to_vec();
                // No answer: nothing received (the master's buffer still holds the last answer's characters).
                t.received = if out.o_err_timeout {
                    Vec::new()
                } else {
                    self.master.received().to_vec()
                };
                if out.o_valid && t.op == OpKind::Read {
                    let d = &self.cfg.devices[0];
                    let v = if d.gray {
                        from_gray(out.o_value as u64) as u32
                    } else {
                        out.o_value
                    };
                    t.value = Some(v);
                    t.angle_deg = Some(angle_deg(v as u64, d.bits));
                }
                if out.o_valid && t.op != OpKind::Read {
                    t.station = Some(out.o_station);
                }
                if out.o_err_exception {
                    t.exception = Some(out.o_exception);
                }
                for (flag, name) in [
                    (out.o_err_parity, "parity"),
                    (out.o_err_framing, "framing"),
                    (out.o_err_gap, "gap"),
                    (out.o_err_length, "length"),
                    (out.o_err_crc, "crc"),
                    (out.o_err_address, "address"),
                    (out.o_err_exception, "exception"),
                    (out.o_err_function, "function"),
                    (out.o_err_count, "count"),
                    (out.o_err_timeout, "timeout"),
                ] {
                    if flag {
                        t.errors.push(name);
                    }
                }
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
        self.last_out = out;
        self.cycle += 1;
        let Some(sample) = sample else { return };
        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        // What the devices drive, high while none does: the server-to-client
        // channel of a decoder that wants the two directions apart (sigrok's `modbus`).
        let tx_device = !self.device_drive.enable || self.device_drive.level;
        sample.line.copy_from_slice(&[
            master_drive.enable as u64,
            self.device_drive.enable as u64,
            at_master.level as u64,
            at_device.level as u64,
            tx_device as u64,
        ]);
        sample.decoded[0] = self.master.state() as u64;
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
            self.waiting || self.last_out.o_busy,
            self.start_at,
            just_started,
            &self.drivers,
        );
        if q == 0 {
            return 0;
        }
        let out = &self.last_out;
        let input = In {
            i_rx: self.at_master,
            ..In::default()
        };
        let master_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        let (near, far) = self.line.sensed(master_drive, self.device_drive);
        // The level a second driver left at the near end gives way to the line's.
        if near.level != self.at_master {
            return 0;
        }
        let at_device = far.level;
        let devices = self
            .devices
            .iter()
            .map(|d| d.quiet(at_device))
            .min()
            .unwrap_or(u64::MAX);
        q.min(self.master.quiet(&input))
            .min(self.wire_tap.quiet(input.i_rx, out.o_tx_en))
            .min(self.line.quiet(master_drive, self.device_drive))
            .min(devices)
    }

    fn skip(&mut self, n: u64) {
        let out = self.last_out;
        let master_drive = Drive {
            enable: out.o_tx_en,
            level: out.o_tx,
        };
        self.master.skip(n);
        self.wire_tap.skip(n);
        self.line.skip(n, master_drive, self.device_drive);
        for d in &mut self.devices {
            d.skip(n);
        }
        if self.devices_on > 1 {
            self.device_contention += n;
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
