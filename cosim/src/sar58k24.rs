//! The SAR58K24 asynchronous-serial emulator: one to three
//! [`model::sar58k24::Encoder`]s on a half-duplex cable.
//!
//! Configuration: the scenario's `[sar]` table (`baud`, `parity`, `mode`,
//! `[[encoders]]`, `[cable]`); `[host]`, `[[ops]]`, `[[second_drivers]]` and
//! `f_sys_mhz` belong to the host side and are ignored, so a whole scenario
//! file can be given. Two tables of the emulator's own:
//! * `[random] count = N, seed = S`: each encoder's `positions` list becomes
//!   `N` random positions below `2^bits` (a closed-loop test's source), from
//!   the seed `S` (encoder `i` uses `S + i`).
//! * `[checks]`: the limits the host is held to (see [`SarChecks`]).
//!
//! The position an encoder reads is the next entry of its `positions` list
//! (one per acquisition, the last holding), exactly as in the model, until
//! a testbench calls `set_position(device, raw)` (every acquisition from
//! then on reads `raw`, less the zero offset: the next frame carries it) or
//! `set_motion(device, toml)` (a [`crate::motion`] profile, from the
//! emulator's cycle of the call). [`Emulator::last_value`] is what the
//! encoder last sent (binary, after zeroing).
//!
//! Pins (`emu_step`): in bit 0 the trigger line (CLK of 3.1.3, idle high),
//! bit 1 the host's driver level, bit 2 its driver enable, bit 3 CLR (idle
//! high); out bit 0 the encoders' driver level at the host's end of the
//! cable, bit 1 their driver enable there, bit 2 the resolved line level at
//! the host's end (the nearer driver wins, fail-safe high when undriven: what
//! the host's receiver sees).

use serde::{Deserialize, Serialize};

use model::line::{CableConfig, DelayLine, Drive};
use model::sar58k24::{BenchConfig, Encoder, EncoderIn, Mode};
use model::Timebase;

use crate::check::{Checks, VIOLATION_PENDING};
use crate::config::{self, Error};
use crate::motion::Motions;
use crate::{Emulator, Pins, Result};

/// The emulator needs 8 samples per bit of the configured baud rate (the
/// emulator-clock rule of [`config::emulator_clock`] is 4 x a "line clock",
/// here 2 x the baud rate); this is the seed's fastest, 115200 baud, the
/// limit when no baud rate is given.
pub const MAX_LINE_KHZ: f64 = 2.0 * 115.2;

/// Random positions (`[random]`).
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct RandomPositions {
    /// How many (0: keep the scenario's `positions`).
    pub count: usize,
    /// The seed.
    pub seed: u64,
}

/// The limits the host is held to (`[checks]`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SarChecks {
    /// Two drivers on the line at once is a violation (bus modes).
    pub contention: bool,
}

impl Default for SarChecks {
    fn default() -> Self {
        SarChecks { contention: true }
    }
}

/// The tables the emulator reads.
#[derive(Debug, Clone, PartialEq, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
struct Own {
    random: RandomPositions,
    checks: SarChecks,
}

/// A tiny deterministic generator (splitmix64) for `[random]`.
pub(crate) fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// `count` random values below `2^bits` from `seed` (public so that the
/// tests can predict a scenario's `[sar.random]` positions).
pub fn random_list(count: usize, seed: u64, bits: u32) -> Vec<u64> {
    let mut s = seed;
    let mask = if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    };
    (0..count).map(|_| splitmix(&mut s) & mask).collect()
}

/// Takes the emulator's own tables (`random`, `checks`) out of `table`.
pub(crate) fn own_tables<T: serde::de::DeserializeOwned + Default>(
    table: &mut toml::Table,
    keys: &[&str],
    origin: &str,
) -> Result<T> {
    let mut own = toml::Table::new();
    for k in keys {
        if let Some(v) = table.remove(*k) {
            own.insert(k.to_string(), v);
        }
    }
    config::decode(own, origin)
}

/// The first steps of a half-duplex UART emulator (SAR58K24, Modbus): the
/// scenario's table `proto` without the host's keys, the emulator's own
/// tables (`O`), the emulator clock checked against 8 samples per bit of the
/// configured baud rate (the rule of [`config::emulator_clock`] is 4 x a
/// line clock, here 2 x the baud rate), and the model's set-up `B` on the
/// emulator clock.
pub(crate) fn uart_bench<O, B>(
    text: &str,
    origin: &str,
    f_emu_hz: u64,
    proto: &str,
    name: &str,
    default_baud: f64,
) -> Result<(Timebase, O, B)>
where
    O: serde::de::DeserializeOwned + Default,
    B: serde::de::DeserializeOwned,
{
    let tables = config::tables(text, origin, proto)?;
    let mut device = tables.device.clone();
    for k in ["ops", "second_drivers"] {
        device.remove(k);
    }
    let own: O = own_tables(&mut device, &["random", "checks"], origin)?;
    let baud = device
        .get("baud")
        .and_then(|v| v.as_float().or(v.as_integer().map(|i| i as f64)))
        .unwrap_or(default_baud);
    // The models' range (their `clocks_per_bit`): the monitors, which do not
    // build a model host, would otherwise take any rate, down to zero.
    if !(300.0..=10e6).contains(&baud) {
        return Err(Error::field(
            origin,
            "baud",
            format!("{baud}"),
            "give a baud rate from 300 to 10e6, such as 9600, 19200 or 115200",
        ));
    }
    let mut settings = tables.emulator.clone();
    settings.max_line_clock_khz = settings.max_line_clock_khz.or(Some(2.0 * baud / 1e3));
    let tb = config::emulator_clock(f_emu_hz, &settings, MAX_LINE_KHZ, name, origin)?;
    device.insert(
        "f_sys_mhz".into(),
        toml::Value::Float(f_emu_hz as f64 / 1e6),
    );
    Ok((tb, own, config::decode(device, origin)?))
}

/// The random position list of each device (`None`: keep its own), for
/// devices of `bits`; `field` and `table` name the devices in errors.
pub(crate) fn random_lists(
    r: &RandomPositions,
    bits: &[u32],
    origin: &str,
    field: &str,
    table: &str,
) -> Result<Vec<Option<Vec<u64>>>> {
    if bits.is_empty() || bits.len() > 3 {
        return Err(Error::field(
            origin,
            field,
            format!("{} devices", bits.len()),
            format!("give one to three {table} tables"),
        ));
    }
    if r.count > 1_000_000 {
        return Err(Error::field(
            origin,
            "random.count",
            format!("{}", r.count),
            "give at most 10^6 random positions",
        ));
    }
    Ok(bits
        .iter()
        .enumerate()
        .map(|(i, &b)| {
            (r.count > 0).then(|| random_list(r.count, r.seed.wrapping_add(i as u64), b.min(32)))
        })
        .collect())
}

/// The run-time positions of a half-duplex emulator's devices (SAR58K24,
/// Modbus): `set_position` and `set_motion` of [`Emulator`], checked here
/// once for both; the emulator hands the positions to its model devices.
pub(crate) struct Shafts {
    motions: Motions,
    period_ps: u64,
    bits: Vec<u32>,
    what: &'static str,
}

impl Shafts {
    /// Devices of `bits` on the emulator clock `tb`; `what` names them in errors.
    pub(crate) fn new(tb: &Timebase, bits: Vec<u32>, what: &'static str) -> Self {
        Shafts {
            motions: Motions::default(),
            period_ps: tb.period_ps(),
            bits,
            what,
        }
    }

    fn bits(&self, device: usize) -> Result<u32> {
        self.bits.get(device).copied().ok_or_else(|| {
            Error::Usage(format!(
                "the emulator has {} {}(s), not {} {device}",
                self.bits.len(),
                self.what,
                self.what
            ))
        })
    }

    /// Checks `set_position(device, position)` and stops the device's motion.
    pub(crate) fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        let bits = self.bits(device)?;
        if bits < 64 && position >> bits != 0 {
            return Err(Error::Usage(format!("position {position} does not fit {bits} bits ({} {device}); give a position below 2^{bits}", self.what)));
        }
        self.motions.stop(device);
        Ok(())
    }

    /// `set_motion(device, toml)` from emulator cycle `cycle` on.
    pub(crate) fn set_motion(&mut self, device: usize, toml: &str, cycle: u64) -> Result<()> {
        self.bits(device)?;
        self.motions.set(device, toml, cycle)
    }

    /// The positions of the moving devices at `cycle`.
    pub(crate) fn moving(&self, cycle: u64) -> Vec<(usize, u64)> {
        if !self.motions.any() {
            return Vec::new();
        }
        (0..self.bits.len())
            .filter_map(|i| {
                self.motions
                    .position(i, cycle, self.period_ps, self.bits[i])
                    .map(|p| (i, p))
            })
            .collect()
    }
}

/// A half-duplex pair between the host (end A, at the pins) and the devices
/// (end B), one delay line per direction for the level and the enable.
pub(crate) struct HalfDuplex {
    a_to_b_en: DelayLine,
    a_to_b_level: DelayLine,
    b_to_a_en: DelayLine,
    b_to_a_level: DelayLine,
    /// Cycles in which two drivers were on at one end.
    pub contention: u64,
}

/// What one step of [`HalfDuplex`] gives.
pub(crate) struct Ends {
    /// The level the devices' receivers see (their own driver wins).
    pub at_device: bool,
    /// The devices' drive as it arrives at the host's end.
    pub far: Drive,
    /// Both drivers on at one end now.
    pub contention: bool,
}

impl HalfDuplex {
    pub(crate) fn new(cable: &CableConfig, tb: &Timebase) -> Self {
        let d = cable.delay_cycles(tb);
        HalfDuplex {
            a_to_b_en: DelayLine::new(d, false),
            a_to_b_level: DelayLine::new(d, true),
            b_to_a_en: DelayLine::new(d, false),
            b_to_a_level: DelayLine::new(d, true),
            contention: 0,
        }
    }

    /// The host drives `host` now; `device` is what the devices drove in
    /// the last step (they answer after it).
    pub(crate) fn step(&mut self, host: Drive, device: Drive) -> Ends {
        let near_b = Drive {
            enable: self.a_to_b_en.step(host.enable),
            level: self.a_to_b_level.step(host.level),
        };
        let far = Drive {
            enable: self.b_to_a_en.step(device.enable),
            level: self.b_to_a_level.step(device.level),
        };
        let at_device = if device.enable {
            device.level
        } else if near_b.enable {
            near_b.level
        } else {
            true
        };
        let contention = (host.enable && far.enable) || (device.enable && near_b.enable);
        if contention {
            self.contention += 1;
        }
        Ends {
            at_device,
            far,
            contention,
        }
    }
}

/// The output pins of a half-duplex emulator: the devices' drive at the
/// host's end and the resolved level (bits 0, 1, 2).
pub(crate) fn half_duplex_pins(host: Drive, far: Drive) -> u32 {
    let line = if host.enable {
        host.level
    } else if far.enable {
        far.level
    } else {
        true
    };
    far.level as u32 | (far.enable as u32) << 1 | (line as u32) << 2
}

/// One frame an encoder sent.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// 0-based frame number over all encoders.
    pub index: u64,
    /// The encoder (index in `[[encoders]]`).
    pub device: usize,
    /// Its bus address.
    pub address: u8,
    /// Emulator cycle the frame was queued.
    pub cycle: u64,
    /// The position in it (binary, after zeroing).
    pub position: u64,
    /// The bytes as meant, hex.
    pub bytes: String,
}

/// Bytes as `FF 81 01 7F 00`.
pub(crate) fn hex(bytes: &[u8]) -> String {
    bytes
        .iter()
        .map(|b| format!("{b:02X}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// One to three SAR58K24 encoders on their cable, on the emulator clock.
pub struct SarEmulator {
    f_emu_hz: u64,
    mode: Mode,
    addresses: Vec<u8>,
    encoders: Vec<Encoder>,
    seen: Vec<usize>,
    glitches: Vec<usize>,
    line: HalfDuplex,
    trigger: DelayLine,
    clr: DelayLine,
    drive: Drive,
    own: Own,
    cycle: u64,
    entries: Vec<Entry>,
    last: Vec<Option<u64>>,
    checks: Checks,
    in_contention: bool,
    shafts: Shafts,
}

impl SarEmulator {
    /// An emulator from TOML text (`origin` names it in errors) at `f_emu_hz`.
    pub fn from_toml(text: &str, origin: &str, f_emu_hz: u64) -> Result<Self> {
        let (tb, own, mut bench) =
            uart_bench::<Own, BenchConfig>(text, origin, f_emu_hz, "sar", "SAR58K24", 115_200.0)?;
        let bits: Vec<u32> = bench.encoders.iter().map(|e| e.bits).collect();
        let lists = random_lists(&own.random, &bits, origin, "encoders", "[[encoders]]")?;
        for (e, list) in bench.encoders.iter_mut().zip(lists) {
            if let Some(list) = list {
                e.positions = list;
            }
        }
        bench
            .cable
            .validate("cable")
            .map_err(|e| Error::config(origin, e))?;
        let encoders = (0..bench.encoders.len())
            .map(|i| {
                bench
                    .encoder_config(i)
                    .and_then(Encoder::new)
                    .map_err(|e| Error::config(origin, e))
            })
            .collect::<Result<Vec<_>>>()?;
        let n = encoders.len();
        let delay = bench.cable.delay_cycles(&tb);
        Ok(SarEmulator {
            f_emu_hz,
            mode: bench.mode,
            addresses: bench.encoders.iter().map(|e| e.address).collect(),
            encoders,
            seen: vec![0; n],
            glitches: vec![0; n],
            line: HalfDuplex::new(&bench.cable, &tb),
            trigger: DelayLine::new(delay, true),
            clr: DelayLine::new(delay, true),
            drive: Drive {
                enable: false,
                level: true,
            },
            own,
            cycle: 0,
            entries: Vec::new(),
            last: vec![None; n],
            checks: Checks::new(tb.period_ps()),
            in_contention: false,
            shafts: Shafts::new(&tb, bits, "encoder"),
        })
    }

    /// The frames sent so far.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }
}

impl Emulator for SarEmulator {
    fn kind(&self) -> &'static str {
        "sar58k24"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let host = Drive {
            enable: pins.0 & 4 != 0,
            level: pins.0 & 2 != 0,
        };
        let ends = self.line.step(host, self.drive);
        if ends.contention && !self.in_contention && self.own.checks.contention {
            self.checks.push(
                self.cycle,
                "one driver at a time (seed 001, 3.1.5: half-duplex bus, the host releases the line before the encoder answers)",
                "the host and an encoder drive the line together".into(),
            );
        }
        self.in_contention = ends.contention;
        let input = EncoderIn {
            rx: ends.at_device,
            trigger: self.trigger.step(pins.0 & 1 != 0),
            clr: self.clr.step(pins.0 & 8 != 0),
        };
        for (i, p) in self.shafts.moving(self.cycle) {
            // A motion profile wraps at the encoder's resolution: always fits.
            let _ = self.encoders[i].set_position(p);
        }
        let mut drive = Drive {
            enable: false,
            level: true,
        };
        for (i, e) in self.encoders.iter_mut().enumerate() {
            let d = e.step(&input);
            if d.enable && !drive.enable {
                drive = d;
            }
            if e.sent().len() > self.seen[i] {
                for f in &e.sent()[self.seen[i]..] {
                    self.entries.push(Entry {
                        index: self.entries.len() as u64,
                        device: i,
                        address: self.addresses[i],
                        cycle: f.cycle,
                        position: f.position,
                        bytes: hex(&f.bytes),
                    });
                    self.last[i] = Some(f.position);
                }
                self.seen[i] = e.sent().len();
            }
            if e.glitches() > self.glitches[i] {
                self.glitches[i] = e.glitches();
                self.checks.push(
                    self.cycle,
                    "T2 (seed 001, 3.1.3: the trigger pulse is low for T2 >= 10 us)",
                    format!(
                        "encoder {i} ignored a trigger pulse shorter than its trigger_min_low_us"
                    ),
                );
            }
        }
        if !self.mode.is_bus() {
            drive.enable = true;
        }
        self.drive = drive;
        self.cycle += 1;
        let flag = if self.checks.pending() {
            VIOLATION_PENDING
        } else {
            0
        };
        Pins(half_duplex_pins(host, ends.far) | flag)
    }

    fn set_position(&mut self, device: usize, position: u64) -> Result<()> {
        self.shafts.set_position(device, position)?;
        self.encoders[device]
            .set_position(position)
            .map_err(|e| Error::Usage(e.to_string()))
    }

    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        self.shafts.set_motion(device, toml, self.cycle)
    }

    fn set_status(&mut self, _device: usize, name: &str, _value: bool) -> Result<()> {
        Err(Error::Usage(format!(
            "a SAR58K24 frame carries no status bits (`{name}`): FF 81, the position and a checksum"
        )))
    }

    fn schedule_fault(&mut self, _toml: &str) -> Result<()> {
        Err(Error::Usage(
            "SAR58K24 frame faults are scheduled in the configuration (encoders[i].faults, by frame number)".into(),
        ))
    }

    fn count(&self) -> u64 {
        self.entries.len() as u64
    }

    fn last_value(&self, device: usize) -> Option<u64> {
        self.last.get(device).copied().flatten()
    }

    fn last_status(&self, _device: usize, name: &str) -> Result<bool> {
        Err(Error::Usage(format!(
            "a SAR58K24 frame carries no status bits (`{name}`)"
        )))
    }

    fn transcript(&self) -> serde_json::Value {
        serde_json::json!({
            "protocol": "sar58k24",
            "f_emu_hz": self.f_emu_hz,
            "frames": self.entries,
            "contention_cycles": self.line.contention,
            "violations": self.checks.all(),
        })
    }

    fn checks(&mut self) -> &mut Checks {
        &mut self.checks
    }
}
