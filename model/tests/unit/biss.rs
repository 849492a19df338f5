//! Behaviour of the BiSS-C master, slaves and control frame, each test citing what it pins down.

use proptest::prelude::*;

use model::biss::*;
use model::crc::BISS_CRC6;
use model::line::CableConfig;
use model::testbench::Testbench;
use model::Setup;

fn frames(cfg: &BenchConfig) -> Vec<Transaction> {
    Bench::new(cfg)
        .expect("valid scenario")
        .run_to_end()
        .transactions
}

fn bits(s: &str) -> Vec<bool> {
    s.chars().map(|c| c == '1').collect()
}

#[test]
fn seed_example_crc_of_1000101011100011_with_ne_1_nw_0_is_110101_sent_as_001010() {
    // Seed 001, BiSS-C: "the complete data information code is 100010101110001110 ...
    // the calculated CRC check code is 110101, with its negative logic being 001010".
    let crc = BISS_CRC6.checksum_bits(&bits("100010101110001110"));
    assert_eq!(crc, 0b110101);
    assert_eq!(BISS_CRC6.wire_bits(crc), bits("001010"));
}

#[test]
fn seed_example_frame_decodes_to_35555_and_195_3094_degrees_with_the_warning_set() {
    // Seed 001, BiSS-C: 16-bit 1000101011100011 = 35555, θ = 195.3094°; nE = 1, nW = 0.
    let t = &frames(&BenchConfig::seed_example())[0];
    assert!(t.errors.is_empty(), "{:?}", t.errors);
    let s = &t.slaves[0];
    assert_eq!(
        s.sent_bits,
        "0".to_string() + "1000101011100011" + "10" + "001010"
    );
    assert_eq!(s.position, 35555);
    assert_eq!(s.angle_deg, 195.3094);
    assert!(s.crc_ok && !s.error && s.warning && !s.cds);
    assert_eq!(
        t.received_bits,
        "1".to_string() + &s.sent_bits,
        "start bit, then the section"
    );
}

#[test]
fn the_ack_comes_with_the_second_rising_edge_and_the_delay_is_measured_each_frame() {
    // Seed 001: "The second rising edge of MA+ triggers the encoder to pull SLO+ low".
    let mut cfg = BenchConfig::seed_example();
    cfg.cable = CableConfig {
        length_m: 0.0,
        ..CableConfig::default()
    };
    cfg.slaves[0].output_delay_ns = 0.0;
    let d0 = frames(&cfg)[0].delay_cycles.unwrap();
    // No cable, no output delay: one cycle to the pin (registered transceiver) and two of synchroniser.
    assert_eq!(d0, 1 + SYNC_STAGES);
    cfg.cable.length_m = 100.0;
    let d100 = frames(&cfg)[0].delay_cycles.unwrap();
    // 100 m at 5 ns/m, both ways, at 80 MHz: 2 × 40 cycles more.
    assert_eq!(d100 - d0, 80);
}

#[test]
fn cable_of_0_to_100_m_at_10_mhz_gives_zero_bit_errors() {
    // Line-delay compensation; 0 to 100 m at 10 MHz without a bit error.
    for length in [0.0, 1.0, 7.0, 13.0, 25.0, 50.0, 75.0, 99.0, 100.0] {
        let mut cfg = BenchConfig::seed_example();
        cfg.cable = CableConfig {
            length_m: length,
            ..CableConfig::default()
        };
        cfg.slaves[0].positions = vec![0, 0xFFFF, 0xA5A5, 0x5A5A, 35555];
        cfg.host.frames = 5;
        let ts = frames(&cfg);
        for (k, t) in ts.iter().enumerate() {
            assert!(t.errors.is_empty(), "{length} m frame {k}: {:?}", t.errors);
            assert_eq!(
                t.slaves[0].position,
                cfg.position_at(0, k),
                "{length} m frame {k}"
            );
        }
    }
}

#[test]
fn jitter_of_one_cycle_each_way_on_100_m_at_2_5_mhz_still_reads_clean() {
    // At 2.5 MHz half a bit cell (16 cycles) absorbs the jitter of the ack
    // and of the bit edges even in the start-up frames sampled by their own ack.
    let mut cfg = BenchConfig::seed_example();
    cfg.master.clock_khz = 2500.0;
    cfg.cable = CableConfig {
        length_m: 100.0,
        jitter_ns: 12.0,
        seed: 7,
        ..CableConfig::default()
    };
    cfg.slaves[0].step = 4099;
    cfg.host.frames = 20;
    for t in frames(&cfg) {
        assert!(t.errors.is_empty(), "{:?}", t.errors);
    }
}

#[test]
fn a_flipped_data_ne_nw_or_crc_bit_is_a_crc_error() {
    for bit in [0, 7, 15, 16, 17, 18, 23] {
        let mut cfg = BenchConfig::seed_example();
        cfg.flips = vec![FlipFault {
            frame: 0,
            slave: 0,
            bits: vec![bit],
        }];
        let t = &frames(&cfg)[0];
        assert!(!t.slaves[0].crc_ok, "bit {bit}");
        assert_eq!(t.errors, vec!["crc_error_slave0"], "bit {bit}");
    }
}

#[test]
fn an_absent_slave_leaves_slo_high_and_is_no_ack_not_a_frame() {
    // An open RS-485 line idles high: it must not read as a valid frame.
    let mut cfg = BenchConfig::seed_example();
    cfg.stuck = Some(StuckFault {
        level: true,
        from_frame: 0,
    });
    let t = &frames(&cfg)[0];
    assert_eq!(t.errors, vec!["no_ack"]);
    assert!(t.slaves.is_empty());
}

#[test]
fn slo_stuck_low_refuses_the_start() {
    let mut cfg = BenchConfig::seed_example();
    cfg.host.frames = 2;
    cfg.stuck = Some(StuckFault {
        level: false,
        from_frame: 1,
    });
    let ts = frames(&cfg);
    assert!(ts[0].errors.is_empty());
    assert_eq!(ts[1].errors, vec!["line_low_at_start"]);
}

#[test]
fn a_start_bit_later_than_the_timeout_is_flagged() {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves[0].busy_ns = Some(60_000.0); // longer than the master's 40 µs timeout
    let t = &frames(&cfg)[0];
    assert_eq!(t.errors, vec!["no_start_bit"]);
    assert!(t.slaves.is_empty());
}

#[test]
fn a_cable_longer_than_the_compensation_range_is_flagged_not_misread() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.max_delay_ns = 500.0;
    cfg.cable = CableConfig {
        length_m: 100.0,
        ..CableConfig::default()
    };
    let t = &frames(&cfg)[0];
    assert_eq!(t.errors, vec!["delay_beyond_compensation"]);
    assert!(t.slaves.is_empty());
}

#[test]
fn three_slaves_of_different_widths_are_each_decoded_and_crc_checked() {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves = vec![
        SlaveSettings {
            bits: 12,
            positions: vec![0xABC],
            ..SlaveSettings::default()
        },
        SlaveSettings {
            bits: 26,
            positions: vec![0x2AA_AAAA],
            error: true,
            ..SlaveSettings::default()
        },
        SlaveSettings {
            bits: 64,
            positions: vec![0xDEAD_BEEF_0123_4567],
            crc_width: 8,
            crc_poly: 0x07,
            ..SlaveSettings::default()
        },
    ];
    cfg.flips = vec![FlipFault {
        frame: 1,
        slave: 1,
        bits: vec![3],
    }];
    cfg.host.frames = 2;
    let ts = frames(&cfg);
    let p: Vec<u64> = ts[0].slaves.iter().map(|s| s.position).collect();
    assert_eq!(p, vec![0xABC, 0x2AA_AAAA, 0xDEAD_BEEF_0123_4567]);
    assert!(ts[0].slaves.iter().all(|s| s.crc_ok));
    assert!(ts[0].slaves[1].error && !ts[0].slaves[0].error);
    let ok: Vec<bool> = ts[1].slaves.iter().map(|s| s.crc_ok).collect();
    assert_eq!(
        ok,
        vec![true, false, true],
        "only the corrupted slave fails"
    );
}

#[test]
fn a_master_expecting_the_wrong_width_sees_crc_errors() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.bits = Some(vec![15]);
    assert!(!frames(&cfg)[0].slaves[0].crc_ok);
}

#[test]
fn register_read_returns_the_slave_register_over_the_control_frame() {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves[0].registers = (0..128)
        .map(|a| (a as u8).wrapping_mul(37) ^ 0x5A)
        .collect();
    cfg.host.registers = vec![RegOp {
        write: false,
        id: 0,
        addr: 0x42,
        data: 0,
    }];
    let ts = frames(&cfg);
    let r = ts
        .iter()
        .find_map(|t| t.register.clone())
        .expect("the access ends");
    assert!(r.ok);
    assert_eq!(r.rdata, 0x42u8.wrapping_mul(37) ^ 0x5A);
    // 14 zeros, then control bits k = 0..=32 (the last frame brings the slave's stop bit).
    assert_eq!(ts.len(), 14 + 33);
    assert!(ts.iter().all(|t| t.errors.is_empty()));
}

#[test]
fn register_write_then_read_back_across_frames() {
    let mut cfg = BenchConfig::seed_example();
    cfg.host.registers = vec![
        RegOp {
            write: true,
            id: 0,
            addr: 0x11,
            data: 0xC3,
        },
        RegOp {
            write: false,
            id: 0,
            addr: 0x11,
            data: 0,
        },
    ];
    let bench = Bench::new(&cfg).unwrap();
    let run = bench.run_to_end();
    let regs: Vec<RegResult> = run
        .transactions
        .iter()
        .filter_map(|t| t.register.clone())
        .collect();
    assert_eq!(regs.len(), 2);
    assert!(regs[0].ok && regs[1].ok, "{regs:?}");
    assert_eq!(regs[0].rdata, 0xC3, "the write is echoed");
    assert_eq!(regs[1].rdata, 0xC3, "and reads back");
}

#[test]
fn cdm_is_the_inverted_ma_level_during_the_timeout() {
    // Public BiSS C description: "The inverse state of the MA line during the BiSS time-out is the state of the CDM bit".
    let mut cfg = BenchConfig::seed_example();
    cfg.host.registers = vec![RegOp {
        write: false,
        id: 0,
        addr: 0x01,
        data: 0,
    }];
    let ts = frames(&cfg);
    let sent: String = ts[14..14 + 33]
        .iter()
        .map(|t| if t.cdm { '1' } else { '0' })
        .collect();
    let expected = control::cdm_sequence(&control::Access {
        write: false,
        id: 0,
        addr: 0x01,
        wdata: 0,
        ..control::Access::default()
    });
    assert_eq!(
        sent,
        expected
            .iter()
            .map(|&b| if b { '1' } else { '0' })
            .collect::<String>()
    );
}

#[test]
fn a_crc4_error_in_the_read_answer_fails_the_access() {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves[0].cds_crc_error = true;
    cfg.host.registers = vec![RegOp {
        write: false,
        id: 0,
        addr: 3,
        data: 0,
    }];
    let r = frames(&cfg)
        .iter()
        .find_map(|t| t.register.clone())
        .unwrap();
    assert!(!r.ok);
}

#[test]
fn a_cdm_bit_misread_by_the_slave_fails_the_address_crc4_and_the_access() {
    for k in [3, 8, 13] {
        let mut cfg = BenchConfig::seed_example();
        cfg.slaves[0].cdm_flip_at = Some(k);
        cfg.host.registers = vec![
            RegOp {
                write: true,
                id: 0,
                addr: 9,
                data: 0x77,
            },
            RegOp {
                write: false,
                id: 0,
                addr: 9,
                data: 0,
            },
        ];
        let bench = Bench::new(&cfg).unwrap();
        let regs: Vec<RegResult> = bench
            .run_to_end()
            .transactions
            .iter()
            .filter_map(|t| t.register.clone())
            .collect();
        assert!(!regs[0].ok, "k = {k}");
        assert!(
            regs[1].ok && regs[1].rdata == 0,
            "k = {k}: the refused write left the register alone"
        );
    }
}

#[test]
fn an_access_to_an_id_nobody_has_is_not_acknowledged() {
    let mut cfg = BenchConfig::seed_example();
    cfg.host.registers = vec![RegOp {
        write: false,
        id: 5,
        addr: 3,
        data: 0,
    }];
    assert!(
        !frames(&cfg)
            .iter()
            .find_map(|t| t.register.clone())
            .unwrap()
            .ok
    );
}

#[test]
fn impossible_ma_frequency_is_refused_naming_the_field() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.clock_khz = 12_000.0;
    assert_eq!(Bench::new(&cfg).err().unwrap().field(), "master.clock_khz");
    cfg.master.clock_khz = 3_000.0; // 80 MHz / 26.67
    assert_eq!(Bench::new(&cfg).err().unwrap().field(), "master.clock_khz");
}

#[test]
fn verilog_parameters_pack_per_slave_values_eight_bits_each() {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves = vec![
        SlaveSettings {
            bits: 12,
            ..SlaveSettings::default()
        },
        SlaveSettings {
            bits: 40,
            ..SlaveSettings::default()
        },
    ];
    let p = cfg.verilog_parameters().unwrap();
    assert!(p.contains(&("SLAVE_BITS", 12 | 40 << 8)));
    assert!(p.contains(&("SLAVE_CRC_WIDTH", 6 | 6 << 8)));
}

#[test]
fn campaign_catches_every_one_and_two_bit_corruption() {
    // At least 100 000 random corruptions; every 1- and 2-bit one detected.
    let report = campaign::run(100_000, 16, 6, 2024);
    println!("{report}");
    assert_eq!(report.total(), 100_000);
    for k in [1, 2] {
        let c = report.by_flips[&k];
        assert!(c.detected > 10_000 && c.undetected == 0, "{k} bits: {c:?}");
    }
}

#[test]
fn every_single_and_double_flip_of_the_seed_frame_is_detected() {
    // Seed 001 example frame (24 covered and CRC bits): all 24 single and 276 double corruptions.
    let n = 16 + 2 + 6;
    let position = 0b1000_1010_1110_0011;
    assert!(
        !campaign::detected(16, position, &[]),
        "a clean frame passes"
    );
    for i in 0..n {
        assert!(campaign::detected(16, position, &[i]), "bit {i}");
        for j in i + 1..n {
            assert!(campaign::detected(16, position, &[i, j]), "bits {i}, {j}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn any_width_position_and_cable_round_trips(bits in 1u32..=64, raw in any::<u64>(), cable in 0.0f64..100.0, mhz in prop::sample::select(vec![1000.0, 2500.0, 5000.0, 10000.0])) {
        let mask = if bits == 64 { u64::MAX } else { (1u64 << bits) - 1 };
        let cfg = BenchConfig {
            master: MasterSettings { clock_khz: mhz, ..MasterSettings::default() },
            slaves: vec![SlaveSettings { bits, positions: vec![raw & mask, !raw & mask], timeout_us: 2.0, ..SlaveSettings::default() }],
            cable: CableConfig { length_m: cable, ..CableConfig::default() },
            host: HostSettings { frames: 2, ..HostSettings::default() },
            ..BenchConfig::default()
        };
        let ts = frames(&cfg);
        prop_assert!(ts.iter().all(|t| t.errors.is_empty()), "{:?}", ts.iter().map(|t| t.errors.clone()).collect::<Vec<_>>());
        prop_assert_eq!(ts[0].slaves[0].position, raw & mask);
        prop_assert_eq!(ts[1].slaves[0].position, !raw & mask);
    }
}

/// A master and one slave wired directly (no host model, no cable): what
/// the host sees at the core's ports.
struct Wired {
    master: Master,
    chain: Chain,
    slo: bool,
}

impl Wired {
    fn new(cfg: &BenchConfig) -> Self {
        let master = Master::new(cfg.master_config().unwrap()).unwrap();
        let chain = Chain::new(vec![Slave::new(cfg.slave_config(0).unwrap()).unwrap()], 1);
        Wired {
            master,
            chain,
            slo: true,
        }
    }

    fn step(&mut self, input: In) -> Out {
        let out = self.master.step(&In {
            i_slo: self.slo,
            ..input
        });
        self.slo = self.chain.step(out.o_ma);
        out
    }
}

#[test]
fn a_register_read_is_one_host_operation_the_master_runs_every_frame_itself() {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves[0].registers = vec![0, 0, 0, 0xA7];
    cfg.slaves[0].timeout_us = 2.0;
    let mut w = Wired::new(&cfg);
    for _ in 0..10 {
        w.step(In::default());
    }
    let mut out = w.step(In {
        i_reg_start: true,
        i_reg_addr: 3,
        ..In::default()
    });
    assert!(out.o_reg_busy);
    let (mut done, mut valid, mut cycles) = (0, 0, 0);
    while !out.o_reg_done {
        out = w.step(In::default()); // never i_start
        done += out.o_done as u32;
        valid += out.o_slave_valid as u32;
        cycles += 1;
        assert!(cycles < 2_000_000, "the access never ended");
    }
    assert!(!out.o_reg_err && !out.o_reg_crc_err, "{out:?}");
    assert_eq!(out.o_reg_rdata, 0xA7);
    // 14 sync frames and 33 control frames, each with its position result.
    assert_eq!((done, valid), (47, 47));
    assert!(!w.step(In::default()).o_reg_busy);
}

#[test]
fn a_crc4_error_in_the_answer_is_reported_as_such() {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves[0].cds_crc_error = true;
    cfg.host.registers = vec![RegOp {
        write: false,
        id: 0,
        addr: 0,
        data: 0,
    }];
    let r = frames(&cfg)
        .iter()
        .find_map(|t| t.register.clone())
        .unwrap();
    assert!(!r.ok && !r.crc4_ok, "{r:?}");
    let mut good = BenchConfig::seed_example();
    good.host.registers = cfg.host.registers.clone();
    let r = frames(&good)
        .iter()
        .find_map(|t| t.register.clone())
        .unwrap();
    assert!(r.ok && r.crc4_ok, "{r:?}");
}

#[test]
fn a_line_stuck_low_during_the_sync_frames_ends_the_access_with_an_error() {
    let mut cfg = BenchConfig::seed_example();
    cfg.host.registers = vec![RegOp {
        write: false,
        id: 0,
        addr: 0,
        data: 0,
    }];
    cfg.stuck = Some(StuckFault {
        level: false,
        from_frame: 5,
    });
    let ts = frames(&cfg);
    let r = ts
        .iter()
        .find_map(|t| t.register.clone())
        .expect("the access ends");
    assert!(!r.ok);
    // The master starts frame 5 before the stuck level is through its
    // synchroniser, so that frame fails on the line (no start bit; the "ack"
    // of a low line comes far earlier than the start-up mean) instead of
    // being refused.
    assert_eq!(ts.len(), 6, "five good sync frames, one failed frame");
    assert!(ts[..5].iter().all(|t| t.errors.is_empty()));
    assert_eq!(
        ts[5].errors,
        vec![
            "no_start_bit",
            "slo_not_released",
            "delay_departs_from_mean"
        ]
    );
    assert!(
        ts[5].register.is_some(),
        "the access ends with the failed frame"
    );
}

/// A frame of the bench as a line observer would see it.
fn view(t: &Transaction) -> control::FrameView {
    let mut v = control::FrameView {
        ok: t.errors.iter().all(|e| e.starts_with("crc_error")),
        cdm: t.cdm,
        slaves: t.slaves.len(),
        ..Default::default()
    };
    for s in &t.slaves {
        v.cds[s.slave as usize] = s.cds;
        v.crc_bad[s.slave as usize] = !s.crc_ok;
    }
    v
}

#[test]
fn the_line_observer_follows_control_frames_as_the_master_runs_them() {
    let mut cases = Vec::new();
    let mut read = BenchConfig::seed_example();
    read.slaves[0].registers = vec![9, 8, 7, 6];
    read.host.registers = vec![
        RegOp {
            write: false,
            id: 0,
            addr: 2,
            data: 0,
        },
        RegOp {
            write: true,
            id: 0,
            addr: 1,
            data: 0x5C,
        },
        RegOp {
            write: false,
            id: 4,
            addr: 1,
            data: 0,
        },
    ];
    cases.push(read.clone());
    let mut crc = read.clone();
    crc.slaves[0].cds_crc_error = true;
    cases.push(crc);
    let mut flip = read.clone();
    flip.slaves[0].cdm_flip_at = Some(6);
    cases.push(flip);
    let mut commands = command_chain();
    commands.host.commands = vec![
        CmdOp {
            ids: 0b010,
            code: 3,
        },
        CmdOp {
            ids: 0b1000,
            code: 0,
        },
        CmdOp { ids: 0, code: 1 },
    ];
    let mut observed_commands = Vec::new();
    let mut obs = control::Observer::default();
    for t in frames(&commands) {
        assert_eq!(obs.index(t.cdm), t.control_index, "frame {}", t.index);
        let seen = obs.take(&view(&t));
        assert_eq!(seen.is_some(), t.command.is_some(), "frame {}", t.index);
        if let (Some(o), Some(c)) = (seen, &t.command) {
            assert_eq!(
                (
                    o.access.command,
                    o.access.ids,
                    o.access.code,
                    o.ok,
                    o.last_k as usize + 1
                ),
                (true, c.ids, c.code, c.ok, c.cdm.len())
            );
            observed_commands.push(o.ok);
        }
    }
    assert_eq!(observed_commands, vec![true, false, true]);
    let (mut accesses, mut failed) = (0, 0);
    for cfg in &cases {
        let mut obs = control::Observer::default();
        for t in frames(cfg) {
            assert_eq!(obs.index(t.cdm), t.control_index, "frame {}", t.index);
            let seen = obs.take(&view(&t));
            assert_eq!(seen.is_some(), t.register.is_some(), "frame {}", t.index);
            if let (Some(o), Some(r)) = (seen, &t.register) {
                assert_eq!(
                    (o.access.write, o.access.id, o.access.addr, o.access.wdata),
                    (r.write, r.id, r.addr, r.wdata)
                );
                assert_eq!(
                    (o.rdata, o.ok, o.crc4_ok),
                    (r.rdata, r.ok, r.crc4_ok),
                    "frame {}",
                    t.index
                );
                accesses += 1;
                failed += !r.ok as u32;
            }
        }
    }
    assert_eq!(
        (accesses, failed),
        (9, 5),
        "three accesses per case; ID 4 fails in each, the CRC-4 and CDM faults one more each"
    );
}

/// The calibration scenarios' set-up (scenarios/biss/calibration_*.toml):
/// 2.5 MHz through 100 m with ±12 ns of jitter (seeded), 4 calibrating frames.
fn jittery_calibration(frames: usize, seed: u64) -> BenchConfig {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.clock_khz = 2500.0;
    cfg.slaves[0].step = 4099;
    cfg.slaves[0].timeout_us = 4.0;
    cfg.host = HostSettings {
        frames,
        gap_us: 0.5,
        ..HostSettings::default()
    };
    cfg.cable = CableConfig {
        length_m: 100.0,
        jitter_ns: 12.0,
        seed,
        ..CableConfig::default()
    };
    cfg
}

#[test]
fn the_start_up_mean_is_used_and_a_later_delay_step_is_flagged_but_read() {
    // The set-up of scenarios/biss/calibration_drift.toml.
    let mut cfg = jittery_calibration(12, 7);
    cfg.delay_step = Some(DelayStep {
        from_frame: 8,
        extra_ns: 150.0,
    });
    let ts = frames(&cfg);
    assert_eq!(ts.len(), 12);
    let first4: u64 = ts[..4].iter().map(|t| t.delay_cycles.unwrap()).sum();
    assert!(ts[..3].iter().all(|t| t.delay_mean_cycles.is_none()));
    for t in &ts[3..] {
        assert_eq!(t.delay_mean_cycles, Some(first4 / 4), "frame {}", t.index);
    }
    // The jitter moves single acks, never beyond a quarter MA period.
    let spread: Vec<u64> = ts[..8].iter().map(|t| t.delay_cycles.unwrap()).collect();
    assert!(
        spread.iter().max() != spread.iter().min(),
        "the cable jitters: {spread:?}"
    );
    for t in &ts {
        assert!(
            t.slaves[0].crc_ok && t.slaves[0].position == t.slaves[0].sent_position,
            "frame {}: {t:?}",
            t.index
        );
        let flagged = t.errors == vec!["delay_departs_from_mean"];
        assert_eq!(flagged, t.index >= 8, "frame {}: {:?}", t.index, t.errors);
    }
}

#[test]
fn acks_that_jitter_before_the_start_up_mean_within_the_tolerance_are_sampled_by_it_unflagged() {
    // The set-up of scenarios/biss/calibration_jitter.toml: no delay step,
    // the acks jitter on both sides of the (rounded down) start-up mean.
    let ts = frames(&jittery_calibration(10, 1));
    let mean = ts[3].delay_mean_cycles.expect("the mean after 4 frames");
    let early: Vec<usize> = ts[4..]
        .iter()
        .filter(|t| t.delay_cycles.unwrap() < mean)
        .map(|t| t.index)
        .collect();
    assert!(early.len() >= 2, "acks before the mean {mean}: {early:?}");
    for t in &ts {
        assert!(t.errors.is_empty(), "frame {}: {:?}", t.index, t.errors);
        assert!(
            t.slaves[0].crc_ok && t.slaves[0].position == t.slaves[0].sent_position,
            "frame {}: {t:?}",
            t.index
        );
    }
}

#[test]
fn calibration_settings_out_of_range_are_refused_naming_the_field() {
    let mut cfg = BenchConfig::seed_example();
    cfg.master.cal_frames = 3;
    assert!(cfg
        .master_config()
        .unwrap_err()
        .to_string()
        .contains("master.cal_frames"));
    let mut cfg = BenchConfig::seed_example();
    cfg.master.delay_tolerance_ns = Some(50.0); // half of 100 ns
    assert!(cfg
        .master_config()
        .unwrap_err()
        .to_string()
        .contains("master.delay_tolerance_ns"));
}

fn command_chain() -> BenchConfig {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves = (0..3)
        .map(|_| SlaveSettings {
            bits: 12,
            timeout_us: 2.0,
            ..SlaveSettings::default()
        })
        .collect();
    cfg.host.gap_us = 0.5;
    cfg
}

fn commands_run(cfg: &BenchConfig) -> (Vec<CmdResult>, Vec<Vec<u8>>) {
    let mut bench = Bench::new(cfg).unwrap();
    while !bench.finished() {
        bench.step(None);
    }
    let executed = bench
        .chain()
        .slaves()
        .iter()
        .map(|s| s.executed_commands().to_vec())
        .collect();
    let results = bench
        .into_transactions()
        .into_iter()
        .filter_map(|t| t.command)
        .collect();
    (results, executed)
}

#[test]
fn an_addressed_command_is_carried_out_by_the_selected_slaves_only_and_a_broadcast_by_all() {
    let mut cfg = command_chain();
    cfg.host.commands = vec![
        CmdOp {
            ids: 0b010,
            code: 3,
        },
        CmdOp {
            ids: 0b101,
            code: 2,
        },
        CmdOp { ids: 0, code: 1 },
    ];
    let (results, executed) = commands_run(&cfg);
    assert_eq!(
        results.iter().map(|r| r.ok).collect::<Vec<_>>(),
        vec![true, true, true]
    );
    assert_eq!(executed, vec![vec![2, 1], vec![3, 1], vec![2, 1]]);
    // S, CTS = 0, IDS 00000010, CMD 11, the CRC-4 of those 11 bits inverted, 0, EX, 0.
    let crc = &model::crc::BISS_CTRL_CRC4;
    let covered = bits("00000001011");
    let wire: String = crc
        .wire_bits(crc.checksum_bits(&covered))
        .iter()
        .map(|&b| if b { '1' } else { '0' })
        .collect();
    assert_eq!(results[0].cdm, format!("100000001011{wire}010"));
}

#[test]
fn a_command_nobody_acknowledges_fails_and_nothing_is_carried_out() {
    let mut cfg = command_chain();
    cfg.host.commands = vec![CmdOp {
        ids: 0b1000_0000,
        code: 2,
    }];
    let (results, executed) = commands_run(&cfg);
    assert!(!results[0].ok);
    assert_eq!(
        results[0].cdm.len() as u32,
        control::K_IDA + 1,
        "no EX after a missing IDA"
    );
    assert!(executed.iter().all(|e| e.is_empty()));
    // One slave misreads a CRC bit: its IDA is missing, the master sends no EX to anybody.
    let mut cfg = command_chain();
    cfg.slaves[2].cdm_flip_at = Some(13);
    cfg.host.commands = vec![CmdOp { ids: 0, code: 1 }];
    let (results, executed) = commands_run(&cfg);
    assert!(!results[0].ok);
    assert!(executed.iter().all(|e| e.is_empty()), "{executed:?}");
}

#[test]
fn the_start_up_mean_reads_through_ack_jitter_that_own_edge_sampling_misreads() {
    // 10 MHz MA at 80 MHz: half a bit cell is 4 cycles. A 100 m cable whose
    // edges jitter by ±1 cycle each way moves every ack by up to ±2 cycles;
    // sampled by its own ack (tolerance 0: every departure falls back to
    // it) a frame then often misses its cells, sampled by the mean of 16
    // start-up acks it reads clean once calibrated.
    let run = |tol_ns: f64| {
        let mut cfg = BenchConfig::seed_example();
        cfg.master.cal_frames = 16;
        cfg.master.delay_tolerance_ns = Some(tol_ns);
        cfg.slaves[0].step = 4099;
        cfg.slaves[0].timeout_us = 2.0;
        cfg.host = HostSettings {
            frames: 400,
            gap_us: 0.5,
            ..HostSettings::default()
        };
        cfg.cable = CableConfig {
            length_m: 100.0,
            jitter_ns: 12.0,
            seed: 3,
            ..CableConfig::default()
        };
        let ts = frames(&cfg);
        let bad: Vec<usize> = ts
            .iter()
            .filter(|t| t.slaves.iter().any(|s| !s.crc_ok))
            .map(|t| t.index)
            .collect();
        bad
    };
    let own_edge = run(0.0);
    let mean = run(37.5); // 3 cycles, below half a cell
    assert!(
        own_edge.len() >= 20,
        "own-edge sampling: {} CRC errors in 400 frames",
        own_edge.len()
    );
    assert!(
        mean.iter().all(|&k| k < 16),
        "after calibration the mean reads every frame: errors in frames {mean:?}"
    );
}

#[test]
fn a_fault_in_a_frame_the_run_never_reaches_is_refused_with_the_count() {
    let mut cfg = BenchConfig::seed_example();
    cfg.host.frames = 6;
    cfg.flips = vec![FlipFault {
        frame: 5,
        slave: 0,
        bits: vec![0],
    }];
    assert!(cfg.validate().is_ok());
    cfg.flips[0].frame = 40;
    let e = cfg.validate().unwrap_err();
    assert_eq!(e.field(), "flips[0].frame");
    assert!(
        e.to_string().contains("frame 40, but the run has 6 frames"),
        "{e}"
    );
    cfg.flips.clear();
    cfg.stuck = Some(StuckFault {
        level: true,
        from_frame: 6,
    });
    assert_eq!(cfg.validate().unwrap_err().field(), "stuck.from_frame");
}

#[test]
fn register_access_and_commands_keep_tmash_tmasl_and_t_busy_at_every_ma_rate() {
    // Seed 001, BiSS-C timing table: TMASH and TMASL > 25 ns, Tbusy at least
    // 2 x TMAS. Register read, write and a command at 80 MHz from 100 kHz to
    // 10 MHz (every even divider of this sweep), MA stopping low for CDM = 1.
    for khz in [
        100.0, 250.0, 500.0, 1000.0, 2000.0, 2500.0, 4000.0, 5000.0, 10_000.0,
    ] {
        let cfg = BenchConfig {
            master: MasterSettings {
                clock_khz: khz,
                timeout_us: 400.0,
                ..MasterSettings::default()
            },
            slaves: vec![SlaveSettings {
                timeout_us: 30.0,
                registers: vec![0x5A, 0xA5],
                ..SlaveSettings::default()
            }],
            host: HostSettings {
                registers: vec![
                    RegOp {
                        write: false,
                        id: 0,
                        addr: 1,
                        data: 0,
                    },
                    RegOp {
                        write: true,
                        id: 0,
                        addr: 0,
                        data: 0x3C,
                    },
                ],
                commands: vec![CmdOp { ids: 0, code: 1 }],
                ..HostSettings::default()
            },
            ..BenchConfig::default()
        };
        let bad = seed_timing::check(&cfg).expect("valid scenario");
        assert!(
            bad.is_empty(),
            "{khz} kHz: {} violations, first: {}",
            bad.len(),
            bad[0]
        );
    }
}

/// Odd MA dividers. MA is HIGH_CLOCKS = period - period / 2
/// high and LOW_CLOCKS = period / 2 low, every phase (frame ends and the gaps
/// of a register access included) keeps TMASH and TMASL (> 25 ns) and Tbusy,
/// and every frame reads back, at odd dividers from 9 to 25.
#[test]
fn odd_ma_dividers_split_high_first_keep_the_seed_timing_and_read_back() {
    for (mhz, khz, high, low) in [
        (90.0, 10_000.0, 5, 4),
        (100.0, 4000.0, 13, 12),
        (55.0, 5000.0, 6, 5),
        (62.5, 2500.0, 13, 12),
    ] {
        let mut cfg = BenchConfig {
            f_sys_mhz: mhz,
            master: MasterSettings {
                clock_khz: khz,
                timeout_us: 400.0,
                ..MasterSettings::default()
            },
            slaves: vec![SlaveSettings {
                timeout_us: 30.0,
                registers: vec![0x5A, 0xA5],
                ..SlaveSettings::default()
            }],
            host: HostSettings {
                registers: vec![RegOp {
                    write: false,
                    id: 0,
                    addr: 1,
                    data: 0,
                }],
                ..HostSettings::default()
            },
            ..BenchConfig::default()
        };
        let m = cfg
            .master_config()
            .unwrap_or_else(|e| panic!("{khz} kHz from {mhz} MHz refused: {e}"));
        assert_eq!(
            (m.high_clocks, m.low_clocks),
            (high, low),
            "{khz} kHz from {mhz} MHz"
        );
        let bad = seed_timing::check(&cfg).expect("valid scenario");
        assert!(
            bad.is_empty(),
            "{khz} kHz from {mhz} MHz: {} violations, first: {}",
            bad.len(),
            bad[0]
        );
        crate::phases::assert_split(
            Bench::new(&cfg).unwrap(),
            0,
            high,
            low,
            &format!("MA {khz} kHz from {mhz} MHz"),
        );
        let ts = frames(&cfg);
        let reg = ts
            .iter()
            .find_map(|t| t.register.as_ref())
            .expect("the register read ends");
        assert!(reg.ok && reg.rdata == 0xA5, "{reg:?}");
        cfg.host.registers.clear();
        cfg.host.frames = 6;
        let ts = frames(&cfg);
        assert!(
            ts.iter()
                .all(|t| t.errors.is_empty() && t.slaves[0].position == t.slaves[0].sent_position),
            "{ts:#?}"
        );
    }
}

/// A register access of slave 0 (`data` only for a write).
fn access(write: bool, addr: u8, data: u8) -> RegOp {
    RegOp {
        write,
        id: 0,
        addr,
        data,
    }
}

/// The register results of a run, in order.
fn accesses(cfg: &BenchConfig) -> Vec<RegResult> {
    frames(cfg).into_iter().filter_map(|t| t.register).collect()
}

#[test]
fn a_crc4_wrong_in_any_one_bit_of_the_read_answer_is_a_crc_error_with_the_data_right() {
    for bit in 0..4 {
        let mut cfg = BenchConfig::seed_example();
        cfg.slaves[0].registers = vec![0x5A];
        cfg.slaves[0].cds_crc_error = true;
        cfg.slaves[0].cds_crc_bit = bit;
        cfg.host.registers = vec![access(false, 0, 0)];
        let r = &accesses(&cfg)[0];
        assert!(!r.ok && !r.crc4_ok && r.rdata == 0x5A, "bit {bit}: {r:?}");
    }
}

#[test]
fn a_wrong_write_echo_with_its_own_crc4_fails_the_write_without_a_crc_error_and_stores_nothing() {
    let mut cfg = BenchConfig::seed_example();
    cfg.slaves[0].cds_write_echo = Some(0x3D);
    cfg.host.registers = vec![access(true, 0x10, 0x3C), access(false, 0x10, 0)];
    let rs = accesses(&cfg);
    assert_eq!(rs.len(), 2, "{rs:?}");
    assert!(
        !rs[0].ok && rs[0].crc4_ok && rs[0].rdata == 0x3D,
        "{:?}",
        rs[0]
    );
    assert!(rs[1].ok && rs[1].rdata == 0, "{:?}", rs[1]);
}

#[test]
fn control_faults_that_cannot_happen_are_refused_with_the_field() {
    let mut cfg = BenchConfig::seed_example();
    cfg.host.registers = vec![access(false, 0, 0)];
    cfg.slaves[0].cds_crc_error = true;
    cfg.slaves[0].cds_crc_bit = 4;
    let e = cfg.validate().unwrap_err();
    assert_eq!(e.field(), "slaves[0].cds_crc_bit");
    assert!(
        e.to_string().contains("from 0 (the first sent) to 3"),
        "{e}"
    );
    cfg.slaves[0].cds_crc_error = false;
    cfg.slaves[0].cds_crc_bit = 3;
    let e = cfg.validate().unwrap_err();
    assert_eq!(e.field(), "slaves[0].cds_crc_bit");
    assert!(e.to_string().contains("set cds_crc_error = true"), "{e}");
    cfg.slaves[0].cds_crc_bit = 0;
    cfg.slaves[0].cds_write_echo = Some(0x11);
    let e = cfg.validate().unwrap_err();
    assert_eq!(e.field(), "slaves[0].cds_write_echo");
    assert!(e.to_string().contains("no register write to ID 0"), "{e}");
    cfg.host.registers[0].write = true;
    assert!(cfg.validate().is_ok());
}
