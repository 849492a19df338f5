//! The monitors against the emulators (clean closed loops: the monitor reads
//! what the emulator sent, and says nothing), and against crafted masters
//! that break each rule once (the rule fires, with its time).

use crate::{open, Emulator, Pins};

/// A line pattern: `(level, cycles)` segments of pin 0, in order.
fn segments(list: &[(bool, u64)]) -> Vec<bool> {
    list.iter().flat_map(|&(l, n)| std::iter::repeat_n(l, n as usize)).collect()
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
fn closed_loop(emu: &mut dyn Emulator, mon: &mut dyn Emulator, clk: &[bool], mut each: impl FnMut(u64, &mut dyn Emulator)) {
    let mut data = true;
    for (c, &l) in clk.iter().enumerate() {
        each(c as u64, emu);
        mon.step(Pins(l as u32 | (data as u32) << 1));
        data = emu.step(Pins::line(l)).data();
    }
}

fn rules(mon: &mut dyn Emulator) -> Vec<(f64, String)> {
    mon.violations().iter().map(|v| (v.time_ns, v.rule.split(' ').next().unwrap_or("").to_string())).collect()
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
    let sent: Vec<u64> = emu.transcript()["reads"].as_array().unwrap().iter().map(|r| r["position"].as_u64().unwrap()).collect();
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
    assert!(v[0].rule.contains("seed 001") && v[0].detail.contains("2.500 us"), "{v:?}");
    // 500 kHz (4 cycles a half period) > 250 kHz: every half period after T_cs.
    let (r, _) = run(&[ssi_read(200, 18, 4, 12)]);
    assert_eq!(r.len(), 24, "{r:?}");
    assert!(r.iter().all(|(_, n)| n == "clock"));
    assert_eq!(r[0].0, (200 + 18 + 4) as f64 * 250.0);
    // 62.5 kHz (32 cycles) < 100 kHz.
    let (r, _) = run(&[ssi_read(200, 18, 32, 4)]);
    assert!(!r.is_empty() && r.iter().all(|(_, n)| n == "clock"), "{r:?}");
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
    let set = [(35555u64, false, true), (0, true, false), (65535, false, false), (4660, true, true)];
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
        assert_eq!((s["position"].as_u64(), s["error"].as_bool(), s["warning"].as_bool(), s["crc_ok"].as_bool()), (Some(p), Some(err), Some(wrn), Some(true)), "{f}");
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
    assert!(v.iter().any(|v| v.rule.starts_with("TMASH (seed 001") && v.detail.contains("10.0 ns")), "{v:?}");
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
    // The next frame 5 us after the last MA edge (the seed's timeout is 16 us).
    let (r, v) = run(&[clean.clone(), biss_frame(1000, 40, 10, 10)], None);
    assert_eq!(r, vec![((4000 + 800 + 1000) as f64 * 5.0, "timeout".to_string())]);
    assert!(v[0].detail.contains("5.050 us after"), "{v:?}");
    // Late enough but SLO still low at the master.
    let (r, v) = run(&[clean.clone(), clean.clone()], Some(4000 + 800 + 10));
    assert_eq!(r.len(), 1, "{r:?}");
    assert!(v[0].detail.contains("SLO was still low"), "{v:?}");
}

#[test]
fn a_monitor_refuses_controls_and_a_bad_table_names_file_and_field() {
    let mut mon = open("ssi_monitor", "", "m.toml", 4_000_000).unwrap();
    let e = mon.set_position(0, 1).unwrap_err().to_string();
    assert!(e.contains("ssi_monitor is a monitor"), "{e}");
    let e = open("ssi_monitor", "[monitor]\nbits = 70\n", "m.toml", 4_000_000).err().unwrap().to_string();
    assert!(e.contains("m.toml") && e.contains("monitor.bits") && e.contains("give 1 to 64 bits"), "{e}");
    let e = open("biss_monitor", "[monitor]\ntmash = 3\n", "b.toml", 80_000_000).err().unwrap().to_string();
    assert!(e.contains("b.toml") && e.contains("tmash"), "{e}");
    let e = open("biss_monitor", "", "b.toml", 1_000_000).err().unwrap().to_string();
    assert!(e.contains("too slow") && e.contains("40000000"), "{e}");
    // The emulator reads the same file with a [monitor] table.
    assert!(open("biss", "[monitor]\ntimeout_us = 16\n", "b.toml", 80_000_000).is_ok());
}
