//! Fault campaign: random corruptions of the wire bits of single-cycle data
//! (data, nE, nW, CRC), run through the cycle model of the master and the
//! slave, counted by the number of flipped bits.

use std::collections::BTreeMap;

use rand::seq::index::sample;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use super::master::{In, Master, MasterConfig};
use super::slave::{Chain, Slave, SlaveConfig};

/// Detected and undetected corruptions for one number of flipped bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counts {
    /// The master flagged a CRC error.
    pub detected: u64,
    /// The master accepted the corrupted frame.
    pub undetected: u64,
}

/// The campaign's result: counts by number of flipped bits.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Report {
    /// `flipped bits -> counts`.
    pub by_flips: BTreeMap<u32, Counts>,
}

impl Report {
    /// All corruptions run.
    pub fn total(&self) -> u64 {
        self.by_flips
            .values()
            .map(|c| c.detected + c.undetected)
            .sum()
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "flipped_bits  detected  undetected")?;
        for (k, c) in &self.by_flips {
            writeln!(f, "{k:>12}  {:>8}  {:>10}", c.detected, c.undetected)?;
        }
        write!(f, "total {}", self.total())
    }
}

/// Runs `trials` frames of a `bits`-bit slave with BiSS-C CRC-6, each with
/// 1 to `max_flips` distinct bits of its data/nE/nW/CRC field flipped on the
/// wire, and counts what the master's CRC check caught. MA at f_sys / 8, no
/// cable, 1 µs slave timeout at 80 MHz: about 300 cycles per frame.
pub fn run(trials: u64, bits: u32, max_flips: u32, seed: u64) -> Report {
    run_with(trials, bits, max_flips, seed, true)
}

/// [`run`], with fast-forward through quiet cycles or stepping every cycle.
pub fn run_with(trials: u64, bits: u32, max_flips: u32, seed: u64, fast_forward: bool) -> Report {
    let (mut master, mut chain) = pair(bits);
    let mut rng = Pcg64Mcg::seed_from_u64(seed);
    let field = bits + 2 + 6;
    let mut report = Report::default();
    for _ in 0..trials {
        let k = rng.random_range(1..=max_flips.min(field));
        let flips: Vec<u32> = sample(&mut rng, field as usize, k as usize)
            .into_iter()
            .map(|i| i as u32)
            .collect();
        let position = rng.random::<u64>();
        let (error, warning) = (rng.random_bool(0.1), rng.random_bool(0.1));
        let entry = report.by_flips.entry(k).or_default();
        if frame_detected(
            &mut master,
            &mut chain,
            position,
            error,
            warning,
            flips,
            fast_forward,
        ) {
            entry.detected += 1;
        } else {
            entry.undetected += 1;
        }
    }
    report
}

/// Whether the master flags one frame of a `bits`-bit slave holding
/// `position` (nE = nW = 1) whose section bits `flips` are corrupted.
pub fn detected(bits: u32, position: u64, flips: &[u32]) -> bool {
    let (mut master, mut chain) = pair(bits);
    frame_detected(
        &mut master,
        &mut chain,
        position,
        false,
        false,
        flips.to_vec(),
        true,
    )
}

fn pair(bits: u32) -> (Master, Chain) {
    let mcfg = MasterConfig {
        slaves: 1,
        slave_bits: vec![bits],
        slave_crc_width: vec![6],
        slave_crc_poly: vec![0x03],
        clocks_per_bit: 8,
        high_clocks: 4,
        low_clocks: 4,
        max_delay: 64,
        timeout_clocks: 400,
        cal_frames: 1,
        delay_tol: 1,
    };
    let scfg = SlaveConfig {
        bits,
        crc_width: 6,
        crc_poly: 0x03,
        busy_clocks: 16,
        timeout_clocks: 80,
        id: 0,
        registers: vec![],
    };
    let master = Master::new(mcfg).expect("campaign master configuration is valid");
    let chain = Chain::new(
        vec![Slave::new(scfg).expect("campaign slave configuration is valid")],
        1,
    );
    (master, chain)
}

/// Runs one frame; the master is idle with SLO high before and after it.
fn frame_detected(
    master: &mut Master,
    chain: &mut Chain,
    position: u64,
    error: bool,
    warning: bool,
    flips: Vec<u32>,
    fast_forward: bool,
) -> bool {
    {
        let s = &mut chain.slaves_mut()[0];
        s.set_position(position);
        s.set_flags(error, warning);
        s.set_flips(flips);
    }
    let mut start = true;
    let mut slo = true;
    let mut ma = true;
    let mut crc_err = None;
    loop {
        let input = In {
            i_start: start,
            i_slo: slo,
            ..In::default()
        };
        // Fast-forward through the slave's busy time and timeout: nothing
        // changes there but counters (tests/fast_forward.rs).
        let quiet = if fast_forward {
            master.quiet(&input).min(chain.quiet(ma))
        } else {
            0
        };
        if quiet > 0 && quiet < u64::MAX {
            master.skip(quiet);
            chain.skip(quiet);
            continue;
        }
        let out = master.step(&input);
        start = false;
        ma = out.o_ma;
        slo = chain.step(out.o_ma);
        if out.o_slave_valid {
            crc_err = Some(out.o_crc_err);
        }
        if out.o_done {
            break;
        }
    }
    crc_err != Some(false)
}
