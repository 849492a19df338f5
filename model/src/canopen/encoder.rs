//! The DS 406 encoder behind the Leine & Linde gateway at frame level
//! (seed 003): NMT states, boot-up, SDO server on its object dictionary,
//! scaling and preset, TPDO1 cyclic by 6200h, TPDO2 on SYNC, node guarding
//! and heartbeat, emergencies. [`super::node::EncoderNode`] puts it on a
//! bit-level [`crate::can::Bus`].
//!
//! ```text
//!  power-on ─> INITIALISATION ─(boot-up: 0x80+node, no data)─> PRE_OPERATIONAL
//!  PRE_OPERATIONAL ─NMT 01─> OPERATIONAL ─NMT 02─> STOPPED ─NMT 80─> PRE_OPERATIONAL
//!  any ─NMT 81 (reset node) / 82 (reset communication)─> INITIALISATION (5000h/5001h applied)
//!  OPERATIONAL: every 6200h ms (≠ 0): TPDO1 0x180+node, 4 bytes position (6004h, little-endian)
//!               every n-th SYNC (1801h sub 2 = n): TPDO2 0x280+node, same bytes
//! ```
//! Time is in nanoseconds since power-on; the caller owns it.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::cob::{self, cob_id, BootUp, NmtCommand, NmtState, Service};
use super::od::{self, value, Access, Dictionary, ALARM_POSITION_ERROR};
use super::scaling::{NonCyclicLimit, Scaling};
use super::sdo::{self, abort, ObjectAccess};
use crate::can::frame::Frame;
use crate::{ConfigError, Result};

/// The encoder types of seed 003 §7.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum EncoderKind {
    /// §7.1: 13-bit singleturn; range = scaled singleturn resolution.
    Singleturn13,
    /// §7.2: 25-bit multiturn (13 + 12 bits), cyclic or non-cyclic.
    #[default]
    Multiturn25,
    /// §7.3: 20-bit angle encoder, binary scaling only.
    Angle20,
    /// §7.3: 23-bit angle encoder, binary scaling only.
    Angle23,
    /// §7.4: linear encoder: preset only, 6501h = measuring step in nm.
    Linear,
}

impl EncoderKind {
    /// Singleturn resolution (positions per revolution; linear: the raw count's 2^32 in one "turn").
    pub fn singleturn_resolution(self) -> u32 {
        match self {
            EncoderKind::Singleturn13 | EncoderKind::Multiturn25 => 1 << 13,
            EncoderKind::Angle20 => 1 << 20,
            EncoderKind::Angle23 => 1 << 23,
            EncoderKind::Linear => 0,
        }
    }

    /// Revolutions (1 for singleturn).
    pub fn revolutions(self) -> u32 {
        if self == EncoderKind::Multiturn25 {
            1 << 12
        } else {
            1
        }
    }

    /// Positions of the raw disk or scale.
    pub fn total_resolution(self) -> u64 {
        match self {
            EncoderKind::Linear => 1 << 32,
            k => k.singleturn_resolution() as u64 * k.revolutions() as u64,
        }
    }

    /// 1000h: encoder type (DS 406: 1 singleturn, 2 multiturn, 8 absolute linear) << 16 | 406.
    pub fn device_type(self) -> u32 {
        let t = match self {
            EncoderKind::Multiturn25 => 2,
            EncoderKind::Linear => 8,
            _ => 1,
        };
        t << 16 | 406
    }
}

/// The emulated encoder (`[canopen.encoders]` of a scenario).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderConfig {
    /// Address switch (seed 003 §5.4), 1 to 127.
    pub node_switch: u8,
    /// Bit-rate switch code (§5.5), 0 to 7.
    pub bit_rate_switch: u8,
    /// Encoder type (§7).
    pub kind: EncoderKind,
    /// Boot-up form: `emergency` (the note) or `ds301`.
    pub boot_up: BootUp,
    /// Output outside a non-cyclic range: `total_range` (the note) or `clamp`.
    pub non_cyclic_limit: NonCyclicLimit,
    /// 5500h and 1018h sub 4; FFFF FFFFh = not used (§6.3).
    pub serial_number: u32,
    /// 650Bh: the encoder's own serial number.
    pub encoder_serial: u32,
    /// 1018h sub 1.
    pub vendor_id: u32,
    /// 6501h of a linear encoder: measuring step, nm.
    pub linear_step_nm: u32,
    /// Raw position at power-on (disk counts).
    pub raw_position: u64,
    /// Raw counts per second (constant speed; negative: backwards).
    pub speed_cps: f64,
    /// Time from a request's reception to its answer being queued, µs.
    pub response_delay_us: f64,
}

impl Default for EncoderConfig {
    fn default() -> Self {
        EncoderConfig {
            node_switch: 1,
            bit_rate_switch: 4,
            kind: EncoderKind::Multiturn25,
            boot_up: BootUp::Emergency,
            non_cyclic_limit: NonCyclicLimit::TotalRange,
            serial_number: 0xFFFF_FFFF,
            encoder_serial: 0x0012_3456,
            vendor_id: 0,
            linear_step_nm: 50,
            raw_position: 0,
            speed_cps: 0.0,
            response_delay_us: 0.0,
        }
    }
}

/// Bit rates of the switch and of 5000h, kbit/s, by code (§5.5, §6.1).
pub const BIT_RATES_KBPS: [u32; 8] = [10, 20, 50, 125, 250, 500, 800, 1000];

impl EncoderConfig {
    /// Checks the fields; `field` names the table.
    pub fn validate(&self, field: &str) -> Result<()> {
        if !(1..=127).contains(&self.node_switch) {
            return Err(ConfigError::invalid(
                format!("{field}.node_switch"),
                format!("{}", self.node_switch),
                "give a node number from 1 to 127 (seed 003 §5.4)",
            ));
        }
        if self.bit_rate_switch > 7 {
            return Err(ConfigError::invalid(
                format!("{field}.bit_rate_switch"),
                format!("{}", self.bit_rate_switch),
                "give a code from 0 (10 kbit/s) to 7 (1000 kbit/s) (seed 003 §5.5)",
            ));
        }
        if self.raw_position >= self.kind.total_resolution() {
            return Err(ConfigError::invalid(
                format!("{field}.raw_position"),
                format!("{}", self.raw_position),
                format!("give a raw position below {}", self.kind.total_resolution()),
            ));
        }
        if !(0.0..=1e6).contains(&self.response_delay_us) {
            return Err(ConfigError::invalid(
                format!("{field}.response_delay_us"),
                format!("{}", self.response_delay_us),
                "give 0 to 1 000 000 µs",
            ));
        }
        if !self.speed_cps.is_finite() || self.speed_cps.abs() > 1e9 {
            return Err(ConfigError::invalid(
                format!("{field}.speed_cps"),
                format!("{}", self.speed_cps),
                "give at most 1e9 counts per second",
            ));
        }
        if self.kind == EncoderKind::Linear && self.linear_step_nm == 0 {
            return Err(ConfigError::invalid(
                format!("{field}.linear_step_nm"),
                "0",
                "give the measuring step in nm, at least 1",
            ));
        }
        Ok(())
    }
}

/// Objects kept through a reset ("securely stored", §3.1, §4.1; 5000h/5001h, §6).
const STORED: [u16; 6] = [0x5000, 0x5001, 0x6000, 0x6001, 0x6002, 0x6509];

/// The encoder at frame level.
#[derive(Debug, Clone)]
pub struct Encoder {
    cfg: EncoderConfig,
    node: u8,
    bit_code: u8,
    state: NmtState,
    dict: Dictionary,
    values: BTreeMap<(u16, u8), Vec<u8>>,
    stored: BTreeMap<(u16, u8), Vec<u8>>,
    scaling: Scaling,
    cyclic_stored: bool,
    sdo: sdo::Server,
    raw_base: u64,
    raw_base_ns: u64,
    now_ns: u64,
    next_cyclic: Option<u64>,
    next_heartbeat: Option<u64>,
    sync_count: u32,
    guard_toggle: bool,
    life_deadline: Option<u64>,
    alarms: u16,
    error_register: u8,
}

impl Encoder {
    /// An encoder before power-on.
    pub fn new(cfg: &EncoderConfig) -> Result<Encoder> {
        cfg.validate("encoder")?;
        let k = cfg.kind;
        let limit = cfg.non_cyclic_limit;
        let mut e = Encoder {
            cfg: cfg.clone(),
            node: cfg.node_switch,
            bit_code: cfg.bit_rate_switch,
            state: NmtState::Initialisation,
            dict: Dictionary::encoder(cfg, cfg.node_switch),
            values: BTreeMap::new(),
            stored: BTreeMap::new(),
            scaling: if k == EncoderKind::Linear {
                Scaling::new(1 << 32, 1, limit)
            } else {
                Scaling::new(
                    k.singleturn_resolution() as u64,
                    k.revolutions() as u64,
                    limit,
                )
            },
            cyclic_stored: true,
            sdo: sdo::Server::default(),
            raw_base: cfg.raw_position,
            raw_base_ns: 0,
            now_ns: 0,
            next_cyclic: None,
            next_heartbeat: None,
            sync_count: 0,
            guard_toggle: false,
            life_deadline: None,
            alarms: 0,
            error_register: 0,
        };
        e.load_defaults(true);
        Ok(e)
    }

    fn load_defaults(&mut self, all: bool) {
        let dict = Dictionary::encoder(&self.cfg, self.node);
        for (index, s) in dict.entries() {
            let keep = STORED.contains(&index) || (!all && index >= 0x2000);
            let v = if keep {
                self.stored
                    .get(&(index, s.sub))
                    .or(self.values.get(&(index, s.sub)))
                    .cloned()
            } else {
                None
            };
            self.values
                .insert((index, s.sub), v.unwrap_or_else(|| s.default.clone()));
        }
        self.dict = dict;
        let get = |i: u16| self.values.get(&(i, 0)).map(|v| value(v)).unwrap_or(0);
        let op = get(0x6000);
        self.scaling.ccw = op & 1 != 0;
        self.scaling.scaling = op & 4 != 0;
        if self.cfg.kind != EncoderKind::Linear {
            self.scaling.units_per_rev = get(0x6001);
            self.scaling.range = get(0x6002);
            self.scaling.cyclic = self.cyclic_stored;
        }
        self.scaling.offset = get(0x6509) as i32;
    }

    /// Power-on (or the end of a reset): the boot-up frame; the encoder is then PRE_OPERATIONAL.
    pub fn power_on(&mut self, now_ns: u64) -> Vec<Frame> {
        self.now_ns = now_ns;
        self.initialise(true)
    }

    fn initialise(&mut self, all: bool) -> Vec<Frame> {
        let sw = |v: u32, s: u8| if v == 0xFF { s } else { v as u8 };
        self.node = sw(
            self.stored
                .get(&(0x5001, 0))
                .map(|v| value(v))
                .unwrap_or(0xFF),
            self.cfg.node_switch,
        );
        self.bit_code = sw(
            self.stored
                .get(&(0x5000, 0))
                .map(|v| value(v))
                .unwrap_or(0xFF),
            self.cfg.bit_rate_switch,
        );
        self.load_defaults(all);
        self.sdo = sdo::Server::default();
        self.state = NmtState::PreOperational;
        self.next_cyclic = None;
        self.sync_count = 0;
        self.guard_toggle = false;
        self.life_deadline = None;
        self.arm_heartbeat();
        let (id, data) = self.cfg.boot_up.frame(self.node);
        vec![Frame::data(id as u32, &data)]
    }

    /// The configuration.
    pub fn config(&self) -> &EncoderConfig {
        &self.cfg
    }

    /// The node number in use.
    pub fn node(&self) -> u8 {
        self.node
    }

    /// The bit-rate code in use (index of [`BIT_RATES_KBPS`]).
    pub fn bit_code(&self) -> u8 {
        self.bit_code
    }

    /// The NMT state.
    pub fn state(&self) -> NmtState {
        self.state
    }

    /// The scaling state.
    pub fn scaling(&self) -> &Scaling {
        &self.scaling
    }

    /// The dictionary (names, types, defaults).
    pub fn dictionary(&self) -> &Dictionary {
        &self.dict
    }

    /// The raw disk position at `now_ns`.
    pub fn raw(&self, now_ns: u64) -> u64 {
        let total = self.cfg.kind.total_resolution() as i128;
        let moved = (self.cfg.speed_cps * (now_ns.saturating_sub(self.raw_base_ns)) as f64 * 1e-9)
            .round() as i128;
        (self.raw_base as i128 + moved).rem_euclid(total) as u64
    }

    /// Moves the disk to `raw` at `now_ns` (it keeps its speed from there).
    pub fn set_raw(&mut self, raw: u64, now_ns: u64) {
        self.raw_base = raw % self.cfg.kind.total_resolution();
        self.raw_base_ns = now_ns;
    }

    /// The position value 6004h at `now_ns`.
    pub fn position(&self, now_ns: u64) -> u32 {
        self.scaling.output(self.raw(now_ns))
    }

    /// Raises or clears the position-error alarm (6503h bit 0): an emergency
    /// `10 00 01 <alarms low> <alarms high> 00 00 00` when raised, `00 00 00 …` when cleared
    /// (not in STOPPED).
    pub fn set_alarm(&mut self, on: bool, now_ns: u64) -> Vec<Frame> {
        self.now_ns = now_ns;
        let was = self.alarms & ALARM_POSITION_ERROR != 0;
        if on == was {
            return Vec::new();
        }
        self.alarms ^= ALARM_POSITION_ERROR;
        // Bit 0, generic error, follows the alarm; bit 4 (a life guarding event) stays.
        self.error_register = (self.error_register & !0x01) | on as u8;
        self.emcy(if on { 0x1000 } else { 0x0000 })
    }

    fn emcy(&self, code: u16) -> Vec<Frame> {
        if matches!(self.state, NmtState::Stopped | NmtState::Initialisation) {
            return Vec::new();
        }
        let a = self.alarms.to_le_bytes();
        vec![Frame::data(
            cob_id(cob::EMCY, self.node) as u32,
            &[
                code as u8,
                (code >> 8) as u8,
                self.error_register,
                a[0],
                a[1],
                0,
                0,
                0,
            ],
        )]
    }

    fn arm_heartbeat(&mut self) {
        let hb = self.values.get(&(0x1017, 0)).map(|v| value(v)).unwrap_or(0) as u64;
        self.next_heartbeat = (hb > 0).then(|| self.now_ns + hb * 1_000_000);
    }

    fn arm_cyclic(&mut self) {
        let t = self.values.get(&(0x6200, 0)).map(|v| value(v)).unwrap_or(0) as u64;
        self.next_cyclic =
            (t > 0 && self.state == NmtState::Operational).then(|| self.now_ns + t * 1_000_000);
    }

    fn tpdo(&self, n: u16) -> Option<Frame> {
        let id = value(&self.values[&(0x1800 + n, 1)]);
        (id & 0x8000_0000 == 0)
            .then(|| Frame::data(id & 0x7FF, &self.position(self.now_ns).to_le_bytes()))
    }

    /// The earliest of the cyclic timer, the heartbeat and the life
    /// guarding deadline: before then [`Encoder::poll`] only records the time.
    pub fn next_due_ns(&self) -> Option<u64> {
        [self.next_cyclic, self.next_heartbeat, self.life_deadline]
            .into_iter()
            .flatten()
            .min()
    }

    /// Frames due by `now_ns` (TPDOs of the cyclic timer, heartbeat, life guarding).
    pub fn poll(&mut self, now_ns: u64) -> Vec<Frame> {
        self.now_ns = now_ns;
        let mut out = Vec::new();
        if let Some(t) = self.next_cyclic {
            if now_ns >= t {
                let p = value(&self.values[&(0x6200, 0)]) as u64 * 1_000_000;
                self.next_cyclic = Some(t + p);
                for n in 0..2 {
                    if value(&self.values[&(0x1800 + n, 2)]) >= 0xFE {
                        out.extend(self.tpdo(n));
                    }
                }
            }
        }
        if let Some(t) = self.next_heartbeat {
            if now_ns >= t {
                let p = value(&self.values[&(0x1017, 0)]) as u64 * 1_000_000;
                self.next_heartbeat = Some(t + p);
                out.push(Frame::data(
                    cob_id(cob::NMT_ERR, self.node) as u32,
                    &[self.state as u8],
                ));
            }
        }
        if let Some(t) = self.life_deadline {
            if now_ns >= t {
                // Life guarding event: emergency 8130h with error register
                // bit 4, communication error (CiA 301; the note is silent).
                self.life_deadline = None;
                self.error_register |= 0x10;
                out.extend(self.emcy(0x8130));
            }
        }
        out
    }

    /// The answer frames to a received frame at `now_ns`.
    pub fn on_frame(&mut self, f: &Frame, now_ns: u64) -> Vec<Frame> {
        self.now_ns = now_ns;
        if f.ide || f.id > 0x7FF {
            return Vec::new();
        }
        let sync_id = value(&self.values[&(0x1005, 0)]) & 0x7FF;
        if f.id == sync_id && !f.rtr {
            return self.on_sync();
        }
        match cob::classify(f.id as u16) {
            Service::Nmt
                if f.data.len() >= 2 && !f.rtr && (f.data[1] == 0 || f.data[1] == self.node) =>
            {
                self.on_nmt(f.data[0])
            }
            Service::SdoRx(n)
                if n == self.node
                    && !f.rtr
                    && matches!(self.state, NmtState::PreOperational | NmtState::Operational) =>
            {
                let mut server = std::mem::take(&mut self.sdo);
                let r = server.request(&f.data, &mut Access_ { enc: self });
                self.sdo = server;
                r.map(|a| vec![Frame::data(cob_id(cob::SDO_TX, self.node) as u32, &a)])
                    .unwrap_or_default()
            }
            Service::NmtErr(n) if n == self.node && f.rtr && self.next_heartbeat.is_none() => {
                let b = (self.guard_toggle as u8) << 7 | self.state as u8;
                self.guard_toggle = !self.guard_toggle;
                let life = value(&self.values[&(0x100C, 0)]) as u64
                    * value(&self.values[&(0x100D, 0)]) as u64;
                self.life_deadline = (life > 0).then(|| now_ns + life * 1_000_000);
                vec![Frame::data(f.id, &[b])]
            }
            _ => Vec::new(),
        }
    }

    fn on_sync(&mut self) -> Vec<Frame> {
        if self.state != NmtState::Operational {
            return Vec::new();
        }
        self.sync_count = self.sync_count.wrapping_add(1);
        let mut out = Vec::new();
        for n in 0..2 {
            let t = value(&self.values[&(0x1800 + n, 2)]);
            if (1..=240).contains(&t) && self.sync_count % t == 0 {
                out.extend(self.tpdo(n));
            }
        }
        out
    }

    fn on_nmt(&mut self, cs: u8) -> Vec<Frame> {
        match NmtCommand::from_byte(cs) {
            Some(NmtCommand::Start) => {
                if self.state != NmtState::Operational {
                    self.state = NmtState::Operational;
                    self.arm_cyclic();
                }
                Vec::new()
            }
            Some(NmtCommand::Stop) => {
                self.state = NmtState::Stopped;
                self.next_cyclic = None;
                Vec::new()
            }
            Some(NmtCommand::EnterPreOperational) => {
                self.state = NmtState::PreOperational;
                self.next_cyclic = None;
                Vec::new()
            }
            Some(NmtCommand::ResetNode) => {
                self.state = NmtState::Initialisation;
                self.initialise(true)
            }
            Some(NmtCommand::ResetCommunication) => {
                self.state = NmtState::Initialisation;
                self.initialise(false)
            }
            None => Vec::new(),
        }
    }

    fn check_write(&self, index: u16, sub: u8, v: u32) -> std::result::Result<(), u32> {
        let k = self.cfg.kind;
        let in_range = |lo: u32, hi: u32| {
            if v < lo {
                Err(abort::TOO_LOW)
            } else if v > hi {
                Err(abort::TOO_HIGH)
            } else {
                Ok(())
            }
        };
        match (index, sub) {
            (0x1005, 0) | (0x1800, 1) | (0x1801, 1) => {
                if v & 0x7FFF_F800 != 0 {
                    return Err(abort::RANGE);
                }
                Ok(())
            }
            (0x1800, 2) | (0x1801, 2) => {
                if (1..=240).contains(&v) || v >= 0xFE {
                    Ok(())
                } else {
                    Err(abort::RANGE)
                }
            }
            (0x5000, 0) => {
                if v <= 7 || v == 0xFF {
                    Ok(())
                } else {
                    Err(abort::RANGE)
                }
            }
            (0x5001, 0) => {
                if (1..=127).contains(&v) || v == 0xFF {
                    Ok(())
                } else {
                    Err(abort::RANGE)
                }
            }
            (0x6000, 0) => {
                let allowed = if k == EncoderKind::Linear { 0 } else { 0x0005 };
                if v & !allowed != 0 {
                    Err(abort::RANGE)
                } else {
                    Ok(())
                }
            }
            (0x6001, 0) => match k {
                EncoderKind::Angle20 | EncoderKind::Angle23 => {
                    if v.is_power_of_two() && v >= 2 && v <= k.singleturn_resolution() {
                        Ok(())
                    } else {
                        Err(abort::RANGE)
                    }
                }
                _ => in_range(2, k.singleturn_resolution()),
            },
            (0x6002, 0) => match k {
                EncoderKind::Multiturn25 => in_range(
                    1,
                    self.scaling.units_per_rev.saturating_mul(k.revolutions()),
                ),
                _ => {
                    if v == self.scaling.units_per_rev {
                        Ok(())
                    } else {
                        Err(abort::RANGE)
                    }
                }
            },
            (0x6003, 0) => {
                if (v as u64) < self.scaling.out_range() || k == EncoderKind::Linear {
                    Ok(())
                } else {
                    Err(abort::TOO_HIGH)
                }
            }
            _ => Ok(()),
        }
    }

    fn apply(&mut self, index: u16, v: u32) {
        match index {
            0x6000 => {
                self.scaling.ccw = v & 1 != 0;
                self.scaling.scaling = v & 4 != 0;
            }
            0x6001 => {
                self.scaling.units_per_rev = v;
                if self.cfg.kind != EncoderKind::Multiturn25 {
                    // Singleturn and angle encoders: the range is the scaled singleturn resolution (§7.1, §7.3).
                    self.scaling.set_range(v);
                    self.values
                        .insert((0x6002, 0), od::le(od::DataType::Unsigned32, v));
                    self.stored
                        .insert((0x6002, 0), od::le(od::DataType::Unsigned32, v));
                }
            }
            0x6002 => {
                self.scaling.set_range(v);
                self.cyclic_stored = self.scaling.cyclic;
            }
            0x6003 => {
                let off = self.scaling.preset_offset(v, self.raw(self.now_ns));
                self.scaling.offset = off;
                let b = off.to_le_bytes().to_vec();
                self.values.insert((0x6509, 0), b.clone());
                self.stored.insert((0x6509, 0), b);
            }
            0x6200 => self.arm_cyclic(),
            0x1017 => self.arm_heartbeat(),
            _ => {}
        }
    }

    fn live(&self, index: u16) -> Option<u32> {
        Some(match index {
            0x1001 => self.error_register as u32,
            0x6004 => self.position(self.now_ns),
            0x6500 => value(&self.values[&(0x6000, 0)]),
            0x6503 => self.alarms as u32,
            0x6508 => (self.now_ns / 360_000_000_000) as u32,
            _ => return None,
        })
    }

    /// Reads an entry as the SDO server does (for tests and the master's checks).
    pub fn read(&self, index: u16, sub: u8) -> std::result::Result<Vec<u8>, u32> {
        let e = self.dict.entry(index, sub)?;
        Ok(match (sub, self.live(index)) {
            (0, Some(v)) => od::le(e.dtype, v),
            _ => self.values[&(index, sub)].clone(),
        })
    }
}

struct Access_<'a> {
    enc: &'a mut Encoder,
}

impl ObjectAccess for Access_<'_> {
    fn writable(&self, index: u16, sub: u8) -> std::result::Result<(), u32> {
        let e = self.enc.dict.entry(index, sub)?;
        if e.access != Access::Rw {
            return Err(abort::READ_ONLY);
        }
        Ok(())
    }

    fn read(&mut self, index: u16, sub: u8) -> std::result::Result<Vec<u8>, u32> {
        self.enc.read(index, sub)
    }

    fn write(
        &mut self,
        index: u16,
        sub: u8,
        data: &[u8],
        sized: bool,
    ) -> std::result::Result<(), u32> {
        self.writable(index, sub)?;
        let e = self.enc.dict.entry(index, sub)?;
        let size = e.dtype.size().unwrap_or(data.len());
        if (sized && data.len() != size) || data.len() < size {
            return Err(abort::LENGTH);
        }
        let bytes = data[..size].to_vec();
        let v = value(&bytes);
        self.enc.check_write(index, sub, v)?;
        self.enc.values.insert((index, sub), bytes.clone());
        if STORED.contains(&index) {
            self.enc.stored.insert((index, sub), bytes);
        }
        self.enc.apply(index, v);
        Ok(())
    }
}
