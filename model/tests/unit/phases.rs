//! Test support: the clock phases a bench drives.

use std::collections::BTreeMap;

use model::testbench::Testbench;
use model::trace::Sample;

/// How often each run length of line signal `line` (the master's clock
/// pin) occurs over a whole run, high runs and low runs apart.
pub fn runs<B: Testbench>(mut bench: B, line: usize) -> (BTreeMap<u64, u64>, BTreeMap<u64, u64>) {
    let mut sample = Sample::for_layout(bench.layout());
    let (mut high, mut low) = (BTreeMap::new(), BTreeMap::new());
    let mut level: Option<u64> = None;
    let mut len = 0;
    while !bench.finished() {
        bench.step(Some(&mut sample));
        let v = sample.line[line];
        if Some(v) != level {
            match level {
                // The first run (from reset) has no edge before it.
                Some(l) if len > 0 => {
                    *(if l == 1 { &mut high } else { &mut low })
                        .entry(len)
                        .or_insert(0) += 1
                }
                _ => {}
            }
            level = Some(v);
            len = 0;
        }
        len += 1;
    }
    (high, low)
}

/// Asserts that the shortest high run is `high` cycles and the shortest
/// low run `low` cycles, each seen at least 8 times (a frame's worth).
pub fn assert_split<B: Testbench>(bench: B, line: usize, high: u64, low: u64, what: &str) {
    let (h, l) = runs(bench, line);
    assert_eq!(
        h.keys().next().copied(),
        Some(high),
        "{what}: shortest high phase; high runs {h:?}"
    );
    assert_eq!(
        l.keys().next().copied(),
        Some(low),
        "{what}: shortest low phase; low runs {l:?}"
    );
    assert!(
        h[&high] >= 8 && l[&low] >= 8,
        "{what}: too few clock phases; {h:?} {l:?}"
    );
}
