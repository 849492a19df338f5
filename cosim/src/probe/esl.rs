//! The ESL probes: the host's transceiver as it drives it (bit 1 DI, bit 2
//! DE, [`super::half_duplex`]); the emulator sees DI and DE, the monitor RO
//! (the bus at the host: an encoder while it drives, else the host's
//! driver, else the idle high), DI and DE, as `esl_monitor.v`'s ports `rx`,
//! `tx`, `tx_en`.

use model::esl::frames::{self, PAGE_REGISTER};

use super::half_duplex::{bits, driven, idle, pause, runs, spaced, DE};
use super::{Kit, Probe, Src, Stimulus, NS, US};
use crate::Pins;

/// ESL's kit.
pub const KIT: Kit = Kit {
    protocol: "esl",
    monitor: &[Src::Bus, Src::Master(1), Src::Master(2)],
    idle: Pins(1),
    probes,
};

/// The seed's encoder (address 0) at 10 Mbps on a cable of no length.
const ESL: &str = "baud = 10e6\n[cable]\nlength_m = 0\n";
/// The same with a page change of 20 us (the EEPROM spacing probes: the
/// page register is set first, and the least stimulus waits no 18 ms).
const ESL_QUICK_PAGE: &str =
    "baud = 10e6\n[cable]\nlength_m = 0\n[[encoders]]\naddress = 0\npage_change_us = 20\n";
/// 1 GHz: edges placed to the ns (the bit-rate probes).
const FINE_HZ: u64 = 1_000_000_000;
/// 80 MHz: the spacing probes.
const SPACING_HZ: u64 = 80_000_000;
/// One bit at 10 Mbps.
const BIT: u64 = 100 * NS;
/// One sample at 80 MHz.
const SAMPLE: u64 = 12_500;
/// An EEPROM address (not the page register).
const CELL: u8 = 0x10;

/// A request of Data ID `code` to encoder 0, at `bit_ps` a bit, DE
/// released at its last end bit.
fn request(code: u8, mem: u8, data: u8, bit_ps: u64) -> Stimulus {
    driven(
        &runs(&bits(&frames::request(0, code, mem, data)), bit_ps),
        0,
    )
}

/// One request after 2 us of idle, then 40 us of idle (the answer).
fn alone(r: Stimulus) -> Stimulus {
    let mut s = vec![idle(2 * US)];
    s.extend(r);
    s.push(idle(40 * US));
    s
}

/// A safety position read (Data ID 1).
fn read1() -> Stimulus {
    request(1, 0, 0, BIT)
}

/// The page register set to page 0 (EEPROM), then after `wait` ps (start
/// to start) the requests `then` spaced `every`.
fn paged(wait: u64, every: &[u64], then: &[Stimulus]) -> Stimulus {
    let mut rs = vec![request(0xF, PAGE_REGISTER, 0, BIT)];
    rs.extend(then.iter().cloned());
    let mut gaps = vec![wait];
    gaps.extend(every);
    spaced(2 * US, &gaps, &rs, 40 * US)
}

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, toml, f_hz, line| Probe {
        protocol: "esl",
        rule,
        legal,
        what,
        toml,
        f_hz,
        line,
        unknown: 0,
        unknown_ps: 0,
        reads: &[],
    };
    let ide = bits(&frames::request(0, 0xE, CELL, 0));
    let eeprom_read = || request(0xE, CELL, 0, BIT);
    let eeprom_write = || request(0xF, CELL, 0x5A, BIT);
    let b = || request(0xB, 0, 0, BIT);
    vec![
        p("bit rate", true, "a position read at 103.0 ns a bit (9.709 Mbps, 3 % slow: its edge at 9 bits 27 ns late, 27.8 ns allowed)", ESL, FINE_HZ, alone(request(1, 0, 0, 103_000))),
        p("bit rate", true, "a position read at 97.1 ns a bit (10.30 Mbps, 3 % fast: its edge at 9 bits 26 ns early, 26.2 ns allowed)", ESL, FINE_HZ, alone(request(1, 0, 0, 97_100))),
        p("bit rate", false, "a position read at 103.1 ns a bit (its edge at 4 bits 13 ns late, 12.4 ns allowed)", ESL, FINE_HZ, alone(request(1, 0, 0, 103_100))),
        p("bit rate", false, "a position read at 97.0 ns a bit (its edge at 4 bits 12 ns early, 11.6 ns allowed)", ESL, FINE_HZ, alone(request(1, 0, 0, 97_000))),
        p("request frames", true, "an EEPROM read (Data ID E): RCF ADF CRC", ESL, FINE_HZ, alone(driven(&runs(&ide, BIT), 0))),
        p("request frames", false, "an EEPROM read (Data ID E) of RCF and ADF alone", ESL, FINE_HZ, alone(driven(&runs(&ide[..20], BIT), 0))),
        p("end of frame set", true, "an EEPROM read with 50 ns (half a bit) between ADF and CRC", ESL, FINE_HZ, alone(driven(&pause(&ide, 1, BIT, 50 * NS), 0))),
        p("end of frame set", false, "an EEPROM read with 51 ns between ADF and CRC", ESL, FINE_HZ, alone(driven(&pause(&ide, 1, BIT, 51 * NS), 0))),
        p("release", true, "DE released 1 us after the last end bit", ESL, FINE_HZ, alone(driven(&runs(&bits(&frames::request(0, 1, 0, 0)), BIT), US))),
        p("release", false, "DE released 1.001 us after the last end bit", ESL, FINE_HZ, alone(driven(&runs(&bits(&frames::request(0, 1, 0, 0)), BIT), 1_001 * NS))),
        p("half duplex", true, "a position read, then the next 22.102 us after its start (11 bits after the start bit of the answer's last frame)", ESL, FINE_HZ, spaced(2 * US, &[22_102 * NS], &[read1(), read1()], 40 * US)),
        p("half duplex", false, "a position read, then the next 22.101 us after its start", ESL, FINE_HZ, spaced(2 * US, &[22_101 * NS], &[read1(), read1()], 40 * US)),
        p("half duplex", false, "a position read, then DE on 10 us after its start", ESL, FINE_HZ, spaced(2 * US, &[10 * US], &[read1(), read1()], 40 * US)),
        p("repeat", true, "Data ID B twice, 200 us apart", ESL, SPACING_HZ, spaced(2 * US, &[200 * US], &[b(), b()], 40 * US)),
        p("repeat", false, "Data ID B twice, 200.0125 us apart", ESL, SPACING_HZ, spaced(2 * US, &[200 * US + SAMPLE], &[b(), b()], 40 * US)),
        p("repeat", true, "Data ID B 8 times, 40 us apart, then a position read", ESL, SPACING_HZ, spaced(2 * US, &[40 * US; 8], &[b(), b(), b(), b(), b(), b(), b(), b(), read1()], 40 * US)),
        p("repeat", false, "Data ID B once, then a position read", ESL, SPACING_HZ, spaced(2 * US, &[40 * US], &[b(), read1()], 40 * US)),
        p("EEPROM read", true, "two EEPROM reads 200.0125 us apart", ESL_QUICK_PAGE, SPACING_HZ, paged(50 * US, &[200 * US + SAMPLE], &[eeprom_read(), eeprom_read()])),
        p("EEPROM read", false, "two EEPROM reads 200 us apart", ESL_QUICK_PAGE, SPACING_HZ, paged(50 * US, &[200 * US], &[eeprom_read(), eeprom_read()])),
        p("EEPROM write", true, "two EEPROM writes 6.0000125 ms apart", ESL_QUICK_PAGE, SPACING_HZ, paged(50 * US, &[6_000 * US + SAMPLE], &[eeprom_write(), eeprom_write()])),
        p("EEPROM write", false, "two EEPROM writes 6 ms apart", ESL_QUICK_PAGE, SPACING_HZ, paged(50 * US, &[6_000 * US], &[eeprom_write(), eeprom_write()])),
        // The page write has four frames, the read three: their ends are 1 us closer than their starts.
        p("page change", true, "an EEPROM read 18 ms after the end of a page-register write", ESL, SPACING_HZ, paged(18_001 * US, &[], &[eeprom_read()])),
        p("page change", false, "an EEPROM read 17.9999875 ms after the end of a page-register write", ESL, SPACING_HZ, paged(18_001 * US - SAMPLE, &[], &[eeprom_read()])),
        Probe {
            unknown: DE,
            unknown_ps: 5 * US,
            ..p("bit rate", true, "DE unknown (X) and DI low for 5 us from time 0, then a position read", ESL, FINE_HZ, {
                let mut s = vec![(DE, 5 * US)];
                s.extend(alone(read1()));
                s
            })
        },
        p("bit rate", true, "a host in reset driving the bus low for 5 us from time 0, then a position read 40 us later", ESL, FINE_HZ, {
            let mut s = vec![(DE, 5 * US), idle(40 * US)];
            s.extend(alone(read1()));
            s
        }),
    ]
}
