//! BiSS-C slaves (encoders) and the chain that puts their frames on SLO.

use super::control;
use super::data_crc;
use crate::crc::BISS_CTRL_CRC4;
use crate::line::DelayLine;
use crate::{ConfigError, Result};

/// One slave's configuration, in cycles.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SlaveConfig {
    /// Data bits, 1 to 64, sent MSB first.
    pub bits: u32,
    /// CRC width (BiSS-C: 6).
    pub crc_width: u32,
    /// CRC polynomial without its top term (BiSS-C: 0x03).
    pub crc_poly: u64,
    /// `t_busy`: cycles from the ack to the earliest rising MA edge that
    /// sends the start bit.
    pub busy_clocks: u64,
    /// BiSS timeout: cycles without an MA edge after which the slave takes
    /// the CDM bit and returns to idle.
    pub timeout_clocks: u64,
    /// The slave's ID for register access (0 to 7).
    pub id: u8,
    /// Register bank, addresses 0 to 127.
    pub registers: Vec<u8>,
}

impl SlaveConfig {
    /// Checks the configuration; `prefix` is the scenario table (`slaves[1]`).
    pub fn validate(&self, prefix: &str) -> Result<()> {
        let range = super::master::DATA_BITS;
        if !range.contains(&self.bits) {
            return Err(ConfigError::invalid(
                format!("{prefix}.bits"),
                format!("{} bits", self.bits),
                format!("give {} to {} data bits", range.start(), range.end()),
            ));
        }
        if !(1..=8).contains(&self.crc_width)
            || self.crc_poly >= 1 << self.crc_width
            || self.crc_poly & 1 == 0
        {
            return Err(ConfigError::invalid(
                format!("{prefix}.crc_poly"),
                format!("{:#x} for a {}-bit CRC", self.crc_poly, self.crc_width),
                "give a 1- to 8-bit CRC and its generator without the top term (BiSS-C: crc_width = 6, crc_poly = 0x03)",
            ));
        }
        if self.timeout_clocks == 0 {
            return Err(ConfigError::invalid(
                format!("{prefix}.timeout_us"),
                "zero",
                "give the slave's BiSS timeout, e.g. 16 µs",
            ));
        }
        if self.id > 7 {
            return Err(ConfigError::invalid(
                format!("{prefix}.id"),
                format!("{}", self.id),
                "give an ID of 0 to 7",
            ));
        }
        if self.registers.len() > 128 {
            return Err(ConfigError::invalid(
                format!("{prefix}.registers"),
                format!("{} values", self.registers.len()),
                "give at most 128 registers",
            ));
        }
        Ok(())
    }
}

/// One slave: its position, its flags, its register bank and its side of
/// the control frame.
#[derive(Debug, Clone)]
pub struct Slave {
    cfg: SlaveConfig,
    position: u64,
    error: bool,
    warning: bool,
    flips: Vec<u32>,
    registers: [u8; 128],
    // Control frame, slave side.
    zeros: u32,
    ctl_k: Option<u32>,
    addr_bits: Vec<bool>,
    crc_bits: Vec<bool>,
    accepted: bool,
    read: bool,
    tx: Vec<bool>,
    wbits: Vec<bool>,
    cds_next: bool,
    faults: ControlFaults,
    last_section: Vec<bool>,
    command: bool,
    executed: Vec<u8>,
}

impl Slave {
    /// A slave at rest holding position 0, no error, no warning.
    pub fn new(cfg: SlaveConfig) -> Result<Self> {
        cfg.validate("slave")?;
        let mut registers = [0u8; 128];
        registers[..cfg.registers.len()].copy_from_slice(&cfg.registers);
        Ok(Slave {
            cfg,
            position: 0,
            error: false,
            warning: false,
            flips: Vec::new(),
            registers,
            zeros: 0,
            ctl_k: None,
            addr_bits: Vec::new(),
            crc_bits: Vec::new(),
            accepted: false,
            read: false,
            tx: Vec::new(),
            wbits: Vec::new(),
            cds_next: false,
            faults: ControlFaults::default(),
            last_section: Vec::new(),
            command: false,
            executed: Vec::new(),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &SlaveConfig {
        &self.cfg
    }

    /// The value the next latch stores (masked to the width).
    pub fn set_position(&mut self, position: u64) {
        let mask = if self.cfg.bits == 64 {
            u64::MAX
        } else {
            (1u64 << self.cfg.bits) - 1
        };
        self.position = position & mask;
    }

    /// The position the slave holds.
    pub fn position(&self) -> u64 {
        self.position
    }

    /// The error and warning conditions the next frame reports (nE = !error, nW = !warning).
    pub fn set_flags(&mut self, error: bool, warning: bool) {
        self.error = error;
        self.warning = warning;
    }

    /// Bits of the next frame's section to corrupt on the wire: 0 is the
    /// data MSB, `bits` is nE, `bits + 1` nW, `bits + 2 ..` the CRC field.
    pub fn set_flips(&mut self, flips: Vec<u32>) {
        self.flips = flips;
    }

    /// Faults of the control side, each spent on its first occasion.
    pub fn set_control_faults(&mut self, faults: ControlFaults) {
        self.faults = faults;
    }

    /// The commands (`CTS = 0`) this slave carried out, in order.
    pub fn executed_commands(&self) -> &[u8] {
        &self.executed
    }

    /// Register `addr` of the bank.
    pub fn register(&self, addr: u8) -> u8 {
        self.registers[(addr & 0x7F) as usize]
    }

    /// The section sent in the last frame (CDS first), as it left the slave.
    pub fn last_section(&self) -> &[bool] {
        &self.last_section
    }

    /// The slave's section of the frame, as sent: CDS, data MSB first, nE,
    /// nW, the CRC inverted MSB first, then the requested corruptions.
    pub fn section(&mut self) -> Vec<bool> {
        let n = self.cfg.bits;
        let mut covered: Vec<bool> = (0..n)
            .rev()
            .map(|i| (self.position >> i) & 1 == 1)
            .collect();
        covered.push(!self.error);
        covered.push(!self.warning);
        let alg = data_crc(self.cfg.crc_width, self.cfg.crc_poly);
        let crc = alg.checksum_bits(&covered);
        let mut bits = vec![self.cds_next];
        bits.extend(&covered);
        bits.extend(alg.wire_bits(crc));
        for &f in &self.flips {
            if let Some(b) = bits.get_mut(1 + f as usize) {
                *b = !*b;
            }
        }
        self.flips.clear();
        self.last_section = bits.clone();
        bits
    }

    /// Takes the CDM bit of the frame that just timed out and prepares the
    /// CDS bit of the next frame (layout in [`control`]).
    pub fn take_cdm(&mut self, cdm: bool) {
        let mut bit = cdm;
        if let (Some(k), Some(at)) = (self.ctl_k.map(|k| k + 1), self.faults.cdm_flip_at) {
            if k == at {
                bit = !bit;
                self.faults.cdm_flip_at = None;
            }
        }
        let zeros_before = self.zeros;
        self.zeros = if bit {
            0
        } else {
            (self.zeros + 1).min(control::SYNC_ZEROS)
        };
        let mut cds = false;
        match self.ctl_k {
            None => {
                if bit && zeros_before >= control::SYNC_ZEROS {
                    self.ctl_k = Some(0);
                    self.addr_bits.clear();
                    self.crc_bits.clear();
                    self.wbits.clear();
                    self.accepted = false;
                }
            }
            Some(prev) => {
                let k = prev + 1;
                self.ctl_k = Some(k);
                let crc4 = &BISS_CTRL_CRC4;
                match k {
                    1..=11 => self.addr_bits.push(bit),
                    12..=15 => {
                        self.crc_bits.push(bit);
                        if k == 15 {
                            let crc_ok = crc4.crc_from_wire_bits(&self.crc_bits)
                                == Some(crc4.checksum_bits(&self.addr_bits));
                            self.command = !self.addr_bits[0];
                            if self.command {
                                let ids = self.addr_bits[1..9]
                                    .iter()
                                    .fold(0u8, |a, &b| (a << 1) | b as u8);
                                self.accepted = crc_ok && control::selects(ids, self.cfg.id);
                                cds = self.accepted; // IDA
                            } else {
                                let id = self.addr_bits[1..4]
                                    .iter()
                                    .fold(0u8, |a, &b| (a << 1) | b as u8);
                                self.accepted = crc_ok && id == self.cfg.id;
                            }
                        }
                    }
                    control::K_IDA..=control::K_CMD_LAST if self.command => {
                        if k == control::K_EX {
                            cds = self.accepted && bit; // the EX echo
                            if self.accepted && bit {
                                let code = self.addr_bits[9..11]
                                    .iter()
                                    .fold(0u8, |a, &b| (a << 1) | b as u8);
                                self.executed.push(code);
                            }
                        } else if k == control::K_CMD_LAST {
                            self.ctl_k = None;
                        }
                    }
                    control::K_R => {
                        self.read = bit;
                        cds = self.accepted && bit;
                    }
                    control::K_W => {
                        if self.read == bit {
                            self.accepted = false; // R W must be 1 0 or 0 1
                        }
                        cds = self.accepted && bit;
                        if self.accepted && self.read {
                            let value = self.register(self.addr());
                            let d = control::data_bits(value);
                            let mut crc = crc4.wire_bits(crc4.checksum_bits(&d));
                            if let Some(b) = self.faults.cds_crc_flip.take() {
                                crc[b as usize] = !crc[b as usize];
                            }
                            self.tx = d;
                            self.tx.extend(crc);
                        }
                    }
                    control::K_S2 => {
                        cds = self.accepted && bit;
                        if !self.read {
                            self.tx.clear();
                        }
                        if self.accepted && !self.read {
                            // A wrong echo carries its own right CRC-4, so
                            // only the comparison with the written byte sees it.
                            if let Some(echo) = self.faults.cds_write_echo.take() {
                                let d = control::data_bits(echo);
                                self.tx = crc4.wire_bits(crc4.checksum_bits(&d));
                                self.tx.splice(0..0, d);
                            }
                        }
                    }
                    19..=30 => {
                        if self.read {
                            cds = self.accepted && self.tx[(k - 19) as usize];
                        } else if let Some(&echo) = self.tx.get((k - 19) as usize) {
                            // The wrong echo: the slave stores nothing.
                            cds = self.accepted && echo;
                        } else {
                            self.wbits.push(bit);
                            cds = self.accepted && bit;
                            if k == 30 && self.accepted {
                                let (d, c) = self.wbits.split_at(8);
                                if crc4.crc_from_wire_bits(c) == Some(crc4.checksum_bits(d)) {
                                    let value = d.iter().fold(0u8, |a, &b| (a << 1) | b as u8);
                                    let addr = self.addr();
                                    self.registers[addr as usize] = value;
                                }
                            }
                        }
                    }
                    _ => self.ctl_k = None, // the stop bit ends the frame
                }
                if self.ctl_k.is_some() && self.zeros >= control::SYNC_ZEROS {
                    self.ctl_k = None; // 14 zeros cancel a control frame
                }
            }
        }
        self.cds_next = cds;
    }

    fn addr(&self) -> u8 {
        self.addr_bits[4..11]
            .iter()
            .fold(0u8, |a, &b| (a << 1) | b as u8)
    }
}

/// Faults of a slave's side of the control frame, each spent on its first
/// occasion.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ControlFaults {
    /// The slave misreads CDM bit `k` of its first control frame.
    pub cdm_flip_at: Option<u32>,
    /// The slave answers its first register read with this bit of the
    /// CRC-4 inverted (0 = the first CRC bit sent, 3 = the last).
    pub cds_crc_flip: Option<u32>,
    /// The slave echoes this byte, with the right CRC-4 for it, in place of
    /// the data of its first register write, and stores nothing.
    pub cds_write_echo: Option<u8>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Idle,
    Armed,
    Latched,
    Busy,
    Shift,
}

/// One to three slaves on one MA line; the first one's SLO goes to the
/// master. The frame is ack, one start bit (when every slave's `t_busy` is
/// over), then each slave's section in chain order, then `0` until the
/// longest BiSS timeout of the chain has passed after the last MA edge.
#[derive(Debug, Clone)]
pub struct Chain {
    slaves: Vec<Slave>,
    busy_clocks: u64,
    timeout_clocks: u64,
    phase: Phase,
    last_ma: bool,
    quiet: u64,
    busy: u64,
    frame: Vec<bool>,
    next_bit: usize,
    level: bool,
    output: DelayLine,
    frames: u64,
    latches: u64,
}

impl Chain {
    /// A chain of `slaves` whose SLO output changes `output_delay_clocks` after an MA edge.
    pub fn new(slaves: Vec<Slave>, output_delay_clocks: u64) -> Self {
        let busy_clocks = slaves.iter().map(|s| s.cfg.busy_clocks).max().unwrap_or(0);
        let timeout_clocks = slaves
            .iter()
            .map(|s| s.cfg.timeout_clocks)
            .max()
            .unwrap_or(1);
        Chain {
            slaves,
            busy_clocks,
            timeout_clocks,
            phase: Phase::Idle,
            last_ma: true,
            quiet: 0,
            busy: 0,
            frame: Vec::new(),
            next_bit: 0,
            level: true,
            output: DelayLine::new(output_delay_clocks, true),
            frames: 0,
            latches: 0,
        }
    }

    /// The slaves, in chain order.
    pub fn slaves(&self) -> &[Slave] {
        &self.slaves
    }

    /// The slaves, for setting positions, flags and faults.
    pub fn slaves_mut(&mut self) -> &mut [Slave] {
        &mut self.slaves
    }

    /// Frames that reached their timeout with a latch.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// Frames latched so far (first rising MA edges): a co-simulation numbers
    /// its transcript by it and sets up the next frame after each latch.
    pub fn latches(&self) -> u64 {
        self.latches
    }

    /// How many of the next steps with `ma` leave SLO and the phase as they
    /// are (fast-forward): none on an MA edge, up to the timeout otherwise,
    /// and up to the next edge in flight on the output delay.
    pub fn quiet(&self, ma: bool) -> u64 {
        if ma != self.last_ma {
            return 0;
        }
        let phase = match self.phase {
            Phase::Idle if self.level => u64::MAX,
            Phase::Idle => 0,
            _ => (self.timeout_clocks - 1).saturating_sub(self.quiet),
        };
        phase.min(self.output.quiet(self.level))
    }

    /// The same as `n` steps with the last MA level, for `n` up to [`Chain::quiet`].
    pub fn skip(&mut self, n: u64) {
        self.quiet += n;
        if self.phase == Phase::Busy {
            self.busy += n;
        }
        self.output.skip(n);
    }

    /// The SLO level the chain drives after the last step.
    pub fn slo(&self) -> bool {
        self.output.output()
    }

    /// One cycle with MA at the slaves' pins; returns SLO as it leaves the first slave.
    pub fn step(&mut self, ma: bool) -> bool {
        let fell = self.last_ma && !ma;
        let rose = !self.last_ma && ma;
        self.last_ma = ma;
        self.quiet = if fell || rose { 0 } else { self.quiet + 1 };
        match self.phase {
            Phase::Idle => {
                self.level = true;
                if fell {
                    self.phase = Phase::Armed;
                }
            }
            Phase::Armed => {
                if rose {
                    // First rising edge: every slave latches its position.
                    self.frame = self.slaves.iter_mut().flat_map(|s| s.section()).collect();
                    self.phase = Phase::Latched;
                    self.latches += 1;
                }
            }
            Phase::Latched => {
                if rose {
                    self.level = false; // the ack
                    self.phase = Phase::Busy;
                    self.busy = 0;
                }
            }
            Phase::Busy => {
                self.busy += 1;
                if rose && self.busy >= self.busy_clocks {
                    self.level = true; // the start bit
                    self.phase = Phase::Shift;
                    self.next_bit = 0;
                }
            }
            Phase::Shift => {
                if rose {
                    self.level = self.frame.get(self.next_bit).copied().unwrap_or(false);
                    self.next_bit += 1;
                }
            }
        }
        if self.phase != Phase::Idle && self.quiet >= self.timeout_clocks {
            if self.phase != Phase::Armed {
                // The BiSS timeout: CDM is the inverted MA level.
                let cdm = !ma;
                for s in &mut self.slaves {
                    s.take_cdm(cdm);
                }
                self.frames += 1;
            }
            self.phase = Phase::Idle;
            self.level = true;
        }
        self.output.step(self.level)
    }
}
