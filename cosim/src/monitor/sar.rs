//! The SAR58K24 asynchronous-serial monitor: the host's side of the line
//! (seed 001, 3.1.1 to 3.1.6): its RS-485 driver (bus commands), its
//! receiver (the encoders' frames), its trigger (CLK of the handshake
//! modes) and CLR outputs.
//!
//! Pins in: bit 0 the host's receiver output (R), bit 1 its driver input
//! (D), bit 2 its driver enable (DE), bit 3 the trigger, bit 4 CLR (both
//! idle high). Events are decoded by [`model::sar58k24::decode`] (the
//! decoder of `tbgen decode sar`) from the wire at the host (D while DE is
//! on, else R) and DE, piece by piece: the line is cut wherever it has been
//! idle for the host's gap after a character, and the piece before is
//! decoded and dropped. The checks ([`super::uart`] for the shared ones),
//! each with one monitor cycle of tolerance:
//!
//! * character timing of the host's commands: every edge within the baud
//!   rate tolerance of the bit grid (`monitor.baud_tolerance_percent`, 2;
//!   the seed gives none), the parity bit right, the stop bit high and a
//!   full bit (seed 001: start, 8 data, "no parity check bit" or the
//!   customer's parity, stop);
//! * command gap: the three characters of `BC AA Bx` with at most the
//!   encoder's `command_gap_bits` (15) of silence between them (the
//!   project's reading, `docs/timing/sar58k24.md`: the encoder drops such a
//!   command);
//! * turnaround: DE off within `monitor.release_bits` (1) of the command's
//!   last stop bit; never both drivers on; DE never switched on inside a
//!   character of an encoder's frame;
//! * answer wait: after a read command (and a zeroing command the encoder
//!   answers, `answer_zeroing`) or a trigger, the next command or trigger
//!   only once the answer began or the host's `timeout_us` passed;
//! * T2 (3.1.3: "The falling edge of the external pulse signal triggers the
//!   encoder to work, T2 ≥ 10 µs"): every trigger low pulse at least the
//!   encoder's `trigger_min_low_us`; a trigger's falling edge not inside a
//!   character of the encoder's frame ("T1-T3: data transmission time");
//! * CLR: every CLR low pulse at least the encoder's `clr_min_low_us` (the
//!   manual gives only the level; 10 µs is the project's reading).

use serde::Deserialize;
use serde_json::Value;

use model::sar58k24::decode::{Decoder, Options};
use model::sar58k24::{BenchConfig, Mode};

use super::modbus::EmulatorOwn;
use super::uart::{self, Limits, Line, Rules, Watch};
use super::{field, first_given, host_timeout_us, limit, listens_only, proto_table, sub, Base};
use crate::config::{self, Error};
use crate::{Emulator, Pins, Result};

/// The rules, as the seed states them (or the project's reading).
pub const RULE_CHARACTER: &str = "character timing (seed 001 3.1.5: commands BC AA Bx as characters of start, 8 data LSB first, the configured parity, stop; baud rate tolerance: the project's reading, docs/timing/sar58k24.md)";
/// See [`RULE_CHARACTER`].
pub const RULE_GAP: &str = "command gap (seed 001 3.1.5, 3.1.6: BC AA Bx as one command; the project's reading: at most command_gap_bits of silence between its characters)";
/// See [`RULE_CHARACTER`].
pub const RULE_RELEASE: &str =
    "turnaround (seed 001 3.1.5: the host releases the shared RS-485 line after its command)";
/// See [`RULE_CHARACTER`].
pub const RULE_ANSWER: &str =
    "turnaround (seed 001 3.1.5: one driver at a time; never during an encoder's answer)";
/// See [`RULE_CHARACTER`].
pub const RULE_WAIT: &str = "answer wait (seed 001 3.1.3, 3.1.5: one answer per trigger or command; the host waits for it or its timeout, [host] timeout_us)";
/// See [`RULE_CHARACTER`].
pub const RULE_T2: &str =
    "T2 (seed 001 3.1.3: the falling edge of the external pulse triggers the encoder, T2 >= 10 us)";
/// See [`RULE_CHARACTER`].
pub const RULE_TRIGGER_BUSY: &str =
    "T1-T3 (seed 001 3.1.3: the data transmission time; a trigger inside the encoder's frame)";
/// See [`RULE_CHARACTER`].
pub const RULE_CLR: &str = "CLR (seed 001 3.1.2, 3.1.4: a low level on CLR zeroes; the project's reading: at least clr_min_low_us)";

/// The monitor's own table (`[monitor]`), every field optional.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct MonitorTable {
    timeout_us: Option<f64>,
    baud_tolerance_percent: Option<f64>,
    release_bits: Option<f64>,
    t2_us: Option<f64>,
    clr_min_low_us: Option<f64>,
    command_gap_bits: Option<f64>,
}

/// A SAR58K24 monitor.
pub struct SarMonitor {
    base: Base,
    watch: Watch,
    line: Line,
    decoder: Decoder,
    /// Bit time and the idle after a character's start that cuts the line, ps.
    cut_after_ps: u64,
    /// A character and half a bit, ps: the line is cut between two of the
    /// encoder's characters once the last has ended and the line is idle.
    char_ps: u64,
    last_fall: Option<u64>,
    wire: bool,
    /// The host's driver enable at the last step.
    de: bool,
    /// The last character on the line is the encoder's and not yet cut after.
    uncut_answer: bool,
    handshake: bool,
    zero_answered: bool,
    t2_ps: u64,
    clr_ps: u64,
    trigger: (bool, u64),
    clr: (bool, u64),
    /// Frames in `base.done`.
    frames: u64,
}

impl SarMonitor {
    /// A monitor from TOML text (`origin` names it in errors) at `f_mon_hz`.
    pub fn from_toml(text: &str, origin: &str, f_mon_hz: u64) -> Result<Self> {
        let (_, _, cfg): (_, EmulatorOwn, BenchConfig) = crate::half_duplex::uart_bench(
            text,
            origin,
            f_mon_hz,
            "sar",
            "the SAR58K24 monitor",
            115_200.0,
        )?;
        let whole = proto_table(text, origin, "sar")?;
        let mon: MonitorTable = config::decode_in(&whole, "monitor", origin)?;
        let host = sub(&whole, "host", origin)?;
        let enc = cfg.encoders.first().cloned().unwrap_or_default();
        let timeout = host_timeout_us(mon.timeout_us, &host, origin, 5000.0)?;
        let gap_bits: f64 = field(&host, "gap_bits", origin, "host.gap_bits")?.unwrap_or(15.0);
        let tol = limit(
            origin,
            "monitor.baud_tolerance_percent",
            mon.baud_tolerance_percent.unwrap_or(2.0),
            "give the baud rate tolerance of the host's characters in percent (2)",
        )?;
        let release = limit(
            origin,
            "monitor.release_bits",
            mon.release_bits.unwrap_or(1.0),
            "give the longest time from the command's last stop bit to DE off, in bit times (1)",
        )?;
        let (t2, t2_field) = first_given(
            [
                ("monitor.t2_us", mon.t2_us),
                (
                    "encoders[0].trigger_min_low_us",
                    Some(enc.trigger_min_low_us),
                ),
            ],
            0.0,
        );
        let t2 = limit(
            origin,
            t2_field,
            t2,
            "give the shortest trigger pulse in µs (seed 001: T2 >= 10)",
        )?;
        let (clr, clr_field) = first_given(
            [
                ("monitor.clr_min_low_us", mon.clr_min_low_us),
                ("encoders[0].clr_min_low_us", Some(enc.clr_min_low_us)),
            ],
            0.0,
        );
        let clr = limit(
            origin,
            clr_field,
            clr,
            "give the shortest CLR pulse in µs (10)",
        )?;
        let (cmd_gap, cmd_gap_field) = first_given(
            [
                ("monitor.command_gap_bits", mon.command_gap_bits),
                ("encoders[0].command_gap_bits", Some(enc.command_gap_bits)),
            ],
            0.0,
        );
        let cmd_gap = limit(
            origin,
            cmd_gap_field,
            cmd_gap,
            "give the longest silence between two characters of a command in bit times (15)",
        )?;
        let fb = cfg.parity.frame_bits() as f64;
        let bit_ps = 1e12 / cfg.baud;
        let limits = Limits {
            bit_ps,
            parity: cfg.parity,
            tolerance: tol / 100.0,
            max_gap_ps: cmd_gap * bit_ps,
            min_silence_ps: 0.0,
            release_ps: release * bit_ps,
            timeout_ps: timeout * 1e6,
        };
        let rules = Rules {
            character: RULE_CHARACTER,
            gap: RULE_GAP,
            silence: RULE_GAP,
            release: RULE_RELEASE,
            answer: RULE_ANSWER,
            wait: RULE_WAIT,
        };
        let options = Options {
            baud: cfg.baud,
            parity: cfg.parity,
            bits: enc.bits,
            gray: enc.code == model::sar58k24::OutputCode::Gray,
            gap_bits,
            answer_tag: enc.answer_tag,
        };
        Ok(SarMonitor {
            base: Base::new(f_mon_hz),
            watch: Watch::new(limits, rules),
            line: Line::new(),
            decoder: Decoder::new(options),
            cut_after_ps: ((fb + gap_bits + 1.0) * bit_ps).ceil() as u64,
            char_ps: ((fb + 0.5) * bit_ps).ceil() as u64,
            last_fall: None,
            wire: true,
            de: false,
            uncut_answer: false,
            handshake: matches!(cfg.mode, Mode::Handshake | Mode::HandshakeClear),
            zero_answered: enc.answer_zeroing,
            t2_ps: (t2 * 1e6).round() as u64,
            clr_ps: (clr * 1e6).round() as u64,
            trigger: (true, 0),
            clr: (true, 0),
            frames: 0,
        })
    }

    /// The events not yet in `base.done` (the decoder's state is not changed).
    fn pending(&self) -> Vec<Value> {
        let mut d = self.decoder.clone();
        d.feed(&self.line.wire, &self.line.de)
            .into_iter()
            .map(|b| serde_json::to_value(b).unwrap_or(Value::Null))
            .collect()
    }

    /// The last event that is a frame (`frames`) or not a command, the piece in progress included.
    fn last_where(&self, frames: bool) -> Option<Value> {
        let keep = |e: &Value| {
            if frames {
                e["kind"] == "frame"
            } else {
                e["kind"] != "command"
            }
        };
        self.pending()
            .into_iter()
            .rev()
            .find(keep)
            .or_else(|| self.base.done.iter().rev().find(|e| keep(e)).cloned())
    }

    /// Decodes the piece of line before `now` into `base.done` and starts
    /// the next piece there: after an idle gap (`carry` false: the piece
    /// ends the frame finder's run, and the gap cut waits for the next
    /// character), or between two of the encoder's characters (`carry`).
    fn cut(&mut self, now: u64, carry: bool) {
        let events = if carry {
            self.decoder.feed_carrying(&self.line.wire, &self.line.de)
        } else {
            self.decoder.feed(&self.line.wire, &self.line.de)
        };
        self.frames += events.iter().filter(|b| b.kind == "frame").count() as u64;
        self.base.done.extend(
            events
                .into_iter()
                .map(|b| serde_json::to_value(b).unwrap_or(Value::Null)),
        );
        self.line.cut(now);
        self.uncut_answer = false;
        if !carry {
            self.last_fall = None;
        }
    }

    fn pulse(&mut self, now: u64, level: bool, clr: bool) {
        let (last, since) = if clr { self.clr } else { self.trigger };
        if level == last {
            return;
        }
        if level {
            let low = now - since;
            let (min, rule, name) = if clr {
                (self.clr_ps, RULE_CLR, "CLR")
            } else {
                (self.t2_ps, RULE_T2, "trigger")
            };
            if low + self.base.period_ps < min {
                self.base.violation(
                    now,
                    rule,
                    format!(
                        "{name} low for {:.3} us; at least {:.3} us",
                        low as f64 / 1e6,
                        min as f64 / 1e6
                    ),
                );
            }
        } else if !clr {
            if self.watch.device_busy(now) {
                self.base.violation(
                    now,
                    RULE_TRIGGER_BUSY,
                    "a trigger's falling edge while the encoder sends a character of its frame"
                        .to_string(),
                );
            }
            self.watch.check_wait(&mut self.base, now, "a trigger");
            if self.handshake {
                self.watch.expect_answer(now);
            }
        }
        if clr {
            self.clr = (level, now);
        } else {
            self.trigger = (level, now);
        }
    }
}

impl Emulator for SarMonitor {
    fn kind(&self) -> &'static str {
        "sar58k24_monitor"
    }

    fn step(&mut self, pins: Pins) -> Pins {
        let now = self.base.now_ps();
        let (rx, tx, de) = uart::pins(pins);
        let wire = if de { tx } else { rx };
        if self
            .last_fall
            .is_some_and(|f| wire && self.wire && now >= f + self.cut_after_ps)
        {
            // The line has been idle the host's gap after the last character: decode the piece.
            self.cut(now, false);
        } else if self.uncut_answer
            && !de
            && !self.de
            && wire
            && self.wire
            && self.last_fall.is_some_and(|f| now >= f + self.char_ps)
        {
            // Between two of the encoder's characters, the line idle: cut
            // here too, carrying the frame finder over (the events are those
            // of one piece), so that `count` and `last_value`, which decode
            // the piece since the last cut on every call, decode one
            // transaction, not every read since the last idle gap (the
            // testbench's reads may follow each other closer than that).
            self.cut(now, true);
        }
        if !wire && self.wire {
            self.last_fall = Some(now);
            self.uncut_answer = !de;
        }
        self.wire = wire;
        self.de = de;
        self.line.step(now, tx, de, rx);
        if let Some(r) = self.watch.step(&mut self.base, now, tx, de, rx) {
            let answered = match model::sar58k24::frames::parse_command(&r.bytes) {
                Some(model::sar58k24::frames::Command::Read(_)) => true,
                Some(model::sar58k24::frames::Command::Zero(_)) => self.zero_answered,
                None => false,
            };
            if answered {
                self.watch.expect_answer(now);
            }
        }
        self.pulse(now, pins.0 & 8 != 0, false);
        self.pulse(now, pins.0 & 16 != 0, true);
        self.base.step_out()
    }

    fn set_position(&mut self, _: usize, _: u64) -> Result<()> {
        Err(listens_only("sar58k24_monitor", "position to set"))
    }

    fn set_status(&mut self, _: usize, _: &str, _: bool) -> Result<()> {
        Err(listens_only("sar58k24_monitor", "status to set"))
    }

    fn schedule_fault(&mut self, _: &str) -> Result<()> {
        Err(listens_only("sar58k24_monitor", "faults to schedule"))
    }

    /// Frames accepted so far (positions; the piece in progress included).
    fn count(&self) -> u64 {
        self.frames
            + self
                .pending()
                .iter()
                .filter(|e| e["kind"] == "frame")
                .count() as u64
    }

    /// The position of the last frame accepted (binary, after Gray decoding).
    fn last_value(&self, _: usize) -> Option<u64> {
        self.last_where(true)?["position"].as_u64()
    }

    /// A flag of the last event on the line that is not a command
    /// (`checksum`, `parity`, `frame`, `address`), or `frame_ok` (it was a frame).
    fn last_status(&self, _: usize, name: &str) -> Result<bool> {
        let e = self
            .last_where(false)
            .ok_or_else(|| Error::Usage("sar58k24_monitor: no frame decoded yet".into()))?;
        match name {
            "frame_ok" => Ok(e["kind"] == "frame"),
            "checksum" | "parity" | "frame" | "address" => Ok(e["errors"].as_array().is_some_and(|x| x.iter().any(|f| f == name))),
            other => Err(Error::Usage(format!("sar58k24_monitor: no status `{other}`; give frame_ok, checksum, parity, frame or address"))),
        }
    }

    fn transcript(&self) -> Value {
        self.base.transcript(
            "sar",
            &["rx", "tx", "tx_en", "trigger", "clr"],
            self.pending(),
        )
    }

    fn checks(&mut self) -> &mut crate::check::Checks {
        &mut self.base.checks
    }
}
