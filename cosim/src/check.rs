//! Protocol checks: the emulator sees the master's line pins every emulator
//! cycle, so it holds the master to the timing limits the seeds state and
//! records each violation with its time and the seed's rule.
//!
//! Limits are named fields of a `[checks]` table (defaults: the seed's
//! numbers), because a master may run outside the seed's encoder on purpose
//! (an SSI reader at 1 MHz) and must say so. A measured time is allowed one
//! emulator cycle of tolerance either way: the master's clock and the
//! emulator's need not be the same.

use serde::Serialize;

/// One broken timing rule.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Violation {
    /// Emulator cycle at which it was seen.
    pub cycle: u64,
    /// The same in nanoseconds from the emulator's start.
    pub time_ns: f64,
    /// The rule, as the seed states it.
    pub rule: &'static str,
    /// What was measured.
    pub detail: String,
}

/// The violations of one emulator, and how many the testbench has been shown.
#[derive(Debug, Clone, Default)]
pub struct Checks {
    /// The emulator clock period in ps, exact to the float (not rounded
    /// to whole picoseconds: 48 MHz is 20 833.33 ps).
    period_ps: f64,
    list: Vec<Violation>,
    shown: usize,
}

impl Checks {
    /// Checks on an emulator clock of `period_ps` (whole picoseconds).
    pub fn new(period_ps: u64) -> Self {
        Checks::with_period(period_ps as f64)
    }

    /// Checks on the emulator clock `tb`, its period exact (any clock the
    /// shared [`model::Timebase`] accepts).
    pub fn for_clock(tb: &model::Timebase) -> Self {
        Checks::with_period(model::time::PS_PER_S as f64 / tb.f_sys_hz() as f64)
    }

    fn with_period(period_ps: f64) -> Self {
        Checks {
            period_ps,
            list: Vec::new(),
            shown: 0,
        }
    }

    /// Records a violation at `cycle`.
    pub fn push(&mut self, cycle: u64, rule: &'static str, detail: String) {
        let time_ns = cycle as f64 * self.period_ps / 1e3;
        self.list.push(Violation {
            cycle,
            time_ns,
            rule,
            detail,
        });
    }

    /// Cycles to microseconds.
    pub fn us(&self, cycles: u64) -> f64 {
        cycles as f64 * self.period_ps / 1e6
    }

    /// A time in ns as emulator cycles (not rounded).
    pub fn cycles_of_ns(&self, ns: f64) -> f64 {
        ns * 1e3 / self.period_ps
    }

    /// Every violation so far.
    pub fn all(&self) -> &[Violation] {
        &self.list
    }

    /// Violations not yet shown to the testbench.
    pub fn pending(&self) -> bool {
        self.shown < self.list.len()
    }

    /// The next violation not yet shown, as one line.
    pub fn take(&mut self) -> Option<String> {
        let v = self.list.get(self.shown)?;
        self.shown += 1;
        Some(format!(
            "at {} ns (emulator cycle {}): {}: {}",
            v.time_ns, v.cycle, v.rule, v.detail
        ))
    }
}

/// Pins-out bit set by `step` when a violation waits to be shown.
pub const VIOLATION_PENDING: u32 = 1 << 7;
