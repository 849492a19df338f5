//! What the half-duplex UART emulators (SAR58K24, Modbus RTU) share: one
//! to three devices of a model behind one RS-485 cable to the host, set up
//! from the scenario's protocol table, with random position lists, run-time
//! positions and motion, the cable's two delay lines each way, the line at
//! the host's receiver and the output pins. A protocol's emulator keeps
//! only its devices' model, its transcript entries and its rule book's
//! watcher (which judges contention: one driver at a time).
//!
//! Pins: in bit 1 the host's driver level, bit 2 its enable; out bit 0 the
//! devices' level at the host's end of the cable, bit 1 their enable there,
//! bit 2 the resolved line level at the host's end (the nearer driver wins,
//! fail-safe high when undriven: what the host's receiver sees), bit 7 a
//! violation waiting.

use serde::Deserialize;

use model::line::{CableConfig, Drive, HalfDuplexLine};
use model::Timebase;

use crate::check::{Checks, VIOLATION_PENDING};
use crate::config::{self, Error};
use crate::motion::Motions;
use crate::{Pins, Result};

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

/// A tiny deterministic generator (splitmix64) for `[random]`.
fn splitmix(state: &mut u64) -> u64 {
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
fn own_tables<T: serde::de::DeserializeOwned + Default>(
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

/// A rule limit of a half-duplex emulator or monitor: the first value
/// `sources` give (`[monitor]`'s, `[checks]`', then the device's or the
/// host's field), else `default`, with the field it came from, refused
/// unless finite and non-negative (the rule book then holds it to its
/// rule's range).
pub(crate) fn rule_limit(
    origin: &str,
    sources: [(&'static str, Option<f64>); 3],
    default: f64,
) -> Result<(&'static str, f64)> {
    let (v, f) = crate::monitor::first_given(sources, default);
    crate::monitor::limit(origin, f, v, "give a finite non-negative number").map(|v| (f, v))
}

/// The character rules' limits both half-duplex rule books take, with the
/// fields they came from: the baud rate tolerance (%, 2 by default) and
/// the release after the request (bit times, 1), each `[monitor]`'s
/// (`mon`), else `[checks]`' (`chk`).
pub(crate) fn character_limits(
    origin: &str,
    mon: [Option<f64>; 2],
    chk: [Option<f64>; 2],
) -> Result<[(&'static str, f64); 2]> {
    Ok([
        rule_limit(
            origin,
            [
                ("monitor.baud_tolerance_percent", mon[0]),
                ("checks.baud_tolerance_percent", chk[0]),
                ("checks.baud_tolerance_percent", None),
            ],
            2.0,
        )?,
        rule_limit(
            origin,
            [
                ("monitor.release_bits", mon[1]),
                ("checks.release_bits", chk[1]),
                ("checks.release_bits", None),
            ],
            1.0,
        )?,
    ])
}

/// Gives each device (its resolution and its `positions` list) the random
/// positions `[random]` asks for (none: it keeps its list); returns the
/// devices' resolutions. `field` and `table` name the devices in errors.
pub(crate) fn randomize<'a>(
    r: &RandomPositions,
    devices: impl ExactSizeIterator<Item = (u32, &'a mut Vec<u64>)>,
    origin: &str,
    field: &str,
    table: &str,
) -> Result<Vec<u32>> {
    if devices.len() == 0 || devices.len() > 3 {
        return Err(Error::field(
            origin,
            field,
            format!("{} devices", devices.len()),
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
    Ok(devices
        .enumerate()
        .map(|(i, (bits, positions))| {
            if r.count > 0 {
                *positions = random_list(r.count, r.seed.wrapping_add(i as u64), bits.min(32));
            }
            bits
        })
        .collect())
}

/// The run-time positions of a half-duplex emulator's devices (SAR58K24,
/// Modbus): `set_position` and `set_motion` of [`Emulator`], checked here
/// once for both; the emulator hands the positions to its model devices.
struct Shafts {
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

/// Around a half-duplex emulator's devices, every cycle: the host's drive
/// from the pins, the cable, the contention check, the devices' positions
/// and motion, the emulator cycle and the pins out.
pub(crate) struct Bus {
    /// The host at end A (the pins), the devices at end B, fail-safe high.
    cable: HalfDuplexLine,
    /// What the devices drove in the last step.
    drive: Drive,
    /// The line level at the host's end in this step.
    at_host: bool,
    /// The emulator cycle.
    pub(crate) cycle: u64,
    pub(crate) checks: Checks,
    shafts: Shafts,
}

impl Bus {
    /// The bus of devices of `bits` (named `what` in errors) on `cable`, on
    /// the emulator clock `tb`.
    pub(crate) fn new(
        cable: &CableConfig,
        tb: &Timebase,
        bits: Vec<u32>,
        what: &'static str,
    ) -> Self {
        Bus {
            cable: HalfDuplexLine::new(cable.delay_cycles(tb), true),
            drive: IDLE,
            at_host: true,
            cycle: 0,
            checks: Checks::new(tb.period_ps()),
            shafts: Shafts::new(tb, bits, what),
        }
    }

    /// The first half of a step: the host drives `pins` now, the cable
    /// moves one cycle; returns the level the devices' receivers see. The
    /// caller then hands the moving positions ([`Bus::moving`]) to its
    /// devices, steps them and ends the step with [`Bus::end`].
    pub(crate) fn begin(&mut self, pins: Pins) -> bool {
        let host = Drive {
            enable: pins.0 & 4 != 0,
            level: pins.0 & 2 != 0,
        };
        // The devices answer after this step: the cable carries what they
        // drove in the last one.
        let (at_host, at_device) = self.cable.step(host, self.drive);
        self.at_host = at_host.level;
        at_device.level
    }

    /// The positions of the moving devices now.
    pub(crate) fn moving(&self) -> Vec<(usize, u64)> {
        self.shafts.moving(self.cycle)
    }

    /// The second half of a step: the devices drove `drive` (they reach the
    /// host from the next step on); returns the pins out.
    pub(crate) fn end(&mut self, drive: Drive) -> Pins {
        self.drive = drive;
        self.cycle += 1;
        let flag = if self.checks.pending() {
            VIOLATION_PENDING
        } else {
            0
        };
        let far = self.cable.b_at_a();
        Pins(far.level as u32 | (far.enable as u32) << 1 | (self.at_host as u32) << 2 | flag)
    }

    /// `set_position(device, position)` of [`crate::Emulator`]: checked,
    /// the device's motion stopped, then `set` hands it to the device's model.
    pub(crate) fn set_position(
        &mut self,
        device: usize,
        position: u64,
        set: impl FnOnce(u64) -> model::Result<()>,
    ) -> Result<()> {
        self.shafts.set_position(device, position)?;
        set(position).map_err(|e| Error::Usage(e.to_string()))
    }

    /// `set_motion(device, toml)` of [`crate::Emulator`], from this cycle on.
    pub(crate) fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        self.shafts.set_motion(device, toml, self.cycle)
    }

    /// A breach of the rule book, at the emulator cycle of its time
    /// (`f_hz` the emulator clock).
    pub(crate) fn breach(&mut self, f_hz: u64, b: &model::rules::Breach) {
        let ps = model::time::PS_PER_S as u128;
        let cycle = (b.at_ps as u128 * f_hz as u128 + ps / 2) / ps;
        self.checks.breach(cycle as u64, b);
    }

    /// Cycles in which two drivers were on at one end.
    pub(crate) fn contention_cycles(&self) -> u64 {
        self.cable.contention_cycles()
    }
}

/// No driver on: the line's fail-safe level.
pub(crate) const IDLE: Drive = Drive {
    enable: false,
    level: true,
};

/// The line at the host's receiver: the devices' level while they drive
/// at the host's end (`out`, the emulator's last pins out: bit 0 their
/// level, bit 1 their enable), else the host's own driver (`tx` while `de`),
/// else high (the fail-safe bias of an idle RS-485 pair). The rule books'
/// watchers read it here in the emulator, and the probes wire a monitor's
/// receiver from it.
pub fn receiver(tx: bool, de: bool, out: Pins) -> bool {
    if out.enable() {
        out.data()
    } else {
        !de || tx
    }
}

/// The devices' drive on the shared line: the first device that drives wins
/// (`drive` so far, then device `d`).
pub(crate) fn wire(drive: Drive, d: Drive) -> Drive {
    if d.enable && !drive.enable {
        d
    } else {
        drive
    }
}
