//! The ESL host against the QS35 emulator: every Data ID, the 8-times
//! commands, memory with busy and page change, daisy chain, baud error and
//! the faults the host must survive.

use model::esl::frames::{self, Alarms, DataId};
use model::esl::*;
use model::testbench::Testbench;
use model::Setup;

fn op(data_id: u8) -> Operation {
    Operation {
        data_id,
        address: 0,
        broadcast: false,
        mem_address: 0,
        data: 0,
        gap_us: 2.0,
    }
}

fn mem(data_id: u8, mem_address: u8, data: u8, gap_us: f64) -> Operation {
    Operation {
        data_id,
        address: 0,
        broadcast: false,
        mem_address,
        data,
        gap_us,
    }
}

/// Runs to the end; asserts the line never had two drivers.
fn run(cfg: &BenchConfig) -> (Vec<Transaction>, Bench) {
    let mut bench = cfg.bench().unwrap();
    while !bench.finished() {
        bench.step(None);
    }
    let ts = bench.transactions().to_vec();
    (ts, bench)
}

fn assert_no_contention(bench: &Bench) {
    assert_eq!(bench.contention_cycles(), 0, "two drivers on the line");
}

fn clean(cfg: &BenchConfig) -> Vec<Transaction> {
    let (ts, bench) = run(cfg);
    assert_no_contention(&bench);
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:#?}");
    ts
}

#[test]
#[allow(clippy::unusual_byte_groupings)] // ENID grouped as the seed's {safety, MT bytes, ST bits}
fn every_data_id_of_table_12_is_answered_and_checked_clean() {
    let enc = EncoderSettings {
        single_turn: 0xAB_CDEF,
        multi_turn: 0xBEEF,
        temperature_c: -5,
        ..EncoderSettings::default()
    };
    let ops: Vec<Operation> = DataId::ALL
        .iter()
        .filter(|d| !d.is_repeated())
        .map(|d| op(d.code()))
        .collect();
    let cfg = BenchConfig {
        encoders: vec![enc],
        ops,
        ..BenchConfig::default()
    };
    let ts = clean(&cfg);
    let by = |id: DataId| ts.iter().find(|t| t.data_id == id.code()).unwrap();
    for id in DataId::ALL.iter().filter(|d| !d.is_repeated()) {
        assert_eq!(by(*id).received.len(), id.answer_fields(), "{id:?}");
        assert_eq!(by(*id).cf, id.control_field(0), "{id:?}");
    }
    assert_eq!(
        (by(DataId::Id1).abs, by(DataId::Id1).abm, by(DataId::Id1).rs),
        (0xAB_CDEF, 0xBEEF, (0xAB_CDEF >> 15) as u16)
    );
    assert_eq!(by(DataId::Id2).abs, 0xAB_CDEF);
    assert_eq!(
        (by(DataId::Id4).abs, by(DataId::Id4).abm),
        (0xAB_CDEF, 0xBEEF)
    );
    assert_eq!(by(DataId::Id5).abs, 0xAB_CDEF);
    assert_eq!(by(DataId::Id6).rs, 0xABCD, "extended RS: top 16 bits");
    assert_eq!(by(DataId::Id8).enid, 0b1_10_11000, "Table 6 MT example");
    assert_eq!(by(DataId::Id9).temp as i8, -5);
    assert_eq!(by(DataId::Id1).sf & 0x40, 0x40, "DD2 ready");
    assert_eq!(
        by(DataId::Id1).sf2 & frames::STATUS_CH2,
        frames::STATUS_CH2,
        "DD1 marks channel 2"
    );
}

#[test]
fn the_answer_begins_2_us_after_the_request() {
    // Seed 000, Figure 2 text: "after 2.0 µs (typical), the encoder shall respond".
    let cfg = BenchConfig {
        cable: model::line::CableConfig::default(),
        ..BenchConfig::default()
    };
    let (_, bench) = run(&cfg);
    let start = bench.encoders()[0].answered()[0].0;
    // 80 MHz: request from cycle 160 (2 µs), CF + CRC = 20 bits of 8 cycles
    // end at 320; the answer's start bit 2 µs = 160 cycles later.
    assert_eq!(start, 160 + 160 + 160);
}

#[test]
fn safety_reads_carry_counters_that_count_up_and_are_checked() {
    let cfg = BenchConfig {
        encoders: vec![EncoderSettings {
            sequence_start: 126,
            ..EncoderSettings::default()
        }],
        ops: vec![op(1), op(2), op(8), op(1)],
        ..BenchConfig::default()
    };
    let ts = clean(&cfg);
    let sc: Vec<(u8, u8)> = ts.iter().map(|t| (t.sc1, t.sc2)).collect();
    assert_eq!(
        sc,
        [(126, 126), (127, 127), (128, 0), (129, 1)],
        "SC2 has 7 bits on the line"
    );
}

#[test]
fn a_sequence_jump_on_either_channel_is_flagged_once() {
    for channel in [1, 2] {
        let enc = EncoderSettings {
            sequence_jumps: vec![SequenceJump { answer: 2, channel }],
            ..EncoderSettings::default()
        };
        let cfg = BenchConfig {
            encoders: vec![enc],
            ops: vec![op(1); 4],
            ..BenchConfig::default()
        };
        let (ts, _) = run(&cfg);
        let errs: Vec<_> = ts.iter().map(|t| t.errors.clone()).collect();
        assert_eq!(
            errs,
            [vec![], vec![], vec!["sequence"], vec![]],
            "channel {channel}"
        );
    }
}

#[test]
fn channel_disagreement_is_flagged() {
    let enc = EncoderSettings {
        rs_offset: 3,
        ..EncoderSettings::default()
    };
    let cfg = BenchConfig {
        encoders: vec![enc],
        ops: vec![op(1), op(0xC), op(6)],
        ..BenchConfig::default()
    };
    let (ts, _) = run(&cfg);
    assert_eq!(ts[0].errors, ["channel_mismatch"]);
    assert!(ts[1].errors.contains(&"channel_mismatch"));
    assert_eq!(ts[2].errors, ["channel_mismatch"]);
    let cfg = BenchConfig {
        encoders: vec![EncoderSettings {
            rs_offset: 1,
            ..EncoderSettings::default()
        }],
        ..cfg
    };
    assert!(
        run(&cfg).0[0].errors.is_empty(),
        "one RS LSB is within the default tolerance"
    );
}

#[test]
fn commands_b_c_d_are_sent_8_times_as_one_operation_and_take_effect() {
    let enc = EncoderSettings {
        single_turn: 0x12_3456,
        multi_turn: 77,
        alarms: Alarms {
            xc: true,
            mt: true,
            uv: true,
            ..Alarms::default()
        },
        ..EncoderSettings::default()
    };
    let cfg = BenchConfig {
        encoders: vec![enc],
        ops: vec![op(0xB), op(0xC), op(0xD), op(1)],
        ..BenchConfig::default()
    };
    let (ts, bench) = run(&cfg);
    assert_no_contention(&bench);
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:#?}");
    assert!(ts[..3].iter().all(|t| t.requests == 8));
    assert_eq!(
        bench.encoders()[0].executed(),
        [DataId::IdB, DataId::IdC, DataId::IdD]
    );
    assert_eq!(ts[0].abs, 0, "the 8th answer shows the cleared single-turn");
    assert_eq!(
        ts[1].alm1,
        Alarms {
            uv: true,
            ..Alarms::default()
        }
        .byte(),
        "C clears XC and MT, not UV"
    );
    assert_eq!(ts[2].abm, 0);
    assert_eq!((ts[3].abs, ts[3].abm), (0, 0));
}

#[test]
fn seven_requests_or_too_slow_repeats_do_not_execute() {
    let enc = EncoderSettings {
        multi_turn: 77,
        repeat_window_us: 30.0,
        ..EncoderSettings::default()
    };
    let cfg = BenchConfig {
        encoders: vec![enc],
        ops: vec![op(0xD), op(4)],
        ..BenchConfig::default()
    };
    let (ts, bench) = run(&cfg);
    assert!(bench.encoders()[0].executed().is_empty());
    assert_eq!(ts[1].abm, 77);
}

#[test]
fn an_eeprom_read_takes_two_requests_200_us_apart() {
    // Seed 000, "Direct Read from EEPROM": first read busy and 00, second
    // (200 µs later) the data. Page 0 is EEPROM.
    let enc = EncoderSettings {
        memory: vec![MemoryInit {
            page: 0,
            address: 0x10,
            data: vec![0x5A],
        }],
        ..EncoderSettings::default()
    };
    let cfg = BenchConfig {
        host: HostSettings {
            page_wait_us: 50.0,
            ..HostSettings::default()
        },
        encoders: vec![EncoderSettings {
            page_change_us: 50.0,
            ..enc
        }],
        ops: vec![
            mem(0xF, 0x7F, 0, 2.0),
            mem(0xE, 0x10, 0, 2.0),
            mem(0xE, 0x7F, 0, 2.0),
        ],
        ..BenchConfig::default()
    };
    let (ts, bench) = run(&cfg);
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:#?}");
    assert!(
        ts[0].done_cycle - ts[0].start_cycle >= 4_000,
        "the page change holds the operation"
    );
    assert_eq!(bench.host().page(), 0);
    assert_eq!(
        (ts[1].requests, ts[1].adf, ts[1].edf),
        (2, frames::adf(0x10, false), 0x5A)
    );
    assert_eq!(
        (ts[2].requests, ts[2].edf),
        (1, 0),
        "the page register reads back at once"
    );
}

#[test]
fn register_access_on_page_8_needs_one_request_and_no_wait() {
    let cfg = BenchConfig {
        ops: vec![mem(0xF, 0x05, 0xA5, 2.0), mem(0xE, 0x05, 0, 2.0)],
        ..BenchConfig::default()
    };
    let ts = clean(&cfg);
    assert_eq!((ts[0].requests, ts[1].requests, ts[1].edf), (1, 1, 0xA5));
    assert!(
        ts[0].done_cycle - ts[0].start_cycle < 1_200,
        "no write wait on the register page"
    );
}

#[test]
fn an_eeprom_write_waits_its_6_ms_then_reads_back() {
    let enc = EncoderSettings {
        eeprom_write_us: 300.0,
        page_change_us: 20.0,
        ..EncoderSettings::default()
    };
    let cfg = BenchConfig {
        host: HostSettings {
            write_wait_us: 300.0,
            page_wait_us: 20.0,
            ..HostSettings::default()
        },
        encoders: vec![enc],
        ops: vec![
            mem(0xF, 0x7F, 0, 2.0),
            mem(0xF, 0x22, 0xC3, 2.0),
            mem(0xE, 0x22, 0, 2.0),
        ],
        ..BenchConfig::default()
    };
    let (ts, bench) = run(&cfg);
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:#?}");
    assert!(ts[1].done_cycle - ts[1].start_cycle >= 24_000);
    assert_eq!(bench.encoders()[0].memory(0, 0x22), 0xC3);
    assert_eq!(ts[2].edf, 0xC3);
}

#[test]
fn a_write_during_the_write_time_is_answered_busy_and_retried() {
    let enc = EncoderSettings {
        eeprom_write_us: 300.0,
        page_change_us: 20.0,
        ..EncoderSettings::default()
    };
    let cfg = BenchConfig {
        // The host does not wait after a write (a short write_wait), so the
        // second write meets a busy EEPROM; with one try it reports busy.
        host: HostSettings {
            write_wait_us: 1.0,
            page_wait_us: 20.0,
            busy_tries: 1,
            ..HostSettings::default()
        },
        encoders: vec![enc],
        ops: vec![
            mem(0xF, 0x7F, 0, 2.0),
            mem(0xF, 0x22, 0xC3, 2.0),
            mem(0xF, 0x23, 0x3C, 2.0),
        ],
        ..BenchConfig::default()
    };
    let (ts, _) = run(&cfg);
    assert_eq!(ts[2].errors, ["busy"]);
    assert_eq!((ts[2].adf & 1, ts[2].edf), (1, 0), "Table 10: busy, EDF 00");
}

#[test]
fn daisy_chain_single_access_and_broadcast() {
    let enc = |address, st| EncoderSettings {
        address,
        single_turn: st,
        multi_turn: 9,
        ..EncoderSettings::default()
    };
    let cfg = BenchConfig {
        encoders: vec![enc(0, 0x100), enc(1, 0x200), enc(2, 0x300)],
        ops: vec![
            op(4),
            Operation {
                address: 2,
                ..op(4)
            },
            Operation {
                address: 1,
                ..op(1)
            },
            Operation {
                broadcast: true,
                ..op(0xD)
            },
            Operation {
                address: 1,
                ..op(4)
            },
        ],
        ..BenchConfig::default()
    };
    let ts = clean(&cfg);
    assert_eq!((ts[0].abs, ts[1].abs, ts[2].abs), (0x100, 0x300, 0x200));
    assert_eq!(ts[3].requests, 8);
    assert!(ts[3].received.is_empty(), "nobody answers a broadcast");
    assert_eq!(ts[4].abm, 0, "every encoder cleared its multi-turn");
}

#[test]
fn an_answer_from_another_address_is_flagged() {
    let enc = EncoderSettings {
        foreign_address_answers: vec![0],
        ..EncoderSettings::default()
    };
    let cfg = BenchConfig {
        encoders: vec![enc],
        ops: vec![op(4), op(4)],
        ..BenchConfig::default()
    };
    let (ts, _) = run(&cfg);
    assert_eq!(ts[0].errors, ["cf_mismatch"]);
    assert!(ts[1].errors.is_empty());
}

#[test]
fn bad_parity_and_bad_stop_bits_are_answered_with_ca0_and_ca1() {
    // Seed 000, Table 5. Request 0: parity bit (CF bit 8 on the line) flipped;
    // request 1: CF stop bit flipped; request 2: a CRC bit flipped: no answer.
    let cfg = BenchConfig {
        request_flips: vec![
            RequestFlip {
                request: 0,
                field: 0,
                bit: 8,
            },
            RequestFlip {
                request: 1,
                field: 0,
                bit: 9,
            },
            RequestFlip {
                request: 2,
                field: 1,
                bit: 3,
            },
        ],
        ops: vec![op(1), op(1), op(1), op(1)],
        ..BenchConfig::default()
    };
    let (ts, bench) = run(&cfg);
    assert_no_contention(&bench);
    assert_eq!(ts[0].errors, ["comm_alarm"]);
    assert_eq!(ts[0].received.len(), frames::COMM_ERROR_FIELDS);
    assert_eq!(ts[0].received[1] & 3, 1, "CA0");
    assert!(ts[1].errors.contains(&"comm_alarm"));
    assert_eq!(ts[1].received[1] & 3, 2, "CA1");
    assert_eq!(ts[2].errors, ["timeout"]);
    assert!(ts[3].errors.is_empty(), "{:?}", ts[3]);
}

#[test]
fn every_single_bit_flip_of_a_safety_answer_is_flagged() {
    for field in 0..18 {
        for bit in 0..10u8 {
            let enc = EncoderSettings {
                flips: vec![AnswerFlip {
                    answer: 0,
                    field,
                    bit,
                }],
                ..EncoderSettings::default()
            };
            let cfg = BenchConfig {
                encoders: vec![enc],
                ops: vec![op(1), op(1)],
                ..BenchConfig::default()
            };
            let (ts, bench) = run(&cfg);
            assert_no_contention(&bench);
            assert!(
                !ts[0].errors.is_empty(),
                "field {field} bit {bit} went through: {:?}",
                ts[0]
            );
            assert!(
                ts[1].errors.is_empty(),
                "field {field} bit {bit}: the next read must be clean: {:?}",
                ts[1]
            );
        }
    }
}

#[test]
fn truncated_answers_and_silence_are_flagged() {
    for fields in [0, 1, 10, 11, 17] {
        let enc = EncoderSettings {
            truncations: vec![Truncation { answer: 0, fields }],
            ..EncoderSettings::default()
        };
        let cfg = BenchConfig {
            encoders: vec![enc],
            ops: vec![op(1)],
            ..BenchConfig::default()
        };
        let t = &run(&cfg).0[0];
        let want = if fields == 0 { "timeout" } else { "frame" };
        assert!(t.errors.contains(&want), "{fields} fields: {:?}", t.errors);
    }
}

#[test]
fn a_second_driver_on_the_line_is_flagged() {
    // The answer of op 0 runs from 6 µs; someone pulls the line low at 8 µs.
    let cfg = BenchConfig {
        intruders: vec![Intruder {
            at_us: 8.0,
            length_us: 0.35,
        }],
        ops: vec![op(1), op(1)],
        ..BenchConfig::default()
    };
    let (ts, bench) = run(&cfg);
    assert!(bench.contention_cycles() > 0);
    assert!(!ts[0].errors.is_empty());
}

#[test]
fn baud_error_inside_the_tolerance_passes_and_far_outside_fails() {
    let (lo, hi) = model::uart::tolerance(8, 0.0);
    for tenth in -30..=30 {
        let err = f64::from(tenth) / 10.0;
        let enc = EncoderSettings {
            baud_error_percent: err,
            ..EncoderSettings::default()
        };
        let cfg = BenchConfig {
            cable: model::line::CableConfig::default(),
            encoders: vec![enc],
            ops: vec![op(1), op(4), op(0xA), op(8)],
            ..BenchConfig::default()
        };
        assert!((lo..hi).contains(&err));
        clean(&cfg);
    }
    for err in [-8.0, -7.0, 7.0, 8.0] {
        let enc = EncoderSettings {
            baud_error_percent: err,
            ..EncoderSettings::default()
        };
        let cfg = BenchConfig {
            encoders: vec![enc],
            ops: vec![op(1), op(4), op(0xA), op(8)],
            ..BenchConfig::default()
        };
        let (ts, _) = run(&cfg);
        assert!(ts.iter().all(|t| !t.errors.is_empty()), "{err} %: {ts:#?}");
    }
}

#[test]
fn an_undefined_data_id_is_not_acknowledged() {
    let t = &run(&BenchConfig {
        ops: vec![op(3)],
        ..BenchConfig::default()
    })
    .0[0];
    assert!(t.errors.contains(&"timeout"), "{:?}", t.errors);
}

#[test]
fn campaign_of_100_000_random_corruptions() {
    let report = campaign::run(100_000, 6, 2026);
    println!("ESL corruption campaign (answers of every Data ID, wire bits):\n{report}");
    assert_eq!(report.total(), 100_000);
    for k in 1..=3 {
        assert_eq!(
            report.by_flips[&k].undetected, 0,
            "{k} flipped bits: {report}"
        );
    }
    assert!(report.undetected() * 200 < report.total(), "{report}");
}

#[test]
fn campaign_receiver_and_check_see_a_clean_answer_as_clean() {
    let id = DataId::Id1;
    let d = frames::AnswerData {
        cf: id.control_field(0),
        abs: 0x800,
        rs: frames::redundant(0x800, id),
        ..frames::AnswerData::default()
    };
    assert!(!campaign::detected(id, &d, &[]));
    assert!(campaign::detected(id, &d, &[5]));
}

#[test]
fn the_transcript_carries_every_character_on_the_wire_at_the_host() {
    // Clean reads: the wire holds exactly the request sent and the answer
    // received; a command sent 8 times: 8 requests, 8 answers, in order,
    // the last the one the host kept.
    let ts = clean(&BenchConfig {
        ops: vec![op(1), op(0xB), op(2)],
        ..BenchConfig::default()
    });
    for t in [&ts[0], &ts[2]] {
        assert_eq!(
            (&t.wire_requests, &t.wire_answers),
            (&vec![t.sent.clone()], &vec![t.received.clone()]),
            "{t:?}"
        );
    }
    let t = &ts[1];
    assert_eq!((t.wire_requests.len(), t.wire_answers.len()), (8, 8));
    assert!(t.wire_requests.iter().all(|r| *r == t.sent), "{t:?}");
    assert_eq!(t.wire_answers[7], t.received);
    assert!(
        t.wire_answers.windows(2).all(|w| w[0] != w[1]),
        "the sequence counters count: every answer differs"
    );
    // A flipped request: the wire shows the bit as the line carried it (the
    // parity bit is CF data bit 7), the host's `sent` what it meant to send.
    let flipped = BenchConfig {
        request_flips: vec![RequestFlip {
            request: 0,
            field: 0,
            bit: 8,
        }],
        ops: vec![op(1)],
        ..BenchConfig::default()
    };
    let t = &run(&flipped).0[0];
    assert_eq!(t.wire_requests, [vec![t.sent[0] ^ 0x80, t.sent[1]]]);
    assert_eq!(
        t.wire_answers,
        std::slice::from_ref(&t.received),
        "the CA0 answer"
    );
    // A second driver holds the line low from the stop bit of answer
    // character 1 into character 2 (0x00): the host stops at the framing
    // error; the wire keeps the rest of the answer, one character short (the
    // receiver waits for a high line after a low stop bit, and character 2
    // never gives one).
    let intruder = BenchConfig {
        intruders: vec![Intruder {
            at_us: 8.0,
            length_us: 0.35,
        }],
        ops: vec![op(1), op(1)],
        ..BenchConfig::default()
    };
    let ts = run(&intruder).0;
    let whole = &clean(&BenchConfig {
        ops: vec![op(1)],
        ..BenchConfig::default()
    })[0]
        .received;
    assert!(ts[0].errors.contains(&"frame"), "{:?}", ts[0]);
    assert_eq!(ts[0].received, whole[..2]);
    assert_eq!(ts[0].wire_answers, [[&whole[..2], &whole[3..]].concat()]);
    assert_eq!(ts[1].wire_answers, [ts[1].received.clone()]);
}

/// The rule book's seed limits in ps: the bit, the release, and the
/// encoder times of every address (seed 000 Table 1, Figures 2, 3, 5, Table 4, Table 11).
#[test]
fn the_esl_rule_books_seed_limits_in_ps() {
    use model::esl::rules::{Limits, Spacing};
    let l = Limits::seed(10e6, 3.0);
    assert_eq!(l.line.bit_ps, 100_000.0);
    assert_eq!(l.line.release_ps, 1_000_000);
    assert_eq!(
        l.spacing[5],
        Spacing {
            repeat_window: 200_000_000,
            read: 200_000_000,
            write: 6_000_000_000,
            page_change: 18_000_000_000,
        }
    );
}
