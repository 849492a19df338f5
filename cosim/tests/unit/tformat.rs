use cosim::tformat::*;
use cosim::{Emulator, Pins};
use model::tformat::frames::control_field_for_code;

/// Sends one request field (at 32 cycles per bit, 80 MHz) and listens for
/// `listen` cycles; returns the emulator's outputs while listening.
/// The ten bits of one field on the line: start 0, data LSB first, delimiter 1.
fn frame_bits(byte: u8) -> impl Iterator<Item = bool> {
    std::iter::once(false)
        .chain((0..8).map(move |i| (byte >> i) & 1 == 1))
        .chain(std::iter::once(true))
}

fn request(emu: &mut TformatEmulator, cf: u8, listen: usize) -> Vec<Pins> {
    for b in frame_bits(cf) {
        for _ in 0..32 {
            emu.step(Pins((b as u32) << 1 | 4));
        }
    }
    (0..listen).map(|_| emu.step(Pins(2))).collect()
}

#[test]
fn a_data_id_3_readout_carries_the_position_and_alarms_set() {
    let mut emu =
        TformatEmulator::from_toml("[cable]\nlength_m = 0\n", "t.toml", 80_000_000).unwrap();
    emu.set_position(0, (0x1234u64 << 17) | 0x1_5A5A).unwrap();
    emu.set_status(0, "battery_alarm", true).unwrap();
    emu.set_status(0, "over_speed", true).unwrap();
    let out = request(&mut emu, control_field_for_code(3), 4000);
    assert_eq!(emu.count(), 1);
    assert_eq!(emu.last_value(0), Some((0x1234u64 << 17) | 0x1_5A5A));
    assert!(emu.last_status(0, "battery_alarm").unwrap());
    assert!(emu.last_status(0, "over_speed").unwrap());
    assert!(!emu.last_status(0, "counting_error").unwrap());
    let e = &emu.entries()[0];
    assert_eq!(e.sf, 0x20, "ea1 from the battery alarm (seed 002 6.3.2)");
    assert_eq!(e.fields.len(), 11);
    // The encoder drove the line: its driver enable rose at the host's end.
    assert!(out.iter().any(|p| p.enable()));
    assert!(emu.violations().is_empty());
}

#[test]
fn an_emulator_clock_that_is_no_multiple_of_the_baud_rate_is_refused() {
    let err = TformatEmulator::from_toml("", "t.toml", 16_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("whole multiple") && err.contains("t.toml"),
        "{err}"
    );
    let err = TformatEmulator::from_toml("", "t.toml", 5_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("at least 10000000 Hz"), "{err}");
}

#[test]
fn a_host_that_keeps_driving_into_the_answer_is_reported() {
    let mut emu =
        TformatEmulator::from_toml("[cable]\nlength_m = 0\n", "t.toml", 80_000_000).unwrap();
    // The line idle a character and more: the rule book times a host from its first request after idle.
    for _ in 0..400 {
        emu.step(Pins(2));
    }
    for b in frame_bits(control_field_for_code(0)) {
        for _ in 0..32 {
            emu.step(Pins((b as u32) << 1 | 4));
        }
    }
    for _ in 0..4000 {
        emu.step(Pins(2 | 4)); // still driving idle high
    }
    // DE held past the release, then the answer's first low against the host's 1.
    let rules: Vec<&str> = emu
        .violations()
        .iter()
        .map(|v| v.rule.split(" (").next().unwrap())
        .collect();
    assert_eq!(
        rules[..2],
        ["release", "no request during the answer"],
        "{rules:?}"
    );
    assert!(
        rules[2..]
            .iter()
            .all(|r| *r == "no request during the answer"),
        "{rules:?}"
    );
}
