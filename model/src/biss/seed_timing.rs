//! The seed's BiSS-C line timing checked on a whole run of a scenario (seed
//! 001, SAR58K24 manual, "Synchronous serial", BiSS-C timing table):
//!
//! * `TMASH: High level duration > 25 ns` and `TMASL: Low level duration >
//!   25 ns`: every high and every low phase of MA between two of its edges,
//!   at the master's pin, including the high level between two frames that
//!   the master runs back to back (register access, commands);
//! * `Tbusy: Minimum data output delay 2 TMAS`: at the slave's SLO pin, from
//!   the ack (SLO low after the second rising MA edge of a frame) to the
//!   start bit (SLO high again), at least two MA periods of the master.
//!
//! [`check`] steps a bench cycle by cycle and returns every violation as a
//! sentence naming the cycle, the time, the rule and the seed's limit; the
//! tests run it on every built-in BiSS-C scenario and on register access and
//! commands at every MA rate of a sweep.

use super::bench::{Bench, BenchConfig};
use crate::testbench::Testbench;
use crate::trace::Sample;
use crate::{Result, Setup};

/// The seed's TMASH and TMASL lower limit, exclusive, ns.
pub const TMAS_HL_MIN_NS: f64 = 25.0;
/// The seed's t_busy, in MA periods (TMAS), inclusive.
pub const BUSY_MIN_PERIODS: u64 = 2;

/// Every violation of the seed's MA phase and t_busy limits in a run of `cfg`.
pub fn check(cfg: &BenchConfig) -> Result<Vec<String>> {
    let ns = cfg.timebase()?.period_ps() as f64 / 1000.0;
    let period = cfg.master_config()?.clocks_per_bit;
    let mut bench = Bench::new(cfg)?;
    let mut sample = Sample::for_layout(bench.layout());
    // Per cycle: MA at the master, MA at the slave, SLO at the slave, state after the step.
    let mut rows: Vec<(bool, bool, bool, u64)> = Vec::new();
    while !bench.finished() {
        bench.step(Some(&mut sample));
        rows.push((
            sample.line[0] == 1,
            sample.line[1] == 1,
            sample.line[2] == 1,
            sample.decoded[0],
        ));
    }
    let mut bad = Vec::new();
    let at = |cycle: usize| format!("cycle {cycle} ({:.1} ns)", cycle as f64 * ns);

    // MA phases between two edges at the master's pin.
    let mut last_edge: Option<usize> = None;
    for c in 1..rows.len() {
        if rows[c].0 == rows[c - 1].0 {
            continue;
        }
        if let Some(e) = last_edge {
            let len = (c - e) as f64 * ns;
            if len <= TMAS_HL_MIN_NS {
                let (rule, level) = if rows[e].0 {
                    ("TMASH", "high")
                } else {
                    ("TMASL", "low")
                };
                bad.push(format!(
                    "{}: MA {level} for {len} ns, {} cycles (seed 001, BiSS-C: {rule} > 25 ns)",
                    at(e),
                    c - e
                ));
            }
        }
        last_edge = Some(c);
    }

    // t_busy at the slave: from each frame's start (IDLE to ACK), the second
    // rising MA edge at the slave, the ack after it, the start bit after that.
    let starts: Vec<usize> = (1..rows.len())
        .filter(|&c| rows[c].3 == 1 && rows[c - 1].3 == 0)
        .collect();
    for (i, &s) in starts.iter().enumerate() {
        let end = starts.get(i + 1).copied().unwrap_or(rows.len());
        // An ack is SLO falling after the second rising MA edge at the
        // slave and before the third, SLO having been high since the frame
        // began; otherwise the slave was still in an earlier frame (its line
        // to the master stuck, so the master could not wait for it).
        let mut rises = 0;
        let mut ack: Option<usize> = None;
        for c in s + 1..end {
            if rows[c].1 && !rows[c - 1].1 {
                rises += 1;
            }
            if rises < 2 {
                if !rows[c].2 {
                    break;
                }
                continue;
            }
            if ack.is_none() && rises > 2 {
                break;
            }
            match ack {
                None if !rows[c].2 && rows[c - 1].2 => ack = Some(c),
                Some(a) if rows[c].2 => {
                    let busy = (c - a) as u64;
                    if busy < BUSY_MIN_PERIODS * period {
                        bad.push(format!(
                            "{}: SLO busy for {} ns, {busy} cycles, after the ack, below 2 x TMAS = {} ns (seed 001, BiSS-C: Tbusy 2 TMAS)",
                            at(a),
                            busy as f64 * ns,
                            (BUSY_MIN_PERIODS * period) as f64 * ns
                        ));
                    }
                    break;
                }
                _ => {}
            }
        }
    }
    Ok(bad)
}
