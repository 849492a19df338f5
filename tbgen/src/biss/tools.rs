//! `tbgen timing biss` and `tbgen decode biss`: the BiSS-C cycle budget, and
//! a captured MA/SLO waveform turned into a JSON transcript.

use std::fmt::Write as _;
use std::path::Path;

use model::biss::decode;
pub use model::biss::decode::{FrameSeen, Layout};
use model::biss::{BenchConfig, CmdOp, HostSettings, RegOp};
use model::testbench;
use model::Setup;

use crate::{capture, Error, Result};

/// The cycle budget of one scenario, in TI's published form
/// `t_cycle = T_MA × (frame bits) + line delay + t_busy + timeout`, beside
/// what the cycle model measures for the same set-up.
pub fn timing_report(cfg: &BenchConfig, name: &str) -> std::result::Result<String, model::ConfigError> {
    let mc = cfg.master_config()?;
    let tb = cfg.timebase()?;
    let f_sys = tb.f_sys_hz() as f64;
    let t_ma_ns = mc.clocks_per_bit as f64 / f_sys * 1e9;
    let frame_bits = 2 + mc.frame_bits();
    let delay_ns = 2.0 * cfg.cable.length_m * cfg.cable.ns_per_m + cfg.slaves[0].output_delay_ns;
    let busy_ns = (0..cfg.slaves.len()).map(|i| cfg.busy_ns(i)).fold(0.0, f64::max);
    let timeout_ns = cfg.slaves.iter().map(|s| s.timeout_us).fold(0.0, f64::max) * 1e3;
    let cycle_ns = t_ma_ns * frame_bits as f64 + delay_ns + busy_ns + timeout_ns;
    let mut s = String::new();
    let _ = writeln!(s, "scenario: {name}");
    let _ = writeln!(s, "f_sys: {} MHz   MA: {} kHz = f_sys / {}   T_MA: {:.1} ns", f_sys / 1e6, f_sys / mc.clocks_per_bit as f64 / 1e3, mc.clocks_per_bit, t_ma_ns);
    let _ = writeln!(s, "frame bits: {frame_bits} = 2 (latch, ack) + 1 (start) + per slave (CDS + data + nE + nW + CRC): {:?}", mc.slave_bits);
    let _ = writeln!(s, "t_cycle = T_MA x frame bits + line delay + t_busy + timeout");
    let _ = writeln!(
        s,
        "        = {t_ma_ns:.1} ns x {frame_bits} + {delay_ns:.1} ns + {busy_ns:.1} ns + {:.1} ns = {:.3} us",
        timeout_ns,
        cycle_ns / 1e3
    );
    let _ = writeln!(s, "position-read rate (formula): {:.2} kHz", 1e6 / cycle_ns);
    let _ = writeln!(s, "  in f_sys cycles: {:.0}", cycle_ns * f_sys / 1e9);
    // What the cycle model does with the same set-up (every frame, start to o_done, plus the host gap).
    let mut one = cfg.clone();
    one.host.frames = 2;
    one.host.registers.clear();
    one.host.commands.clear();
    let run = testbench::run_to_end(one.bench()?);
    if let [a, b, ..] = run.transactions.as_slice() {
        let frame = a.done_cycle - a.start_cycle + 1;
        let period = b.start_cycle - a.start_cycle;
        let delay = a.delay_cycles.map_or("not measured (no ack)".to_string(), |d| format!("{d} cycles"));
        let _ = writeln!(s, "model: start to o_done {frame} cycles ({:.3} us), start to start {period} cycles ({:.3} us) = {:.2} kHz, measured line delay {delay}",
            frame as f64 / f_sys * 1e6, period as f64 / f_sys * 1e6, f_sys / period as f64 / 1e3);
        // Why the measured delay exceeds the formula's: the formula counts the
        // cable and the slave's output delay only; the model also counts the
        // registers between the pins and the delay counter.
        if let Some(d) = a.delay_cycles {
            let cable = 2 * cfg.cable.delay_cycles(&tb);
            let output = tb.cycles_nearest_ns(cfg.slaves[0].output_delay_ns);
            let sync = model::biss::SYNC_STAGES;
            let rest = d as i64 - (cable + output + sync) as i64;
            let _ = writeln!(
                s,
                "  measured line delay {d} cycles = {:.1} ns: cable both ways {cable} + slave output delay {output} (the formula's {delay_ns:.1} ns, in whole cycles) + the master's {sync}-flop synchroniser {sync} + {rest} (the delay counter counts the MA edge's own cycle as 1); the formula leaves the synchroniser and the count's start out",
                d as f64 / f_sys * 1e9
            );
        }
    }
    // One register read and one command, each one host operation: the frames
    // the master runs for it back to back, first start to o_reg_done.
    let mut ops = cfg.clone();
    ops.host = HostSettings {
        frames: 0,
        registers: vec![RegOp { write: false, id: 0, addr: 0, data: 0 }],
        commands: vec![CmdOp { ids: 1, code: 0 }],
        ..cfg.host.clone()
    };
    let run = testbench::run_to_end(ops.bench()?);
    let mut first = run.transactions.first().map_or(0, |t| t.start_cycle);
    for t in &run.transactions {
        let what = match (&t.register, &t.command) {
            (Some(_), _) => "register read",
            (_, Some(_)) => "command",
            _ => continue,
        };
        let frames = run.transactions.iter().filter(|u| u.start_cycle >= first && u.start_cycle <= t.start_cycle).count();
        let cycles = t.done_cycle - first + 1;
        let _ = writeln!(s, "model: {what} (one host operation): {frames} frames, {cycles} cycles ({:.1} us)", cycles as f64 / f_sys * 1e6);
        first = run.transactions.iter().find(|u| u.start_cycle > t.done_cycle).map_or(first, |u| u.start_cycle);
    }
    Ok(s)
}

/// Decodes the MA and SLO scalars `ma` / `slo` (dotted paths, e.g.
/// `top.line.ma_master`) of a VCD file into frames with the model's decode
/// core ([`model::biss::decode`], which the co-simulation monitor shares).
pub fn decode(path: &Path, ma: &str, slo: &str, layout: &Layout) -> Result<Vec<FrameSeen>> {
    let signals = capture::read(path, &[(ma, "--ma"), (slo, "--slo")])?;
    let read = |l: &Layout| decode::Decoder::default().feed(&signals[0], &signals[1], l);
    let frames = read(layout);
    decode::check_layout(&frames, layout, read).map_err(|e| Error::Decode(format!("{}: {e}", path.display())))?;
    Ok(frames)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{builtin, generate, scenario::Setup as S};

    fn biss(name: &str) -> (crate::scenario::Scenario, BenchConfig) {
        let s = builtin::find(name).unwrap();
        let S::Biss(cfg) = s.setup.clone() else { panic!("{name} is not BiSS-C") };
        (s, cfg)
    }

    fn layout_of(cfg: &BenchConfig) -> Layout {
        let mc = cfg.master_config().unwrap();
        Layout { bits: mc.slave_bits, crc_width: mc.slave_crc_width, crc_poly: mc.slave_crc_poly, timeout_ps: None }
    }

    /// Decodes the VCD `gen` writes for `name`; returns the decoded frames,
    /// `gen`'s JSON transactions and the system clock period in ps.
    fn decode_generated(name: &str) -> (Vec<FrameSeen>, Vec<serde_json::Value>, f64) {
        let (s, cfg) = biss(name);
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let decoded = decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &layout_of(&cfg)).unwrap();
        let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        // The exact period: at 90 MHz it is 11 111.1 ps, and the waves' edges
        // are each rounded to the nearest picosecond.
        let period_ps = 1e12 / cfg.timebase().unwrap().f_sys_hz() as f64;
        (decoded, json["transactions"].as_array().unwrap().clone(), period_ps)
    }

    #[test]
    fn a_missing_r_or_start_echo_fails_the_access_at_that_frame() {
        for (name, k) in [("biss_fault_no_read_echo", 17), ("biss_fault_no_start_echo", 19)] {
            let (s, _) = biss(name);
            let dir = tempfile::tempdir().unwrap();
            let summary = generate::generate(&s, dir.path()).unwrap();
            let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
            let t = json["transactions"].as_array().unwrap();
            let regs: Vec<&serde_json::Value> = t.iter().filter(|t| !t["register"].is_null()).collect();
            assert_eq!(regs.len(), 1, "{name}: one access");
            assert_eq!((regs[0]["register"]["ok"].as_bool(), regs[0]["register"]["crc4_ok"].as_bool()), (Some(false), Some(true)), "{name}: failed, with a right address CRC");
            assert_eq!(regs[0]["control_index"].as_u64(), Some(k), "{name}: fails at the frame whose echo is missing");
        }
    }

    #[test]
    fn a_wrong_bits_says_the_frame_does_not_fit_and_what_would() {
        let (s, _) = biss("biss_seed_16bit");
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let layout = Layout { bits: vec![12], crc_width: vec![6], crc_poly: vec![3], timeout_ps: None };
        let msg = decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &layout).unwrap_err().to_string();
        assert!(msg.contains("biss_seed_16bit.vcd: --bits 12 with --crc-width 6 read 21 bits after the start bit"), "{msg}");
        assert!(msg.ends_with("--bits 16 would fit (every CRC passes)"), "{msg}");
        let right = Layout { bits: vec![16], ..layout };
        assert!(decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &right).is_ok());
    }

    /// On a long line the master clocks a cell more per period of delay:
    /// 100 m at 10 MHz (9 cells) once drew "--bits 25 would fit" for a
    /// 16-bit frame, 0 m at 5 MHz "--bits 15". The hint is the width with
    /// which every CRC passes.
    #[test]
    fn the_bits_hint_is_right_on_a_long_line_and_a_short_one() {
        for name in ["biss_clock_10mhz_100m", "biss_clock_5mhz_0m"] {
            let (s, _) = biss(name);
            let dir = tempfile::tempdir().unwrap();
            let summary = generate::generate(&s, dir.path()).unwrap();
            let layout = Layout { bits: vec![12], crc_width: vec![6], crc_poly: vec![3], timeout_ps: None };
            let msg = decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &layout).unwrap_err().to_string();
            assert!(msg.ends_with("--bits 16 would fit (every CRC passes)"), "{name}: {msg}");
        }
    }

    #[test]
    fn every_field_the_decoder_prints_equals_the_gen_transcript_of_every_biss_scenario() {
        let names: Vec<String> = builtin::all().unwrap().into_iter().filter(|s| matches!(s.setup, S::Biss(_))).map(|s| s.name).collect();
        assert_eq!(names.len(), 34);
        // biss_fault_timeout reads a 16-bit slave as 8 bits on purpose: its
        // frames fit no layout the master was given, which decode refuses
        // (a_wrong_bits_says_the_frame_does_not_fit_and_what_would).
        let names: Vec<String> = names.into_iter().filter(|n| n != "biss_fault_timeout").collect();
        let (mut frames, mut registers, mut failed_registers, mut flagged, mut unseen) = (0, 0, 0, 0, 0);
        let (mut commands, mut failed_commands) = (0, 0);
        for name in &names {
            let (decoded, model, period_ps) = decode_generated(name);
            // A start refused because SLO is low at IDLE (`line_low_at_start`)
            // never moves MA: the line shows no frame to decode.
            let refused = |t: &&serde_json::Value| t["errors"].as_array().unwrap().iter().any(|e| e == "line_low_at_start");
            unseen += model.iter().filter(refused).count();
            let model: Vec<&serde_json::Value> = model.iter().filter(|t| !refused(t)).collect();
            // `delay_departs_from_mean` compares with the master's start-up
            // mean and tolerance, which the line does not carry.
            let mut model: Vec<serde_json::Value> = model.into_iter().cloned().collect();
            for t in &mut model {
                // `slo_not_released` compares with the master's TIMEOUT_CLOCKS, which the line does not carry either.
                t["errors"].as_array_mut().unwrap().retain(|e| e != "delay_departs_from_mean" && e != "slo_not_released");
            }
            assert_eq!(decoded.len(), model.len(), "{name}");
            for (d, m) in decoded.iter().zip(&model) {
                let d = serde_json::to_value(d).unwrap();
                for (key, value) in d.as_object().unwrap() {
                    match key.as_str() {
                        "start_ps" => {}
                        // gen counts cycles from edge 2 to the ack at the synchroniser's output.
                        "delay_ps" => match (value.as_u64(), m["delay_cycles"].as_u64()) {
                            // SLO already low at edge 2 (a line stuck low): the master's count
                            // ends within the synchroniser's two cycles, wherever the edge fell.
                            (Some(0), Some(cycles)) => assert!(cycles <= 2, "{name}: delay 0 ps, {cycles} cycles"),
                            (Some(ps), Some(cycles)) => assert_eq!((ps as f64 / period_ps - 1e-3).ceil() as u64 + 2, cycles, "{name}: delay {ps} ps"),
                            (a, b) => assert_eq!(a.is_some(), b.is_some(), "{name}: delay"),
                        },
                        "slaves" => {
                            assert_eq!(value.as_array().unwrap().len(), m["slaves"].as_array().unwrap().len(), "{name}");
                            for (ds, ms) in value.as_array().unwrap().iter().zip(m["slaves"].as_array().unwrap()) {
                                for (k, v) in ds.as_object().unwrap() {
                                    assert_eq!(v, &ms[k], "{name} frame {} slave field {k}", d["index"]);
                                }
                            }
                        }
                        // An access that failed in its sync frames (empty `cdm`) is not on the line.
                        "register" if value.is_null() && m[key]["cdm"] == "" => {}
                        // A write that ended before its data went out has no `wdata` on the line.
                        "register" if value.is_object() => {
                            // An access that ended before its address (k = 12) or its R/W
                            // bits (k = 18) went out has only part of them on the line.
                            let sent = m[key]["cdm"].as_str().map_or(0, str::len);
                            for (k, v) in value.as_object().unwrap() {
                                if (sent < 12 && (k == "id" || k == "addr")) || (sent < 18 && k == "write") {
                                    continue;
                                }
                                assert_eq!(v, &m[key][k], "{name} frame {} register field {k}", d["index"]);
                            }
                        }
                        _ => assert_eq!(value, &m[key], "{name} frame {} field {key}", d["index"]),
                    }
                }
                frames += 1;
                registers += m["register"].is_object() as u32;
                failed_registers += (m["register"]["ok"] == false) as u32;
                commands += m["command"].is_object() as u32;
                failed_commands += (m["command"]["ok"] == false) as u32;
                flagged += !m["errors"].as_array().unwrap().is_empty() as u32;
            }
        }
        assert_eq!(
            (registers, failed_registers, unseen),
            (16, 9, 4),
            "register read (and one more with an odd MA divider), write, a wrong write echo and its read back, three CRC-4 faults, three along a chain, two aborted mid-way, one failed in its sync frames, a missing R and a missing S echo; four refused starts (one with a pending read)"
        );
        assert_eq!((commands, failed_commands), (3, 1), "biss_command_chain: addressed, unacknowledged; biss_register_chain: broadcast");
        assert!(frames > 200 && flagged >= 10, "{frames} frames, {flagged} flagged");
    }

    #[test]
    fn an_absent_slave_decodes_as_no_ack() {
        let (decoded, _, _) = decode_generated("biss_fault_no_ack");
        assert_eq!(decoded.len(), 2);
        assert!(decoded.iter().all(|f| f.errors == vec!["no_ack"] && f.received_bits.is_empty()));
    }

    #[test]
    fn timing_budget_of_the_seed_scenario_follows_the_ti_formula() {
        let (s, cfg) = biss("biss_seed_16bit");
        let r = timing_report(&cfg, &s.name).unwrap();
        // 100 ns x 28 bits + 120 ns (10 m both ways + 20 ns output delay) + 200 ns busy + 16 us timeout.
        assert!(r.contains("= 19.120 us"), "{r}");
        // The measured delay is explained, not just printed: 2 x 4 + 2 + 2 + 1 = 13 cycles = 162.5 ns.
        assert!(r.contains("measured line delay 13 cycles = 162.5 ns: cable both ways 8 + slave output delay 2"), "{r}");
        assert!(r.contains("2-flop synchroniser 2 + 1 (the delay counter counts the MA edge's own cycle as 1)"), "{r}");
        assert!(r.contains("52.30 kHz"), "{r}");
        // 14 sync frames, then 33 control frames for a read; the read's last
        // 14 frames already carried CDM = 0, so the command that follows needs
        // one frame (a request starts a control frame at the end of a frame)
        // and its 19.
        assert!(r.contains("register read (one host operation): 47 frames"), "{r}");
        assert!(r.contains("command (one host operation): 20 frames"), "{r}");
    }
}
