//! The monitors against the emulators (clean closed loops: the monitor reads
//! what the emulator sent, and says nothing), and against crafted masters
//! that break each rule once (the rule fires, with its time).

use cosim::{open, Emulator, Pins};

/// A line pattern: `(level, cycles)` segments of pin 0, in order.
fn segments(list: &[(bool, u64)]) -> Vec<bool> {
    list.iter()
        .flat_map(|&(l, n)| std::iter::repeat_n(l, n as usize))
        .collect()
}

/// An SSI read of `bits` clocks: idle `idle` cycles, T_cs `t_cs`, half period `half`.
fn ssi_read(idle: u64, t_cs: u64, half: u64, bits: u32) -> Vec<(bool, u64)> {
    let mut s = vec![(true, idle), (false, t_cs)];
    for _ in 0..bits {
        s.push((true, half));
        s.push((false, half));
    }
    s.push((true, 4 * half));
    s
}

/// Runs an emulator and a monitor on the same clock; `clk` is the master's
/// line clock per cycle. The monitor sees the clock and the emulator's answer.
fn closed_loop(
    emu: &mut dyn Emulator,
    mon: &mut dyn Emulator,
    clk: &[bool],
    mut each: impl FnMut(u64, &mut dyn Emulator),
) {
    let mut data = true;
    for (c, &l) in clk.iter().enumerate() {
        each(c as u64, emu);
        mon.step(Pins(l as u32 | (data as u32) << 1));
        data = emu.step(Pins::line(l)).data();
    }
}

fn rules(mon: &mut dyn Emulator) -> Vec<(f64, String)> {
    mon.violations()
        .iter()
        .map(|v| {
            (
                v.time_ns,
                v.rule.split(' ').next().unwrap_or("").to_string(),
            )
        })
        .collect()
}

const SSI_TOML: &str = "[encoder]\nbits = 12\nmonoflop_us = 20\n[cable]\nlength_m = 10\n";

/// 250 kHz at 4 MHz: 8 cycles a half period, T_cs 4.5 us, 30 us between reads.
#[test]
fn ssi_monitor_reads_what_the_emulator_sent_and_is_silent_on_a_clean_master() {
    let mut emu = open("ssi", SSI_TOML, "t.toml", 4_000_000).unwrap();
    let mut mon = open("ssi_monitor", SSI_TOML, "t.toml", 4_000_000).unwrap();
    let positions = [495u64, 0, 4095, 1234, 2730];
    let mut clk = Vec::new();
    let mut starts = Vec::new();
    for _ in positions {
        starts.push(clk.len() as u64 + 120);
        clk.extend(segments(&ssi_read(120, 18, 8, 12)));
    }
    clk.extend(segments(&[(true, 200)]));
    let mut k = 0;
    closed_loop(emu.as_mut(), mon.as_mut(), &clk, |c, e| {
        if k < positions.len() && c == starts[k] - 10 {
            e.set_position(0, positions[k]).unwrap();
            k += 1;
        }
    });
    let t = mon.transcript();
    let reads = t["transactions"].as_array().unwrap();
    assert_eq!(reads.len(), 5, "{t}");
    for (r, p) in reads.iter().zip(positions) {
        assert_eq!(r["position"].as_u64(), Some(p), "{r}");
    }
    // The seed's example (seed 001, SSI (4)): 000111101111 = 495.
    assert_eq!(reads[0]["received_bits"], "000111101111");
    let sent: Vec<u64> = emu.transcript()["reads"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["position"].as_u64().unwrap())
        .collect();
    assert_eq!(sent, positions);
    assert_eq!(mon.count(), 5);
    assert_eq!(mon.last_value(0), Some(2730));
    assert!(mon.violations().is_empty(), "{:?}", mon.violations());
    assert_eq!(t["violations"].as_array().unwrap().len(), 0);
}

/// Each SSI rule broken once by a crafted master, at 4 MHz (250 ns a cycle).
#[test]
fn each_ssi_rule_fires_once_with_its_time_and_the_seed_reference() {
    let run = |reads: &[Vec<(bool, u64)>]| {
        let mut mon = open("ssi_monitor", SSI_TOML, "t.toml", 4_000_000).unwrap();
        let clk = segments(&reads.concat());
        for &l in &clk {
            mon.step(Pins(l as u32 | 2));
        }
        (rules(mon.as_mut()), mon.violations().to_vec())
    };
    let clean = ssi_read(200, 18, 8, 12);
    assert!(run(&[clean.clone(), clean.clone()]).0.is_empty());
    // T_cs 2.5 us (10 cycles) < 4 us: at the first rising edge, cycle 210.
    let (r, v) = run(&[ssi_read(200, 10, 8, 12)]);
    assert_eq!(r, vec![(52_500.0, "T_cs".to_string())]);
    assert!(
        v[0].rule.contains("seed 001") && v[0].detail.contains("2.500 us"),
        "{v:?}"
    );
    // 500 kHz (4 cycles a half period) > 250 kHz: every period (rising
    // edge to rising edge) after T_cs.
    let (r, _) = run(&[ssi_read(200, 18, 4, 12)]);
    assert_eq!(r.len(), 12, "{r:?}");
    assert!(r.iter().all(|(_, n)| n == "f_clk"));
    assert_eq!(r[0].0, (200 + 18 + 4 + 4) as f64 * 250.0);
    // 62.5 kHz (32 cycles) < 100 kHz.
    let (r, _) = run(&[ssi_read(200, 18, 32, 4)]);
    assert!(
        !r.is_empty() && r.iter().all(|(_, n)| n == "f_clk"),
        "{r:?}"
    );
    // T_m: the second read starts 2 us + idle after the first; the encoder's monoflop is 20 us.
    let (r, v) = run(&[clean.clone(), ssi_read(40, 18, 8, 12)]);
    assert_eq!(r.len(), 1, "{r:?}");
    assert_eq!(r[0].1, "T_m");
    assert!(v[0].detail.contains("T_m is 20.000 us"), "{v:?}");
}

const BISS_TOML: &str = "[[slaves]]\nbits = 16\n[cable]\nlength_m = 10\n";

/// A BiSS-C frame: idle, then `clocks` MA periods of `low` + `high` cycles, MA left high.
fn biss_frame(idle: u64, clocks: u32, low: u64, high: u64) -> Vec<(bool, u64)> {
    let mut s = vec![(true, idle)];
    for _ in 0..clocks {
        s.push((false, low));
        s.push((true, high));
    }
    s
}

/// 10 MHz MA at 80 MHz: 4 + 4 cycles; frames 20 us apart (the seed's timeout is 16 us).
#[test]
fn biss_monitor_reads_what_the_emulator_sent_and_is_silent_on_a_clean_master() {
    let mut emu = open("biss", BISS_TOML, "t.toml", 80_000_000).unwrap();
    let mut mon = open("biss_monitor", BISS_TOML, "t.toml", 80_000_000).unwrap();
    let set = [
        (35555u64, false, true),
        (0, true, false),
        (65535, false, false),
        (4660, true, true),
    ];
    let mut clk = Vec::new();
    let mut starts = Vec::new();
    for _ in set {
        starts.push(clk.len() as u64 + 1700);
        clk.extend(segments(&biss_frame(1700, 40, 4, 4)));
    }
    clk.extend(segments(&[(true, 1700)]));
    let mut k = 0;
    closed_loop(emu.as_mut(), mon.as_mut(), &clk, |c, e| {
        if k < set.len() && c == starts[k] - 10 {
            let (p, err, wrn) = set[k];
            e.set_position(0, p).unwrap();
            e.set_status(0, "error", err).unwrap();
            e.set_status(0, "warning", wrn).unwrap();
            k += 1;
        }
    });
    let t = mon.transcript();
    let frames = t["transactions"].as_array().unwrap();
    assert_eq!(frames.len(), 4, "{t}");
    for (f, (p, err, wrn)) in frames.iter().zip(set) {
        let s = &f["slaves"][0];
        assert_eq!(
            (
                s["position"].as_u64(),
                s["error"].as_bool(),
                s["warning"].as_bool(),
                s["crc_ok"].as_bool()
            ),
            (Some(p), Some(err), Some(wrn), Some(true)),
            "{f}"
        );
    }
    let sent = emu.transcript();
    for (f, e) in frames.iter().zip(sent["frames"].as_array().unwrap()) {
        assert_eq!(f["slaves"][0]["position"], e["slaves"][0]["position"]);
    }
    assert_eq!(mon.last_value(0), Some(4660));
    assert!(mon.last_status(0, "error").unwrap());
    assert!(mon.violations().is_empty(), "{:?}", mon.violations());
}

/// Each BiSS-C rule broken once, at 200 MHz (5 ns a cycle), SLO held high.
#[test]
fn each_biss_rule_fires_with_its_time_and_the_seed_reference() {
    let run = |frames: &[Vec<(bool, u64)>], slo_low_from: Option<usize>| {
        let mut mon = open("biss_monitor", BISS_TOML, "t.toml", 200_000_000).unwrap();
        for (c, l) in segments(&frames.concat()).into_iter().enumerate() {
            let slo = slo_low_from.is_none_or(|f| c < f);
            mon.step(Pins(l as u32 | (slo as u32) << 1));
        }
        (rules(mon.as_mut()), mon.violations().to_vec())
    };
    // 100 ns MA (10 + 10 cycles), frames 20 us (4000 cycles) apart: clean.
    let clean = biss_frame(4000, 40, 10, 10);
    assert!(run(&[clean.clone(), clean.clone()], None).0.is_empty());
    // MA high 10 ns (2 cycles) once: TMASH, at the falling edge that ends it.
    let mut short_high = clean.clone();
    short_high[10] = (true, 2);
    let (r, v) = run(&[short_high], None);
    assert_eq!(r.iter().filter(|x| x.1 == "TMASH").count(), 1, "{r:?}");
    assert!(
        v.iter()
            .any(|v| v.rule.starts_with("TMASH (seed 001") && v.detail.contains("10.0 ns")),
        "{v:?}"
    );
    // MA low 10 ns once: TMASL (and that period, 10 + 50 ns, breaks TMAS too).
    let mut short_low = clean.clone();
    short_low[9] = (false, 2);
    let (r, _) = run(&[short_low], None);
    assert_eq!(r.iter().filter(|x| x.1 == "TMASL").count(), 1, "{r:?}");
    // 60 ns periods (6 + 6 cycles): TMAS at every rising edge after the first, no TMASH/TMASL.
    let (r, _) = run(&[biss_frame(4000, 40, 6, 6)], None);
    assert_eq!(r.len(), 39, "{r:?}");
    assert!(r.iter().all(|x| x.1 == "TMAS"));
    assert_eq!(r[0].0, (4000 + 6 + 6 + 6) as f64 * 5.0);
    // More clocks 5 us after the last MA edge (the seed's timeout is 16
    // us): for the slave the same frame, so no report.
    let (r, _) = run(&[clean.clone(), biss_frame(1000, 40, 10, 10)], None);
    assert!(r.is_empty(), "{r:?}");
    // Late enough but SLO still low at the master.
    let (r, v) = run(&[clean.clone(), clean.clone()], Some(4000 + 800 + 10));
    assert_eq!(r.len(), 1, "{r:?}");
    assert_eq!(r[0].1, "timeout");
    assert!(v[0].detail.contains("SLO still low"), "{v:?}");
}

#[test]
fn a_monitor_refuses_controls_and_a_bad_table_names_file_and_field() {
    let mut mon = open("ssi_monitor", "", "m.toml", 4_000_000).unwrap();
    let e = mon.set_position(0, 1).unwrap_err().to_string();
    assert!(e.contains("ssi_monitor is a monitor"), "{e}");
    let e = open("ssi_monitor", "[monitor]\nbits = 70\n", "m.toml", 4_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("m.toml") && e.contains("monitor.bits") && e.contains("give 1 to 64 bits"),
        "{e}"
    );
    let e = open(
        "biss_monitor",
        "[monitor]\ntmash = 3\n",
        "b.toml",
        80_000_000,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.contains("b.toml") && e.contains("tmash"), "{e}");
    let e = open("biss_monitor", "", "b.toml", 1_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("too slow") && e.contains("40000000"), "{e}");
    // The emulator reads the same file with a [monitor] table.
    assert!(open("biss", "[monitor]\ntimeout_us = 16\n", "b.toml", 80_000_000).is_ok());
}

// ---- EnDat ----

const ENDAT_TOML: &str = "[emulator]\nmax_line_clock_khz = 1000\n[cable]\nlength_m = 0\n";

/// One EnDat master transfer against `emu` (or a crafted line): `mode`, half period `half` cycles, first low
/// `t_st` cycles; it polls for the start bit at the end of each high phase and stops the clock after `frame`
/// further bits; then `idle` cycles of high clock. `phase(k, high)` may change the length of phase k.
struct Master<'a> {
    emu: Option<&'a mut dyn Emulator>,
    mon: &'a mut dyn Emulator,
    rx: bool,
    cycle: u64,
}

impl Master<'_> {
    fn tick(&mut self, clk: bool, d: bool, de: bool) {
        let rx = self.rx;
        self.mon.step(Pins(
            clk as u32 | (d as u32) << 1 | (de as u32) << 2 | (rx as u32) << 3,
        ));
        if let Some(e) = self.emu.as_mut() {
            self.rx = e
                .step(Pins(clk as u32 | (d as u32) << 1 | (de as u32) << 2))
                .data();
        }
        self.cycle += 1;
    }

    fn hold(&mut self, clk: bool, d: bool, de: bool, n: u64) {
        for _ in 0..n {
            self.tick(clk, d, de);
        }
    }

    /// Returns the cycle of F1.
    fn transfer(
        &mut self,
        mode: u8,
        half: u64,
        t_st: u64,
        frame: u32,
        idle: u64,
        phase: &dyn Fn(u32, bool) -> Option<u64>,
    ) -> u64 {
        let f1 = self.cycle;
        self.hold(false, true, false, phase(1, false).unwrap_or(t_st));
        // One clock after the last bit: the master samples each bit after the falling edge that follows it.
        let (mut start, mut left, mut k) = (false, frame + 1, 1u32);
        let mut low_seen = false;
        let (mut d, mut de) = (true, false);
        loop {
            // The master holds its bit through the high phase (the encoder takes it at the rising edge).
            self.hold(true, d, de, phase(k, true).unwrap_or(half));
            // End of the high phase after R_k: the encoder's bit is settled.
            if k >= 9 {
                if !start && !self.rx {
                    low_seen = true;
                } else if !start && self.rx && low_seen {
                    start = true;
                } else if start {
                    left -= 1;
                }
            }
            if (start && left == 0) || k > 200 {
                break;
            }
            k += 1;
            (d, de) = if (2..=7).contains(&k) {
                (mode >> (7 - k) & 1 != 0, true)
            } else {
                (true, false)
            };
            self.hold(false, d, de, phase(k, false).unwrap_or(half));
        }
        self.hold(true, true, false, idle);
        f1
    }
}

fn none(_: u32, _: bool) -> Option<u64> {
    None
}

/// The monitor beside the emulator in a closed loop at 1 MHz (8 MHz, 8 cycles a period): type 2.2 and 2.1
/// position reads with random positions and F1/F2, one type I error; the monitor reads what the emulator sent
/// and says nothing.
#[test]
fn endat_monitor_reads_what_the_emulator_sent_and_is_silent_on_a_clean_master() {
    let mut emu = open("endat", ENDAT_TOML, "t.toml", 8_000_000).unwrap();
    let mut mon = open("endat_monitor", ENDAT_TOML, "t.toml", 8_000_000).unwrap();
    let mut m = Master {
        emu: Some(emu.as_mut()),
        mon: mon.as_mut(),
        rx: true,
        cycle: 0,
    };
    m.hold(true, true, false, 100);
    let set = [
        (0x1ABCDEFu64, false, true, 0b111000u8),
        (0, true, false, 0b111000),
        (0x1FFFFFF, false, false, 0b000111),
        (12345, true, true, 0b111000),
        (777, false, true, 0b000000),
        (4242, false, true, 0b111000),
    ];
    for &(p, f1, f2, mode) in &set {
        let e = m.emu.as_mut().unwrap();
        e.set_position(0, p).unwrap();
        e.set_status(0, "f1", f1).unwrap();
        e.set_status(0, "f2", f2).unwrap();
        // Frame bits after the start bit: 2.2 F1 F2 25 CRC5; 2.1 F1 25 CRC5. A type I answer has no start bit.
        let frame = if mode == 0b111000 { 32 } else { 31 };
        // Waits: t_b after 2.1 (1 ms), 30 us after an error, else t_m (15 us) + t_R.
        let idle = match mode {
            0b000111 => 8100,
            0b000000 => 250,
            _ => 130,
        };
        m.transfer(mode, 4, 4, frame, idle, &none);
    }
    let t = mon.transcript();
    let list = t["transactions"].as_array().unwrap();
    assert_eq!(list.len(), set.len(), "{t:#}");
    for (x, &(p, f1, f2, mode)) in list.iter().zip(&set) {
        assert_eq!(x["mode"], format!("{mode:06b}"), "{x}");
        if mode == 0 {
            assert_eq!(x["errors"][0], "no_start_bit", "{x}");
            continue;
        }
        assert_eq!(x["position"].as_u64(), Some(p), "{x}");
        assert_eq!(x["f1"].as_bool(), Some(f1), "{x}");
        if mode == 0b111000 {
            // F2 is low-active on the line: the emulator's "f2" status (error) sends 0.
            assert_eq!(x["f2"].as_bool(), Some(!f2), "{x}");
        }
        let errors: Vec<&str> = x["errors"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e.as_str().unwrap())
            .collect();
        assert!(!errors.contains(&"crc"), "{x}");
    }
    let sent: Vec<u64> = emu.transcript()["transfers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["position"].as_u64().unwrap())
        .collect();
    assert_eq!(sent, set.iter().map(|s| s.0).collect::<Vec<_>>());
    assert_eq!(mon.count(), set.len() as u64);
    assert_eq!(mon.last_value(0), Some(4242));
    assert!(mon.last_status(0, "crc_ok").unwrap() && !mon.last_status(0, "error").unwrap());
    assert!(mon.violations().is_empty(), "{:?}", mon.violations());
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
}

/// A crafted line (no emulator): 2.2 position reads whose answer is a start bit at R12 and zeros, the encoder's
/// recovery low `rec` cycles after the last edge; `phase` shapes the clock, `gap` is the idle between transfers
/// (the line high again `rec` cycles into it).
fn endat_rules(
    toml: &str,
    f_hz: u64,
    transfers: &[(u8, u64, u64, u64, u64)],
    phase: &dyn Fn(usize, u32, bool) -> Option<u64>,
    de_early: Option<usize>,
) -> (Vec<(f64, String)>, Vec<cosim::check::Violation>) {
    let mut mon = open("endat_monitor", toml, "t.toml", f_hz).unwrap();
    let mut m = Master {
        emu: None,
        mon: mon.as_mut(),
        rx: true,
        cycle: 0,
    };
    m.hold(true, true, false, 50);
    for (i, &(mode, half, t_st, rec, gap)) in transfers.iter().enumerate() {
        if de_early == Some(i) {
            m.hold(true, true, true, 2);
        }
        let f1 = m.cycle;
        // The encoder's answer by cycle from F1 (the burst is periodic from F2: R_k at t_st + (k - 1) * 2 half + half).
        let r = |k: u64| t_st + (k - 1) * 2 * half;
        let falls = 46u64;
        let end = r(falls);
        let answer = move |c: u64| -> bool {
            if c < r(8) + 1 {
                true
            } else if c < r(12) + 1 {
                false
            } else if c < r(13) + 1 {
                mode != 0 // no command: error type I, no start bit
            } else {
                c >= end + rec
            }
        };
        m.hold(false, true, false, phase(i, 1, false).unwrap_or(t_st));
        let (mut d, mut de) = (true, false);
        for k in 1..=falls as u32 {
            let n = phase(i, k, true).unwrap_or(half);
            for _ in 0..n {
                m.rx = answer(m.cycle - f1);
                m.tick(true, d, de || (de_early == Some(i) && k == 8));
            }
            if k == falls as u32 {
                break;
            }
            let k2 = k + 1;
            (d, de) = if (2..=7).contains(&k2) {
                (mode >> (7 - k2) & 1 != 0, true)
            } else {
                (true, false)
            };
            let n = phase(i, k2, false).unwrap_or(half);
            for _ in 0..n {
                m.rx = answer(m.cycle - f1);
                m.tick(false, d, de || (de_early == Some(i) && k2 == 8));
            }
        }
        for _ in 0..gap {
            m.rx = answer(m.cycle - f1);
            m.tick(true, true, false);
        }
    }
    (rules(mon.as_mut()), mon.violations().to_vec())
}

/// Each EnDat rule broken by a crafted master, at 8 MHz (125 ns a cycle) and 1 MHz (4 + 4 cycles), the encoder's
/// recovery low 15 us (120 cycles), 31 us (248 cycles) between transfers.
#[test]
fn each_endat_rule_fires_with_its_time_and_the_seed_reference() {
    let p22 = (0b111000u8, 4u64, 4u64, 120u64, 248u64);
    let clean = [p22, p22];
    let no = |_: usize, _: u32, _: bool| None;
    let (r, v) = endat_rules(ENDAT_TOML, 8_000_000, &clean, &no, None);
    assert!(r.is_empty(), "{v:?}");
    // f_c: at most 1 MHz (the [monitor] table; 500 ns a phase), one high and one low phase of 2 cycles
    // (250 ns) in the first transfer: at F20 and R20.
    let fc = format!("{ENDAT_TOML}[monitor]\nmax_clock_khz = 1000\n");
    let (r, v) = endat_rules(
        &fc,
        8_000_000,
        &clean,
        &|i, k, h| (i == 0 && (k == 19 && h || k == 20 && !h)).then_some(2),
        None,
    );
    // Each short phase also makes its period's phases 250 and 500 ns: the on-off ratio, exact since
    // the rule book (it had two monitor cycles of slack).
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["f_c", "on-off", "f_c", "on-off"],
        "{v:?}"
    );
    assert_eq!(r[0].0, (50 + 4 + 18 * 8 + 2) as f64 * 125.0);
    assert!(
        v[0].rule.contains("without delay compensation <= 2000 kHz")
            && v[0].detail.contains("clock high for 0.250 us"),
        "{v:?}"
    );
    assert!(v[2].detail.contains("clock low for 0.250 us"), "{v:?}");
    // f_c at least 100 kHz: 5.5 us half periods (44 cycles) throughout, every period from F3 on.
    let slow = [(0b111000u8, 44, 44, 120, 248)];
    let (r, _) = endat_rules(ENDAT_TOML, 8_000_000, &slow, &no, None);
    assert!(r.len() >= 40 && r.iter().all(|x| x.1 == "f_c"), "{r:?}");
    // On-off ratio: one period of 6 + 2 cycles (750 and 250 ns).
    let (r, v) = endat_rules(
        ENDAT_TOML,
        8_000_000,
        &clean,
        &|i, k, h| (i == 1 && k == 20).then_some(if h { 6 } else { 2 }),
        None,
    );
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["on-off"],
        "{v:?}"
    );
    assert!(
        v[0].detail.contains("high 0.750 us and low 0.250 us"),
        "{v:?}"
    );
    // t_ST: a 2 MHz clock (2 + 2 cycles) with a first low phase of 2 cycles (250 ns < 2 us).
    let fast = [(0b111000u8, 2, 2, 120, 248), (0b111000u8, 2, 16, 120, 248)];
    let (r, v) = endat_rules(ENDAT_TOML, 8_000_000, &fast, &no, None);
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["t_ST"],
        "{v:?}"
    );
    assert_eq!(r[0].0, (50 + 2) as f64 * 125.0); // at R1, the edge that ends the first low phase
    assert!(
        v[0].detail
            .contains("first low phase 0.250 us at a 2000 kHz clock; t_ST is 2.000 us"),
        "{v:?}"
    );
    // Send block: the driver on 2 cycles before F1 of the second transfer, and left on through F8/R8 of it.
    let (r, v) = endat_rules(ENDAT_TOML, 8_000_000, &clean, &no, Some(1));
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["send", "send"],
        "{v:?}"
    );
    assert!(
        v[0].detail.contains("outside a transfer") && v[1].detail.contains("still on at R8"),
        "{v:?}"
    );
    // t_m: the next transfer 10.5 us (4 + 80 cycles) after the last edge, the line high again after 5 us.
    let (r, v) = endat_rules(
        ENDAT_TOML,
        8_000_000,
        &[(0b111000, 4, 4, 40, 80), p22],
        &no,
        None,
    );
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["t_m"],
        "{v:?}"
    );
    assert!(
        v[0].detail.contains("10.500 us after") && v[0].detail.contains("t_m is 15.000 us"),
        "{v:?}"
    );
    // t_m, the line: 20 us later but the encoder still holds the line low (its t_m 25 us).
    let (r, v) = endat_rules(
        ENDAT_TOML,
        8_000_000,
        &[(0b111000, 4, 4, 200, 160), p22],
        &no,
        None,
    );
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["t_m"],
        "{v:?}"
    );
    assert!(v[0].detail.contains("still low"), "{v:?}");
    // t_R: the line high again 16 us after the last edge, the next transfer 250 ns later (no cable).
    // (The encoder's output delay, 200 ns by default, counts in the round trip: none here.)
    let no_delay = format!("{ENDAT_TOML}[encoder]\noutput_delay_ns = 0\n");
    let (r, v) = endat_rules(
        &no_delay,
        8_000_000,
        &[(0b111000, 4, 4, 128, 126), p22],
        &no,
        None,
    );
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["t_R"],
        "{v:?}"
    );
    assert!(v[0].detail.contains("0.250 us before"), "{v:?}");
    // With 50 m of cable the round trip (500 ns) makes the same 250 ns at the master 750 ns at the encoder: no report.
    let cable50 = "[emulator]\nmax_line_clock_khz = 1000\n[cable]\nlength_m = 50\n[encoder]\noutput_delay_ns = 0\n";
    let (r, v) = endat_rules(
        cable50,
        8_000_000,
        &[(0b111000, 4, 4, 128, 126), p22],
        &no,
        None,
    );
    assert!(r.is_empty(), "{v:?}");
    // After an error (mode 000000 is no command: no start bit, the line low until t_m after the last edge):
    // 20 us is too short, 31 us is enough.
    let (r, v) = endat_rules(
        ENDAT_TOML,
        8_000_000,
        &[(0b000000, 4, 4, 120, 160), p22],
        &no,
        None,
    );
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["t_m"],
        "{v:?}"
    );
    assert!(
        v[0].rule.contains("after an error") && v[0].detail.contains("20.500 us after"),
        "{v:?}"
    );
    let (r, v) = endat_rules(
        ENDAT_TOML,
        8_000_000,
        &[(0b000000, 4, 4, 120, 248), p22],
        &no,
        None,
    );
    assert!(r.is_empty(), "{v:?}");
    // t_b: a type 2.1 command (000111), the next transfer 500 us later.
    let (r, v) = endat_rules(
        ENDAT_TOML,
        8_000_000,
        &[(0b000111, 4, 4, 120, 4000), p22],
        &no,
        None,
    );
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["t_b"],
        "{v:?}"
    );
    assert!(
        v[0].detail.contains("500.500 us after") && v[0].detail.contains("(000111)"),
        "{v:?}"
    );
}

/// The delay-measurement rules, with delay compensation (`[master] delay_comp`): 000111 frames below 500 kHz
/// are the measurement; 1 ms (t_b) between them.
#[test]
fn each_endat_delay_measurement_rule_fires() {
    let toml = "[emulator]\nmax_line_clock_khz = 1000\n[master]\ndelay_comp = true\n";
    let no = |_: usize, _: u32, _: bool| None;
    let p22 = (0b111000u8, 4u64, 4u64, 120u64, 248u64);
    let meas = |half: u64| (0b000111u8, half, half, 120u64, 8100u64);
    let (r, v) = endat_rules(
        toml,
        8_000_000,
        &[meas(20), meas(20), meas(20), p22],
        &no,
        None,
    );
    assert!(r.is_empty(), "{v:?}");
    // 250 kHz: every phase 2 us (< 2.25 us), one report per frame.
    let (r, v) = endat_rules(
        toml,
        8_000_000,
        &[meas(16), meas(16), meas(16), p22],
        &no,
        None,
    );
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["measurement"; 3],
        "{v:?}"
    );
    assert!(
        v[0].detail.contains("clock low for 2.000 us (91 phase(s)"),
        "{v:?}"
    );
    // Two frames only.
    let (r, v) = endat_rules(toml, 8_000_000, &[meas(20), meas(20), p22], &no, None);
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["delay"],
        "{v:?}"
    );
    assert!(
        v[0].detail.contains("a delay measurement of 2 frame(s)"),
        "{v:?}"
    );
    // None at all before a compensated transfer (reported once).
    let (r, v) = endat_rules(toml, 8_000_000, &[p22, p22], &no, None);
    assert_eq!(
        r.iter().map(|x| x.1.as_str()).collect::<Vec<_>>(),
        ["delay"],
        "{v:?}"
    );
    assert!(
        v[0].detail.contains("no delay measurement before it"),
        "{v:?}"
    );
    // Without compensation the same line is clean.
    let (r, v) = endat_rules(ENDAT_TOML, 8_000_000, &[p22, p22], &no, None);
    assert!(r.is_empty(), "{v:?}");
}

#[test]
fn the_endat_monitor_refuses_controls_and_names_file_and_field() {
    let mut mon = open("endat_monitor", "", "e.toml", 64_000_000).unwrap();
    assert!(mon
        .set_status(0, "f1", true)
        .unwrap_err()
        .to_string()
        .contains("endat_monitor is a monitor"));
    let e = open(
        "endat_monitor",
        "[monitor]\npos_bits = 60\n",
        "e.toml",
        64_000_000,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(
        e.contains("e.toml") && e.contains("monitor.pos_bits") && e.contains("give 1 to 48"),
        "{e}"
    );
    let e = open(
        "endat_monitor",
        "[monitor]\nt_st = 2\n",
        "e.toml",
        64_000_000,
    )
    .err()
    .unwrap()
    .to_string();
    assert!(e.contains("e.toml") && e.contains("t_st"), "{e}");
    let e = open("endat_monitor", "", "e.toml", 8_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("too slow") && e.contains("32000000"), "{e}");
    // The emulator reads the same file with a [monitor] table.
    assert!(open("endat", "[monitor]\nt_r_us = 0.5\n", "e.toml", 64_000_000).is_ok());
}
