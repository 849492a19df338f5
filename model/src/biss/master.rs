//! The BiSS-C master, cycle for cycle the same machine as `hdl/rtl/biss_master.v`.

use super::control::{self, Access};
use super::data_crc;
use crate::crc::{BitSerial, BISS_CTRL_CRC4};
use crate::ports::{Port, Ports};
use crate::time::BitClock;
use crate::{ConfigError, Result};

/// The data bits a slave may send (the master's shift register).
pub const DATA_BITS: std::ops::RangeInclusive<u32> = 1..=64;

/// Synchroniser depth on `i_slo` (fixed, as in the RTL).
pub const SYNC_STAGES: u64 = 2;
/// Slaves one master serves in a chain (the RTL packs per-slave parameters 8 bits each).
pub const MAX_SLAVES: usize = 3;
/// Width of `o_delay` and of the delay counter.
pub const DELAY_BITS: u32 = 16;

/// The master's configuration, in cycles; each field is the Verilog parameter
/// of the same name in upper case (per-slave lists are packed 8 bits per
/// slave, slave 0 in bits 7..0).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MasterConfig {
    /// Slaves in the chain, 1 to 3 (`SLAVES`).
    pub slaves: u32,
    /// Data bits of each slave, 1 to 64 (`SLAVE_BITS`).
    pub slave_bits: Vec<u32>,
    /// CRC width of each slave, 1 to 8 (`SLAVE_CRC_WIDTH`); BiSS-C: 6.
    pub slave_crc_width: Vec<u32>,
    /// CRC polynomial of each slave, normal notation without the top term
    /// (`SLAVE_CRC_POLY`); BiSS-C `x^6 + x + 1`: 0x03.
    pub slave_crc_poly: Vec<u64>,
    /// System clocks per MA period, 8 to 4096 (`CLOCKS_PER_BIT`).
    pub clocks_per_bit: u64,
    /// System clocks of each MA high phase (`HIGH_CLOCKS`); with
    /// `low_clocks` it makes up the period. An odd period gives the high
    /// phase the extra cycle ([`crate::time::BitClock`]): the master
    /// samples by the measured delay whatever the split, and the seed's
    /// TMASH and TMASL (> 25 ns) then bind the low phase.
    pub high_clocks: u64,
    /// System clocks of each MA low phase (`LOW_CLOCKS`).
    pub low_clocks: u64,
    /// Longest delay from the second rising MA edge to the ack at the
    /// synchroniser output that the master compensates, cycles (`MAX_DELAY`).
    pub max_delay: u64,
    /// Longest wait for the start bit after the ack, for SLO to go low and
    /// high after the last clock, and for a late ack (`TIMEOUT_CLOCKS`).
    pub timeout_clocks: u64,
    /// Frames with an ack measured at start-up whose mean delay the master
    /// samples by afterwards: 1, 2, 4, 8 or 16 (`CAL_FRAMES`).
    pub cal_frames: u64,
    /// Largest departure of a frame's delay from the mean that is still
    /// sampled by the mean, cycles, below `CLOCKS_PER_BIT / 2`; a larger one
    /// is sampled by its own ack and flagged (`DELAY_TOL`).
    pub delay_tol: u64,
}

/// Whether the control-frame operation `a` addresses the slave at chain
/// position `slave` (its ID is its position): the register access's ID, or
/// a command's IDS bit (every slave on a broadcast).
fn selected(a: &Access, slave: u8) -> bool {
    if a.command {
        control::selects(a.ids, slave)
    } else {
        a.id == slave
    }
}

/// Packs per-slave values 8 bits each, slave 0 lowest (the RTL's parameter form).
pub fn pack8(values: &[u64]) -> u64 {
    values
        .iter()
        .enumerate()
        .fold(0, |acc, (i, v)| acc | ((v & 0xFF) << (8 * i)))
}

impl MasterConfig {
    /// Checks the configuration; field names are those of a scenario's `[master]` table.
    pub fn validate(&self) -> Result<()> {
        let n = self.slaves as usize;
        if !(1..=MAX_SLAVES).contains(&n) {
            return Err(ConfigError::invalid(
                "slaves",
                format!("{n} slaves"),
                "give 1 to 3 slaves",
            ));
        }
        for (field, len) in [
            ("master.bits", self.slave_bits.len()),
            ("master.crc_width", self.slave_crc_width.len()),
            ("master.crc_poly", self.slave_crc_poly.len()),
        ] {
            if len != n {
                return Err(ConfigError::invalid(
                    field,
                    format!("{len} entries for {n} slaves"),
                    "give one entry per slave",
                ));
            }
        }
        for i in 0..n {
            if !DATA_BITS.contains(&self.slave_bits[i]) {
                return Err(ConfigError::invalid(
                    format!("master.bits[{i}]"),
                    format!("{} bits", self.slave_bits[i]),
                    format!(
                        "give {} to {} data bits",
                        DATA_BITS.start(),
                        DATA_BITS.end()
                    ),
                ));
            }
            let w = self.slave_crc_width[i];
            if !(1..=8).contains(&w) {
                return Err(ConfigError::invalid(
                    format!("master.crc_width[{i}]"),
                    format!("{w} bits"),
                    "give a CRC of 1 to 8 bits (BiSS-C: 6)",
                ));
            }
            let p = self.slave_crc_poly[i];
            if p >= 1 << w || p & 1 == 0 {
                return Err(ConfigError::invalid(
                    format!("master.crc_poly[{i}]"),
                    format!("{p:#x} for a {w}-bit CRC"),
                    "give the generator without its top term, with the +1 term (BiSS-C x^6 + x + 1: 0x03)",
                ));
            }
        }
        if self.clocks_per_bit < 8 || self.clocks_per_bit > 4096 {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!("MA is f_sys / {}", self.clocks_per_bit),
                "make f_sys a multiple of MA, 8 to 4096 times (10 MHz needs f_sys of at least 80 MHz)",
            ));
        }
        if self.high_clocks + self.low_clocks != self.clocks_per_bit
            || self.high_clocks == 0
            || self.low_clocks == 0
        {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!(
                    "MA phases of {} + {} cycles for a period of {}",
                    self.high_clocks, self.low_clocks, self.clocks_per_bit
                ),
                "give high and low phases that make up the period",
            ));
        }
        if self.max_delay < 1 || self.max_delay >= 1 << DELAY_BITS {
            return Err(ConfigError::invalid(
                "master.max_delay_ns",
                format!("{} cycles", self.max_delay),
                "give a compensation range of 1 to 65535 system clocks",
            ));
        }
        if !matches!(self.cal_frames, 1 | 2 | 4 | 8 | 16) {
            return Err(ConfigError::invalid(
                "master.cal_frames",
                format!("{}", self.cal_frames),
                "give 1, 2, 4, 8 or 16 start-up frames (a power of two: the mean is a shift)",
            ));
        }
        if self.delay_tol >= self.clocks_per_bit / 2 {
            return Err(ConfigError::invalid(
                "master.delay_tolerance_ns",
                format!(
                    "{} cycles for half an MA period of {}",
                    self.delay_tol,
                    self.clocks_per_bit / 2
                ),
                "give a tolerance below half an MA period (the sample must stay inside its cell)",
            ));
        }
        if self.timeout_clocks < 2 * self.clocks_per_bit || self.timeout_clocks >= 1 << 24 {
            return Err(ConfigError::invalid(
                "master.timeout_us",
                format!("{} cycles", self.timeout_clocks),
                "give a timeout of at least two MA periods and below 2^24 system clocks",
            ));
        }
        Ok(())
    }

    /// The widest slave's data bits (the width of `o_data`).
    pub fn data_width(&self) -> u32 {
        self.slave_bits.iter().copied().max().unwrap_or(1)
    }

    /// Bits after the ack in one frame: start, then per slave CDS, data, nE, nW, CRC.
    pub fn frame_bits(&self) -> u64 {
        1 + (0..self.slaves as usize)
            .map(|i| 1 + self.slave_bits[i] as u64 + 2 + self.slave_crc_width[i] as u64)
            .sum::<u64>()
    }

    /// The Verilog parameters, in vector-header order.
    pub fn parameters(&self) -> Vec<(&'static str, u64)> {
        let bits: Vec<u64> = self.slave_bits.iter().map(|&b| b as u64).collect();
        let widths: Vec<u64> = self.slave_crc_width.iter().map(|&b| b as u64).collect();
        vec![
            ("SLAVES", self.slaves as u64),
            ("SLAVE_BITS", pack8(&bits)),
            ("SLAVE_CRC_WIDTH", pack8(&widths)),
            ("SLAVE_CRC_POLY", pack8(&self.slave_crc_poly)),
            ("CLOCKS_PER_BIT", self.clocks_per_bit),
        ]
        .into_iter()
        .chain(BitClock::parameters(
            self.high_clocks,
            self.low_clocks,
            ["HIGH_CLOCKS", "LOW_CLOCKS"],
        ))
        .chain([
            ("MAX_DELAY", self.max_delay),
            ("TIMEOUT_CLOCKS", self.timeout_clocks),
            ("CAL_FRAMES", self.cal_frames),
            ("DELAY_TOL", self.delay_tol),
        ])
        .collect()
    }
}

/// The master's states; the RTL's `localparam`s carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// MA high, waiting for `i_start`.
    Idle = 0,
    /// Clocking; after the second rising edge, measuring the delay to the ack.
    Ack = 1,
    /// Sampling for the start bit (the slave is busy while SLO stays low).
    Start = 2,
    /// The CDS bit of the current slave.
    Cds = 3,
    /// The data bits of the current slave, MSB first.
    Data = 4,
    /// nE, the error bit (active low).
    Err = 5,
    /// nW, the warning bit (active low).
    Warn = 6,
    /// The inverted CRC of the current slave.
    Crc = 7,
    /// Stopping MA at `!CDM`; waiting for SLO low (the slave's timeout phase).
    Stop = 8,
    /// Waiting for SLO high (the slave is ready again).
    Timeout = 9,
    /// No ack within `MAX_DELAY`: MA stopped high, watching for a late ack.
    NoAck = 10,
}

/// Inputs sampled at one rising edge of the system clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct In {
    /// Host: start one frame (one-cycle pulse; ignored while busy). A
    /// register access runs its frames without it.
    pub i_start: bool,
    /// Line: SLO as it arrives at the master's receiver.
    pub i_slo: bool,
    /// Host: start a register access, one host operation: the master runs
    /// the sync and control frames by itself (one-cycle pulse; ignored while
    /// `o_reg_busy`).
    pub i_reg_start: bool,
    /// Host: the access is a write.
    pub i_reg_write: bool,
    /// Host: slave ID (its position in the chain, 0 nearest the master's SLO input).
    pub i_reg_id: u8,
    /// Host: register address, 7 bits.
    pub i_reg_addr: u8,
    /// Host: data to write.
    pub i_reg_wdata: u8,
    /// Host: send a BiSS-C command (`CTS = 0`), one host operation like a
    /// register access, reported on `o_reg_done`/`o_reg_err` (one-cycle
    /// pulse; ignored while `o_reg_busy`; `i_reg_start` wins a tie).
    pub i_cmd_start: bool,
    /// Host: the slave-select bits IDS (bit `i` = ID `i`; 0 = broadcast).
    pub i_cmd_ids: u8,
    /// Host: the 2-bit command.
    pub i_cmd_code: u8,
}

/// Registered outputs after one rising edge of the system clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Out {
    /// Line: MA to the slaves.
    pub o_ma: bool,
    /// Host: a frame is under way.
    pub o_busy: bool,
    /// Host: one-cycle pulse at the end of every frame (or refused start).
    pub o_done: bool,
    /// With `o_done`: SLO was low at the start; nothing was clocked.
    pub o_err_line: bool,
    /// With `o_done`: no ack at all (slave absent, SLO stuck high, open line).
    pub o_err_ack: bool,
    /// With `o_done`: the ack came later than `MAX_DELAY` (cable too long).
    pub o_err_delay: bool,
    /// With `o_done`: no start bit within `TIMEOUT_CLOCKS` of the ack.
    pub o_err_start: bool,
    /// With `o_done`: SLO did not return high within `TIMEOUT_CLOCKS`.
    pub o_err_timeout: bool,
    /// The last measured delay, edge 2 to the ack at the synchroniser, cycles.
    pub o_delay: u64,
    /// The mean delay of the start-up frames, once `CAL_FRAMES` were measured (0 before).
    pub o_delay_mean: u64,
    /// With `o_done`: this frame's delay departed from the mean by more than
    /// `DELAY_TOL`; it was sampled by its own ack.
    pub o_err_drift: bool,
    /// One-cycle pulse: one slave's result is on the outputs below.
    pub o_slave_valid: bool,
    /// Which slave (chain position).
    pub o_slave_index: u8,
    /// Its data, right-aligned.
    pub o_data: u64,
    /// Its CRC did not match (data, nE, nW or CRC corrupted).
    pub o_crc_err: bool,
    /// Its error bit was active (nE = 0).
    pub o_error: bool,
    /// Its warning bit was active (nW = 0).
    pub o_warning: bool,
    /// Its CDS bit.
    pub o_cds: bool,
    /// Host: a register access is pending or under way.
    pub o_reg_busy: bool,
    /// Host: one-cycle pulse at the end of a register access (with `o_done`).
    pub o_reg_done: bool,
    /// With `o_reg_done`: the access failed (not acknowledged, CRC-4, echo, frame error).
    pub o_reg_err: bool,
    /// With `o_reg_done`: the register's value (read) or its echo (write).
    pub o_reg_rdata: u8,
    /// With `o_reg_done`: the CRC-4 of the slave's answer did not match.
    pub o_reg_crc_err: bool,
}

impl Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_start as u64;
        dst[1] = self.i_slo as u64;
        dst[2] = self.i_reg_start as u64;
        dst[3] = self.i_reg_write as u64;
        dst[4] = self.i_reg_id as u64;
        dst[5] = self.i_reg_addr as u64;
        dst[6] = self.i_reg_wdata as u64;
        dst[7] = self.i_cmd_start as u64;
        dst[8] = self.i_cmd_ids as u64;
        dst[9] = self.i_cmd_code as u64;
    }
}

impl Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        let v = [
            self.o_ma as u64,
            self.o_busy as u64,
            self.o_done as u64,
            self.o_err_line as u64,
            self.o_err_ack as u64,
            self.o_err_delay as u64,
            self.o_err_start as u64,
            self.o_err_timeout as u64,
            self.o_delay,
            self.o_slave_valid as u64,
            self.o_slave_index as u64,
            self.o_data,
            self.o_crc_err as u64,
            self.o_error as u64,
            self.o_warning as u64,
            self.o_cds as u64,
            self.o_reg_busy as u64,
            self.o_reg_done as u64,
            self.o_reg_err as u64,
            self.o_reg_rdata as u64,
            self.o_reg_crc_err as u64,
            self.o_delay_mean,
            self.o_err_drift as u64,
        ];
        dst[..v.len()].copy_from_slice(&v);
    }
}

/// Every register of the master except the CRC shift registers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Regs {
    state: State,
    cnt: u64,
    delay_cnt: u64,
    smp_cnt: u64,
    ma: bool,
    ma_cnt: u64,
    ma_run: bool,
    ma_edges: u8,
    ma_stop: bool,
    ma_stop_level: bool,
    slo_meta: bool,
    slo_sync: bool,
    slave: u8,
    bit_cnt: u32,
    data: u64,
    crc_bad: bool,
    nerr: bool,
    nwarn: bool,
    cds: bool,
    e_delay: bool,
    e_start: bool,
    e_drift: bool,
    cal_cnt: u64,
    cal_sum: u64,
    delay_mean: u64,
    frame_cds: bool,
    frame_sel: bool,
    frame_crc_bad: bool,
    cdm: bool,
    zeros: u32,
    reg_pending: bool,
    ctl_active: bool,
    ctl_k: u32,
    acc: Access,
    reg_bad: bool,
    rdata: u8,
}

/// The BiSS-C master. One [`Master::step`] is one rising edge of the system clock.
#[derive(Debug, Clone)]
pub struct Master {
    cfg: MasterConfig,
    r: Regs,
    crc: BitSerial,
    crc4_tx: BitSerial,
    crc4_rx: BitSerial,
    crcs: Vec<BitSerial>,
    raw: Vec<bool>,
    out: Out,
}

impl Master {
    /// A master in its reset state.
    pub fn new(cfg: MasterConfig) -> Result<Self> {
        cfg.validate()?;
        let crcs: Vec<BitSerial> = (0..cfg.slaves as usize)
            .map(|i| BitSerial::new(&data_crc(cfg.slave_crc_width[i], cfg.slave_crc_poly[i])))
            .collect();
        Ok(Master {
            r: Regs {
                state: State::Idle,
                cnt: 0,
                delay_cnt: 0,
                smp_cnt: 0,
                ma: true,
                ma_cnt: 0,
                ma_run: false,
                ma_edges: 0,
                ma_stop: false,
                ma_stop_level: true,
                slo_meta: true,
                slo_sync: true,
                slave: 0,
                bit_cnt: 0,
                data: 0,
                crc_bad: false,
                nerr: true,
                nwarn: true,
                cds: false,
                e_delay: false,
                e_start: false,
                e_drift: false,
                cal_cnt: 0,
                cal_sum: 0,
                delay_mean: 0,
                frame_cds: false,
                frame_sel: false,
                frame_crc_bad: false,
                cdm: false,
                zeros: 0,
                reg_pending: false,
                ctl_active: false,
                ctl_k: 0,
                acc: Access::default(),
                reg_bad: false,
                rdata: 0,
            },
            crc: crcs[0].clone(),
            crc4_tx: BitSerial::new(&BISS_CTRL_CRC4),
            crc4_rx: BitSerial::new(&BISS_CTRL_CRC4),
            crcs,
            raw: Vec::new(),
            out: Out {
                o_ma: true,
                ..Out::default()
            },
            cfg,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &MasterConfig {
        &self.cfg
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        self.r.state
    }

    /// The slave being decoded.
    pub fn slave(&self) -> u8 {
        self.r.slave
    }

    /// The CDM bit of the current (or next) frame.
    pub fn cdm(&self) -> bool {
        self.r.cdm
    }

    /// Index of the control bit in the current frame, if a control frame is running.
    pub fn control_index(&self) -> Option<u32> {
        self.r.ctl_active.then_some(self.r.ctl_k)
    }

    /// Every bit sampled since the last start (start bit first), for transcripts.
    pub fn sampled_bits(&self) -> &[bool] {
        &self.raw
    }

    /// The input ports, in vector order.
    pub fn input_ports(&self) -> Vec<Port> {
        vec![
            Port::new("i_start", 1),
            Port::new("i_slo", 1).idle_high(),
            Port::new("i_reg_start", 1),
            Port::new("i_reg_write", 1),
            Port::new("i_reg_id", 3),
            Port::new("i_reg_addr", 7),
            Port::new("i_reg_wdata", 8),
            Port::new("i_cmd_start", 1),
            Port::new("i_cmd_ids", 8),
            Port::new("i_cmd_code", 2),
        ]
    }

    /// The output ports, in vector order.
    pub fn output_ports(&self) -> Vec<Port> {
        vec![
            Port::new("o_ma", 1),
            Port::new("o_busy", 1),
            Port::new("o_done", 1),
            Port::new("o_err_line", 1),
            Port::new("o_err_ack", 1),
            Port::new("o_err_delay", 1),
            Port::new("o_err_start", 1),
            Port::new("o_err_timeout", 1),
            Port::new("o_delay", DELAY_BITS),
            Port::new("o_slave_valid", 1),
            Port::new("o_slave_index", 2),
            Port::new("o_data", self.cfg.data_width()).width_from("DATA_W"),
            Port::new("o_crc_err", 1),
            Port::new("o_error", 1),
            Port::new("o_warning", 1),
            Port::new("o_cds", 1),
            Port::new("o_reg_busy", 1),
            Port::new("o_reg_done", 1),
            Port::new("o_reg_err", 1),
            Port::new("o_reg_rdata", 8),
            Port::new("o_reg_crc_err", 1),
            Port::new("o_delay_mean", DELAY_BITS),
            Port::new("o_err_drift", 1),
        ]
    }

    /// How many of the next steps with `input` only count (fast-forward):
    /// idle without a request, or waiting out the slave's timeout with SLO
    /// steady, MA stopped or between two of its edges. 0 while a pulse is
    /// up, a request or start is in, or the SLO synchroniser has not settled.
    pub fn quiet(&self, input: &In) -> u64 {
        let (c, o) = (&self.r, &self.out);
        let pulse = o.o_done
            || o.o_err_line
            || o.o_err_ack
            || o.o_err_delay
            || o.o_err_start
            || o.o_err_timeout
            || o.o_slave_valid
            || o.o_reg_done
            || o.o_reg_err
            || o.o_reg_crc_err
            || o.o_err_drift;
        let request = input.i_start || input.i_reg_start || input.i_cmd_start;
        if pulse
            || request
            || c.slo_meta != input.i_slo
            || c.slo_sync != input.i_slo
            || (!c.ma_run && c.ma_cnt != 0)
        {
            return 0;
        }
        let ma = if c.ma_run { c.ma_cnt } else { u64::MAX };
        let timeout = self.cfg.timeout_clocks;
        let state = match c.state {
            State::Idle if c.reg_pending || c.ctl_active => 0,
            State::Idle => u64::MAX,
            State::Stop | State::NoAck if c.slo_sync => timeout.saturating_sub(c.cnt),
            State::Timeout if !c.slo_sync || c.ma_run => timeout.saturating_sub(c.cnt),
            _ => 0,
        };
        state.min(ma)
    }

    /// The same as `n` steps with the last input, for `n` up to [`Master::quiet`].
    pub fn skip(&mut self, n: u64) {
        let r = &mut self.r;
        if r.ma_run {
            r.ma_cnt -= n;
        }
        if matches!(r.state, State::Stop | State::NoAck | State::Timeout) {
            r.cnt += n;
        }
    }

    /// One rising edge of the system clock: every register takes its next
    /// value, computed from the registers' present values and `input`.
    pub fn step(&mut self, input: &In) -> Out {
        let cfg = &self.cfg;
        let c = self.r;
        let mut n = c;
        let (high, low) = (cfg.high_clocks, cfg.low_clocks);
        let period = cfg.clocks_per_bit;
        let mut o = Out {
            o_done: false,
            o_err_line: false,
            o_err_ack: false,
            o_err_delay: false,
            o_err_start: false,
            o_err_timeout: false,
            o_slave_valid: false,
            o_reg_done: false,
            o_reg_err: false,
            o_reg_crc_err: false,
            o_err_drift: false,
            ..self.out
        };

        // MA generator: toggles after HIGH_CLOCKS high and LOW_CLOCKS low
        // cycles while running; stops at a phase boundary where MA equals
        // the requested stop level.
        if c.ma_run {
            if c.ma_cnt == 0 {
                if c.ma_stop && c.ma == c.ma_stop_level {
                    n.ma_run = false;
                } else {
                    n.ma = !c.ma;
                    n.ma_cnt = if c.ma { low - 1 } else { high - 1 };
                    if !c.ma {
                        n.ma_edges = (c.ma_edges + 1).min(2);
                        if c.ma_edges == 1 {
                            n.delay_cnt = 1;
                        }
                    }
                }
            } else {
                n.ma_cnt = c.ma_cnt - 1;
            }
        } else if c.ma_cnt != 0 {
            // Stopped: counting out the high level that ends a frame.
            n.ma_cnt = c.ma_cnt - 1;
        }

        // Bit sampling: once per MA period, in the middle of each cell as it arrives.
        let sampling = matches!(
            c.state,
            State::Start | State::Cds | State::Data | State::Err | State::Warn | State::Crc
        );
        let sample = sampling && c.smp_cnt == 0;
        if sampling {
            n.smp_cnt = if c.smp_cnt == 0 {
                period - 1
            } else {
                c.smp_cnt - 1
            };
        }
        let b = c.slo_sync;
        if sample && (c.state != State::Start || b) {
            self.raw.push(b);
        }
        let mut finish: Option<(bool, bool)> = None; // (err_ack, err_timeout) of the finishing step

        match c.state {
            State::Idle => {
                // A register access starts its own frames, back to back.
                if input.i_start || c.reg_pending || c.ctl_active {
                    if c.slo_sync {
                        n.state = State::Ack;
                        n.ma = false;
                        n.ma_cnt = low - 1;
                        n.ma_run = true;
                        n.ma_edges = 0;
                        n.ma_stop = false;
                        n.delay_cnt = 0;
                        n.e_delay = false;
                        n.e_start = false;
                        n.e_drift = false;
                        n.slave = 0;
                        n.frame_cds = true;
                        n.frame_sel = false;
                        n.frame_crc_bad = false;
                        o.o_busy = true;
                        self.raw.clear();
                    } else {
                        o.o_done = true;
                        o.o_err_line = true;
                        self.control(&c, &mut n, &mut o, false);
                    }
                }
            }
            State::Ack => {
                if c.ma_edges == 2 {
                    if !c.slo_sync {
                        n.state = State::Start;
                        n.cnt = 0;
                        o.o_delay = c.delay_cnt;
                        self.calibrate(&c, &mut n);
                    } else if c.delay_cnt == cfg.max_delay {
                        n.state = State::NoAck;
                        n.ma_stop = true;
                        n.ma_stop_level = true;
                        n.cnt = 0;
                    } else {
                        n.delay_cnt = c.delay_cnt + 1;
                    }
                }
            }
            State::Start => {
                n.cnt = c.cnt + 1;
                if sample && b {
                    n.state = State::Cds;
                } else if c.cnt == cfg.timeout_clocks {
                    n.state = State::Timeout;
                    n.e_start = true;
                    n.ma_stop = true;
                    n.ma_stop_level = true;
                    n.cnt = 0;
                }
            }
            State::Cds => {
                if sample {
                    let i = c.slave as usize;
                    n.cds = b;
                    if c.ctl_active && selected(&c.acc, c.slave) {
                        n.frame_cds = c.frame_cds && b;
                        n.frame_sel = true;
                    }
                    n.state = State::Data;
                    n.bit_cnt = cfg.slave_bits[i] - 1;
                    n.data = 0;
                    self.crc = self.crcs[i].clone();
                    self.crc.reset();
                }
            }
            State::Data => {
                if sample {
                    let bits = cfg.slave_bits[c.slave as usize];
                    let mask = if bits == 64 {
                        u64::MAX
                    } else {
                        (1u64 << bits) - 1
                    };
                    n.data = ((c.data << 1) | b as u64) & mask;
                    self.crc.push(b);
                    if c.bit_cnt == 0 {
                        n.state = State::Err;
                    } else {
                        n.bit_cnt = c.bit_cnt - 1;
                    }
                }
            }
            State::Err => {
                if sample {
                    n.nerr = b;
                    self.crc.push(b);
                    n.state = State::Warn;
                }
            }
            State::Warn => {
                if sample {
                    n.nwarn = b;
                    self.crc.push(b);
                    n.state = State::Crc;
                    n.bit_cnt = cfg.slave_crc_width[c.slave as usize] - 1;
                    n.crc_bad = false;
                }
            }
            State::Crc => {
                if sample {
                    let w = cfg.slave_crc_width[c.slave as usize];
                    let msb = (self.crc.register() >> (w - 1)) & 1 == 1;
                    // The CRC is sent inverted: the wire bit must be the complement of the remainder's MSB.
                    let bad = c.crc_bad || b == msb;
                    n.crc_bad = bad;
                    self.crc.push(msb); // shifts the remainder without feedback
                    if c.bit_cnt == 0 {
                        o.o_slave_valid = true;
                        o.o_slave_index = c.slave;
                        o.o_data = c.data;
                        o.o_crc_err = bad;
                        o.o_error = !c.nerr;
                        o.o_warning = !c.nwarn;
                        o.o_cds = c.cds;
                        if c.ctl_active && selected(&c.acc, c.slave) {
                            n.frame_crc_bad = c.frame_crc_bad || bad;
                        }
                        if (c.slave as u32) + 1 < cfg.slaves {
                            n.slave = c.slave + 1;
                            n.state = State::Cds;
                        } else {
                            n.state = State::Stop;
                            n.ma_stop = true;
                            n.ma_stop_level = !c.cdm;
                            n.cnt = 0;
                        }
                    } else {
                        n.bit_cnt = c.bit_cnt - 1;
                    }
                }
            }
            State::Stop => {
                n.cnt = c.cnt + 1;
                if !c.slo_sync {
                    n.state = State::Timeout;
                } else if c.cnt >= cfg.timeout_clocks {
                    finish = Some((false, true));
                }
            }
            State::Timeout => {
                n.cnt = c.cnt + 1;
                if c.slo_sync && !c.ma_run {
                    finish = Some((false, false));
                } else if c.cnt >= cfg.timeout_clocks {
                    finish = Some((false, true));
                }
            }
            State::NoAck => {
                n.cnt = c.cnt + 1;
                if !c.slo_sync {
                    n.e_delay = true;
                    n.state = State::Timeout;
                } else if c.cnt >= cfg.timeout_clocks {
                    finish = Some((true, false));
                }
            }
        }

        // A frame ends with MA high for at least a high phase (seed 001,
        // BiSS-C: TMASH > 25 ns), so that the next frame's first falling
        // edge, in the cycle after o_done at the earliest, never follows a
        // short high level: a frame that stopped MA low (CDM = 1) raises it
        // first and ends HIGH_CLOCKS cycles later (o_done then).
        if finish.is_some() && (!c.ma || c.ma_cnt != 0) {
            if !c.ma {
                n.ma = true;
                n.ma_cnt = high - 1;
            }
            finish = None;
        }

        if let Some((err_ack, err_timeout)) = finish {
            n.state = State::Idle;
            n.ma = true;
            n.ma_run = false;
            o.o_busy = false;
            o.o_done = true;
            o.o_err_ack = err_ack;
            o.o_err_delay = c.e_delay;
            o.o_err_start = c.e_start;
            o.o_err_timeout = err_timeout;
            o.o_err_drift = c.e_drift;
            let frame_ok = !(err_ack || err_timeout || c.e_delay || c.e_start);
            self.control(&c, &mut n, &mut o, frame_ok);
        }

        // Register requests are taken whenever no access is pending.
        if (input.i_reg_start || input.i_cmd_start) && !c.reg_pending && !c.ctl_active {
            n.reg_pending = true;
            n.acc = if input.i_reg_start {
                Access {
                    write: input.i_reg_write,
                    id: input.i_reg_id & 7,
                    addr: input.i_reg_addr & 0x7F,
                    wdata: input.i_reg_wdata,
                    ..Access::default()
                }
            } else {
                Access {
                    command: true,
                    ids: input.i_cmd_ids,
                    code: input.i_cmd_code & 3,
                    ..Access::default()
                }
            };
            o.o_reg_busy = true;
        }

        n.slo_sync = c.slo_meta;
        n.slo_meta = input.i_slo;
        o.o_ma = n.ma;
        o.o_delay_mean = n.delay_mean;
        self.r = n;
        self.out = o;
        o
    }

    /// The first sample of a frame, from its ack: during start-up the
    /// `CAL_FRAMES` delays are summed and each frame is sampled by its own
    /// ack; then by the mean (`first + mean - delay`, the cell middles of an
    /// ack at the mean), unless this ack departs from it by more than
    /// `DELAY_TOL`: that frame is sampled by its own ack and flagged.
    /// `biss_master` does the comparison in the two cycles after the ack
    /// (timing at 80 MHz); the first sample is further away than that, so
    /// the sample times and every output are the same.
    fn calibrate(&self, c: &Regs, n: &mut Regs) {
        let first = self.cfg.clocks_per_bit / 2 + self.cfg.clocks_per_bit - 1;
        let d = c.delay_cnt;
        n.smp_cnt = first;
        if c.cal_cnt < self.cfg.cal_frames {
            n.cal_sum = c.cal_sum + d;
            n.cal_cnt = c.cal_cnt + 1;
            if n.cal_cnt == self.cfg.cal_frames {
                n.delay_mean = n.cal_sum >> self.cfg.cal_frames.trailing_zeros();
            }
        } else if d.abs_diff(c.delay_mean) <= self.cfg.delay_tol {
            n.smp_cnt = first + c.delay_mean - d;
        } else {
            n.e_drift = true;
        }
    }

    /// Whether the start-up delay mean is in use.
    pub fn calibrated(&self) -> bool {
        self.r.cal_cnt == self.cfg.cal_frames
    }

    /// The control-frame sequencer, run once at the end of every frame (and
    /// at a refused start): it takes the CDS bit the frame brought back and
    /// chooses the next CDM. Only frames that completed count as sent: the
    /// slave may not have seen the CDM of a failed one.
    fn control(&mut self, c: &Regs, n: &mut Regs, o: &mut Out, frame_ok: bool) {
        let zeros = match (frame_ok, c.cdm) {
            (true, true) => 0,
            (true, false) => (c.zeros + 1).min(control::SYNC_ZEROS),
            (false, _) => c.zeros,
        };
        n.zeros = zeros;
        n.cdm = false;
        if c.ctl_active {
            let k = c.ctl_k;
            let a = c.acc;
            let cds = c.frame_sel && c.frame_cds;
            let mut end: Option<bool> = None; // Some(error)
            if !frame_ok || c.frame_crc_bad {
                end = Some(true);
            } else if a.command {
                // IDA from every selected slave, then the echo of EX.
                match k {
                    control::K_IDA if !cds => end = Some(true),
                    control::K_CMD_LAST => end = Some(!cds),
                    _ => {}
                }
            } else {
                match k {
                    control::K_W if cds == a.write => end = Some(true),
                    control::K_S2 if cds != a.write => end = Some(true),
                    control::K_DATA => {
                        if !cds {
                            end = Some(true);
                        }
                        self.crc4_rx.reset();
                    }
                    20..=27 => {
                        n.rdata = (c.rdata << 1) | cds as u8;
                        self.crc4_rx.push(cds);
                    }
                    28..=31 => {
                        let msb = (self.crc4_rx.register() >> 3) & 1 == 1;
                        if cds == msb {
                            n.reg_bad = true;
                        }
                        self.crc4_rx.push(msb);
                    }
                    control::K_LAST => {
                        let bad = c.reg_bad || cds || (a.write && c.rdata != a.wdata);
                        end = Some(bad);
                    }
                    _ => {}
                }
            }
            match end {
                Some(err) => {
                    n.ctl_active = false;
                    o.o_reg_done = true;
                    o.o_reg_err = err;
                    o.o_reg_crc_err = k == control::K_LAST && c.reg_bad;
                    o.o_reg_rdata = c.rdata;
                    o.o_reg_busy = false;
                }
                None => {
                    let k = k + 1;
                    n.ctl_k = k;
                    n.cdm = self.cdm_bit(&a, k);
                }
            }
        } else if c.reg_pending && !frame_ok {
            // A sync frame failed: the line cannot carry the access.
            n.reg_pending = false;
            o.o_reg_done = true;
            o.o_reg_err = true;
            o.o_reg_rdata = c.rdata;
            o.o_reg_busy = false;
        } else if c.reg_pending && zeros >= control::SYNC_ZEROS {
            n.reg_pending = false;
            n.ctl_active = true;
            n.ctl_k = 0;
            n.cdm = true;
            n.reg_bad = false;
            n.rdata = 0;
            self.crc4_tx.reset();
            self.crc4_rx.reset();
        }
    }

    /// CDM bit `k` of the access `a`; pushes the bits the CRC-4 covers.
    fn cdm_bit(&mut self, a: &Access, k: u32) -> bool {
        let tx = &mut self.crc4_tx;
        let covered = |tx: &mut BitSerial, bit: bool| {
            tx.push(bit);
            bit
        };
        let crc_out = |tx: &mut BitSerial| {
            let msb = (tx.register() >> 3) & 1 == 1;
            tx.push(msb);
            !msb
        };
        if a.command {
            return match k {
                1 => covered(tx, false),
                2..=9 => covered(tx, (a.ids >> (9 - k)) & 1 == 1),
                10..=11 => covered(tx, (a.code >> (11 - k)) & 1 == 1),
                12..=15 => crc_out(tx),
                control::K_EX => true,
                _ => false,
            };
        }
        match k {
            1 => covered(tx, true),
            2..=4 => covered(tx, (a.id >> (4 - k)) & 1 == 1),
            5..=11 => covered(tx, (a.addr >> (11 - k)) & 1 == 1),
            12..=15 => crc_out(tx),
            control::K_R => !a.write,
            control::K_W => a.write,
            control::K_S2 => {
                tx.reset();
                true
            }
            19..=26 => a.write && covered(tx, (a.wdata >> (26 - k)) & 1 == 1),
            27..=30 => a.write && crc_out(tx),
            _ => false,
        }
    }
}
