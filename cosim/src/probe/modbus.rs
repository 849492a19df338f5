//! The Modbus RTU probes, in the emulator's input layout: bit 1 the
//! master's driver input D, bit 2 its driver enable DE. The monitor sees
//! the master's receiver R (the line at the master), D and DE (bits 0 to
//! 2), as `modbus_monitor.v` wires them.

use model::modbus::frames::{self, BROADCAST};
use model::uart::Parity;

use super::uart::Host;
use super::{Kit, Probe, Src, Stimulus};
use crate::Pins;

/// Modbus RTU's kit.
pub const KIT: Kit = Kit {
    protocol: "modbus",
    monitor: &[Src::Bus, Src::Master(1), Src::Master(2)],
    idle: Pins(0b101),
    probes,
};

/// A microsecond in ps, as the builder counts.
const US: f64 = 1e6;

/// One device (address 1, 16 bits) answering 100 µs after t3.5; the
/// master's timeout 5 ms; no cable.
macro_rules! modbus {
    ($baud:literal) => {
        concat!(
            "[modbus]\nbaud = ",
            $baud,
            "\n[modbus.master]\ntimeout_us = 5000.0\n[[modbus.devices]]\naddress = 1\nbits = 16\npositions = [383, 4660]\n[modbus.cable]\nlength_m = 0.0\n"
        )
    };
}
const B2400: &str = modbus!("2400.0");
const B9600: &str = modbus!("9600.0");
const B19200: &str = modbus!("19200.0");
const B57600: &str = modbus!("57600.0");

/// The seed's request: read one register of station 1.
const READ: [u8; 8] = [0x01, 0x03, 0x00, 0x00, 0x00, 0x01, 0x84, 0x0A];

/// The clock for `baud`: a period under 0.1 % of the first edge's time
/// after a start edge (one bit), so that a character 0.2 % inside the 2 %
/// tolerance is measured inside it.
fn clock(baud: f64) -> u64 {
    ((baud * 1000.0) as u64).max(1_000_000).div_ceil(1_000_000) * 1_000_000
}

/// A master at `baud`, the line idle 20 µs.
fn master(baud: f64) -> Host {
    let mut h = Host::new(baud, Parity::None, 0);
    h.idle(20.0 * US);
    h
}

/// The read request with every bit `scale` bit times, then 100 µs idle.
fn skewed(baud: f64, scale: f64) -> Stimulus {
    master(baud).skewed(&READ, scale).idle(100.0 * US).line()
}

/// t1.5 and t3.5 at `baud`, ps.
fn t15_t35(baud: f64) -> (f64, f64) {
    (
        frames::t15_seconds(baud, 10) * 1e12,
        frames::t35_seconds(baud, 10) * 1e12,
    )
}

/// The read request with `silence` ps from the third character's
/// stop-bit middle to the fourth's start edge.
fn gap(baud: f64, silence: f64) -> Stimulus {
    let mut h = master(baud);
    let bit = h.bit();
    h.request(&READ[..3])
        .hold(silence - bit / 2.0)
        .chars(&READ[3..])
        .idle(100.0 * US)
        .line()
}

/// A broadcast, then the read request's first start edge `silence` ps
/// after the end of the broadcast's last stop bit.
fn silence(baud: f64, silence: f64) -> Stimulus {
    let mut bcast = READ;
    bcast[0] = BROADCAST;
    let crc = frames::crc_bytes(&bcast[..6]);
    bcast[6..].copy_from_slice(&crc);
    let mut h = master(baud);
    let bit = h.bit();
    h.request(&bcast)
        .idle(silence - bit)
        .request(&READ)
        .idle(100.0 * US)
        .line()
}

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, toml, baud: f64, line| Probe {
        protocol: "modbus",
        rule,
        legal,
        what,
        toml,
        f_hz: clock(baud),
        line,
        unknown: 0,
        unknown_ps: 0,
        reads: &[],
    };
    let (t15_9600, t35_9600) = t15_t35(9600.0);
    let (t15_19200, t35_19200) = t15_t35(19200.0);
    let (t15_57600, t35_57600) = t15_t35(57600.0);
    let bit = 1e12 / 19200.0;
    let mut other = READ;
    other[0] = 9;
    let crc = frames::crc_bytes(&other[..6]);
    other[6..].copy_from_slice(&crc);
    let mut bad_crc = READ;
    bad_crc[7] ^= 1;
    vec![
        p("character", true, "2400 baud, every bit 1.8 % long", B2400, 2400.0, skewed(2400.0, 1.018)),
        p("character", false, "2400 baud, every bit 2.2 % long", B2400, 2400.0, skewed(2400.0, 1.022)),
        p("character", true, "9600 baud, every bit 1.8 % short", B9600, 9600.0, skewed(9600.0, 0.982)),
        p("character", false, "9600 baud, every bit 2.2 % short", B9600, 9600.0, skewed(9600.0, 0.978)),
        p("character", true, "57600 baud, every bit 1.8 % short", B57600, 57600.0, skewed(57600.0, 0.982)),
        p("character", false, "57600 baud, every bit 2.2 % short", B57600, 57600.0, skewed(57600.0, 0.978)),
        p("character", true, "57600 baud, every bit 1.8 % long", B57600, 57600.0, skewed(57600.0, 1.018)),
        p("character", false, "57600 baud, every bit 2.2 % long", B57600, 57600.0, skewed(57600.0, 1.022)),
        Probe {
            unknown: 4,
            unknown_ps: 2000 * super::US,
            ..p("character", true, "DE unknown (X) for 2 ms from time 0 while D toggles, then a request", B19200, 19200.0, {
                let mut h = Host::new(19200.0, Parity::None, 0);
                h.chars(&[0x55, 0x0F, 0x01]).hold(2000.0 * US - 30.0 * bit);
                h.idle(100.0 * US).request(&READ).idle(100.0 * US).line()
            })
        },
        p("t1.5", true, "9600 baud: 1.5 characters less 5 us inside the request", B9600, 9600.0, gap(9600.0, t15_9600 - 5.0 * US)),
        p("t1.5", false, "9600 baud: 1.5 characters and 5 us inside the request", B9600, 9600.0, gap(9600.0, t15_9600 + 5.0 * US)),
        p("t1.5", true, "19200 baud: 1.5 characters less 5 us inside the request", B19200, 19200.0, gap(19200.0, t15_19200 - 5.0 * US)),
        p("t1.5", false, "19200 baud: 1.5 characters and 5 us inside the request", B19200, 19200.0, gap(19200.0, t15_19200 + 5.0 * US)),
        p("t1.5", true, "57600 baud: 745 us inside the request (750 us above 19200 baud)", B57600, 57600.0, gap(57600.0, t15_57600 - 5.0 * US)),
        p("t1.5", false, "57600 baud: 755 us inside the request (750 us above 19200 baud)", B57600, 57600.0, gap(57600.0, t15_57600 + 5.0 * US)),
        p("t3.5", true, "9600 baud: a request 3.5 characters and 5 us after a broadcast's last stop bit", B9600, 9600.0, silence(9600.0, t35_9600 + 5.0 * US)),
        p("t3.5", false, "9600 baud: a request 3.5 characters less 5 us after a broadcast's last stop bit", B9600, 9600.0, silence(9600.0, t35_9600 - 5.0 * US)),
        p("t3.5", true, "19200 baud: a request 3.5 characters and 5 us after a broadcast's last stop bit", B19200, 19200.0, silence(19200.0, t35_19200 + 5.0 * US)),
        p("t3.5", false, "19200 baud: a request 3.5 characters less 5 us after a broadcast's last stop bit", B19200, 19200.0, silence(19200.0, t35_19200 - 5.0 * US)),
        p("t3.5", true, "57600 baud: a request 1755 us after a broadcast's last stop bit (1750 us above 19200 baud)", B57600, 57600.0, silence(57600.0, t35_57600 + 5.0 * US)),
        p("t3.5", false, "57600 baud: a request 1745 us after a broadcast's last stop bit (1750 us above 19200 baud)", B57600, 57600.0, silence(57600.0, t35_57600 - 5.0 * US)),
        p("t3.5", false, "19200 baud: a request restarted two bits after a broadcast's last stop bit (DE off for one)", B19200, 19200.0, silence(19200.0, 2.0 * bit)),
        p("release", true, "DE off 0.9 bit after the request's last stop bit", B19200, 19200.0, {
            master(19200.0).request(&READ).hold(0.9 * bit).idle(100.0 * US).line()
        }),
        p("release", false, "DE off 1.1 bits after the request's last stop bit", B19200, 19200.0, {
            master(19200.0).request(&READ).hold(1.1 * bit).idle(100.0 * US).line()
        }),
        p("one driver", true, "the next request t3.5 and 50 us after the answer's last stop bit", B19200, 19200.0, {
            // The answer: t3.5 and 100 µs after the request, 7 characters.
            master(19200.0)
                .request(&READ)
                .idle(t35_19200 + 100.0 * US + 70.0 * bit + t35_19200 + 50.0 * US)
                .request(&READ)
                .idle(100.0 * US)
                .line()
        }),
        p("one driver", false, "DE on, D high, 200 us into the answer, for 200 us", B19200, 19200.0, {
            master(19200.0)
                .request(&READ)
                .idle(t35_19200 + 300.0 * US)
                .hold(200.0 * US)
                .idle(100.0 * US)
                .line()
        }),
        p("response timeout", true, "a request to absent station 9, the next 5.01 ms after DE fell (timeout 5 ms)", B19200, 19200.0, {
            master(19200.0).request(&other).idle(5010.0 * US - bit).request(&READ).idle(100.0 * US).line()
        }),
        p("response timeout", false, "a request to absent station 9, the next 4.99 ms after DE fell (timeout 5 ms)", B19200, 19200.0, {
            master(19200.0).request(&other).idle(4990.0 * US - bit).request(&READ).idle(100.0 * US).line()
        }),
        p("CRC", true, "the seed's request 01 03 00 00 00 01 84 0A", B19200, 19200.0, {
            master(19200.0).request(&READ).idle(100.0 * US).line()
        }),
        p("CRC", false, "the seed's request with its last CRC bit flipped (01 03 00 00 00 01 84 0B)", B19200, 19200.0, {
            master(19200.0).request(&bad_crc).idle(100.0 * US).line()
        }),
    ]
}
