//! The cycle-time budget of a configuration, phase by phase, computed from
//! the same schedule the master runs (module docs of [`crate::endat`]); a
//! test holds it equal to the model's and the RTL's cycle.

use serde::Serialize;

use super::{BenchConfig, Command};
use crate::{Result, Setup};

/// One phase of a transaction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Phase {
    /// What happens.
    pub name: String,
    /// System clocks.
    pub cycles: u64,
    /// Nanoseconds.
    pub ns: f64,
}

/// The budget of one command under a configuration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Budget {
    /// The command.
    pub command: String,
    /// System clock in Hz.
    pub f_sys_hz: u64,
    /// The phases, in order; their sum is `cycle_clocks`.
    pub phases: Vec<Phase>,
    /// From the start pulse to the first cycle a new start is accepted.
    pub cycle_clocks: u64,
    /// From the start pulse to `o_done` (results valid).
    pub latency_clocks: u64,
    /// Reads per second with back-to-back starts.
    pub reads_per_second: f64,
    /// The sample delay `D` the measurement is expected to find (or the fixed one).
    pub sample_delay_clocks: u64,
}

/// The budget of `command` (a position command: `pos21`, `pos22`, or any other) under `cfg`.
pub fn budget(cfg: &BenchConfig, command: Command) -> Result<Budget> {
    cfg.validate()?;
    let m = cfg.master_config()?;
    let e = cfg.encoder_config()?;
    let tb = cfg.timebase()?;
    let cpb = m.clocks_per_bit;
    let half = m.high_clocks; // the first high phase (the longer one of an odd period)
    let kind = super::frame_kind(command.code());
    use super::FrameKind as K;
    let k_off = if kind == K::Param21 {
        8 + super::BLOCK_BITS
    } else {
        8
    };
    let t_ready = if command == Command::Reset21 {
        e.reset_clocks
    } else {
        e.t_cal_clocks
    };
    // R_j - F1 = t_ST + (j - 1) * CPB; the start bit goes out at the first R_j, j >= k_off + 3, at least t_ready
    // after F1, or, for the type 2.1 parameter commands, after R36, where the encoder has taken the block's last bit.
    let ready_from = if kind == K::Param21 {
        m.t_st_clocks + (k_off - 2) * cpb
    } else {
        0
    };
    let mut j = k_off + 3;
    while m.t_st_clocks + (j - 1) * cpb < ready_from + t_ready {
        j += 1;
    }
    let (nf, len) = match kind {
        K::Pos21 => (1, m.pos_bits as u64),
        K::Pos22 | K::Block22 => (2, m.pos_bits as u64),
        K::Param21 => (0, 24),
        K::Test21 => (1, super::TEST_VALUE_BITS as u64),
    };
    let ads = if matches!(kind, K::Pos22 | K::Block22) {
        cfg.master.ad_count_hint()
    } else {
        0
    };
    let frame = nf + len + 5 + super::AD_WIRE_BITS * ads;
    let s = j + 1;
    let mut stop = s + frame;
    if kind == K::Block22 {
        stop += m.block_gap + super::BLOCK_BITS - 1;
    }
    let pause = if matches!(kind, K::Pos21 | K::Param21 | K::Test21) {
        m.t_b_clocks
    } else {
        m.t_m_clocks
    };
    let delay = if m.delay_comp {
        cfg.expected_delay()?
    } else {
        m.fixed_delay()
    };
    let ns = |c: u64| c as f64 * tb.period_ps() as f64 / 1e3;
    let mut phases = Vec::new();
    let mut push = |name: &str, cycles: u64| {
        phases.push(Phase {
            name: name.into(),
            cycles,
            ns: ns(cycles),
        })
    };
    push(
        "t_ST: first low phase after the first falling clock edge (it latches the position)",
        m.t_st_clocks,
    );
    push("first high phase", half);
    push(
        "mode bits M2..(M0), falling clock edges 2 to 8 (6 clocks)",
        6 * cpb,
    );
    if kind == K::Param21 {
        push(
            "parameter block: MRS/address, parameter, CRC (29 clocks)",
            29 * cpb,
        );
    }
    push(
        &format!(
            "turnaround and start-bit polling, t_cal ({} clocks)",
            s - k_off
        ),
        (s - k_off) * cpb,
    );
    push(&format!("frame after the start bit: {nf} error bits, {len} data bits, CRC, {ads} additional data ({frame} clocks)"), frame * cpb);
    if kind == K::Block22 {
        push(
            "gap and the master's parameter block",
            (m.block_gap + super::BLOCK_BITS - 1) * cpb,
        );
    }
    push(
        "last rising edge, clock high until the driver is released",
        cpb,
    );
    push(
        if pause == m.t_b_clocks {
            "t_b: time between type 2.1 cycles"
        } else {
            "t_m + t_R: recovery times I and II"
        },
        pause,
    );
    push("return to idle", 1);
    let cycle = m.t_st_clocks + half + (stop - 2) * cpb + cpb + pause + 1;
    let sum: u64 = phases.iter().map(|p| p.cycles).sum();
    debug_assert_eq!(sum, cycle, "phases must add up");
    let latency = m.t_st_clocks + half + (s + frame - 2) * cpb + delay;
    Ok(Budget {
        command: command.name().into(),
        f_sys_hz: tb.f_sys_hz(),
        phases,
        cycle_clocks: cycle,
        latency_clocks: latency,
        reads_per_second: tb.f_sys_hz() as f64 / cycle as f64,
        sample_delay_clocks: delay,
    })
}

impl super::MasterSettings {
    /// Additional data the budget assumes are selected (`ad_count` in the scenario's master table is not a master
    /// setting; the budget reads the requests instead, see [`budget_for`]).
    fn ad_count_hint(&self) -> u64 {
        AD_HINT.with(|h| *h.borrow())
    }
}

thread_local! {
    static AD_HINT: std::cell::RefCell<u64> = const { std::cell::RefCell::new(0) };
}

/// The budget of `command` with `ads` additional data selected (0, 1 or 2).
pub fn budget_for(cfg: &BenchConfig, command: Command, ads: u64) -> Result<Budget> {
    AD_HINT.with(|h| *h.borrow_mut() = ads.min(2));
    let b = budget(cfg, command);
    AD_HINT.with(|h| *h.borrow_mut() = 0);
    b
}

impl Budget {
    /// A human-readable table.
    pub fn render(&self) -> String {
        let mut s = format!(
            "EnDat cycle-time budget: {} at f_sys = {} Hz\n",
            self.command, self.f_sys_hz
        );
        for p in &self.phases {
            s += &format!("  {:>9} cycles {:>11.1} ns  {}\n", p.cycles, p.ns, p.name);
        }
        let ns = |c: u64| c as f64 * 1e9 / self.f_sys_hz as f64;
        s += &format!(
            "  {:>9} cycles {:>11.1} ns  cycle (start to next possible start)\n",
            self.cycle_clocks,
            ns(self.cycle_clocks)
        );
        s += &format!(
            "  {:>9} cycles {:>11.1} ns  latency (start to o_done), sample delay D = {} cycles\n",
            self.latency_clocks,
            ns(self.latency_clocks),
            self.sample_delay_clocks
        );
        s += &format!(
            "  position-read rate: {:.0} reads/s\n",
            self.reads_per_second
        );
        s
    }
}
