//! The CANopen probes: the master's frames on TXD (bit 1, as for CAN: see
//! [`super::can`]) against a DS 406 encoder (node 1) and a SAR58K24 (node
//! 0x20) that acknowledge them. Most frames go to node 9 or SAR58K24 node
//! 0x21, which are not on the bus: nobody answers, so each probe's timing
//! is the stimulus's alone (the present nodes still acknowledge every
//! frame). Each gap is counted from the end of EOF (the SDO and SAR58K24
//! rules: the previous request's end) or SOF to SOF (guarding, SYNC).

use model::can::frame::Frame;
use model::canopen::sdo;

use super::can::{idle, line, sent, BIT, HZ, SAMPLE};
use super::{Kit, Probe, Src, Stimulus, US};
use crate::Pins;

/// CANopen's kit.
pub const KIT: Kit = Kit {
    protocol: "canopen",
    monitor: &[Src::WiredAnd(1), Src::Master(1)],
    idle: Pins(1),
    probes,
};

/// 500 kbit/s, 16 quanta (as the CAN probes), SDO timeout 1 ms, SYNC period
/// 1 ms; a guard time of 1 ms; the SAR58K24 answer timeout 1 ms; the
/// tolerance 0.5 %.
const CANOPEN: &str = "[canopen]\nf_sys_mhz = 16\nbit_rate_kbps = 500\ntq_per_bit = 16\nsample_point = 0.75\n\
    [canopen.master]\nsdo_timeout_us = 1000\nsync_period_us = 1000\n\
    [[canopen.encoders]]\nname = \"enc\"\nposition_m = 5\n[canopen.encoders.encoder]\nnode_switch = 1\nbit_rate_switch = 5\n\
    [[canopen.sar]]\nname = \"sar\"\nposition_m = 5\n[canopen.sar.encoder]\nnode = 0x20\nbit_rate_kbps = 500\n\
    [canopen.monitor]\nbit_tolerance_percent = 0.5\nguard_time_ms = 1\nsar_answer_timeout_us = 1000\n";

/// TXD recessive for `ps`.
fn gap(ps: u64) -> Stimulus {
    vec![(3, ps)]
}

/// The encoder's boot-up (on the bus about 270 us after power-on) over,
/// then `parts`.
fn after_boot(parts: &[Stimulus]) -> Stimulus {
    let mut l = gap(400 * US);
    l.extend(line(parts, BIT));
    l
}

/// Frames with the gaps between them (ps, end of EOF to SOF).
fn frames(list: &[(&Frame, u64)]) -> Stimulus {
    let parts: Vec<Stimulus> = list
        .iter()
        .flat_map(|&(f, g)| [sent(f, BIT), gap(g)])
        .collect();
    after_boot(&parts)
}

/// Frames sent SOF to SOF `period` ps apart.
fn every(f: &Frame, periods: &[u64]) -> Stimulus {
    let len = f.wire_bits(false).len() as u64 * BIT;
    let list: Vec<(&Frame, u64)> = periods.iter().map(|&p| (f, p - len)).collect();
    let mut parts: Vec<Stimulus> = list
        .iter()
        .flat_map(|&(f, g)| [sent(f, BIT), gap(g)])
        .collect();
    parts.push(sent(f, BIT));
    after_boot(&parts)
}

fn remote(id: u32) -> Frame {
    Frame {
        id,
        ide: false,
        rtr: true,
        dlc: 1,
        data: vec![],
    }
}

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, line| Probe {
        protocol: "canopen",
        rule,
        legal,
        what,
        toml: CANOPEN,
        f_hz: HZ,
        line,
        unknown: 0,
        unknown_ps: 0,
        reads: &[],
    };
    let ms = 1_000 * US;
    // An SDO upload of the device type (1000h) from node 9 and from node 1.
    let sdo9 = Frame::data(0x609, &sdo::upload(0x1000, 0));
    let sdo1 = Frame::data(0x601, &sdo::upload(0x1000, 0));
    let start = Frame::data(0, &[0x01, 9]);
    let stop = Frame::data(0, &[0x02, 9]);
    let guard = remote(0x709);
    let heartbeat = |v: u16| Frame::data(0x609, &sdo::download(0x1017, 0, &v.to_le_bytes()));
    let sync = Frame::data(0x80, &[]);
    let click = |nn: u32| Frame::data(0x200 + nn, &[0x80, nn as u8, 0, 0, 0, 0, 0, 0]);
    // Guarding: at most 1 ms x 1.1 + 160 bits (320 us) SOF to SOF.
    let guard_most = 1_420 * US;
    // SYNC: 1 ms ± (0.5 % of it + 160 bits) = ± 325 us.
    let (sync_least, sync_most) = (675 * US, 1_325 * US);
    vec![
        p("SDO", true, "a second request to node 1 after its answer, 200 us after the first (the timeout is 1 ms)", frames(&[(&sdo1, 200 * US), (&sdo1, 10 * US)])),
        p("SDO", true, "a second request to node 9 (no answer) 1 ms after the first's end: the timeout", frames(&[(&sdo9, ms), (&sdo9, 10 * US)])),
        p("SDO", false, "a second request to node 9, unanswered, 2 samples (125 ns) before the timeout", frames(&[(&sdo9, ms - 2 * SAMPLE), (&sdo9, 10 * US)])),
        p("SDO", false, "a second request to node 9 right after the first (3 bits of intermission)", frames(&[(&sdo9, 3 * BIT), (&sdo9, 10 * US)])),
        p("NMT start", true, "start node 9, stop it, start it again", frames(&[(&start, 100 * US), (&stop, 100 * US), (&start, 10 * US)])),
        p("NMT start", false, "start node 9 twice", frames(&[(&start, 100 * US), (&start, 10 * US)])),
        Probe {
            unknown: 2,
            unknown_ps: 40 * US,
            ..p("NMT start", true, "a master holding reset (TXD unknown) for 20 bits from time 0, then start, stop, start", {
                let mut l = idle(20, BIT);
                l.extend(frames(&[(&start, 100 * US), (&stop, 100 * US), (&start, 10 * US)]));
                l
            })
        },
        p("node guarding", true, "guard requests to node 9 1.42 ms apart (1 ms + 10 % + 160 bits)", every(&guard, &[guard_most, guard_most])),
        p("node guarding", false, "guard requests to node 9 1.42 ms and 2 samples apart", every(&guard, &[guard_most, guard_most + 2 * SAMPLE])),
        p("guarding with heartbeat", true, "a producer heartbeat time of 0 written to node 9 (1017h), then a guard request", frames(&[(&heartbeat(0), 100 * US), (&guard, 10 * US)])),
        p("guarding with heartbeat", false, "a producer heartbeat time of 100 ms written to node 9 (1017h), then a guard request", frames(&[(&heartbeat(100), 100 * US), (&guard, 10 * US)])),
        p("SYNC period", true, "SYNCs 1.325 ms and 0.675 ms apart (1 ms ± 0.5 % ± 160 bits)", every(&sync, &[sync_most, sync_least])),
        p("SYNC period", false, "SYNCs 1.325 ms and 2 samples apart", every(&sync, &[sync_most + 2 * SAMPLE])),
        p("SYNC period", false, "SYNCs 0.675 ms less 2 samples apart", every(&sync, &[sync_least - 2 * SAMPLE])),
        p("SAR58K24 command", true, "a click to SAR58K24 node 0x20, its answer, another click 200 us after the first", frames(&[(&click(0x20), 200 * US), (&click(0x20), 10 * US)])),
        p("SAR58K24 command", true, "clicks to node 0x21 (no answer) 1 ms apart, end to start: the answer timeout", frames(&[(&click(0x21), ms), (&click(0x21), 10 * US)])),
        p("SAR58K24 command", false, "clicks to node 0x21, unanswered, 2 samples less than 1 ms apart", frames(&[(&click(0x21), ms - 2 * SAMPLE), (&click(0x21), 10 * US)])),
    ]
}
