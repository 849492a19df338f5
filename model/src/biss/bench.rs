//! A whole BiSS-C set-up: host, master, cable and a chain of slaves.
//!
//! The host runs its register accesses first, each as one operation (one
//! `i_reg_start`, then it waits for `o_reg_done` while the master runs the
//! frames), then starts frames until `frames` have run. Every frame, whoever
//! started it, is a transaction.
//!
//! Each cycle `c`:
//! 1. the host decides `i_start` and register requests; the master's SLO
//!    input is the level that left the cable at the master's end in the
//!    previous cycle (or the stuck level of a fault);
//! 2. the master steps and drives MA;
//! 3. MA crosses the cable (its delay, 0 cycles for no cable);
//! 4. the chain steps with MA at its pins and drives SLO (after its output delay);
//! 5. SLO crosses the cable back; the master sees it in cycle `c + 1`.

use serde::{Deserialize, Serialize};

use super::control;
use super::master::{In, Master, MasterConfig, Out, MAX_SLAVES};
use super::slave::{Chain, ControlFaults, Slave, SlaveConfig};
use crate::line::{CableConfig, DelayLine};
use crate::ports::{Port, Ports};
use crate::testbench::{self, Setup, Testbench};
use crate::trace::{Layout, Sample};
use crate::{ConfigError, Result, Timebase};

/// The master's settings in a scenario file's units (`[master]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MasterSettings {
    /// MA frequency in kHz (seed: TMAS > 100 ns, so up to 10 000 kHz); f_sys divided by a whole number of at least 8, odd allowed (the high phase takes the extra cycle).
    pub clock_khz: f64,
    /// Longest delay from the second rising MA edge to the ack that the
    /// master compensates, in ns.
    pub max_delay_ns: f64,
    /// Longest wait for the start bit, for the end of the slave's timeout
    /// and for a late ack, in µs (at least the slaves' BiSS timeout plus the
    /// round trip).
    pub timeout_us: f64,
    /// Data bits the master expects of each slave (default: what the slaves send).
    pub bits: Option<Vec<u32>>,
    /// CRC width per slave (default: the slaves').
    pub crc_width: Option<Vec<u32>>,
    /// CRC polynomial per slave (default: the slaves').
    pub crc_poly: Option<Vec<u64>>,
    /// Start-up frames whose mean delay the master samples by: 1, 2, 4, 8 or 16.
    pub cal_frames: u64,
    /// Largest departure from the mean delay still sampled by the mean, ns
    /// (default: a quarter of an MA period, rounded down to whole cycles).
    pub delay_tolerance_ns: Option<f64>,
}

impl Default for MasterSettings {
    fn default() -> Self {
        MasterSettings {
            clock_khz: 10_000.0,
            max_delay_ns: 2_000.0,
            timeout_us: 40.0,
            bits: None,
            crc_width: None,
            crc_poly: None,
            cal_frames: 4,
            delay_tolerance_ns: None,
        }
    }
}

/// One slave in a scenario file's units (`[[slaves]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SlaveSettings {
    /// Data bits.
    #[schemars(range(min = *super::master::DATA_BITS.start(), max = *super::master::DATA_BITS.end()))]
    pub bits: u32,
    /// CRC width (BiSS-C: 6).
    pub crc_width: u32,
    /// CRC polynomial without the top term (BiSS-C `x^6 + x + 1`: 3).
    pub crc_poly: u64,
    /// `t_busy` in ns from the ack to the earliest start bit (seed: at
    /// least 2 × TMAS; default exactly 2 × TMAS of the master's MA clock:
    /// the seed gives it in MA periods, so a fixed time would fall short at
    /// slow clocks).
    pub busy_ns: Option<f64>,
    /// BiSS timeout in µs (seed: 16 µs).
    pub timeout_us: f64,
    /// MA edge to SLO change in ns (transceivers and logic).
    pub output_delay_ns: f64,
    /// ID for register access (default: the chain position).
    pub id: Option<u8>,
    /// Positions at successive frames (cycled), plus `step` per frame.
    pub positions: Vec<u64>,
    /// Counts added per frame.
    pub step: u64,
    /// The error bit is active (nE = 0) in every frame...
    pub error: bool,
    /// ...or only in these frames (0-based).
    pub error_frames: Vec<usize>,
    /// The warning bit is active (nW = 0) in every frame...
    pub warning: bool,
    /// ...or only in these frames.
    pub warning_frames: Vec<usize>,
    /// Register bank from address 0.
    pub registers: Vec<u8>,
    /// Fault: the slave misreads CDM bit `k` of its first control frame.
    pub cdm_flip_at: Option<u32>,
    /// Fault: the slave answers its first register read with a wrong CRC-4.
    pub cds_crc_error: bool,
    /// The CRC-4 bit `cds_crc_error` inverts: 0 = the first CRC bit sent
    /// (the CRC's MSB), 3 = the last.
    pub cds_crc_bit: u32,
    /// Fault: the slave echoes this byte, with the right CRC-4 for it, in
    /// place of the data of its first register write, and stores nothing:
    /// only the master's comparison of the echo with the byte it wrote sees it.
    pub cds_write_echo: Option<u8>,
}

impl Default for SlaveSettings {
    fn default() -> Self {
        SlaveSettings {
            bits: 16,
            crc_width: 6,
            crc_poly: 0x03,
            busy_ns: None,
            timeout_us: 16.0,
            output_delay_ns: 20.0,
            id: None,
            positions: vec![0],
            step: 0,
            error: false,
            error_frames: Vec::new(),
            warning: false,
            warning_frames: Vec::new(),
            registers: Vec::new(),
            cdm_flip_at: None,
            cds_crc_error: false,
            cds_crc_bit: 0,
            cds_write_echo: None,
        }
    }
}

/// One register access the host asks for (`[[host.registers]]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RegOp {
    /// Write (`true`) or read.
    #[serde(default)]
    pub write: bool,
    /// Slave ID (chain position).
    #[serde(default)]
    pub id: u8,
    /// Register address, 0 to 127.
    pub addr: u8,
    /// Data for a write.
    #[serde(default)]
    pub data: u8,
}

/// One BiSS-C command the host sends (`[[host.commands]]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CmdOp {
    /// Slave-select bits IDS: bit `i` selects ID `i`; 0 is a broadcast.
    #[serde(default)]
    pub ids: u8,
    /// The 2-bit command.
    pub code: u8,
}

/// When the host starts frames and register accesses (`[host]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HostSettings {
    /// The first start, µs after reset.
    pub first_start_us: f64,
    /// Idle time between the end of one frame and the next start, µs.
    pub gap_us: f64,
    /// Frames to run at least (the frames of register accesses count).
    pub frames: usize,
    /// Register accesses, one after the other, before the host's own frames.
    pub registers: Vec<RegOp>,
    /// Commands, one after the other, after the register accesses.
    pub commands: Vec<CmdOp>,
}

impl Default for HostSettings {
    fn default() -> Self {
        HostSettings {
            first_start_us: 1.0,
            gap_us: 1.0,
            frames: 1,
            registers: Vec::new(),
            commands: Vec::new(),
        }
    }
}

/// SLO held at one level at the master from a given frame on (`[stuck]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StuckFault {
    /// `true`: stuck high (open RS-485 line, slave absent); `false`: stuck low.
    pub level: bool,
    /// The first frame (0-based) that sees it.
    pub from_frame: usize,
}

/// Bits of one slave's section corrupted on the wire in one frame (`[[flips]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FlipFault {
    /// The frame (0-based).
    pub frame: usize,
    /// The slave (chain position).
    #[serde(default)]
    pub slave: usize,
    /// Bit indices: 0 = data MSB, `bits` = nE, `bits + 1` = nW, then the CRC field.
    pub bits: Vec<u32>,
}

/// Extra SLO delay from a given frame on: the line changed after the
/// master calibrated (`[delay_step]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DelayStep {
    /// The first frame (0-based) that sees it.
    pub from_frame: usize,
    /// Extra delay on SLO at the master, ns.
    pub extra_ns: f64,
}

/// Everything a scenario says about a BiSS-C set-up.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock in MHz.
    pub f_sys_mhz: f64,
    /// The master.
    pub master: MasterSettings,
    /// The slaves in chain order (1 to 3).
    pub slaves: Vec<SlaveSettings>,
    /// The cable.
    pub cable: CableConfig,
    /// The host.
    pub host: HostSettings,
    /// Wire corruptions.
    pub flips: Vec<FlipFault>,
    /// A stuck SLO line.
    pub stuck: Option<StuckFault>,
    /// A change of the line delay after start-up.
    pub delay_step: Option<DelayStep>,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 80.0,
            master: MasterSettings::default(),
            slaves: vec![SlaveSettings::default()],
            cable: CableConfig::default(),
            host: HostSettings::default(),
            flips: Vec::new(),
            stuck: None,
            delay_step: None,
        }
    }
}

fn check_time(field: &str, value: f64) -> Result<()> {
    if !(0.0..1e7).contains(&value) {
        return Err(ConfigError::invalid(
            field,
            format!("{value}"),
            "give a non-negative time",
        ));
    }
    Ok(())
}

impl BenchConfig {
    /// The seed's example: one 16-bit slave holding 35555 with nE = 1 and
    /// nW = 0 (seed 001, BiSS-C section), read at 10 MHz through 10 m.
    pub fn seed_example() -> Self {
        BenchConfig {
            slaves: vec![SlaveSettings {
                positions: vec![0b1000_1010_1110_0011],
                warning: true,
                ..SlaveSettings::default()
            }],
            cable: CableConfig {
                length_m: 10.0,
                ..CableConfig::default()
            },
            ..BenchConfig::default()
        }
    }

    /// The master's configuration in cycles (the Verilog parameters).
    pub fn master_config(&self) -> Result<MasterConfig> {
        let tb = self.timebase()?;
        let m = &self.master;
        if !(m.clock_khz >= 100.0 && m.clock_khz <= 10_000.0) {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!("{} kHz", m.clock_khz),
                "give MA from 100 to 10000 kHz (seed: TMAS > 100 ns)",
            ));
        }
        check_time("master.max_delay_ns", m.max_delay_ns)?;
        check_time("master.timeout_us", m.timeout_us)?;
        let clock = tb.divider(m.clock_khz * 1e3, "master.clock_khz", 8)?;
        let clocks_per_bit = clock.period;
        let delay_tol = match m.delay_tolerance_ns {
            Some(ns) => {
                check_time("master.delay_tolerance_ns", ns)?;
                tb.cycles_nearest_ns(ns)
            }
            None => clocks_per_bit / 4,
        };
        let n = self.slaves.len();
        let cfg = MasterConfig {
            slaves: n as u32,
            slave_bits: m
                .bits
                .clone()
                .unwrap_or_else(|| self.slaves.iter().map(|s| s.bits).collect()),
            slave_crc_width: m
                .crc_width
                .clone()
                .unwrap_or_else(|| self.slaves.iter().map(|s| s.crc_width).collect()),
            slave_crc_poly: m
                .crc_poly
                .clone()
                .unwrap_or_else(|| self.slaves.iter().map(|s| s.crc_poly).collect()),
            clocks_per_bit,
            high_clocks: clock.high,
            low_clocks: clock.low,
            max_delay: tb.cycles_at_least_ns(m.max_delay_ns),
            timeout_clocks: tb.cycles_at_least_ns(m.timeout_us * 1e3),
            cal_frames: m.cal_frames,
            delay_tol,
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// Slave `i`'s configuration in cycles.
    pub fn slave_config(&self, i: usize) -> Result<SlaveConfig> {
        let tb = self.timebase()?;
        let s = &self.slaves[i];
        let prefix = format!("slaves[{i}]");
        check_time(&format!("{prefix}.timeout_us"), s.timeout_us)?;
        check_time(&format!("{prefix}.output_delay_ns"), s.output_delay_ns)?;
        let mut cfg = SlaveConfig {
            bits: s.bits,
            crc_width: s.crc_width,
            crc_poly: s.crc_poly,
            busy_clocks: 0,
            timeout_clocks: tb.cycles_at_least_ns(s.timeout_us * 1e3),
            id: s.id.unwrap_or(i as u8),
            registers: s.registers.clone(),
        };
        // The slave's own fields first, so that a bad one is blamed on the
        // slave's table and not on the master's settings derived from it.
        cfg.validate(&prefix)?;
        // Seed 001, BiSS-C: "Tbusy: Minimum data output delay 2 TMAS". TMAS
        // from the MA clock alone (not master_config, whose divider limits
        // are the master core's, not the slave's: the co-simulation slave
        // runs at any emulator clock of 4 x MA or more); at an even divider
        // it is exactly the master's clocks per bit.
        if !(self.master.clock_khz >= 100.0 && self.master.clock_khz <= 10_000.0) {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!("{} kHz", self.master.clock_khz),
                "give MA from 100 to 10000 kHz (seed: TMAS > 100 ns)",
            ));
        }
        let two_tmas = 2 * tb.cycles_nearest_ns(1e6 / self.master.clock_khz).max(1);
        cfg.busy_clocks = match s.busy_ns {
            Some(ns) => {
                check_time(&format!("{prefix}.busy_ns"), ns)?;
                let clocks = tb.cycles_at_least_ns(ns);
                if clocks < two_tmas {
                    return Err(ConfigError::invalid(
                        format!("{prefix}.busy_ns"),
                        format!("{ns} ns at {} kHz", self.master.clock_khz),
                        format!("give at least 2 x TMAS = {} ns (seed: Tbusy 2 TMAS), or leave it out for exactly that", 2e6 / self.master.clock_khz),
                    ));
                }
                clocks
            }
            None => two_tmas,
        };
        Ok(cfg)
    }

    /// Slave `i`'s `t_busy` in ns: as given, or 2 × TMAS of the MA clock.
    pub fn busy_ns(&self, i: usize) -> f64 {
        self.slaves[i]
            .busy_ns
            .unwrap_or(2e6 / self.master.clock_khz)
    }

    /// The position slave `i` holds in frame `k`.
    pub fn position_at(&self, i: usize, k: usize) -> u64 {
        let s = &self.slaves[i];
        let listed = if s.positions.is_empty() {
            0
        } else {
            s.positions[k % s.positions.len()]
        };
        listed.wrapping_add((k as u64).wrapping_mul(s.step))
    }

    fn check(&self) -> Result<()> {
        if self.slaves.is_empty() || self.slaves.len() > MAX_SLAVES {
            return Err(ConfigError::invalid(
                "slaves",
                format!("{} slaves", self.slaves.len()),
                "give 1 to 3 [[slaves]] tables",
            ));
        }
        self.cable.validate("cable")?;
        // The slaves first: the master's per-slave lists default to theirs.
        for i in 0..self.slaves.len() {
            self.slave_config(i)?;
        }
        self.master_config()?;
        for i in 0..self.slaves.len() {
            let s = &self.slaves[i];
            let limit = if s.bits == 64 {
                u64::MAX
            } else {
                (1u64 << s.bits) - 1
            };
            if let Some((j, p)) = s.positions.iter().enumerate().find(|(_, p)| **p > limit) {
                return Err(ConfigError::invalid(
                    format!("slaves[{i}].positions[{j}]"),
                    format!("{p} does not fit {} bits", s.bits),
                    format!("give positions from 0 to {limit}"),
                ));
            }
        }
        if let Some(d) = &self.delay_step {
            check_time("delay_step.extra_ns", d.extra_ns)?;
        }
        check_time("host.first_start_us", self.host.first_start_us)?;
        check_time("host.gap_us", self.host.gap_us)?;
        if let Some((j, _)) = self
            .host
            .commands
            .iter()
            .enumerate()
            .find(|(_, c)| c.code > 3)
        {
            return Err(ConfigError::invalid(
                format!("host.commands[{j}].code"),
                "above 3",
                "give a 2-bit command, 0 to 3",
            ));
        }
        if self.host.frames == 0 && self.host.registers.is_empty() && self.host.commands.is_empty()
        {
            return Err(ConfigError::invalid(
                "host.frames",
                "no frames",
                "ask for at least one frame",
            ));
        }
        if self.host.frames > 1_000_000 {
            return Err(ConfigError::invalid(
                "host.frames",
                format!("{}", self.host.frames),
                "ask for at most a million frames",
            ));
        }
        for (j, op) in self.host.registers.iter().enumerate() {
            if op.id > 7 || op.addr > 127 {
                return Err(ConfigError::invalid(
                    format!("host.registers[{j}]"),
                    "ID or address out of range",
                    "give id 0 to 7 and addr 0 to 127",
                ));
            }
        }
        for (i, s) in self.slaves.iter().enumerate() {
            self.check_control_faults(i, s)?;
        }
        for (j, f) in self.flips.iter().enumerate() {
            if f.slave >= self.slaves.len() {
                return Err(ConfigError::invalid(
                    format!("flips[{j}].slave"),
                    format!("slave {}", f.slave),
                    "name a slave of the chain (0-based)",
                ));
            }
            let s = &self.slaves[f.slave];
            let len = s.bits + 2 + s.crc_width;
            if let Some(b) = f.bits.iter().find(|&&b| b >= len) {
                return Err(ConfigError::invalid(
                    format!("flips[{j}].bits"),
                    format!("bit {b}"),
                    format!("give bits 0 to {}", len - 1),
                ));
            }
        }
        // A fault in a frame the run never reaches would pass unnoticed.
        let frames = self.frame_limit();
        let scheduled = self
            .flips
            .iter()
            .enumerate()
            .map(|(j, f)| (format!("flips[{j}].frame"), f.frame));
        let scheduled = scheduled
            .chain(
                self.stuck
                    .iter()
                    .map(|s| ("stuck.from_frame".to_string(), s.from_frame)),
            )
            .chain(
                self.delay_step
                    .iter()
                    .map(|d| ("delay_step.from_frame".to_string(), d.from_frame)),
            );
        for (field, frame) in scheduled {
            if frame >= frames {
                return Err(ConfigError::invalid(
                    field,
                    format!(
                        "frame {frame}, but the run has {frames} frames (0 to {})",
                        frames - 1
                    ),
                    "give a frame below host.frames (0-based), or raise host.frames",
                ));
            }
        }
        Ok(())
    }

    /// Slave `i`'s control-frame faults: a CRC-4 bit that exists, and a
    /// wrong echo only where the host writes to that slave (else it would
    /// pass unnoticed).
    fn check_control_faults(&self, i: usize, s: &SlaveSettings) -> Result<()> {
        if s.cds_crc_bit > 3 {
            return Err(ConfigError::invalid(
                format!("slaves[{i}].cds_crc_bit"),
                format!("bit {}", s.cds_crc_bit),
                "give a CRC-4 bit from 0 (the first sent) to 3 (the last)",
            ));
        }
        if s.cds_crc_bit != 0 && !s.cds_crc_error {
            return Err(ConfigError::invalid(
                format!("slaves[{i}].cds_crc_bit"),
                format!("bit {} without cds_crc_error", s.cds_crc_bit),
                "set cds_crc_error = true to corrupt that bit, or leave cds_crc_bit out",
            ));
        }
        let id = s.id.unwrap_or(i as u8);
        if s.cds_write_echo.is_some() && !self.host.registers.iter().any(|r| r.write && r.id == id)
        {
            return Err(ConfigError::invalid(
                format!("slaves[{i}].cds_write_echo"),
                format!("no register write to ID {id} in host.registers"),
                format!("add {{ write = true, id = {id}, addr = .., data = .. }} to host.registers, or leave cds_write_echo out"),
            ));
        }
        Ok(())
    }

    /// The most frames a run may take: the frames asked for plus what the
    /// register accesses need (14 sync zeros and 33 control frames each).
    pub fn frame_limit(&self) -> usize {
        self.host.frames
            + self.host.registers.len()
                * (control::SYNC_ZEROS as usize + control::K_LAST as usize + 2)
            + self.host.commands.len()
                * (control::SYNC_ZEROS as usize + control::K_CMD_LAST as usize + 2)
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
        Ok(self.master_config()?.parameters())
    }

    fn bench(&self) -> Result<Bench> {
        Bench::new(self)
    }
}

/// One slave's part of a frame as the transcript reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlaveResult {
    /// Chain position.
    pub slave: u8,
    /// The position the slave latched.
    pub sent_position: u64,
    /// Its section as it left the slave: CDS, data, nE, nW, CRC (inverted).
    pub sent_bits: String,
    /// The decoded data.
    pub position: u64,
    /// `360° × position / 2^bits`, cut to 4 decimals as the seed prints it.
    pub angle_deg: f64,
    /// nE was 0.
    pub error: bool,
    /// nW was 0.
    pub warning: bool,
    /// The CDS bit.
    pub cds: bool,
    /// The CRC matched.
    pub crc_ok: bool,
}

/// A finished register access.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegResult {
    /// Write or read.
    pub write: bool,
    /// Slave ID.
    pub id: u8,
    /// Address.
    pub addr: u8,
    /// Data written (writes; 0 on a read).
    pub wdata: u8,
    /// Data read, or the slave's echo of a write.
    pub rdata: u8,
    /// The access succeeded.
    pub ok: bool,
    /// `false` when the slave's answer came with a wrong CRC-4 (`o_reg_crc_err`).
    pub crc4_ok: bool,
    /// The CDM bits the master sent, `k = 0` up to the frame that ended the
    /// access (`k = 32` when it ran to the end).
    pub cdm: String,
}

/// A finished command.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CmdResult {
    /// Slave-select bits IDS (0 = broadcast).
    pub ids: u8,
    /// The command.
    pub code: u8,
    /// Every selected slave acknowledged (IDA) and echoed EX.
    pub ok: bool,
    /// The CDM bits the master sent, `k = 0` up to the frame that ended it.
    pub cdm: String,
}

/// One frame as the transcript reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based frame number.
    pub index: usize,
    /// The cycle the master left IDLE (the host's start pulse, or the
    /// master's own start inside a register access).
    pub start_cycle: u64,
    /// Cycle of `o_done`.
    pub done_cycle: u64,
    /// Edge 2 to ack at the synchroniser, cycles, when there was an ack.
    pub delay_cycles: Option<u64>,
    /// The start-up mean the master samples by, once calibrated.
    pub delay_mean_cycles: Option<u64>,
    /// The CDM bit this frame carried.
    pub cdm: bool,
    /// Control-frame index of that bit, when a control frame was running.
    pub control_index: Option<u32>,
    /// Every bit sampled after the ack (start bit first).
    pub received_bits: String,
    /// Each slave's result, in chain order.
    pub slaves: Vec<SlaveResult>,
    /// Frame errors: `line_low_at_start`, `no_ack`, `delay_beyond_compensation`,
    /// `no_start_bit`, `slo_not_released`, `delay_departs_from_mean`; per
    /// slave `crc_error_slave<i>`.
    pub errors: Vec<String>,
    /// A register access that ended with this frame.
    pub register: Option<RegResult>,
    /// A command that ended with this frame.
    pub command: Option<CmdResult>,
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.start_cycle, self.done_cycle)
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Host {
    WaitUntil(u64),
    WaitDone,
    WaitRegDone,
    Finished(u64),
}

/// Cycles the bench keeps running after the last frame.
const TAIL_CYCLES: u64 = 16;

/// Host, master, cable and chain.
pub struct Bench {
    cfg: BenchConfig,
    master: Master,
    chain: Chain,
    ma_line: DelayLine,
    slo_line: DelayLine,
    slo_at_master: bool,
    host: Host,
    gap_clocks: u64,
    next_frame: usize,
    next_op: usize,
    stuck: Option<bool>,
    extra_slo: Option<DelayLine>,
    delay_step: Option<(usize, u64)>,
    cycle: u64,
    last_in: In,
    last_out: Out,
    open: Option<Transaction>,
    open_op: Option<RegOp>,
    open_cmd: Option<CmdOp>,
    next_cmd: usize,
    transactions: Vec<Transaction>,
    layout: Layout,
}

impl Bench {
    /// A bench in its reset state.
    pub fn new(cfg: &BenchConfig) -> Result<Self> {
        cfg.check()?;
        let tb = cfg.timebase()?;
        let master = Master::new(cfg.master_config()?)?;
        let mut slaves = Vec::new();
        for i in 0..cfg.slaves.len() {
            let mut s = Slave::new(cfg.slave_config(i)?)?;
            let f = &cfg.slaves[i];
            s.set_control_faults(ControlFaults {
                cdm_flip_at: f.cdm_flip_at,
                cds_crc_flip: f.cds_crc_error.then_some(f.cds_crc_bit),
                cds_write_echo: f.cds_write_echo,
            });
            slaves.push(s);
        }
        let chain = Chain::new(slaves, tb.cycles_nearest_ns(cfg.slaves[0].output_delay_ns));
        let (ma_line, slo_line) = cfg.cable.lines(&tb, true);
        let layout = Layout {
            inputs: master.input_ports(),
            outputs: master.output_ports(),
            line: vec![
                Port::new("ma_master", 1),
                Port::new("ma_slave", 1),
                Port::new("slo_slave", 1),
                Port::new("slo_master", 1),
            ],
            decoded: vec![
                Port::new("state", 4),
                Port::new("slave", 2),
                Port::new("cdm", 1),
                Port::new("control_index", 6),
                Port::new("sent_position0", cfg.slaves[0].bits),
            ],
        };
        let mut bench = Bench {
            master,
            chain,
            ma_line,
            slo_line,
            slo_at_master: true,
            host: Host::WaitUntil(tb.cycles_at_least_ns(cfg.host.first_start_us * 1e3)),
            gap_clocks: tb.cycles_at_least_ns(cfg.host.gap_us * 1e3),
            next_frame: 0,
            next_op: 0,
            stuck: None,
            extra_slo: None,
            delay_step: cfg
                .delay_step
                .as_ref()
                .map(|d| (d.from_frame, tb.cycles_nearest_ns(d.extra_ns))),
            cycle: 0,
            last_in: In {
                i_slo: true,
                ..In::default()
            },
            last_out: Out {
                o_ma: true,
                ..Out::default()
            },
            open: None,
            open_op: None,
            open_cmd: None,
            next_cmd: 0,
            transactions: Vec::new(),
            layout,
            cfg: cfg.clone(),
        };
        bench.apply_stuck_before(0);
        Ok(bench)
    }

    /// Runs to the end with nothing recorded.
    pub fn run_to_end(self) -> testbench::Run<Transaction> {
        testbench::run_to_end(self)
    }

    /// The slaves (to inspect register banks after a run).
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    fn apply_stuck_before(&mut self, k: usize) {
        if let Some(f) = &self.cfg.stuck {
            if k >= f.from_frame {
                self.stuck = Some(f.level);
            }
        }
        if let (Some((from, cycles)), None) = (self.delay_step, &self.extra_slo) {
            if k >= from {
                self.extra_slo = Some(DelayLine::new(cycles, true));
            }
        }
    }

    fn host_decides(&mut self) -> In {
        let mut input = In {
            i_slo: self.stuck.unwrap_or(self.slo_at_master),
            ..In::default()
        };
        if let Host::WaitUntil(at) = self.host {
            if self.cycle >= at && !self.last_out.o_busy && !self.last_out.o_reg_busy {
                if self.next_op < self.cfg.host.registers.len() {
                    let op = self.cfg.host.registers[self.next_op];
                    self.next_op += 1;
                    self.open_op = Some(op);
                    input.i_reg_start = true;
                    input.i_reg_write = op.write;
                    input.i_reg_id = op.id;
                    input.i_reg_addr = op.addr;
                    input.i_reg_wdata = op.data;
                    self.host = Host::WaitRegDone;
                } else if self.next_cmd < self.cfg.host.commands.len() {
                    let cmd = self.cfg.host.commands[self.next_cmd];
                    self.next_cmd += 1;
                    self.open_cmd = Some(cmd);
                    input.i_cmd_start = true;
                    input.i_cmd_ids = cmd.ids;
                    input.i_cmd_code = cmd.code;
                    self.host = Host::WaitRegDone;
                } else {
                    input.i_start = true;
                    self.host = Host::WaitDone;
                }
            }
        }
        input
    }

    /// A frame begins when the master leaves IDLE (or refuses a start): the
    /// slaves take this frame's position and flags before the first MA edge
    /// reaches them.
    fn frame_begins(&mut self, out: &Out) {
        if self.last_out.o_busy || !(out.o_busy || out.o_done) {
            return;
        }
        let k = self.next_frame;
        for i in 0..self.cfg.slaves.len() {
            let p = self.cfg.position_at(i, k);
            let s = &self.cfg.slaves[i];
            let error = s.error || s.error_frames.contains(&k);
            let warning = s.warning || s.warning_frames.contains(&k);
            let flips: Vec<u32> = self
                .cfg
                .flips
                .iter()
                .filter(|f| f.frame == k && f.slave == i)
                .flat_map(|f| f.bits.clone())
                .collect();
            let slave = &mut self.chain.slaves_mut()[i];
            slave.set_position(p);
            slave.set_flags(error, warning);
            slave.set_flips(flips);
        }
        self.open = Some(Transaction {
            index: k,
            start_cycle: self.cycle,
            done_cycle: 0,
            delay_cycles: None,
            delay_mean_cycles: None,
            cdm: self.master.cdm(),
            control_index: self.master.control_index(),
            received_bits: String::new(),
            slaves: Vec::new(),
            errors: Vec::new(),
            register: None,
            command: None,
        });
        self.next_frame += 1;
    }

    fn host_observes(&mut self, out: &Out) {
        if out.o_slave_valid {
            if let Some(t) = self.open.as_mut() {
                let i = out.o_slave_index as usize;
                let bits = self.cfg.slaves.get(i).map(|s| s.bits).unwrap_or(1);
                let slave = &self.chain.slaves()[i.min(self.chain.slaves().len() - 1)];
                t.slaves.push(SlaveResult {
                    slave: out.o_slave_index,
                    sent_position: slave.position(),
                    sent_bits: crate::bits::string(slave.last_section()),
                    position: out.o_data,
                    angle_deg: crate::angle::angle_deg(out.o_data, bits),
                    error: out.o_error,
                    warning: out.o_warning,
                    cds: out.o_cds,
                    crc_ok: !out.o_crc_err,
                });
                if out.o_crc_err {
                    t.errors.push(format!("crc_error_slave{i}"));
                }
            }
        }
        if out.o_done {
            if let Some(mut t) = self.open.take() {
                t.done_cycle = self.cycle;
                if !out.o_err_line && !out.o_err_ack && !out.o_err_delay {
                    t.delay_cycles = Some(out.o_delay);
                }
                for (flag, name) in [
                    (out.o_err_line, "line_low_at_start"),
                    (out.o_err_ack, "no_ack"),
                    (out.o_err_delay, "delay_beyond_compensation"),
                    (out.o_err_start, "no_start_bit"),
                    (out.o_err_timeout, "slo_not_released"),
                    (out.o_err_drift, "delay_departs_from_mean"),
                ] {
                    if flag {
                        t.errors.push(name.to_string());
                    }
                }
                t.received_bits = crate::bits::string(self.master.sampled_bits());
                t.delay_mean_cycles = self.master.calibrated().then_some(out.o_delay_mean);
                if out.o_reg_done {
                    if let Some(op) = self.open_op.take() {
                        let acc = control::Access {
                            write: op.write,
                            id: op.id,
                            addr: op.addr,
                            wdata: op.data,
                            ..control::Access::default()
                        };
                        let sent = t.control_index.map_or(0, |k| k as usize + 1);
                        let cdm = &control::cdm_sequence(&acc)[..sent];
                        t.register = Some(RegResult {
                            write: op.write,
                            id: op.id,
                            addr: op.addr,
                            wdata: if op.write { op.data } else { 0 },
                            rdata: out.o_reg_rdata,
                            ok: !out.o_reg_err,
                            crc4_ok: !out.o_reg_crc_err,
                            cdm: crate::bits::string(cdm),
                        });
                    }
                    if let Some(cmd) = self.open_cmd.take() {
                        let acc = control::Access {
                            command: true,
                            ids: cmd.ids,
                            code: cmd.code,
                            ..control::Access::default()
                        };
                        let sent = t.control_index.map_or(0, |k| k as usize + 1);
                        t.command = Some(CmdResult {
                            ids: cmd.ids,
                            code: cmd.code,
                            ok: !out.o_reg_err,
                            cdm: crate::bits::string(&control::cdm_sequence(&acc)[..sent]),
                        });
                    }
                }
                self.transactions.push(t);
            }
            self.apply_stuck_before(self.next_frame);
            let host_done = match self.host {
                Host::WaitDone => true,
                Host::WaitRegDone => out.o_reg_done,
                _ => false,
            };
            if host_done {
                let more_ops = self.next_op < self.cfg.host.registers.len()
                    || self.next_cmd < self.cfg.host.commands.len();
                let more = (self.next_frame < self.cfg.host.frames || more_ops)
                    && self.next_frame < self.cfg.frame_limit();
                self.host = if more {
                    Host::WaitUntil(self.cycle + self.gap_clocks)
                } else {
                    Host::Finished(self.cycle + TAIL_CYCLES)
                };
            }
        }
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

    fn step(&mut self, sample: Option<&mut Sample>) {
        let input = self.host_decides();
        let out = self.master.step(&input);
        self.frame_begins(&out);
        let ma_at_slave = self.ma_line.step(out.o_ma);
        let slo_from_slave = self.chain.step(ma_at_slave);
        let slo_back = self.slo_line.step(slo_from_slave);
        self.slo_at_master = match self.extra_slo.as_mut() {
            Some(extra) => extra.step(slo_back),
            None => slo_back,
        };
        self.host_observes(&out);
        self.last_in = input;
        self.last_out = out;
        self.cycle += 1;
        let Some(sample) = sample else { return };

        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        sample.line[0] = out.o_ma as u64;
        sample.line[1] = ma_at_slave as u64;
        sample.line[2] = slo_from_slave as u64;
        sample.line[3] = input.i_slo as u64;
        sample.decoded[0] = self.master.state() as u64;
        sample.decoded[1] = self.master.slave() as u64;
        sample.decoded[2] = self.master.cdm() as u64;
        sample.decoded[3] = self.master.control_index().unwrap_or(0) as u64;
        sample.decoded[4] = self.chain.slaves()[0].position();
    }

    fn quiet_cycles(&self) -> u64 {
        let busy = self.last_out.o_busy || self.last_out.o_reg_busy;
        let host = match self.host {
            Host::WaitUntil(at) if self.cycle < at => at - self.cycle,
            Host::WaitUntil(_) if !busy => 0,
            Host::WaitUntil(_) | Host::WaitDone | Host::WaitRegDone => u64::MAX,
            Host::Finished(end) => end.saturating_sub(self.cycle),
        };
        let input = In {
            i_slo: self.stuck.unwrap_or(self.slo_at_master),
            ..In::default()
        };
        // The cycle after a request shows its pulse falling.
        if host == 0 || input != self.last_in {
            return 0;
        }
        let slo_back = self.slo_line.quiet(self.chain.slo());
        let extra = self
            .extra_slo
            .as_ref()
            .map_or(u64::MAX, |l| l.quiet(self.slo_line.output()));
        host.min(self.master.quiet(&input))
            .min(self.ma_line.quiet(self.last_out.o_ma))
            .min(self.chain.quiet(self.ma_line.output()))
            .min(slo_back)
            .min(extra)
    }

    fn skip(&mut self, n: u64) {
        self.master.skip(n);
        self.ma_line.skip(n);
        self.chain.skip(n);
        self.slo_line.skip(n);
        if let Some(extra) = self.extra_slo.as_mut() {
            extra.skip(n);
        }
        self.cycle += n;
    }
}
