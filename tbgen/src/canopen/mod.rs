//! CANopen in `tbgen`: the [`Protocol`] of `model::canopen::BenchConfig`
//! (core `canopen_master`), `tbgen decode canopen` ([`decode`]: the CAN
//! decoder's frames read as NMT, SYNC, EMCY/boot-up, PDO, SDO with object
//! names, node guarding and heartbeat), `tbgen timing canopen` ([`timing`])
//! and the electronic data sheet of the emulated encoder (`tbgen eds`, [`eds`]).

mod closed_loop;
pub mod decode;
pub mod eds;
pub mod timing;

use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::canopen::BenchConfig;

use crate::registry::{self, Protocol, SigrokCheck, TransactionSignals, WaveNames};
use crate::{Error, Result};

/// CANopen: the CAN line read as CANopen frames.
#[derive(Parser)]
#[command(name = "canopen", after_help = "Examples:\n  tbgen decode canopen vectors/canopen_master/canopen_setup_example.vcd\n  tbgen decode canopen capture.vcd --line top.rxd --bit-rate 500000")]
pub struct DecodeArgs {
    /// The VCD file.
    file: PathBuf,
    /// Dotted path of the receive line.
    #[arg(long, default_value = "top.line.can_rx")]
    line: String,
    /// Nominal bit rate, bit/s.
    #[arg(long, default_value_t = 250_000)]
    bit_rate: u64,
    /// Sample point, fraction of the bit.
    #[arg(long, default_value_t = 0.875)]
    sample_point: f64,
}

/// CANopen: PDO frame time, latency, bus load per encoder and encoders per SYNC cycle at every bit rate.
#[derive(Parser)]
#[command(name = "canopen", after_help = "Examples:\n  tbgen timing canopen\n  tbgen timing canopen --period-ms 1 --cycle-us 500\n  tbgen timing canopen --scenario canopen_cyclic_1ms_1000k")]
pub struct TimingArgs {
    /// Cyclic timer (6200h) of each encoder, ms, for the bus load.
    #[arg(long, default_value_t = 10.0)]
    period_ms: f64,
    /// SYNC cycle, µs, for the encoders that fit one.
    #[arg(long, default_value_t = 1000.0)]
    cycle_us: f64,
    /// A built-in scenario or scenario .toml file with a [canopen] table: its master, as the model drives the bus, held to the rule book.
    #[arg(long)]
    scenario: Option<String>,
}

/// sigrok's `can` decoder option for a scenario: the master's nominal bit rate and sample point.
pub fn sigrok_decoder(cfg: &BenchConfig) -> Option<String> {
    let t = cfg.master_config().ok()?.can.timing;
    let tb = model::Setup::timebase(cfg).ok()?;
    let rate = tb.f_sys_hz() / t.clocks_per_bit();
    Some(format!("can:can_rx=can_rx:nominal_bitrate={rate}:sample_point={}", t.sample_point() * 100.0))
}

impl Protocol for BenchConfig {
    /// The monitor's i_can_rx, i_can_tx: the bus and the node's own TX.
    const MONITOR_PINS: &'static [&'static str] = &["line.can_rx", "line.can_tx"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_booted", "o_config_done", "o_sdo_abort", "o_node_lost", "o_pos_valid", "o_pos_timeout", "o_emcy_valid", "o_sync_sent"], "o_position", "position");
    const SIGROK_DECODER: Option<&'static str> = Some("can");
    const SIGROK_MINIMUM: (usize, usize) = (6, 300);

    /// The master's state by the RTL's names, and its can_controller's
    /// (`can_state`, `monitor_state`) by that core's.
    fn wave_names() -> WaveNames {
        use model::canopen::master::State as M;
        let names = ["WAIT_BOOT", "SDO_SEND", "SDO_WAIT", "NMT_SEND", "RUN", "FAILED"];
        vec![
            ("state", [M::WaitBoot, M::SdoSend, M::SdoWait, M::NmtSend, M::Run, M::Failed].iter().map(|&s| (s as u64, names[s as usize].to_string())).collect()),
            ("can_state", crate::can::state_names()),
            ("monitor_state", crate::can::state_names()),
        ]
    }

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, line, bit_rate, sample_point } = registry::parse_args(args)?;
        if !(1_000..=1_000_000).contains(&bit_rate) || !(0.5..0.95).contains(&sample_point) {
            return Err(Error::Decode(format!("decode canopen: --bit-rate {bit_rate} or --sample-point {sample_point}: give 1000 to 1000000 bit/s and a sample point between 0.5 and 0.95")));
        }
        let frames = decode::decode(&file, &line, bit_rate, sample_point)?;
        decode::to_json(&file, &line, bit_rate, sample_point, &frames)
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { period_ms, cycle_us, scenario } = registry::parse_args(args)?;
        if !(period_ms > 0.0 && period_ms <= 65_535.0 && cycle_us > 0.0 && cycle_us <= 1e7) {
            return Err(Error::Decode(format!("timing canopen: --period-ms {period_ms} or --cycle-us {cycle_us}: give a cyclic timer of 1 to 65535 ms (6200h) and a SYNC cycle above 0 µs")));
        }
        let mut report = timing::report(period_ms, cycle_us);
        if let Some(scenario) = scenario {
            let (s, _) = registry::scenario_of::<BenchConfig>(&scenario, "timing canopen", "a CANopen")?;
            report += &crate::rule_verdict::of_scenario(&s)?;
        }
        Ok(report)
    }

    /// sigrok's `can` decoder on `can_rx` must print, frame by frame, the
    /// identifier, DLC, data bytes, CRC sequence and ACK of every frame the
    /// transcript lists (in every transaction, in order). A scenario with a
    /// remote frame of DLC above 0 (sigrok reads a data field there) or a
    /// damaged frame (errors, another bit rate on the bus) is not compared:
    /// sigrok decodes error flags as frames of their own.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        let decoder = sigrok_decoder(self)?;
        let mut expected = Vec::new();
        for tr in transcript["transactions"].as_array()? {
            for f in tr["frames"].as_array()? {
                if !f["complete"].as_bool()? || !f["errors"].as_array()?.is_empty() {
                    return None;
                }
                // A remote frame (node guarding: DLC 1, no data field) is
                // not compared: sigrok's `can` decoder (libsigrokdecode
                // can/pd.py) takes the data field's length from the DLC
                // even for remote frames, so it reads the CRC as data and
                // loses the frame. Our decoder and the replays check them.
                if (f["data"].as_array()?.len() as u64) < f["dlc"].as_u64()?.min(8) {
                    return None;
                }
                expected.push(Some(f["id"].as_u64()? as u128));
                expected.push(Some(f["dlc"].as_u64()? as u128));
                expected.extend(f["data"].as_array()?.iter().map(|b| b.as_u64().map(|v| v as u128)));
                expected.push(Some(f["crc"].as_u64()? as u128));
                expected.push(Some(f["ack"].as_bool()? as u128));
            }
        }
        Some(SigrokCheck { decoder, annotation: "can=id:ext-id:dlc:data:crc-sequence:ack-slot", expected })
    }

    /// `canopen_master`'s loop: the core's parameters; `sar58k24_can`'s:
    /// can_controller's bit timing and the SAR58K24 the harness commands.
    fn closed_loop(name: &str, table: toml::Table, origin: &str) -> std::result::Result<crate::closed_loop::LoopParameters, String> {
        match name {
            "sar58k24_can" => closed_loop::sar58k24_can(table, origin),
            _ => Ok(crate::closed_loop::LoopParameters { core: crate::closed_loop::core::<Self>(table, origin, &[])?, harness: Vec::new() }),
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    // What the tests below exercise of seed 003 (docs/compliance/canopen.md).
    include!("compliance.rs");

    use model::canopen::bench::{Bench, BusFrame as BusFrameT, Transaction};
    use model::canopen::sdo::abort;
    use model::testbench::Testbench;

    use super::*;
    use crate::builtin;

    fn config(name: &str) -> BenchConfig {
        builtin::find(name).unwrap().setup.get::<BenchConfig>().unwrap().clone()
    }

    /// Runs a built-in scenario to its end; the bench (its encoders) and the transcript.
    fn run(name: &str) -> (Bench, Vec<Transaction>) {
        let mut b = model::Setup::bench(&config(name)).unwrap();
        while !b.finished() {
            b.step(None);
        }
        let t = model::testbench::run_to_end(model::Setup::bench(&config(name)).unwrap()).transactions;
        (b, t)
    }

    fn outcomes(t: &[Transaction]) -> Vec<&str> {
        t.iter().map(|t| t.outcome).collect()
    }

    fn frames(t: &[Transaction]) -> Vec<(u32, Vec<u8>)> {
        t.iter().flat_map(|t| t.frames.iter().map(|f| (f.id, f.data.clone()))).collect()
    }

    /// Seed 003 §8, the setup example: boot-up on 0x80 + node without data,
    /// the SDO write of 6200h sub 0 = 10 on 0x600 + node (the master sends
    /// it with the size indicated, 2Bh, where the note writes 22h: same
    /// object, same value), the confirmation `60 00 62 00` on 0x580 + node,
    /// NMT start `01 <node>` on COB-ID 0, then the position on 0x180 + node
    /// every 10 ms.
    #[test]
    fn the_setup_example_frame_by_frame() {
        let (_, t) = run("canopen_setup_example");
        assert_eq!(outcomes(&t), ["booted", "config_done", "pos_valid", "pos_valid", "pos_valid"]);
        let f = frames(&t);
        assert_eq!(f[0], (0x8C, vec![]));
        assert_eq!(f[1], (0x60C, vec![0x2B, 0x00, 0x62, 0x00, 0x0A, 0x00, 0x00, 0x00]));
        assert_eq!(f[2], (0x58C, vec![0x60, 0x00, 0x62, 0x00, 0, 0, 0, 0]));
        assert_eq!(f[3], (0x000, vec![0x01, 0x0C]));
        assert!(f[4..].iter().all(|(id, d)| *id == 0x18C && d == &4242u32.to_le_bytes()));
        let pdo: Vec<u64> = t.iter().filter(|t| t.outcome == "pos_valid").map(|t| t.cycle).collect();
        // 10 ms within one bit (4 µs at 250 kbit/s), in cycles of the scenario's f_sys.
        let per_us = config("canopen_setup_example").f_sys_mhz as u64;
        for w in pdo.windows(2) {
            assert!((w[1] - w[0]).abs_diff(10_000 * per_us) <= 4 * per_us, "{w:?}");
        }
        assert!(t.iter().filter(|t| t.outcome == "pos_valid").all(|t| t.position == Some(4242) && t.state == 4));
    }

    /// Cyclic TPDO1 at two rates: every 1 ms at 1000 kbit/s with a moving
    /// position (100 000 counts/s: 100 counts per PDO), every 5 ms at 125 kbit/s.
    /// The spacing at the master varies by the stuff bits of the changing
    /// data: at most 16 in a 4-byte frame, so within 16 bits.
    #[test]
    fn cyclic_pdos_at_two_rates() {
        for (name, period, bit, step) in [("canopen_cyclic_1ms_1000k", 40_000u64, 16 * 40u64, 100i64), ("canopen_cyclic_5ms_125k", 200_000, 16 * 320, -10)] {
            let (_, t) = run(name);
            let pdo: Vec<&Transaction> = t.iter().filter(|t| t.outcome == "pos_valid").collect();
            assert!(pdo.len() >= 4, "{name}");
            for w in pdo.windows(2) {
                assert!((w[1].cycle - w[0].cycle).abs_diff(period) <= bit, "{name}: {} {}", w[0].cycle, w[1].cycle);
                assert_eq!(w[1].position.unwrap() as i64 - w[0].position.unwrap() as i64, step, "{name}");
            }
        }
    }

    /// Seed 003 §4.2: TPDO2 follows every n-th SYNC (1801h sub 2 = n = 2).
    #[test]
    fn tpdo2_after_every_second_sync() {
        let (_, t) = run("canopen_sync_tpdo2");
        let o = outcomes(&t);
        assert_eq!(&o[2..], ["sync_sent", "sync_sent", "pos_valid", "sync_sent", "sync_sent", "pos_valid", "sync_sent", "sync_sent", "pos_valid"]);
        assert!(t.iter().filter(|t| t.outcome == "pos_valid").all(|t| t.frames.len() == 1 && t.frames[0].id == 0x287 && t.position == Some(99)));
        assert!(t.iter().filter(|t| t.outcome == "sync_sent").all(|t| t.frames.last().map(|f| (f.id, f.dlc)) == Some((0x080, 0))));
    }

    /// Seed 003 §3.2.1 A: 1000 units per revolution, range 32 000 (binary,
    /// cyclic); turn 31 and a half reads 31 × 1000 + 500 = 31 500.
    #[test]
    fn scaling_example_a_through_the_master() {
        let (b, t) = run("canopen_scaling_cyclic");
        assert_eq!(t.iter().find(|t| t.outcome == "pos_valid").unwrap().position, Some(31_500));
        assert!(b.encoders().next().unwrap().encoder().scaling().cyclic);
    }

    /// Seed 003 §3.2.1 B and §3.3: 100 units per revolution, range 5000 (not
    /// binary: non-cyclic); turn 49 + 8191/8192 reads 4999; the preset 1200
    /// gives offset = preset − current = 1200 − 4999 = −3799 (6509h) and the output 1200.
    #[test]
    fn scaling_example_b_and_preset_through_the_master() {
        let (b, t) = run("canopen_scaling_non_cyclic_preset");
        assert_eq!(t.iter().find(|t| t.outcome == "pos_valid").unwrap().position, Some(1200));
        let e = b.encoders().next().unwrap().encoder();
        assert!(!e.scaling().cyclic);
        assert_eq!(e.read(0x6509, 0).unwrap(), (-3799i32).to_le_bytes().to_vec());
    }

    /// An abort reports its code, index and sub-index and stops the master;
    /// i_start begins again (NMT reset node after BOOT_TIMEOUT, boot-up, the same abort).
    #[test]
    fn an_sdo_abort_is_reported_and_stops_the_master() {
        let (_, t) = run("canopen_sdo_abort");
        assert_eq!(outcomes(&t), ["booted", "sdo_abort", "booted", "sdo_abort"]);
        for a in t.iter().filter(|t| t.outcome == "sdo_abort") {
            assert_eq!(a.abort, Some((abort::TOO_LOW, 0x6001, 0)));
            assert_eq!(a.state, 5, "FAILED");
        }
        assert_eq!(t[2].frames[0].data, vec![0x81, 0x03]);
    }

    /// No boot-up from the awaited node: two NMT resets, then o_node_lost after 3 × BOOT_TIMEOUT.
    #[test]
    fn a_missing_boot_up_ends_in_node_lost() {
        let (_, t) = run("canopen_missing_boot_up");
        assert_eq!(outcomes(&t), ["node_lost"]);
        assert_eq!(t[0].cycle, 3 * 40_000 - 1);
        assert_eq!(frames(&t), [(0x85, vec![]), (0, vec![0x81, 6]), (0, vec![0x81, 6])]);
    }

    /// An encoder at 500 kbit/s on a 250 kbit/s master: only damaged frames, node lost.
    #[test]
    fn an_encoder_at_another_bit_rate_is_never_seen() {
        let (_, t) = run("canopen_other_bit_rate");
        assert_eq!(outcomes(&t), ["node_lost"]);
        assert!(t[0].frames.iter().any(|f| !f.errors.is_empty()));
        assert!(sigrok_check_of("canopen_other_bit_rate").is_none(), "no sigrok comparison over error frames");
    }

    /// The same scenario at the master's CAN controller: after its NMT frame
    /// the bus carries only error flags and is never idle, so the master
    /// stays that frame's transmitter (CAN 2.0: "A unit stays TRANSMITTER
    /// until the bus is idle or the unit loses ARBITRATION"), each error
    /// flag it sends costs TEC 8 (rule 3), and it goes bus-off (rule 10,
    /// measured at 4 136.15 µs) and drives nothing more to the run's end.
    #[test]
    fn a_master_whose_frame_meets_only_error_flags_goes_bus_off_and_falls_silent() {
        let mut b = model::Setup::bench(&config("canopen_other_bit_rate")).unwrap();
        let mut off = None;
        while !b.finished() {
            b.step(None);
            let o = b.master().controller().out();
            if off.is_none() && o.o_err_state == 2 {
                assert!(o.o_tec > 255, "bus-off with TEC {}", o.o_tec);
                off = Some(b.cycle());
            }
            if let Some(at) = off {
                assert!(o.o_can_tx, "TXD dominant at cycle {} after bus-off at {at}", b.cycle());
            }
        }
        let at = off.expect("the master goes bus-off");
        assert!(b.cycle() - at > 100_000, "silent for the rest of the run: {} cycles", b.cycle() - at);
    }

    fn sigrok_check_of(name: &str) -> Option<SigrokCheck> {
        let s = builtin::find(name).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let summary = crate::generate::generate(&s, dir.path()).unwrap();
        let tr: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        s.setup.sigrok(&tr)
    }

    /// An emergency in RUN (seed 003 §9: position error, 1000h, register 01h),
    /// the DS 301 boot-up form, and a stale position between 4 ms PDOs with a 2.5 ms timeout.
    #[test]
    fn emergency_ds301_boot_up_and_pdo_timeout() {
        let (_, t) = run("canopen_emergency_and_timeout");
        assert_eq!(outcomes(&t), ["booted", "config_done", "pos_timeout", "emcy_valid", "pos_valid", "pos_timeout", "pos_valid"]);
        assert_eq!(frames(&t)[0], (0x709, vec![0x00]));
        assert_eq!(t[3].emcy, Some((0x1000, 0x01)));
        // PDO_TIMEOUT after NMT start: 2.5 ms = 100 000 cycles after config_done.
        assert_eq!(t[2].cycle - t[1].cycle, 100_000);
    }

    /// Three encoders: boot-ups in identifier order, only node 2 started.
    #[test]
    fn three_encoders_only_the_masters_node_runs() {
        let (_, t) = run("canopen_three_encoders");
        let ids: Vec<u32> = frames(&t).iter().map(|f| f.0).collect();
        assert_eq!(&ids[..3], [0x81, 0x82, 0x83]);
        assert!(ids[3..].iter().all(|&id| [0x602, 0x582, 0x000, 0x182].contains(&id)), "{ids:x?}");
        assert_eq!(t.iter().filter(|t| t.outcome == "pos_valid").map(|t| t.position).collect::<Vec<_>>(), [Some(222), Some(222)]);
    }

    /// Seed 001 §3.4: the SAR58K24 (14 bits, node 0x20) answers a read with
    /// `47 26` = 9799 = 215.3100°, on 0x100 + node (its examples; the
    /// function-code table's 0x180 + node is the named alternative); after
    /// the zero command the next read is 0.
    #[test]
    fn sar58k24_can_mode_example() {
        let (_, t) = run("canopen_sar58k24_can_mode");
        let answers: Vec<Vec<u8>> = frames(&t).into_iter().filter(|f| f.0 == 0x120).map(|f| f.1).collect();
        assert_eq!(answers.len(), 3);
        assert_eq!(&answers[0][..2], [0x47, 0x26]);
        let v = u16::from_le_bytes([answers[0][0], answers[0][1]]);
        assert_eq!(v, 9799);
        assert_eq!(format!("{:.4}", model::angle::angle_deg(v as u64, 14)), "215.3100");
        assert_eq!(answers[1][0], 0x20, "the zero command's acknowledgement");
        assert_eq!(&answers[2][..2], [0, 0]);
        assert_eq!(outcomes(&t), ["node_lost"], "no CANopen boot-up from a SAR58K24");
    }

    /// Each abort code of the SDO server (CiA 301 codes: seed 003 lists
    /// none) through the master: `80h`, the index and sub-index echoed, the
    /// code little-endian in bytes 4 to 7; o_sdo_abort carries code, index and
    /// the sub-index sent (non-zero for 1800h sub 5 and 1018h sub 4), then FAILED.
    #[test]
    fn every_abort_code_through_the_master() {
        for (name, code, index, sub) in [
            ("canopen_abort_no_object", abort::NO_OBJECT, 0x2000u16, 0u8),
            ("canopen_abort_no_subindex", abort::NO_SUBINDEX, 0x1800, 5),
            ("canopen_abort_read_only", abort::READ_ONLY, 0x1018, 4),
            ("canopen_abort_length", abort::LENGTH, 0x6200, 0),
            ("canopen_abort_range", abort::RANGE, 0x5001, 0),
        ] {
            let (_, t) = run(name);
            assert_eq!(outcomes(&t), ["booted", "sdo_abort"], "{name}");
            assert_eq!(t[1].abort, Some((code, index, sub)), "{name}");
            assert_eq!(t[1].state, 5, "{name}: FAILED");
            let [i0, i1] = index.to_le_bytes();
            let [c0, c1, c2, c3] = code.to_le_bytes();
            assert_eq!(frames(&t)[2], (0x585, vec![0x80, i0, i1, sub, c0, c1, c2, c3]), "{name}");
        }
        assert_eq!(config("canopen_abort_range").master_config().unwrap().can.timing.brp, 1);
    }

    /// Node guarding: each remote frame on 0x700 + node is answered with the
    /// NMT state (05h operational) and bit 7 toggling, first 0; when the
    /// guarding stops, guard time × life time factor (1 ms × 2) later the
    /// encoder sends the life guarding emergency 8130h (error register bit 4).
    #[test]
    fn node_guarding_and_the_life_guarding_emergency() {
        let (_, t) = run("canopen_node_guarding");
        assert_eq!(outcomes(&t), ["booted", "config_done", "emcy_valid"]);
        let f = frames(&t);
        let answers: Vec<&Vec<u8>> = f.iter().filter(|(id, d)| *id == 0x708 && !d.is_empty()).map(|(_, d)| d).collect();
        assert_eq!(answers, [&vec![0x05], &vec![0x85], &vec![0x05]]);
        assert_eq!(t[2].emcy, Some((0x8130, 0x10)));
        assert_eq!(f.last().unwrap(), &(0x88, vec![0x30, 0x81, 0x10, 0, 0, 0, 0, 0]));
        // The emergency 2 ms after the last guarding answer ended, within a frame time.
        let last_answer = t[2].frames.iter().rev().find(|b| b.id == 0x708).unwrap();
        let emcy = t[2].frames.last().unwrap();
        assert!((emcy.sof_cycle - last_answer.sof_cycle).abs_diff(80_000) < 4_000, "{} {}", last_answer.sof_cycle, emcy.sof_cycle);
    }

    /// All eight table entries, in order, with the command of their size
    /// (2Bh, 23h, 2Fh); the heartbeat 1017h = 2 ms: 7Fh while
    /// pre-operational, 05h after NMT start; the preset 1234 read back.
    #[test]
    fn eight_entries_and_the_heartbeat() {
        let (_, t) = run("canopen_eight_params_heartbeat");
        assert_eq!(&outcomes(&t)[..2], ["booted", "config_done"]);
        let f = frames(&t);
        let requests: Vec<(u8, u16, u8)> = f.iter().filter(|(id, _)| *id == 0x608).map(|(_, d)| (d[0], u16::from_le_bytes([d[1], d[2]]), d[3])).collect();
        assert_eq!(requests, [(0x2B, 0x1017, 0), (0x2B, 0x6000, 0), (0x23, 0x6001, 0), (0x23, 0x6002, 0), (0x23, 0x6003, 0), (0x2F, 0x1800, 2), (0x2F, 0x1801, 2), (0x2B, 0x6200, 0)]);
        let beats: Vec<&BusFrameT> = t.iter().flat_map(|t| &t.frames).filter(|b| b.id == 0x708).collect();
        assert_eq!(beats[0].data, [0x7F]);
        assert!(beats.len() >= 3 && beats[1..].iter().all(|b| b.data == [0x05]), "{beats:?}");
        assert!(t.iter().filter(|t| t.outcome == "pos_valid").all(|t| t.position == Some(1234)));
    }

    /// Seed 003 §6: 5001h = 5 written to node 4 takes effect at the reset:
    /// the boot-up comes from node 5, which the master then configures and runs.
    #[test]
    fn a_node_change_takes_effect_after_the_reset() {
        let (b, t) = run("canopen_node_change_reset");
        assert_eq!(&outcomes(&t)[..3], ["booted", "config_done", "pos_valid"]);
        assert_eq!(frames(&t)[..5], [(0x84, vec![]), (0x604, vec![0x2F, 0x01, 0x50, 0x00, 0x05, 0, 0, 0]), (0x584, vec![0x60, 0x01, 0x50, 0x00, 0, 0, 0, 0]), (0x000, vec![0x81, 0x04]), (0x85, vec![])]);
        assert!(t.iter().filter(|t| t.outcome == "pos_valid").all(|t| t.frames.last().unwrap().id == 0x185 && t.position == Some(4444)));
        assert_eq!(b.encoders().next().unwrap().encoder().node(), 5);
    }

    /// Seed 003 §6: 5000h = 4 (250 kbit/s) takes effect at the reset the
    /// master sends after i_start: from then on the encoder's frames are
    /// damaged at 500 kbit/s and the master flags the node lost.
    #[test]
    fn a_bit_rate_change_takes_effect_after_the_reset() {
        let (b, t) = run("canopen_bit_rate_change_reset");
        assert_eq!(outcomes(&t), ["booted", "config_done", "node_lost"]);
        assert_eq!(t[1].frames[0].data, [0x2F, 0x00, 0x50, 0x00, 0x04, 0, 0, 0]);
        let f = &t[2].frames;
        let reset = f.iter().position(|b| b.id == 0 && b.data == [0x81, 0x03]).unwrap();
        assert!(f[reset + 1..].iter().all(|b| !b.errors.is_empty()) && f.len() > reset + 1);
        assert_eq!(b.encoders().next().unwrap().encoder().bit_code(), 4);
    }

    /// No SDO answer: the request again after each SDO_TIMEOUT; a boot-up
    /// during SDO_WAIT restarts the table with all its retries; after
    /// RETRIES = 2 more timeouts, o_node_lost.
    #[test]
    fn sdo_timeouts_retries_and_a_boot_up_during_the_wait() {
        let (_, t) = run("canopen_sdo_no_answer");
        assert_eq!(outcomes(&t), ["booted", "booted", "node_lost"]);
        assert_eq!(t[1].state, 1, "SDO_SEND after the second boot-up");
        let req = |k: usize| t[k].frames.iter().filter(|b| b.id == 0x606).count();
        assert_eq!((req(1), req(2)), (2, 3));
    }

    /// Nobody acknowledges: no frame has its ACK slot dominant, the buffer stays
    /// busy, so the master gives up from SDO_SEND (one SDO_TIMEOUT in SDO_WAIT,
    /// one in SDO_SEND) or, alone on the bus, after RETRIES boot timeouts.
    #[test]
    fn frames_nobody_acknowledges() {
        let (_, t) = run("canopen_no_ack_sdo");
        assert_eq!(outcomes(&t), ["booted", "node_lost"]);
        assert!(t[1].frames.iter().filter(|b| b.id == 0x606 && !b.ack).count() > 5);
        let (_, t) = run("canopen_no_ack_boot");
        assert_eq!(outcomes(&t), ["node_lost"]);
        assert_eq!(t[0].cycle, 3 * 20_000 - 1);
        assert!(t[0].frames.iter().all(|b| b.id == 0 && b.data == [0x81, 0x06] && !b.ack));
    }

    /// A boot-up in RUN (the node reset by a tool): o_booted, the table
    /// again, NMT start, positions again; SYNCs go on around it.
    #[test]
    fn a_boot_up_during_run_configures_again() {
        let (_, t) = run("canopen_reset_in_run");
        let o = outcomes(&t);
        let second = o.iter().enumerate().skip(1).find(|(_, o)| **o == "booted").unwrap().0;
        assert!(t[second - 1].frames.iter().any(|b| b.id == 0 && b.data == [0x81, 0x03]));
        assert_eq!(t[second].frames.last().map(|b| b.id), Some(0x83));
        assert!(o[second + 1..].contains(&"config_done"));
        assert!(o[second + 1..].contains(&"pos_valid") && o.contains(&"sync_sent"));
    }

    /// Bus faults: the master's CRC error on a frame whose bit it read wrong,
    /// the frame sent again and received whole; the stuck-dominant bus;
    /// the master stays in RUN and every position is right.
    #[test]
    fn bus_faults_leave_the_master_running() {
        let (_, t) = run("canopen_bus_faults");
        let all: Vec<&BusFrameT> = t.iter().flat_map(|t| &t.frames).collect();
        let bad = all.iter().position(|b| b.errors.contains(&"crc")).unwrap();
        assert_eq!((all[bad + 1].id, all[bad + 1].data.clone(), all[bad + 1].errors.len()), (0x1ABCDEF, vec![0x12, 0x34], 0));
        assert!(all.iter().any(|b| b.errors.contains(&"stuff")));
        assert!(t.iter().filter(|t| t.outcome == "pos_valid").all(|t| t.position == Some(1111) && t.state == 4));
        assert_eq!(outcomes(&t).iter().filter(|o| **o == "pos_valid").count(), 5);
    }

    /// Bus-off: 32 SYNC attempts, each with an error, then silence for at
    /// least 128 × 11 recessive bits (80 cycles a bit), then the SYNC goes
    /// out and TPDO2 answers.
    #[test]
    fn bus_off_and_recovery() {
        let (_, t) = run("canopen_bus_off");
        let all: Vec<&BusFrameT> = t.iter().flat_map(|t| &t.frames).collect();
        let damaged: Vec<&&BusFrameT> = all.iter().filter(|b| !b.errors.is_empty()).collect();
        assert_eq!(damaged.len(), 32);
        let sync = t.iter().find(|t| t.outcome == "sync_sent").unwrap();
        assert!(sync.frames.last().unwrap().sof_cycle - damaged.last().unwrap().sof_cycle >= 128 * 11 * 80);
        assert!(t.iter().any(|t| t.outcome == "pos_valid" && t.position == Some(2222) && t.frames[0].id == 0x283));
    }

    /// Seed 001 §3.4 ② ③ on the bus: configuration commands are ignored
    /// before `04 01`, answered after it (`11 00`, `13 00` for the codes 00,
    /// 02, 03); node and bit rate wait for the next power-on (the answers stay
    /// on 0x120 at 250 kbit/s); start sends every cycle_ms, `31 20 TT` stops
    /// it, starts a timed send at TT per second and stops it; after the
    /// direction command the count runs backwards; after zero the read is 0.
    #[test]
    fn sar58k24_configuration_and_commands() {
        let (_, t) = run("canopen_sar58k24_config");
        // Cycles per ms of the scenario's f_sys.
        let ms = 1_000 * config("canopen_sar58k24_config").f_sys_mhz as u64;
        let f = frames(&t);
        let cfg: Vec<&Vec<u8>> = f.iter().filter(|(id, _)| *id == 0x7E5).map(|(_, d)| d).collect();
        let b = |x: &[u8]| -> Vec<u8> { let mut v = x.to_vec(); v.resize(8, 0); v };
        assert_eq!(cfg, [&b(&[0x11, 0x21]), &b(&[0x04, 0x01]), &b(&[0x11, 0x21]), &b(&[0x11]), &b(&[0x13, 0, 0]), &b(&[0x13]), &b(&[0x13, 0, 2]), &b(&[0x13]), &b(&[0x13, 0, 3]), &b(&[0x13])]);
        let answers: Vec<&BusFrameT> = t.iter().flat_map(|t| &t.frames).filter(|b| b.id == 0x120).collect();
        let pos = |b: &BusFrameT| u16::from_le_bytes([b.data[0], b.data[1]]) as i64;
        // Start: the answer, then one every 1 ms, counting up 1 a millisecond.
        let stream: Vec<&&BusFrameT> = answers.iter().take_while(|b| b.data[0] != 0x31).collect();
        assert!(stream.len() >= 4);
        for w in stream.windows(2) {
            assert!((w[1].sof_cycle - w[0].sof_cycle).abs_diff(ms) < ms / 40);
            assert_eq!(pos(w[1]) - pos(w[0]), 1);
        }
        let acks: Vec<u8> = answers.iter().filter(|b| b.data[1..].iter().all(|&x| x == 0) && [0x20, 0x22, 0x31].contains(&b.data[0])).map(|b| b.data[0]).collect();
        assert_eq!(acks, [0x31, 0x31, 0x31, 0x22, 0x20]);
        // The timed send: one position 5 ms after the second 31 command.
        let k31: Vec<usize> = answers.iter().enumerate().filter(|(_, b)| b.data[0] == 0x31 && b.data[1] == 0).map(|(k, _)| k).collect();
        assert_eq!(k31[2] - k31[1], 2);
        assert!((answers[k31[1] + 1].sof_cycle - answers[k31[1]].sof_cycle).abs_diff(5 * ms) < ms / 20);
        // Reversed after 22 20: 2^14 − the forward count; zeroed after 20 20.
        let last_two: Vec<&&BusFrameT> = answers.iter().rev().take(3).collect();
        // Zeroed while counting backwards: 0, then 2^14 − 1 ... (the read comes a little later).
        assert!(pos(last_two[0]) <= 2 || pos(last_two[0]) >= 16_384 - 2, "{:?}", last_two[0].data);
        assert_eq!(last_two[1].data, b(&[0x20]));
        assert!(pos(last_two[2]) > 16_384 - 1_100 && pos(last_two[2]) < 16_384 - 1_000, "{:?}", last_two[2].data);
    }

    /// `tbgen decode canopen` on the setup example's waves gives back the transcript's frames and meanings.
    #[test]
    fn decode_canopen_reads_the_setup_example() {
        let s = builtin::find("canopen_setup_example").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let summary = crate::generate::generate(&s, dir.path()).unwrap();
        let decoded = decode::decode(&summary.files[1], "top.line.can_rx", 250_000, 0.875).unwrap();
        let (_, t) = run("canopen_setup_example");
        let want: Vec<&model::canopen::bench::BusFrame> = t.iter().flat_map(|t| &t.frames).collect();
        assert_eq!(decoded.len(), want.len());
        for (d, w) in decoded.iter().zip(want) {
            assert_eq!((d.frame.id, &d.frame.data, d.frame.crc, d.frame.ack), (w.id, &w.data, Some(w.crc), w.ack));
            assert_eq!(d.meaning, w.meaning);
        }
        assert_eq!(decoded[1].meaning, "SDO write 6200h sub 0 (Cyclic timer) = 10 (0xA)");
        let json = decode::to_json(&summary.files[1], "top.line.can_rx", 250_000, 0.875, &decoded).unwrap();
        assert!(json.contains("\"protocol\": \"canopen\"") && json.contains("boot-up of node 12"));
    }

    /// `tbgen timing canopen` from its command line; a bad option is refused naming it.
    #[test]
    fn timing_canopen_from_the_command_line() {
        let m = TimingArgs::command().try_get_matches_from(["canopen", "--period-ms", "10"]).unwrap();
        let r = <BenchConfig as Protocol>::timing(&m).unwrap();
        assert!(r.contains("3.800%"), "{r}");
        let m = TimingArgs::command().try_get_matches_from(["canopen", "--period-ms", "0"]).unwrap();
        assert!(<BenchConfig as Protocol>::timing(&m).unwrap_err().to_string().contains("--period-ms"));
    }

    /// A bad scenario value is an error naming the field.
    #[test]
    fn bad_fields_are_named() {
        let mut c = config("canopen_setup_example");
        c.master.params = vec![model::canopen::master::Param { index: 0x6200, sub: 0, size: 2, value: 1 }; 9];
        assert_eq!(model::Setup::validate(&c).unwrap_err().field(), "master.params");
        let mut c = config("canopen_setup_example");
        c.bit_rate_kbps = 300;
        assert_eq!(model::Setup::validate(&c).unwrap_err().field(), "bit_rate_kbps");
        let mut c = config("canopen_setup_example");
        c.master.boot_timeout_us = 0.0;
        assert_eq!(model::Setup::validate(&c).unwrap_err().field(), "master.boot_timeout_us");
    }
}
