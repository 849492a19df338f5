use cosim::half_duplex::random_list;
use cosim::sar58k24::*;
use cosim::{Emulator, Pins};

use crate::levels;

/// Receives 8N1 characters from the resolved line level (bit 2).
fn receive(line: &[bool], c: usize) -> Vec<u8> {
    let mut out = Vec::new();
    let mut i = 1;
    while i < line.len() {
        if line[i - 1] && !line[i] {
            let mut b = 0u8;
            for k in 0..8 {
                let at = i + c / 2 + (k + 1) * c;
                if at < line.len() && line[at] {
                    b |= 1 << k;
                }
            }
            out.push(b);
            i += 10 * c - c / 2;
        } else {
            i += 1;
        }
    }
    out
}

#[test]
fn the_seed_timed_frame_ff_81_01_7f_00_reaches_the_host() {
    // Seed 001, 3.1.1: 14 bits, 383 = FF 81 01 7F 00, at 115200 baud.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/sar/seed_timed_14bit.toml"
    ))
    .unwrap();
    let mut emu = SarEmulator::from_toml(&text, "seed_timed_14bit.toml", 10_000_000).unwrap();
    let line: Vec<bool> = (0..16_000)
        .map(|_| emu.step(Pins(0b1001)).0 & 4 != 0)
        .collect();
    assert_eq!(receive(&line, 87), vec![0xFF, 0x81, 0x01, 0x7F, 0x00]);
    assert_eq!(emu.last_value(0), Some(383));
    assert_eq!(emu.count(), 1);
    assert_eq!(emu.entries()[0].bytes, "FF 81 01 7F 00");
}

#[test]
fn a_bus_command_is_answered_and_a_talking_host_is_a_violation() {
    // Seed 001, 3.1.5: BC AA B1 answered FF B1 <position> <sum>.
    let text = "[sar]\nmode = \"bus\"\n[[sar.encoders]]\naddress = 1\nbits = 16\n[sar.random]\ncount = 4\nseed = 9\n";
    let mut emu = SarEmulator::from_toml(text, "bus.toml", 10_000_000).unwrap();
    let got = command(&mut emu);
    let p = random_list(4, 9, 16)[0];
    assert_eq!(got[..2], [0xFF, 0xB1]);
    assert_eq!(((got[2] as u64) << 8) | got[3] as u64, p);
    assert_eq!(emu.last_value(0), Some(p));
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
    // The host talks over the answer: reported once, with the rule.
    let cmd2 = levels(&[0xBC, 0xAA, 0xB1], 87);
    for &l in &cmd2 {
        emu.step(Pins(0b1001 | 4 | (l as u32) << 1));
    }
    // The host keeps its driver on, driving 1, into the answer.
    for _ in 0..1500 {
        emu.step(Pins(0b1001 | 4 | 2));
    }
    assert_eq!(emu.violations().len(), 1, "{:?}", emu.violations());
    assert!(emu.violations()[0].rule == model::sar58k24::rules::ANSWER.label());
}

/// Sends `BC AA B1` at 115200 baud (87 cycles a bit) and returns the
/// characters that came back within 1.2 ms.
fn command(emu: &mut SarEmulator) -> Vec<u8> {
    let cmd = levels(&[0xBC, 0xAA, 0xB1], 87);
    let mut line = Vec::new();
    for k in 0..12_000 {
        let pins = match cmd.get(k) {
            Some(&l) => 0b1001 | 4 | (l as u32) << 1,
            None => 0b1001,
        };
        line.push(emu.step(Pins(pins)).0 & 4 != 0);
    }
    receive(&line[cmd.len()..], 87)
}

/// Sends `BC AA B1` and returns the position in the answer.
fn poll(emu: &mut SarEmulator) -> u64 {
    let got = command(emu);
    assert_eq!(got[..2], [0xFF, 0xB1]);
    ((got[2] as u64) << 8) | got[3] as u64
}

#[test]
fn set_position_and_set_motion_drive_the_next_answers() {
    // A closed-loop bench sets the shaft at run time.
    let text = "[sar]\nmode = \"bus\"\n[[sar.encoders]]\naddress = 1\nbits = 16\npositions = [7]\n";
    let mut emu = SarEmulator::from_toml(text, "bus.toml", 10_000_000).unwrap();
    assert_eq!(poll(&mut emu), 7);
    emu.set_position(0, 0xABCD).unwrap();
    assert_eq!(poll(&mut emu), 0xABCD);
    assert_eq!(emu.last_value(0), Some(0xABCD));
    // 1000 counts per ms from 100: each poll (12 000 cycles, 1.2 ms) reads a later position.
    emu.set_motion(
        0,
        "[motion]\nkind = \"constant\"\nstart = 100\ncounts_per_ms = 1000\n",
    )
    .unwrap();
    let (a, b) = (poll(&mut emu), poll(&mut emu));
    assert!(
        (100..1400).contains(&a) && b > a + 1000 && b < a + 1400,
        "{a} {b}"
    );
    // A set position stops the motion.
    emu.set_position(0, 5).unwrap();
    assert_eq!((poll(&mut emu), poll(&mut emu)), (5, 5));
    let e = emu.set_position(1, 5).unwrap_err().to_string();
    assert!(e.contains("1 encoder(s), not encoder 1"), "{e}");
    let e = emu.set_position(0, 1 << 16).unwrap_err().to_string();
    assert!(e.contains("does not fit 16 bits"), "{e}");
}

#[test]
fn bad_tables_name_the_file_and_field() {
    let err = SarEmulator::from_toml("[sar]\n[[sar.encoders]]\nbits = 40\n", "s.toml", 10_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.starts_with("s.toml: ") && err.contains("encoders[0].bits")
            || err.contains("encoder.bits"),
        "{err}"
    );
    let err = SarEmulator::from_toml("[sar]\n[sar.random]\ncount = \"x\"\n", "s.toml", 10_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.starts_with("s.toml: ") && err.contains("count"),
        "{err}"
    );
    let err = SarEmulator::from_toml("", "s.toml", 500_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("at least 921600 Hz"), "{err}");
}
