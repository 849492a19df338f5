//! The rule probe suite: every rule of the rule book
//! ([`model::rules::all`]) probed at both sides of its limit through the
//! library, as a simulator drives it: pin levels into an emulator and the
//! monitor of the same protocol ([`cosim::Emulator`]), one step per rising
//! edge of their clock, the monitor seeing the master's pins and the
//! emulator's answer.
//!
//! For every rule there is at least one stimulus that meets its limit by a
//! small margin, which must draw no report from either, and one that breaks
//! it by a small margin, which must draw that rule and no other from both,
//! with the same text. A report whose rule is not in the rule book, a probe
//! naming a rule the book lacks, and a rule of the book without both probes
//! each fail the suite. `docs/rules.md` is written from the suite
//! (`rules_md_is_current`).

use std::fmt::Write as _;

use cosim::{open, Emulator, Pins};
use model::rules::{self, Rule};

/// A master's line as `(level, ps)` segments: bit 0 the line clock, bit 1
/// the data a monitor watches besides the emulator's answer (unused here).
type Line = Vec<(bool, u64)>;

const NS: u64 = 1_000;
const US: u64 = 1_000_000;

/// One stimulus: what it shows, the rule it probes, whether it must pass.
struct Probe {
    protocol: &'static str,
    rule: &'static str,
    legal: bool,
    what: &'static str,
    /// The emulator's (and monitor's) configuration.
    toml: &'static str,
    /// The emulator and monitor clock.
    f_hz: u64,
    line: Line,
    /// Positions the emulator must have latched, in order (when checked).
    reads: &'static [u64],
}

/// What the emulator and the monitor reported, as `(rule name, text)`.
struct Outcome {
    emulator: Vec<(String, String)>,
    monitor: Vec<(String, String)>,
    latched: Vec<u64>,
    decoded: Vec<Option<u64>>,
}

/// The rule of the book a report's label names; a label the book does not
/// hold fails the suite (a rule without a name).
fn named(label: &str) -> String {
    rules::all()
        .iter()
        .find(|r| r.label() == label)
        .map(|r| r.name.to_string())
        .unwrap_or_else(|| panic!("a report names no rule of the rule book: `{label}`"))
}

fn run(p: &Probe) -> Outcome {
    let mut emu = open(p.protocol, p.toml, "probe.toml", p.f_hz).unwrap();
    let mut mon = open(
        &format!("{}_monitor", p.protocol),
        p.toml,
        "probe.toml",
        p.f_hz,
    )
    .unwrap();
    let total: u64 = p.line.iter().map(|s| s.1).sum();
    let (mut seg, mut seg_end) = (0, p.line[0].1);
    let mut answer = true;
    for n in 0.. {
        let t = rules::ps_at(n, p.f_hz);
        if t >= total {
            break;
        }
        while t >= seg_end {
            seg += 1;
            seg_end += p.line[seg].1;
        }
        let clk = p.line[seg].0;
        mon.step(Pins(clk as u32 | (answer as u32) << 1));
        answer = emu.step(Pins::line(clk)).data();
    }
    let reports = |e: &mut Box<dyn Emulator>| -> Vec<(String, String)> {
        e.violations()
            .iter()
            .map(|v| (named(v.rule), v.detail.clone()))
            .collect()
    };
    let t = mon.transcript();
    let decoded = t["transactions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| {
            x.get("position")
                .or_else(|| x.get("slaves").and_then(|s| s.get(0)?.get("position")))
                .and_then(|v| v.as_u64())
        })
        .collect();
    let sent = emu.transcript();
    let list = sent.get("reads").or_else(|| sent.get("frames")).unwrap();
    let latched = list
        .as_array()
        .unwrap()
        .iter()
        .map(|x| {
            x.get("position")
                .or_else(|| x["slaves"].get(0)?.get("position"))
                .and_then(|v| v.as_u64())
                .unwrap()
        })
        .collect();
    Outcome {
        emulator: reports(&mut emu),
        monitor: reports(&mut mon),
        latched,
        decoded,
    }
}

// ---- BiSS-C ----

/// One slave of 16 bits (25 bits after the start bit) behind 100 m of
/// cable (500 ns each way), the seed's 16 µs timeout; 200 MHz (5 ns).
const BISS: &str =
    "[[slaves]]\nbits = 16\npositions = [35555, 4660, 65535]\n[cable]\nlength_m = 100\n";
const BISS_HZ: u64 = 200_000_000;

/// A frame of `periods` MA periods of `low` + `high` ps, then MA high for `rest` ps.
fn frame(periods: u32, low: u64, high: u64, rest: u64) -> Line {
    let mut l = Vec::new();
    for _ in 0..periods {
        l.push((false, low));
        l.push((true, high));
    }
    l.push((true, rest));
    l
}

/// MA idle, then frames; each frame clocks enough periods for the ack, the
/// start bit and 25 bits at any MA rate and line delay of these probes.
fn biss(frames: &[Line]) -> Line {
    let mut l = vec![(true, 2 * US)];
    for f in frames {
        l.extend(f.iter().copied());
    }
    l
}

/// A 10 MHz frame (50 + 50 ns) with two neighbouring phases, from phase
/// `k` on (phase 0 the first low), replaced by `a` and `b` ps.
fn frame_with(k: usize, a: u64, b: u64) -> Line {
    let mut l = frame(40, 50 * NS, 50 * NS, 20 * US);
    l[k].1 = a;
    l[k + 1].1 = b;
    l
}

fn biss_probes() -> Vec<Probe> {
    let p = |rule, legal, what, line, reads: &'static [u64]| Probe {
        protocol: "biss",
        rule,
        legal,
        what,
        toml: BISS,
        f_hz: BISS_HZ,
        line,
        reads,
    };
    let clean = || frame(40, 50 * NS, 50 * NS, 20 * US);
    vec![
        p("TMAS", true, "10 MHz, the fastest MA: periods of exactly 100 ns", biss(&[clean(), clean()]), &[35555, 4660]),
        p("TMAS", true, "1 MHz with MA low 100 ns, high 900 ns", biss(&[frame(40, 100 * NS, 900 * NS, 20 * US)]), &[35555]),
        p("TMAS", false, "one MA period of 95 ns (45 ns low, 50 ns high)", biss(&[frame_with(14, 45 * NS, 50 * NS)]), &[]),
        p("TMASH", true, "MA high 30 ns, low 70 ns", biss(&[frame(40, 70 * NS, 30 * NS, 20 * US)]), &[35555]),
        p("TMASH", false, "one MA high phase of 25 ns, the next low 75 ns", biss(&[frame_with(15, 25 * NS, 75 * NS)]), &[]),
        p("TMASH", false, "a frame restarted 20 ns after the last MA edge", {
                // The last rising edge, MA high 20 ns, the next frame's
                // first falling edge, its first low 80 ns (a 100 ns period).
                let mut f = frame(40, 50 * NS, 50 * NS, 0);
                let n = f.len();
                f[n - 2].1 = 20 * NS;
                biss(&[f, frame_with(0, 80 * NS, 50 * NS)])
            }, &[]),
        p("TMASL", true, "2.5 MHz with MA low 30 ns, high 370 ns", biss(&[frame(40, 30 * NS, 370 * NS, 20 * US)]), &[35555]),
        p("TMASL", false, "one MA high phase of 75 ns, the next low 25 ns", biss(&[frame_with(15, 75 * NS, 25 * NS)]), &[]),
        p(
            "timeout",
            true,
            "the next frame 17.1 us after the last MA edge: SLO high at the master since 17.02 us (16 us timeout, 2 x 500 ns of cable, 20 ns output delay)",
            biss(&[frame(40, 50 * NS, 50 * NS, 17_100 * NS), clean()]),
            &[35555, 4660],
        ),
        p(
            "timeout",
            false,
            "the next frame 16.9 us after the last MA edge: the slave has timed out, its SLO high not yet at the master",
            biss(&[frame(40, 50 * NS, 50 * NS, 16_900 * NS), clean()]),
            &[],
        ),
        p(
            "timeout",
            true,
            "a master holding MA low in reset for 3 us from time 0, then idle 20 us, then frames",
            {
                let mut l = vec![(false, 3 * US)];
                l.extend(biss(&[frame(40, 50 * NS, 50 * NS, 20 * US), clean()]));
                l
            },
            &[35555, 4660],
        ),
    ]
}

// ---- SSI ----

/// The seed's 12-bit encoder (T_m 500 µs) behind 10 m of cable; 10 MHz (100 ns).
const SSI: &str = "positions = [495, 1234, 4095]\n[encoder]\nbits = 12\n[cable]\nlength_m = 10\n";
const SSI_HZ: u64 = 10_000_000;

/// A read: the storing falling edge, T_cs, then 12 periods of `high` +
/// `low` (the master samples each bit at the end of a low phase), then the
/// clock high for `rest`.
fn read(t_cs: u64, high: u64, low: u64, rest: u64) -> Line {
    let mut l = vec![(false, t_cs)];
    for _ in 0..12 {
        l.push((true, high));
        l.push((false, low));
    }
    l.push((true, rest));
    l
}

/// The clock idle 20 µs, then reads.
fn ssi(reads: &[Line]) -> Line {
    let mut l = vec![(true, 20 * US)];
    for r in reads {
        l.extend(r.iter().copied());
    }
    l
}

fn ssi_probes() -> Vec<Probe> {
    let p = |rule, legal, what, line, reads: &'static [u64]| Probe {
        protocol: "ssi",
        rule,
        legal,
        what,
        toml: SSI,
        f_hz: SSI_HZ,
        line,
        reads,
    };
    let at = |khz: u64, rest| read(4 * US, 500 * US / khz, 500 * US / khz, rest);
    vec![
        p("T_cs", true, "T_cs of exactly 4 us", ssi(&[read(4 * US, 2 * US, 2 * US, 600 * US)]), &[495]),
        p("T_cs", false, "T_cs of 3.9 us", ssi(&[read(3_900 * NS, 2 * US, 2 * US, 600 * US)]), &[495]),
        p("f_clk", true, "250 kHz, the fastest clock: periods of 4 us", ssi(&[at(250, 600 * US)]), &[495]),
        p("f_clk", true, "100 kHz, the slowest clock: periods of 10 us", ssi(&[at(100, 600 * US)]), &[495]),
        p("f_clk", true, "200 kHz with the clock low 1.5 us, high 3.5 us", ssi(&[read(4 * US, 3_500 * NS, 1_500 * NS, 600 * US)]), &[495]),
        p("f_clk", true, "100 kHz with the clock high 9 us, low 1 us", ssi(&[read(4 * US, 9 * US, US, 600 * US)]), &[495]),
        p("f_clk", false, "periods of 3.9 us (256 kHz)", ssi(&[read(4 * US, 2 * US, 1_900 * NS, 600 * US)]), &[495]),
        p("f_clk", false, "periods of 10.1 us (99 kHz)", ssi(&[read(4 * US, 5 * US, 5_100 * NS, 600 * US)]), &[495]),
        p("f_clk", false, "83 kHz, 50 % duty", ssi(&[read(4 * US, 6 * US, 6 * US, 600 * US)]), &[495]),
        p(
            "T_m",
            true,
            "the next read 500.1 us after the last clock edge",
            ssi(&[at(250, 500_100 * NS), at(250, 600 * US)]),
            &[495, 1234],
        ),
        p(
            "T_m",
            false,
            "the next read 499.9 us after the last clock edge",
            ssi(&[at(250, 499_900 * NS), at(250, 600 * US)]),
            &[],
        ),
        p(
            "T_m",
            false,
            "the next read 10 us after the last clock edge (a pause as long as the slowest period)",
            ssi(&[at(250, 10 * US), at(250, 600 * US)]),
            &[],
        ),
        p(
            "T_m",
            true,
            "a master holding the clock low in reset for 50 us from time 0, then a read 10 us after it",
            {
                let mut l = vec![(false, 50 * US), (true, 10 * US)];
                l.extend(at(250, 600 * US));
                l.extend(at(250, 600 * US));
                l
            },
            &[495, 1234],
        ),
    ]
}

fn probes() -> Vec<Probe> {
    let mut all = biss_probes();
    all.extend(ssi_probes());
    all
}

/// Runs every probe: a legal one draws no report from either side, an
/// illegal one exactly its rule from both, with the same text; the
/// emulator latched what it must.
fn verdicts() -> Vec<(Probe, Outcome)> {
    let mut out = Vec::new();
    for p in probes() {
        assert!(
            rules::all()
                .iter()
                .any(|r| r.protocol == p.protocol && r.name == p.rule),
            "the probe `{}` names `{}`, which the {} rule book lacks",
            p.what,
            p.rule,
            p.protocol
        );
        let o = run(&p);
        let label = format!("{} {} `{}`", p.protocol, p.rule, p.what);
        if p.legal {
            assert!(
                o.emulator.is_empty(),
                "{label}: the emulator reported {:?}",
                o.emulator
            );
            assert!(
                o.monitor.is_empty(),
                "{label}: the monitor reported {:?}",
                o.monitor
            );
        } else {
            assert!(!o.emulator.is_empty(), "{label}: the emulator saw no break");
            assert!(!o.monitor.is_empty(), "{label}: the monitor saw no break");
            for (side, list) in [("emulator", &o.emulator), ("monitor", &o.monitor)] {
                assert!(
                    list.iter().all(|(r, _)| r == p.rule),
                    "{label}: the {side} reported other rules: {list:?}"
                );
            }
            assert_eq!(
                o.emulator, o.monitor,
                "{label}: the emulator and the monitor say it differently"
            );
        }
        if !p.reads.is_empty() {
            assert_eq!(
                o.latched, p.reads,
                "{label}: the emulator latched other positions"
            );
            let decoded: Vec<Option<u64>> = p.reads.iter().map(|&v| Some(v)).collect();
            assert_eq!(
                o.decoded, decoded,
                "{label}: the monitor decoded other positions"
            );
        }
        out.push((p, o));
    }
    out
}

/// `docs/rules.md`: one row per rule, with its probes.
fn document(v: &[(Probe, Outcome)]) -> String {
    let mut s = String::from(
        "# The rule book\n\n\
         Every timing rule a seed states for a master, as `model::<proto>::rules` holds it: the emulator and the\n\
         monitor of each protocol both call it and print the same rule. Each rule is probed at both sides of its\n\
         limit by `cosim/tests/unit/rules.rs` (pin-level stimuli into the emulator and the monitor through the\n\
         `Emulator` trait): every legal probe drew no report from either, every illegal one exactly its rule from\n\
         both. Generated by that suite: `WRITE_RULES_MD=1 cargo test --release -p cosim --test unit rules::` rewrites it.\n\n\
         | protocol | rule | seed section | bound | measured | legal probes: quiet | illegal probes: flagged |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for r in rules::all() {
        let list = |legal: bool| {
            v.iter()
                .filter(|(p, _)| p.protocol == r.protocol && p.rule == r.name && p.legal == legal)
                .map(|(p, o)| {
                    let n = if legal {
                        o.emulator.len() + o.monitor.len()
                    } else {
                        o.monitor.len()
                    };
                    if legal {
                        format!("{} (quiet: {n} reports)", p.what)
                    } else {
                        format!("{} (flagged: {n} x {})", p.what, r.name)
                    }
                })
                .collect::<Vec<_>>()
                .join("; ")
        };
        let _ = writeln!(
            s,
            "| {} | `{}` | {}: \"{}\" | {} | {}{} | {} | {} |",
            r.protocol,
            r.name,
            r.section,
            r.seed_words,
            r.bound,
            r.measured,
            if r.reading.is_empty() {
                String::new()
            } else {
                format!(" ({})", r.reading)
            },
            list(true),
            list(false)
        );
    }
    s
}

/// Every rule of the book has both probes, and each passes.
#[test]
fn every_rule_is_quiet_on_its_legal_probe_and_flags_its_illegal_one() {
    let v = verdicts();
    for r in rules::all() {
        let has = |legal: bool| {
            v.iter()
                .any(|(p, _)| p.protocol == r.protocol && p.rule == r.name && p.legal == legal)
        };
        assert!(
            has(true),
            "{} has no legal probe (a rule without a probe)",
            r.label()
        );
        assert!(
            has(false),
            "{} has no illegal probe (a rule without a probe)",
            r.label()
        );
    }
}

/// A limit a configuration sets outside the seed's range is refused with
/// that range, by the emulator and the monitor alike.
#[test]
fn a_bound_outside_the_seeds_range_is_refused_with_the_range() {
    for (kind, toml, field) in [
        ("biss", "[checks]\nmin_tmas_ns = 90\n", "checks.min_tmas_ns"),
        (
            "biss_monitor",
            "[monitor]\nmin_tmash_ns = 20\n",
            "monitor.min_tmash_ns",
        ),
        (
            "biss_monitor",
            "[checks]\nmin_tmasl_ns = 10\n",
            "checks.min_tmasl_ns",
        ),
        (
            "ssi",
            "[checks]\nmin_clock_khz = 0.5\n",
            "checks.min_clock_khz",
        ),
        (
            "ssi_monitor",
            "[checks]\nt_cs_min_us = 0\n",
            "checks.t_cs_min_us",
        ),
    ] {
        let e = open(kind, toml, "r.toml", 200_000_000)
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("r.toml")
                && e.contains(field)
                && e.contains("outside the seed's range")
                && e.contains("seed 001"),
            "{kind}: {e}"
        );
    }
    assert!(open(
        "biss",
        "[checks]\nmin_tmas_ns = 150\n",
        "r.toml",
        200_000_000
    )
    .is_ok());
}

/// A clock too coarse for a limit is said once, at time 0, with the clock
/// the limit needs; a fine one says nothing.
#[test]
fn a_clock_that_cannot_resolve_a_limit_says_so_once_with_the_clock_it_needs() {
    let mut emu = open("biss", "", "r.toml", 40_000_000).unwrap();
    let notes = emu.transcript()["notes"].as_array().unwrap().clone();
    assert_eq!(notes.len(), 2, "{notes:?}");
    assert!(
        notes
            .iter()
            .all(|n| n.as_str().unwrap().contains("needs at least 80000000 Hz")),
        "{notes:?}"
    );
    for _ in 0..100 {
        emu.step(Pins::line(true));
    }
    assert_eq!(emu.transcript()["notes"].as_array().unwrap().len(), 2);
    assert!(emu.violations().is_empty());
    let mon = open("biss_monitor", "", "r.toml", 80_000_000).unwrap();
    assert!(mon.transcript()["notes"].as_array().unwrap().is_empty());
}

/// `docs/rules.md` is what the suite writes.
#[test]
fn rules_md_is_current() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/rules.md");
    let fresh = document(&verdicts());
    if std::env::var_os("WRITE_RULES_MD").is_some() {
        std::fs::write(&path, &fresh).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == fresh,
        "docs/rules.md is not what the rule probe suite writes: run `WRITE_RULES_MD=1 cargo test --release -p cosim --test unit rules::` and commit it"
    );
}

/// The book's rule names are unique within a protocol (one name per break).
#[test]
fn every_rule_has_one_name() {
    let all: Vec<&Rule> = rules::all();
    for (i, a) in all.iter().enumerate() {
        assert!(
            all[i + 1..]
                .iter()
                .all(|b| (b.protocol, b.name) != (a.protocol, a.name)),
            "{} is named twice",
            a.label()
        );
    }
}
