//! The SAR58K24 asynchronous modes end to end: seed examples, every mode,
//! every baud rate, resolutions, Gray, a three-encoder bus, and the faults.

use model::sar58k24::*;
use model::testbench::run_to_end;
use model::uart::Parity;
use model::Setup;

fn run(cfg: &BenchConfig) -> (Vec<Transaction>, u64) {
    let bench = cfg.bench().unwrap();
    let r = run_to_end(bench);
    (r.transactions, r.cycles)
}

/// `n` timed reads back to back: "the next n frame events".
fn listen(n: u32) -> Vec<Operation> {
    vec![Operation {
        op: OpKind::Read,
        address: 0,
        gap_us: 0.0,
        repeat: n,
    }]
}

/// A run of timed reads seen as one listening window: every position and
/// every error of every transaction, in order.
struct Window {
    positions: Vec<u32>,
    angles_deg: Vec<f64>,
    errors: Vec<&'static str>,
    encoder_frames: Vec<Vec<u8>>,
    wire_answers: Vec<Vec<u8>>,
}

fn window(t: Vec<Transaction>) -> Vec<Window> {
    vec![Window {
        positions: t.iter().flat_map(|t| t.positions.clone()).collect(),
        angles_deg: t.iter().flat_map(|t| t.angles_deg.clone()).collect(),
        errors: t.iter().flat_map(|t| t.errors.clone()).collect(),
        encoder_frames: t.iter().flat_map(|t| t.encoder_frames.clone()).collect(),
        wire_answers: vec![t.iter().flat_map(|t| t.wire_answers.concat()).collect()],
    }]
}

fn run_window(cfg: &BenchConfig) -> Vec<Window> {
    window(run(cfg).0)
}

fn timed(refresh_hz: f64, positions: Vec<u64>, bits: u32) -> BenchConfig {
    BenchConfig {
        encoders: vec![EncoderSettings {
            bits,
            positions,
            refresh_hz,
            ..EncoderSettings::default()
        }],
        ops: listen(5),
        ..BenchConfig::default()
    }
}

fn op(op: OpKind, address: u8) -> Operation {
    Operation {
        op,
        address,
        gap_us: 200.0,
        repeat: 1,
    }
}

#[test]
fn seed_001_timed_send_ff_81_01_7f_00_is_383_and_8_4155_degrees() {
    // Seed 001, 3.1.1 (4): a 14-bit encoder returns FF 81 01 7F 00: a = 383, θ = 8.4155°.
    let (t, _) = run(&timed(1000.0, vec![383], 14));
    // One read per frame: o_done with o_valid, the position on o_position.
    assert_eq!(
        t.iter().map(|t| t.position).collect::<Vec<_>>(),
        vec![Some(383); 5]
    );
    let t = &window(t)[0];
    assert_eq!(t.positions, vec![383; 5]);
    assert_eq!(t.angles_deg[0], 8.4155);
    assert!(t.errors.is_empty(), "{:?}", t.errors);
    assert_eq!(t.encoder_frames[0], vec![0xFF, 0x81, 0x01, 0x7F, 0x00]);
    assert_eq!(t.wire_answers[0][..5], [0xFF, 0x81, 0x01, 0x7F, 0x00]);
}

#[test]
fn every_baud_rate_of_the_manual_carries_a_16_bit_frame() {
    // 2.4: 115200 ... 2400 baud; 20 Hz fits a 5-byte frame even at 2400 (20.8 ms).
    for baud in BAUD_RATES {
        let mut cfg = timed(20.0, vec![0xBEEF], 16);
        cfg.baud = baud;
        cfg.ops = listen(2);
        cfg.host.timeout_us = 100_000.0;
        let t = run_window(&cfg);
        assert_eq!(t[0].positions, vec![0xBEEF; 2], "{baud}");
        assert!(t[0].errors.is_empty(), "{baud}: {:?}", t[0].errors);
    }
}

#[test]
fn sixteen_twenty_four_and_thirty_two_bit_frames_binary_and_gray() {
    for (bits, value, len) in [
        (16, 0xFFFFu64, 5),
        (24, 0x12_3456, 6),
        (32, 0xFF81_FF81, 7),
        (10, 0x3FF, 5),
    ] {
        for code in [OutputCode::Binary, OutputCode::Gray] {
            let mut cfg = timed(1000.0, vec![value], bits);
            cfg.encoders[0].code = code;
            let t = run_window(&cfg);
            assert_eq!(t[0].positions, vec![value as u32; 5], "{bits} {code:?}");
            assert_eq!(t[0].encoder_frames[0].len(), len);
            assert!(t[0].errors.is_empty());
        }
    }
}

#[test]
fn a_refresh_rate_whose_period_cannot_hold_the_frame_is_refused_with_the_numbers() {
    let mut cfg = timed(2000.0, vec![1], 32);
    cfg.baud = 9600.0;
    let err = cfg.validate().unwrap_err().to_string();
    assert!(
        err.contains("encoders[0].refresh_hz")
            && err.contains("7291.7 µs")
            && err.contains("500.0 µs")
            && err.contains("137 Hz"),
        "{err}"
    );
    // 5 bytes at 115200 fit 2 kHz (434 µs < 500 µs), 6 bytes do not (521 µs).
    assert!(timed(2000.0, vec![1], 16).validate().is_ok());
    assert!(timed(2000.0, vec![1], 24).validate().is_err());
}

#[test]
fn timed_clear_zeroes_on_a_clr_pulse() {
    let mut cfg = timed(
        1000.0,
        vec![5000, 5000, 5000, 5010, 5020, 5030, 5040, 5050],
        14,
    );
    cfg.mode = Mode::TimedClear;
    cfg.ops = vec![
        Operation {
            op: OpKind::Read,
            address: 0,
            gap_us: 0.0,
            repeat: 2,
        },
        Operation {
            op: OpKind::Zero,
            address: 0,
            gap_us: 500.0,
            repeat: 1,
        },
        Operation {
            op: OpKind::Read,
            address: 0,
            gap_us: 0.0,
            repeat: 3,
        },
    ];
    let (t, _) = run(&cfg);
    assert_eq!(t[0].positions, vec![5000]);
    assert_eq!(t[1].positions, vec![5000]);
    assert!(t.iter().all(|t| t.errors.is_empty()), "{t:?}");
    let t = [
        window(t[..2].to_vec()).remove(0),
        window(vec![t[2].clone()]).remove(0),
        window(t[3..].to_vec()).remove(0),
    ];
    // Zeroed on the raw position 5000 (the third acquisition's): the next
    // frames read 0, then the movement from there.
    assert_eq!(t[2].positions, vec![0, 10, 20]);
}

#[test]
fn handshake_sends_one_frame_t3_after_the_falling_edge_and_ignores_a_short_pulse() {
    let mut cfg = timed(100.0, vec![100, 200, 300], 17);
    cfg.mode = Mode::Handshake;
    cfg.ops = vec![op(OpKind::Read, 0), op(OpKind::Read, 0)];
    let (t, _) = run(&cfg);
    assert_eq!(t[0].positions, vec![100]);
    assert_eq!(t[1].positions, vec![200]);
    assert!(t.iter().all(|t| t.errors.is_empty()));
    // Latency: trigger 10 µs low is inside T3 = 20 µs; the frame (6 bytes)
    // follows T3 and is taken at the middle of its last stop bit, 59.5 bits later.
    let span = (t[0].done_cycle - t[0].start_cycle) as f64 / 10.0;
    let expected = 20.0 + 59.5e6 / 115_200.0;
    assert!(
        (expected..expected + 1.0).contains(&span),
        "{span} µs, {expected} µs"
    );
    // A 5 µs trigger pulse is shorter than T2 = 10 µs: no frame, a timeout.
    cfg.host.trigger_low_us = 5.0;
    cfg.host.timeout_us = 1000.0;
    let bench = cfg.bench().unwrap();
    let r = run_to_end(bench);
    assert_eq!(r.transactions[0].errors, vec!["timeout"]);
    assert!(r.transactions[0].positions.is_empty());
}

#[test]
fn handshake_clear_zeroes_then_reads_zero() {
    let mut cfg = timed(100.0, vec![777], 16);
    cfg.mode = Mode::HandshakeClear;
    cfg.ops = vec![
        op(OpKind::Read, 0),
        op(OpKind::Zero, 0),
        op(OpKind::Read, 0),
    ];
    let (t, _) = run(&cfg);
    assert_eq!(t[0].positions, vec![777]);
    assert_eq!(t[2].positions, vec![0]);
    assert!(t.iter().all(|t| t.errors.is_empty()));
}

fn three_on_a_bus() -> BenchConfig {
    let enc = |address: u8, p: u64| EncoderSettings {
        address,
        bits: 16,
        positions: vec![p],
        ..EncoderSettings::default()
    };
    BenchConfig {
        mode: Mode::BusClear,
        encoders: vec![enc(1, 0x1111), enc(2, 0x2222), enc(3, 0x3333)],
        ops: vec![
            op(OpKind::Read, 1),
            op(OpKind::Read, 2),
            op(OpKind::Read, 3),
            op(OpKind::Zero, 2),
            op(OpKind::Read, 2),
            op(OpKind::Read, 3),
        ],
        ..BenchConfig::default()
    }
}

#[test]
fn three_encoders_on_one_bus_answer_only_their_own_command_and_zero_on_cx() {
    // Seed 001, 3.1.5/3.1.6: BC AA B1/B2/B3 answered FF B1/B2/B3 ...; BC AA C2 zeroes product 2.
    let cfg = three_on_a_bus();
    let bench = cfg.bench().unwrap();
    let r = run_to_end(bench);
    let t = &r.transactions;
    assert_eq!(t[0].wire_requests, vec![vec![0xBC, 0xAA, 0xB1]]);
    assert_eq!(
        t[0].wire_answers[0],
        frames::encode_tagged(0x1111, 16, 0xB1)
    );
    assert_eq!(t[1].positions, vec![0x2222]);
    assert_eq!(t[2].positions, vec![0x3333]);
    assert_eq!(t[3].wire_requests, vec![vec![0xBC, 0xAA, 0xC2]]);
    assert_eq!(t[3].positions, vec![0]);
    assert_eq!(t[4].positions, vec![0]);
    assert_eq!(t[5].positions, vec![0x3333]);
    assert!(t.iter().all(|t| t.errors.is_empty()), "{t:?}");
    assert_eq!(
        t.iter().map(|t| t.encoder_frames.len()).collect::<Vec<_>>(),
        vec![1; 6]
    );
}

#[test]
fn bus_answers_tagged_81_when_the_tables_are_followed() {
    let mut cfg = three_on_a_bus();
    for e in &mut cfg.encoders {
        e.answer_tag = AnswerTag::Fixed81;
    }
    let (t, _) = run(&cfg);
    assert_eq!(t[0].wire_answers[0], frames::encode(0x1111, 16));
    assert_eq!(t[2].positions, vec![0x3333]);
    assert!(t.iter().all(|t| t.errors.is_empty()));
}

#[test]
fn bus_without_clear_ignores_a_zeroing_command() {
    let mut cfg = three_on_a_bus();
    cfg.mode = Mode::Bus;
    cfg.ops = vec![op(OpKind::Read, 2)];
    let (t, _) = run(&cfg);
    assert_eq!(t[0].positions, vec![0x2222]);
    cfg.ops = vec![op(OpKind::Zero, 2)];
    assert!(cfg.validate().unwrap_err().to_string().contains("ops[0]"));
}

fn faulty(kind: FaultKind, byte: usize, bit: usize) -> BenchConfig {
    let mut cfg = timed(1000.0, vec![383], 14);
    cfg.encoders[0].faults = vec![FrameFault {
        frame: 1,
        kind,
        byte,
        bit,
        gap_bits: 0.0,
        bytes: Vec::new(),
    }];
    cfg
}

#[test]
fn a_flipped_data_bit_is_a_checksum_error_and_the_next_frame_is_read() {
    let t = run_window(&faulty(FaultKind::Flip, 3, 4));
    assert_eq!(t[0].errors, vec!["checksum"]);
    assert_eq!(t[0].positions, vec![383; 4]);
}

#[test]
fn a_wrong_parity_bit_and_a_low_stop_bit_are_flagged() {
    let mut cfg = faulty(FaultKind::Flip, 2, 9);
    cfg.parity = Parity::Even;
    let t = run_window(&cfg);
    assert_eq!(t[0].errors, vec!["parity"]);
    assert_eq!(t[0].positions, vec![383; 4]);
    let t = run_window(&faulty(FaultKind::Flip, 2, 9));
    // The low stop bit runs into the next start bit: the receiver finds its
    // next frame inside the following character, one or more framing errors.
    assert!(
        !t[0].errors.is_empty() && t[0].errors.iter().all(|&e| e == "frame"),
        "{:?}",
        t[0].errors
    );
    // Five reads, each ended by one event: the good frames and the errors.
    assert!(
        t[0].positions.iter().all(|&p| p == 383) && t[0].positions.len() + t[0].errors.len() == 5,
        "{:?}",
        t[0].positions
    );
}

#[test]
fn a_truncated_frame_and_a_gap_longer_than_t1_5_are_frame_errors() {
    let t = run_window(&faulty(FaultKind::Truncate, 3, 0));
    assert_eq!(t[0].errors, vec!["frame"]);
    assert_eq!(t[0].positions, vec![383; 4]);
    let mut cfg = faulty(FaultKind::Gap, 2, 0);
    cfg.encoders[0].faults[0].gap_bits = 20.0;
    let t = run_window(&cfg);
    assert_eq!(t[0].errors, vec!["frame", "frame"]);
    assert_eq!(t[0].positions, vec![383; 3]);
    // A gap shorter than 1.5 characters is no fault.
    cfg.encoders[0].faults[0].gap_bits = 10.0;
    let t = run_window(&cfg);
    assert!(t[0].errors.is_empty());
    assert_eq!(t[0].positions, vec![383; 5]);
}

#[test]
fn noise_bytes_and_a_false_ff_81_in_the_data_cannot_fool_the_host() {
    // The position holds FF 81 in its data bytes: 0xFF81 at 16 bits.
    let mut cfg = timed(2000.0, vec![0xFF81], 16);
    cfg.ops = listen(11);
    let t = run_window(&cfg);
    assert_eq!(t[0].positions, vec![0xFF81; 11]);
    assert!(t[0].errors.is_empty());
    // Noise just before frame 1, back to back with it: the host loses sync,
    // flags it once, and hunts on the checksum and length to the next frame.
    cfg.encoders[0].faults = vec![FrameFault {
        frame: 1,
        kind: FaultKind::Noise,
        byte: 0,
        bit: 0,
        gap_bits: 0.0,
        bytes: vec![0xFF, 0x81, 0xFF],
    }];
    let t = run_window(&cfg);
    assert_eq!(t[0].errors.len(), 1, "{:?}", t[0].errors);
    assert!(
        t[0].positions.iter().all(|&p| p == 0xFF81),
        "{:?}",
        t[0].positions
    );
    assert!(t[0].positions.len() >= 10, "{:?}", t[0].positions);
}

#[test]
fn an_answer_from_the_wrong_address_and_no_answer_are_flagged() {
    let mut cfg = three_on_a_bus();
    cfg.encoders[1].faults = vec![FrameFault {
        frame: 0,
        kind: FaultKind::Retag,
        byte: 0,
        bit: 0,
        gap_bits: 0.0,
        bytes: vec![0xB3],
    }];
    cfg.host.timeout_us = 2000.0;
    let (t, _) = run(&cfg);
    assert_eq!(t[1].errors, vec!["address"]);
    assert!(t[1].positions.is_empty());
    cfg.encoders[1].faults[0].kind = FaultKind::Silent;
    let (t, _) = run(&cfg);
    assert_eq!(t[1].errors, vec!["timeout"]);
    assert_eq!(t[2].positions, vec![0x3333]);
}

#[test]
fn stale_data_is_flagged_when_frames_stop() {
    let mut cfg = timed(1000.0, vec![9], 14);
    cfg.encoders[0].faults = (1..5)
        .map(|frame| FrameFault {
            frame,
            kind: FaultKind::Silent,
            byte: 0,
            bit: 0,
            gap_bits: 0.0,
            bytes: Vec::new(),
        })
        .collect();
    cfg.ops = listen(3);
    cfg.host.timeout_us = 10_000.0;
    let t = run_window(&cfg);
    // Frames at 1, 6, 7 ms get through; 3 refresh periods after the one at 1 ms: stale at 4 ms.
    assert_eq!(t[0].positions, vec![9; 3]);
    assert_eq!(t[0].errors, vec!["stale"]);
}

#[test]
fn a_second_driver_on_the_bus_is_seen_as_contention_and_flagged() {
    let mut cfg = three_on_a_bus();
    cfg.ops = vec![op(OpKind::Read, 1)];
    // The answer starts ~0.46 ms after the command (3 chars at 115200 plus 100 µs).
    cfg.second_drivers = vec![SecondDriver {
        at_us: 700.0,
        bytes: vec![0x00, 0x00],
        ..SecondDriver::default()
    }];
    let bench = cfg.bench().unwrap();
    let mut bench = bench;
    while !model::Testbench::finished(&bench) {
        model::Testbench::step(&mut bench, None);
    }
    assert!(bench.fault_contention_cycles() > 0);
    let t = model::Testbench::into_transactions(bench);
    assert!(!t[0].errors.is_empty(), "{:?}", t[0]);
    assert!(t[0].positions.is_empty());
}

#[test]
fn baud_mismatch_inside_plus_minus_3_percent_costs_nothing_and_beyond_the_tolerance_every_frame_is_flagged(
) {
    for err in [-3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0] {
        let mut cfg = timed(1000.0, vec![0x2AAA], 14);
        cfg.encoders[0].baud_error_percent = err;
        let t = run_window(&cfg);
        assert_eq!(t[0].positions, vec![0x2AAA; 5], "{err} %");
        assert!(t[0].errors.is_empty(), "{err} %");
    }
    for err in [-8.0, 8.0] {
        let mut cfg = timed(1000.0, vec![0x2AAA], 14);
        cfg.encoders[0].baud_error_percent = err;
        let t = run_window(&cfg);
        assert!(t[0].positions.is_empty(), "{err} %: {:?}", t[0].positions);
        assert!(t[0].errors.len() >= 5, "{err} %: {:?}", t[0].errors);
    }
}

#[test]
fn a_campaign_of_100_000_random_corruptions_flags_every_one_the_frame_checks_can_see() {
    let report = campaign::run(100_000, 8, 2026);
    println!("SAR58K24 asynchronous frames, corruption campaign:\n{report}");
    assert_eq!(report.total(), 100_000);
    let one = report.by_flips[&1];
    assert!(
        one.undetected * 1000 < one.total(),
        "one inverted bit escapes only through a re-framed character: {one:?}"
    );
    assert_eq!(
        report.disagreements, 0,
        "the host flags exactly what the checks can see"
    );
    assert_eq!(
        report.lost_recoveries, 0,
        "the clean frame after a corruption is always read"
    );
    assert!(
        report.blind.total() > 0,
        "the campaign met sum-blind corruptions"
    );
}

#[test]
fn a_pair_of_opposite_flips_of_the_same_bit_in_two_bytes_escapes_the_sum_as_promised() {
    // 0x1234 at 16 bits: FF 81 12 34 sum. Bit 2 of 0x12 is 0 (data level 3),
    // bit 2 of 0x34 is 1: +4 and -4 cancel.
    let clean = campaign::levels(&frames::encode(0x1234, 16));
    let mut c = clean.clone();
    c[2 * 10 + 3] = !c[2 * 10 + 3];
    c[3 * 10 + 3] = !c[3 * 10 + 3];
    assert!(campaign::blind(&c, 16));
    assert_eq!(campaign::judge(16, &c, &clean, 0x1234), (false, true));
    // One of them alone is seen.
    c[3 * 10 + 3] = !c[3 * 10 + 3];
    assert!(!campaign::blind(&c, 16));
    assert_eq!(campaign::judge(16, &c, &clean, 0x1234), (true, true));
}

#[test]
fn an_inverted_start_bit_re_frames_a_character_and_the_sum_sees_it_unless_it_matches_by_chance() {
    // Found by the campaign: FF 81 9A 9D 5B 12 (24 bits), start bit of 5B
    // inverted: the receiver starts at 5B's first 0 data bit and reads new
    // bytes whose sum happens to match. The host cannot know; the bit-level
    // reference agrees.
    let frame = [0xFF, 0x81, 0x9A, 0x9D, 0x5B, 0x12];
    let clean = campaign::levels(&frame);
    let mut c = clean.clone();
    c[40] = !c[40];
    assert!(campaign::blind(&c, 24));
    assert!(!campaign::judge(24, &c, &clean, 0x9A9D5B).0);
    // Its neighbour with another data byte is caught.
    let frame = frames::encode(0x9A9D5C, 24);
    let mut c = campaign::levels(&frame);
    c[40] = !c[40];
    assert!(!campaign::blind(&c, 24));
    assert!(campaign::judge(24, &c, &campaign::levels(&frame), 0x9A9D5C).0);
}

#[test]
fn a_run_time_position_replaces_the_list_from_the_next_acquisition_on() {
    // Timed send at 1 kHz: frame k carries positions[k] until set_position,
    // then every frame carries the position set (closed-loop benches).
    let cfg = timed(1000.0, vec![10, 11, 12, 13], 14);
    let mut enc = Encoder::new(cfg.encoder_config(0).unwrap()).unwrap();
    let idle = EncoderIn {
        rx: true,
        trigger: true,
        clr: true,
    };
    let mut cycles = 0u64;
    while enc.sent().len() < 2 {
        enc.step(&idle);
        cycles += 1;
        assert!(cycles < 1_000_000);
    }
    enc.set_position(0x1234).unwrap();
    while enc.sent().len() < 4 {
        enc.step(&idle);
    }
    assert_eq!(
        enc.sent().iter().map(|f| f.position).collect::<Vec<_>>(),
        vec![10, 11, 0x1234, 0x1234]
    );
    assert_eq!(enc.sent()[2].bytes, frames::encode(0x1234, 14));
    // 14 bits: 2^14 does not fit, and is refused by name.
    let e = enc.set_position(1 << 14).unwrap_err().to_string();
    assert!(e.contains("position") && e.contains("14 bits"), "{e}");
}

#[test]
fn a_replaced_byte_keeps_the_checksum_right_and_is_read_as_sent() {
    // Replace: byte 3 of the 16-bit frame (the low data byte) becomes 0x55,
    // the checksum recomputed: a well-formed frame the host reads as 0x1255.
    let mut cfg = timed(1000.0, vec![0x1234], 16);
    cfg.encoders[0].faults = vec![FrameFault {
        frame: 1,
        kind: FaultKind::Replace,
        byte: 3,
        bit: 0,
        gap_bits: 0.0,
        bytes: vec![0x55],
    }];
    cfg.ops = listen(3);
    let t = run_window(&cfg);
    assert_eq!(t[0].positions, vec![0x1234, 0x1255, 0x1234]);
    assert!(t[0].errors.is_empty(), "{:?}", t[0].errors);
    // The checksum byte itself cannot be replaced (the emulator recomputes it).
    cfg.encoders[0].faults[0].byte = 4;
    let e = cfg.validate().unwrap_err().to_string();
    assert!(e.contains("faults[0]") && e.contains("replace"), "{e}");
    // An inserted character is a Modbus fault: a SAR58K24 frame has one length.
    cfg.encoders[0].faults[0] = FrameFault {
        frame: 1,
        kind: FaultKind::Insert,
        byte: 2,
        bit: 0,
        gap_bits: 0.0,
        bytes: vec![0x55],
    };
    let e = cfg.validate().unwrap_err().to_string();
    assert!(
        e.contains("faults[0].kind") && e.contains("one length"),
        "{e}"
    );
}

#[test]
fn an_unanswered_zeroing_command_ends_when_sent_and_a_glitch_on_the_bus_is_no_character() {
    // answer_zeroing = false (ZERO_ANSWER = 0): BC AA C4 zeroes, no answer
    // awaited; a 2 µs low glitch (under half a bit) is rejected by the receiver.
    let mut cfg = three_on_a_bus();
    cfg.encoders = vec![EncoderSettings {
        address: 4,
        bits: 16,
        positions: vec![1000, 1000, 1500],
        answer_zeroing: false,
        ..EncoderSettings::default()
    }];
    // The read after the zeroing 1 ms later; the glitch on the idle bus between.
    cfg.ops = vec![
        op(OpKind::Read, 4),
        op(OpKind::Zero, 4),
        Operation {
            gap_us: 1000.0,
            ..op(OpKind::Read, 4)
        },
    ];
    cfg.second_drivers = vec![SecondDriver {
        at_us: 2000.0,
        glitch_ns: 2000.0,
        ..SecondDriver::default()
    }];
    let (t, _) = run(&cfg);
    assert_eq!(t[0].positions, vec![1000]);
    assert!(
        t[1].positions.is_empty()
            && t[1].errors.is_empty()
            && t[1].wire_answers.iter().all(|a| a.is_empty()),
        "{:?}",
        t[1]
    );
    // Zeroed at the raw 1000 the next acquisition would read: it reads 1000 - 1000.
    assert_eq!(
        (t[2].positions.clone(), t[2].errors.clone()),
        (vec![0], vec![])
    );
    // A second driver with neither bytes nor a glitch is refused by name.
    cfg.second_drivers[0].glitch_ns = 0.0;
    assert!(cfg
        .validate()
        .unwrap_err()
        .to_string()
        .contains("second_drivers[0]"));
}
