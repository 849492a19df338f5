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
//! decoded and dropped. The rules are the rule book's,
//! [`model::sar58k24::rules`] (characters, command gap, release, one
//! driver, answer wait, T2, T1-T3, CLR): the monitor feeds its watcher the
//! host's pins every cycle, as the emulator does, and prints what it
//! returns; the limits are the emulator's ([`crate::sar58k24`]'s
//! `rule_limits`: `[monitor]`, then `[checks]`, then the host's and the
//! first encoder's settings).

use serde_json::Value;

use model::sar58k24::decode::{Decoder, Options};
use model::sar58k24::rules::{HostPins, Watch};
use model::sar58k24::BenchConfig;

use super::modbus::EmulatorOwn;
use super::uart::{self, Line};
use super::{field, listens_only, proto_table, sub, Base};
use crate::config::Error;
use crate::{Emulator, Pins, Result};

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
        let host = sub(&whole, "host", origin)?;
        let enc = cfg.encoders.first().cloned().unwrap_or_default();
        let gap_bits: f64 = field(&host, "gap_bits", origin, "host.gap_bits")?.unwrap_or(15.0);
        let limits = crate::sar58k24::rule_limits(text, origin, &cfg)?;
        let fb = cfg.parity.frame_bits() as f64;
        let bit_ps = 1e12 / cfg.baud;
        let mut base = Base::new(f_mon_hz);
        for note in model::rules::resolution_notes(f_mon_hz, &limits.least()) {
            base.checks.note(note);
        }
        let options = Options {
            baud: cfg.baud,
            parity: cfg.parity,
            bits: enc.bits,
            gray: enc.code == model::sar58k24::OutputCode::Gray,
            gap_bits,
            answer_tag: enc.answer_tag,
        };
        Ok(SarMonitor {
            base,
            watch: Watch::new(limits),
            line: Line::new(),
            decoder: Decoder::new(options),
            cut_after_ps: ((fb + gap_bits + 1.0) * bit_ps).ceil() as u64,
            char_ps: ((fb + 0.5) * bit_ps).ceil() as u64,
            last_fall: None,
            wire: true,
            de: false,
            uncut_answer: false,
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
        let host = HostPins {
            rx,
            tx,
            de,
            trigger: pins.0 & 8 != 0,
            clr: pins.0 & 16 != 0,
        };
        for b in self.watch.sample(self.base.exact_ps(), host) {
            self.base.breach(&b);
        }
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
