//! VCD waveforms through a thin typed wrapper over the `vcd` crate.
//!
//! The wrapper knows every signal's width, writes a value only when it
//! changes, refuses to write time backwards, and always declares vectors with
//! their range (`o_position [11:0]`) so that every viewer shows the same name.
//! Scopes: `top.line` holds the line-level scalars (clock, data, driver
//! enables) so that scalar-only readers such as sigrok can decode them;
//! `top.<core>` holds the core's ports; `top.decoded` holds the model's view.
//! The timescale is 1 ps: a whole-picosecond period is exact, any other `f_sys` has each cycle at its exact time rounded to the picosecond (`model::time`).

use std::fs::File;
use std::io::{self, BufWriter};

use model::trace::{Layout, Sample, Sink};
use model::Port;
use vcd::{IdCode, ReferenceIndex, SimulationCommand, TimescaleUnit, Value, VarType};

/// One declared signal.
#[derive(Debug, Clone, Copy)]
struct Signal {
    id: IdCode,
    width: u32,
}

/// A VCD writer for one bench layout, into a buffered file. Not generic over
/// the writer, so that this crate (compiled optimised) holds its code rather
/// than the crate that uses it (see the crate's Cargo.toml).
pub struct Waves {
    vcd: vcd::Writer<BufWriter<File>>,
    signals: Vec<Signal>,
    /// The values last written, in declaration order (line, ports, decoded).
    last: Vec<u64>,
    last_time: Option<u64>,
    timebase: model::time::Timebase,
}

/// The full hierarchical names of a layout's signals as `Waves` declares
/// them, by scope, for the `.gtkw` writer: `(scope, [name])`, in display order.
pub fn signal_names(core: &str, layout: &Layout) -> Vec<(String, Vec<String>)> {
    let name = |scope: &str, p: &Port| {
        if p.width == 1 {
            format!("top.{scope}.{}", p.name)
        } else {
            format!("top.{scope}.{}[{}:0]", p.name, p.width - 1)
        }
    };
    let mut ports: Vec<String> = layout.inputs.iter().map(|p| name(core, p)).collect();
    ports.extend(layout.outputs.iter().map(|p| name(core, p)));
    // The decoded group before the many core ports, so that it shows in an
    // 800-pixel-high window.
    vec![
        (
            "line".to_string(),
            layout.line.iter().map(|p| name("line", p)).collect(),
        ),
        (
            "decoded".to_string(),
            layout.decoded.iter().map(|p| name("decoded", p)).collect(),
        ),
        (core.to_string(), ports),
    ]
}

impl Waves {
    /// Writes the header for `layout` of `core` on the system clock `timebase`
    /// (each cycle at its exact time rounded to the picosecond, [`model::time::Timebase::ps_at`]).
    pub fn new(
        out: BufWriter<File>,
        core: &str,
        layout: &Layout,
        timebase: model::time::Timebase,
        comment: &str,
    ) -> io::Result<Self> {
        let mut vcd = vcd::Writer::new(out);
        vcd.comment(comment)?;
        vcd.timescale(1, TimescaleUnit::PS)?;
        vcd.add_module("top")?;
        let mut signals = Vec::new();
        let groups: [(&str, Vec<Port>); 3] = [
            ("line", layout.line.clone()),
            (
                core,
                layout
                    .inputs
                    .iter()
                    .chain(&layout.outputs)
                    .copied()
                    .collect(),
            ),
            ("decoded", layout.decoded.clone()),
        ];
        for (scope, ports) in groups.iter() {
            vcd.add_module(scope)?;
            for p in ports {
                if *scope == "line" && p.width != 1 {
                    return Err(io::Error::new(
                        io::ErrorKind::InvalidInput,
                        format!("line signal {} must be a scalar", p.name),
                    ));
                }
                let index = (p.width > 1).then(|| ReferenceIndex::Range(p.width as i32 - 1, 0));
                let id = vcd.add_var(VarType::Wire, p.width, p.name, index)?;
                signals.push(Signal { id, width: p.width });
            }
            vcd.upscope()?;
        }
        vcd.upscope()?;
        vcd.enddefinitions()?;
        let n = signals.len();
        Ok(Waves {
            vcd,
            signals,
            last: vec![0; n],
            last_time: None,
            timebase,
        })
    }

    fn write_value(&mut self, index: usize, value: u64) -> io::Result<()> {
        let s = self.signals[index];
        if s.width == 1 {
            self.vcd.change_scalar(s.id, value & 1 == 1)
        } else {
            let bits = (0..s.width).rev().map(|b| {
                if (value >> b) & 1 == 1 {
                    Value::V1
                } else {
                    Value::V0
                }
            });
            self.vcd.change_vector(s.id, bits)
        }
    }

    /// Records the values of cycle `cycle`; writes only the signals that changed.
    pub fn at_cycle(&mut self, cycle: u64, s: &Sample) -> io::Result<()> {
        let time = self.timebase.ps_at(cycle);
        if let Some(last) = self.last_time {
            if time <= last {
                return Err(io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!("time {time} ps is not after {last} ps: waveforms never go backwards"),
                ));
            }
        }
        let first = self.last_time.is_none();
        // Fast path: most cycles change nothing; compare whole groups first.
        let groups: [&[u64]; 4] = [&s.line, &s.inputs, &s.outputs, &s.decoded];
        if !first {
            let mut at = 0;
            let mut same = true;
            for g in groups {
                same &= self.last[at..at + g.len()] == *g;
                at += g.len();
            }
            if same {
                return Ok(());
            }
        }
        self.vcd.timestamp(time)?;
        self.last_time = Some(time);
        if first {
            self.vcd.begin(SimulationCommand::Dumpvars)?;
        }
        let mut i = 0;
        for g in groups {
            for &value in g {
                if first || self.last[i] != value {
                    self.write_value(i, value)?;
                    self.last[i] = value;
                }
                i += 1;
            }
        }
        if first {
            self.vcd.end()?;
        }
        Ok(())
    }

    /// Writes a closing timestamp at the end of cycle `cycles - 1` so viewers
    /// show the whole run, and flushes.
    pub fn finish(mut self, cycles: u64) -> io::Result<()> {
        let end = self.timebase.ps_at(cycles);
        if self.last_time.is_none_or(|t| end > t) {
            self.vcd.timestamp(end)?;
        }
        self.vcd.flush()
    }
}

/// Writes a run's VCD from its samples held in memory: `changes` holds the
/// first cycle's sample and each cycle whose sample differs from the cycle
/// before, in cycle order; every cycle of `0..cycles` is handed to
/// [`Waves::at_cycle`] as stepping would, then [`Waves::finish`]. The file is
/// `tbgen gen`'s byte for byte; `tbgen bench` times this as the VCD writer
/// alone.
pub fn write_changes(
    out: BufWriter<File>,
    core: &str,
    layout: &Layout,
    timebase: model::time::Timebase,
    comment: &str,
    changes: &[(u64, Sample)],
    cycles: u64,
) -> io::Result<()> {
    let mut waves = Waves::new(out, core, layout, timebase, comment)?;
    let mut next = 0;
    for cycle in 0..cycles {
        while next + 1 < changes.len() && changes[next + 1].0 <= cycle {
            next += 1;
        }
        waves.at_cycle(cycle, &changes[next].1)?;
    }
    waves.finish(cycles)
}

impl Sink for Waves {
    type Error = io::Error;
    fn sample(&mut self, cycle: u64, sample: &Sample) -> io::Result<()> {
        self.at_cycle(cycle, sample)
    }
}

/// The scalar signals of a VCD only: vector declarations and vector value
/// changes removed. sigrok-cli 0.5 (libsigrok's VCD input) stops reading at
/// the first vector value without a word, so this is the file to give it (or
/// PulseView); the line-level signals are all scalars and all kept.
pub fn scalars_only(vcd_text: &str) -> String {
    let mut out = String::with_capacity(vcd_text.len());
    for line in vcd_text.lines() {
        let t = line.trim_start();
        let is_vector_var =
            t.starts_with("$var") && t.split_whitespace().nth(2).is_some_and(|w| w != "1");
        if is_vector_var || t.starts_with('b') || t.starts_with('B') {
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}
