use cosim::ssi::*;
use cosim::{Emulator, Pins};

#[test]
fn a_missing_field_value_names_the_file_and_field() {
    let err = SsiEmulator::from_toml("[encoder]\nbits = 0\n", "enc.toml", 50_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.starts_with("enc.toml: field `encoder.bits`"), "{err}");
    let err = SsiEmulator::from_toml("[encoder]\nbitz = 12\n", "enc.toml", 50_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("enc.toml") && err.contains("bitz"), "{err}");
}

#[test]
fn an_emulator_clock_below_four_times_250_khz_is_refused_with_the_minimum() {
    let err = SsiEmulator::from_toml("", "e.toml", 500_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("at least 1000000 Hz"), "{err}");
    assert!(SsiEmulator::from_toml("", "e.toml", 1_000_000).is_ok());
}

/// The emulator takes any clock the model's Timebase
/// takes (48, 60, 120, 150 MHz have no whole-picosecond period), and its
/// times are the exact ones: a check 48 000 cycles in at 48 MHz is at 1 ms.
#[test]
fn fabric_clocks_without_a_whole_picosecond_period_open_and_keep_exact_time() {
    for hz in [48_000_000, 60_000_000, 120_000_000, 150_000_000, 45_000_000] {
        assert!(
            SsiEmulator::from_toml("", "e.toml", hz).is_ok(),
            "{hz} Hz refused"
        );
        assert!(
            cosim::biss::BissEmulator::from_toml("", "s.toml", hz).is_ok(),
            "BiSS-C at {hz} Hz refused"
        );
        assert!(
            cosim::endat::EndatEmulator::from_toml("", "e.toml", hz).is_ok(),
            "EnDat at {hz} Hz refused"
        );
    }
    let tb = model::Timebase::new(48_000_000).unwrap();
    let checks = cosim::check::Checks::for_clock(&tb);
    assert!(
        (checks.us(48_000) - 1000.0).abs() < 1e-6,
        "{}",
        checks.us(48_000)
    );
    assert!(
        SsiEmulator::from_toml("", "e.toml", 1_000_000_001).is_err(),
        "above 1 GHz"
    );
}

/// An emulator at 4 MHz (`checks`: its `[checks]` table) whose master has
/// shown its clock idle high for one cycle: the emulator takes no read
/// before it has seen the clock high (a master in reset holds it at 0).
fn at_4_mhz(checks: &str) -> SsiEmulator {
    let mut emu = SsiEmulator::from_toml(checks, "e.toml", 4_000_000).unwrap();
    emu.step(Pins::line(true));
    emu
}

/// Clocks `bits` bits with a first low phase of `t_cs` cycles and half
/// periods of `half` cycles, then holds the clock high for `rest` cycles.
fn read(emu: &mut SsiEmulator, bits: u32, t_cs: u64, half: u64, rest: u64) {
    for _ in 0..t_cs {
        emu.step(Pins::line(false));
    }
    for _ in 0..bits {
        for _ in 0..half {
            emu.step(Pins::line(true));
        }
        for _ in 0..half {
            emu.step(Pins::line(false));
        }
    }
    for _ in 0..rest {
        emu.step(Pins::line(true));
    }
}

#[test]
fn a_master_within_the_seeds_limits_breaks_no_rule() {
    // 4 MHz: 250 kHz = 8 cycles per half period, T_cs 4 us = 16 cycles, T_m 500 us = 2000 cycles.
    let mut emu = at_4_mhz("");
    read(&mut emu, 12, 16, 8, 2010);
    read(&mut emu, 12, 16, 8, 2010);
    assert_eq!(emu.count(), 2);
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
}

#[test]
fn short_t_cs_fast_clock_and_early_reread_are_each_reported_with_the_seed_rule() {
    let mut emu = at_4_mhz("");
    // T_cs 2.5 us (10 cycles), then 500 kHz (4 cycles per half), then a new read 100 us later.
    read(&mut emu, 12, 10, 4, 400);
    read(&mut emu, 12, 16, 8, 10);
    let rules: Vec<&str> = emu
        .violations()
        .iter()
        .map(|v| v.rule.split(' ').next().unwrap())
        .collect();
    assert_eq!(rules[0], "T_cs");
    assert!(rules.contains(&"f_clk"));
    assert!(rules.contains(&"T_m"), "{rules:?}");
    let first = emu.take_violation().unwrap();
    assert!(first.starts_with("at 2750 ns (emulator cycle 11): T_cs (seed 001 SAR58K24 manual, SSI (2): first low phase >= 4 us): first low phase 2.500 us"), "{first}");
}

#[test]
fn a_faster_master_says_so_in_its_checks_table() {
    let mut emu = at_4_mhz("[checks]\nmax_clock_khz = 500\nt_cs_min_us = 2\n");
    read(&mut emu, 12, 10, 4, 2010);
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
}

#[test]
fn a_whole_scenario_file_is_accepted_and_its_master_ignored() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/ssi/seed_12bit.toml"
    ))
    .unwrap();
    let emu = SsiEmulator::from_toml(&text, "seed_12bit.toml", 50_000_000).unwrap();
    assert_eq!(emu.config().positions, vec![495, 0, 4095, 2730]);
}

#[test]
fn a_motion_profile_moves_the_position_between_reads() {
    // 4 MHz: 1 ms = 4000 cycles; 1000 counts per ms from 100.
    let mut emu = at_4_mhz("[checks]\nmax_clock_khz = 500\nt_cs_min_us = 2\n");
    emu.set_motion(
        0,
        "[motion]\nkind = \"constant\"\nstart = 100\ncounts_per_ms = 1000\n",
    )
    .unwrap();
    read(&mut emu, 12, 10, 4, 2000); // latched at cycle 1: 100
    for _ in 0..1990 {
        emu.step(Pins::line(true));
    }
    read(&mut emu, 12, 10, 4, 2010); // latched at cycle 4097 (1.02425 ms): 1124
    let got: Vec<(u64, u64)> = emu
        .entries()
        .iter()
        .map(|e| (e.cycle, e.position))
        .collect();
    assert_eq!(got, vec![(1, 100), (4097, 1124)]);
    assert!(emu
        .set_motion(
            0,
            "[motion]\nkind = \"steps\"\nstart = 0\nstep = 1\nevery_us = -1\n"
        )
        .is_err());
}
