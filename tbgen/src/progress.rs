//! Progress of a long `tbgen gen` on stderr: cycles done of the run's total,
//! the waveform's size so far and at the end, the time left.
//!
//! Shown when stderr is a terminal (one line rewritten in place, as cargo
//! does) or when asked with `--progress` (one line every few seconds, for a
//! log, every 2 s); never otherwise, so that scripts and tests read clean output.
//!
//! The total comes from a second thread that runs the same set-up without
//! recording, fast-forwarding its quiet stretches (about a tenth of the
//! recorded run's time): until it has counted, the lines say how far the
//! run is and how much it has written; from then on, the share done, the
//! waveform's final size and the time left.

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use model::testbench::Testbench;
use model::trace::{Sample, Sink};
use model::Setup;

/// The cycles of a run, counted on a thread of its own; the count stops
/// when this is dropped (the recorded run ended first).
pub struct Counter {
    /// The run's cycles, 0 until counted.
    total: Arc<AtomicU64>,
    stop: Arc<AtomicBool>,
}

impl Counter {
    /// Starts counting the cycles of `setup`'s run.
    pub fn start<S: Setup + Send + 'static>(setup: &S) -> Counter {
        let (total, stop) = (
            Arc::new(AtomicU64::new(0)),
            Arc::new(AtomicBool::new(false)),
        );
        let (t, s, setup) = (total.clone(), stop.clone(), setup.clone());
        std::thread::spawn(move || {
            // The recorded run reports a bad set-up; the count just ends.
            let Ok(mut bench) = setup.bench() else { return };
            while !bench.finished() {
                if s.load(Ordering::Relaxed) {
                    return;
                }
                match bench.quiet_cycles() {
                    0 => bench.step(None),
                    n => bench.skip(n),
                }
            }
            t.store(bench.cycle().max(1), Ordering::Relaxed);
        });
        Counter { total, stop }
    }

    /// The run's cycles, once counted.
    fn total(&self) -> Option<u64> {
        Some(self.total.load(Ordering::Relaxed)).filter(|&t| t > 0)
    }
}

impl Drop for Counter {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

/// How progress is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Not at all.
    Off,
    /// One line rewritten in place (stderr is a terminal).
    Terminal,
    /// A line every 2 s (asked for, stderr not a terminal).
    Lines,
}

impl Mode {
    /// The mode for a run: a terminal gets the line in place, `asked`
    /// (`--progress`) gets lines anywhere, others nothing.
    pub fn choose(asked: bool) -> Mode {
        match (std::io::stderr().is_terminal(), asked) {
            (true, _) => Mode::Terminal,
            (false, true) => Mode::Lines,
            (false, false) => Mode::Off,
        }
    }

    fn every(self) -> Duration {
        match self {
            Mode::Terminal => Duration::from_millis(250),
            _ => Duration::from_secs(2),
        }
    }
}

/// A sink that passes every sample on and reports now and then.
pub struct Progress<S> {
    inner: S,
    mode: Mode,
    name: String,
    f_sys_hz: u64,
    total: Counter,
    /// The waveform being written, whose size is reported.
    vcd: PathBuf,
    started: Instant,
    last: Instant,
    /// The next cycle at which the clock is read (reading it every cycle
    /// would cost more than the report is worth).
    next_look: u64,
}

/// Cycles between two looks at the clock.
const LOOK_EVERY: u64 = 1 << 14;

impl<S: Sink> Progress<S> {
    /// Reports the run of scenario `name` at `f_sys_hz`, its length counted
    /// by `total`, written to `vcd`.
    pub fn new(
        inner: S,
        mode: Mode,
        name: &str,
        f_sys_hz: u64,
        total: Counter,
        vcd: PathBuf,
    ) -> Self {
        let now = Instant::now();
        Progress {
            inner,
            mode,
            name: name.to_string(),
            f_sys_hz,
            total,
            vcd,
            started: now,
            last: now,
            next_look: LOOK_EVERY,
        }
    }

    fn report(&mut self, cycle: u64) {
        let elapsed = self.started.elapsed().as_secs_f64();
        let bytes = std::fs::metadata(&self.vcd).map(|m| m.len()).unwrap_or(0) as f64;
        let at = simulated(cycle, self.f_sys_hz);
        let line = match self.total.total() {
            Some(total) => {
                let done = (cycle as f64 / total as f64).max(1e-9);
                format!(
                    "tbgen: {}: {:5.1} % ({at} of {} simulated), VCD {} of about {}, {} left",
                    self.name,
                    100.0 * done,
                    simulated(total, self.f_sys_hz),
                    size(bytes),
                    size(bytes / done),
                    duration(elapsed / done - elapsed)
                )
            }
            None => format!(
                "tbgen: {}: {at} simulated, VCD {} so far (counting the run's length)",
                self.name,
                size(bytes)
            ),
        };
        match self.mode {
            Mode::Terminal => eprint!("\r{line}\x1b[K"),
            _ => eprintln!("{line}"),
        }
        let _ = std::io::stderr().flush();
    }

    /// Clears the line in place; the run is over (or failed).
    pub fn finish(self) -> S {
        if self.mode == Mode::Terminal && self.last != self.started {
            eprint!("\r\x1b[K");
        }
        self.inner
    }
}

impl<S: Sink> Sink for Progress<S> {
    type Error = S::Error;
    fn sample(&mut self, cycle: u64, sample: &Sample) -> Result<(), S::Error> {
        if cycle >= self.next_look && self.mode != Mode::Off {
            self.next_look = cycle + LOOK_EVERY;
            if self.last.elapsed() >= self.mode.every() {
                self.last = Instant::now();
                self.report(cycle);
            }
        }
        self.inner.sample(cycle, sample)
    }
}

/// Bytes as a person reads them: `812 kB`, `36.4 MB`, `2.1 GB`.
fn size(bytes: f64) -> String {
    match bytes {
        b if b < 1e6 => format!("{:.0} kB", b / 1e3),
        b if b < 1e9 => format!("{:.1} MB", b / 1e6),
        b => format!("{:.1} GB", b / 1e9),
    }
}

/// Seconds as a person reads them: `42 s`, `3 min 05 s`, `1 h 02 min`.
fn duration(s: f64) -> String {
    let s = s.max(0.0).round() as u64;
    match s {
        s if s < 60 => format!("{s} s"),
        s if s < 3600 => format!("{} min {:02} s", s / 60, s % 60),
        s => format!("{} h {:02} min", s / 3600, s / 60 % 60),
    }
}

/// Simulated time, `cycles` at `f_sys_hz`: `2.26 ms`, `1.00 s`.
pub fn simulated(cycles: u64, f_sys_hz: u64) -> String {
    let s = cycles as f64 / f_sys_hz as f64;
    match s {
        s if s < 1e-3 => format!("{:.2} µs", s * 1e6),
        s if s < 1.0 => format!("{:.2} ms", s * 1e3),
        s => format!("{s:.2} s"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_durations_read_as_a_person_writes_them() {
        assert_eq!(size(36.4e6), "36.4 MB");
        assert_eq!(size(812e3), "812 kB");
        assert_eq!(duration(185.0), "3 min 05 s");
        assert_eq!(duration(3720.0), "1 h 02 min");
        assert_eq!(simulated(112_766, 50_000_000), "2.26 ms");
    }
}
