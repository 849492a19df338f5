//! The BiSS-C probes: MA as the master drives it (bit 0 of the stimulus);
//! the emulator sees MA, the monitor MA and SLO at the master (bits 0, 1).

use super::{Kit, Probe, Src, Stimulus, NS, US};
use crate::Pins;

/// BiSS-C's kit.
pub const KIT: Kit = Kit {
    protocol: "biss",
    monitor: &[Src::Master(0), Src::Emulator(0)],
    idle: Pins(1),
    probes,
};

/// One slave of 16 bits (25 bits after the start bit) behind 100 m of
/// cable (500 ns each way), the seed's 16 µs timeout; 200 MHz (5 ns).
const BISS: &str =
    "[[slaves]]\nbits = 16\npositions = [35555, 4660, 65535]\n[cable]\nlength_m = 100\n";
const BISS_HZ: u64 = 200_000_000;

/// A frame of `periods` MA periods of `low` + `high` ps, then MA high for `rest` ps.
fn frame(periods: u32, low: u64, high: u64, rest: u64) -> Stimulus {
    let mut l = Vec::new();
    for _ in 0..periods {
        l.push((0, low));
        l.push((1, high));
    }
    l.push((1, rest));
    l
}

/// MA idle, then frames; each frame clocks enough periods for the ack, the
/// start bit and 25 bits at any MA rate and line delay of these probes.
fn biss(frames: &[Stimulus]) -> Stimulus {
    let mut l = vec![(1, 2 * US)];
    for f in frames {
        l.extend(f.iter().copied());
    }
    l
}

/// A 10 MHz frame (50 + 50 ns) with two neighbouring phases, from phase
/// `k` on (phase 0 the first low), replaced by `a` and `b` ps.
fn frame_with(k: usize, a: u64, b: u64) -> Stimulus {
    let mut l = frame(40, 50 * NS, 50 * NS, 20 * US);
    l[k].1 = a;
    l[k + 1].1 = b;
    l
}

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, line, reads: &'static [u64]| Probe {
        protocol: "biss",
        rule,
        legal,
        what,
        toml: BISS,
        f_hz: BISS_HZ,
        line,
        unknown: 0,
        unknown_ps: 0,
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
                let mut l = vec![(0, 3 * US)];
                l.extend(biss(&[frame(40, 50 * NS, 50 * NS, 20 * US), clean()]));
                l
            },
            &[35555, 4660],
        ),
    ]
}
