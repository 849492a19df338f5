//! The SAR58K24 in Modbus RTU mode (seed 001, 3.1.7): the emulator the
//! master is tested against. It lives here rather than in `sar58k24`
//! because a protocol module imports no other; the position source is the
//! same kind (raw positions, binary or Gray, zero offset none).
//!
//! [`Device::respond`] is the frame-level behaviour (what a complete,
//! well-timed frame gets); [`Device::step`] adds the character timing: a
//! frame ends after t3.5 of silence, a silence longer than t1.5 inside it
//! (or a parity or framing error) makes the whole frame discarded, and the
//! answer starts `answer_delay_us` after the request was recognised.

use serde::{Deserialize, Serialize};

use super::frames::{self, Exception};
use crate::gray::to_gray;
use crate::line::Drive;
use crate::uart::{self, FaultKind, FrameFault, Parity, Receiver, ReceiverConfig, Transmitter};
use crate::{ConfigError, Result};

/// The device's settings in a scenario's units (`[modbus.device]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct DeviceSettings {
    /// Station address (factory default 1).
    pub address: u8,
    /// Resolution (10..32 bits).
    pub bits: u32,
    /// The position is sent in Gray code.
    pub gray: bool,
    /// Raw positions, one per answer; the last holds.
    pub positions: Vec<u64>,
    /// From the request's recognition (t3.5 after its last character) to
    /// the answer's first start bit, µs (the manual gives none).
    pub answer_delay_us: f64,
    /// The holding register an address change is written to.
    pub address_register: u16,
    /// The device knows the address change (function 06); without it a
    /// write is an unknown function, answered with exception 01, as firmware
    /// that lacks it would answer.
    pub address_change: bool,
    /// The device's baud error in percent.
    pub baud_error_percent: f64,
    /// Faults on the answers (`frame` counts answers).
    pub faults: Vec<FrameFault>,
}

impl Default for DeviceSettings {
    fn default() -> Self {
        DeviceSettings {
            address: 1,
            bits: 16,
            gray: false,
            positions: vec![383],
            answer_delay_us: 100.0,
            address_register: frames::ADDRESS_REGISTER,
            address_change: true,
            baud_error_percent: 0.0,
            faults: Vec::new(),
        }
    }
}

impl DeviceSettings {
    /// Checks the settings.
    pub fn validate(&self, parity: Parity) -> Result<()> {
        if !(1..=247).contains(&self.address) {
            return Err(ConfigError::invalid(
                "device.address",
                format!("{}", self.address),
                "give a station address from 1 to 247",
            ));
        }
        if !(10..=32).contains(&self.bits) {
            return Err(ConfigError::invalid(
                "device.bits",
                format!("{}", self.bits),
                "give 10 to 32 bits",
            ));
        }
        if self.positions.is_empty() || self.positions.iter().any(|&p| p >> self.bits != 0) {
            return Err(ConfigError::invalid(
                "device.positions",
                "empty, or a position does not fit the resolution",
                "list positions below 2^bits",
            ));
        }
        if !(0.0..1e7).contains(&self.answer_delay_us) {
            return Err(ConfigError::invalid(
                "device.answer_delay_us",
                format!("{}", self.answer_delay_us),
                "give 0 to 10^7 µs",
            ));
        }
        if !(-10.0..=10.0).contains(&self.baud_error_percent) {
            return Err(ConfigError::invalid(
                "device.baud_error_percent",
                format!("{}", self.baud_error_percent),
                "give −10 to +10 %",
            ));
        }
        for (i, f) in self.faults.iter().enumerate() {
            f.validate(9, parity)
                .map_err(|e| ConfigError::invalid(format!("device.faults[{i}]"), e.0, e.1))?;
        }
        Ok(())
    }
}

/// The device's configuration in cycles.
#[derive(Debug, Clone, PartialEq)]
pub struct DeviceConfig {
    /// System clock period, ps.
    pub period_ps: u64,
    /// Nominal baud.
    pub baud: f64,
    /// The character format.
    pub parity: Parity,
    /// Receiver clocks per bit.
    pub clocks_per_bit: u64,
    /// t1.5 in cycles.
    pub t15: u64,
    /// t3.5 in cycles.
    pub t35: u64,
    /// Answer delay in cycles.
    pub answer_delay: u64,
    /// The rest.
    pub settings: DeviceSettings,
}

/// What the device did with one request.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Answered.
    Answered,
    /// Dropped: bad CRC, too short, a gap over t1.5, a parity or framing error.
    Discarded,
    /// Not for this device (another address, or broadcast).
    NotAddressed,
}

/// One request the device saw.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Seen {
    /// Cycle the frame ended (t3.5 of silence).
    pub cycle: u64,
    /// The bytes.
    pub request: Vec<u8>,
    /// What it did.
    pub verdict: Verdict,
    /// The answer it meant to send (before faults).
    pub answer: Vec<u8>,
}

/// The emulator.
#[derive(Debug, Clone)]
pub struct Device {
    cfg: DeviceConfig,
    address: u8,
    answers: usize,
    reads: usize,
    tx: Transmitter,
    rx: Receiver,
    frame: Vec<u8>,
    bad: bool,
    idle: u64,
    pending: Option<(u64, Vec<u8>)>,
    driving_until_ps: f64,
    cycle: u64,
    seen: Vec<Seen>,
    position_now: Option<u64>,
}

impl Device {
    /// A device in its power-on state.
    pub fn new(cfg: DeviceConfig) -> Result<Self> {
        cfg.settings.validate(cfg.parity)?;
        Ok(Device {
            address: cfg.settings.address,
            answers: 0,
            reads: 0,
            position_now: None,
            tx: Transmitter::new(
                cfg.period_ps,
                cfg.baud,
                cfg.settings.baud_error_percent,
                0.0,
                1,
            )
            .with_parity(cfg.parity),
            rx: Receiver::with_parity(
                ReceiverConfig {
                    clocks_per_bit: cfg.clocks_per_bit,
                },
                cfg.parity,
            )?,
            frame: Vec::new(),
            bad: false,
            idle: 0,
            pending: None,
            driving_until_ps: -1.0,
            cycle: 0,
            seen: Vec::new(),
            cfg,
        })
    }

    /// The station address now (after any change).
    pub fn address(&self) -> u8 {
        self.address
    }

    /// Every request seen.
    pub fn seen(&self) -> &[Seen] {
        &self.seen
    }

    /// Sets the raw position every answer from now on carries, in place of
    /// the `positions` list (a closed-loop bench moving the shaft). Refused
    /// when it does not fit the resolution.
    pub fn set_position(&mut self, raw: u64) -> Result<()> {
        if raw >> self.cfg.settings.bits != 0 {
            return Err(ConfigError::invalid(
                "position",
                format!("{raw} does not fit {} bits", self.cfg.settings.bits),
                "give a position below 2^bits",
            ));
        }
        self.position_now = Some(raw);
        Ok(())
    }

    fn position(&mut self) -> u64 {
        let p = &self.cfg.settings.positions;
        let v = self
            .position_now
            .unwrap_or_else(|| p[self.reads.min(p.len() - 1)]);
        self.reads += 1;
        if self.cfg.settings.gray {
            to_gray(v)
        } else {
            v
        }
    }

    /// The answer to a complete, well-timed frame (CRC included), or why none.
    pub fn respond(&mut self, frame: &[u8]) -> (Verdict, Vec<u8>) {
        if frame.len() < 4 || !frames::crc_ok(frame) {
            return (Verdict::Discarded, Vec::new());
        }
        let (addr, function) = (frame[0], frame[1]);
        if addr == frames::QUERY_ADDRESS && function == frames::QUERY_FUNCTION && frame.len() == 4 {
            return (Verdict::Answered, frames::address_answer(self.address));
        }
        if addr != self.address {
            return (Verdict::NotAddressed, Vec::new());
        }
        let word = |i: usize| u16::from_be_bytes([frame[i], frame[i + 1]]);
        let answer = match function {
            frames::READ_HOLDING if frame.len() == 8 => {
                let (start, count) = (word(2), word(4));
                if !(1..=125).contains(&count) {
                    frames::exception_answer(addr, function, Exception::IllegalDataValue)
                } else if start != frames::POSITION_REGISTER || count > 2 {
                    frames::exception_answer(addr, function, Exception::IllegalDataAddress)
                } else if count == 1 && self.cfg.settings.bits > 16 {
                    // One register cannot hold a position above 16 bits: this
                    // project answers 03 rather than a cut value.
                    frames::exception_answer(addr, function, Exception::IllegalDataValue)
                } else {
                    let v = self.position() as u32;
                    frames::read_answer(addr, count, v)
                }
            }
            frames::WRITE_SINGLE if !self.cfg.settings.address_change => {
                frames::exception_answer(addr, function, Exception::IllegalFunction)
            }
            frames::WRITE_SINGLE if frame.len() == 8 => {
                let (register, value) = (word(2), word(4));
                if register != self.cfg.settings.address_register {
                    frames::exception_answer(addr, function, Exception::IllegalDataAddress)
                } else if !(1..=247).contains(&value) {
                    frames::exception_answer(addr, function, Exception::IllegalDataValue)
                } else {
                    self.address = value as u8;
                    frame.to_vec()
                }
            }
            frames::READ_HOLDING | frames::WRITE_SINGLE => {
                frames::exception_answer(addr, function, Exception::IllegalDataValue)
            }
            _ => frames::exception_answer(addr, function, Exception::IllegalFunction),
        };
        (Verdict::Answered, answer)
    }

    fn answer(&mut self, mut bytes: Vec<u8>) {
        let index = self.answers;
        self.answers += 1;
        let faults: Vec<FrameFault> = self
            .cfg
            .settings
            .faults
            .iter()
            .filter(|f| f.frame == index)
            .cloned()
            .collect();
        let n = bytes.len();
        let mut changed = false;
        for f in &faults {
            let at = match f.kind {
                FaultKind::Retag => 0,
                FaultKind::Replace if f.byte + 2 < n => f.byte,
                _ => continue,
            };
            bytes[at] = f.bytes[0];
            changed = true;
        }
        // Insertions after replacements (whose `byte` counts the answer as
        // built), last position first so that each `byte` still names a
        // character of the answer as built; only before the CRC.
        let mut inserts: Vec<&FrameFault> = faults
            .iter()
            .filter(|f| f.kind == FaultKind::Insert && f.byte + 2 <= n)
            .collect();
        inserts.sort_by_key(|f| std::cmp::Reverse(f.byte));
        for f in inserts {
            bytes.splice(f.byte..f.byte, f.bytes.iter().copied());
            changed = true;
        }
        if changed {
            let n = bytes.len();
            let crc = frames::crc_bytes(&bytes[..n - 2]);
            bytes[n - 2..].copy_from_slice(&crc);
        }
        if faults.iter().any(|f| f.kind == FaultKind::Silent) {
            return;
        }
        let now_ps = (self.cycle * self.cfg.period_ps) as f64;
        uart::send_with_faults(&mut self.tx, &bytes, &faults, self.cfg.parity, now_ps);
        self.driving_until_ps = self.tx.idle_from_ps();
    }

    /// How many of the next steps with the line at `rx` change nothing but
    /// counters (fast-forward): no character, frame end, answer or edge,
    /// and the same drive.
    pub fn quiet(&self, rx: bool) -> u64 {
        let c = self.cycle;
        let period = self.cfg.period_ps;
        let now_ps = (c * period) as f64;
        let mut q = self.tx.quiet();
        // The drive enable falls at `driving_until_ps`, the receiver's
        // own-driver blanking one cycle later; a quiet cycle repeats the last
        // step's drive, so the window ends where the level that step saw
        // changes (at once when it changed at this cycle).
        let last_ps = (c.saturating_sub(1) * period) as f64;
        for edge in [self.driving_until_ps, self.driving_until_ps + period as f64] {
            if last_ps < edge {
                q = q.min(uart::first_cycle_at(c, period, edge) - c);
            }
        }
        if let Some((at, _)) = &self.pending {
            q = q.min(at.saturating_sub(c));
        }
        if self.rx.state() == uart::State::Idle && !self.frame.is_empty() {
            q = q.min(self.cfg.t35.saturating_sub(self.idle + 1));
        }
        let driving = now_ps < self.driving_until_ps + period as f64;
        q.min(self.rx.quiet(&uart::In {
            i_rx: rx || driving,
        }))
    }

    /// The same as `n` steps with the last line level, for `n` up to [`Device::quiet`].
    pub fn skip(&mut self, n: u64) {
        if self.rx.state() != uart::State::Idle {
            if !self.frame.is_empty() && self.idle > self.cfg.t15 {
                self.bad = true;
            }
            self.idle = 0;
        } else if !self.frame.is_empty() {
            self.idle += n;
        }
        self.rx.skip(n);
        self.tx.skip(n);
        self.cycle += n;
    }

    /// One system clock: `rx` is the line at the device; returns its driver.
    pub fn step(&mut self, rx: bool) -> Drive {
        let now_ps = (self.cycle * self.cfg.period_ps) as f64;
        let driving = now_ps < self.driving_until_ps + self.cfg.period_ps as f64;
        let r = self.rx.step(&uart::In {
            i_rx: rx || driving,
        });
        if r.o_valid || r.o_parity_err || r.o_frame_err {
            self.frame.push(r.o_data);
            self.bad |= !r.o_valid;
            self.idle = 0;
        } else if r.o_busy {
            // A start bit: the silence before it is complete.
            if !self.frame.is_empty() && self.idle > self.cfg.t15 {
                self.bad = true;
            }
            self.idle = 0;
        } else if !self.frame.is_empty() {
            self.idle += 1;
            if self.idle == self.cfg.t35 {
                let request = std::mem::take(&mut self.frame);
                let (verdict, answer) = if self.bad || request.len() > 256 {
                    (Verdict::Discarded, Vec::new())
                } else {
                    self.respond(&request)
                };
                self.bad = false;
                if verdict == Verdict::Answered {
                    self.pending = Some((self.cycle + self.cfg.answer_delay, answer.clone()));
                }
                self.seen.push(Seen {
                    cycle: self.cycle,
                    request,
                    verdict,
                    answer,
                });
            }
        }
        if let Some((at, _)) = &self.pending {
            if self.cycle >= *at {
                let (_, bytes) = self.pending.take().expect("pending answer");
                self.answer(bytes);
            }
        }
        let level = self.tx.step();
        self.cycle += 1;
        Drive {
            enable: now_ps < self.driving_until_ps,
            level,
        }
    }
}
