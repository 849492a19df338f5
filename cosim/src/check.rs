//! Protocol checks: the emulator sees the master's line pins every emulator
//! cycle, so it holds the master to the timing limits the seeds state and
//! records each violation with its time and the seed's rule.
//!
//! Limits are named fields of a `[checks]` table (defaults: the seed's
//! numbers). Where a protocol has a rule book (`model::<proto>::rules`, see
//! [`model::rules`]), the emulator and the monitor both feed its watcher and
//! record its breaches here ([`Checks::breach`]); a limit is then the seed's
//! bound measured at the emulator clock's resolution, with no cycle of
//! slack, and what that clock cannot resolve is noted once at time 0
//! ([`Checks::note`]).

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
    notes: Vec<String>,
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
            notes: Vec::new(),
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

    /// Records a breach of a rule of the rule book seen at `cycle`.
    pub fn breach(&mut self, cycle: u64, b: &model::rules::Breach) {
        self.push(cycle, b.rule.label(), b.detail.clone());
    }

    /// A remark on the checks themselves (not a violation of the master),
    /// printed once when made: a limit the clock cannot resolve.
    pub fn note(&mut self, text: String) {
        eprintln!("NOTE: {text}");
        self.notes.push(text);
    }

    /// The remarks so far.
    pub fn notes(&self) -> &[String] {
        &self.notes
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
