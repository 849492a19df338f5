//! The CAN probes: the master's TXD (bit 1 of the stimulus; bit 0 held
//! high, as `can_node_emu` ties it), against one emulated node that
//! acknowledges its frames. The monitor sees the bus at the master's RXD
//! (bit 0: the master's TXD and the emulator's answer, wired-AND) and TXD
//! (bit 1), as `can_monitor`'s `i_can_rx` and `i_can_tx`.
//!
//! Every stimulus is made of the model's own frame encoder
//! ([`Frame::wire_bits`], the stuffed bits SOF to EOF with the ACK slot
//! recessive as a transmitter sends it), each bit a whole number of samples
//! long, so an edge lands where the stimulus puts it.

use model::can::frame::{self, Frame};

use super::{Kit, Probe, Src, Stimulus, US};
use crate::Pins;

/// CAN's kit.
pub const KIT: Kit = Kit {
    protocol: "can",
    monitor: &[Src::WiredAnd(1), Src::Master(1)],
    idle: Pins(1),
    probes,
};

/// 500 kbit/s, 16 quanta of 125 ns (PROP_SEG 7, PHASE_SEG1 4, PHASE_SEG2 4),
/// SJW 2 quanta (250 ns), the tolerance 0.5 %; one node.
const CAN: &str = "[can]\nf_sys_mhz = 16\ntiming = { bit_rate_kbps = 500, tq_per_bit = 16, sample_point = 0.75, sjw = 2 }\n[[can.nodes]]\nname = \"a\"\nposition_m = 5\n[can.monitor]\nbit_tolerance_percent = 0.5\n";
/// The fastest rate, 1 Mbit/s (16 quanta of 62.5 ns).
const CAN_1M: &str = "[can]\nf_sys_mhz = 16\ntiming = { bit_rate_kbps = 1000, tq_per_bit = 16, sample_point = 0.75, sjw = 2 }\n[[can.nodes]]\nname = \"a\"\nposition_m = 5\n[can.monitor]\nbit_tolerance_percent = 0.5\n";
/// The slowest rate of seed 003 §5.5, 10 kbit/s (20 quanta of 5 us).
const CAN_10K: &str = "[can]\nf_sys_mhz = 16\ntiming = { bit_rate_kbps = 10, tq_per_bit = 20, sample_point = 0.75, sjw = 2 }\n[[can.nodes]]\nname = \"a\"\nposition_m = 5\n[can.monitor]\nbit_tolerance_percent = 0.5\n";
/// The emulator and monitor clock: 62.5 ns a sample, 32 samples a bit.
pub const HZ: u64 = 16_000_000;
/// One bit at 500 kbit/s, ps.
pub const BIT: u64 = 2 * US;
/// One sample at [`HZ`], ps.
pub const SAMPLE: u64 = 62_500;

/// TXD at `level` for `ps` (bit 0 held high).
fn seg(level: bool, ps: u64) -> (u32, u64) {
    (1 | (level as u32) << 1, ps)
}

/// `bits` on TXD, each `bit` ps long.
pub fn bits(bits: &[bool], bit: u64) -> Stimulus {
    let mut l: Stimulus = Vec::new();
    for &b in bits {
        match l.last_mut() {
            Some(last) if last.0 == seg(b, 0).0 => last.1 += bit,
            _ => l.push(seg(b, bit)),
        }
    }
    l
}

/// TXD recessive for `n` bits of `bit` ps.
pub fn idle(n: u64, bit: u64) -> Stimulus {
    vec![seg(true, n * bit)]
}

/// The bus idle 20 bits, then the parts, then 40 bits idle (a frame is
/// judged once the bus has been idle 10.5 bits after it, and a node's error
/// or overload frame may come first).
pub fn line(parts: &[Stimulus], bit: u64) -> Stimulus {
    let mut l = idle(20, bit);
    for p in parts {
        l.extend(p.iter().copied());
    }
    l.extend(idle(40, bit));
    l
}

/// A frame as its transmitter drives TXD: the encoder's wire bits, the ACK
/// slot recessive, EOF included.
pub fn sent(f: &Frame, bit: u64) -> Stimulus {
    bits(&f.wire_bits(false), bit)
}

/// The frame of most probes: a standard data frame of two bytes.
fn frame() -> Frame {
    Frame::data(0x123, &[0xDE, 0xAD])
}

/// `f` sent with the TXD edge into wire bit `k` moved `d` ps late.
fn late_edge(f: &Frame, k: usize, d: u64) -> Stimulus {
    let w = f.wire_bits(false);
    assert!(w[k] != w[k - 1], "wire bit {k} starts with an edge");
    let mut l = bits(&w[..k], BIT);
    let rest = bits(&w[k..], BIT);
    l.last_mut().expect("bits before the edge").1 += d;
    let mut rest = rest.into_iter();
    let (lv, len) = rest.next().expect("bits after the edge");
    l.push((lv, len - d));
    l.extend(rest);
    l
}

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, toml, line| Probe {
        protocol: "can",
        rule,
        legal,
        what,
        toml,
        f_hz: HZ,
        line,
        unknown: 0,
        unknown_ps: 0,
        reads: &[],
    };
    let f = frame();
    // The stuffed part of 0x7E5 opens with SOF and six recessive identifier bits.
    let f7e5 = Frame::data(0x7E5, &[0x55]);
    let unstuffed = {
        let mut w = f7e5.destuffed_bits();
        w.extend([true; 10]);
        bits(&w, BIT)
    };
    let bad_crc = {
        let mut d = f.destuffed_bits();
        let last = d.len() - 1;
        d[last] = !d[last];
        let mut w = frame::stuff(&d);
        w.extend([true; 10]);
        bits(&w, BIT)
    };
    let wire = f.wire_bits(false);
    let n = wire.len();
    let dominant_at = |k: usize| {
        let mut w = wire.clone();
        w[k] = false;
        bits(&w, BIT)
    };
    let scaled = |num: u64, den: u64| bits(&wire, BIT * num / den);
    // An edge of identifier bit 0x123's first one: wire bit 3 (SOF, 0, 0, 1).
    let k = (1..n).find(|&k| wire[k] != wire[k - 1]).expect("an edge");
    let at = (k as u64 * BIT) as f64;
    // The limit at that edge: 0.5 % of its time since the SOF plus one SJW (250 ns).
    let limit = 0.005 * at + 250_000.0;
    let under = (limit / SAMPLE as f64).floor() as u64 * SAMPLE;
    let over = under + SAMPLE;
    vec![
        p("stuffing", true, "0x7E5 as the encoder stuffs it (a stuff bit after SOF and five recessive identifier bits)", CAN, line(&[sent(&f7e5, BIT)], BIT)),
        p("stuffing", false, "0x7E5 without its stuff bits: SOF and six recessive identifier bits", CAN, line(&[unstuffed], BIT)),
        p("CRC", true, "a frame with its CRC-15", CAN, line(&[sent(&f, BIT)], BIT)),
        p("CRC", false, "the same frame with the CRC sequence's last bit flipped (restuffed)", CAN, line(&[bad_crc], BIT)),
        p("form", true, "TXD recessive in the ACK slot (the node acknowledges), the delimiters and EOF", CAN, line(&[sent(&f, BIT)], BIT)),
        p("form", false, "TXD dominant in the CRC delimiter", CAN, line(&[dominant_at(n - 10)], BIT)),
        p("form", false, "TXD dominant in the ACK slot of the master's own frame", CAN, line(&[dominant_at(n - 9)], BIT)),
        p("form", false, "TXD dominant in the last EOF bit", CAN, line(&[dominant_at(n - 1)], BIT)),
        p("intermission", true, "the next SOF after 3 bits of intermission, right after the last one", CAN, line(&[sent(&f, BIT), idle(3, BIT), sent(&f, BIT)], BIT)),
        p("intermission", false, "the next SOF after 2 bits of intermission", CAN, line(&[sent(&f, BIT), idle(2, BIT), sent(&f, BIT)], BIT)),
        p("bit time", true, "a frame 0.5 % fast, the tolerance", CAN, line(&[scaled(995, 1000)], BIT)),
        p("bit time", true, "a frame 0.5 % slow, the tolerance", CAN, line(&[scaled(1005, 1000)], BIT)),
        p("bit time", false, "a frame 0.8 % fast: its last edges beyond the tolerance and one SJW", CAN, line(&[scaled(992, 1000)], BIT)),
        p("bit time", true, "one TXD edge late by the tolerance and one SJW, to the sample below the limit", CAN, line(&[late_edge(&f, k, under)], BIT)),
        p("bit time", false, "one TXD edge late by one sample more", CAN, line(&[late_edge(&f, k, over)], BIT)),
        p("bit time", true, "1 Mbit/s, the fastest rate", CAN_1M, line(&[sent(&f, US)], US)),
        p("bit time", true, "10 kbit/s, the slowest rate", CAN_10K, line(&[sent(&f, 100 * US)], 100 * US)),
        p("dominant length", true, "an error flag of 6 bits after bus idle", CAN, line(&[bits(&[false; 6], BIT)], BIT)),
        p("dominant length", false, "an error flag of 6 bits and 2 samples (125 ns), beyond 6 bits and 0.5 %", CAN, line(&[vec![seg(false, 6 * BIT + 2 * SAMPLE)]], BIT)),
        Probe {
            unknown: 2,
            unknown_ps: 40 * US,
            ..p("dominant length", true, "a master holding reset (TXD unknown) for 20 bits from time 0, then a frame", CAN, {
                let mut l = vec![seg(true, 40 * US)];
                l.extend(line(&[sent(&f, BIT)], BIT));
                l
            })
        },
        p("dominant length", false, "TXD dominant for 23 bits", CAN, line(&[vec![seg(false, 46 * US)]], BIT)),
    ]
}
