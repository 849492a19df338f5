//! Seed 003 (Leine & Linde CANopen gateway) examples and the DS 406 encoder's behaviour.

use model::can::emulator::{NodeSettings, Scripted};
use model::can::frame::Frame;
use model::can::{Bus, Emulator};
use model::canopen::cob::{BootUp, NmtState};
use model::canopen::encoder::{Encoder, EncoderConfig, EncoderKind};
use model::canopen::node::{EncoderNode, NodeTiming};
use model::canopen::scaling::{is_binary, NonCyclicLimit};
use model::canopen::sdo::{self, abort, Response};
use model::Timebase;

const MS: u64 = 1_000_000;

fn enc(node: u8) -> Encoder {
    let mut e = Encoder::new(&EncoderConfig {
        node_switch: node,
        ..Default::default()
    })
    .unwrap();
    e.power_on(0);
    e
}

fn sdo_req(e: &mut Encoder, d: [u8; 8]) -> Vec<u8> {
    let n = e.node();
    let a = e.on_frame(&Frame::data(0x600 + n as u32, &d), 0);
    assert_eq!(a.len(), 1, "one SDO answer");
    assert_eq!(a[0].id, 0x580 + n as u32);
    a[0].data.clone()
}

fn write(e: &mut Encoder, index: u16, v: u32) -> Response {
    let n = e
        .dictionary()
        .entry(index, 0)
        .ok()
        .and_then(|s| s.dtype.size())
        .unwrap_or(4);
    let d = sdo_req(e, sdo::download(index, 0, &v.to_le_bytes()[..n]));
    sdo::parse_response(&d, false)
}

fn ok(index: u16) -> Response {
    Response::Downloaded { index, sub: 0 }
}

fn aborted(index: u16, sub: u8, code: u32) -> Response {
    Response::Abort { index, sub, code }
}

fn read(e: &mut Encoder, index: u16, sub: u8) -> Response {
    let d = sdo_req(e, sdo::upload(index, sub));
    sdo::parse_response(&d, false)
}

/// Seed 003 §2.2 and §8 step 4: boot-up on 128 + address, no data bytes.
#[test]
fn boot_up_on_the_emergency_identifier_without_data() {
    for node in [1u8, 0x20, 127] {
        let mut e = Encoder::new(&EncoderConfig {
            node_switch: node,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(e.power_on(0), vec![Frame::data(128 + node as u32, &[])]);
        assert_eq!(e.state(), NmtState::PreOperational);
    }
    let mut e = Encoder::new(&EncoderConfig {
        node_switch: 3,
        boot_up: BootUp::Ds301,
        ..Default::default()
    })
    .unwrap();
    assert_eq!(e.power_on(0), vec![Frame::data(0x703, &[0x00])]);
}

/// Seed 003 §8 steps 5 to 7, at frame level: SDO `22 00 62 00 0A 00 00 00`
/// on 1536 + address, confirmation on 1408 + address, NMT `01 <node>`,
/// position on 384 + address every 10 ms.
#[test]
fn setup_example_frames() {
    let mut e = enc(0x0C);
    e.set_raw(123_456, 0);
    let a = e.on_frame(
        &Frame::data(
            1536 + 0x0C,
            &[0x22, 0x00, 0x62, 0x00, 0x0A, 0x00, 0x00, 0x00],
        ),
        MS,
    );
    assert_eq!(
        a,
        vec![Frame::data(
            1408 + 0x0C,
            &[0x60, 0x00, 0x62, 0x00, 0, 0, 0, 0]
        )]
    );
    assert_eq!(e.read(0x6200, 0), Ok(vec![0x0A, 0x00]));
    assert!(e.poll(20 * MS).is_empty(), "no PDO before NMT start");
    assert!(e
        .on_frame(&Frame::data(0, &[0x01, 0x0C]), 20 * MS)
        .is_empty());
    assert_eq!(e.state(), NmtState::Operational);
    assert!(e.poll(29 * MS).is_empty());
    for k in 1..=3u64 {
        let p = e.poll(20 * MS + k * 10 * MS);
        assert_eq!(
            p,
            vec![Frame::data(384 + 0x0C, &123_456u32.to_le_bytes())],
            "PDO {k}"
        );
        assert!(e.poll(20 * MS + k * 10 * MS + 1).is_empty());
    }
}

/// NMT to another node or an unknown command changes nothing; node 0 addresses all.
#[test]
fn nmt_addressing_and_states() {
    let mut e = enc(7);
    e.on_frame(&Frame::data(0, &[0x01, 0x08]), 0);
    assert_eq!(e.state(), NmtState::PreOperational);
    e.on_frame(&Frame::data(0, &[0x01, 0x00]), 0);
    assert_eq!(e.state(), NmtState::Operational);
    e.on_frame(&Frame::data(0, &[0x02, 0x07]), 0);
    assert_eq!(e.state(), NmtState::Stopped);
    assert!(
        e.on_frame(&Frame::data(0x607, &sdo::upload(0x1000, 0)), 0)
            .is_empty(),
        "no SDO in STOPPED"
    );
    e.on_frame(&Frame::data(0, &[0x80, 0x07]), 0);
    assert_eq!(e.state(), NmtState::PreOperational);
    e.on_frame(&Frame::data(0, &[0x55, 0x07]), 0);
    assert_eq!(e.state(), NmtState::PreOperational);
    assert_eq!(
        e.on_frame(&Frame::data(0, &[0x82, 0x07]), 0),
        vec![Frame::data(0x87, &[])]
    );
    assert_eq!(
        e.on_frame(&Frame::data(0, &[0x81, 0x00]), 0),
        vec![Frame::data(0x87, &[])]
    );
}

/// Seed 003 §3.2.1 A: 1000 units per revolution and a range of 32 000 is
/// binary (2^5 turns): cyclic, 0 - max - 0.
#[test]
fn scaling_example_cyclic_1000_32000() {
    let mut e = enc(1);
    assert_eq!(write(&mut e, 0x6000, 4), ok(0x6000));
    assert_eq!(write(&mut e, 0x6001, 1000), ok(0x6001));
    assert_eq!(write(&mut e, 0x6002, 32_000), ok(0x6002));
    assert!(e.scaling().cyclic);
    // A = 1000 * 4096 / 8192 = 500 in turn 31: 31 500.
    e.set_raw(31 * 8192 + 4096, 0);
    assert_eq!(e.position(0), 31_500);
    // Turn 31, last step: 31 * 1000 + 1000 * 8191 / 8192 = 31 999 = range − 1.
    e.set_raw(31 * 8192 + 8191, 0);
    assert_eq!(e.position(0), 31_999);
    // One step on: turn 32 → 0 again.
    e.set_raw(32 * 8192, 0);
    assert_eq!(e.position(0), 0);
    e.set_raw(33 * 8192 + 8192 / 4, 0);
    assert_eq!(e.position(0), 1_250);
}

/// Seed 003 §3.2.1 B: 100 units per revolution and 5000 steps (50 turns)
/// is not binary: non-cyclic; beyond the range the total range value.
#[test]
fn scaling_example_non_cyclic_100_5000() {
    for (limit, beyond) in [
        (NonCyclicLimit::TotalRange, 5000),
        (NonCyclicLimit::Clamp, 4999),
    ] {
        let mut e = Encoder::new(&EncoderConfig {
            non_cyclic_limit: limit,
            ..Default::default()
        })
        .unwrap();
        e.power_on(0);
        assert_eq!(write(&mut e, 0x6000, 4), ok(0x6000));
        assert_eq!(write(&mut e, 0x6001, 100), ok(0x6001));
        assert_eq!(write(&mut e, 0x6002, 5000), ok(0x6002));
        assert!(!e.scaling().cyclic);
        e.set_raw(49 * 8192 + 8191, 0);
        assert_eq!(e.position(0), 4999);
        e.set_raw(50 * 8192, 0);
        assert_eq!(e.position(0), beyond);
        // Below 0 after a preset: 10 at turn 1 (current 100) → offset −90; turn 0 → −90.
        e.set_raw(8192, 0);
        assert_eq!(write(&mut e, 0x6003, 10), ok(0x6003));
        e.set_raw(0, 0);
        assert_eq!(
            e.position(0),
            if limit == NonCyclicLimit::Clamp {
                0
            } else {
                5000
            }
        );
    }
    assert!(
        is_binary(1000, 32_000)
            && !is_binary(100, 5000)
            && is_binary(8192, 1 << 25)
            && !is_binary(1000, 1000 << 13)
    );
}

/// Seed 003 §3.1 NOTE: the mode is chosen when the range arrives, so the
/// units per revolution must come first.
#[test]
fn range_before_units_keeps_the_stale_mode() {
    let mut e = enc(1);
    write(&mut e, 0x6000, 4);
    assert_eq!(write(&mut e, 0x6002, 32_000), ok(0x6002));
    assert!(!e.scaling().cyclic, "32 000 is not 8192 × 2^x");
    assert_eq!(write(&mut e, 0x6001, 1000), ok(0x6001));
    assert!(
        !e.scaling().cyclic,
        "still non-cyclic until the range is sent again"
    );
    assert_eq!(write(&mut e, 0x6002, 32_000), ok(0x6002));
    assert!(e.scaling().cyclic);
}

/// Seed 003 §4.2: offset = preset − current (signed), a previous offset not
/// included; output = current + offset; 6509h reads it back; it survives a reset.
#[test]
fn preset_formula_and_offset_object() {
    let mut e = enc(2);
    e.set_raw(1000, 0);
    assert_eq!(write(&mut e, 0x6003, 300), ok(0x6003));
    assert_eq!(e.read(0x6509, 0), Ok((-700i32).to_le_bytes().to_vec()));
    assert_eq!(e.position(0), 300);
    e.set_raw(1100, 0);
    assert_eq!(e.position(0), 400);
    // Second preset: the current position is 1100 (without the old offset).
    assert_eq!(write(&mut e, 0x6003, 5000), ok(0x6003));
    assert_eq!(e.read(0x6509, 0), Ok(3900i32.to_le_bytes().to_vec()));
    // Wraps in the 2^25 raw range below 0.
    assert_eq!(write(&mut e, 0x6003, 0), ok(0x6003));
    e.set_raw(1099, 0);
    assert_eq!(e.position(0), (1 << 25) - 1);
    e.on_frame(&Frame::data(0, &[0x81, 2]), 0);
    assert_eq!(
        e.read(0x6509, 0),
        Ok((-1100i32).to_le_bytes().to_vec()),
        "stored through a reset (§4.1)"
    );
    assert_eq!(
        write(&mut e, 0x6003, 1 << 25),
        aborted(0x6003, 0, abort::TOO_HIGH)
    );
}

/// Code sequence (6000h bit 0): counter-clockwise inverts the raw position.
#[test]
fn code_sequence_inverts() {
    let mut e = enc(1);
    e.set_raw(5, 0);
    write(&mut e, 0x6000, 1);
    assert_eq!(e.position(0), (1 << 25) - 6);
    assert_eq!(
        read(&mut e, 0x6500, 0),
        Response::Uploaded {
            index: 0x6500,
            sub: 0,
            data: vec![1, 0]
        }
    );
}

/// Each SDO abort code the server sends.
#[test]
fn sdo_abort_codes() {
    let mut e = enc(4);
    assert_eq!(
        read(&mut e, 0x2000, 0),
        aborted(0x2000, 0, abort::NO_OBJECT)
    );
    assert_eq!(
        read(&mut e, 0x6200, 1),
        aborted(0x6200, 1, abort::NO_SUBINDEX)
    );
    assert_eq!(
        write(&mut e, 0x6004, 1),
        aborted(0x6004, 0, abort::READ_ONLY)
    );
    assert_eq!(
        write(&mut e, 0x1000, 1),
        aborted(0x1000, 0, abort::READ_ONLY)
    );
    let d = sdo_req(&mut e, sdo::download(0x6001, 0, &[0x10, 0x00]));
    assert_eq!(
        sdo::parse_response(&d, false),
        aborted(0x6001, 0, abort::LENGTH)
    );
    assert_eq!(
        write(&mut e, 0x5001, 0x80),
        aborted(0x5001, 0, abort::RANGE)
    );
    assert_eq!(write(&mut e, 0x5000, 8), aborted(0x5000, 0, abort::RANGE));
    assert_eq!(
        write(&mut e, 0x6001, 8193),
        aborted(0x6001, 0, abort::TOO_HIGH)
    );
    assert_eq!(write(&mut e, 0x6001, 1), aborted(0x6001, 0, abort::TOO_LOW));
    assert_eq!(write(&mut e, 0x6000, 2), aborted(0x6000, 0, abort::RANGE));
    let d = sdo_req(
        &mut e,
        sdo::download(0x1800, 1, &0x8000_0300u32.to_le_bytes()),
    );
    assert_eq!(
        sdo::parse_response(&d, false),
        Response::Downloaded {
            index: 0x1800,
            sub: 1
        }
    );
    let d = sdo_req(
        &mut e,
        sdo::download(0x1800, 1, &0x0001_0300u32.to_le_bytes()),
    );
    assert_eq!(
        sdo::parse_response(&d, false),
        aborted(0x1800, 1, abort::RANGE)
    );
    let d = sdo_req(&mut e, sdo::download(0x1800, 0, &[9]));
    assert_eq!(
        sdo::parse_response(&d, false),
        aborted(0x1800, 0, abort::READ_ONLY)
    );
    let d = sdo_req(&mut e, [0xE0, 0, 0x10, 0, 0, 0, 0, 0]);
    assert_eq!(
        sdo::parse_response(&d, false),
        aborted(0x1000, 0, abort::COMMAND)
    );
    let d = sdo_req(&mut e, [0x60, 0, 0, 0, 0, 0, 0, 0]);
    assert_eq!(
        sdo::parse_response(&d, false),
        aborted(0x0000, 0, abort::COMMAND),
        "segment without a transfer"
    );
    // Toggle error in a segmented upload.
    let d = sdo_req(&mut e, sdo::upload(0x1008, 0));
    assert!(matches!(
        sdo::parse_response(&d, false),
        Response::UploadSegmented { .. }
    ));
    let d = sdo_req(&mut e, [0x70, 0, 0, 0, 0, 0, 0, 0]);
    assert_eq!(
        sdo::parse_response(&d, true),
        aborted(0x1008, 0, abort::TOGGLE)
    );
    // Every code has a name.
    for c in [
        abort::TOGGLE,
        abort::COMMAND,
        abort::READ_ONLY,
        abort::NO_OBJECT,
        abort::LENGTH,
        abort::NO_SUBINDEX,
        abort::RANGE,
        abort::TOO_HIGH,
        abort::TOO_LOW,
    ] {
        assert_ne!(sdo::abort_name(c), "unknown abort code");
    }
}

/// Segmented upload of the device name (1008h, longer than 4 bytes).
#[test]
fn segmented_upload_of_the_device_name() {
    let mut e = enc(9);
    let d = sdo_req(&mut e, sdo::upload(0x1008, 0));
    let name = model::canopen::od::DEVICE_NAME.as_bytes();
    assert_eq!(
        sdo::parse_response(&d, false),
        Response::UploadSegmented {
            index: 0x1008,
            sub: 0,
            size: name.len() as u32
        }
    );
    let (mut got, mut t) = (Vec::new(), false);
    loop {
        let d = sdo_req(&mut e, [0x60 | (t as u8) << 4, 0, 0, 0, 0, 0, 0, 0]);
        let Response::Segment(tt, bytes, last) = sdo::parse_response(&d, true) else {
            panic!("segment expected: {d:02X?}")
        };
        assert_eq!(tt, t);
        got.extend(bytes);
        t = !t;
        if last {
            break;
        }
    }
    assert_eq!(got, name);
}

/// Segmented download of the preset (4 bytes in one segment), and a wrong total length.
#[test]
fn segmented_download() {
    let mut e = enc(9);
    e.set_raw(10, 0);
    assert_eq!(
        sdo::parse_response(&sdo_req(&mut e, [0x21, 0x03, 0x60, 0, 4, 0, 0, 0]), false),
        ok(0x6003)
    );
    // Segment: t=0, n = 3 unused bytes, c = 1.
    assert_eq!(
        sdo_req(&mut e, [(3 << 1) | 1, 0x2C, 0x01, 0, 0, 0, 0, 0]),
        vec![0x20, 0, 0, 0, 0, 0, 0, 0]
    );
    assert_eq!(e.position(0), 300);
    assert_eq!(
        sdo::parse_response(&sdo_req(&mut e, [0x21, 0x03, 0x60, 0, 5, 0, 0, 0]), false),
        ok(0x6003)
    );
    let d = sdo_req(&mut e, [(2 << 1) | 1, 1, 2, 3, 4, 5, 0, 0]);
    assert_eq!(
        sdo::parse_response(&d, true),
        aborted(0x6003, 0, abort::LENGTH)
    );
    // Read-only refused at the initiate.
    assert_eq!(
        sdo::parse_response(&sdo_req(&mut e, [0x21, 0x04, 0x60, 0, 4, 0, 0, 0]), false),
        aborted(0x6004, 0, abort::READ_ONLY)
    );
}

/// TPDO2 on every SYNC (1801h sub 2 = 1) in OPERATIONAL only; every n-th for n.
#[test]
fn tpdo2_on_sync() {
    let mut e = enc(3);
    e.set_raw(77, 0);
    assert!(
        e.on_frame(&Frame::data(0x80, &[]), 0).is_empty(),
        "no PDO in PRE_OPERATIONAL"
    );
    e.on_frame(&Frame::data(0, &[1, 3]), 0);
    assert_eq!(
        e.on_frame(&Frame::data(0x80, &[]), 0),
        vec![Frame::data(0x283, &[77, 0, 0, 0])]
    );
    let d = sdo_req(&mut e, sdo::download(0x1801, 2, &[3]));
    assert_eq!(
        sdo::parse_response(&d, false),
        Response::Downloaded {
            index: 0x1801,
            sub: 2
        }
    );
    let n: usize = (0..6)
        .map(|_| e.on_frame(&Frame::data(0x80, &[]), 0).len())
        .sum();
    assert_eq!(n, 2);
    let d = sdo_req(&mut e, sdo::download(0x1801, 2, &[0]));
    assert_eq!(
        sdo::parse_response(&d, false),
        Response::Abort {
            index: 0x1801,
            sub: 2,
            code: abort::RANGE
        }
    );
}

/// 5000h and 5001h take effect at the next reset (seed 003 §6.1, §6.2); FFh = switches.
#[test]
fn bit_rate_and_node_objects_after_reset() {
    let mut e = enc(5);
    assert_eq!(
        read(&mut e, 0x5000, 0),
        Response::Uploaded {
            index: 0x5000,
            sub: 0,
            data: vec![0xFF]
        }
    );
    assert_eq!(write(&mut e, 0x5001, 9), ok(0x5001));
    assert_eq!(write(&mut e, 0x5000, 6), ok(0x5000));
    assert_eq!(e.node(), 5);
    assert_eq!(
        e.on_frame(&Frame::data(0, &[0x81, 5]), 0),
        vec![Frame::data(0x89, &[])]
    );
    assert_eq!((e.node(), e.bit_code()), (9, 6));
    assert_eq!(
        e.read(0x1800, 1),
        Ok(vec![0x89, 0x01, 0, 0]),
        "TPDO1 COB-ID follows the node"
    );
    let a = e.on_frame(&Frame::data(0x609, &sdo::download(0x5001, 0, &[0xFF])), 0);
    assert_eq!(a[0].id, 0x589);
    assert_eq!(
        e.on_frame(&Frame::data(0, &[0x82, 9]), 0),
        vec![Frame::data(0x85, &[])]
    );
}

/// Node guarding answers with the toggle bit and the state; heartbeat replaces it.
#[test]
fn node_guarding_and_heartbeat() {
    let mut e = enc(6);
    let rtr = Frame {
        id: 0x706,
        ide: false,
        rtr: true,
        dlc: 1,
        data: vec![],
    };
    assert_eq!(e.on_frame(&rtr, 0), vec![Frame::data(0x706, &[0x7F])]);
    assert_eq!(e.on_frame(&rtr, 0), vec![Frame::data(0x706, &[0xFF])]);
    e.on_frame(&Frame::data(0, &[1, 6]), 0);
    assert_eq!(e.on_frame(&rtr, 0), vec![Frame::data(0x706, &[0x05])]);
    // Life guarding: 100 ms × 3 without a guard request → EMCY 8130h with
    // error register bit 4, communication error (CiA 301), kept in 1001h.
    write(&mut e, 0x100C, 100);
    write(&mut e, 0x100D, 3);
    e.on_frame(&rtr, 0);
    assert!(e.poll(299 * MS).is_empty());
    assert_eq!(
        e.poll(300 * MS),
        vec![Frame::data(0x86, &[0x30, 0x81, 0x10, 0, 0, 0, 0, 0])]
    );
    assert_eq!(e.read(0x1001, 0), Ok(vec![0x10]));
    let mut h = enc(6);
    write(&mut h, 0x1017, 50);
    assert!(h.on_frame(&rtr, 0).is_empty(), "heartbeat on: guarding off");
    assert!(h.poll(49 * MS).is_empty());
    assert_eq!(h.poll(50 * MS), vec![Frame::data(0x706, &[0x7F])]);
    assert!(h.poll(99 * MS).is_empty());
    assert_eq!(h.poll(100 * MS), vec![Frame::data(0x706, &[0x7F])]);
}

/// An alarm sends an emergency; clearing it sends the error reset.
#[test]
fn emergency_on_alarm() {
    let mut e = enc(8);
    assert_eq!(
        e.set_alarm(true, 0),
        vec![Frame::data(0x88, &[0x00, 0x10, 0x01, 0x01, 0x00, 0, 0, 0])]
    );
    assert_eq!(e.read(0x1001, 0), Ok(vec![1]));
    assert_eq!(e.read(0x6503, 0), Ok(vec![1, 0]));
    assert!(e.set_alarm(true, 0).is_empty());
    assert_eq!(
        e.set_alarm(false, 0),
        vec![Frame::data(0x88, &[0, 0, 0, 0, 0, 0, 0, 0])]
    );
}

/// The encoder types of seed 003 §7.
#[test]
fn encoder_types() {
    let mk = |kind| {
        let mut e = Encoder::new(&EncoderConfig {
            kind,
            ..Default::default()
        })
        .unwrap();
        e.power_on(0);
        e
    };
    // §7.1: singleturn, range = scaled singleturn resolution.
    let mut s = mk(EncoderKind::Singleturn13);
    assert_eq!(write(&mut s, 0x6001, 360), ok(0x6001));
    assert_eq!(s.read(0x6002, 0), Ok(360u32.to_le_bytes().to_vec()));
    assert_eq!(write(&mut s, 0x6002, 720), aborted(0x6002, 0, abort::RANGE));
    assert_eq!(s.read(0x1000, 0), Ok(0x0001_0196u32.to_le_bytes().to_vec()));
    // §7.3: binary scaling only; the note's 20-bit → 18-bit example.
    let mut a = mk(EncoderKind::Angle20);
    assert_eq!(write(&mut a, 0x6001, 262_144), ok(0x6001));
    assert_eq!(
        write(&mut a, 0x6001, 262_145),
        aborted(0x6001, 0, abort::RANGE)
    );
    assert_eq!(
        write(&mut a, 0x6001, 1 << 21),
        aborted(0x6001, 0, abort::RANGE)
    );
    write(&mut a, 0x6000, 4);
    a.set_raw(3 << 18, 0);
    assert_eq!(a.position(0), 3 << 16);
    // §7.4: linear: preset only, 6501h the step in nm.
    let mut l = mk(EncoderKind::Linear);
    assert_eq!(
        read(&mut l, 0x6001, 0),
        aborted(0x6001, 0, abort::NO_OBJECT)
    );
    assert_eq!(write(&mut l, 0x6000, 1), aborted(0x6000, 0, abort::RANGE));
    assert_eq!(l.read(0x6501, 0), Ok(50u32.to_le_bytes().to_vec()));
    l.set_raw(1000, 0);
    assert_eq!(write(&mut l, 0x6003, 5), ok(0x6003));
    assert_eq!(l.position(0), 5);
    // §7.2: the multiturn range is limited by 4096 turns.
    let mut m = mk(EncoderKind::Multiturn25);
    assert_eq!(
        write(&mut m, 0x6002, (1 << 25) + 1),
        aborted(0x6002, 0, abort::TOO_HIGH)
    );
    assert_eq!(m.read(0x6502, 0), Ok(vec![0x00, 0x10]));
}

/// Bad configuration is an error naming the field.
#[test]
fn bad_configuration_names_the_field() {
    let e = Encoder::new(&EncoderConfig {
        node_switch: 0,
        ..Default::default()
    })
    .unwrap_err();
    assert_eq!(e.field(), "encoder.node_switch");
    let e = Encoder::new(&EncoderConfig {
        bit_rate_switch: 8,
        ..Default::default()
    })
    .unwrap_err();
    assert_eq!(e.field(), "encoder.bit_rate_switch");
}

/// Runs a host (scripted generic node) and encoder nodes on one bus.
fn run_bus(encoders: &mut [EncoderNode], host: &mut Emulator, cycles: u64) -> Vec<(u64, Frame)> {
    let places: Vec<_> = std::iter::once(model::can::bus::Place {
        position_m: 0.0,
        loop_delay_ns: 150.0,
    })
    .chain((0..encoders.len()).map(|k| model::can::bus::Place {
        position_m: 5.0 * (k + 1) as f64,
        loop_delay_ns: 150.0,
    }))
    .collect();
    let tb = Timebase::from_mhz(40.0).unwrap();
    let mut bus = Bus::new(&places, 5.0, &tb);
    let mut seen = 0;
    let mut log = Vec::new();
    for c in 0..cycles {
        let mut tx = vec![host.step(bus.rx(0))];
        for (k, e) in encoders.iter_mut().enumerate() {
            tx.push(e.step(bus.rx(k + 1)));
        }
        bus.push(&tx);
        while seen < host.received().len() {
            log.push((c, host.received()[seen].clone()));
            seen += 1;
        }
    }
    log
}

/// Seed 003 §8 on the bit-level bus at 250 kbit/s: boot-up, the SDO write
/// and its confirmation, NMT start, then TPDO1 every 10 ms.
#[test]
fn setup_example_on_the_bus() {
    let tb = Timebase::from_mhz(40.0).unwrap();
    let node = 0x0C;
    let cfg = EncoderConfig {
        node_switch: node,
        bit_rate_switch: 4,
        raw_position: 4242,
        ..Default::default()
    };
    let settings = NodeSettings {
        name: "encoder".into(),
        position_m: 5.0,
        loop_delay_ns: 150.0,
        ppm: 0.0,
        ack: true,
        frames: vec![],
    };
    let mut e = vec![EncoderNode::new(&cfg, &settings, NodeTiming::default(), &tb).unwrap()];
    let host_cfg = NodeTiming::default().controller(&tb, 250).unwrap();
    let frames = vec![
        Scripted::new(
            1000.0,
            Frame::data(
                0x600 + node as u32,
                &[0x22, 0x00, 0x62, 0x00, 0x0A, 0x00, 0x00, 0x00],
            ),
        ),
        Scripted::new(2000.0, Frame::data(0, &[0x01, node])),
    ];
    let mut host = Emulator::new(
        &NodeSettings {
            name: "host".into(),
            position_m: 0.0,
            loop_delay_ns: 150.0,
            ppm: 0.0,
            ack: true,
            frames,
        },
        host_cfg,
        &tb,
    )
    .unwrap();
    let log = run_bus(&mut e, &mut host, tb.cycles_nearest_ns(34.0e6));
    let ids: Vec<u32> = log.iter().map(|(_, f)| f.id).collect();
    assert_eq!(ids, vec![0x8C, 0x58C, 0x18C, 0x18C, 0x18C]);
    assert_eq!(log[0].1.data, Vec::<u8>::new());
    assert_eq!(log[1].1.data, vec![0x60, 0x00, 0x62, 0x00, 0, 0, 0, 0]);
    assert_eq!(e[0].encoder().state(), NmtState::Operational);
    for (_, f) in &log[2..] {
        assert_eq!(f.data, 4242u32.to_le_bytes());
    }
    // Every 10 ms: the cycles between PDO receptions, within one bit (160 cycles).
    for w in log[2..].windows(2) {
        let d = w[1].0 - w[0].0;
        assert!(d.abs_diff(400_000) <= 160, "PDO spacing {d} cycles");
    }
}

/// Three encoders on one bus: each boot-up arrives, lowest identifier first when they collide.
#[test]
fn three_encoders_boot_on_one_bus() {
    let tb = Timebase::from_mhz(40.0).unwrap();
    let mut es: Vec<EncoderNode> = [3u8, 1, 2]
        .iter()
        .map(|&n| {
            let s = NodeSettings {
                name: format!("enc{n}"),
                position_m: 2.0 * n as f64,
                loop_delay_ns: 150.0,
                ppm: 0.0,
                ack: true,
                frames: vec![],
            };
            EncoderNode::new(
                &EncoderConfig {
                    node_switch: n,
                    ..Default::default()
                },
                &s,
                NodeTiming::default(),
                &tb,
            )
            .unwrap()
        })
        .collect();
    let mut host = Emulator::new(
        &NodeSettings {
            name: "host".into(),
            position_m: 0.0,
            loop_delay_ns: 150.0,
            ppm: 0.0,
            ack: true,
            frames: vec![],
        },
        NodeTiming::default().controller(&tb, 250).unwrap(),
        &tb,
    )
    .unwrap();
    let log = run_bus(&mut es, &mut host, tb.cycles_nearest_ns(2.0e6));
    let ids: Vec<u32> = log.iter().map(|(_, f)| f.id).collect();
    assert_eq!(ids, vec![0x81, 0x82, 0x83]);
}

mod master {
    use super::*;
    use model::canopen::master::{In, Master, MasterConfig, Out, Param, State};

    fn cfg(node: u8, params: Vec<Param>) -> MasterConfig {
        let tb = Timebase::from_mhz(40.0).unwrap();
        MasterConfig {
            can: NodeTiming::default().controller(&tb, 250).unwrap(),
            node,
            params,
            boot_timeout: 400_000,
            sdo_timeout: 200_000,
            retries: 2,
            pdo_timeout: 600_000,
            sync_period: 0,
        }
    }

    /// Runs the master with `encoders` (and a mute acknowledging node if none) for `cycles`; every output.
    fn run(m: &mut Master, encoders: &mut [EncoderNode], cycles: u64) -> Vec<Out> {
        let tb = Timebase::from_mhz(40.0).unwrap();
        let mut places = vec![model::can::bus::Place {
            position_m: 0.0,
            loop_delay_ns: 150.0,
        }];
        places.extend((0..encoders.len().max(1)).map(|k| model::can::bus::Place {
            position_m: 10.0 * (k + 1) as f64,
            loop_delay_ns: 150.0,
        }));
        let mut bus = Bus::new(&places, 5.0, &tb);
        let mut mute = Emulator::new(
            &NodeSettings {
                name: "mute".into(),
                position_m: 10.0,
                loop_delay_ns: 150.0,
                ppm: 0.0,
                ack: true,
                frames: vec![],
            },
            NodeTiming::default().controller(&tb, 250).unwrap(),
            &tb,
        )
        .unwrap();
        let mut outs = Vec::with_capacity(cycles as usize);
        for _ in 0..cycles {
            let o = m.step(&In {
                i_start: false,
                i_can_rx: bus.rx(0),
            });
            let mut tx = vec![o.o_can_tx];
            if encoders.is_empty() {
                tx.push(mute.step(bus.rx(1)));
            }
            for (k, e) in encoders.iter_mut().enumerate() {
                tx.push(e.step(bus.rx(k + 1)));
            }
            bus.push(&tx);
            outs.push(o);
        }
        outs
    }

    fn encoder(node: u8, raw: u64) -> EncoderNode {
        let tb = Timebase::from_mhz(40.0).unwrap();
        let s = NodeSettings {
            name: format!("enc{node}"),
            position_m: 10.0,
            loop_delay_ns: 150.0,
            ppm: 0.0,
            ack: true,
            frames: vec![],
        };
        EncoderNode::new(
            &EncoderConfig {
                node_switch: node,
                raw_position: raw,
                ..Default::default()
            },
            &s,
            NodeTiming::default(),
            &tb,
        )
        .unwrap()
    }

    fn cycles_of(outs: &[Out], f: impl Fn(&Out) -> bool) -> Vec<usize> {
        outs.iter()
            .enumerate()
            .filter(|(_, o)| f(o))
            .map(|(k, _)| k)
            .collect()
    }

    /// Seed 003 §8 driven by the master: boot-up, 6200h = 10 ms by SDO, NMT start, a position every 10 ms.
    #[test]
    fn master_runs_the_setup_example() {
        let mut m = Master::new(&cfg(
            0x0C,
            vec![Param {
                index: 0x6200,
                sub: 0,
                size: 2,
                value: 10,
            }],
        ))
        .unwrap();
        let mut e = vec![encoder(0x0C, 4242)];
        let outs = run(&mut m, &mut e, 1_400_000);
        assert_eq!(cycles_of(&outs, |o| o.o_booted).len(), 1);
        assert_eq!(cycles_of(&outs, |o| o.o_config_done).len(), 1);
        let pos = cycles_of(&outs, |o| o.o_pos_valid);
        assert_eq!(pos.len(), 3, "PDOs at 10, 20, 30 ms after the start");
        for &k in &pos {
            assert_eq!(outs[k].o_position, 4242);
        }
        for w in pos.windows(2) {
            assert!((w[1] - w[0]).abs_diff(400_000) <= 160);
        }
        assert!(cycles_of(&outs, |o| o.o_sdo_abort || o.o_node_lost || o.o_pos_timeout).is_empty());
        assert_eq!(m.state(), State::Run);
        // The encoder saw exactly the note's SDO bytes, sized (2B) instead of 22: same object, same value.
        let sdo: Vec<&Frame> = e[0]
            .received()
            .iter()
            .map(|(_, f)| f)
            .filter(|f| f.id == 0x60C)
            .collect();
        assert_eq!(sdo.len(), 1);
        assert_eq!(
            sdo[0].data,
            vec![0x2B, 0x00, 0x62, 0x00, 0x0A, 0x00, 0x00, 0x00]
        );
    }

    /// An abort stops the configuration and reports code, index and sub-index.
    #[test]
    fn master_reports_an_abort() {
        let mut m = Master::new(&cfg(
            3,
            vec![
                Param {
                    index: 0x6000,
                    sub: 0,
                    size: 2,
                    value: 4,
                },
                Param {
                    index: 0x6001,
                    sub: 0,
                    size: 4,
                    value: 1,
                },
            ],
        ))
        .unwrap();
        let outs = run(&mut m, &mut [encoder(3, 0)], 200_000);
        let a = cycles_of(&outs, |o| o.o_sdo_abort);
        assert_eq!(a.len(), 1);
        let o = outs[a[0]];
        assert_eq!(
            (o.o_abort_code, o.o_abort_index, o.o_abort_sub),
            (abort::TOO_LOW, 0x6001, 0)
        );
        assert_eq!(m.state(), State::Failed);
        assert!(cycles_of(&outs, |o| o.o_config_done).is_empty());
    }

    /// A node that never boots: reset-node retries, then o_node_lost after (RETRIES + 1) × BOOT_TIMEOUT.
    #[test]
    fn master_flags_a_silent_node() {
        let mut m = Master::new(&cfg(5, vec![])).unwrap();
        let outs = run(&mut m, &mut [], 1_300_000);
        assert_eq!(cycles_of(&outs, |o| o.o_node_lost), vec![3 * 400_000 - 1]);
        assert_eq!(m.state(), State::Failed);
    }

    /// SYNC producer with TPDO2: positions arrive after each SYNC; the age resets; an emergency is captured.
    #[test]
    fn master_sync_pdo_and_emergency() {
        let mut c = cfg(7, vec![]);
        c.sync_period = 80_000; // 2 ms
        let mut m = Master::new(&c).unwrap();
        let mut e = vec![encoder(7, 99)];
        let outs = run(&mut m, &mut e, 300_000);
        let syncs = cycles_of(&outs, |o| o.o_sync_sent).len();
        let pos = cycles_of(&outs, |o| o.o_pos_valid);
        assert!(
            syncs >= 2 && pos.len() == syncs,
            "{syncs} SYNCs, {} PDOs",
            pos.len()
        );
        assert_eq!(outs[pos[0]].o_position, 99);
        assert!(!outs[pos[0]].o_pos_stale);
        let f = e[0].encoder_mut().set_alarm(true, 0);
        e[0].send(f);
        let outs = run(&mut m, &mut e, 40_000);
        let em = cycles_of(&outs, |o| o.o_emcy_valid);
        assert_eq!(em.len(), 1);
        assert_eq!(
            (outs[em[0]].o_emcy_code, outs[em[0]].o_emcy_reg),
            (0x1000, 1)
        );
    }

    /// No position for PDO_TIMEOUT cycles: one o_pos_timeout pulse and o_pos_stale until the next.
    #[test]
    fn master_flags_a_stale_position() {
        let mut c = cfg(2, vec![]);
        c.pdo_timeout = 100_000;
        let mut m = Master::new(&c).unwrap();
        let outs = run(&mut m, &mut [encoder(2, 0)], 400_000);
        let done = cycles_of(&outs, |o| o.o_config_done)[0];
        assert_eq!(cycles_of(&outs, |o| o.o_pos_timeout), vec![done + 100_000]);
        assert!(outs[done + 100_000].o_pos_stale && outs.last().unwrap().o_pos_stale);
    }

    /// A bad parameter list is an error naming the entry.
    #[test]
    fn master_config_errors_name_the_field() {
        let e = Master::new(&cfg(
            2,
            vec![Param {
                index: 0x6200,
                sub: 0,
                size: 1,
                value: 300,
            }],
        ))
        .unwrap_err();
        assert_eq!(e.field(), "master.params[0].size");
        assert_eq!(
            Master::new(&cfg(0, vec![])).unwrap_err().field(),
            "master.node"
        );
    }
}

/// Seed 003 §6.1, §6.2 on the bus: 5000h = 5 (500 kbit/s) and 5001h = 9 at
/// 250 kbit/s, NMT reset node; the boot-up then comes on 0x89 at 500 kbit/s.
#[test]
fn bit_rate_and_node_change_on_the_bus() {
    let tb = Timebase::from_mhz(40.0).unwrap();
    let t = NodeTiming::default();
    let s = NodeSettings {
        name: "encoder".into(),
        position_m: 5.0,
        loop_delay_ns: 150.0,
        ppm: 0.0,
        ack: true,
        frames: vec![],
    };
    let mut e = EncoderNode::new(
        &EncoderConfig {
            node_switch: 5,
            bit_rate_switch: 4,
            ..Default::default()
        },
        &s,
        t,
        &tb,
    )
    .unwrap();
    let frames = vec![
        Scripted::new(1000.0, Frame::data(0x605, &sdo::download(0x5000, 0, &[5]))),
        Scripted::new(2000.0, Frame::data(0x605, &sdo::download(0x5001, 0, &[9]))),
        Scripted::new(3000.0, Frame::data(0, &[0x81, 5])),
    ];
    let host_s = NodeSettings {
        name: "host".into(),
        position_m: 0.0,
        frames,
        ..s.clone()
    };
    let mut host = Emulator::new(&host_s, t.controller(&tb, 250).unwrap(), &tb).unwrap();
    let mut fast = Emulator::new(
        &NodeSettings {
            name: "fast".into(),
            frames: vec![],
            ..host_s.clone()
        },
        t.controller(&tb, 500).unwrap(),
        &tb,
    )
    .unwrap();
    let places = [s.place(), host_s.place()];
    let mut bus = Bus::new(&places, 5.0, &tb);
    let reset_done = tb.cycles_nearest_ns(3.6e6);
    for c in 0..tb.cycles_nearest_ns(5.0e6) {
        // The 250 kbit/s host leaves the bus once its reset command is out; a 500 kbit/s node takes its place.
        let h = if c < reset_done {
            host.step(bus.rx(1))
        } else {
            fast.step(bus.rx(1))
        };
        let tx = [e.step(bus.rx(0)), h];
        bus.push(&tx);
    }
    let ids: Vec<u32> = host.received().iter().map(|f| f.id).collect();
    assert_eq!(ids, vec![0x85, 0x585, 0x585]);
    assert_eq!(fast.received(), &[Frame::data(0x89, &[])]);
    assert_eq!((e.encoder().node(), e.encoder().bit_code()), (9, 5));
}

/// Fast-forward through a SYNC gap: SYNC every 1 ms (40 000 cycles at
/// 40 MHz), TPDO2 after every SYNC at 500 kbit/s. Once the bus is idle in
/// RUN the bench skips to the cycle before the SYNC is requested, in one
/// go; the first stepped cycle after the skip requests it; and the run
/// matches stepping sample for sample.
#[test]
fn sync_gap_is_skipped_in_one_go() {
    use model::canopen::bench::{BenchConfig, EncoderSettings, MasterSettings};
    use model::canopen::master::{Param, State};
    use model::testbench::{lockstep, Testbench};
    use model::Setup;
    let c = BenchConfig {
        bit_rate_kbps: 500,
        run_us: 6000.0,
        master: MasterSettings {
            node: 7,
            sync_period_us: 1000.0,
            params: vec![Param {
                index: 0x1801,
                sub: 2,
                size: 1,
                value: 1,
            }],
            ..MasterSettings::default()
        },
        encoders: vec![EncoderSettings {
            encoder: EncoderConfig {
                node_switch: 7,
                bit_rate_switch: 5,
                ..Default::default()
            },
            ..EncoderSettings::default()
        }],
        ..BenchConfig::default()
    };
    let mut b = c.bench().unwrap();
    let mut gaps = 0;
    while !b.finished() {
        let q = b.quiet_cycles();
        // Skips of less than a bit (80 cycles) end at a sample point or bit
        // end of some controller (in a frame, or the monitor's last
        // intermission bits): stepped here, the gaps are longer.
        if q < 1000 || b.master().state() != State::Run {
            b.step(None);
            continue;
        }
        // In RUN nothing but the SYNC ends a gap (no cyclic TPDO, the PDO
        // timeout 25 ms away): it is requested on the first stepped cycle
        // and loaded into the buffer on the next.
        b.skip(q);
        assert!(!b.master().controller().out().o_tx_busy);
        b.step(None);
        b.step(None);
        assert!(
            b.master().controller().out().o_tx_busy,
            "the SYNC is requested right after the gap"
        );
        // A SYNC and its TPDO2 take about 150 bits (300 µs): the rest of the 1 ms goes in one skip.
        gaps += (q > 20_000 && q < 40_000) as u32;
    }
    assert!(gaps >= 4, "{gaps} SYNC gaps skipped whole");
    let run = lockstep("SYNC gaps", c.bench().unwrap(), c.bench().unwrap());
    assert_eq!(run.skipping, run.stepped, "transcripts differ");
    let (cycles, skipped) = (run.cycles, run.skipped);
    assert!(
        skipped * 2 > cycles,
        "only {skipped} of {cycles} cycles skipped"
    );
}
