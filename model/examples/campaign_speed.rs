//! Frames per second of each corruption campaign (fast-forward
//! against stepping), as `make bench` prints them.
//! Each campaign runs with its test's seed and arguments; each figure is the
//! best of three runs of `trials` frames.
//!
//! ```text
//! cargo run --release -p model --example campaign_speed [trials]
//! ```
//!
//! One line per campaign, `campaign NAME KIND TRIALS STEPPED FAST` (frames
//! per second; `-` where there is no such run):
//! - BiSS-C, T-format, SAR58K24 and Modbus run cycle models (the master's,
//!   the host's) that fast-forward: STEPPED steps every cycle, FAST skips
//!   quiet cycles (the campaigns' default);
//! - ESL and CAN are bit-level (no cycle model in the loop): FAST only.

use std::time::Instant;

fn best_of_three(f: &dyn Fn()) -> f64 {
    (0..3)
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

type Run = Box<dyn Fn()>;

fn main() {
    let trials: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(20_000);
    let t = trials;
    let runs: Vec<(&str, &str, Option<Run>, Option<Run>)> = vec![
        (
            "biss",
            "cycle-model",
            Some(Box::new(move || {
                drop(model::biss::campaign::run_with(t, 16, 6, 2024, false))
            })),
            Some(Box::new(move || {
                drop(model::biss::campaign::run_with(t, 16, 6, 2024, true))
            })),
        ),
        (
            "tformat",
            "cycle-model",
            Some(Box::new(move || {
                drop(model::tformat::campaign::run_with(t, 8, 2024, false))
            })),
            Some(Box::new(move || {
                drop(model::tformat::campaign::run_with(t, 8, 2024, true))
            })),
        ),
        (
            "sar58k24",
            "cycle-model",
            Some(Box::new(move || {
                drop(model::sar58k24::campaign::run_with(t, 8, 2026, false))
            })),
            Some(Box::new(move || {
                drop(model::sar58k24::campaign::run_with(t, 8, 2026, true))
            })),
        ),
        (
            "modbus",
            "cycle-model",
            Some(Box::new(move || {
                drop(model::modbus::campaign::run_with(t, 8, 2026, false))
            })),
            Some(Box::new(move || {
                drop(model::modbus::campaign::run_with(t, 8, 2026, true))
            })),
        ),
        (
            "esl",
            "bit-level",
            None,
            Some(Box::new(move || {
                drop(model::esl::campaign::run(t, 6, 2026))
            })),
        ),
        (
            "can",
            "bit-level",
            None,
            Some(Box::new(move || drop(model::can::campaign::run(t, 1)))),
        ),
    ];
    let rate = |r: &Option<Run>| {
        r.as_ref().map_or("-".to_string(), |f| {
            format!("{:.0}", trials as f64 / best_of_three(f.as_ref()))
        })
    };
    for (name, kind, stepped, fast) in &runs {
        println!(
            "campaign {name} {kind} {trials} {} {}",
            rate(stepped),
            rate(fast)
        );
    }
}
