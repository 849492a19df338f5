use cosim::modbus::*;
use cosim::{Emulator, Pins};
use model::modbus::Verdict;

use crate::levels;

#[test]
fn the_seed_request_01_03_00_00_00_01_84_0a_is_answered_with_383() {
    // Seed 001, 3.1.7: factory defaults, 19200 baud, position 383.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenarios/modbus/seed_19200.toml"
    ))
    .unwrap();
    let mut emu = ModbusEmulator::from_toml(&text, "seed_19200.toml", 2_000_000).unwrap();
    let req = levels(&[0x01, 0x03, 0x00, 0x00, 0x00, 0x01, 0x84, 0x0A], 104);
    let mut enabled = 0u64;
    for k in 0..40_000 {
        let pins = match req.get(k) {
            Some(&l) => 4 | (l as u32) << 1,
            None => 2,
        };
        enabled += (emu.step(Pins(pins)).0 & 2 != 0) as u64;
    }
    assert_eq!(emu.count(), 1);
    assert_eq!(emu.entries()[0].verdict, Verdict::Answered);
    // Seed 001, 3.1.7 (5): 01 03 02 XX XX CRC; the CRC checked by the model's frame layer.
    assert!(
        emu.entries()[0].answer.starts_with("01 03 02 01 7F "),
        "{}",
        emu.entries()[0].answer
    );
    let bytes: Vec<u8> = emu.entries()[0]
        .answer
        .split(' ')
        .map(|b| u8::from_str_radix(b, 16).unwrap())
        .collect();
    assert!(model::modbus::frames::crc_ok(&bytes));
    assert_eq!(emu.last_value(0), Some(383));
    assert!(emu.last_status(0, "answered").unwrap());
    assert!(!emu.last_status(0, "exception").unwrap());
    assert!(
        enabled > 7 * 10 * 104 - 10,
        "the answer drove the line for {enabled} cycles"
    );
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
}

#[test]
fn set_position_and_set_motion_drive_the_next_answers() {
    // A closed-loop bench sets the shaft at run time.
    let mut emu = ModbusEmulator::from_toml(
        "[modbus]\nbaud = 19200.0\n[[modbus.devices]]\npositions = [9]\n",
        "m.toml",
        2_000_000,
    )
    .unwrap();
    let req = levels(&[0x01, 0x03, 0x00, 0x00, 0x00, 0x01, 0x84, 0x0A], 104);
    let poll = |emu: &mut ModbusEmulator| {
        for k in 0..40_000 {
            let pins = match req.get(k) {
                Some(&l) => 4 | (l as u32) << 1,
                None => 2,
            };
            emu.step(Pins(pins));
        }
        emu.last_value(0).unwrap()
    };
    assert_eq!(poll(&mut emu), 9);
    emu.set_position(0, 0xBEEF).unwrap();
    assert_eq!(poll(&mut emu), 0xBEEF);
    // 100 counts per ms from 0: each poll (40 000 cycles, 20 ms) reads about 2000 counts later.
    emu.set_motion(
        0,
        "[motion]\nkind = \"constant\"\nstart = 0\ncounts_per_ms = 100\n",
    )
    .unwrap();
    let (a, b) = (poll(&mut emu), poll(&mut emu));
    assert!(a < 2000 && b > a + 1900 && b < a + 2100, "{a} {b}");
    emu.set_position(0, 3).unwrap();
    assert_eq!(poll(&mut emu), 3);
    assert!(emu
        .set_position(2, 3)
        .unwrap_err()
        .to_string()
        .contains("not device 2"));
    assert!(emu
        .set_position(0, 1 << 16)
        .unwrap_err()
        .to_string()
        .contains("does not fit 16 bits"));
}

#[test]
fn a_request_with_a_long_silence_inside_is_a_violation() {
    let mut emu =
        ModbusEmulator::from_toml("[modbus]\nbaud = 19200.0\n", "m.toml", 2_000_000).unwrap();
    let a = levels(&[0x01, 0x03, 0x00], 104);
    let b = levels(&[0x00, 0x00, 0x01, 0x84, 0x0A], 104);
    let mut line: Vec<bool> = a;
    line.extend(std::iter::repeat_n(true, 2000)); // 1 ms > t1.5 (859 us at 19200)
    line.extend(b);
    for k in 0..30_000 {
        let pins = match line.get(k) {
            Some(&l) => 4 | (l as u32) << 1,
            None => 2,
        };
        emu.step(Pins(pins));
    }
    assert_eq!(emu.entries()[0].verdict, Verdict::Discarded);
    assert_eq!(emu.violations().len(), 1);
    assert!(emu.violations()[0].rule == model::modbus::rules::T15.label());
}
