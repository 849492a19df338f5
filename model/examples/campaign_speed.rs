//! Frames per second of each corruption campaign (issue 15: campaign
//! throughput before and after fast-forward). Each campaign runs with its
//! test's seed; the figure is the best of three runs.
//!
//! ```text
//! cargo run --release -p model --example campaign_speed [trials]
//! ```

use std::time::Instant;

fn best_of_three(f: impl Fn()) -> f64 {
    (0..3)
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let trials: u64 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(20_000);
    let runs: [(&str, Box<dyn Fn()>); 3] = [
        ("biss (master + slave cycle model)", Box::new(move || drop(model::biss::campaign::run(trials, 16, 6, 2024)))),
        ("tformat (host cycle model)", Box::new(move || drop(model::tformat::campaign::run(trials, 8, 2024)))),
        ("esl (bit-level receiver)", Box::new(move || drop(model::esl::campaign::run(trials, 6, 2026)))),
    ];
    for (name, run) in runs {
        let s = best_of_three(run);
        println!("{name:<36} {trials} frames in {s:.3} s: {:.0} frames/s", trials as f64 / s);
    }
}
