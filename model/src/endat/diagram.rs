//! ASCII timing diagrams rendered from a bench run: the model draws its own
//! waveforms for `docs/timing/endat.md`, one character per half clock period.

use super::{Bench, BenchConfig};
use crate::testbench::{self, Testbench};
use crate::trace::{Sample, Sink};
use crate::{Result, Setup};

struct Collect {
    rows: Vec<(bool, bool, bool, bool, bool, u64)>,
    from: u64,
    to: u64,
}

impl Sink for Collect {
    type Error = std::convert::Infallible;
    fn sample(&mut self, cycle: u64, s: &Sample) -> std::result::Result<(), Self::Error> {
        if cycle >= self.from && cycle < self.to {
            // clk, master oe, master out, data at master pin, encoder oe, rx phase
            self.rows.push((
                s.line[0] == 1,
                s.line[4] == 1,
                s.outputs[1] == 1,
                s.line[2] == 1,
                s.line[5] == 1,
                s.decoded[1],
            ));
        }
        Ok(())
    }
}

/// Renders the first transaction after the power-on measurement of `cfg`,
/// one character per `step` system clocks, from `from_cycle` for `width` characters.
pub fn render(cfg: &BenchConfig, step: u64, from_cycle: u64, width: usize) -> Result<String> {
    let bench = Bench::new(cfg)?;
    let _ = cfg.timebase()?;
    let to = from_cycle + step * width as u64;
    let mut sink = Collect {
        rows: Vec::new(),
        from: from_cycle,
        to,
    };
    let run = testbench::run(bench, &mut sink).unwrap_or_else(|e| match e {});
    let _ = run;
    let mut lines = [
        String::new(),
        String::new(),
        String::new(),
        String::new(),
        String::new(),
    ];
    let names = [
        "clk      ",
        "master oe",
        "data pin ",
        "enc oe   ",
        "rx phase ",
    ];
    for chunk in sink.rows.chunks(step as usize) {
        let r = chunk[0];
        lines[0].push(if r.0 { '‾' } else { '_' });
        lines[1].push(if r.1 { '#' } else { '.' });
        lines[2].push(if r.3 { '1' } else { '0' });
        lines[3].push(if r.4 { '#' } else { '.' });
        lines[4].push(char::from_digit(r.5 as u32, 16).unwrap_or('?'));
    }
    Ok(names
        .iter()
        .zip(lines.iter())
        .map(|(n, l)| format!("{n} {l}\n"))
        .collect())
}

/// The cycle of the first host start of a run (after the power-on measurement).
pub fn first_start(cfg: &BenchConfig) -> Result<u64> {
    let run = Bench::new(cfg)?.run_to_end();
    Ok(run
        .transactions
        .iter()
        .find(|t| t.request.is_some())
        .map(|t| t.start_cycle)
        .unwrap_or(0))
}

#[allow(dead_code)]
fn unused(b: &Bench) -> u64 {
    b.cycle()
}
