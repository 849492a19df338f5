//! The T-format probes: the host's transceiver as it drives it (bit 1 D,
//! bit 2 DE, [`super::half_duplex`]); the emulator sees D and DE, the
//! monitor R (the line at the host: the encoder while it drives, else the
//! host's driver, else the idle high), D and DE, as `tformat_monitor.v`'s
//! ports `rx`, `tx`, `tx_en`.

use model::tformat::frames::{self, DataId};

use super::half_duplex::{bits, driven, idle, pause, runs, shift, spaced, DE};
use super::{Kit, Probe, Src, Stimulus, NS, US};
use crate::Pins;

/// T-format's kit.
pub const KIT: Kit = Kit {
    protocol: "tformat",
    monitor: &[Src::Bus, Src::Master(1), Src::Master(2)],
    idle: Pins(1),
    probes,
};

/// The seed's encoder at 2.5 Mbps on a cable of no length.
const TF: &str = "baud = 2.5e6\n[cable]\nlength_m = 0\n";
/// 1 GHz: edges placed to the ns (the jitter probes).
const FINE_HZ: u64 = 1_000_000_000;
/// 20 MHz: the least clock that resolves the jitter (the spacing probes).
const SLOW_HZ: u64 = 20_000_000;
/// One bit at 2.5 Mbps.
const BIT: u64 = 400 * NS;

/// The fields of a request of `id`.
fn request(id: DataId) -> Vec<u8> {
    frames::request(id, 5, 0x3C)
}

/// The line idle before the first request: more than a character (the
/// rule book times a host from its first request after a character of idle).
const LEAD: u64 = 5 * US;

/// One request after the lead, then 60 us of idle (the answer).
fn alone(r: Stimulus) -> Stimulus {
    let mut s = vec![idle(LEAD)];
    s.extend(r);
    s.push(idle(60 * US));
    s
}

/// A readout (Data ID 0) with its edge `k` moved by `delta` ps.
fn bent(k: usize, delta: i64) -> Stimulus {
    alone(driven(
        &shift(runs(&bits(&request(DataId::Id0)), BIT), k, delta),
        0,
    ))
}

/// A readout (Data ID 0) at `bit_ps` a bit.
fn rate(bit_ps: u64) -> Stimulus {
    alone(driven(&runs(&bits(&request(DataId::Id0)), bit_ps), 0))
}

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, f_hz, line| Probe {
        protocol: "tformat",
        rule,
        legal,
        what,
        toml: TF,
        f_hz,
        line,
        unknown: 0,
        unknown_ps: 0,
        reads: &[],
    };
    let id0 = || driven(&runs(&bits(&request(DataId::Id0)), BIT), 0);
    let id7 = || driven(&runs(&bits(&request(DataId::Id7)), BIT), 0);
    let idd = bits(&request(DataId::IdD));
    vec![
        p("jitter", true, "a readout with one edge 100 ns late", FINE_HZ, bent(2, 100 * NS as i64)),
        p("jitter", true, "a readout with one edge 100 ns early", FINE_HZ, bent(2, -(100 * NS as i64))),
        p("jitter", false, "a readout with one edge 101 ns late", FINE_HZ, bent(2, 101 * NS as i64)),
        p("jitter", false, "a readout with one edge 101 ns early", FINE_HZ, bent(2, -(101 * NS as i64))),
        p("jitter", true, "a readout at 411.1 ns a bit (2.432 Mbps, the slowest: its stop bit's edge 100 ns late)", FINE_HZ, rate(411_100)),
        p("jitter", true, "a readout at 388.9 ns a bit (2.571 Mbps, the fastest: its stop bit's edge 99 ns early)", FINE_HZ, rate(388_900)),
        p("jitter", false, "a readout at 411.2 ns a bit (its stop bit's edge 101 ns late)", FINE_HZ, rate(411_200)),
        p("jitter", false, "a readout at 388.7 ns a bit (its stop bit's edge 101 ns early)", FINE_HZ, rate(388_700)),
        p("request fields", true, "an EEPROM read (Data ID D): CF ADF CRC", FINE_HZ, alone(driven(&runs(&idd, BIT), 0))),
        p("request fields", false, "an EEPROM read (Data ID D) of CF and ADF alone", FINE_HZ, alone(driven(&runs(&idd[..20], BIT), 0))),
        p("release", true, "DE released 1.5 us after the delimiter", FINE_HZ, alone(driven(&runs(&bits(&request(DataId::Id0)), BIT), 1_500 * NS))),
        p("release", false, "DE released 1.501 us after the delimiter", FINE_HZ, alone(driven(&runs(&bits(&request(DataId::Id0)), BIT), 1_501 * NS))),
        p("end of frame", true, "an EEPROM read with 300 ns (half a bit and the jitter) between ADF and CRC", FINE_HZ, alone(driven(&pause(&idd, 1, BIT, 300 * NS), 0))),
        p("end of frame", false, "an EEPROM read with 301 ns between ADF and CRC", FINE_HZ, alone(driven(&pause(&idd, 1, BIT, 301 * NS), 0))),
        p("reset interval", true, "two resets (Data ID 7) 40 ms apart", SLOW_HZ, spaced(LEAD, &[40_000 * US], &[id7(), id7()], 60 * US)),
        p("reset interval", false, "two resets (Data ID 7) 39.99995 ms apart", SLOW_HZ, spaced(LEAD, &[40_000 * US - 50 * NS], &[id7(), id7()], 60 * US)),
        p("reset interval", false, "a reset (Data ID 7) sent twice, 40 ms apart, then a readout", SLOW_HZ, spaced(LEAD, &[40_000 * US, 100 * US], &[id7(), id7(), id0()], 60 * US)),
        p("no request during the answer", true, "a readout, then the next 31.402 us after its start (11 bits after the start bit of the answer's last field)", FINE_HZ, spaced(LEAD, &[31_402 * NS], &[id0(), id0()], 60 * US)),
        p("no request during the answer", false, "a readout, then the next 31.401 us after its start", FINE_HZ, spaced(LEAD, &[31_401 * NS], &[id0(), id0()], 60 * US)),
        p("no request during the answer", false, "a readout, then DE on 20 us after its start", FINE_HZ, spaced(LEAD, &[20 * US], &[id0(), id0()], 60 * US)),
        Probe {
            unknown: DE,
            unknown_ps: 5 * US,
            ..p("jitter", true, "DE unknown (X) and D low for 5 us from time 0, then a readout", FINE_HZ, {
                let mut s = vec![(DE, 5 * US)];
                s.extend(alone(id0()));
                s
            })
        },
        p("jitter", true, "a host in reset driving the line low for 5 us from time 0, then a readout 60 us later", FINE_HZ, {
            let mut s = vec![(DE, 5 * US), idle(60 * US)];
            s.extend(alone(id0()));
            s
        }),
    ]
}
