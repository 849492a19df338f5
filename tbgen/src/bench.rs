//! `tbgen bench`: the model's own speed on a scenario, and the VCD writer's.
//!
//! Figures, each the best of several runs (at least [`MIN_RUNS`], and as
//! many more as fit in [`MIN_SECONDS`]) so that a busy moment on a shared
//! machine costs a run, not the figure:
//!
//! | key | what it is |
//! |---|---|
//! | `cycles` | system-clock cycles the scenario runs |
//! | `quiet_share` | share of them fast-forward skips ([`Testbench::quiet_cycles`]) |
//! | `model_stepped_cycles_per_second` | the model stepped every cycle, recording nothing |
//! | `model_cycles_per_second` | the model with fast-forward, recording nothing: what campaigns run |
//! | `vcd_bytes` | size of the scenario's `.vcd` |
//! | `vcd_writer_bytes_per_second` | the VCD writer alone: every cycle's sample, taken from memory, written to a file |
//!
//! Model runs record nothing, so neither the vector nor the VCD writer is
//! in them; the VCD writer's run replays samples recorded beforehand (only
//! the cycles where one changed are kept), so no model is in it.

pub mod capture;

use std::fs::{self, File};
use std::io::BufWriter;
use std::path::Path;
use std::time::Instant;

use model::testbench::Testbench;
use model::trace::Sample;

use crate::scenario::{Scenario, Visitor};
use crate::wave;
use crate::{builtin, Error, Result};

/// Runs per figure at least.
pub const MIN_RUNS: u32 = 3;
/// Seconds per figure at least (more runs while they fit).
pub const MIN_SECONDS: f64 = 0.3;

/// What [`measure`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct Figures {
    /// Scenario name.
    pub scenario: String,
    /// Cycles the scenario runs.
    pub cycles: u64,
    /// Cycles fast-forward skips.
    pub quiet_cycles: u64,
    /// Best time of the model stepped every cycle, s.
    pub stepped_seconds: f64,
    /// Best time of the model with fast-forward, s.
    pub model_seconds: f64,
    /// Size of the VCD, bytes.
    pub vcd_bytes: u64,
    /// Best time of the VCD writer alone, s.
    pub vcd_seconds: f64,
}

/// The best (shortest) time of `run` over [`MIN_RUNS`] runs or [`MIN_SECONDS`].
fn best_of(mut run: impl FnMut() -> Result<()>) -> Result<f64> {
    let (mut best, mut total, mut runs) = (f64::INFINITY, 0.0, 0);
    while runs < MIN_RUNS || total < MIN_SECONDS {
        let t0 = Instant::now();
        run()?;
        let t = t0.elapsed().as_secs_f64();
        best = best.min(t);
        total += t;
        runs += 1;
    }
    Ok(best)
}

/// Measures `scenario`; the VCD is written into (and removed from) `scratch`.
pub fn measure(scenario: &Scenario, scratch: &Path) -> Result<Figures> {
    scenario.setup.accept(Measure { scenario, scratch })
}

struct Measure<'a> {
    scenario: &'a Scenario,
    scratch: &'a Path,
}

impl Visitor for Measure<'_> {
    type Output = Result<Figures>;
    fn visit<S: model::Setup>(self, cfg: &S) -> Result<Figures> {
        let value_error = |e| self.scenario.value_error(e);
        let bench = || cfg.bench().map_err(value_error);

        // One untimed pass: the quiet share, and every change of the sample.
        let mut b = bench()?;
        let layout = b.layout().clone();
        let mut sample = Sample::for_layout(&layout);
        let mut changes: Vec<(u64, Sample)> = Vec::new();
        while !b.finished() {
            b.step(Some(&mut sample));
            if changes.last().is_none_or(|(_, last)| *last != sample) {
                changes.push((b.cycle() - 1, sample.clone()));
            }
        }
        let cycles = b.cycle();
        let mut b = bench()?;
        let mut quiet_cycles = 0;
        while !b.finished() {
            match b.quiet_cycles() {
                0 => b.step(None),
                n => {
                    b.skip(n);
                    quiet_cycles += n;
                }
            }
        }

        let stepped_seconds = best_of(|| {
            let b = bench()?;
            std::hint::black_box(b.run_every_cycle_compiled());
            Ok(())
        })?;
        let model_seconds = best_of(|| {
            let b = bench()?;
            std::hint::black_box(b.run_to_end_compiled());
            Ok(())
        })?;

        fs::create_dir_all(self.scratch).map_err(|e| Error::io(self.scratch, e))?;
        let path = self
            .scratch
            .join(format!("{}.bench.vcd", self.scenario.name));
        let tb = cfg.timebase().map_err(value_error)?;
        // `gen`'s comment, so that the file is `gen`'s to the byte.
        let comment =
            crate::generate::waveform_comment(&self.scenario.name, S::CORE, tb.f_sys_hz());
        let vcd_seconds = best_of(|| {
            let file = File::create(&path).map_err(|e| Error::io(&path, e))?;
            wave::write_changes(
                BufWriter::with_capacity(1 << 20, file),
                S::CORE,
                &layout,
                tb,
                &comment,
                &changes,
                cycles,
            )
            .map_err(|e| Error::io(&path, e))
        })?;
        let vcd_bytes = fs::metadata(&path)
            .map(|m| m.len())
            .map_err(|e| Error::io(&path, e))?;
        let _ = fs::remove_file(&path);
        Ok(Figures {
            scenario: self.scenario.name.clone(),
            cycles,
            quiet_cycles,
            stepped_seconds,
            model_seconds,
            vcd_bytes,
            vcd_seconds,
        })
    }
}

/// `tbgen bench <scenario>`: [`measure`] as `key: value` lines (the keys
/// of the module docs), for `scripts/bench.sh`.
pub fn report(scenario_arg: &str) -> Result<String> {
    let s = builtin::resolve(scenario_arg)?;
    let scratch = std::env::temp_dir().join(format!("tbgen-bench-{}", std::process::id()));
    let f = measure(&s, &scratch);
    let _ = fs::remove_dir_all(&scratch);
    let f = f?;
    let rate = |n: u64, s: f64| n as f64 / s;
    Ok(format!(
        "scenario: {}\ncycles: {}\nquiet_share: {:.4}\nmodel_stepped_seconds: {:.6}\nmodel_stepped_cycles_per_second: {:.0}\n\
         model_seconds: {:.6}\nmodel_cycles_per_second: {:.0}\nvcd_bytes: {}\nvcd_writer_seconds: {:.6}\nvcd_writer_bytes_per_second: {:.0}\n",
        f.scenario,
        f.cycles,
        f.quiet_cycles as f64 / f.cycles.max(1) as f64,
        f.stepped_seconds,
        rate(f.cycles, f.stepped_seconds),
        f.model_seconds,
        rate(f.cycles, f.model_seconds),
        f.vcd_bytes,
        f.vcd_seconds,
        rate(f.vcd_bytes, f.vcd_seconds),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bench_of_a_small_scenario_counts_its_cycles_and_writes_its_vcd() {
        let s = builtin::find("ssi_seed_12bit").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let f = measure(&s, dir.path()).unwrap();
        let summary = crate::generate::generate(&s, dir.path()).unwrap();
        assert_eq!(f.cycles, summary.cycles);
        // The writer alone writes the VCD `gen` writes.
        assert_eq!(f.vcd_bytes, fs::metadata(&summary.files[1]).unwrap().len());
        assert!(
            f.quiet_cycles > f.cycles / 2,
            "the SSI seed scenario is mostly monoflop pause: {} of {}",
            f.quiet_cycles,
            f.cycles
        );
        assert!(f.model_seconds > 0.0 && f.stepped_seconds > 0.0 && f.vcd_seconds > 0.0);
    }
}
