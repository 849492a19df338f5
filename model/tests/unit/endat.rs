//! Behaviour of the EnDat master and encoder, each test citing what it pins down.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;

use crate::seed_reference::{make_crc_norm, make_crc_pos};
use model::endat::*;
use model::line::CableConfig;

fn run(cfg: &BenchConfig) -> Vec<Transaction> {
    Bench::new(cfg)
        .expect("valid scenario")
        .run_to_end()
        .transactions
}

fn commands(ts: &[Transaction]) -> Vec<&Transaction> {
    ts.iter().filter(|t| t.request.is_some()).collect()
}

fn fast(clock_khz: f64, f_sys: f64, cable_m: f64) -> BenchConfig {
    let mut cfg = BenchConfig::example();
    cfg.f_sys_mhz = f_sys;
    cfg.master.clock_khz = clock_khz;
    cfg.master.delay_comp = true;
    cfg.master.recovery_short = true;
    cfg.encoder.recovery_short = true;
    cfg.encoder.t_m_us = Some(2.0);
    cfg.cable = CableConfig {
        length_m: cable_m,
        ..CableConfig::default()
    };
    cfg
}

#[test]
fn seed_crc_examples_hold_through_the_endat_helpers() {
    // Seed A4 4.4.2: MakeCrcNorm(13, 32793) = 14; MakeCrcPos(25, 0, 1, 1, 0, 104462) = 3.
    assert_eq!(crc_norm(13, 32793), 14);
    assert_eq!(make_crc_norm(13, 32793), 14);
    assert_eq!(crc_pos(false, Some(true), 104_462, 25), 3);
    assert_eq!(make_crc_pos(25, 0, 1, 1, 0, 104_462), 3);
}

#[test]
fn endat_crc_helpers_agree_with_the_seeds_c_functions_on_random_inputs() {
    // Seed A4: the C functions are the reference.
    let mut rng = Pcg64Mcg::seed_from_u64(4);
    for _ in 0..20_000 {
        let (p8, p16): (u8, u16) = (rng.random(), rng.random());
        assert_eq!(
            crc_norm(p8, p16) as u32,
            make_crc_norm(p8 as u32, p16 as u32)
        );
        let bits = rng.random_range(1..=48u32);
        let v: u64 = rng.random::<u64>() & ((1u64 << bits) - 1);
        let (e1, e2, is22): (bool, bool, bool) = (rng.random(), rng.random(), rng.random());
        let reference = make_crc_pos(
            bits,
            e1 as u32,
            e2 as u32,
            is22 as u32,
            (v >> 32) as u32,
            v as u32,
        );
        assert_eq!(crc_pos(e1, is22.then_some(e2), v, bits) as u32, reference);
    }
}

#[test]
fn the_masters_lfsr_is_the_catalogue_engine() {
    // One CRC engine for everything (docs/crc.md): the master's register update is BitSerial's.
    let mut rng = Pcg64Mcg::seed_from_u64(5);
    for _ in 0..200 {
        let mut reg = 0x1F;
        let mut engine = catalogue_engine();
        for _ in 0..rng.random_range(1..80) {
            let b: bool = rng.random();
            reg = lfsr_push_for_test(reg, b);
            engine.push(b);
        }
        assert_eq!(reg, engine.register());
    }
    assert_eq!(model::crc::ENDAT_CRC5.wire_residue(), CRC_RESIDUE);
}

#[test]
fn a_type_21_position_read_returns_the_encoders_position() {
    // Seed 2.3.1.1: "Encoder send position values" 000111, F1, position LSB first, CRC.
    let mut cfg = BenchConfig::example();
    cfg.positions = vec![104_462, 0, (1 << 25) - 1];
    cfg.commands = vec![HostCommand {
        repeat: 3,
        ..HostCommand::new(Command::Pos21)
    }];
    let ts = run(&cfg);
    assert_eq!(
        ts.iter().map(|t| t.position).collect::<Vec<_>>(),
        vec![Some(104_462), Some(0), Some((1 << 25) - 1)]
    );
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:#?}");
    assert_eq!(
        ts[0].f2,
        Some(true),
        "F2 is not sent with type 2.1 commands and reads inactive"
    );
}

#[test]
fn additional_data_2_then_1_follow_the_position_after_their_selection() {
    // Seed 2.3.5, 2.4.2.2: select with 001001 + MRS code 0x4C (temperature 1) and 0x52 (acceleration).
    let mut cfg = fast(8000.0, 64.0, 20.0);
    cfg.positions = vec![12_345];
    cfg.commands = vec![
        HostCommand::with(Command::Select22, 0x4C, 0),
        HostCommand::with(Command::Select22, 0x52, 0),
        HostCommand::new(Command::Pos22),
    ];
    let ts = run(&cfg);
    let c = commands(&ts);
    assert_eq!(c[0].ad1, None);
    assert_eq!(c[1].ad1.as_deref(), Some("4c0c3b"), "{c:#?}"); // RM, I = 12, 3131 = 313.1 K
    let last = c[2];
    assert_eq!(last.position, Some(12_345));
    assert_eq!(last.ad2.as_deref(), Some("5204b0"), "{last:#?}"); // I = 18, 1200
    assert_eq!(last.ad1.as_deref(), Some("4c0c3b"));
    assert!(last.errors.is_empty(), "{last:#?}");
}

#[test]
fn delay_compensation_reads_without_error_at_8_mhz_through_0_to_100_m() {
    // Seed 2.1.2: with delay compensation 8 MHz for up to 100 m; t_D = 0.2 µs + 0.01 µs/m, ±10 %.
    let mut rng = Pcg64Mcg::seed_from_u64(8);
    for length in [0.0, 10.0, 35.0, 60.0, 100.0] {
        for tolerance in [0.9, 1.0, 1.1] {
            let mut cfg = fast(8000.0, 64.0, length);
            cfg.cable.ns_per_m = 5.0 * tolerance;
            cfg.encoder.output_delay_ns = 200.0 * tolerance;
            cfg.positions = (0..6)
                .map(|_| rng.random::<u64>() & ((1 << 25) - 1))
                .collect();
            cfg.commands = vec![HostCommand {
                repeat: 6,
                ..HostCommand::new(Command::Pos22)
            }];
            let ts = run(&cfg);
            assert_eq!(ts[0].kind, "delay_measurement");
            assert_eq!(
                ts[0].delay_cycles,
                Some(cfg.expected_delay().unwrap()),
                "{length} m ×{tolerance}"
            );
            let got: Vec<_> = commands(&ts).iter().map(|t| t.position.unwrap()).collect();
            assert_eq!(got, cfg.positions, "{length} m ×{tolerance}: {ts:#?}");
            assert!(
                commands(&ts).iter().all(|t| t.errors.is_empty()),
                "{length} m: {ts:#?}"
            );
        }
    }
}

#[test]
fn reading_word_13_gives_the_clocks_per_position() {
    // Seed 2.4.1, 2.5, 3.5.6: select 0xA1 (manufacturer parameters), read address 13 = 0x8000 | 25.
    let mut cfg = BenchConfig::example();
    cfg.commands = vec![
        HostCommand::with(Command::Select21, 0xA1, 0),
        HostCommand::with(Command::Send21, 13, 0),
    ];
    let ts = run(&cfg);
    assert_eq!(ts[0].ack, Some((0xA1, 0)));
    assert_eq!(ts[1].ack, Some((13, 0x8019)));
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:#?}");
}

#[test]
fn writing_protected_memory_is_answered_inverted_and_flagged_as_type_ii() {
    // Seed A2 4.2.2 (cause 9): write into the factory-protected manufacturer area.
    let mut cfg = BenchConfig::example();
    cfg.commands = vec![
        HostCommand::with(Command::Select21, 0xA1, 0),
        HostCommand::with(Command::Receive21, 8, 0x1234),
    ];
    let ts = run(&cfg);
    assert_eq!(ts[1].ack, Some((!8u8, !0x1234u16)));
    assert_eq!(ts[1].errors, vec!["type_ii"]);
}

#[test]
fn a_crc_valid_acknowledgement_with_other_content_is_type_ii_only_when_inverted_at_the_right_address(
) {
    // Seed A2 4.2.2: type II returns the address or the data inverted. A
    // select21 of 0xA1 with parameter 0x1234, acknowledged with a correct
    // CRC over: the data inverted at the right address (type II); the data
    // inverted under another address (a mismatch, not type II); one data bit
    // off (a mismatch); the address inverted (type II).
    let mut cfg = BenchConfig::example();
    cfg.commands = vec![HostCommand {
        repeat: 4,
        ..HostCommand::with(Command::Select21, 0xA1, 0x1234)
    }];
    let x = |request, address, data| AckXor {
        request,
        address,
        data,
    };
    cfg.faults.ack_xor = vec![
        x(0, 0, 0xFFFF),
        x(1, 0x01, 0xFFFF),
        x(2, 0, 0x0001),
        x(3, 0xFF, 0),
    ];
    let ts = run(&cfg);
    let acks: Vec<Option<(u8, u16)>> = ts.iter().map(|t| t.ack).collect();
    assert_eq!(
        acks,
        vec![
            Some((0xA1, !0x1234)),
            Some((0xA0, !0x1234)),
            Some((0xA1, 0x1235)),
            Some((!0xA1, 0x1234))
        ]
    );
    let errors: Vec<Vec<String>> = ts.iter().map(|t| t.errors.clone()).collect();
    assert_eq!(errors[0], vec!["type_ii"]);
    assert_eq!(errors[1], vec!["acknowledgement_mismatch"]);
    assert_eq!(errors[2], vec!["acknowledgement_mismatch"]);
    assert_eq!(errors[3], vec!["type_ii"]);
    // Only a request that sends a type 2.1 acknowledgement can carry the fault.
    cfg.commands.push(HostCommand::new(Command::Pos21));
    cfg.faults.ack_xor = vec![x(4, 0, 1)];
    let e = Bench::new(&cfg).err().expect("refused").to_string();
    assert!(
        e.contains("faults.ack_xor[0].request") && e.contains("pos21"),
        "{e}"
    );
}

#[test]
fn an_invalid_mode_command_gets_no_start_bit_and_is_flagged_type_i() {
    // Seed A2 4.2.1: mode bits disrupted (000000 is no mode command) → no start bit; clock high, wait t_m.
    let mut cfg = BenchConfig::example();
    cfg.commands = vec![
        HostCommand {
            raw_mode: Some(0),
            ..HostCommand::new(Command::Pos21)
        },
        HostCommand::new(Command::Pos21),
    ];
    cfg.positions = vec![5, 6];
    let ts = run(&cfg);
    assert_eq!(ts[0].errors, vec!["no_start_bit"]);
    assert_eq!(ts[0].encoder_answer, "type_i");
    assert_eq!(
        ts[1].position,
        Some(6),
        "the encoder answers again after t_m"
    );
}

#[test]
fn a_type_22_access_answered_with_type_ii_is_flagged_when_its_acknowledgement_arrives() {
    // Seed A2 4.2.2: the acknowledgement of the MRS code (I = 7) or of the memory access (I = 5) comes back with
    // the address inverted; with 2.2 commands it arrives in additional datum 1 of the next frame.
    let mut cfg = fast(4000.0, 64.0, 10.0);
    cfg.encoder.t_ac_us = 100.0;
    cfg.commands = vec![
        HostCommand::with(Command::Select22, 0x47, 0), // I = 7: acknowledge MRS code
        HostCommand::with(Command::Select22, 0xAD, 0), // OEM area 3: not in this encoder (cause 7)
        HostCommand::with(Command::Select22, 0xA1, 0), // shows ~0xAD
        HostCommand::with(Command::Select22, 0x45, 0), // shows 0xA1; I = 5 from now on
        HostCommand::with(Command::Receive22, 8, 0x1234), // write-protected (cause 9)
        HostCommand::with(Command::Select22, 0xA9, 0), // shows ~8
        HostCommand::with(Command::Receive22, 1, 0x00FF), // accepted: busy for t_ac
        HostCommand::with(Command::Receive22, 2, 0x0011), // ignored while busy
        HostCommand::new(Command::Pos22),              // still acknowledges address 1
    ];
    let ts = run(&cfg);
    let c = commands(&ts);
    let errors: Vec<Vec<String>> = c.iter().map(|t| t.errors.clone()).collect();
    let none: Vec<String> = Vec::new();
    assert_eq!(c[2].ad1.as_deref(), Some("475200"), "{c:#?}");
    assert_eq!(errors[2], vec!["type_ii"]);
    assert_eq!(errors[3], none, "0xA1 echoed as sent");
    assert_eq!(c[5].ad1.as_deref().map(|s| &s[2..4]), Some("f7"));
    assert_eq!(errors[5], vec!["type_ii"]);
    assert_eq!(errors[7], none, "address 1 acknowledged");
    assert_eq!(c[7].encoder_answer, "ignored");
    assert_eq!(
        errors[8],
        vec!["acknowledgement_mismatch"],
        "the ignored write is not acknowledged"
    );
    assert_eq!(c[1].encoder_answer, "type_ii");
}

#[test]
fn word_3_selects_recovery_time_i_at_the_next_reset() {
    // Seed 3.4.4: word 3 bit 0 / bit 1 select t_m of 1.25..3.75 µs or 10..30 µs for type 2.2 commands; like every
    // function parameter it takes effect with a reset. A master timed for the short setting is then too fast.
    let mut cfg = fast(2000.0, 64.0, 5.0);
    cfg.master.delay_comp = false;
    cfg.encoder.output_delay_ns = 120.0;
    cfg.host.gap_us = 8.0;
    let reads = HostCommand {
        repeat: 2,
        ..HostCommand::new(Command::Pos22)
    };
    cfg.commands = vec![
        reads.clone(),
        HostCommand::with(Command::Select21, 0xB9, 0),
        HostCommand::with(Command::Receive21, 3, 0x10AA),
        reads.clone(),
        HostCommand::new(Command::Reset21),
        reads,
    ];
    let ts = run(&cfg);
    let errors: Vec<Vec<String>> = commands(&ts).iter().map(|t| t.errors.clone()).collect();
    let none: Vec<String> = Vec::new();
    assert_eq!(
        errors[..6],
        vec![none.clone(); 6],
        "written but not yet active: still short"
    );
    assert_eq!(errors[6], none, "the reset itself");
    assert_eq!(errors[7], none);
    assert_eq!(
        errors[8],
        vec!["line_not_idle"],
        "8 µs after a 2.2 frame the encoder is still in its 15 µs t_m"
    );
}

#[test]
fn an_impermissible_additional_datum_is_answered_with_i_31_type_iii() {
    // Seed A2 4.2.3 (cause 13): I = 26 is not assignable → I = 31 until a valid selection.
    let mut cfg = fast(4000.0, 64.0, 10.0);
    cfg.commands = vec![
        HostCommand::with(Command::Select22, 0x5A, 0),
        HostCommand::new(Command::Pos22),
    ];
    let ts = run(&cfg);
    let c = commands(&ts);
    assert_eq!(c[1].ad2.as_deref().map(|s| &s[..2]), Some("5f"));
    assert_eq!(c[1].errors, vec!["type_iii"]);
}

#[test]
fn a_continuous_clock_reads_successive_values_with_at_most_7_low_bits_between() {
    // Seed 2.3.1.1 figure 15: continuous clock only with 000111; max 7 low bits between values.
    let mut cfg = BenchConfig::example();
    cfg.positions = vec![1000];
    cfg.step = 3;
    cfg.commands = vec![HostCommand {
        cont_values: 4,
        ..HostCommand::new(Command::Pos21)
    }];
    let ts = run(&cfg);
    assert_eq!(
        ts.iter().map(|t| t.position).collect::<Vec<_>>(),
        vec![Some(1000), Some(1003), Some(1006), Some(1009)],
        "{ts:#?}"
    );
    assert!(ts.iter().all(|t| t.errors.is_empty()));
}

#[test]
fn the_budget_equals_the_models_position_read_cycle() {
    // The RTL is tested against the model cycle for cycle; the model against the budget here.
    for (clock, f_sys, cable, comp) in [
        (1000.0, 64.0, 10.0, false),
        (8000.0, 64.0, 100.0, true),
        (2000.0, 64.0, 0.0, false),
    ] {
        let mut cfg = if comp {
            fast(clock, f_sys, cable)
        } else {
            BenchConfig::example()
        };
        cfg.master.clock_khz = clock;
        cfg.cable.length_m = cable;
        cfg.commands = vec![HostCommand {
            repeat: 2,
            ..HostCommand::new(Command::Pos22)
        }];
        let ts = run(&cfg);
        let c = commands(&ts);
        let b = budget::budget(&cfg, Command::Pos22).unwrap();
        assert!(c.iter().all(|t| t.errors.is_empty()), "{c:#?}");
        assert_eq!(
            c[1].start_cycle - c[0].start_cycle,
            b.cycle_clocks,
            "{clock} kHz: {}",
            b.render()
        );
        assert_eq!(
            c[0].done_cycle - c[0].start_cycle,
            b.latency_clocks,
            "{clock} kHz"
        );
    }
}

/// Whether two flipped bits of one CRC field (at distance `dist`) can escape the CRC:
/// x^5 + x^3 + x + 1 = (x + 1)(x^4 + x^3 + 1), and x^4 + x^3 + 1 is primitive of period 15,
/// so x^dist + 1 is a multiple of the generator exactly when 15 divides `dist`.
fn double_error_undetectable(dist: usize) -> bool {
    dist % 15 == 0
}

#[test]
fn a_corruption_campaign_detects_every_1_bit_error_and_every_2_bit_error_the_crc_can_see() {
    // Seed A4: "All single errors ... can be detected. The detection of high-order data
    // transmission errors depends on the data word length."
    let mut rng = Pcg64Mcg::seed_from_u64(2024);
    let frames = 100_000;
    let mut by_flips = [(0u64, 0u64, 0u64); 9]; // (frames, detected, undetected)
    let mut double_blind = (0u64, 0u64); // (2-bit flips 15 apart in one field, of them undetected)
    let checker = FrameChecker::new(Command::Pos22.code(), 25, true, true);
    let n = checker.frame_bits() as usize;
    let field = |i: usize| if i < 32 { 0 } else { 1 + (i - 32) / 29 };
    for _ in 0..frames {
        let pos = rng.random::<u64>() & ((1 << 25) - 1);
        let f1: bool = rng.random();
        let mut bits = vec![f1, !f1];
        bits.extend((0..25).map(|i| (pos >> i) & 1 == 1));
        bits.extend(crc_wire(crc_pos(f1, Some(!f1), pos, 25)));
        for _ in 0..2 {
            let w: u32 = rng.random::<u32>() & 0xFF_FFFF;
            bits.extend((0..24).rev().map(|i| (w >> i) & 1 == 1));
            bits.extend(crc_wire(crc_norm((w >> 16) as u8, w as u16)));
        }
        assert_eq!(bits.len(), n);
        let clean = checker.check(&bits);
        assert!(!clean.bad_head && !clean.bad_ad1 && !clean.bad_ad2 && clean.data == pos);
        let k = match rng.random_range(0..10) {
            0..=3 => 1,
            4..=6 => 2,
            _ => rng.random_range(3..=8),
        };
        let mut flipped = bits.clone();
        let mut chosen: Vec<usize> = Vec::new();
        while chosen.len() < k {
            let i = rng.random_range(0..n);
            if !chosen.contains(&i) {
                chosen.push(i);
                flipped[i] = !flipped[i];
            }
        }
        let r = checker.check(&flipped);
        let detected = r.bad_head || r.bad_ad1 || r.bad_ad2;
        by_flips[k].0 += 1;
        if detected {
            by_flips[k].1 += 1;
        } else {
            by_flips[k].2 += 1;
        }
        if k == 2 {
            let blind = field(chosen[0]) == field(chosen[1])
                && double_error_undetectable(chosen[0].abs_diff(chosen[1]));
            if blind {
                double_blind.0 += 1;
                double_blind.1 += !detected as u64;
            } else {
                assert!(
                    detected,
                    "2-bit error at {chosen:?} escaped although its distance is no multiple of 15"
                );
            }
        }
    }
    println!("EnDat 2.2 frame (F1 F2, 25-bit position, CRC, two additional data with CRCs), {frames} corrupted frames:");
    println!("flipped bits | frames | detected | undetected | undetected rate");
    let mut more = (0u64, 0u64);
    for (k, (f, d, u)) in by_flips.iter().enumerate().skip(1) {
        if *f > 0 {
            println!(
                "{k:>12} | {f:>6} | {d:>8} | {u:>10} | {:.5}",
                *u as f64 / *f as f64
            );
        }
        if k >= 3 {
            more.0 += f;
            more.1 += u;
        }
    }
    println!(
        "2-bit flips 15 apart inside one CRC field: {} of them, {} undetected (the generator's factor x^4+x^3+1 has period 15)",
        double_blind.0, double_blind.1
    );
    println!(
        "3 to 8 bits: undetected rate {:.5} (CRC-5 theoretical 2^-5 = {:.5})",
        more.1 as f64 / more.0 as f64,
        1.0 / 32.0
    );
    assert_eq!(by_flips[1].2, 0, "every single-bit error is detected");
    assert_eq!(
        by_flips[2].2, double_blind.1,
        "the only 2-bit escapes are the ones 15 apart"
    );
    assert_eq!(
        double_blind.0, double_blind.1,
        "a 2-bit error 15 apart in one field always escapes"
    );
    assert!(by_flips.iter().map(|x| x.0).sum::<u64>() >= 100_000);
    assert!((more.1 as f64 / more.0 as f64) < 1.0 / 32.0 * 1.5);
}

#[test]
fn every_2_bit_error_in_a_frame_of_at_most_15_bits_is_detected() {
    // The other side of the period-15 argument: a 2.1 frame with a 9-bit position (F1 + 9 + CRC = 15 bits).
    let checker = FrameChecker::new(Command::Pos21.code(), 9, false, false);
    let mut bits = vec![false];
    bits.extend((0..9).map(|i| (0x1A5u64 >> i) & 1 == 1));
    bits.extend(crc_wire(crc_pos(false, None, 0x1A5, 9)));
    for i in 0..bits.len() {
        for j in i + 1..bits.len() {
            let mut f = bits.clone();
            f[i] = !f[i];
            f[j] = !f[j];
            assert!(checker.check(&f).bad_head, "flips {i} {j}");
        }
    }
}

#[test]
fn a_selection_whose_frame_had_no_start_bit_is_not_taken_as_made() {
    // The type 2.2 block follows the frame: without a start bit the master stops before it, so the encoder keeps
    // its selection and the master must not expect the additional datum.
    let mut judge = LineJudge::new(25);
    let good: Vec<bool> = {
        let mut b = vec![false, true];
        b.extend((0..25).map(|i| (7u64 >> i) & 1 == 1));
        b.extend(crc_wire(crc_pos(false, Some(true), 7, 25)));
        b
    };
    judge.begin(Command::Select22.code(), 0x41, 0);
    assert!(judge.aborted(true).o_err_timeout);
    judge.end();
    judge.begin(Command::Pos22.code(), 0, 0);
    assert_eq!(
        judge.frame_bits(),
        32,
        "no additional datum after the aborted selection"
    );
    judge.begin(Command::Select22.code(), 0x41, 0);
    let out = judge.frame(&good);
    assert!(
        out.o_done && !out.o_err_crc && out.o_position == 7,
        "{out:?}"
    );
    judge.end();
    judge.begin(Command::Pos22.code(), 0, 0);
    assert_eq!(judge.frame_bits(), 32 + 29, "diagnosis selected");
}

#[test]
fn a_fault_in_a_request_the_run_never_makes_is_refused_with_the_count() {
    use model::Setup as _;
    let mut cfg = BenchConfig::example();
    let n = cfg.requests().len();
    cfg.faults.flips = vec![Flip {
        request: n - 1,
        bits: vec![2],
    }];
    assert!(cfg.validate().is_ok());
    cfg.faults.flips[0].request = n + 36;
    let e = cfg.validate().unwrap_err();
    assert_eq!(e.field(), "faults.flips[0].request");
    assert!(
        e.to_string().contains(&format!(
            "request {}, but the commands make {n} requests",
            n + 36
        )),
        "{e}"
    );
    cfg.faults.flips.clear();
    cfg.faults.dead_from = Some(n);
    assert_eq!(cfg.validate().unwrap_err().field(), "faults.dead_from");
}

#[test]
fn recovery_short_alone_takes_a_short_t_m_instead_of_refusing_the_long_default() {
    use model::Setup as _;
    let mut cfg = BenchConfig::example();
    cfg.master.clock_khz = 2000.0;
    // At 2 MHz without delay compensation the example's 10 m and 200 ns
    // output delay answer after the fixed sample point (a set-up refused).
    cfg.cable.length_m = 0.0;
    cfg.master.recovery_short = true;
    cfg.encoder.recovery_short = true;
    assert_eq!(cfg.validate(), Ok(()));
    cfg.encoder.t_m_us = Some(15.0);
    let e = cfg.validate().unwrap_err().to_string();
    assert!(
        e.contains("15 µs with encoder.recovery_short = true") && e.contains("1.25 to 3.75"),
        "{e}"
    );
}

#[test]
fn after_a_type_i_error_the_line_is_high_again_t_m_after_the_last_clock_edge() {
    // Seed A2 4.2.1: after a type I error the control sets the clock high and waits t_m
    // ("the maximum t_m of 30 µs must at least be waited before the next command"), so the
    // encoder must be ready again t_m after the last clock edge, not t_m after noticing the
    // clock stopped (which held the line low for about 2 t_m).
    for t_m21_us in [10.0, 20.0, 30.0] {
        let mut bench = BenchConfig::example();
        bench.encoder.t_m21_us = t_m21_us;
        bench.encoder.output_delay_ns = 0.0;
        let cfg = bench.encoder_config().unwrap();
        let t_m = cfg.t_m21_clocks;
        let mut enc = Encoder::new(cfg).unwrap();
        let half = 32; // 1 MHz at 64 MHz
        let mut clk = true;
        let mut now = 0u64;
        let step = |enc: &mut Encoder,
                    clk: bool,
                    n: u64,
                    now: &mut u64|
         -> Vec<(u64, model::line::Drive)> {
            (0..n)
                .map(|_| {
                    let d = enc.step(clk, false);
                    *now += 1;
                    (*now - 1, d)
                })
                .collect()
        };
        step(&mut enc, clk, 10, &mut now);
        // Mode bits 000000 (no mode command): type I; ten clock periods, then the clock stays high.
        for _ in 0..10 {
            clk = false;
            step(&mut enc, clk, half, &mut now);
            clk = true;
            step(&mut enc, clk, half, &mut now);
        }
        let last_edge = now - half;
        let after = step(&mut enc, true, 3 * t_m, &mut now);
        assert_eq!(enc.answer, model::endat::Answer::TypeI);
        assert!(
            after.iter().any(|(_, d)| d.enable && !d.level),
            "the line is held low in the recovery"
        );
        let high = after
            .iter()
            .find(|(_, d)| d.enable && d.level)
            .map(|(c, _)| *c)
            .expect("released");
        let low_for = high - last_edge;
        assert!(low_for <= t_m + 2 && low_for >= t_m, "t_m21 = {t_m21_us} us ({t_m} cycles): line released {low_for} cycles after the last edge");
        assert!(
            after
                .iter()
                .skip_while(|(c, _)| *c < high)
                .all(|(_, d)| d.enable && d.level),
            "stays high"
        );
    }
}

/// Odd dividers for the EnDat clock and the measuring
/// clock. 4 MHz from 100 MHz (f_sys / 25) is 13 cycles high and 12 low; from
/// 45 MHz both clocks are odd (3 MHz = f_sys / 15: 8 and 7; 200 kHz =
/// f_sys / 225: 113 and 112). The delay measurement finds the expected
/// delay, the drift check centres on the high phase, and every position reads back.
#[test]
fn odd_dividers_split_high_first_and_read_every_position() {
    use model::Setup;
    for (mhz, khz, high, low, meas) in [
        (100.0, 4000.0, 13, 12, (250, 250)),
        (45.0, 3000.0, 8, 7, (113, 112)),
    ] {
        let mut cfg = fast(khz, mhz, 50.0);
        cfg.master.meas_clock_khz = 200.0;
        cfg.positions = vec![0, 33554431, 104462, 16777216];
        cfg.commands = vec![HostCommand {
            repeat: 4,
            ..HostCommand::new(Command::Pos22)
        }];
        let m = cfg
            .master_config()
            .unwrap_or_else(|e| panic!("{khz} kHz from {mhz} MHz refused: {e}"));
        assert_eq!(
            (
                m.high_clocks,
                m.low_clocks,
                m.meas_high_clocks,
                m.meas_low_clocks
            ),
            (high, low, meas.0, meas.1)
        );
        let params = cfg.verilog_parameters().unwrap();
        assert!(
            params.contains(&("HIGH_CLOCKS", high)) && params.contains(&("LOW_CLOCKS", low)),
            "{params:?}"
        );
        assert_eq!(
            params.iter().any(|(n, _)| *n == "MEAS_HIGH_CLOCKS"),
            meas.0 != meas.1,
            "{params:?}"
        );
        let ts = run(&cfg);
        assert_eq!(ts[0].kind, "delay_measurement");
        assert_eq!(
            ts[0].delay_cycles,
            Some(cfg.expected_delay().unwrap()),
            "{mhz} MHz"
        );
        let got: Vec<_> = commands(&ts).iter().map(|t| t.position.unwrap()).collect();
        assert_eq!(got, cfg.positions, "{mhz} MHz: {ts:#?}");
        assert!(
            commands(&ts).iter().all(|t| t.errors.is_empty()),
            "{mhz} MHz: {ts:#?}"
        );
        crate::phases::assert_split(
            Bench::new(&cfg).unwrap(),
            0,
            high,
            low,
            &format!("EnDat {khz} kHz from {mhz} MHz"),
        );
    }
}

/// Seed 2.3.2 ("on-off ratio error", read as each phase within 45 % to
/// 55 % of the period): an odd divider below 10 departs from 1:1 by more
/// than 10 % and is refused, naming the clock field; a divider below 8 is
/// refused as before.
#[test]
fn odd_dividers_beyond_the_on_off_ratio_error_and_dividers_below_eight_are_refused() {
    let cfg = fast(8000.0, 72.0, 10.0); // f_sys / 9: 5 high, 4 low, 11 % off
    let e = cfg.master_config().unwrap_err();
    assert_eq!(e.field(), "master.clock_khz");
    assert!(e.to_string().contains("10 %"), "{e}");
    assert!(
        fast(8000.0, 88.0, 10.0).master_config().is_ok(),
        "f_sys / 11 is 4.5 % off"
    );
    let e = fast(16000.0, 64.0, 10.0).master_config().unwrap_err(); // f_sys / 4
    assert_eq!(e.field(), "master.clock_khz");
    assert!(e.to_string().contains("at least 8"), "{e}");
}

#[test]
fn an_early_start_bit_ends_the_read_sooner_and_fools_the_delay_counter_into_saturation() {
    // Fault `early_start`: the encoder ignores t_cal (seed 2.3.2: at least 10.5 clock periods) and sends its
    // start bit 1 or 2 rising edges after R_off instead of R_off + 3 at the earliest.
    let mut cfg = BenchConfig::example();
    cfg.encoder.t_cal_us = 0.0;
    let plain = run(&cfg);
    cfg.faults.early_start = Some(2);
    let early = run(&cfg);
    // A polling master reads the same position, one clock period (64 cycles at 1 MHz) sooner.
    assert_eq!(
        (early[0].position, &early[0].errors),
        (plain[0].position, &plain[0].errors)
    );
    assert_eq!(plain[0].done_cycle - early[0].done_cycle, 64);
    // Its power-on measurement: the start bit (at R9) reaches the master before R10 restarts the delay counter,
    // which after t_b (more than 1 ms at 257 MHz) and after reset holds its saturated 65535: four equal
    // captures, accepted as a delay of 65535 cycles. The read after it samples at that delay and fails.
    let cfg = BenchConfig {
        f_sys_mhz: 257.0,
        block_gap_clocks: 26,
        master: MasterSettings {
            clock_khz: 100.0,
            delay_comp: true,
            meas_retries: 2,
            ..MasterSettings::default()
        },
        faults: FaultSettings {
            early_start: Some(1),
            ..FaultSettings::default()
        },
        ..BenchConfig::default()
    };
    let t = run(&cfg);
    assert_eq!(
        (t[0].kind.as_str(), t[0].delay_cycles, t[0].errors.len()),
        ("delay_measurement", Some(65535), 0)
    );
    assert!(t[1].errors.contains(&"crc".to_string()), "{:?}", t[1]);
    // Only 1 and 2 are early starts.
    for bad in [0, 3] {
        let cfg = BenchConfig {
            faults: FaultSettings {
                early_start: Some(bad),
                ..FaultSettings::default()
            },
            ..BenchConfig::example()
        };
        let e = Bench::new(&cfg).err().expect("refused");
        assert_eq!(e.field(), "faults.early_start");
        assert!(e.to_string().contains("give 1 or 2"), "{e}");
    }
}

/// With delay compensation the reads sample after the measured round trip,
/// but the measurement's own frames (seed 2.1.2: "with reduced clock pulse
/// frequency (100 kHz to 200 kHz)") are sampled at the fixed point, a high
/// phase of the measurement clock after the rising edge: at 500 kHz and
/// 200 kHz measuring, from 229 m at 32 MHz every measurement failed as
/// `delay_measurement_inconsistent`, every read as `not_calibrated`, and
/// the scenario was accepted. The model's own runs are the check of
/// `late_answer`: it says "late" exactly where the measurement fails, the
/// scenario is refused on `cable.length_m`, and each fix it gives (the
/// measurement clock it names, the least `sample_delay_ns`) reads cleanly.
#[test]
fn a_round_trip_beyond_the_measurement_clocks_sample_point_is_refused_where_no_read_succeeds() {
    let mut late_seen = 0;
    for (f_sys, meas_khz, lengths) in [
        (32.0, 200.0, (200..=260).step_by(3)),
        (64.0, 200.0, (200..=260).step_by(3)),
        (32.0, 100.0, (440..=500).step_by(3)),
    ] {
        for len in lengths {
            let mut cfg = BenchConfig::example();
            cfg.f_sys_mhz = f_sys;
            cfg.master.clock_khz = 500.0;
            cfg.master.delay_comp = true;
            cfg.master.meas_clock_khz = meas_khz;
            cfg.cable.length_m = len as f64;
            let what = format!("{f_sys} MHz, measuring at {meas_khz} kHz, {len} m");
            let ts = run(&cfg);
            let measured = ts
                .iter()
                .any(|t| t.kind == "delay_measurement" && t.errors.is_empty());
            let reads_ok = commands(&ts).iter().all(|t| t.errors.is_empty());
            let late = cfg.late_answer().unwrap();
            assert_eq!(late.is_none(), measured && reads_ok, "{what}: {late:?}");
            let Some(_) = late else {
                assert!(model::Setup::validate(&cfg).is_ok(), "{what}");
                continue;
            };
            late_seen += 1;
            assert!(
                commands(&ts)
                    .iter()
                    .all(|t| t.errors.iter().any(|e| e == "not_calibrated")),
                "{what}"
            );
            let e = model::Setup::validate(&cfg).unwrap_err();
            assert_eq!(e.field(), "cable.length_m", "{what}: {e}");
            let text = e.to_string();
            assert!(text.contains("delay_measurement_inconsistent"), "{text}");
            let mut fixes = Vec::new();
            if let Some(k) = text.split("master.meas_clock_khz = ").nth(1) {
                let mut c = cfg.clone();
                c.master.meas_clock_khz = k.split(' ').next().unwrap().parse().unwrap();
                fixes.push(c);
            }
            if let Some(ns) = text.split("master.sample_delay_ns = ").nth(1) {
                let mut c = cfg.clone();
                c.master.sample_delay_ns = ns.split(' ').next().unwrap().parse().unwrap();
                fixes.push(c);
            }
            assert!(!fixes.is_empty(), "{what}: {text}");
            for c in fixes {
                assert!(model::Setup::validate(&c).is_ok(), "{what}: {text}");
                let ts = run(&c);
                assert!(
                    ts.iter().all(|t| t.errors.is_empty()),
                    "{what}: {text}: {:?}",
                    ts.iter().map(|t| (&t.kind, &t.errors)).collect::<Vec<_>>()
                );
            }
        }
    }
    assert!(late_seen >= 20, "{late_seen} late set-ups");
}

/// Without delay compensation the master samples at a fixed point after each
/// falling clock edge; a cable whose round trip comes later fails every read
/// as `line_not_driven` (500 kHz and 1 MHz beyond about 100 m, 2 MHz sooner).
/// The model's own runs, from 0 to 200 m, are the check of
/// `late_answer`: it says "late" exactly where every read fails, the
/// scenario is then refused on `cable.length_m` with `delay_comp` and the
/// least `sample_delay_ns`, and with either fix every read is clean.
#[test]
fn a_round_trip_beyond_the_fixed_sample_point_is_refused_where_every_read_fails() {
    let mut late_seen = 0;
    for (f_sys, khz) in [(64.0, 500.0), (64.0, 1000.0), (50.0, 2000.0)] {
        for len in (0..=200).step_by(5) {
            let mut cfg = BenchConfig::example();
            cfg.f_sys_mhz = f_sys;
            cfg.master.clock_khz = khz;
            cfg.cable.length_m = len as f64;
            let reads = run(&cfg);
            let reads = commands(&reads);
            let what = format!("{khz} kHz, {len} m");
            assert!(!reads.is_empty(), "{what}");
            let failed = reads
                .iter()
                .filter(|t| t.errors.iter().any(|e| e == "line_not_driven"))
                .count();
            let late = cfg.late_answer().unwrap();
            assert_eq!(
                failed,
                if late.is_some() { reads.len() } else { 0 },
                "{what}: {late:?}"
            );
            let Some(_) = late else {
                assert!(reads.iter().all(|t| t.errors.is_empty()), "{what}");
                assert!(model::Setup::validate(&cfg).is_ok(), "{what}");
                continue;
            };
            late_seen += 1;
            let e = model::Setup::validate(&cfg).unwrap_err();
            assert_eq!(e.field(), "cable.length_m", "{what}: {e}");
            let text = e.to_string();
            assert!(
                text.contains("line_not_driven") && text.contains("master.delay_comp = true"),
                "{text}"
            );
            let mut comp = cfg.clone();
            comp.master.delay_comp = true;
            assert!(model::Setup::validate(&comp).is_ok(), "{what}");
            let ts = run(&comp);
            assert!(
                commands(&ts).iter().all(|t| t.errors.is_empty()),
                "{what}: with delay compensation: {:?}",
                ts.iter().map(|t| (&t.kind, &t.errors)).collect::<Vec<_>>()
            );
            if let Some(ns) = text.split("master.sample_delay_ns = ").nth(1) {
                let ns: f64 = ns.split(' ').next().unwrap().parse().unwrap();
                let mut later = cfg.clone();
                later.master.sample_delay_ns = ns;
                assert!(
                    model::Setup::validate(&later).is_ok(),
                    "{what}: sample_delay_ns = {ns}"
                );
                let reads = run(&later);
                assert!(
                    commands(&reads).iter().all(|t| t.errors.is_empty()),
                    "{what}: sample_delay_ns = {ns}: {:?}",
                    commands(&reads)
                        .iter()
                        .map(|t| &t.errors)
                        .collect::<Vec<_>>()
                );
            }
        }
    }
    assert!(late_seen >= 90, "{late_seen} late set-ups");
}

/// A position of no bits is blamed on the encoder's fields the user wrote,
/// not on the master's `pos_bits` derived from them, whether the set-up is
/// validated whole or only the master's side is asked for (`tbgen timing`).
#[test]
fn no_position_bits_are_blamed_on_the_encoders_field() {
    use model::Setup as _;
    let mut cfg = BenchConfig::example();
    cfg.encoder.singleturn_bits = 0;
    cfg.encoder.multiturn_bits = 0;
    assert_eq!(
        cfg.validate().unwrap_err().field(),
        "encoder.singleturn_bits"
    );
    assert_eq!(
        cfg.master_config().unwrap_err().field(),
        "encoder.singleturn_bits"
    );
    cfg.encoder.singleturn_bits = 13;
    cfg.encoder.multiturn_bits = model::endat::POSITION_BITS.end() - 12;
    assert_eq!(
        cfg.master_config().unwrap_err().field(),
        "encoder.singleturn_bits"
    );
    cfg.encoder.multiturn_bits -= 1;
    assert!(cfg.master_config().is_ok());
}
