//! The CAN and CANopen monitors on crafted lines (each rule broken once, or
//! none) and beside the CAN emulator with a master node of the model.

use model::can::frame::Frame;

use cosim::monitor::can::*;
use cosim::monitor::canopen::CanopenMonitor;
use cosim::{Emulator, Pins};
use model::can::rules as can_rules;
use model::canopen::rules as co_rules;

/// 500 kbit/s, 16 quanta on an 8 MHz clock: 16 monitor cycles per bit.
const CAN: &str = "[can]\nf_sys_mhz = 8\ntiming = { bit_rate_kbps = 500, tq_per_bit = 16, sample_point = 0.75, sjw = 1 }\n";
const CANOPEN: &str = "[canopen]\nf_sys_mhz = 8\nbit_rate_kbps = 500\ntq_per_bit = 16\nsample_point = 0.75\n[canopen.master]\nsdo_timeout_us = 1000\n";
const F: u64 = 8_000_000;
const CPB: f64 = 16.0;

/// A line under construction: TXD and RXD, bit by bit, each bit `cpb` cycles.
#[derive(Default)]
struct Line {
    pins: Vec<(bool, bool)>,
    at: f64,
}

impl Line {
    fn bits(&mut self, tx: &[bool], rx: &[bool], cpb: f64) -> &mut Self {
        for (&t, &r) in tx.iter().zip(rx) {
            self.at += cpb;
            while (self.pins.len() as f64) < self.at.round() {
                self.pins.push((t, r));
            }
        }
        self
    }
    fn idle(&mut self, n: usize) -> &mut Self {
        self.bits(&vec![true; n], &vec![true; n], CPB)
    }
    /// A frame the master sends, acknowledged by another node; then 3 bits of intermission.
    fn sent(&mut self, f: &Frame) -> &mut Self {
        self.bits(&f.wire_bits(false), &f.wire_bits(true), CPB)
            .idle(3)
    }
    /// A frame another node sends, acknowledged by the master.
    fn heard(&mut self, f: &Frame) -> &mut Self {
        let rx = f.wire_bits(true);
        let ack = rx.len() - 9;
        let tx: Vec<bool> = (0..rx.len()).map(|k| k != ack).collect();
        self.bits(&tx, &rx, CPB).idle(3)
    }
    fn play(&self, mon: &mut dyn Emulator) {
        for &(t, r) in &self.pins {
            mon.step(Pins(r as u32 | (t as u32) << 1));
        }
    }
}

fn can() -> CanMonitor {
    CanMonitor::from_toml(CAN, "can.toml", F).unwrap()
}

fn rules(m: &mut dyn Emulator) -> Vec<&'static str> {
    m.violations().iter().map(|v| v.rule).collect()
}

#[test]
fn a_clean_exchange_is_decoded_with_its_senders_and_no_violation() {
    let mut m = can();
    let (a, b) = (
        Frame::data(0x123, &[0xDE, 0xAD]),
        Frame {
            id: 0x456,
            ide: false,
            rtr: true,
            dlc: 2,
            data: vec![],
        },
    );
    let ext = Frame {
        id: 0x1ABCDEF,
        ide: true,
        rtr: false,
        dlc: 1,
        data: vec![0x55],
    };
    let mut l = Line::default();
    l.idle(20).sent(&a).heard(&b).sent(&ext).idle(20);
    l.play(&mut m);
    assert!(rules(&mut m).is_empty(), "{:?}", m.violations());
    assert_eq!(m.count(), 3);
    let t = m.transcript();
    let list = t["transactions"].as_array().unwrap();
    assert_eq!(
        (
            list[0]["id"].clone(),
            list[0]["data"].clone(),
            list[0]["sender"].clone()
        ),
        (
            0x123.into(),
            serde_json::json!([0xDE, 0xAD]),
            "master".into()
        )
    );
    assert_eq!(
        (
            list[1]["rtr"].clone(),
            list[1]["dlc"].clone(),
            list[1]["sender"].clone()
        ),
        (true.into(), 2.into(), "bus".into())
    );
    assert_eq!(
        (
            m.last_value(1),
            m.last_value(0),
            m.last_value(3),
            m.last_value(4)
        ),
        (Some(0x1ABCDEF), Some(0x55 << 56), Some(3), Some(2))
    );
    assert!(m.last_status(0, "ide").unwrap() && m.last_status(0, "master").unwrap());
}

/// The bus reaches the master's RXD late by its loop delay (transceiver,
/// bus, a testbench's registers). A delay longer than the time from the
/// sample point to the bit's end (here 5 cycles against 4) still leaves the
/// frame the master's, with no violation: TXD is read on its own grid.
#[test]
fn a_frame_the_master_sends_stays_its_own_when_rxd_lags_txd_past_the_bit_end() {
    let f = Frame::data(0x2F, &[0x43, 0x10, 0xF0, 0x40, 0xE2]);
    let mut l = Line::default();
    l.idle(20).sent(&f).idle(20);
    let lag = 5;
    let pins: Vec<(bool, bool)> = (0..l.pins.len())
        .map(|i| (l.pins[i].0, if i < lag { true } else { l.pins[i - lag].1 }))
        .collect();
    let mut m = can();
    for &(t, r) in &pins {
        m.step(Pins(r as u32 | (t as u32) << 1));
    }
    assert!(rules(&mut m).is_empty(), "{:?}", m.violations());
    assert_eq!(m.count(), 1);
    assert_eq!(m.transcript()["transactions"][0]["sender"], "master");
}

/// Each CAN rule broken once, reported once with its time.
#[test]
fn each_can_rule_fires_once() {
    let f = Frame::data(0x123, &[0xDE, 0xAD]);
    let check = |l: &Line, rule: &str| {
        let mut m = can();
        l.play(&mut m);
        let got = rules(&mut m);
        assert_eq!(got, vec![rule], "{:?}", m.violations());
        m.violations()[0].time_ns
    };
    // Stuffing: SOF and six recessive identifier bits with no stuff bit.
    let mut l = Line::default();
    let raw = Frame::data(0x7E5, &[0x55]).destuffed_bits();
    l.idle(20).bits(&raw, &raw, CPB).idle(30);
    assert_eq!(
        check(&l, can_rules::STUFF.label()),
        ((20.0f64 + 6.75) * 2000.0).round()
    );
    // Form: the master's CRC delimiter dominant.
    let mut l = Line::default();
    let mut tx = f.wire_bits(false);
    let n = tx.len();
    tx[n - 10] = false;
    let mut rx = f.wire_bits(true);
    rx[n - 10] = false;
    l.idle(20).bits(&tx, &rx, CPB).idle(30);
    check(&l, can_rules::FORM.label());
    // Intermission: the next SOF after 2 bits of it.
    let mut l = Line::default();
    l.idle(20)
        .bits(&f.wire_bits(false), &f.wire_bits(true), CPB)
        .idle(2)
        .sent(&f)
        .idle(20);
    check(&l, can_rules::INTERMISSION.label());
    // Bit time: a frame 3 % fast.
    let mut l = Line::default();
    l.idle(20)
        .bits(&f.wire_bits(false), &f.wire_bits(true), CPB * 0.97)
        .idle(30);
    check(&l, can_rules::BIT_TIME.label());
    // Dominant length: an error flag of 8 bits after bus idle.
    let mut l = Line::default();
    l.idle(20).bits(&[false; 8], &[false; 8], CPB).idle(30);
    check(&l, can_rules::DOMINANT.label());
}

/// The master loses arbitration to another node: a receiver from then on, no violation.
#[test]
fn a_lost_arbitration_is_not_the_masters_frame() {
    let (mine, theirs) = (Frame::data(0x124, &[1]), Frame::data(0x123, &[2]));
    let (mut tx, rx) = (mine.wire_bits(false), theirs.wire_bits(true));
    // The master sends its identifier until the bit where 0x123 is dominant and 0x124 recessive, then listens (and acknowledges).
    let lost = (1..12).find(|&k| !rx[k] && tx[k]).unwrap();
    let ack = rx.len() - 9;
    for (k, b) in tx.iter_mut().enumerate() {
        if k >= lost {
            *b = k != ack;
        }
    }
    tx.truncate(rx.len());
    let mut m = can();
    let mut l = Line::default();
    l.idle(20).bits(&tx, &rx, CPB).idle(20);
    l.play(&mut m);
    assert!(rules(&mut m).is_empty(), "{:?}", m.violations());
    assert_eq!(
        (m.last_value(1), m.last_status(0, "master").unwrap()),
        (Some(0x123), false)
    );
}

fn canopen(extra: &str) -> CanopenMonitor {
    CanopenMonitor::from_toml(&format!("{CANOPEN}{extra}"), "co.toml", F).unwrap()
}

fn sdo(node: u32, index: u16, v: u32) -> Frame {
    Frame::data(
        0x600 + node,
        &model::canopen::sdo::download(index, 0, &v.to_le_bytes()[..2]),
    )
}

/// Each CANopen rule broken once; the clean sequence says nothing.
#[test]
fn each_canopen_rule_fires_once() {
    let confirm = |node: u32, index: u16| {
        Frame::data(
            0x580 + node,
            &[0x60, index as u8, (index >> 8) as u8, 0, 0, 0, 0, 0],
        )
    };
    let start = Frame::data(0, &[1, 5]);
    let guard = Frame {
        id: 0x705,
        ide: false,
        rtr: true,
        dlc: 1,
        data: vec![],
    };
    let sync = Frame::data(0x80, &[]);
    let run = |l: &Line, extra: &str| {
        let mut m = canopen(extra);
        l.play(&mut m);
        (rules(&mut m), m)
    };
    // Clean: boot-up, an SDO and its answer, a timed-out SDO resent after 1 ms, start, guarding every 10 ms, SYNC every 2 ms.
    let mut l = Line::default();
    l.idle(20)
        .heard(&Frame::data(0x85, &[]))
        .sent(&sdo(5, 0x100C, 10))
        .heard(&confirm(5, 0x100C))
        .sent(&sdo(5, 0x6200, 1))
        .idle(520)
        .sent(&sdo(5, 0x6200, 1))
        .heard(&confirm(5, 0x6200))
        .sent(&start);
    for _ in 0..3 {
        l.sent(&guard)
            .heard(&Frame::data(0x705, &[0x05]))
            .idle(4900);
    }
    l.idle(200);
    let (got, mut m) = run(&l, "");
    assert!(got.is_empty(), "{:?}", m.violations());
    let mut l = Line::default();
    for _ in 0..4 {
        l.sent(&sync).idle(940);
    }
    l.idle(20);
    let (got, _) = run(&l, "sync_period_us = 2000\n");
    assert!(got.is_empty(), "{got:?}");
    // SDO: the second request 100 us after the first, unanswered.
    let mut l = Line::default();
    l.idle(20)
        .sent(&sdo(5, 0x6200, 1))
        .idle(50)
        .sent(&sdo(5, 0x6200, 2))
        .idle(20);
    assert_eq!(run(&l, "").0, vec![co_rules::SDO.label()]);
    // NMT: start twice.
    let mut l = Line::default();
    l.idle(20).sent(&start).idle(50).sent(&start).idle(20);
    assert_eq!(run(&l, "").0, vec![co_rules::NMT.label()]);
    // Guarding: 10 ms guard time, the third request 16 ms after the second.
    let mut l = Line::default();
    l.idle(20)
        .sent(&sdo(5, 0x100C, 10))
        .heard(&confirm(5, 0x100C));
    for gap in [4900, 7900, 100] {
        l.sent(&guard).heard(&Frame::data(0x705, &[0x05])).idle(gap);
    }
    assert_eq!(run(&l, "").0, vec![co_rules::GUARD.label()]);
    // SYNC: every 2 ms, one after 3 ms.
    let mut l = Line::default();
    for gap in [940, 1440, 940] {
        l.sent(&sync).idle(gap);
    }
    l.sent(&sync).idle(20);
    assert_eq!(
        run(&l, "sync_period_us = 2000\n").0,
        vec![co_rules::SYNC.label()]
    );
    // SAR58K24: a click to node 0x20, and another before its answer.
    let click = Frame::data(0x220, &[0x80, 0x20, 0, 0, 0, 0, 0, 0]);
    let sar = "[[canopen.sar]]\n[canopen.sar.encoder]\nnode = 0x20\n";
    let mut l = Line::default();
    l.idle(20)
        .sent(&click)
        .heard(&Frame::data(0x120, &[0x47, 0x26, 0, 0, 0, 0, 0, 0]))
        .sent(&click)
        .idle(50)
        .sent(&click)
        .idle(20);
    assert_eq!(run(&l, sar).0, vec![co_rules::SAR.label()]);
}

/// The monitor beside the CAN emulator, a model node as the master: every frame both ways decoded as sent, no violation.
#[test]
fn beside_the_emulator_every_frame_is_read_as_sent() {
    use model::can::emulator::NodeSettings;
    let toml = "[can]\nf_sys_mhz = 8\ntiming = { bit_rate_kbps = 500, tq_per_bit = 16, sample_point = 0.75, sjw = 1 }\n[[can.nodes]]\nname = \"a\"\nposition_m = 20\nppm = 200\n";
    let mut emu = cosim::open("can", toml, "t.toml", F).unwrap();
    let mut mon = cosim::open("can_monitor", toml, "t.toml", F).unwrap();
    let tb = model::Timebase::new(F).unwrap();
    let bench: model::can::BenchConfig = toml::from_str::<toml::Table>(toml).unwrap()["can"]
        .clone()
        .try_into()
        .unwrap();
    let cc = bench.controller_config().unwrap();
    let s = NodeSettings {
        name: "master".into(),
        position_m: 0.0,
        loop_delay_ns: 150.0,
        ppm: 0.0,
        ack: true,
        frames: Vec::new(),
    };
    let mut host = model::can::Emulator::new(&s, cc, &tb).unwrap();
    let mut rx = true;
    let mut sent = Vec::new();
    for k in 0..20u32 {
        if k % 2 == 0 {
            let f = Frame::data(0x100 + k, &[k as u8, 0xA5, (k * 7) as u8]);
            assert!(host.load(&f));
            sent.push(f);
        } else {
            emu.schedule_fault(&format!(
                "[[send]]\nnode = 0\nid = {}\ndlc = 1\ndata = [{k}]\n",
                0x200 + k
            ))
            .unwrap();
            sent.push(Frame::data(0x200 + k, &[k as u8]));
        }
        for _ in 0..16 * 200 {
            let tx = host.step(rx);
            mon.step(Pins(rx as u32 | (tx as u32) << 1));
            rx = emu.step(Pins((tx as u32) << 1)).data();
        }
    }
    assert!(mon.violations().is_empty(), "{:?}", mon.violations());
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
    let t = mon.transcript();
    let got: Vec<Frame> = t["transactions"].as_array().unwrap().iter().map(|v| serde_json::from_value::<Frame>(serde_json::json!({"id": v["id"], "ide": v["ide"], "rtr": v["rtr"], "dlc": v["dlc"], "data": v["data"]})).unwrap()).collect();
    assert_eq!(got, sent);
    let senders: Vec<&str> = t["transactions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["sender"].as_str().unwrap())
        .collect();
    assert_eq!(senders.iter().filter(|&&s| s == "master").count(), 10);
}
