//! `tbgen timing biss` and `tbgen decode biss`: the BiSS-C cycle budget, and
//! a captured MA/SLO waveform turned into a JSON transcript.

use std::fmt::Write as _;
use std::path::Path;

use model::angle::angle_deg;
use model::biss::{control, data_crc, BenchConfig, CmdOp, HostSettings, RegOp, MAX_SLAVES};
use model::testbench;
use model::Setup;
use serde::Serialize;

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

/// One slave's part of a decoded frame: the fields of the `gen`
/// transcript's `slaves` entries that the line shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlaveSeen {
    /// Chain position.
    pub slave: u8,
    /// The decoded data.
    pub position: u64,
    /// `360° × position / 2^bits`, cut to 4 decimals.
    pub angle_deg: f64,
    /// nE was 0.
    pub error: bool,
    /// nW was 0.
    pub warning: bool,
    /// The CDS bit.
    pub cds: bool,
    /// The CRC matched.
    pub crc_ok: bool,
}

/// One decoded frame, with the field names of the model's transaction in the
/// `gen` transcript. Left out, because only the model knows them: cycle
/// numbers, what the slave was told to send. Times are in ps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameSeen {
    /// 0-based, counting the frames visible on MA.
    pub index: usize,
    /// The first falling MA edge, ps.
    pub start_ps: u64,
    /// Second rising MA edge to the ack at the master's end, ps, when the ack
    /// came while MA was running.
    pub delay_ps: Option<u64>,
    /// The CDM bit: MA stopped low after the last clock.
    pub cdm: bool,
    /// Control-frame index of that bit, when a control frame was running.
    pub control_index: Option<u32>,
    /// Every bit read after the ack (start bit first).
    pub received_bits: String,
    /// Each slave's result, in chain order.
    pub slaves: Vec<SlaveSeen>,
    /// `no_ack`, `delay_beyond_compensation`, `no_start_bit`, per slave
    /// `crc_error_slave<i>`; `short_frame` (fewer than two rising MA edges,
    /// a capture cut short) is the decoder's own.
    pub errors: Vec<String>,
    /// A register access that ended with this frame.
    pub register: Option<RegisterSeen>,
    /// A command (`CTS = 0`) that ended with this frame.
    pub command: Option<CommandSeen>,
    /// Cells MA clocked after the start bit, and the cells the layout reads.
    #[serde(skip)]
    pub cells: Option<(u64, u64)>,
}

/// A command read off the CDM and CDS bits: the fields of the `gen`
/// transcript's `command`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CommandSeen {
    /// Slave-select bits IDS (0 = broadcast).
    pub ids: u8,
    /// The command.
    pub code: u8,
    /// Every selected slave acknowledged (IDA) and echoed EX.
    pub ok: bool,
    /// The CDM bits sent, `k = 0` to the frame that ended the command.
    pub cdm: String,
}

/// A register access read off the CDM and CDS bits: the fields of the `gen`
/// transcript's `register`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegisterSeen {
    /// Write or read.
    pub write: bool,
    /// Slave ID.
    pub id: u8,
    /// Address.
    pub addr: u8,
    /// Data written (0 on a read); left out when the access ended before
    /// the master sent it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wdata: Option<u8>,
    /// Data read, or the slave's echo of a write, as far as it came.
    pub rdata: u8,
    /// The access succeeded.
    pub ok: bool,
    /// `false` when the answer came with a wrong CRC-4.
    pub crc4_ok: bool,
    /// The CDM bits sent, `k = 0` to the frame that ended the access.
    pub cdm: String,
}

/// Per-slave layout the decoder expects.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// Data bits per slave.
    pub bits: Vec<u32>,
    /// CRC width per slave.
    pub crc_width: Vec<u32>,
    /// CRC polynomial per slave.
    pub crc_poly: Vec<u64>,
}

/// Decodes the MA and SLO scalars `ma` / `slo` (dotted paths, e.g.
/// `top.line.ma_master`) of a VCD file into frames. The master end's signals
/// are expected: the ack edge gives the round-trip delay, and each bit is
/// read half an MA period after its rising edge plus that delay. Control
/// frames are followed from the CDM (MA level after the last clock) and CDS
/// bits by the master's rules ([`control::Observer`]).
pub fn decode(path: &Path, ma: &str, slo: &str, layout: &Layout) -> Result<Vec<FrameSeen>> {
    let signals = capture::read(path, &[(ma, "--ma"), (slo, "--slo")])?;
    let (ma_line, slo_line) = (&signals[0], &signals[1]);
    let edges = ma_line.edges();
    let mut frames = Vec::new();
    let mut observer = control::Observer::default();
    let mut i = 0;
    while i < edges.len() {
        if edges[i].1 {
            i += 1; // MA returning high after a CDM = 1 timeout
            continue;
        }
        // A burst: edges no further apart than 3 half periods.
        let mut j = i + 1;
        let mut half = None;
        while j < edges.len() {
            let gap = edges[j].0 - edges[j - 1].0;
            if gap > 3 * *half.get_or_insert(gap) {
                break;
            }
            j += 1;
        }
        let burst = &edges[i..j];
        let next_start = edges[j..].iter().find(|e| !e.1).map_or(u64::MAX, |e| e.0);
        let mut f = read_frame(frames.len(), burst, next_start, slo_line, layout);
        f.control_index = observer.index(f.cdm);
        let ok = f.errors.iter().all(|e| e.starts_with("crc_error"));
        let mut view = control::FrameView { ok, cdm: f.cdm, slaves: f.slaves.len(), ..Default::default() };
        for s in f.slaves.iter().filter(|s| (s.slave as usize) < MAX_SLAVES) {
            view.cds[s.slave as usize] = s.cds;
            view.crc_bad[s.slave as usize] = !s.crc_ok;
        }
        if let Some(o) = observer.take(&view) {
            let a = o.access;
            let cdm = model::bits::string(&control::cdm_sequence(&a)[..=o.last_k as usize]);
            if a.command {
                f.command = Some(CommandSeen { ids: a.ids, code: a.code, ok: o.ok, cdm });
            } else {
                let wdata_seen = !a.write || o.last_k >= control::K_DATA_CRC - 1;
                f.register = Some(RegisterSeen { write: a.write, id: a.id, addr: a.addr, wdata: wdata_seen.then_some(a.wdata), rdata: o.rdata, ok: o.ok, crc4_ok: o.crc4_ok, cdm });
            }
        }
        frames.push(f);
        i = j;
    }
    check_layout(path, &frames, layout)?;
    Ok(frames)
}

/// Cells MA clocks after the last CRC bit before it stops (the master's
/// stop bit and the first timeout clock, as biss_master does): not frame bits.
const TRAILING_CELLS: u64 = 2;

/// A layout that fits no frame (every frame clocked a different number of
/// cells after its start bit than the layout reads, and every CRC failed) is
/// the wrong `--bits` or `--crc-width`, not a line full of errors: say so,
/// and what would fit.
fn check_layout(path: &Path, frames: &[FrameSeen], layout: &Layout) -> Result<()> {
    let read: Vec<&FrameSeen> = frames.iter().filter(|f| f.cells.is_some()).collect();
    let misfit = |f: &&FrameSeen| f.cells.is_some_and(|(clocked, need)| clocked != need) && f.slaves.iter().all(|s| !s.crc_ok);
    if read.is_empty() || !read.iter().all(misfit) {
        return Ok(());
    }
    let (clocked, need) = read[0].cells.expect("filtered on cells");
    let list = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(",");
    let last_w = *layout.crc_width.last().unwrap_or(&6) as u64;
    let others = need - (1 + *layout.bits.last().unwrap_or(&0) as u64 + 2 + last_w);
    let hint = match clocked.checked_sub(others + 3 + last_w) {
        Some(n) if (1..=64).contains(&n) => format!("; with the same CRC widths, --bits {} would fit", {
            let mut b = layout.bits.clone();
            *b.last_mut().expect("at least one slave") = n as u32;
            list(&b)
        }),
        _ => String::new(),
    };
    Err(Error::Decode(format!(
        "{}: the frames carry {clocked} bits after the start bit, but --bits {} with --crc-width {} read {need} (per slave: CDS, data, nE, nW, CRC), and every CRC fails{hint}",
        path.display(),
        list(&layout.bits),
        list(&layout.crc_width),
    )))
}

/// One frame from its MA burst (falling edge first) and SLO; `next_start`
/// bounds the search for a late ack.
fn read_frame(index: usize, burst: &[(u64, bool)], next_start: u64, slo: &capture::Signal, layout: &Layout) -> FrameSeen {
    let t0 = burst[0].0;
    let cdm = burst.last().is_some_and(|e| !e.1);
    let mut f = FrameSeen {
        index,
        start_ps: t0,
        delay_ps: None,
        cdm,
        control_index: None,
        received_bits: String::new(),
        slaves: Vec::new(),
        errors: Vec::new(),
        register: None,
        command: None,
        cells: None,
    };
    let rises: Vec<u64> = burst.iter().filter(|e| e.1).map(|e| e.0).collect();
    if rises.len() < 2 || burst.len() < 2 {
        f.errors.push("short_frame".into());
        return f;
    }
    let period = 2 * (burst[1].0 - t0);
    let r2 = rises[1];
    let last = burst[burst.len() - 1].0;
    // The ack is SLO falling after the second rising edge, while MA runs; a
    // later one is beyond the master's compensation, none at all no ack.
    match slo.next_level(r2, false) {
        Some(ack) if ack <= last => {
            let delay = ack - r2;
            f.delay_ps = Some(delay);
            read_sections(&mut f, r2 + delay, period, rises.len() as u64, slo, layout);
        }
        Some(ack) if ack < next_start => f.errors.push("delay_beyond_compensation".into()),
        _ => f.errors.push("no_ack".into()),
    }
    f
}

/// The start bit and every slave's section, cell `m` read at
/// `ack + m·period + period/2` (the middle of the cell that rising edge
/// `2 + m` sent), while MA clocked it (`m <= rises - 2`).
fn read_sections(f: &mut FrameSeen, ack: u64, period: u64, rises: u64, slo: &capture::Signal, layout: &Layout) {
    let cell = |m: u64| slo.level_at(ack + m * period + period / 2);
    let Some(start) = (1..=rises.saturating_sub(2)).find(|&m| cell(m)) else {
        f.errors.push("no_start_bit".into());
        return;
    };
    let need: u64 = layout.bits.iter().zip(&layout.crc_width).map(|(n, w)| (1 + n + 2 + w) as u64).sum();
    f.cells = Some((rises.saturating_sub(2 + TRAILING_CELLS) - start, need));
    let mut m = start;
    let mut received = vec![true];
    for s in 0..layout.bits.len() {
        let (n, w) = (layout.bits[s] as usize, layout.crc_width[s] as usize);
        let section: Vec<bool> = (1..=(1 + n + 2 + w) as u64).map(|k| cell(m + k)).collect();
        m += section.len() as u64;
        received.extend(&section);
        let covered = &section[1..1 + n + 2];
        let alg = data_crc(w as u32, layout.crc_poly[s]);
        let crc_ok = alg.crc_from_wire_bits(&section[1 + n + 2..]) == Some(alg.checksum_bits(covered));
        let position = covered[..n].iter().fold(0u64, |a, &b| (a << 1) | b as u64);
        if !crc_ok {
            f.errors.push(format!("crc_error_slave{s}"));
        }
        f.slaves.push(SlaveSeen {
            slave: s as u8,
            position,
            angle_deg: angle_deg(position, n as u32),
            error: !covered[n],
            warning: !covered[n + 1],
            cds: section[0],
            crc_ok,
        });
    }
    f.received_bits = model::bits::string(&received);
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
        Layout { bits: mc.slave_bits, crc_width: mc.slave_crc_width, crc_poly: mc.slave_crc_poly }
    }

    /// Decodes the VCD `gen` writes for `name`; returns the decoded frames,
    /// `gen`'s JSON transactions and the system clock period in ps.
    fn decode_generated(name: &str) -> (Vec<FrameSeen>, Vec<serde_json::Value>, u64) {
        let (s, cfg) = biss(name);
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let decoded = decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &layout_of(&cfg)).unwrap();
        let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        let period_ps = 1_000_000_000_000 / cfg.timebase().unwrap().f_sys_hz();
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
        let layout = Layout { bits: vec![12], crc_width: vec![6], crc_poly: vec![3] };
        let msg = decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &layout).unwrap_err().to_string();
        assert!(msg.contains("biss_seed_16bit.vcd: the frames carry 25 bits after the start bit, but --bits 12 with --crc-width 6 read 21"), "{msg}");
        assert!(msg.ends_with("--bits 16 would fit"), "{msg}");
        let right = Layout { bits: vec![16], ..layout };
        assert!(decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &right).is_ok());
    }

    #[test]
    fn every_field_the_decoder_prints_equals_the_gen_transcript_of_every_biss_scenario() {
        let names: Vec<String> = builtin::all().unwrap().into_iter().filter(|s| matches!(s.setup, S::Biss(_))).map(|s| s.name).collect();
        assert_eq!(names.len(), 28);
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
                            (Some(ps), Some(cycles)) => assert_eq!(ps.div_ceil(period_ps) + 2, cycles, "{name}: delay {ps} ps"),
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
            (12, 7, 2),
            "register read, write, two CRC-4 faults, three along a chain, two aborted mid-way, one failed in its sync frames, a missing R and a missing S echo; two refused starts"
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
