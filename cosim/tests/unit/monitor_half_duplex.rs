//! The T-format and ESL monitors against their emulators (clean closed
//! loops: the monitor decodes what the emulator sent and says nothing) and
//! against a crafted host that breaks each rule once (the rule fires, with
//! its time).

use cosim::{open, Emulator, Pins};

/// A crafted host: its driver input and enable, cycle by cycle.
struct Host {
    cpb: u64,
    cycles: Vec<(bool, bool)>,
}

impl Host {
    fn new(cpb: u64) -> Self {
        Host {
            cpb,
            cycles: Vec::new(),
        }
    }

    /// Driver off for `bits` bit times.
    fn idle(&mut self, bits: u64) -> &mut Self {
        self.cycles.extend(std::iter::repeat_n(
            (true, false),
            (bits * self.cpb) as usize,
        ));
        self
    }

    /// Driver on, line high, for `cycles` cycles.
    fn hold(&mut self, cycles: u64) -> &mut Self {
        self.cycles
            .extend(std::iter::repeat_n((true, true), cycles as usize));
        self
    }

    /// One 10-bit field of `value`, bit `k` (0 start .. 9 stop) lasting `len(k)` cycles, stop bit `stop`.
    fn field(&mut self, value: u8, stop: bool, len: impl Fn(usize) -> u64) -> &mut Self {
        for k in 0..10 {
            let level = match k {
                0 => false,
                9 => stop,
                _ => value >> (k - 1) & 1 == 1,
            };
            self.cycles
                .extend(std::iter::repeat_n((level, true), len(k) as usize));
        }
        self
    }

    /// A request: its fields back to back, then the driver off.
    fn request(&mut self, fields: &[u8]) -> &mut Self {
        let cpb = self.cpb;
        for &f in fields {
            self.field(f, true, |_| cpb);
        }
        self
    }

    fn take(&mut self) -> Vec<(bool, bool)> {
        std::mem::take(&mut self.cycles)
    }
}

/// The monitor beside an emulator (or alone, the receiver idle high).
struct Loop {
    emu: Option<Box<dyn Emulator>>,
    mon: Box<dyn Emulator>,
    rx: bool,
}

impl Loop {
    fn run(&mut self, cycles: &[(bool, bool)]) {
        for &(tx, de) in cycles {
            let pins = (tx as u32) << 1 | (de as u32) << 2;
            self.mon.step(Pins(pins | self.rx as u32));
            if let Some(e) = &mut self.emu {
                self.rx = e.step(Pins(pins)).data();
            }
        }
    }

    fn rules(&mut self) -> Vec<(f64, String)> {
        self.mon
            .violations()
            .iter()
            .map(|v| {
                (
                    v.time_ns,
                    v.rule.split(" (").next().unwrap_or("").to_string(),
                )
            })
            .collect()
    }

    fn details(&mut self) -> Vec<String> {
        self.mon
            .violations()
            .iter()
            .map(|v| format!("{}: {}", v.rule, v.detail))
            .collect()
    }
}

fn with_emulator(kind: &str, toml: &str, f: u64) -> Loop {
    Loop {
        emu: Some(open(kind, toml, "t.toml", f).unwrap()),
        mon: open(&format!("{kind}_monitor"), toml, "t.toml", f).unwrap(),
        rx: true,
    }
}

fn alone(kind: &str, toml: &str, f: u64) -> Loop {
    Loop {
        emu: None,
        mon: open(&format!("{kind}_monitor"), toml, "t.toml", f).unwrap(),
        rx: true,
    }
}

use model::tformat::frames::{self as tf, DataId as TfId};

const TF_TOML: &str = "baud = 2.5e6\n[cable]\nlength_m = 30\n";
/// 20 MHz: 8 cycles a bit at 2.5 Mbps.
const TF_HZ: u64 = 20_000_000;

/// Readouts of Data ID 0, 1, 2, 3 with random positions and alarms against
/// the emulator through 30 m: the monitor decodes each one as the emulator
/// sent it, with no error and no violation.
#[test]
fn tformat_monitor_reads_what_the_emulator_sent_and_is_silent_on_a_clean_host() {
    let mut l = with_emulator("tformat", TF_TOML, TF_HZ);
    let mut h = Host::new(8);
    let ids = [
        TfId::Id3,
        TfId::Id0,
        TfId::Id1,
        TfId::Id3,
        TfId::Id2,
        TfId::Id3,
    ];
    l.run(h.idle(20).take().as_slice());
    let mut set = Vec::new();
    for (k, id) in ids.iter().enumerate() {
        let (st, mt) = (
            (k as u64 * 40_503) % (1 << 17),
            (k as u64 * 7919) % (1 << 16),
        );
        let e = l.emu.as_mut().unwrap();
        e.set_position(0, mt << 17 | st).unwrap();
        e.set_status(0, "battery_alarm", k % 2 == 1).unwrap();
        e.set_status(0, "over_speed", k % 3 == 0).unwrap();
        set.push((st, mt));
        l.run(
            h.request(&tf::request(*id, 0, 0))
                .idle(200)
                .take()
                .as_slice(),
        );
    }
    let t = l.mon.transcript();
    let list = t["transactions"].as_array().unwrap();
    assert_eq!(list.len(), ids.len(), "{t}");
    let sent = l.emu.as_ref().unwrap().transcript();
    let answers = sent["answers"].as_array().unwrap();
    for (k, (tr, id)) in list.iter().zip(ids).enumerate() {
        assert_eq!(tr["data_id"].as_u64(), Some(id.code() as u64), "{tr}");
        assert_eq!(tr["errors"].as_array().unwrap().len(), 0, "{tr}");
        assert_eq!(tr["received"], answers[k]["fields"], "{tr}");
        if matches!(id, TfId::Id0 | TfId::Id3) {
            assert_eq!(tr["abs"].as_u64(), Some(set[k].0), "{tr}");
        }
        if matches!(id, TfId::Id1 | TfId::Id3) {
            assert_eq!(tr["abm"].as_u64(), Some(set[k].1), "{tr}");
        }
    }
    assert_eq!(l.mon.count(), ids.len() as u64);
    assert_eq!(l.mon.last_value(0), Some(set[5].1 << 17 | set[5].0));
    assert!(
        l.mon.last_status(0, "battery_alarm").unwrap()
            && !l.mon.last_status(0, "over_speed").unwrap()
    );
    assert!(!l.mon.last_status(0, "crc").unwrap());
    assert!(l.mon.violations().is_empty(), "{:?}", l.details());
}

/// Each T-format rule broken once by a crafted host, at 20 MHz (50 ns a cycle).
#[test]
fn each_tformat_rule_fires_with_its_time_and_the_seed_reference() {
    let cf0 = TfId::Id0.control_field();
    let read_d = tf::request(TfId::IdD, 5, 0);
    // A clean Data ID D request (3 fields) alone: silent.
    let mut l = alone("tformat", TF_TOML, TF_HZ);
    let mut h = Host::new(8);
    l.run(
        h.idle(10)
            .request(&read_d)
            .idle(200)
            .request(&[cf0])
            .idle(50)
            .take()
            .as_slice(),
    );
    assert!(l.mon.violations().is_empty(), "{:?}", l.details());
    assert_eq!(l.mon.count(), 2);
    // Bit 1 of the control field 12 cycles (600 ns) long: the next edge is off the grid by 4 cycles (200 ns; 100 ns of jitter allowed).
    let mut l = alone("tformat", TF_TOML, TF_HZ);
    let t0 = 80u64;
    l.run(
        h.idle(10)
            .field(0x02, true, |k| if k == 1 { 12 } else { 8 })
            .idle(50)
            .take()
            .as_slice(),
    );
    // CF 0x02: bits 0 1 0 0 0 0 0 0 -> start(0) b0=0 b1=1: the first edge after the start is the rise at bit 2, now at 20 cycles.
    assert_eq!(
        l.rules(),
        vec![((t0 + 20) as f64 * 50.0, "jitter".to_string())],
        "{:?}",
        l.details()
    );
    assert!(
        l.details()[0].contains("seed 002 TS5669 N127, 6.1")
            && l.details()[0].contains("<= 100 ns"),
        "{:?}",
        l.details()
    );
    // A stop bit (delimiter) low: framing.
    let mut l = alone("tformat", TF_TOML, TF_HZ);
    l.run(
        h.idle(10)
            .field(cf0, false, |_| 8)
            .hold(8)
            .idle(50)
            .take()
            .as_slice(),
    );
    assert_eq!(
        l.rules().iter().map(|r| r.1.as_str()).collect::<Vec<_>>(),
        vec!["jitter"],
        "{:?}",
        l.details()
    );
    assert!(l.details()[0].contains("stop bit low"), "{:?}", l.details());
    // A gap of 2 bits between the fields of a Data ID D request.
    let mut l = alone("tformat", TF_TOML, TF_HZ);
    l.run(
        h.idle(10)
            .request(&read_d[..1])
            .hold(16)
            .request(&read_d[1..])
            .idle(200)
            .take()
            .as_slice(),
    );
    assert_eq!(
        l.rules(),
        vec![((80 + 80 + 16) as f64 * 50.0, "end of frame".to_string())],
        "{:?}",
        l.details()
    );
    assert!(
        l.details()[0].contains("7.2") && l.details()[0].contains("2.00 bits"),
        "{:?}",
        l.details()
    );
    // A Data ID D request of two fields (CRC missing).
    let mut l = alone("tformat", TF_TOML, TF_HZ);
    l.run(h.idle(10).request(&read_d[..2]).idle(200).take().as_slice());
    assert_eq!(l.rules().len(), 1, "{:?}", l.details());
    assert!(
        l.details()[0].contains("6.2")
            && l.details()[0].contains("2 field(s) for Data ID D, which takes 3"),
        "{:?}",
        l.details()
    );
    // DE held 2 us (40 cycles) after the delimiter: release (1.5 us).
    let mut l = alone("tformat", TF_TOML, TF_HZ);
    l.run(
        h.idle(10)
            .request(&[cf0])
            .hold(40)
            .idle(200)
            .take()
            .as_slice(),
    );
    assert_eq!(
        l.rules().iter().map(|r| r.1.as_str()).collect::<Vec<_>>(),
        vec!["release"],
        "{:?}",
        l.details()
    );
    assert!(
        l.details()[0].contains("7.1") && l.details()[0].contains("at most 1.500 us"),
        "{:?}",
        l.details()
    );
    // The next request 30 bits after a Data ID 3 request: inside the encoder's answer (11 fields).
    let mut l = with_emulator("tformat", TF_TOML, TF_HZ);
    l.run(
        h.idle(10)
            .request(&[TfId::Id3.control_field()])
            .idle(30)
            .request(&[cf0])
            .idle(300)
            .take()
            .as_slice(),
    );
    let r = l.rules();
    assert!(
        !r.is_empty() && r.iter().all(|x| x.1 == "no request during the answer"),
        "{:?}",
        l.details()
    );
    assert!(
        l.details()
            .iter()
            .any(|d| d.contains("N127, 10:") && d.contains("inside its answer")),
        "{:?}",
        l.details()
    );
    // Resets: Data ID 7 ten times 100 us apart against an interval of 1 ms; then three and a readout.
    let toml = format!("{TF_TOML}[monitor]\nreset_interval_us = 1000\n");
    let mut l = alone("tformat", &toml, TF_HZ);
    l.run(h.idle(10).take().as_slice());
    for _ in 0..10 {
        l.run(
            h.request(&[TfId::Id7.control_field()])
                .idle(240)
                .take()
                .as_slice(),
        );
    }
    assert_eq!(l.rules().len(), 9, "{:?}", l.details());
    assert!(
        l.details()[0].contains("N127, 9:")
            && l.details()[0].contains("request 2 of reset Data ID 7 0.100000 ms after"),
        "{:?}",
        l.details()
    );
    assert_eq!(l.mon.count(), 1, "ten reset requests are one transaction");
    let mut l = alone("tformat", &toml, TF_HZ);
    l.run(h.idle(10).take().as_slice());
    for _ in 0..3 {
        l.run(
            h.request(&[TfId::Id7.control_field()])
                .idle(3000)
                .take()
                .as_slice(),
        );
    }
    l.run(h.request(&[cf0]).idle(100).take().as_slice());
    assert_eq!(l.rules().len(), 1, "{:?}", l.details());
    assert!(
        l.details()[0].contains("sent 3 time(s), then Data ID 0"),
        "{:?}",
        l.details()
    );
}

use model::esl::frames as ef;

const ESL_TOML: &str = "baud = 10e6\n[[encoders]]\naddress = 3\n[cable]\nlength_m = 20\n";
/// 80 MHz: 8 cycles a bit at 10 Mbps.
const ESL_HZ: u64 = 80_000_000;

/// Readouts of Data ID 1, 2, 4, 5, 6, 8, 9, A with positions and alarms
/// against the emulator through 20 m: the monitor decodes each one as the
/// emulator sent it (the safety answers' sequence counters included), with
/// no error and no violation.
#[test]
fn esl_monitor_reads_what_the_emulator_sent_and_is_silent_on_a_clean_host() {
    let mut l = with_emulator("esl", ESL_TOML, ESL_HZ);
    let mut h = Host::new(8);
    let ids = [1u8, 2, 4, 5, 6, 8, 9, 0xA, 1, 2];
    l.run(h.idle(20).take().as_slice());
    let mut set = Vec::new();
    for (k, &id) in ids.iter().enumerate() {
        let p = (k as u64 * 0x1_2345_6789) & ((1 << 40) - 1);
        let e = l.emu.as_mut().unwrap();
        e.set_position(0, p).unwrap();
        e.set_status(0, "uv", k % 2 == 0).unwrap();
        set.push(p);
        l.run(
            h.request(&ef::request(3, id, 0, 0))
                .idle(300)
                .take()
                .as_slice(),
        );
    }
    let t = l.mon.transcript();
    let list = t["transactions"].as_array().unwrap();
    assert_eq!(list.len(), ids.len(), "{t}");
    let sent = l.emu.as_ref().unwrap().transcript();
    let answers = sent["answers"].as_array().unwrap();
    for (k, (tr, &id)) in list.iter().zip(&ids).enumerate() {
        assert_eq!(
            (tr["data_id"].as_u64(), tr["address"].as_u64()),
            (Some(id as u64), Some(3)),
            "{tr}"
        );
        assert_eq!(tr["errors"].as_array().unwrap().len(), 0, "{tr}");
        assert_eq!(tr["received"], answers[k]["fields"], "{tr}");
        if let Some(abs) = answers[k]["abs"].as_u64() {
            assert_eq!(
                (tr["abs"].as_u64(), abs),
                (Some(set[k] & 0xFF_FFFF), set[k] & 0xFF_FFFF),
                "{tr}"
            );
        }
    }
    assert_eq!(l.mon.count(), ids.len() as u64);
    assert!(!l.mon.last_status(0, "uv").unwrap() && !l.mon.last_status(0, "crc1").unwrap());
    assert!(l.mon.violations().is_empty(), "{:?}", l.details());
}

/// Each ESL rule broken once by a crafted host, at 80 MHz (12.5 ns a cycle).
#[test]
fn each_esl_rule_fires_with_its_time_and_the_seed_reference() {
    let rd1 = ef::request(3, 1, 0, 0);
    let mut h = Host::new(8);
    let names = |l: &mut Loop| l.rules().into_iter().map(|r| r.1).collect::<Vec<_>>();
    // Clean: a readout and a register read (E, page 8) right after: silent.
    let mut l = alone("esl", ESL_TOML, ESL_HZ);
    l.run(
        h.idle(10)
            .request(&rd1)
            .idle(100)
            .request(&ef::request(3, 0xE, 0x10, 0))
            .idle(100)
            .take()
            .as_slice(),
    );
    assert!(l.mon.violations().is_empty(), "{:?}", l.details());
    // Bit 1 of the control field 12 cycles: off the grid by 4 cycles (3 % of the time since the start edge allowed).
    let mut l = alone("esl", ESL_TOML, ESL_HZ);
    l.run(
        h.idle(10)
            .field(rd1[0], true, |k| if k == 1 { 12 } else { 8 })
            .request(&rd1[1..])
            .idle(100)
            .take()
            .as_slice(),
    );
    assert_eq!(names(&mut l)[0], "bit rate", "{:?}", l.details());
    assert!(
        l.details()[0].contains("seed 000 QS35 ESL, Table 1 and Figure 1")
            && l.details()[0].contains("off the bit grid"),
        "{:?}",
        l.details()
    );
    // A stop bit 4 cycles long: the next start bit already at the stop bit's middle.
    let mut l = alone("esl", ESL_TOML, ESL_HZ);
    l.run(
        h.idle(10)
            .field(rd1[0], true, |k| if k == 9 { 4 } else { 8 })
            .request(&rd1[1..])
            .idle(100)
            .take()
            .as_slice(),
    );
    assert_eq!(names(&mut l), vec!["bit rate"], "{:?}", l.details());
    assert!(l.details()[0].contains("stop bit low"), "{:?}", l.details());
    // A 1.5-bit pause inside the request.
    let mut l = alone("esl", ESL_TOML, ESL_HZ);
    l.run(
        h.idle(10)
            .request(&rd1[..1])
            .hold(12)
            .request(&rd1[1..])
            .idle(100)
            .take()
            .as_slice(),
    );
    assert_eq!(
        l.rules(),
        vec![((80 + 80 + 12) as f64 * 12.5, "end of frame set".to_string())],
        "{:?}",
        l.details()
    );
    // A readout without its CRC frame.
    let mut l = alone("esl", ESL_TOML, ESL_HZ);
    l.run(h.idle(10).request(&rd1[..1]).idle(100).take().as_slice());
    assert_eq!(names(&mut l), vec!["request frames"], "{:?}", l.details());
    assert!(
        l.details()[0].contains("Figures 1, 3 and 5")
            && l.details()[0].contains("1 frame(s) for Data ID 1, which takes 2"),
        "{:?}",
        l.details()
    );
    // DE held 2 us after the last stop bit (1 us allowed).
    let mut l = alone("esl", ESL_TOML, ESL_HZ);
    l.run(
        h.idle(10)
            .request(&rd1)
            .hold(160)
            .idle(100)
            .take()
            .as_slice(),
    );
    assert_eq!(names(&mut l), vec!["release"], "{:?}", l.details());
    // The next request 25 bits after a Data ID 1 request: inside the answer (18 frames).
    let mut l = with_emulator("esl", ESL_TOML, ESL_HZ);
    l.run(
        h.idle(10)
            .request(&rd1)
            .idle(45)
            .request(&rd1)
            .idle(400)
            .take()
            .as_slice(),
    );
    assert!(
        l.details()
            .iter()
            .any(|d| d.contains("half duplex (seed 000") && d.contains("inside its answer")),
        "{:?}",
        l.details()
    );
    // B 8 times, the 4th 300 us after the 3rd (repeat window 200 us): one violation, the count starts again.
    let clear_b = ef::request(3, 0xB, 0, 0);
    let mut l = alone("esl", ESL_TOML, ESL_HZ);
    l.run(h.idle(10).take().as_slice());
    for k in 0..8 {
        l.run(
            h.request(&clear_b)
                .idle(if k == 2 { 3000 } else { 400 })
                .take()
                .as_slice(),
        );
    }
    assert_eq!(names(&mut l), vec!["repeat"], "{:?}", l.details());
    assert!(
        l.details()[0].contains("Table 4") && l.details()[0].contains("request 4 of Data ID B"),
        "{:?}",
        l.details()
    );
    // C three times, then a readout: the command was not executed.
    let mut l = alone("esl", ESL_TOML, ESL_HZ);
    l.run(h.idle(10).take().as_slice());
    for _ in 0..3 {
        l.run(
            h.request(&ef::request(3, 0xC, 0, 0))
                .idle(400)
                .take()
                .as_slice(),
        );
    }
    l.run(h.request(&rd1).idle(400).take().as_slice());
    assert_eq!(names(&mut l), vec!["repeat"], "{:?}", l.details());
    assert!(
        l.details()[0].contains("Data ID C sent 3 time(s)"),
        "{:?}",
        l.details()
    );
    // EEPROM: page 0 (a page-register write), then an access 50 us later (page change 100 us
    // here), two reads 100 us apart (200 us), two writes 1 ms apart (6 ms).
    let toml = format!("{ESL_TOML}[monitor]\npage_change_us = 100\n");
    let mut l = alone("esl", &toml, ESL_HZ);
    l.run(
        h.idle(10)
            .request(&ef::request(3, 0xF, ef::PAGE_REGISTER, 0))
            .idle(500)
            .take()
            .as_slice(),
    );
    l.run(
        h.request(&ef::request(3, 0xE, 0x10, 0))
            .idle(1000)
            .take()
            .as_slice(),
    );
    l.run(
        h.request(&ef::request(3, 0xE, 0x10, 0))
            .idle(10_000)
            .take()
            .as_slice(),
    );
    l.run(
        h.request(&ef::request(3, 0xF, 0x10, 0x55))
            .idle(10_000)
            .take()
            .as_slice(),
    );
    l.run(
        h.request(&ef::request(3, 0xF, 0x11, 0x55))
            .idle(100)
            .take()
            .as_slice(),
    );
    let d = l.details();
    assert_eq!(d.len(), 3, "{d:?}");
    assert!(
        d[0].contains("18 ms") && d[0].contains("after a write to the page register"),
        "{d:?}"
    );
    assert!(
        d[1].contains("EEPROM reads > 200 us") && d[1].contains("EEPROM read 10"),
        "{d:?}"
    );
    assert!(
        d[2].contains("EEPROM writes > 6 ms") && d[2].contains("EEPROM write 10"),
        "{d:?}"
    );
}

#[test]
fn a_half_duplex_monitor_refuses_controls_and_a_bad_table_names_file_and_field() {
    let mut mon = open("esl_monitor", "", "m.toml", 80_000_000).unwrap();
    assert!(mon
        .set_position(0, 1)
        .unwrap_err()
        .to_string()
        .contains("esl_monitor is a monitor"));
    let e = open(
        "tformat_monitor",
        "[monitor]\njitter = 3\n",
        "m.toml",
        20_000_000,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.contains("m.toml") && e.contains("jitter"), "{e}");
    let e = open("tformat_monitor", "", "m.toml", 5_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("too slow") && e.contains("10000000"), "{e}");
    let e = open(
        "esl_monitor",
        "[monitor]\nbit_tolerance_percent = 40\n",
        "e.toml",
        80_000_000,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(
        e.contains("e.toml")
            && e.contains("monitor.bit_tolerance_percent")
            && e.contains("0 to 20"),
        "{e}"
    );
    // The emulators read the same file with a [monitor] table.
    assert!(open(
        "tformat",
        "[monitor]\nrelease_us = 2\n",
        "t.toml",
        20_000_000
    )
    .is_ok());
    assert!(open("esl", "[monitor]\nrelease_us = 2\n", "t.toml", 80_000_000).is_ok());
}

/// A rule bound a configuration sets outside the seed's range is refused
/// with that range (T-format jitter and release, ESL release); one inside
/// it is taken; a clock too coarse for the jitter says so once.
#[test]
fn a_half_duplex_bound_outside_the_seeds_range_is_refused_with_the_range() {
    for (kind, toml, field, seed) in [
        (
            "tformat_monitor",
            "[monitor]\njitter_ns = 101\n",
            "monitor.jitter_ns",
            "seed 002",
        ),
        (
            "tformat_monitor",
            "[monitor]\nrelease_us = 3.5\n",
            "monitor.release_us",
            "seed 002",
        ),
        (
            "esl_monitor",
            "[monitor]\nrelease_us = 2.5\n",
            "monitor.release_us",
            "seed 000",
        ),
    ] {
        let e = open(kind, toml, "r.toml", 80_000_000)
            .err()
            .unwrap_or_else(|| panic!("{kind} took {toml}"))
            .to_string();
        assert!(
            e.contains("r.toml")
                && e.contains(field)
                && e.contains("outside the seed's range")
                && e.contains(seed),
            "{kind}: {e}"
        );
    }
    assert!(open(
        "tformat_monitor",
        "[monitor]\njitter_ns = 50\nrelease_us = 3\n",
        "r.toml",
        80_000_000
    )
    .is_ok());
    // 10 MHz samples every 100 ns: the jitter of 100 ns needs 20 MHz.
    for kind in ["tformat", "tformat_monitor"] {
        let notes = open(kind, "", "r.toml", 10_000_000).unwrap().transcript()["notes"].clone();
        let notes = notes.as_array().unwrap();
        assert!(
            notes.len() == 1
                && notes[0].as_str().unwrap().starts_with("jitter (")
                && notes[0]
                    .as_str()
                    .unwrap()
                    .contains("needs at least 20000000 Hz"),
            "{kind}: {notes:?}"
        );
        let quiet = open(kind, "", "r.toml", 20_000_000).unwrap().transcript()["notes"].clone();
        assert_eq!(quiet.as_array().map(Vec::len), Some(0), "{kind}: {quiet}");
    }
}
