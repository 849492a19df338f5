//! The T-format host against the Smart Abs emulator: every Data ID, EEPROM,
//! resets, and the abnormal-request answers of Tables 5 and 6.

use model::testbench::run_to_end;
use model::tformat::frames::{Alarms, DataId};
use model::tformat::*;
use model::Setup;

fn op(data_id: u8) -> Operation {
    Operation {
        data_id,
        address: 0,
        data: 0,
        gap_us: 5.0,
    }
}

fn run(cfg: &BenchConfig) -> (Vec<Transaction>, u64) {
    let bench = cfg.bench().unwrap();
    let r = run_to_end(bench);
    (r.transactions, r.cycles)
}

fn contention_free(cfg: &BenchConfig) -> Vec<Transaction> {
    let mut bench = cfg.bench().unwrap();
    while !model::testbench::Testbench::finished(&bench) {
        model::testbench::Testbench::step(&mut bench, None);
    }
    assert_eq!(bench.contention_cycles(), 0, "two drivers on the line");
    model::testbench::Testbench::into_transactions(bench)
}

#[test]
fn readouts_0_1_2_3_decode_what_the_encoder_holds() {
    let cfg = BenchConfig {
        encoder: EncoderSettings {
            single_turn: 0x1_ABCD,
            multi_turn: 0xBEEF,
            ..EncoderSettings::default()
        },
        ops: vec![op(0), op(1), op(2), op(3)],
        ..BenchConfig::default()
    };
    let ts = contention_free(&cfg);
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:?}");
    assert_eq!(ts[0].abs, 0x1_ABCD);
    assert_eq!(ts[0].received.len(), 6, "Table 2: CF SF ABS0 ABS1 ABS2 CRC");
    assert_eq!(ts[1].abm, 0xBEEF);
    assert_eq!(ts[2].enid, 0x11, "ENID is fixed as 11H");
    assert_eq!(ts[2].received.len(), 4);
    assert_eq!(
        (ts[3].abs, ts[3].abm, ts[3].enid, ts[3].received.len()),
        (0x1_ABCD, 0xBEEF, 0x11, 11)
    );
}

#[test]
fn the_answer_begins_3_us_after_the_request() {
    // Seed 002, 7.1: "The Data frame is transmitted at 3 micro-seconds (typ.)
    // after receiving the Delimiter signal of Request frame."
    let cfg = BenchConfig {
        cable: model::line::CableConfig::default(),
        ..BenchConfig::default()
    };
    let bench = cfg.bench().unwrap();
    let mut b = bench;
    while !model::testbench::Testbench::finished(&b) {
        model::testbench::Testbench::step(&mut b, None);
    }
    let start = b.encoder().answered()[0].0;
    // At 80 MHz: start bit from cycle 400 (5 µs), 10 bits of 32 cycles end
    // at 720; with no cable the answer's start bit is at 720 + 240 (3 µs).
    assert_eq!(start, 400 + 320 + 240, "request end + 3 µs");
}

#[test]
fn alarms_reach_almc_and_the_status_field() {
    let alarms = Alarms {
        battery_alarm: true,
        counting_error: true,
        ..Alarms::default()
    };
    let cfg = BenchConfig {
        encoder: EncoderSettings {
            alarms,
            ..EncoderSettings::default()
        },
        ops: vec![op(3)],
        ..BenchConfig::default()
    };
    let t = &run(&cfg).0[0];
    assert_eq!(t.almc, alarms.byte());
    assert_eq!(t.sf & 0x30, 0x30, "ea0 and ea1");
    assert!(
        t.errors.is_empty(),
        "encoder errors are data, not communication errors"
    );
}

#[test]
fn eeprom_write_is_busy_then_reads_back() {
    // Table 4: a write is accepted (EDF echoed); requests during the write get
    // busy and 00; after it, the read returns the data.
    let cfg = BenchConfig {
        encoder: EncoderSettings {
            eeprom_write_us: 100.0,
            ..EncoderSettings::default()
        },
        ops: vec![
            Operation {
                data_id: 6,
                address: 5,
                data: 0xA5,
                gap_us: 5.0,
            },
            Operation {
                data_id: 0xD,
                address: 5,
                data: 0,
                gap_us: 5.0,
            },
            Operation {
                data_id: 0xD,
                address: 5,
                data: 0,
                gap_us: 200.0,
            },
        ],
        ..BenchConfig::default()
    };
    let ts = contention_free(&cfg);
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:?}");
    assert_eq!((ts[0].adf, ts[0].edf), (5, 0xA5));
    assert_eq!((ts[1].adf, ts[1].edf), (0x85, 0x00), "busy");
    assert_eq!((ts[2].adf, ts[2].edf), (5, 0xA5));
}

#[test]
fn an_eeprom_address_not_open_to_the_user_gets_data_id_3() {
    // Table 6 no. 2.
    let cfg = BenchConfig {
        ops: vec![Operation {
            data_id: 0xD,
            address: 80,
            data: 0,
            gap_us: 5.0,
        }],
        ..BenchConfig::default()
    };
    let t = &run(&cfg).0[0];
    assert_eq!(t.received.len(), 11);
    assert!(
        t.errors.contains(&"cf_mismatch") && t.errors.contains(&"frame"),
        "{:?}",
        t.errors
    );
}

#[test]
fn an_undefined_data_id_is_answered_with_data_id_3_and_flagged() {
    // Table 5 no. 2: Data ID 5 is not in Table 1.
    let t = &run(&BenchConfig {
        ops: vec![op(5)],
        ..BenchConfig::default()
    })
    .0[0];
    assert_eq!(t.received[0], DataId::Id3.control_field());
    assert!(t.errors.contains(&"cf_mismatch"), "{:?}", t.errors);
}

#[test]
fn ten_resets_40_ms_apart_clear_the_multi_turn_count() {
    // Seed 002, 9.: Data ID C, ten times, 40 ms or more apart. Scaled down:
    // the emulator's interval and the host's gap are both 400 µs here.
    let cfg = BenchConfig {
        host: HostSettings {
            repeat_gap_us: 400.0,
            ..HostSettings::default()
        },
        encoder: EncoderSettings {
            multi_turn: 777,
            reset_interval_us: 400.0,
            alarms: Alarms {
                multi_turn_error: true,
                ..Alarms::default()
            },
            ..EncoderSettings::default()
        },
        ops: vec![op(0xC), op(3)],
        ..BenchConfig::default()
    };
    let ts = contention_free(&cfg);
    assert!(ts[0].errors.is_empty(), "{:?}", ts[0].errors);
    assert_eq!((ts[1].abm, ts[1].almc), (0, 0));
}

#[test]
fn resets_sent_too_close_together_do_not_count() {
    let cfg = BenchConfig {
        host: HostSettings {
            repeat_gap_us: 100.0,
            ..HostSettings::default()
        },
        encoder: EncoderSettings {
            multi_turn: 777,
            reset_interval_us: 400.0,
            ..EncoderSettings::default()
        },
        ops: vec![op(0xC), op(1)],
        ..BenchConfig::default()
    };
    assert_eq!(run(&cfg).0[1].abm, 777);
}

#[test]
fn no_encoder_on_the_line_times_out() {
    let cfg = BenchConfig {
        encoder: EncoderSettings {
            answer_delay_us: 50.0,
            ..EncoderSettings::default()
        },
        ..BenchConfig::default()
    };
    let mut bench = cfg.bench().unwrap();
    while !model::testbench::Testbench::finished(&bench) {
        model::testbench::Testbench::step(&mut bench, None);
    }
    let ts = model::testbench::Testbench::into_transactions(bench);
    assert_eq!(ts[0].errors, vec!["timeout"]);
}

#[test]
fn every_single_bit_flip_of_an_answer_is_flagged() {
    // Data bits break the CRC; a start bit or delimiter breaks framing or the
    // field count. None may reach the host as a clean answer.
    for field in 0..6 {
        for bit in 0..10u8 {
            let cfg = BenchConfig {
                encoder: EncoderSettings {
                    flips: vec![AnswerFlip {
                        answer: 0,
                        field,
                        bit,
                    }],
                    ..EncoderSettings::default()
                },
                ..BenchConfig::default()
            };
            let t = &run(&cfg).0[0];
            assert!(
                !t.errors.is_empty(),
                "field {field} bit {bit} went through: {t:?}"
            );
        }
    }
}

#[test]
fn after_an_answer_whose_framing_was_lost_the_host_waits_for_quiet_before_the_next_request() {
    // A flipped delimiter or start bit can end the answer early at the host
    // while the encoder still sends; without the quiet wait the next request
    // would land on the rest of that answer (seed 002, 10.: "never transmit
    // any Request to Smart Abs while it transmits the data").
    let flips = vec![
        AnswerFlip {
            answer: 0,
            field: 2,
            bit: 9,
        },
        AnswerFlip {
            answer: 1,
            field: 4,
            bit: 0,
        },
    ];
    let cfg = BenchConfig {
        encoder: EncoderSettings {
            flips,
            single_turn: 0x0F0F0,
            ..EncoderSettings::default()
        },
        ops: vec![op(0), op(0), op(0)],
        ..BenchConfig::default()
    };
    let ts = contention_free(&cfg);
    assert!(
        ts[0].errors.contains(&"frame") && ts[1].errors.contains(&"frame"),
        "{ts:?}"
    );
    assert!(
        ts[2].errors.is_empty() && ts[2].abs == 0x0F0F0,
        "{:?}",
        ts[2]
    );
}

#[test]
fn every_two_bit_corruption_escapes_exactly_when_it_is_a_crc_blind_pair() {
    // X^8 + 1 is a parity per bit column: exhaustively, every pair of
    // inverted wire bits of one answer of each layout (Data ID 0, 2, 3, D)
    // is flagged unless `crc_blind_pair` names it, and every pair it names
    // passes (the host has no further check that could see it).
    use model::tformat::campaign::{crc_blind_pair, detected, random_answer};
    use rand::SeedableRng;
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(5);
    for id in [DataId::Id0, DataId::Id2, DataId::Id3, DataId::IdD] {
        let answer = random_answer(&mut rng, id);
        let bits = answer.len() * 10;
        assert!(
            !detected(id, &answer, 0, &[]),
            "{id:?}: a clean answer passes"
        );
        let mut blind = 0;
        for a in 0..bits {
            assert!(
                detected(id, &answer, 0, &[a]),
                "{id:?}: bit {a} alone went through"
            );
            for b in a + 1..bits {
                let escaped = !detected(id, &answer, 0, &[a, b]);
                assert_eq!(
                    escaped,
                    crc_blind_pair(id, a, b),
                    "{id:?}: bits {a} and {b}"
                );
                blind += escaped as usize;
            }
        }
        // Data ID 0: columns × pairs of the four fields after the CF, less the
        // two ca columns with the SF: 8 × 10 − 2 × 4 = 72 of 1770 pairs.
        if id == DataId::Id0 {
            assert_eq!(blind, 72);
        }
    }
}

#[test]
fn a_campaign_of_100_000_random_corruptions_flags_every_one_bit_error_and_every_pair_a_check_can_see(
) {
    use model::tformat::campaign::{self, crc_blind_pair};
    let report = campaign::run(100_000, 8, 2024);
    println!("T-format answers of every Data ID, one of them corrupted per operation, host at 6 clocks per bit:");
    println!("{report}");
    // The theoretical 2-bit escape rate: blind pairs over all pairs of an
    // answer, averaged over the Data IDs (each is equally likely).
    let theory: f64 = DataId::ALL
        .iter()
        .map(|&id| {
            let n = id.answer_fields() * 10;
            let blind = (0..n)
                .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
                .filter(|&(a, b)| crc_blind_pair(id, a, b))
                .count();
            blind as f64 / (n * (n - 1) / 2) as f64
        })
        .sum::<f64>()
        / DataId::ALL.len() as f64;
    let two = report.by_flips[&2];
    let measured = two.undetected as f64 / two.total() as f64;
    println!("2 bits: undetected rate {measured:.5}, theoretical {theory:.5} (same column, two fields after the CF, not ca0/ca1)");
    let more: (u64, u64) = report
        .by_flips
        .range(3..)
        .fold((0, 0), |(n, u), (_, c)| (n + c.total(), u + c.undetected));
    println!(
        "3 to 8 bits: undetected rate {:.5} (X^8+1 on a long random pattern: 2^-8 = {:.5})",
        more.1 as f64 / more.0 as f64,
        1.0 / 256.0
    );
    assert!(report.total() >= 100_000);
    assert_eq!(
        report.by_data_id.len(),
        DataId::ALL.len(),
        "every Data ID ran"
    );
    assert_eq!(
        report.by_flips[&1].undetected, 0,
        "every single-bit error is flagged"
    );
    assert_eq!(
        report.unexplained_pair_escapes, 0,
        "the only 2-bit escapes are CRC-blind pairs"
    );
    assert_eq!(
        report.blind_pairs.detected, 0,
        "a CRC-blind pair always escapes"
    );
    assert!(
        report.blind_pairs.undetected > 0,
        "the campaign met CRC-blind pairs"
    );
    assert!(
        (measured - theory).abs() < 0.2 * theory,
        "2-bit rate {measured} far from {theory}"
    );
    assert!(
        more.1 as f64 / more.0 as f64 <= 1.0 / 256.0,
        "3 to 8 bits escape no more often than a random pattern"
    );
}

/// Ten reads (Data IDs 0, 1, 2, 3, D twice) from an encoder whose answers run
/// `error_percent` off the nominal rate with `jitter_ns` on every edge:
/// (operations, operations flagged, operations passed with wrong fields).
fn off_rate_reads(error_percent: f64, jitter_ns: f64, seed: u64) -> (usize, usize, usize) {
    let ops = [0, 1, 2, 3, 0xD]
        .iter()
        .cycle()
        .take(10)
        .map(|&id| op(id))
        .collect();
    let cfg = BenchConfig {
        encoder: EncoderSettings {
            baud_error_percent: error_percent,
            jitter_ns,
            seed,
            single_turn: (seed as u32).wrapping_mul(0x9E37_79B9) & 0x1_FFFF,
            multi_turn: (seed as u16).wrapping_mul(0x6F4B),
            eeprom: vec![(seed as u8).wrapping_mul(37)],
            ..EncoderSettings::default()
        },
        ops,
        ..BenchConfig::default()
    };
    let mut bench = cfg.bench().unwrap();
    while !model::testbench::Testbench::finished(&bench) {
        model::testbench::Testbench::step(&mut bench, None);
    }
    assert_eq!(
        bench.contention_cycles(),
        0,
        "two drivers at {error_percent} %"
    );
    let answers: Vec<Vec<u8>> = bench
        .encoder()
        .answered()
        .iter()
        .map(|a| a.1.clone())
        .collect();
    let ts = model::testbench::Testbench::into_transactions(bench);
    let flagged = ts.iter().filter(|t| !t.errors.is_empty()).count();
    let wrong = ts
        .iter()
        .zip(&answers)
        .filter(|(t, a)| t.errors.is_empty() && &t.received != *a)
        .count();
    (ts.len(), flagged, wrong)
}

#[test]
fn an_off_rate_or_jittery_encoder_is_read_without_error_inside_the_tolerance_and_always_flagged_beyond_it(
) {
    // Seed 002, 6.1: 2.5 Mbps, "permissible jitter ±100 ns". The encoder's
    // answers run −8 % to +8 % off in 0.1 % steps, without jitter and with
    // ±100 ns (8 cycles at 80 MHz), ten reads a step.
    let (clocks_per_bit, always) = (32, model::tformat::always_flagged(32));
    println!(
        "always flagged below {:+.2} % and above {:+.2} %",
        always.0, always.1
    );
    for jitter_ns in [0.0, 100.0] {
        let (low, high) = model::tformat::tolerance(clocks_per_bit, jitter_ns / 12.5);
        println!("jitter ±{jitter_ns} ns: no error from {low:+.2} % to {high:+.2} %; between the bounds (error %: flagged, wrong but passed, of 10):");
        let mut between = Vec::new();
        for step in -80..=80 {
            let e = step as f64 / 10.0;
            let (n, flagged, wrong) = off_rate_reads(e, jitter_ns, (200 + step) as u64);
            if (low..=high).contains(&e) {
                assert_eq!(
                    (flagged, wrong),
                    (0, 0),
                    "{e} % inside the tolerance, ±{jitter_ns} ns"
                );
            } else if e < always.0 || e > always.1 {
                assert_eq!(
                    flagged, n,
                    "{e} % beyond the bounds, ±{jitter_ns} ns: every read flagged"
                );
            } else {
                between.push(format!("{e:+.1}: {flagged}, {wrong}"));
                if jitter_ns == 0.0 {
                    assert_eq!(
                        wrong, 0,
                        "{e} %: without jitter a misread breaks the framing"
                    );
                }
            }
        }
        println!("  {}", between.join("; "));
    }
}

#[test]
fn every_truncation_of_an_answer_is_flagged_unless_the_cut_tail_is_all_ones() {
    // A truncated frame set: the encoder's driver turns off early and the
    // fail-safe biased line reads 1. A cut tail of ones (the last delimiter,
    // ones at the end of the CRC) leaves the wire as it was: nothing can see
    // that. Every other cut is flagged.
    for id in [0u8, 2, 3] {
        let clean = run(&BenchConfig {
            ops: vec![op(id)],
            ..BenchConfig::default()
        })
        .0;
        let answer = &clean[0].received;
        let bits: Vec<bool> = answer
            .iter()
            .flat_map(|&b| model::tformat::frame_bits(b))
            .collect();
        for cut in 1..bits.len() {
            let cfg = BenchConfig {
                encoder: EncoderSettings {
                    truncate: Some(AnswerTruncation {
                        answer: 0,
                        bits: cut,
                    }),
                    ..EncoderSettings::default()
                },
                ops: vec![op(id)],
                ..BenchConfig::default()
            };
            let t = &contention_free(&cfg)[0];
            let visible = bits[cut..].contains(&false);
            assert_eq!(
                !t.errors.is_empty(),
                visible,
                "Data ID {id} cut after {cut} bits: {:?}",
                t.errors
            );
        }
    }
}

#[test]
fn a_line_stuck_low_is_flagged_and_cannot_hang_the_host() {
    // Held low from the middle of the first answer to the end of the run:
    // every operation ends (o_done), every one flagged.
    let cfg = BenchConfig {
        line_faults: vec![LineFault {
            kind: LineFaultKind::StuckLow,
            at_us: 15.0,
            width_us: 5000.0,
            bytes: vec![],
        }],
        ops: vec![op(0), op(3), op(0xD)],
        ..BenchConfig::default()
    };
    let ts = run(&cfg).0;
    assert_eq!(ts.len(), 3, "every operation ended");
    assert!(ts.iter().all(|t| t.errors.contains(&"frame")), "{ts:?}");
}

#[test]
fn a_line_stuck_high_times_out_and_a_second_driver_is_flagged() {
    let stuck = BenchConfig {
        line_faults: vec![LineFault {
            kind: LineFaultKind::StuckHigh,
            at_us: 10.0,
            width_us: 5000.0,
            bytes: vec![],
        }],
        ops: vec![op(0), op(3)],
        ..BenchConfig::default()
    };
    assert!(run(&stuck).0.iter().all(|t| t.errors == vec!["timeout"]));
    // A second driver sending 0x00 fields: over the answer (from 13 µs), or
    // over the request (from 6 µs): the answer is flagged either way.
    for at_us in [6.0, 13.0, 20.0, 30.0] {
        let cfg = BenchConfig {
            line_faults: vec![LineFault {
                kind: LineFaultKind::SecondDriver,
                at_us,
                width_us: 0.0,
                bytes: vec![0x00, 0x00],
            }],
            ..BenchConfig::default()
        };
        let mut bench = cfg.bench().unwrap();
        while !model::testbench::Testbench::finished(&bench) {
            model::testbench::Testbench::step(&mut bench, None);
        }
        assert!(
            bench.fault_contention_cycles() > 0,
            "{at_us} µs: the second driver overlapped a driver"
        );
        let ts = model::testbench::Testbench::into_transactions(bench);
        assert!(!ts[0].errors.is_empty(), "{at_us} µs: {:?}", ts[0]);
    }
}

#[test]
fn the_transcript_carries_every_character_on_the_wire_at_the_host() {
    // Clean reads: the wire holds exactly the request sent and the answer received.
    let clean = run(&BenchConfig {
        ops: vec![
            op(0),
            op(3),
            Operation {
                data_id: 6,
                address: 5,
                data: 0xA5,
                gap_us: 5.0,
            },
        ],
        ..BenchConfig::default()
    })
    .0;
    for t in &clean {
        assert_eq!(
            (&t.wire_requests, &t.wire_answers),
            (&vec![t.sent.clone()], &vec![t.received.clone()]),
            "{t:?}"
        );
    }
    // A reset: ten requests, ten answers, in order.
    let cfg = BenchConfig {
        host: HostSettings {
            repeat_gap_us: 400.0,
            ..HostSettings::default()
        },
        encoder: EncoderSettings {
            reset_interval_us: 400.0,
            ..EncoderSettings::default()
        },
        ops: vec![op(0xC)],
        ..BenchConfig::default()
    };
    let t = &run(&cfg).0[0];
    assert_eq!((t.wire_requests.len(), t.wire_answers.len()), (10, 10));
    assert!(
        t.wire_requests.iter().all(|r| *r == t.sent)
            && t.wire_answers.iter().all(|a| *a == t.received)
    );
    // A start bit flipped in an answer: the host stops at the lost framing,
    // the wire keeps the rest of the answer.
    let flipped = BenchConfig {
        encoder: EncoderSettings {
            flips: vec![AnswerFlip {
                answer: 0,
                field: 3,
                bit: 0,
            }],
            ..EncoderSettings::default()
        },
        ..BenchConfig::default()
    };
    let t = &run(&flipped).0[0];
    assert!(
        t.wire_answers[0].len() > t.received.len()
            && t.wire_answers[0].starts_with(&t.received[..2]),
        "{t:?}"
    );
    // Another driver over the request: the wire shows what it forced, not what the host sent.
    let over_request = BenchConfig {
        line_faults: vec![LineFault {
            kind: LineFaultKind::SecondDriver,
            at_us: 5.0,
            width_us: 0.0,
            bytes: vec![0x00],
        }],
        ..BenchConfig::default()
    };
    let t = &run(&over_request).0[0];
    assert_eq!(
        (t.sent.clone(), t.wire_requests.clone()),
        (vec![0x02], vec![vec![0x00]])
    );
}

/// The rule book's seed limits in ps (seed 002 6.1: 2.5 Mbps, jitter 100
/// ns; 7.1; 9: 40 ms).
#[test]
fn the_tformat_rule_books_seed_limits_in_ps() {
    let l = model::tformat::rules::Limits::seed(2.5e6, 40_000.0);
    assert_eq!(l.line.bit_ps, 400_000.0);
    assert_eq!(l.line.jitter_ps, 100_000.0);
    assert_eq!(l.line.release_ps, 1_500_000);
    assert_eq!(l.reset_interval_ps, 40_000_000_000);
}
