//! Behaviour of the SSI reader and encoder, each test citing what it pins down.

use proptest::prelude::*;

use model::angle::angle_deg;
use model::line::CableConfig;
use model::ssi::*;

fn read(cfg: &BenchConfig) -> Vec<Transaction> {
    Bench::new(cfg)
        .expect("valid scenario")
        .run_to_end()
        .transactions
}

#[test]
fn seed_example_twelve_bits_000111101111_is_495_and_43_5058_degrees() {
    // Seed 001, "Synchronous serial" (4): DATA+ 0 0 0 1 1 1 1 0 1 1 1 1 = 495, θ = 43.5058°.
    let t = &read(&BenchConfig::seed_example())[0];
    assert_eq!(t.sent_bits, "000111101111");
    assert_eq!(t.received_bits, "000111101111");
    assert_eq!(t.position, Some(495));
    assert_eq!(t.angle_deg, Some(43.5058));
    assert!(t.errors.is_empty());
}

#[test]
fn fourteen_clocks_on_a_twelve_bit_encoder_shift_in_zeros_and_exceed_1000_degrees() {
    // Seed 001: "when a 12-bit SSI encoder transmits 14-bit clock pulses ... the maximum
    // angular value can exceed 1,000 degrees without reaching full 1 status".
    let mut cfg = BenchConfig::seed_example();
    cfg.master.bits = 14;
    cfg.positions = vec![4095];
    let t = &read(&cfg)[0];
    assert_eq!(t.position, Some(4095 << 2), "two zeros after the LSB");
    // Converted with the encoder's 12 bits, as the seed does.
    let degrees_as_12_bit = 360.0 * (4095u64 << 2) as f64 / 4096.0;
    assert!(degrees_as_12_bit > 1000.0);
}

#[test]
fn fourteen_clocks_on_a_repeating_encoder_read_the_high_bits_again() {
    // Seed 001: "If the timing is precisely matched, the extra clock pulses may read duplicate high-bit data."
    let mut cfg = BenchConfig::seed_example();
    cfg.master.bits = 14;
    cfg.encoder.after_lsb = AfterLsb::Repeat;
    cfg.positions = vec![0b1000_0000_0001];
    let t = &read(&cfg)[0];
    assert_eq!(t.received_bits, "10000000000110");
}

#[test]
fn eight_clocks_on_a_twelve_bit_encoder_give_the_top_bits_at_most_22_4121_degrees() {
    // Seed 001: 8 clocks on 12-bit data, converted as 12 bits: "up to 22.4121 degrees".
    let mut cfg = BenchConfig::seed_example();
    cfg.master.bits = 8;
    cfg.positions = vec![4095, 495];
    let ts = read(&cfg);
    assert_eq!(ts[0].position, Some(255));
    assert_eq!(angle_deg(255, 12), 22.4121);
    assert_eq!(
        ts[1].position,
        Some(495 >> 4),
        "the encoder let go after its monoflop and stored anew"
    );
}

#[test]
fn gray_encoder_and_gray_reader_agree() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.code = Code::Gray;
    cfg.encoder.code = Code::Gray;
    cfg.positions = vec![495, 2048, 4095];
    let ts = read(&cfg);
    assert_eq!(ts[0].sent_bits, "000100011000");
    assert_eq!(
        ts.iter().map(|t| t.position.unwrap()).collect::<Vec<_>>(),
        vec![495, 2048, 4095]
    );
}

#[test]
fn double_read_of_a_repeating_encoder_passes_and_of_a_zeroing_one_is_flagged() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.double_read = true;
    cfg.encoder.after_lsb = AfterLsb::Repeat;
    assert!(read(&cfg)[0].errors.is_empty());
    cfg.encoder.after_lsb = AfterLsb::Zeros;
    assert_eq!(read(&cfg)[0].errors, vec!["double_read_mismatch"]);
}

#[test]
fn wire_check_flags_a_line_stuck_high_and_a_start_on_a_low_line_is_refused() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.wire_check = true;
    cfg.positions = vec![1, 2, 3];
    cfg.fault = Some(StuckFault {
        level: true,
        from_read: 1,
    });
    let ts = read(&cfg);
    assert!(ts[0].errors.is_empty());
    assert_eq!(ts[1].errors, vec!["wire_check_failed"]);
    cfg.fault = Some(StuckFault {
        level: false,
        from_read: 2,
    });
    let ts = read(&cfg);
    assert!(ts[1].errors.is_empty());
    assert_eq!(ts[2].errors, vec!["line_not_idle"]);
    assert_eq!(ts[2].position, None);
}

#[test]
fn a_read_started_inside_the_monoflop_time_is_refused() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.pause_us = 100.0; // shorter than the encoder's 500 µs T_m
    cfg.positions = vec![1, 2];
    let ts = read(&cfg);
    assert_eq!(ts[1].errors, vec!["line_not_idle"]);
}

#[test]
fn a_long_cable_at_a_fast_clock_needs_the_sample_delay() {
    // 1 MHz through 50 m: 2 × 250 ns + 100 ns round trip exceeds the 500 ns half period.
    let mut cfg = BenchConfig::seed_example();
    cfg.master.clock_khz = 1000.0;
    cfg.cable = CableConfig {
        length_m: 50.0,
        ..CableConfig::default()
    };
    cfg.positions = vec![495];
    assert_ne!(read(&cfg)[0].position, Some(495));
    cfg.master.sample_delay_ns = 300.0;
    assert_eq!(read(&cfg)[0].position, Some(495));
}

#[test]
fn o_done_comes_exactly_read_cycles_after_the_start() {
    let cfg = BenchConfig::seed_example();
    let mc = cfg.master_config().unwrap();
    let t = &read(&cfg)[0];
    assert_eq!(t.done_cycle - t.start_cycle, mc.read_cycles());
}

#[test]
fn impossible_clock_is_refused_naming_the_field() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.clock_khz = 300.0;
    let err = Bench::new(&cfg).err().unwrap();
    assert_eq!(err.field(), "master.clock_khz");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn any_width_code_and_position_round_trips(
        bits in 1u32..=64,
        gray in any::<bool>(),
        raw in any::<u64>(),
        cable in 0.0f64..30.0,
    ) {
        let mask = if bits == 64 { u64::MAX } else { (1u64 << bits) - 1 };
        let code = if gray { Code::Gray } else { Code::Binary };
        let cfg = BenchConfig {
            master: MasterSettings { bits, code, clock_khz: 1000.0, t_cs_us: 1.0, pause_us: 25.0, ..MasterSettings::default() },
            encoder: EncoderSettings { bits, code, monoflop_us: 20.0, ..EncoderSettings::default() },
            cable: CableConfig { length_m: cable, ..CableConfig::default() },
            positions: vec![raw & mask, !raw & mask],
            ..BenchConfig::default()
        };
        let ts = read(&cfg);
        prop_assert_eq!(ts[0].position, Some(raw & mask));
        prop_assert_eq!(ts[1].position, Some(!raw & mask));
        prop_assert!(ts.iter().all(|t| t.errors.is_empty()));
    }
}

/// 4 MHz from 100 MHz is f_sys / 25, an odd divider. The
/// clock is 13 cycles high and 12 low (the high phase takes the extra cycle,
/// `model::time::BitClock`), the capture stays 2 cycles into each low phase,
/// the header names the split, and every value reads back.
#[test]
fn an_odd_divider_is_13_cycles_high_and_12_low_and_reads_every_value() {
    use model::Setup;
    let mut cfg = BenchConfig::seed_example();
    cfg.f_sys_mhz = 100.0;
    cfg.master.clock_khz = 4000.0;
    cfg.master.t_cs_us = 1.0;
    cfg.master.pause_us = 30.0;
    cfg.encoder.monoflop_us = 25.0;
    cfg.cable = CableConfig {
        length_m: 2.0,
        ..CableConfig::default()
    };
    cfg.positions = vec![0, 4095, 495, 2730, 1365];
    let m = cfg.master_config().expect("f_sys / 25 is accepted");
    assert_eq!(
        (m.clocks_per_bit, m.high_clocks, m.low_clocks),
        (25, 13, 12)
    );
    let params = cfg.verilog_parameters().unwrap();
    assert_eq!(
        &params[1..4],
        &[
            ("CLOCKS_PER_BIT", 25),
            ("HIGH_CLOCKS", 13),
            ("LOW_CLOCKS", 12)
        ]
    );
    let ts = read(&cfg);
    assert_eq!(
        ts.iter().map(|t| t.position).collect::<Vec<_>>(),
        cfg.positions.iter().map(|&p| Some(p)).collect::<Vec<_>>()
    );
    assert!(ts.iter().all(|t| t.errors.is_empty()), "{ts:#?}");
    crate::phases::assert_split(
        Bench::new(&cfg).unwrap(),
        0,
        13,
        12,
        "SSI 4 MHz from 100 MHz",
    );
    // An even divider keeps its header as it was: no phase parameters.
    let even = BenchConfig::seed_example();
    assert!(even
        .verilog_parameters()
        .unwrap()
        .iter()
        .all(|(n, _)| !n.ends_with("_CLOCKS") || n.starts_with("T_CS") || n.starts_with("PAUSE")));
}

#[test]
fn a_divider_below_eight_is_refused_naming_the_clock_field_and_the_fastest_clock() {
    let mut cfg = BenchConfig::seed_example();
    cfg.f_sys_mhz = 100.0;
    for khz in [50_000.0, 100_000.0, 20_000.0] {
        cfg.master.clock_khz = khz;
        let e = cfg.master_config().unwrap_err();
        assert_eq!(e.field(), "master.clock_khz");
        assert!(
            e.to_string().contains("at least 8") && e.to_string().contains("12500 kHz (f_sys / 8)"),
            "{e}"
        );
    }
}
