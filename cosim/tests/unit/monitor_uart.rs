//! The SAR58K24 and Modbus monitors beside their emulators, with a host
//! written here: a clean host is read exactly and breaks no rule; a crafted
//! host breaks each rule once and the monitor names it, with its time.

use model::uart::Parity;

use cosim::{open, Emulator, Pins};

/// A host on the emulator clock, the emulator and the monitor beside it.
struct Rig {
    emu: Box<dyn Emulator>,
    mon: Box<dyn Emulator>,
    cpb: u64,
    parity: Parity,
    rx: bool,
    trigger: bool,
    cycle: u64,
}

impl Rig {
    fn new(kind: &str, toml: &str, f: u64, cpb: u64, parity: Parity) -> Rig {
        let emu = open(kind, toml, "test.toml", f).unwrap();
        let mon = open(&format!("{kind}_monitor"), toml, "test.toml", f).unwrap();
        Rig {
            emu,
            mon,
            cpb,
            parity,
            rx: true,
            trigger: true,
            cycle: 0,
        }
    }

    fn step(&mut self, tx: bool, de: bool) {
        let out = self.emu.step(Pins(
            self.trigger as u32 | (tx as u32) << 1 | (de as u32) << 2 | 8,
        ));
        self.rx = out.0 & 4 != 0;
        self.mon.step(Pins(
            self.rx as u32 | (tx as u32) << 1 | (de as u32) << 2 | (self.trigger as u32) << 3 | 16,
        ));
        self.cycle += 1;
    }

    fn idle(&mut self, n: u64, de: bool) {
        for _ in 0..n {
            self.step(true, de);
        }
    }

    /// One character, each bit `cpb` cycles (`stretch` more on every bit: a baud error).
    fn char(&mut self, byte: u8, stretch: u64, bad_parity: bool) {
        let mut levels = self.parity.levels(byte);
        if bad_parity && self.parity != Parity::None {
            let k = levels.len() - 2;
            levels[k] = !levels[k];
        }
        for l in levels {
            for _ in 0..self.cpb + stretch {
                self.step(l, true);
            }
        }
    }

    /// A request: DE on a bit before, the characters with `gap` idle cycles between, DE off `hold` cycles after.
    fn send(&mut self, bytes: &[u8], gap: u64, hold: u64) {
        self.idle(self.cpb, true);
        for (k, &b) in bytes.iter().enumerate() {
            if k > 0 {
                self.idle(gap, true);
            }
            self.char(b, 0, false);
        }
        self.idle(hold, true);
        self.step(true, false);
    }

    /// Steps until the line at the host has been idle `n` cycles.
    fn quiet(&mut self, n: u64) {
        let mut idle = 0;
        while idle < n {
            self.step(true, false);
            idle = if self.rx { idle + 1 } else { 0 };
        }
    }

    fn violations(&mut self) -> Vec<String> {
        self.mon
            .violations()
            .iter()
            .map(|v| format!("{} at {} ns: {}", v.rule, v.time_ns, v.detail))
            .collect()
    }
}

const MODBUS: &str = "[modbus]\nbaud = 15625.0\nparity = \"even\"\n[modbus.master]\ntimeout_us = 20000.0\n[[modbus.devices]]\naddress = 1\nbits = 32\n[modbus.random]\ncount = 100\nseed = 3\n[modbus.cable]\nlength_m = 30\n";
const READ2: [u8; 8] = [0x01, 0x03, 0x00, 0x00, 0x00, 0x02, 0xC4, 0x0B];

fn modbus() -> Rig {
    let mut r = Rig::new("modbus", MODBUS, 250_000, 16, Parity::Even);
    r.idle(100, false);
    r
}

/// t3.5 at 15625 baud with parity: 3.5 × 11 bits × 16 cycles from the
/// stop bit's middle (up to 9.5 bits after the last edge), and a margin.
const T35: u64 = 616 + 160;

#[test]
fn the_modbus_monitor_reads_every_answer_of_a_clean_master_and_reports_nothing() {
    let mut r = modbus();
    for n in 0..12 {
        r.send(&READ2, 0, 0);
        r.quiet(T35);
        let sent = r.emu.last_value(0).unwrap();
        assert_eq!(r.mon.count(), n + 1);
        assert_eq!(r.mon.last_value(0), Some(sent), "poll {n}");
        assert!(r.mon.last_status(0, "valid").unwrap());
    }
    assert_eq!(r.violations(), Vec::<String>::new());
    let t = r.mon.transcript();
    assert_eq!(t["protocol"], "modbus");
    let list = t["transactions"].as_array().unwrap();
    assert_eq!(list.len(), 12);
    assert_eq!(list[3]["index"], 3);
    assert_eq!(list[3]["request"], serde_json::json!(READ2));
}

#[test]
fn each_modbus_rule_fires_once_with_its_time() {
    // t1.5: 1.5 × 176 cycles of 4 µs; a gap of 300 cycles after the stop bit.
    let mut r2 = modbus();
    r2.idle(r2.cpb, true);
    for (k, &b) in READ2.iter().enumerate() {
        if k == 4 {
            r2.idle(300, true);
        }
        r2.char(b, 0, false);
    }
    r2.step(true, false);
    r2.quiet(T35);
    let v = r2.violations();
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(v[0].starts_with(model::modbus::rules::T15.label()), "{v:?}");
    // t3.5: the next request 200 cycles after the answer.
    let mut r = modbus();
    r.send(&READ2, 0, 0);
    while r.rx {
        r.step(true, false);
    }
    r.quiet(200);
    r.send(&READ2, 0, 0);
    r.quiet(T35);
    let v = r.violations();
    assert_eq!(v.len(), 1, "{v:?}");
    assert!(v[0].starts_with(model::modbus::rules::T35.label()), "{v:?}");
    // DE held 3 bits after the request.
    let mut r = modbus();
    r.send(&READ2, 0, 48);
    r.quiet(T35);
    let v = r.violations();
    assert!(
        v.len() == 1 && v[0].starts_with(model::modbus::rules::RELEASE.label()),
        "{v:?}"
    );
    // A parity bit wrong, and a character 5 % slow.
    for (stretch, bad) in [(0, true), (1, false)] {
        let mut r = modbus();
        r.idle(r.cpb, true);
        r.char(0x01, 0, false);
        r.char(0x03, stretch, bad);
        r.char(0x00, 0, false);
        r.step(true, false);
        r.quiet(T35);
        let v = r.violations();
        assert!(
            v.len() == 1 && v[0].starts_with(model::modbus::rules::CHARACTER.label()),
            "{v:?}"
        );
    }
    // No answer (station 9 is absent): the next request 10 ms later, inside the 20 ms timeout.
    let mut r = modbus();
    let mut other = READ2;
    other[0] = 9;
    let crc = model::modbus::frames::crc_bytes(&other[..6]);
    other[6..].copy_from_slice(&crc);
    r.send(&other, 0, 0);
    r.idle(2500, false);
    r.send(&READ2, 0, 0);
    r.quiet(T35);
    let v = r.violations();
    assert!(
        v.len() == 1 && v[0].starts_with(model::modbus::rules::TIMEOUT.label()),
        "{v:?}"
    );
}

/// t3.5 before a request counts from the end of the last stop bit on the
/// line, not from its middle: a broadcast (no answer, no timeout to wait
/// for), then the read `silence` cycles after the broadcast's last stop bit
/// ended. t3.5 is 616 cycles (3.5 × 11 bits × 16), held exactly: 616
/// passes and 615 does not. Counted from the stop bit's middle, 615 cycles
/// would pass as 623.
#[test]
fn the_modbus_t35_rule_counts_from_the_end_of_the_stop_bit() {
    let mut broadcast = READ2;
    broadcast[0] = 0;
    let crc = model::modbus::frames::crc_bytes(&broadcast[..6]);
    broadcast[6..].copy_from_slice(&crc);
    for (silence, violations) in [(617, 0), (616, 0), (615, 1)] {
        let mut r = modbus();
        r.send(&broadcast, 0, 0);
        // `send` ends with one cycle DE off; the next `send` drives DE a bit before its start bit.
        r.idle(silence - 1 - r.cpb, false);
        r.send(&READ2, 0, 0);
        r.quiet(T35);
        let v = r.violations();
        assert_eq!(v.len(), violations, "{silence} cycles: {v:?}");
        assert!(
            v.iter()
                .all(|v| v.starts_with(model::modbus::rules::T35.label())),
            "{v:?}"
        );
    }
}

const SAR_BUS: &str = "[sar]\nbaud = 15625.0\nmode = \"bus\"\n[sar.host]\ntimeout_us = 20000.0\n[[sar.encoders]]\naddress = 1\nbits = 32\nanswer_delay_us = 100.0\n[sar.random]\ncount = 100\nseed = 5\n[sar.cable]\nlength_m = 10\n";
const SAR_HS: &str = "[sar]\nbaud = 31250.0\nparity = \"odd\"\nmode = \"handshake\"\n[sar.host]\ntimeout_us = 10000.0\n[[sar.encoders]]\nbits = 24\ncode = \"gray\"\n[sar.random]\ncount = 100\nseed = 6\n";

/// A clean bus host sends `BC AA B1` `reads` times to the emulator of
/// `toml`: the monitor reads each answer as the emulator sent it and reports nothing.
fn sar_bus_reads(toml: &str, reads: u64) -> Rig {
    let mut r = Rig::new("sar58k24", toml, 250_000, 16, Parity::None);
    r.idle(100, false);
    for n in 0..reads {
        r.send(&[0xBC, 0xAA, 0xB1], 0, 0);
        r.quiet(400);
        assert_eq!(r.mon.count(), n + 1);
        assert_eq!(r.mon.last_value(0), r.emu.last_value(0), "read {n}");
        assert!(r.mon.last_status(0, "frame_ok").unwrap(), "read {n}");
    }
    assert_eq!(r.violations(), Vec::<String>::new());
    r
}

#[test]
fn the_sar_monitor_reads_every_frame_of_a_clean_host_and_reports_nothing() {
    let r = sar_bus_reads(SAR_BUS, 10);
    let t = r.mon.transcript();
    let list = t["transactions"].as_array().unwrap();
    assert_eq!(list.len(), 20, "ten commands and ten frames");
    assert_eq!(list[2]["command"], "read");
    // Handshake: triggers of 10 µs (5 cycles at 500 kHz).
    let mut r = Rig::new("sar58k24", SAR_HS, 500_000, 16, Parity::Odd);
    r.idle(100, false);
    for n in 0..10 {
        r.trigger = false;
        r.idle(5, false);
        r.trigger = true;
        r.idle(20, false);
        r.quiet(400);
        assert_eq!(r.mon.count(), n + 1);
        assert_eq!(r.mon.last_value(0), r.emu.last_value(0), "read {n}");
    }
    assert_eq!(r.violations(), Vec::<String>::new());
}

/// Bus answers tagged `81` (`answer_tag = "fixed81"`, the manual's tables;
/// a host with `TAG_ADDRESS = 0`): the monitor reads them as the host does.
#[test]
fn the_sar_monitor_reads_bus_answers_tagged_81_when_the_encoders_send_them() {
    let toml = SAR_BUS.replace("address = 1\n", "address = 1\nanswer_tag = \"fixed81\"\n");
    assert!(toml.contains("fixed81"));
    let r = sar_bus_reads(&toml, 5);
    let t = r.mon.transcript();
    let frame = &t["transactions"].as_array().unwrap()[1];
    assert_eq!(
        (frame["kind"].as_str(), frame["bytes"][1].as_u64()),
        (Some("frame"), Some(0x81)),
        "{frame}"
    );
}

#[test]
fn each_sar_rule_fires_once_with_its_time() {
    // A gap of 20 bits inside the command.
    let mut r = Rig::new("sar58k24", SAR_BUS, 250_000, 16, Parity::None);
    r.idle(100, false);
    r.idle(16, true);
    r.char(0xBC, 0, false);
    r.idle(320, true);
    r.char(0xAA, 0, false);
    r.char(0xB1, 0, false);
    r.step(true, false);
    r.quiet(400);
    let v = r.violations();
    assert!(
        v.len() == 1 && v[0].starts_with(model::sar58k24::rules::GAP.label()),
        "{v:?}"
    );
    // A second command 2 ms after the first, before the answer (100 µs delay, 5.6 ms frame) ends: inside the answer.
    let mut r = Rig::new("sar58k24", SAR_BUS, 250_000, 16, Parity::None);
    r.idle(100, false);
    r.send(&[0xBC, 0xAA, 0xB1], 0, 0);
    r.idle(500, false);
    r.send(&[0xBC, 0xAA, 0xB1], 0, 0);
    r.quiet(400);
    let v = r.violations();
    assert!(
        !v.is_empty()
            && v.iter()
                .all(|x| x.starts_with(model::sar58k24::rules::ANSWER.label())),
        "{v:?}"
    );
    // No answer from encoder 2: the next command 4 ms later, inside the 20 ms timeout.
    let mut r = Rig::new("sar58k24", SAR_BUS, 250_000, 16, Parity::None);
    r.idle(100, false);
    r.send(&[0xBC, 0xAA, 0xB2], 0, 0);
    r.idle(1000, false);
    let at = r.cycle;
    r.send(&[0xBC, 0xAA, 0xB1], 0, 0);
    r.quiet(400);
    let v = r.violations();
    assert!(
        v.len() == 1 && v[0].starts_with(model::sar58k24::rules::WAIT.label()),
        "{v:?}"
    );
    let time = r.mon.violations()[0].time_ns;
    assert!((time - ((at + 16) * 4000) as f64).abs() <= 4000.0, "{time}");
    // A trigger of 6 µs (3 cycles at 500 kHz).
    let mut r = Rig::new("sar58k24", SAR_HS, 500_000, 16, Parity::Odd);
    r.idle(100, false);
    r.trigger = false;
    r.idle(3, false);
    r.trigger = true;
    r.quiet(400);
    let v = r.violations();
    assert!(
        v.len() == 1 && v[0].starts_with(model::sar58k24::rules::T2.label()),
        "{v:?}"
    );
}

/// A limit of the SAR58K24 or Modbus rule book that a configuration sets
/// outside its rule's range is refused with that range, by the emulator
/// and the monitor alike (the two read one set of limits).
#[test]
fn a_sar_or_modbus_bound_outside_the_rules_range_is_refused_with_the_range() {
    // (kind, configuration, the field named, the range given)
    let cases = [
        (
            "sar58k24",
            "[checks]\nbaud_tolerance_percent = 3\n",
            "checks.baud_tolerance_percent",
            "give 0 to 2 %",
        ),
        (
            "sar58k24_monitor",
            "[monitor]\nt2_us = 9.5\n",
            "monitor.t2_us",
            "give 10 to 1000000 us",
        ),
        (
            "sar58k24",
            "[[encoders]]\ntrigger_min_low_us = 5\n",
            "encoders[0].trigger_min_low_us",
            "give 10 to 1000000 us",
        ),
        (
            "sar58k24_monitor",
            "[monitor]\nrelease_bits = 1.5\n",
            "monitor.release_bits",
            "give 0 to 1 bits",
        ),
        (
            "modbus",
            "[checks]\nbaud_tolerance_percent = 2.5\n",
            "checks.baud_tolerance_percent",
            "give 0 to 2 %",
        ),
        (
            "modbus_monitor",
            "[monitor]\nrelease_bits = 2\n",
            "monitor.release_bits",
            "give 0 to 1 bits",
        ),
    ];
    for (kind, toml, field, range) in cases {
        let e = match open(kind, toml, "r.toml", 20_000_000) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("{kind} took {toml}"),
        };
        for part in [
            "r.toml",
            field,
            range,
            "outside the seed's range",
            "seed 001",
        ] {
            assert!(e.contains(part), "{kind}: no `{part}` in {e}");
        }
    }
    let ok = open(
        "modbus",
        "[checks]\nbaud_tolerance_percent = 1.5\n",
        "r.toml",
        20_000_000,
    );
    assert!(ok.is_ok());
}

/// A clock too coarse for 2 % of a bit says so once, at time 0, on both
/// sides, with the clock it needs; a fine one says nothing.
#[test]
fn a_clock_too_coarse_for_the_baud_tolerance_says_so_once() {
    for kind in ["sar58k24", "sar58k24_monitor"] {
        let e = open(kind, "", "r.toml", 2_304_000).unwrap();
        let notes = e.transcript()["notes"].as_array().unwrap().clone();
        assert_eq!(notes.len(), 1, "{kind}: {notes:?}");
        let n = notes[0].as_str().unwrap();
        assert!(
            n.starts_with(model::sar58k24::rules::CHARACTER.label())
                && n.contains("needs at least 11520008 Hz"),
            "{kind}: {n}"
        );
        let fine = open(kind, "", "r.toml", 11_980_800).unwrap();
        assert!(
            fine.transcript()["notes"].as_array().unwrap().is_empty(),
            "{kind}"
        );
    }
}
