//! The two traits every protocol implements so that `tbgen` can drive it
//! without knowing it: [`Setup`] (a scenario's configuration of master,
//! device, cable and host) and [`Testbench`] (the running set-up, one system
//! clock per [`Testbench::step`]).
//!
//! Adding a protocol means writing its `BenchConfig: Setup` and its
//! `Bench: Testbench` in `model/src/<proto>/`, then one line in `tbgen`'s
//! protocol registry (`tbgen/src/lib.rs`, see the README's "Adding a
//! protocol"). A protocol module uses the shared modules (`time`, `line`,
//! `crc`, `uart`, `angle`, `gray`, `bits`...), never another protocol's.

use serde::Serialize;

use crate::trace::{Layout, Sample, Sink};
use crate::{Result, Timebase};

/// One transaction of a transcript.
pub trait Transaction: Serialize {
    /// First and last cycle of the transaction (host request to result).
    fn span(&self) -> (u64, u64);
}

/// A running set-up: host, master, cable and device, stepped together.
pub trait Testbench {
    /// What the transcript records per transaction.
    type Transaction: Transaction;
    /// The signals each sample carries.
    fn layout(&self) -> &Layout;
    /// One system-clock cycle of the whole set-up; fills `sample` in place
    /// when there is one (a run that records nothing passes `None` and saves
    /// the copying).
    fn step(&mut self, sample: Option<&mut Sample>);
    /// Fills `sample` with the set-up as it stands before its first cycle
    /// (its master held in reset) and returns true, if the bench knows it.
    /// Each sample of [`Testbench::step`] shows the set-up after a clock
    /// edge, so a master that acts on its first edge (an EnDat master
    /// starting its power-on delay measurement) shows no sample of its rest
    /// levels; a reader that needs them (a monitor, which takes a clock low
    /// from its first sample for a master held in reset) asks here. The
    /// default: not known (false), the first sample stands for the rest.
    fn before_first_cycle(&self, _sample: &mut Sample) -> bool {
        false
    }
    /// Whether the host is done and the tail has run.
    fn finished(&self) -> bool;
    /// Cycles stepped so far.
    fn cycle(&self) -> u64;
    /// The transactions so far, consuming the bench.
    fn into_transactions(self) -> Vec<Self::Transaction>;

    /// How many of the next cycles are known to change nothing a sample or
    /// the transcript shows: no input, output, line or decoded value (but
    /// the [`Testbench::counters`]), no transaction, and not
    /// [`Testbench::finished`] before their end. Only counters run (a
    /// monoflop, a recovery time, a host's gap, a bit clock between its
    /// sample points), so [`Testbench::skip`] can advance through them in
    /// one go.
    ///
    /// The default, 0, is always correct: a bench that does not know its
    /// quiet stretches is stepped cycle by cycle.
    fn quiet_cycles(&self) -> u64 {
        0
    }

    /// Advances `n` cycles, each with the same sample as the last stepped
    /// one (the [`Testbench::counters`] aside), leaving the bench exactly as
    /// `n` calls of `step(None)` would. Callers pass at most
    /// [`Testbench::quiet_cycles`]; the default steps.
    fn skip(&mut self, n: u64) {
        for _ in 0..n {
            self.step(None);
        }
    }

    /// The columns of [`Layout::decoded`] that are free-running counters (a
    /// bit clock's quantum count): the one thing a quiet stretch may change
    /// in a sample, as stepping would. Were they held, a stretch would end
    /// at each of their steps. The default: none.
    fn counters(&self) -> &'static [usize] {
        &[]
    }

    /// [`run_to_end`] of this bench. Each bench implements it with
    /// [`compiled_here!`] (the CAN bench with its own loop, which steps
    /// only the parts whose event a cycle is: `can::Bench::step_due`), so
    /// that the loop is compiled with the model
    /// (optimised) rather than in the crate that calls it: tbgen is compiled
    /// unoptimised (the workspace's Cargo.toml), and its bench figures time
    /// these loops.
    fn run_to_end_compiled(self) -> Run<Self::Transaction>
    where
        Self: Sized;

    /// [`run_every_cycle`] of this bench, compiled with the model (see
    /// [`Testbench::run_to_end_compiled`]).
    fn run_every_cycle_compiled(self) -> Run<Self::Transaction>
    where
        Self: Sized;

    /// [`lockstep`] of this bench (`self` fast-forwarded, `stepped` stepped),
    /// compiled with the model (see [`Testbench::run_to_end_compiled`]).
    fn lockstep_compiled(self, name: &str, stepped: Self) -> Lockstep<Self::Transaction>
    where
        Self: Sized;
}

/// The [`Testbench`] methods every bench writes the same way, inside its
/// `impl Testbench` block: the run loops instantiated for the concrete bench
/// in this crate, where they are compiled optimised.
#[macro_export]
macro_rules! compiled_here {
    () => {
        fn run_to_end_compiled(self) -> $crate::testbench::Run<Self::Transaction> {
            $crate::testbench::run_to_end(self)
        }
        fn run_every_cycle_compiled(self) -> $crate::testbench::Run<Self::Transaction> {
            $crate::testbench::run_every_cycle(self)
        }
        fn lockstep_compiled(
            self,
            name: &str,
            stepped: Self,
        ) -> $crate::testbench::Lockstep<Self::Transaction> {
            $crate::testbench::lockstep(name, self, stepped)
        }
    };
}

/// A scenario's configuration of one protocol: what `tbgen` needs to run it
/// and to label its outputs.
pub trait Setup: Clone + std::fmt::Debug {
    /// The running set-up this configuration builds.
    type Bench: Testbench;
    /// The protocol's descriptor (`model/src/<module>/descriptor.rs`).
    const PROTOCOL: &'static crate::protocol::Protocol;
    /// The Verilog core the vectors drive (`ssi_master`).
    const CORE: &'static str = Self::PROTOCOL.core;
    /// The scenario file's table for this protocol (`ssi`): its stem.
    const TABLE: &'static str = Self::PROTOCOL.stem;
    /// Checks every field; the error names the field within the table.
    fn validate(&self) -> Result<()>;
    /// The system clock.
    fn timebase(&self) -> Result<Timebase>;
    /// The core's Verilog parameters, in the order vector headers list them.
    fn verilog_parameters(&self) -> Result<Vec<(&'static str, u64)>>;
    /// Builds the set-up in its reset state.
    fn bench(&self) -> Result<Self::Bench>;
}

/// The result of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct Run<T> {
    /// Cycles simulated.
    pub cycles: u64,
    /// One entry per transaction, in order.
    pub transactions: Vec<T>,
}

/// Runs `bench` to the end, handing every cycle's sample to `sink`.
pub fn run<B: Testbench, S: Sink>(
    mut bench: B,
    sink: &mut S,
) -> std::result::Result<Run<B::Transaction>, S::Error> {
    let mut sample = Sample::for_layout(bench.layout());
    while !bench.finished() {
        bench.step(Some(&mut sample));
        sink.sample(bench.cycle() - 1, &sample)?;
    }
    let cycles = bench.cycle();
    Ok(Run {
        cycles,
        transactions: bench.into_transactions(),
    })
}

/// Runs `bench` to the end recording nothing (campaigns, benchmarks),
/// advancing through quiet stretches in one step each
/// ([`Testbench::quiet_cycles`]). Same cycles and transactions as
/// [`run_every_cycle`].
pub fn run_to_end<B: Testbench>(mut bench: B) -> Run<B::Transaction> {
    while !bench.finished() {
        match bench.quiet_cycles() {
            0 => bench.step(None),
            n => bench.skip(n),
        }
    }
    Run {
        cycles: bench.cycle(),
        transactions: bench.into_transactions(),
    }
}

/// Runs `bench` to the end recording nothing, one [`Testbench::step`] per
/// cycle: the reference [`run_to_end`] is checked against, and the
/// "before" of the fast-forward speed figures.
pub fn run_every_cycle<B: Testbench>(mut bench: B) -> Run<B::Transaction> {
    while !bench.finished() {
        bench.step(None);
    }
    Run {
        cycles: bench.cycle(),
        transactions: bench.into_transactions(),
    }
}

/// What [`lockstep`] ran: the cycles, how many of them were skipped, and
/// both transcripts for the caller to compare (a transaction type need not
/// be `PartialEq`: the integration test compares them as JSON).
pub struct Lockstep<T> {
    pub cycles: u64,
    pub skipped: u64,
    pub skipping: Vec<T>,
    pub stepped: Vec<T>,
}

/// Runs `skipping` (fast-forwarded) and `stepped` (every cycle) in lockstep
/// and panics, naming `name` and the cycle, at the first difference:
/// - every cycle's complete sample must be the same, a skipped cycle's
///   sample being the last stepped one but for the free-running counters
///   among the decoded signals ([`Testbench::counters`]), which the next
///   stepped cycle's sample checks;
/// - each skip lands on the cycle stepping reaches, and both finish on the
///   same cycle.
///
/// The check that fast-forward is invisible: `tests/fast_forward.rs` runs
/// it on every built-in and bench scenario, the protocols' unit tests on
/// their own set-ups.
pub fn lockstep<B: Testbench>(
    name: &str,
    mut skipping: B,
    mut stepped: B,
) -> Lockstep<B::Transaction> {
    let mut want = Sample::for_layout(stepped.layout());
    let mut got: Option<Sample> = None;
    let mut skipped = 0;
    while !skipping.finished() {
        assert!(
            !stepped.finished(),
            "{name}: the fast-forwarded bench runs past the end, cycle {}",
            stepped.cycle()
        );
        let quiet = skipping.quiet_cycles();
        if quiet == 0 {
            let mut sample = got
                .take()
                .unwrap_or_else(|| Sample::for_layout(skipping.layout()));
            skipping.step(Some(&mut sample));
            stepped.step(Some(&mut want));
            assert_eq!(
                sample,
                want,
                "{name}: cycle {} differs after fast-forwards",
                stepped.cycle() - 1
            );
            got = Some(sample);
            continue;
        }
        let start = skipping.cycle();
        skipping.skip(quiet);
        skipped += quiet;
        let counters = skipping.counters();
        for _ in 0..quiet {
            assert!(
                !stepped.finished(),
                "{name}: the skip from cycle {start} by {quiet} runs past the end"
            );
            stepped.step(Some(&mut want));
            // Before the first step there is no sample to compare with:
            // the skipped cycles must then all show the first one.
            let reference = got.get_or_insert_with(|| want.clone());
            assert_eq!(
                reference.without_counters(counters),
                want.without_counters(counters),
                "{name}: cycle {} changes within the {quiet} cycles skipped from cycle {start}",
                stepped.cycle() - 1
            );
        }
        assert_eq!(
            skipping.cycle(),
            stepped.cycle(),
            "{name}: skip({quiet}) from cycle {start} lands on the wrong cycle"
        );
    }
    assert!(
        stepped.finished(),
        "{name}: the fast-forwarded bench finished at cycle {}, stepping did not",
        skipping.cycle()
    );
    Lockstep {
        cycles: stepped.cycle(),
        skipped,
        skipping: skipping.into_transactions(),
        stepped: stepped.into_transactions(),
    }
}
