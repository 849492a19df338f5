//! The ESL monitor: the host's side of the half-duplex RS-485 bus.
//!
//! Pins in: bit 0 the host's receiver output (RO: the bus as the host hears
//! it), bit 1 its driver input (DI), bit 2 its driver enable (DE).
//! Operations are decoded by [`model::esl::decode`] (the decoder of `tbgen
//! decode esl`) from the wire at the host (DI while DE is on, else RO) and
//! DE. The checks (seed 000, QS35 ESL Safety protocol), each with one
//! monitor cycle of tolerance, at the host's pins ([`super::half_duplex`]
//! for the shared ones):
//!
//! * character timing (Table 1: 10 Mbps, 10 bits a frame; Figure 1: start,
//!   8 data, stop): every edge of a request frame on the bit grid from its
//!   start edge within `monitor.bit_tolerance_percent` (default the
//!   emulator's `checks.bit_tolerance_percent`, 3 %; the seed gives none)
//!   of the time since that edge, the stop bit high and a full bit, DE not
//!   released inside a frame;
//! * a request's frames back to back (Figure 1: "if there is no Start Bit
//!   after the End Bit of the last frame read ... end of transmission frame
//!   set"): the next start bit within `monitor.max_gap_bits` (0.5) of the
//!   stop bit's end, and the request has the frames of its Data ID (Table
//!   12: RCF and CRC; E adds ADF, F adds ADF and EDF);
//! * turnaround (Table 1: half duplex; Figure 2: the encoder answers "after
//!   2.0 µs (typical)"): DE off within `monitor.release_us` (1.0, half the
//!   typical answer delay) of the request's last stop bit; never DE on
//!   while an encoder drives RO low against a 1 of the host; never DE
//!   switched on inside an answer;
//! * request spacing, per encoder address: B, C, D "minimum 8 times
//!   consecutively at a typical interval of 40 µs" (Table 4: each within
//!   the encoder's `repeat_window_us`, 200, of the one before, none
//!   interrupted by another request to that address before the 8th); "more
//!   than 200 us between each memory read operation" and "more than 6 ms
//!   between each memory write operation" (EEPROM, not the page register or
//!   the register page 8; the encoder's `eeprom_read_us`,
//!   `eeprom_write_us`); after a page-register write "allow a 18ms delay"
//!   before the next memory access (Table 11 note 3; `page_change_us`).
//!
//! Configuration (the emulator's file or a whole scenario will do): `baud`,
//! `[[encoders]]` (address and the four times above), `[host]`
//! `broadcast_address`, `busy_tries`, `rs_tolerance` (how the decoder
//! judges answers), `[checks] bit_tolerance_percent`, and `[monitor]` with
//! `bit_tolerance_percent`, `max_gap_bits`, `release_us`, and the host
//! settings and encoder times above (for every address).

use serde::Deserialize;
use serde_json::Value;

use model::esl::decode::{DecodeOptions, DecodedOp, Decoder};
use model::esl::frames::{self, DataId};
use model::esl::EncoderSettings;
use model::wire::uart_bytes;

use super::half_duplex::{ExchangeDecoder, Exchanges, Limits, Request, Rules, Side, Window};
use super::{field, limit, listens_only, proto_table, sub, Base};
use crate::config::{self, Error};
// The ALM flags by name, as the emulator takes them.
use crate::esl::ALARMS;
use crate::{Emulator, Pins, Result};

/// The rules, as the seed states them.
pub const RULE_CHARACTER: &str =
    "character timing (seed 000 Table 1, Figure 1: 10 Mbps, 10-bit frames, start, 8 data, stop)";
/// See [`RULE_CHARACTER`].
pub const RULE_GAP: &str = "request frame (seed 000 Figure 1: a frame set ends when no start bit follows a stop bit; a request's frames back to back)";
/// See [`RULE_CHARACTER`].
pub const RULE_FIELDS: &str = "request frame (seed 000 Table 12: a request is RCF and CRC; Data ID E adds ADF, F adds ADF and EDF)";
/// See [`RULE_CHARACTER`].
pub const RULE_RELEASE: &str = "turnaround (seed 000 Figure 2: the encoder answers 2.0 us (typ.) after the request; half duplex, the host releases the line before)";
/// See [`RULE_CHARACTER`].
pub const RULE_ANSWER: &str =
    "turnaround (seed 000 Table 1: half duplex; the host does not drive while an encoder answers)";
/// See [`RULE_CHARACTER`].
pub const RULE_REPEAT: &str = "request spacing (seed 000 Table 4: B, C, D minimum 8 times consecutively at a typical interval of 40 us)";
/// See [`RULE_CHARACTER`].
pub const RULE_READ: &str =
    "request spacing (seed 000: wait more than 200 us between each memory read operation)";
/// See [`RULE_CHARACTER`].
pub const RULE_WRITE: &str =
    "request spacing (seed 000: wait more than 6 ms between each memory write operation)";
/// See [`RULE_CHARACTER`].
pub const RULE_PAGE: &str = "request spacing (seed 000 Table 11 note 3: once the page value is changed, allow a 18 ms delay)";

/// The error names of an operation (`model::esl::error_names`).
const ERRORS: [&str; 9] = [
    "crc1",
    "crc2",
    "timeout",
    "frame",
    "cf_mismatch",
    "comm_alarm",
    "sequence",
    "channel_mismatch",
    "busy",
];

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    bit_tolerance_percent: Option<f64>,
    max_gap_bits: Option<f64>,
    release_us: Option<f64>,
    broadcast_address: Option<u8>,
    busy_tries: Option<u64>,
    rs_tolerance: Option<u16>,
    repeat_window_us: Option<f64>,
    eeprom_read_us: Option<f64>,
    eeprom_write_us: Option<f64>,
    page_change_us: Option<f64>,
}

/// One encoder address's limits (ps) and spacing state.
#[derive(Debug, Clone, Default)]
struct Spacing {
    window: u64,
    read: u64,
    write: u64,
    page_change: u64,
    page: u8,
    /// B/C/D in progress: Data ID, requests so far, end of the last.
    repeat: Option<(u8, u32, u64)>,
    last_read: Option<u64>,
    last_write: Option<u64>,
    page_write: Option<u64>,
}

/// The decoder and the bit time.
#[derive(Debug, Clone)]
struct Decode(Decoder, u64);

impl ExchangeDecoder for Decode {
    fn exchange(&mut self, line: &Exchanges, (rise, fall, next): Window) -> Option<Value> {
        self.0
            .exchange(rise, fall, next, &uart_bytes(&line.wire, self.1))
            .map(json)
    }

    fn finish(&mut self) -> Option<Value> {
        self.0.finish().map(json)
    }
}

fn json(t: DecodedOp) -> Value {
    serde_json::to_value(t).unwrap_or(Value::Null)
}

/// An ESL monitor.
pub struct EslMonitor {
    side: Side<Decode>,
    spacing: Vec<Spacing>,
}

impl EslMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let tables = config::tables(text, origin, "esl")?;
        let whole = proto_table(text, origin, "esl")?;
        let baud: f64 = field::<f64>(&whole, "baud", origin, "baud")?.unwrap_or(10e6);
        if !(1e3..=50e6).contains(&baud) {
            return Err(Error::field(
                origin,
                "baud",
                format!("{baud} bit/s"),
                "give the bit rate in bit/s (seed 000: 10e6)",
            ));
        }
        let mut settings = tables.emulator.clone();
        settings.max_line_clock_khz = settings.max_line_clock_khz.or(Some(baud / 1e3));
        config::emulator_clock(
            f_mon_hz,
            &settings,
            baud / 1e3,
            "the ESL monitor (its line clock is the bit rate)",
            origin,
        )?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let host = sub(&whole, "host", origin)?;
        let checks = sub(&whole, "checks", origin)?;
        let tolerance = mon
            .bit_tolerance_percent
            .or(field(
                &checks,
                "bit_tolerance_percent",
                origin,
                "checks.bit_tolerance_percent",
            )?)
            .unwrap_or(3.0);
        if !(0.0..=20.0).contains(&tolerance) {
            return Err(Error::field(
                origin,
                "monitor.bit_tolerance_percent",
                format!("{tolerance}"),
                "give 0 to 20 %",
            ));
        }
        let gap = limit(
            origin,
            "monitor.max_gap_bits",
            mon.max_gap_bits.unwrap_or(0.5),
            "give the longest idle line between two frames of a request, in bits",
        )?;
        let release = limit(
            origin,
            "monitor.release_us",
            mon.release_us.unwrap_or(1.0),
            "give the longest time from the request's last stop bit to DE off, in µs",
        )?;
        let broadcast_address = mon
            .broadcast_address
            .or(field(
                &host,
                "broadcast_address",
                origin,
                "host.broadcast_address",
            )?)
            .unwrap_or(7);
        let busy_tries = mon
            .busy_tries
            .or(field(&host, "busy_tries", origin, "host.busy_tries")?)
            .unwrap_or(3);
        let rs_tolerance = mon
            .rs_tolerance
            .or(field(&host, "rs_tolerance", origin, "host.rs_tolerance")?)
            .unwrap_or(1);
        if broadcast_address > 7 || !(1..=15).contains(&busy_tries) {
            return Err(Error::field(
                origin,
                "monitor.broadcast_address",
                format!("{broadcast_address}, busy_tries {busy_tries}"),
                "give a broadcast address 0..7 and busy_tries 1..15",
            ));
        }
        let base = Base::new(f_mon_hz);
        let ps = |us: f64| ((us * 1e6).round() as u64).saturating_sub(base.period_ps);
        let d = EncoderSettings::default();
        let mut spacing = vec![Spacing::default(); 8];
        let encoders: Vec<toml::Table> =
            field(&whole, "encoders", origin, "encoders")?.unwrap_or_default();
        for a in 0..8u8 {
            let e = encoders.iter().find(|e| {
                e.get("address").and_then(|v| v.as_integer()) == Some(a as i64)
                    || (a == 0 && e.get("address").is_none())
            });
            let time = |key: &str, given: Option<f64>, default: f64| -> Result<u64> {
                let from_encoder = match e {
                    Some(t) => field::<f64>(t, key, origin, &format!("encoders.{key}"))?,
                    None => None,
                };
                Ok(ps(limit(
                    origin,
                    &format!("monitor.{key}"),
                    given.or(from_encoder).unwrap_or(default),
                    "give a time in µs",
                )?))
            };
            let s = &mut spacing[a as usize];
            s.window = time("repeat_window_us", mon.repeat_window_us, d.repeat_window_us)?;
            s.read = time("eeprom_read_us", mon.eeprom_read_us, d.eeprom_read_us)?;
            s.write = time("eeprom_write_us", mon.eeprom_write_us, d.eeprom_write_us)?;
            s.page_change = time("page_change_us", mon.page_change_us, d.page_change_us)?;
            s.page = frames::DEFAULT_PAGE;
        }
        let bit_ps = (1e12 / baud).round() as u64;
        let limits = Limits {
            bit_ps: 1e12 / baud,
            tolerance: tolerance / 100.0,
            jitter_ps: 0.0,
            max_gap_ps: gap * 1e12 / baud,
            release_ps: (release * 1e6).round() as u64,
        };
        let rules = Rules {
            character: RULE_CHARACTER,
            gap: RULE_GAP,
            release: RULE_RELEASE,
            answer: RULE_ANSWER,
        };
        Ok(EslMonitor {
            side: Side::new(
                base,
                limits,
                rules,
                Decode(
                    Decoder::new(DecodeOptions {
                        baud,
                        broadcast_address,
                        busy_tries,
                        rs_tolerance,
                    }),
                    bit_ps,
                ),
            ),
            spacing,
        })
    }

    fn on_request(&mut self, r: Request) {
        let Some(&byte) = r.fields.first() else {
            return;
        };
        let cf = frames::parse_control_field(byte);
        let id = DataId::from_code(cf.code);
        if id.is_some() && !r.damaged {
            let want = frames::request(0, cf.code, 0, 0).len();
            if r.fields.len() != want {
                self.side.base.violation(
                    r.end_ps,
                    RULE_FIELDS,
                    format!(
                        "a request of {} frame(s) for Data ID {:X}, which takes {want}",
                        r.fields.len(),
                        cf.code
                    ),
                );
            }
        }
        if !cf.parity_ok {
            return;
        }
        let s = &mut self.spacing[usize::from(cf.address & 7)];
        let end = r.end_ps;
        let ms = |ps: u64| ps as f64 / 1e6;
        let tol = self.side.base.period_ps;
        let mut found: Vec<(&'static str, String)> = Vec::new();
        match (s.repeat, id.filter(|d| d.is_repeated())) {
            (Some((rid, k, at)), Some(_)) if rid == cf.code => {
                if end - at > s.window + 2 * tol {
                    found.push((RULE_REPEAT, format!("request {} of Data ID {:X} to address {} {:.1} us after the one before, beyond the encoder's repeat window of {:.1} us (the count starts again)", k + 1, cf.code, cf.address, ms(end - at), ms(s.window + tol))));
                    s.repeat = Some((rid, 1, end));
                } else {
                    s.repeat = (k + 1 < 8).then_some((rid, k + 1, end));
                }
            }
            (prev, now_id) => {
                if let Some((rid, k, _)) = prev {
                    found.push((RULE_REPEAT, format!("Data ID {rid:X} sent {k} time(s) to address {}, then Data ID {:X}: the command takes 8 in a row", cf.address, cf.code)));
                }
                s.repeat = now_id.map(|_| (cf.code, 1, end));
            }
        }
        if let Some(id) = id.filter(|d| d.is_memory()) {
            let address = r.fields.get(1).map_or(0, |a| a >> 1);
            if let Some(c) = s.page_write.map(|t| end - t).filter(|&c| c < s.page_change) {
                found.push((RULE_PAGE, format!("a memory access {:.1} us after a write to the page register (page change {:.1} us)", ms(c), ms(s.page_change + tol))));
            }
            let eeprom = address != frames::PAGE_REGISTER && s.page != frames::REGISTER_PAGE;
            if id == DataId::IdE && eeprom {
                if let Some(c) = s.last_read.map(|t| end - t).filter(|&c| c < s.read) {
                    found.push((
                        RULE_READ,
                        format!(
                            "an EEPROM read {:.1} us after the one before (read time {:.1} us)",
                            ms(c),
                            ms(s.read + tol)
                        ),
                    ));
                }
                s.last_read = Some(end);
            }
            if id == DataId::IdF {
                if address == frames::PAGE_REGISTER {
                    s.page_write = Some(end);
                    s.page = r.fields.get(2).copied().unwrap_or(0) & 0xF;
                } else if eeprom {
                    if let Some(c) = s.last_write.map(|t| end - t).filter(|&c| c < s.write) {
                        found.push((RULE_WRITE, format!("an EEPROM write {:.1} us after the one before (write time {:.1} us)", ms(c), ms(s.write + tol))));
                    }
                    s.last_write = Some(end);
                }
            }
        }
        for (rule, detail) in found {
            self.side.base.violation(end, rule, detail);
        }
    }
}

impl Emulator for EslMonitor {
    fn kind(&self) -> &'static str {
        "esl_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        if let Some(r) = self.side.step(pins) {
            self.on_request(r);
        }
        self.side.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("esl_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("esl_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("esl_monitor", "faults to schedule"))
    }

    /// Operations seen so far (the one in progress included; B, C, D's eight requests are one).
    fn count(&self) -> u64 {
        self.side.count()
    }

    /// `abm << 24 | abs` after the last operation (the host's registers: held through a short answer).
    fn last_value(&self, _: usize) -> Option<u64> {
        let t = self.side.last()?;
        Some(t["abm"].as_u64()? << 24 | t["abs"].as_u64()?)
    }

    /// An error of the last operation (`crc1`, `crc2`, `timeout`, `frame`,
    /// `cf_mismatch`, `comm_alarm`, `sequence`, `channel_mismatch`, `busy`)
    /// or an ALM flag (ALM1) after it.
    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        let t = self
            .side
            .last()
            .ok_or_else(|| Error::Usage("esl_monitor: no operation decoded yet".into()))?;
        if let Some(&(_, bit)) = ALARMS.iter().find(|a| a.0 == name) {
            return Ok(t["alm1"].as_u64().unwrap_or(0) >> bit & 1 == 1);
        }
        if ERRORS.contains(&name) {
            return Ok(t["errors"]
                .as_array()
                .is_some_and(|e| e.iter().any(|x| x == name)));
        }
        Err(Error::Usage(format!("esl_monitor: no status `{name}`; give an error ({}) or an ALM flag (xc, mt, led, lis, overspeed, mem, st, uv, ov)", ERRORS.join(", "))))
    }

    fn transcript(&self) -> Value {
        self.side.transcript("esl")
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.side.base.checks
    }
}
