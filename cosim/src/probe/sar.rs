//! The SAR58K24 probes, in the emulator's input layout: bit 0 the trigger
//! (CLK of the handshake modes, idle high), bit 1 the host's driver input
//! D, bit 2 its driver enable DE, bit 3 CLR (idle high). The monitor sees
//! the host's receiver R (the line at the host), D, DE, the trigger and
//! CLR (bits 0 to 4), as `sar58k24_monitor.v` wires them.

use model::uart::Parity;

use super::uart::Host;
use super::{Kit, Probe, Src, Stimulus};
use crate::Pins;

/// The SAR58K24's kit.
pub const KIT: Kit = Kit {
    protocol: "sar58k24",
    monitor: &[
        Src::Bus,
        Src::Master(1),
        Src::Master(2),
        Src::Master(0),
        Src::Master(3),
    ],
    idle: Pins(0b101),
    probes,
};

/// The trigger pin.
const TRIG: u32 = 1;
/// The CLR pin.
const CLR: u32 = 8;
/// A microsecond in ps, as the builder counts.
const US: f64 = 1e6;

/// One encoder (address 1, 16 bits) on the bus at 115200 baud, answering
/// 20 µs after the command; the host's timeout 1 ms; 100 MHz (10 ns), fine
/// enough for 2 % of a bit (174 ns) with a margin of 0.2 %.
const BUS: &str = "[sar]\nbaud = 115200.0\nmode = \"bus\"\n[sar.host]\ntimeout_us = 1000.0\n[[sar.encoders]]\naddress = 1\nbits = 16\npositions = [4660, 383]\nanswer_delay_us = 20.0\n[sar.cable]\nlength_m = 0.0\n";
const BUS_HZ: u64 = 100_000_000;
/// The same at 2400 baud, the seed's lowest, answering 500 µs after the
/// command (past the end of its stop bit, 208 µs after the encoder has
/// seen it); 2 MHz.
const BUS_2400: &str = "[sar]\nbaud = 2400.0\nmode = \"bus\"\n[sar.host]\ntimeout_us = 1000.0\n[[sar.encoders]]\naddress = 1\nbits = 16\npositions = [4660, 383]\nanswer_delay_us = 500.0\n[sar.cable]\nlength_m = 0.0\n";
const BUS_2400_HZ: u64 = 2_000_000;
/// One encoder in the pulse handshake mode (3.1.3) at 115200 baud.
const HS: &str = "[sar]\nbaud = 115200.0\nmode = \"handshake\"\n[sar.host]\ntimeout_us = 1000.0\n[[sar.encoders]]\nbits = 16\npositions = [4660, 383]\n[sar.cable]\nlength_m = 0.0\n";

/// The read command of encoder 1.
const READ: [u8; 3] = [0xBC, 0xAA, 0xB1];
/// The read command of encoder 2, absent: no answer.
const READ_2: [u8; 3] = [0xBC, 0xAA, 0xB2];

/// A host at `baud`, trigger and CLR idle, the line idle 20 µs.
fn host(baud: f64) -> Host {
    let mut h = Host::new(baud, Parity::None, TRIG | CLR);
    h.idle(20.0 * US);
    h
}

/// The read command with every bit `scale` bit times, then 1.2 ms idle (the answer).
fn skewed(baud: f64, scale: f64) -> Stimulus {
    host(baud).skewed(&READ, scale).idle(1200.0 * US).line()
}

/// `READ`'s first character, then the host's driver on and high for
/// `silence` bit times after its stop bit, then the rest of the command.
fn gap(silence: f64) -> Stimulus {
    let mut h = host(115_200.0);
    let bit = h.bit();
    h.request(&READ[..1])
        .hold(silence * bit)
        .chars(&READ[1..])
        .idle(1200.0 * US)
        .line()
}

/// Two triggers of 12 µs, at 20 µs and `second_us`.
fn triggers(second_us: f64) -> Stimulus {
    host(115_200.0)
        .pulse(TRIG, 12.0 * US)
        .idle((second_us - 32.0) * US)
        .pulse(TRIG, 12.0 * US)
        .idle(700.0 * US)
        .line()
}

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, toml, f_hz, line| Probe {
        protocol: "sar58k24",
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
    let bit = 1e12 / 115_200.0;
    vec![
        p("character", true, "115200 baud, every bit 1.8 % long", BUS, BUS_HZ, skewed(115_200.0, 1.018)),
        p("character", false, "115200 baud, every bit 2.2 % long", BUS, BUS_HZ, skewed(115_200.0, 1.022)),
        p("character", true, "115200 baud, every bit 1.8 % short", BUS, BUS_HZ, skewed(115_200.0, 0.982)),
        p("character", false, "115200 baud, every bit 2.2 % short", BUS, BUS_HZ, skewed(115_200.0, 0.978)),
        p("character", true, "2400 baud, every bit 1.8 % long", BUS_2400, BUS_2400_HZ, skewed(2400.0, 1.018)),
        p("character", false, "2400 baud, every bit 2.2 % long", BUS_2400, BUS_2400_HZ, skewed(2400.0, 1.022)),
        p("character", false, "a character with its stop bit low (the line held low ten bits)", BUS, BUS_HZ, {
            let mut h = host(115_200.0);
            h.hold(bit).low(10.0 * bit).hold(2.0 * bit).idle(100.0 * US).line()
        }),
        p("command gap", true, "14.9 bits from BC's stop-bit middle to AA's start edge", BUS, BUS_HZ, gap(14.4)),
        p("command gap", false, "15.1 bits from BC's stop-bit middle to AA's start edge", BUS, BUS_HZ, gap(14.6)),
        p("release", true, "DE off 0.9 bit after the command's last stop bit", BUS, BUS_HZ, {
            let mut h = host(115_200.0);
            h.request(&READ).hold(0.9 * bit).idle(1200.0 * US).line()
        }),
        p("release", false, "DE off 1.1 bits after the command's last stop bit", BUS, BUS_HZ, {
            let mut h = host(115_200.0);
            h.request(&READ).hold(1.1 * bit).idle(1200.0 * US).line()
        }),
        p("one driver", true, "the next command restarted 30 us after the answer's last stop bit", BUS, BUS_HZ, {
            // The answer: 20 µs after the command, five characters (434 µs).
            let mut h = host(115_200.0);
            h.request(&READ).idle(490.0 * US).request(&READ).idle(600.0 * US).line()
        }),
        p("one driver", false, "DE on, D high, 100 us into the answer, for 100 us", BUS, BUS_HZ, {
            let mut h = host(115_200.0);
            h.request(&READ).idle(120.0 * US).hold(100.0 * US).idle(600.0 * US).line()
        }),
        p("answer wait", true, "a command to an absent encoder, the next 1.01 ms after DE fell (timeout 1 ms)", BUS, BUS_HZ, {
            let mut h = host(115_200.0);
            h.request(&READ_2).idle(1010.0 * US - bit).request(&READ).idle(600.0 * US).line()
        }),
        p("answer wait", false, "a command to an absent encoder, the next 0.99 ms after DE fell (timeout 1 ms)", BUS, BUS_HZ, {
            let mut h = host(115_200.0);
            h.request(&READ_2).idle(990.0 * US - bit).request(&READ).idle(600.0 * US).line()
        }),
        p("T2", true, "a trigger low 10.1 us", HS, BUS_HZ, {
            host(115_200.0).pulse(TRIG, 10.1 * US).idle(700.0 * US).line()
        }),
        p("T2", false, "a trigger low 9.9 us", HS, BUS_HZ, {
            host(115_200.0).pulse(TRIG, 9.9 * US).idle(700.0 * US).line()
        }),
        p("T2", true, "a host holding trigger and CLR low in reset for 5 us from time 0, then a trigger after the answer the encoder gave to it", HS, BUS_HZ, {
            let mut h = Host::new(115_200.0, Parity::None, TRIG | CLR);
            h.pulse(TRIG | CLR, 5.0 * US)
                .idle(600.0 * US)
                .pulse(TRIG, 12.0 * US)
                .idle(700.0 * US)
                .line()
        }),
        // The frame: 20 µs of acquisition after the trigger's falling
        // edge, five characters (434 µs): 40 to 474 µs.
        p("T1-T3", true, "the next trigger 30 us after the frame's last stop bit", HS, BUS_HZ, triggers(504.0)),
        p("T1-T3", false, "the next trigger 200 us into the frame", HS, BUS_HZ, triggers(240.0)),
        p("CLR", true, "CLR low 10.1 us", BUS, BUS_HZ, {
            host(115_200.0).pulse(CLR, 10.1 * US).idle(20.0 * US).line()
        }),
        p("CLR", false, "CLR low 9.9 us", BUS, BUS_HZ, {
            host(115_200.0).pulse(CLR, 9.9 * US).idle(20.0 * US).line()
        }),
        Probe {
            unknown: 4,
            unknown_ps: 200 * super::US,
            ..p("character", true, "DE unknown (X) for 200 us from time 0 while D toggles, then a command", BUS, BUS_HZ, {
                let mut h = Host::new(115_200.0, Parity::None, TRIG | CLR);
                h.chars(&[0x55, 0x0F]).hold(200.0 * US - 20.0 * bit);
                h.idle(100.0 * US).request(&READ).idle(600.0 * US).line()
            })
        },
    ]
}
