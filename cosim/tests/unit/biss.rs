use cosim::biss::*;
use cosim::{Emulator, Pins};

#[test]
fn an_emulator_clock_below_four_times_10_mhz_is_refused_with_the_minimum() {
    let err = BissEmulator::from_toml("", "s.toml", 20_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("at least 40000000 Hz"), "{err}");
    let ok = BissEmulator::from_toml(
        "[emulator]\nmax_line_clock_khz = 5000\n",
        "s.toml",
        20_000_000,
    );
    assert!(ok.is_ok());
}

#[test]
fn a_bad_slave_field_names_the_file_and_the_field() {
    let err = BissEmulator::from_toml("[[slaves]]\nbits = 70\n", "s.toml", 80_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.starts_with("s.toml: field `slaves[0].bits`"), "{err}");
}

/// One frame of `periods` MA periods of `half` cycles per half, then MA high for `rest` cycles.
fn frame(emu: &mut BissEmulator, periods: u32, half: u64, rest: u64) {
    for _ in 0..periods {
        for _ in 0..half {
            emu.step(Pins::line(false));
        }
        for _ in 0..half {
            emu.step(Pins::line(true));
        }
    }
    for _ in 0..rest {
        emu.step(Pins::line(true));
    }
}

#[test]
fn tmas_below_100_ns_and_a_start_before_slo_is_high_again_are_reported() {
    // 80 MHz: 10 MHz MA = 4 cycles per half; the 16 us timeout is 1280
    // cycles; 100 m of cable, about 1 us each way, so SLO high after the
    // timeout reaches the master some 160 cycles after it.
    let mut emu =
        BissEmulator::from_toml("[cable]\nlength_m = 100\n", "s.toml", 80_000_000).unwrap();
    // MA idle high first: the emulator takes no frame before it has seen MA high.
    frame(&mut emu, 0, 4, 8);
    frame(&mut emu, 40, 4, 1500);
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
    // 13.3 MHz (3 cycles per half); 200 cycles later more clocks: for the
    // slave (its timeout not over) the same frame, so no new frame and no
    // timeout report, only TMAS.
    frame(&mut emu, 40, 3, 200);
    frame(&mut emu, 40, 4, 1500);
    let rules: Vec<&str> = emu
        .violations()
        .iter()
        .map(|v| v.rule.split(' ').next().unwrap())
        .collect();
    assert!(
        !rules.is_empty() && rules.iter().all(|r| *r == "TMAS"),
        "{rules:?}"
    );
    assert!(emu
        .take_violation()
        .unwrap()
        .contains("MA period 75.0 ns within a frame"));
    // A frame 1290 cycles after the last edge: the slave's timeout is over,
    // but its SLO high has not reached the master yet.
    let before = emu.violations().len();
    frame(&mut emu, 40, 4, 1290);
    frame(&mut emu, 40, 4, 1500);
    let late: Vec<&str> = emu.violations()[before..]
        .iter()
        .map(|v| v.rule.split(' ').next().unwrap())
        .collect();
    assert_eq!(late, vec!["timeout"], "{:?}", emu.violations());
}

#[test]
fn the_seed_scenario_file_is_accepted_whole() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/biss/seed_16bit.toml"
    ))
    .unwrap();
    let emu = BissEmulator::from_toml(&text, "seed_16bit.toml", 80_000_000).unwrap();
    assert_eq!(emu.config().slaves[0].positions[0], 35555);
}
