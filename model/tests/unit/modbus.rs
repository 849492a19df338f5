//! Modbus RTU end to end: the seed's requests, polling at 19200 and
//! 115200, the address query and change, exceptions, and the faults.

use model::modbus::*;
use model::testbench::run_to_end;
use model::uart::{FaultKind, FrameFault, Parity};
use model::Setup;

fn run(cfg: &BenchConfig) -> Vec<Transaction> {
    run_to_end(cfg.bench().unwrap()).transactions
}

fn read(address: u8, count: u8) -> Operation {
    Operation {
        op: OpKind::Read,
        address,
        count,
        gap_us: 100.0,
        new_address: 0,
    }
}

fn fault(kind: FaultKind, byte: usize, bit: usize) -> FrameFault {
    FrameFault {
        frame: 0,
        kind,
        byte,
        bit,
        gap_bits: 0.0,
        bytes: Vec::new(),
    }
}

#[test]
fn seed_001_read_one_register_at_factory_defaults() {
    // Seed 001, 3.1.7 (3) and (5) ①: address 1, 19200 baud, no parity;
    // 01 03 00 00 00 01 84 0A answered 01 03 02 <hi> <lo> <CRC lo> <CRC hi>.
    let cfg = BenchConfig::default();
    let t = &run(&cfg)[0];
    assert_eq!(t.request, [0x01, 0x03, 0x00, 0x00, 0x00, 0x01, 0x84, 0x0A]);
    assert_eq!(t.wire_requests, vec![t.request.clone()]);
    assert_eq!(t.received, frames::read_answer(1, 1, 383));
    assert_eq!(t.wire_answers, vec![t.received.clone()]);
    assert_eq!(t.value, Some(383));
    assert!(t.errors.is_empty());
}

#[test]
fn seed_001_read_two_registers_for_a_24_bit_encoder() {
    // Seed 001, 3.1.7 (5) ②: 01 03 00 00 00 02 C4 0B, answer 01 03 04 <4 bytes high first> CRC.
    let mut cfg = BenchConfig::default();
    cfg.devices[0].bits = 24;
    cfg.devices[0].positions = vec![0x12_3456];
    cfg.ops = vec![read(1, 2)];
    let t = &run(&cfg)[0];
    assert_eq!(t.request, [0x01, 0x03, 0x00, 0x00, 0x00, 0x02, 0xC4, 0x0B]);
    assert_eq!(t.received[..7], [0x01, 0x03, 0x04, 0x00, 0x12, 0x34, 0x56]);
    assert_eq!(t.value, Some(0x12_3456));
    assert_eq!(t.angle_deg, Some(model::angle::angle_deg(0x12_3456, 24)));
}

#[test]
fn seed_001_address_query_ff_a0_40_38() {
    // Seed 001, 3.1.7 (5) ③: FF A0 40 38 answered FF A0 <address> CRC.
    let mut cfg = BenchConfig::default();
    cfg.devices[0].address = 0x2A;
    cfg.ops = vec![Operation {
        op: OpKind::Query,
        address: 0,
        count: 0,
        gap_us: 0.0,
        new_address: 0,
    }];
    let t = &run(&cfg)[0];
    assert_eq!(t.wire_requests, vec![vec![0xFF, 0xA0, 0x40, 0x38]]);
    assert_eq!(t.received, frames::address_answer(0x2A));
    assert_eq!(t.station, Some(0x2A));
}

#[test]
fn polling_at_19200_and_115200_keeps_t35_between_frames() {
    for (baud, t35_us) in [(19_200.0, 3.5 * 10.0 / 19_200.0 * 1e6), (115_200.0, 1750.0)] {
        let mut cfg = BenchConfig {
            baud,
            ..BenchConfig::default()
        };
        cfg.devices[0].positions = vec![10, 20, 30, 40];
        cfg.ops = (0..4)
            .map(|_| Operation {
                gap_us: 0.0,
                ..read(1, 1)
            })
            .collect();
        let bench = cfg.bench().unwrap();
        let m = cfg.master_config().unwrap();
        assert!(
            (m.t35_clocks as f64 / 10.0 - t35_us).abs() < 0.1,
            "{baud}: {}",
            m.t35_clocks
        );
        let r = run_to_end(bench);
        let t = &r.transactions;
        assert_eq!(
            t.iter().map(|t| t.value).collect::<Vec<_>>(),
            vec![Some(10), Some(20), Some(30), Some(40)],
            "{baud}"
        );
        // A poll is the request (8 characters), the device's t3.5 and
        // 100 µs turnaround, the answer (7), and the master's t3.5; the
        // device and the master end a frame t3.5 after its last stop-bit
        // sample, half a bit early.
        let char_us = 10.0 / baud * 1e6;
        let min_us = 8.0 * char_us + t35_us + 100.0 + 7.0 * char_us + t35_us - char_us / 10.0;
        for w in t.windows(2) {
            let us = (w[1].start_cycle - w[0].start_cycle) as f64 / 10.0;
            assert!(us >= min_us, "{baud}: {us} µs < {min_us} µs");
        }
    }
}

#[test]
fn gray_positions_are_decoded() {
    let mut cfg = BenchConfig::default();
    cfg.devices[0].gray = true;
    cfg.devices[0].positions = vec![0xABCD];
    assert_eq!(run(&cfg)[0].value, Some(0xABCD));
}

#[test]
fn exceptions_for_count_and_address_and_unknown_function() {
    let mut cfg = BenchConfig {
        ops: vec![read(1, 3), read(1, 0), read(1, 1)],
        ..BenchConfig::default()
    };
    let t = run(&cfg);
    assert_eq!(
        (t[0].exception, t[0].errors.clone()),
        (Some(2), vec!["exception"])
    );
    assert_eq!(t[0].received[..3], [0x01, 0x83, 0x02]);
    assert_eq!(
        (t[1].exception, t[1].errors.clone()),
        (Some(3), vec!["exception"])
    );
    assert_eq!(t[2].value, Some(383));
    // One register cannot hold a 24-bit position: exception 03.
    cfg.devices[0].bits = 24;
    cfg.ops = vec![read(1, 1)];
    assert_eq!(run(&cfg)[0].exception, Some(3));
    // Function 04 is not supported: 01.
    let mut d = Device::new(cfg.device_config(0).unwrap()).unwrap();
    let (v, a) = d.respond(&frames::with_crc(&[0x01, 0x04, 0x00, 0x00, 0x00, 0x01]));
    assert_eq!(
        (v, a[..3].to_vec()),
        (Verdict::Answered, vec![0x01, 0x84, 0x01])
    );
}

#[test]
fn the_address_change_by_function_06_takes_effect_from_the_next_request() {
    let cfg = BenchConfig::default();
    let mut d = Device::new(cfg.device_config(0).unwrap()).unwrap();
    let write = frames::write_request(1, frames::ADDRESS_REGISTER, 7);
    assert_eq!(d.respond(&write), (Verdict::Answered, write.clone()));
    assert_eq!(d.address(), 7);
    assert_eq!(
        d.respond(&frames::read_request(1, 1)).0,
        Verdict::NotAddressed
    );
    assert_eq!(
        d.respond(&frames::read_request(7, 1)).1,
        frames::read_answer(7, 1, 383)
    );
    assert_eq!(
        d.respond(&frames::address_query()).1,
        frames::address_answer(7)
    );
    // Out of range, or another register: exceptions 03 and 02, address kept.
    assert_eq!(
        d.respond(&frames::write_request(7, frames::ADDRESS_REGISTER, 248))
            .1[..3],
        [7, 0x86, 3]
    );
    assert_eq!(
        d.respond(&frames::write_request(7, 0x0011, 5)).1[..3],
        [7, 0x86, 2]
    );
    assert_eq!(d.address(), 7);
}

#[test]
fn no_answer_to_a_broadcast_another_address_or_a_bad_crc() {
    let mut cfg = BenchConfig::default();
    cfg.master.timeout_us = 3000.0;
    cfg.ops = vec![read(0, 1), read(5, 1), read(1, 1)];
    let bench = cfg.bench().unwrap();
    let mut bench = bench;
    while !model::Testbench::finished(&bench) {
        model::Testbench::step(&mut bench, None);
    }
    let seen: Vec<Verdict> = bench.devices()[0]
        .seen()
        .iter()
        .map(|s| s.verdict.clone())
        .collect();
    assert_eq!(
        seen,
        vec![
            Verdict::NotAddressed,
            Verdict::NotAddressed,
            Verdict::Answered
        ]
    );
    let t = model::Testbench::into_transactions(bench);
    assert_eq!(t[0].errors, vec!["timeout"]);
    assert_eq!(t[1].errors, vec!["timeout"]);
    assert_eq!(t[2].value, Some(383));
    let mut d = Device::new(cfg.device_config(0).unwrap()).unwrap();
    let mut bad = frames::read_request(1, 1);
    bad[7] ^= 1;
    assert_eq!(d.respond(&bad).0, Verdict::Discarded);
}

#[test]
fn a_crc_error_a_parity_error_and_a_framing_error_are_flagged_separately() {
    let mut cfg = BenchConfig::default();
    cfg.devices[0].faults = vec![fault(FaultKind::Flip, 3, 2)];
    assert_eq!(run(&cfg)[0].errors, vec!["crc"]);
    cfg.parity = Parity::Odd;
    cfg.devices[0].faults = vec![fault(FaultKind::Flip, 3, 9)];
    assert_eq!(run(&cfg)[0].errors, vec!["parity"]);
    // Parity and stop bit both wrong in two characters: both flags.
    cfg.devices[0].faults = vec![fault(FaultKind::Flip, 3, 9), fault(FaultKind::Flip, 5, 10)];
    assert_eq!(run(&cfg)[0].errors, vec!["parity", "framing"]);
    cfg.parity = Parity::None;
    cfg.devices[0].faults = vec![fault(FaultKind::Flip, 6, 9)];
    assert_eq!(run(&cfg)[0].errors, vec!["framing"]);
    // Even parity, good answer.
    cfg.parity = Parity::Even;
    cfg.devices[0].faults = Vec::new();
    assert_eq!(run(&cfg)[0].value, Some(383));
}

#[test]
fn a_gap_longer_than_t15_inside_the_answer_and_a_truncated_answer_are_frame_errors() {
    let mut cfg = BenchConfig::default();
    let mut f = fault(FaultKind::Gap, 4, 0);
    f.gap_bits = 20.0; // 2 characters > t1.5
    cfg.devices[0].faults = vec![f.clone()];
    assert_eq!(run(&cfg)[0].errors, vec!["gap"]);
    f.gap_bits = 10.0; // 1 character < t1.5
    cfg.devices[0].faults = vec![f];
    assert!(run(&cfg)[0].errors.is_empty());
    cfg.devices[0].faults = vec![fault(FaultKind::Truncate, 5, 0)];
    assert_eq!(run(&cfg)[0].errors, vec!["crc"]);
    cfg.devices[0].faults = vec![fault(FaultKind::Truncate, 3, 0)];
    assert_eq!(run(&cfg)[0].errors, vec!["length"]);
}

#[test]
fn a_request_with_a_gap_longer_than_t15_is_discarded_by_the_device() {
    let cfg = BenchConfig::default();
    let dc = cfg.device_config(0).unwrap();
    let mut d = Device::new(dc.clone()).unwrap();
    let mut tx = model::uart::Transmitter::new(dc.period_ps, 19_200.0, 0.0, 0.0, 1);
    let req = frames::read_request(1, 1);
    for (i, &b) in req.iter().enumerate() {
        tx.send(b, 0.0, if i == 4 { 20.0 } else { 0.0 });
    }
    for _ in 0..200_000 {
        d.step(tx.step());
    }
    assert_eq!(d.seen().len(), 1);
    assert_eq!(d.seen()[0].verdict, Verdict::Discarded);
}

#[test]
fn an_answer_from_the_wrong_address_no_answer_and_noise_are_flagged() {
    let mut cfg = BenchConfig::default();
    let mut f = fault(FaultKind::Retag, 0, 0);
    f.bytes = vec![0x02];
    cfg.devices[0].faults = vec![f];
    assert_eq!(run(&cfg)[0].errors, vec!["address"]);
    cfg.devices[0].faults = vec![fault(FaultKind::Silent, 0, 0)];
    assert_eq!(run(&cfg)[0].errors, vec!["timeout"]);
    let mut n = fault(FaultKind::Noise, 0, 0);
    n.bytes = vec![0x55];
    cfg.devices[0].faults = vec![n];
    assert_eq!(run(&cfg)[0].errors, vec!["crc"]);
}

#[test]
fn a_second_driver_on_the_line_is_flagged() {
    // The answer starts about 4.2 + 1.8 + 0.1 ms after reset at 19200 baud.
    let cfg = BenchConfig {
        second_drivers: vec![SecondDriver {
            at_us: 6300.0,
            bytes: vec![0x00],
            ..SecondDriver::default()
        }],
        ..BenchConfig::default()
    };
    let mut bench = cfg.bench().unwrap();
    while !model::Testbench::finished(&bench) {
        model::Testbench::step(&mut bench, None);
    }
    assert!(bench.fault_contention_cycles() > 0);
    let t = model::Testbench::into_transactions(bench);
    assert!(
        !t[0].errors.is_empty() && t[0].value.is_none(),
        "{:?}",
        t[0]
    );
}

#[test]
fn baud_mismatch_inside_plus_minus_3_percent_costs_nothing_and_well_outside_every_answer_is_flagged(
) {
    for err in [-3.0, -1.5, 0.0, 1.5, 3.0] {
        let mut cfg = BenchConfig {
            baud: 115_200.0,
            ..BenchConfig::default()
        };
        cfg.devices[0].baud_error_percent = err;
        cfg.devices[0].positions = vec![0x5AA5];
        let t = &run(&cfg)[0];
        assert_eq!(
            (t.value, t.errors.clone()),
            (Some(0x5AA5), vec![]),
            "{err} %"
        );
    }
    for err in [-8.0, 8.0] {
        let mut cfg = BenchConfig {
            baud: 115_200.0,
            ..BenchConfig::default()
        };
        cfg.devices[0].baud_error_percent = err;
        cfg.devices[0].positions = vec![0x5AA5];
        let t = &run(&cfg)[0];
        assert!(t.value.is_none() && !t.errors.is_empty(), "{err} %: {t:?}");
    }
}

#[test]
fn three_devices_on_one_bus_each_answer_their_own_address() {
    let dev = |address: u8, p: u64| DeviceSettings {
        address,
        positions: vec![p],
        ..DeviceSettings::default()
    };
    let cfg = BenchConfig {
        devices: vec![dev(1, 11), dev(2, 22), dev(3, 33)],
        ops: vec![read(1, 1), read(2, 1), read(3, 1), read(2, 2)],
        ..BenchConfig::default()
    };
    let bench = cfg.bench().unwrap();
    let r = run_to_end(bench);
    assert_eq!(
        r.transactions.iter().map(|t| t.value).collect::<Vec<_>>(),
        vec![Some(11), Some(22), Some(33), Some(22)]
    );
}

#[test]
fn a_campaign_of_100_000_random_corruptions_flags_every_one_the_frame_checks_can_see() {
    let report = campaign::run(100_000, 8, 2026);
    println!("Modbus RTU answers, corruption campaign:\n{report}");
    assert_eq!(report.total(), 100_000);
    assert_eq!(
        report.disagreements, 0,
        "the master flags exactly what the checks can see"
    );
    // CRC-16 sees every 1, 2 and 3 inverted data bits; only a re-framed character could escape.
    for k in 1..=3 {
        assert!(
            report.by_flips[&k].undetected * 10_000 < report.by_flips[&k].total(),
            "{k}: {:?}",
            report.by_flips[&k]
        );
    }
}

#[test]
fn the_campaign_master_accepts_a_clean_answer_and_flags_one_inverted_bit() {
    let clean = campaign::levels(&frames::read_answer(7, 2, 0xDEAD_BEEF));
    assert!(!campaign::detected(7, 2, &clean));
    assert!(campaign::blind(&clean, 7, 2));
    let mut c = clean.clone();
    c[35] = !c[35];
    assert!(campaign::detected(7, 2, &c));
    assert!(!campaign::blind(&c, 7, 2));
}

/// The address change as a master operation (this project's reading of the
/// manual's empty "Change the device address", `docs/timing/modbus.md`):
/// function 06 to register 0x0010, the echo confirms it, the station
/// answers at its new address from the next request and no longer at the old.
#[test]
fn the_master_changes_the_device_address_and_the_device_answers_at_the_new_one() {
    let mut cfg = BenchConfig::default();
    let set = Operation {
        op: OpKind::SetAddress,
        address: 1,
        count: 1,
        gap_us: 100.0,
        new_address: 0x2A,
    };
    cfg.ops = vec![set.clone(), read(0x2A, 1), read(1, 1)];
    let t = run(&cfg);
    assert_eq!(
        t[0].request,
        vec![0x01, 0x06, 0x00, 0x10, 0x00, 0x2A, 0x09, 0xD0]
    );
    assert_eq!(t[0].received, t[0].request, "the echo");
    assert_eq!((t[0].station, t[0].errors.clone()), (Some(0x2A), vec![]));
    assert_eq!(t[1].value, Some(383));
    assert_eq!(t[2].errors, vec!["timeout"]);
    // A device whose address register is elsewhere answers exception 02.
    cfg.devices[0].address_register = 0x0020;
    let t = run(&cfg);
    assert_eq!(
        (t[0].exception, t[0].errors.clone(), t[0].station),
        (Some(2), vec!["exception"], None)
    );
    // Outside 1..247 the scenario is refused by field.
    cfg.ops = vec![Operation {
        new_address: 0,
        ..set
    }];
    let e = cfg.validate().unwrap_err().to_string();
    assert!(e.contains("ops[0].new_address"), "{e}");
}

#[test]
fn noise_inside_an_answer_a_wrong_function_and_a_wrong_byte_count_are_each_flagged() {
    let mut cfg = BenchConfig::default();
    // A noise byte 55 before the answer's fourth character: 8 characters, CRC wrong.
    let mut n = fault(FaultKind::Noise, 3, 0);
    n.bytes = vec![0x55];
    cfg.devices[0].faults = vec![n];
    let t = &run(&cfg)[0];
    assert_eq!((t.value, t.errors.clone()), (None, vec!["crc"]));
    assert_eq!(t.wire_answers[0].len(), 8, "{:?}", t.wire_answers);
    // Function 04 with a correct CRC: o_err_function.
    let mut f = fault(FaultKind::Replace, 1, 0);
    f.bytes = vec![0x04];
    cfg.devices[0].faults = vec![f.clone()];
    let t = &run(&cfg)[0];
    assert_eq!((t.value, t.errors.clone()), (None, vec!["function"]));
    // Byte count 04 to a one-register read, CRC correct: o_err_count.
    f.byte = 2;
    cfg.devices[0].faults = vec![f.clone()];
    let t = &run(&cfg)[0];
    assert_eq!((t.value, t.errors.clone()), (None, vec!["count"]));
    // A character 00 inserted before the byte count, CRC correct: 8
    // characters where a one-register read expects 7, o_err_count.
    let mut ins = fault(FaultKind::Insert, 2, 0);
    ins.bytes = vec![0x00];
    cfg.devices[0].faults = vec![ins.clone()];
    let t = &run(&cfg)[0];
    assert_eq!((t.value, t.errors.clone()), (None, vec!["count"]));
    assert_eq!(t.wire_answers[0].len(), 8, "{:?}", t.wire_answers);
    assert_eq!(
        &t.wire_answers[0][..4],
        &[0x01, 0x03, 0x00, 0x02],
        "{:?}",
        t.wire_answers
    );
    // Nothing can be inserted before the address or into the CRC.
    ins.byte = 0;
    cfg.devices[0].faults = vec![ins];
    assert!(cfg
        .validate()
        .unwrap_err()
        .to_string()
        .contains("devices[0].faults[0]"));
    // The CRC itself cannot be replaced (the emulator recomputes it).
    f.byte = 8;
    cfg.devices[0].faults = vec![f];
    assert!(cfg
        .validate()
        .unwrap_err()
        .to_string()
        .contains("devices[0].faults[0]"));
}

#[test]
fn noise_between_frames_is_no_answer_and_the_next_request_waits_for_t3_5_after_it() {
    // Two polls 20 ms apart at 19200 baud; a second driver sends 01 03 at
    // 20 ms, while the line is idle: not an answer (the master is idle),
    // and the next request starts t3.5 after the noise, never inside it.
    let cfg = BenchConfig {
        ops: vec![
            read(1, 1),
            Operation {
                gap_us: 20_000.0,
                ..read(1, 1)
            },
        ],
        second_drivers: vec![SecondDriver {
            at_us: 20_000.0,
            bytes: vec![0x01, 0x03],
            ..SecondDriver::default()
        }],
        ..BenchConfig::default()
    };
    let t = run(&cfg);
    assert_eq!(
        t.iter()
            .map(|t| (t.value, t.errors.clone()))
            .collect::<Vec<_>>(),
        vec![(Some(383), vec![]), (Some(383), vec![])]
    );
}

#[test]
fn a_run_time_position_replaces_the_list_from_the_next_answer_on() {
    let mut cfg = BenchConfig::default();
    cfg.devices[0].positions = vec![1, 2, 3];
    let mut dev = Device::new(cfg.device_config(0).unwrap()).unwrap();
    let first = dev.respond(&frames::read_request(1, 1)).1;
    dev.set_position(0xBEEF).unwrap();
    let second = dev.respond(&frames::read_request(1, 1)).1;
    let third = dev.respond(&frames::read_request(1, 1)).1;
    assert_eq!(first, frames::read_answer(1, 1, 1));
    assert_eq!(second, frames::read_answer(1, 1, 0xBEEF));
    assert_eq!(third, second);
    let e = dev.set_position(1 << 16).unwrap_err().to_string();
    assert!(e.contains("16 bits"), "{e}");
}
