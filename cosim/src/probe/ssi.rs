//! The SSI probes: the clock as the master drives it (bit 0 of the
//! stimulus); the emulator sees the clock, the monitor the clock and the
//! data at the master (bits 0, 1).

use super::{Kit, Probe, Src, Stimulus, NS, US};
use crate::Pins;

/// SSI's kit.
pub const KIT: Kit = Kit {
    protocol: "ssi",
    monitor: &[Src::Master(0), Src::Emulator(0)],
    idle: Pins(1),
    probes,
};

/// The seed's 12-bit encoder (T_m 500 µs) behind 10 m of cable; 10 MHz (100 ns).
const SSI: &str = "positions = [495, 1234, 4095]\n[encoder]\nbits = 12\n[cable]\nlength_m = 10\n";
const SSI_HZ: u64 = 10_000_000;

/// A read: the storing falling edge, T_cs, then 12 periods of `high` +
/// `low` (the master samples each bit at the end of a low phase), then the
/// clock high for `rest`.
fn read(t_cs: u64, high: u64, low: u64, rest: u64) -> Stimulus {
    let mut l = vec![(0, t_cs)];
    for _ in 0..12 {
        l.push((1, high));
        l.push((0, low));
    }
    l.push((1, rest));
    l
}

/// The clock idle 20 µs, then reads.
fn ssi(reads: &[Stimulus]) -> Stimulus {
    let mut l = vec![(1, 20 * US)];
    for r in reads {
        l.extend(r.iter().copied());
    }
    l
}

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, line, reads: &'static [u64]| Probe {
        protocol: "ssi",
        rule,
        legal,
        what,
        toml: SSI,
        f_hz: SSI_HZ,
        line,
        unknown: 0,
        unknown_ps: 0,
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
                let mut l = vec![(0, 50 * US), (1, 10 * US)];
                l.extend(at(250, 600 * US));
                l.extend(at(250, 600 * US));
                l
            },
            &[495, 1234],
        ),
    ]
}
