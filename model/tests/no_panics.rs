//! Whatever a scenario file says, the model answers with a value or a
//! `ConfigError` naming the field, never a panic: arbitrary numbers
//! (NaN, infinities, zero, huge) in every field of every protocol's setup,
//! then a few thousand cycles of any setup that was accepted.

use model::testbench::Testbench;
use model::{esl, ssi, uart, Setup};
use std::sync::atomic::{AtomicUsize, Ordering};

use proptest::prelude::*;

static SSI_RAN: AtomicUsize = AtomicUsize::new(0);
static UART_RAN: AtomicUsize = AtomicUsize::new(0);
static ESL_RAN: AtomicUsize = AtomicUsize::new(0);

/// Realistic values most of the time (so that many setups are accepted and
/// run), and the nasty ones often enough.
fn any_f64(usual: &'static [f64]) -> impl Strategy<Value = f64> {
    prop_oneof![
        19 => proptest::sample::select(usual),
        1 => nasty_f64(),
    ]
}

fn nasty_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-1.0),
        Just(1e300),
        0.0f64..2000.0,
        any::<f64>(),
    ]
}

fn step_a_while<B: Testbench>(mut bench: B) {
    for _ in 0..5000 {
        if bench.finished() {
            break;
        }
        bench.step(None);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn any_ssi_setup_is_accepted_or_refused_by_field(
        f_sys in any_f64(&[50.0, 100.0]), clock in any_f64(&[250.0, 500.0, 1000.0]), t_cs in any_f64(&[4.0, 2.0]),
        pause in any_f64(&[510.0, 40.0]), delay in any_f64(&[0.0, 100.0]), monoflop in any_f64(&[20.0, 500.0]),
        out_delay in any_f64(&[100.0, 0.0]), cable in any_f64(&[0.0, 10.0, 100.0]), jitter in any_f64(&[0.0, 20.0]),
        bits in prop_oneof![4 => Just(12u32), 1 => 0u32..70], enc_bits in prop_oneof![4 => Just(12u32), 1 => 0u32..70], reads in prop_oneof![4 => Just(None), 4 => Just(Some(3usize)), 1 => proptest::option::of(0usize..20_000_000)],
        position in prop_oneof![4 => 0u64..4096, 1 => any::<u64>()], step in any::<u64>(), flags in any::<[bool; 4]>(),
    ) {
        let cfg = ssi::BenchConfig {
            f_sys_mhz: f_sys,
            master: ssi::MasterSettings {
                bits, clock_khz: clock, t_cs_us: t_cs, pause_us: pause, sample_delay_ns: delay,
                double_read: flags[0], wire_check: flags[1],
                code: if flags[2] { ssi::Code::Gray } else { ssi::Code::Binary },
            },
            encoder: ssi::EncoderSettings { bits: enc_bits, monoflop_us: monoflop, output_delay_ns: out_delay, ..Default::default() },
            cable: model::line::CableConfig { length_m: cable, jitter_ns: jitter, ..Default::default() },
            positions: vec![position],
            reads,
            step,
            fault: flags[3].then_some(ssi::StuckFault { level: true, from_read: 1 }),
            ..Default::default()
        };
        match cfg.validate() {
            Ok(()) => {
                step_a_while(cfg.bench().expect("a validated setup builds"));
                SSI_RAN.fetch_add(1, Ordering::Relaxed);
            }
            Err(e) => prop_assert!(!e.field().is_empty()),
        }
    }

    #[test]
    fn any_uart_setup_is_accepted_or_refused_by_field(
        f_sys in any_f64(&[100.0, 80.0]), baud in any_f64(&[10e6, 2.5e6]), error in any_f64(&[0.0, 3.0, -6.0]),
        jitter in any_f64(&[0.0, 20.0]), gap in any_f64(&[0.0, 3.0]), first in any_f64(&[0.5, 0.0]),
        at in any_f64(&[0.1, 5.0]), width in any_f64(&[30.0, 3000.0]),
        bytes in proptest::collection::vec(any::<u8>(), 0..4), repeat in prop_oneof![Just(1usize), 0usize..3_000_000],
    ) {
        let cfg = uart::BenchConfig {
            f_sys_mhz: f_sys, baud, error_percent: error, jitter_ns: jitter, gap_bits: gap, first_us: first,
            bytes, repeat, low: vec![uart::LowPulse { at_us: at, width_ns: width }], ..Default::default()
        };
        match cfg.validate() {
            Ok(()) => {
                step_a_while(cfg.bench().expect("a validated setup builds"));
                UART_RAN.fetch_add(1, Ordering::Relaxed);
            }
            Err(e) => prop_assert!(!e.field().is_empty()),
        }
    }

    #[test]
    fn any_esl_setup_is_accepted_or_refused_by_field(
        f_sys in any_f64(&[80.0, 100.0]), baud in any_f64(&[10e6]), timeout in any_f64(&[5.0, 1.0]),
        gap in any_f64(&[40.0, 1.0]), wait in any_f64(&[200.0, 6000.0, 1.0]), delay in any_f64(&[2.0, 0.0, 50.0]),
        error in any_f64(&[0.0, 3.0, -6.0]), eeprom in any_f64(&[200.0, 1.0]), op_gap in any_f64(&[2.0, 0.0]),
        data_id in prop_oneof![4 => 0u8..16, 1 => any::<u8>()], address in prop_oneof![4 => 0u8..8, 1 => any::<u8>()],
        mem_address in any::<u8>(), tries in prop_oneof![4 => Just(3u64), 1 => any::<u64>()], rs_offset in any::<i32>(),
        flip in (0usize..20, 0usize..20, 0u8..12), truncate in (0usize..3, any::<usize>()), flags in any::<[bool; 3]>(),
    ) {
        let encoder = esl::EncoderSettings {
            address: address & 0x7, answer_delay_us: delay, baud_error_percent: error, eeprom_read_us: eeprom,
            eeprom_write_us: eeprom, page_change_us: eeprom, rs_offset,
            flips: vec![esl::AnswerFlip { answer: flip.0, field: flip.1, bit: flip.2 }],
            truncations: vec![esl::Truncation { answer: truncate.0, fields: truncate.1 }],
            ..Default::default()
        };
        let cfg = esl::BenchConfig {
            f_sys_mhz: f_sys, baud,
            host: esl::HostSettings { timeout_us: timeout, repeat_gap_us: gap, read_wait_us: wait, write_wait_us: wait, page_wait_us: wait, busy_tries: tries, ..Default::default() },
            encoders: vec![encoder],
            request_flips: if flags[0] { vec![esl::RequestFlip { request: 0, field: flip.1, bit: flip.2 }] } else { vec![] },
            intruders: if flags[1] { vec![esl::Intruder { at_us: op_gap, length_us: delay }] } else { vec![] },
            ops: vec![esl::Operation { data_id, address, broadcast: flags[2], mem_address, data: 0x5A, gap_us: op_gap }; 2],
            ..Default::default()
        };
        match cfg.validate() {
            Ok(()) => {
                step_a_while(cfg.bench().expect("a validated setup builds"));
                ESL_RAN.fetch_add(1, Ordering::Relaxed);
            }
            Err(e) => prop_assert!(!e.field().is_empty()),
        }
    }
}

#[test]
fn the_property_tests_above_run_many_accepted_setups() {
    // Runs after them in the same binary only by luck of ordering, so it runs
    // them itself: their counters must show real runs, not only refusals.
    any_ssi_setup_is_accepted_or_refused_by_field();
    any_uart_setup_is_accepted_or_refused_by_field();
    any_esl_setup_is_accepted_or_refused_by_field();
    let (ssi, uart) = (
        SSI_RAN.load(Ordering::Relaxed),
        UART_RAN.load(Ordering::Relaxed),
    );
    assert!(
        ssi >= 20 && uart >= 20,
        "accepted and run: ssi {ssi}, uart {uart}"
    );
    let esl = ESL_RAN.load(Ordering::Relaxed);
    println!("accepted and run: ssi {ssi}, uart {uart}, esl {esl}");
    assert!(esl >= 20, "accepted and run: esl {esl}");
}

static BISS_RAN: AtomicUsize = AtomicUsize::new(0);

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn any_biss_setup_is_accepted_or_refused_by_field(
        (f_sys, clock, max_delay, timeout) in (any_f64(&[80.0, 100.0]), any_f64(&[10_000.0, 2_500.0]), any_f64(&[2_000.0, 50.0]), any_f64(&[40.0, 1.0])),
        (busy, slave_timeout, cable, jitter, step_ns) in (proptest::option::of(any_f64(&[250.0, 1000.0])), any_f64(&[2.0, 16.0]), any_f64(&[0.0, 100.0]), any_f64(&[0.0, 12.0]), any_f64(&[150.0, 0.0])),
        tol in proptest::option::of(any_f64(&[10.0, 30.0])),
        (cal_frames, bits, crc_width, crc_poly) in (prop_oneof![4 => Just(4u64), 1 => any::<u64>()], prop_oneof![4 => Just(16u32), 1 => 0u32..70], prop_oneof![4 => Just(6u32), 1 => 0u32..10], prop_oneof![4 => Just(3u64), 1 => any::<u64>()]),
        frames in prop_oneof![4 => 1usize..3, 1 => any::<usize>()],
        reg in proptest::option::of((any::<bool>(), 0u8..10, prop_oneof![4 => 0u8..128, 1 => any::<u8>()], any::<u8>())),
        cmd in proptest::option::of((any::<u8>(), prop_oneof![4 => 0u8..4, 1 => any::<u8>()])),
        (position, flags) in (prop_oneof![4 => 0u64..65536, 1 => any::<u64>()], any::<[bool; 3]>()),
    ) {
        let cfg = model::biss::BenchConfig {
            f_sys_mhz: f_sys,
            master: model::biss::MasterSettings { clock_khz: clock, max_delay_ns: max_delay, timeout_us: timeout, cal_frames, delay_tolerance_ns: tol, ..Default::default() },
            slaves: vec![model::biss::SlaveSettings { bits, crc_width, crc_poly, busy_ns: busy, timeout_us: slave_timeout, positions: vec![position], cds_crc_error: flags[0], ..Default::default() }],
            cable: model::line::CableConfig { length_m: cable, jitter_ns: jitter, ..Default::default() },
            host: model::biss::HostSettings {
                frames,
                registers: reg.map(|(write, id, addr, data)| model::biss::RegOp { write, id, addr, data }).into_iter().collect(),
                commands: cmd.map(|(ids, code)| model::biss::CmdOp { ids, code }).into_iter().collect(),
                ..Default::default()
            },
            stuck: flags[1].then_some(model::biss::StuckFault { level: flags[2], from_frame: 1 }),
            delay_step: Some(model::biss::DelayStep { from_frame: 1, extra_ns: step_ns }),
            ..Default::default()
        };
        match cfg.validate() {
            Ok(()) => {
                step_a_while(cfg.bench().expect("a validated setup builds"));
                BISS_RAN.fetch_add(1, Ordering::Relaxed);
            }
            Err(e) => prop_assert!(!e.field().is_empty()),
        }
    }
}

#[test]
fn the_biss_property_test_runs_many_accepted_setups() {
    any_biss_setup_is_accepted_or_refused_by_field();
    let biss = BISS_RAN.load(Ordering::Relaxed);
    // t_busy is left out (the default, 2 x TMAS) or drawn: 250 ns is refused at
    // 2.5 MHz (under 2 x TMAS), so most draws still build and run.
    println!("accepted and run: biss {biss} of 300");
    assert!(biss >= 20, "accepted and run: biss {biss}");
}
