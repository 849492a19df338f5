use cosim::endat::*;
use cosim::{Emulator, Pins};

fn pins(clk: bool, oe: bool, d: bool) -> Pins {
    Pins(clk as u32 | (d as u32) << 1 | (oe as u32) << 2)
}

/// The clock idle high for `cycles`: a master out of reset before its first transfer.
fn idle(emu: &mut EndatEmulator, cycles: u64) {
    for _ in 0..cycles {
        emu.step(pins(true, false, true));
    }
}

/// Clocks one EnDat transfer as a master at `half` cycles per half period would,
/// the first low phase (t_ST) 2 us at 64 MHz: mode bits driven from F2, released at
/// F8, then `clocks` more periods; returns the levels the master samples just before
/// each rising edge after the release.
fn transfer(emu: &mut EndatEmulator, mode: u8, half: u64, clocks: u32, rest: u64) -> Vec<bool> {
    let mut seen = Vec::new();
    let mut out = Pins(1);
    for f in 1..=(8 + clocks) {
        // Bit driven at falling edge f (F2..F7: the six mode bits, MSB first).
        let oe = (2..8).contains(&f);
        let d = oe && (mode >> (7 - f)) & 1 == 1;
        for _ in 0..if f == 1 { 128 } else { half } {
            out = emu.step(pins(false, oe, d));
        }
        if f >= 8 {
            seen.push(out.data());
        }
        for _ in 0..half {
            emu.step(pins(true, oe, d));
        }
    }
    for _ in 0..rest {
        emu.step(pins(true, false, true));
    }
    seen
}

#[test]
fn a_position_read_returns_the_position_set_and_f2_differs_from_f1_when_told() {
    // 64 MHz, 2 MHz clock (16 cycles per half), 25-bit encoder, no cable, no output delay.
    let toml = "[encoder]\noutput_delay_ns = 0\n";
    let mut emu = EndatEmulator::from_toml(toml, "e.toml", 64_000_000).unwrap();
    emu.set_position(0, 0x1AB_CDEF).unwrap();
    emu.set_status(0, "f2", true).unwrap();
    idle(&mut emu, 64);
    let seen = transfer(&mut emu, 0b111000, 16, 36, 64 * 40);
    assert_eq!(emu.count(), 1);
    assert_eq!(emu.last_value(0), Some(0x1AB_CDEF));
    // F1 = 0 (no error word), F2 = 0 (low active: the separate unit reports an error).
    assert!(!emu.last_status(0, "f1").unwrap());
    assert!(!emu.last_status(0, "f2").unwrap());
    let e = &emu.entries()[0];
    assert_eq!(e.mode, "111000");
    assert_eq!(&e.sent_bits[..2], "00");
    // The start bit then F1 F2 and the position LSB first on the wire.
    // seen[0] is before the encoder switched its driver on (the idle high), then low until the start bit.
    assert!(!seen[1]);
    let start = 1 + seen[1..].iter().position(|&b| b).expect("start bit");
    let frame: String = seen[start + 1..start + 1 + 27]
        .iter()
        .map(|&b| if b { '1' } else { '0' })
        .collect();
    assert_eq!(frame, e.sent_bits[..27]);
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
}

#[test]
fn clocking_within_the_recovery_time_and_driving_into_the_encoder_are_reported() {
    let toml = "[encoder]\noutput_delay_ns = 0\n";
    let mut emu = EndatEmulator::from_toml(toml, "e.toml", 64_000_000).unwrap();
    idle(&mut emu, 64);
    // Type 2.2 position reads (a falling edge in the recovery of a 2.1 read is a continuous clock).
    transfer(&mut emu, 0b111000, 16, 40, 64); // 1 µs later: t_m is 15 µs
    transfer(&mut emu, 0b111000, 16, 40, 64 * 40);
    let rules: Vec<&str> = emu
        .violations()
        .iter()
        .map(|v| v.rule.split(' ').next().unwrap())
        .collect();
    assert!(rules.contains(&"t_m"), "{rules:?}");
}

#[test]
fn a_type_21_transfer_before_t_b_is_reported_and_one_after_it_is_not() {
    let toml = "[encoder]\noutput_delay_ns = 0\n";
    let mut emu = EndatEmulator::from_toml(toml, "e.toml", 64_000_000).unwrap();
    idle(&mut emu, 64);
    transfer(&mut emu, 0b000111, 16, 33, 64 * 500); // 500 µs later: t_b is 1 ms
    transfer(&mut emu, 0b000111, 16, 33, 64 * 1010); // 1.01 ms later
    transfer(&mut emu, 0b000111, 16, 33, 64 * 40);
    assert_eq!(emu.count(), 3);
    let rules: Vec<(u64, &str)> = emu
        .violations()
        .iter()
        .map(|v| (v.cycle, v.rule.split(' ').next().unwrap()))
        .collect();
    assert_eq!(rules.len(), 1, "{:?}", emu.violations());
    assert_eq!(rules[0].1, "t_b");
    assert_eq!(rules[0].0, emu.entries()[1].cycle);
}

#[test]
fn an_emulator_clock_below_four_times_8_mhz_is_refused_with_the_minimum() {
    let err = EndatEmulator::from_toml("", "e.toml", 16_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("at least 32000000 Hz"), "{err}");
}

#[test]
fn an_unknown_status_names_the_ones_there_are() {
    let mut emu = EndatEmulator::from_toml("", "e.toml", 64_000_000).unwrap();
    let err = emu.set_status(0, "alarm", true).unwrap_err().to_string();
    assert!(
        err.contains("f1") && err.contains("f2") && err.contains("busy"),
        "{err}"
    );
}
