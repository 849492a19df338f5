//! The lines of a sampled capture (a logic analyser's: `.sr`, CSV) as the
//! decoders take them: each chosen channel's value changes in picoseconds,
//! and a refusal when the capture was sampled too slowly to decode.
//!
//! The samples themselves stream through [`Edges::push`]; only the changes
//! are kept, as they are for a VCD.

use model::wire::Signal;

use crate::{Error, Result};

/// Samples a line's typical pulse must span for the decoders to read it: an
/// edge is seen up to one sample late, so at four samples a pulse a bit is
/// still sampled in its middle half (a UART's mid-bit sample, a clocked
/// line's data held around its sampling edge); at two it may be read at the
/// edge itself.
pub const SAMPLES_PER_PULSE: u64 = 4;

/// The chosen channels of a sampled capture, being read.
pub(crate) struct Edges {
    signals: Vec<Signal>,
}

impl Edges {
    /// No changes yet, one line per name.
    pub(crate) fn new(names: &[String]) -> Edges {
        Edges {
            signals: names.iter().map(|n| Signal::named(n)).collect(),
        }
    }

    /// The level of line `i` at `t_ps` (times never go back).
    pub(crate) fn push(&mut self, i: usize, t_ps: u64, level: bool) {
        self.signals[i].push(t_ps, level);
    }

    /// The lines read, once every line has been checked against the capture's
    /// sample period: a line whose median pulse spans fewer than
    /// [`SAMPLES_PER_PULSE`] samples is refused with the rate it needs.
    pub(crate) fn finish(self, file: &str, period_ps: f64) -> Result<Vec<Signal>> {
        for s in &self.signals {
            // The first change is the level the capture opened with, not an edge.
            let mut widths: Vec<u64> = s
                .changes
                .windows(2)
                .skip(1)
                .map(|w| w[1].0 - w[0].0)
                .collect();
            if widths.is_empty() {
                continue;
            }
            let mid = (widths.len() - 1) / 2;
            let median = *widths.select_nth_unstable(mid).1 as f64;
            // A pulse is a whole number of samples (an export may print its
            // times rounded: 12.5 ns samples in whole nanoseconds).
            let samples = (median / period_ps).round() as u64;
            if samples < SAMPLES_PER_PULSE {
                let rate = 1e12 / period_ps;
                let needed = SAMPLES_PER_PULSE as f64 * 1e12 / median;
                return Err(Error::Decode(format!(
                    "{file}: sampled at {}, too slowly for line `{}`: it changes every {} (its median pulse, {samples} samples), and decoding needs {SAMPLES_PER_PULSE} samples a pulse: capture at {} or faster",
                    hz(rate),
                    s.name,
                    ns(median),
                    hz(needed)
                )));
            }
        }
        Ok(self.signals)
    }
}

/// A rate as a user sets it on the analyser (`2.5 MHz`).
pub(crate) fn hz(f: f64) -> String {
    let (v, unit) = match f {
        f if f >= 1e9 => (f / 1e9, "GHz"),
        f if f >= 1e6 => (f / 1e6, "MHz"),
        f if f >= 1e3 => (f / 1e3, "kHz"),
        f => (f, "Hz"),
    };
    format!("{} {unit}", trim(v))
}

/// A time in nanoseconds (`500 ns`).
fn ns(ps: f64) -> String {
    format!("{} ns", trim(ps / 1e3))
}

/// At most three decimals, no trailing zeros.
fn trim(v: f64) -> String {
    let s = format!("{v:.3}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn clock(half_ps: u64, period_ps: u64, n: u64) -> Edges {
        let mut e = Edges::new(&["clk".to_string()]);
        for k in 0..n {
            let t = k * period_ps;
            e.push(0, t, (t / half_ps) % 2 == 0);
        }
        e
    }

    #[test]
    fn four_samples_a_pulse_is_enough_and_fewer_is_refused_with_the_rate_needed() {
        // A 1 MHz clock: 500 ns pulses.
        assert!(clock(500_000, 125_000, 400)
            .finish("c.csv", 125_000.0)
            .is_ok());
        let e = clock(500_000, 250_000, 200)
            .finish("c.csv", 250_000.0)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "c.csv: sampled at 4 MHz, too slowly for line `clk`: it changes every 500 ns (its median pulse, 2 samples), and decoding needs 4 samples a pulse: capture at 8 MHz or faster");
    }

    #[test]
    fn a_few_one_sample_glitches_do_not_make_a_capture_too_slow() {
        let mut e = clock(500_000, 125_000, 400);
        e.signals[0]
            .changes
            .extend([(60_000_000, true), (60_125_000, false), (60_250_000, true)]);
        assert!(e.finish("c.csv", 125_000.0).is_ok());
    }
}
