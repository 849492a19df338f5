//! `tbgen timing biss` and `tbgen decode biss`: the BiSS-C cycle budget, and
//! a captured MA/SLO waveform turned into a JSON transcript.

use std::fmt::Write as _;
use std::path::Path;

use model::biss::{data_crc, BenchConfig};
use model::testbench;
use model::Setup;
use serde::Serialize;

use crate::{capture, Result};

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
    let busy_ns = cfg.slaves.iter().map(|s| s.busy_ns).fold(0.0, f64::max);
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
    let run = testbench::run_to_end(one.bench()?);
    if let [a, b, ..] = run.transactions.as_slice() {
        let frame = a.done_cycle - a.start_cycle + 1;
        let period = b.start_cycle - a.start_cycle;
        let delay = a.delay_cycles.map_or("not measured (no ack)".to_string(), |d| format!("{d} cycles"));
        let _ = writeln!(s, "model: start to o_done {frame} cycles ({:.3} us), start to start {period} cycles ({:.3} us) = {:.2} kHz, measured line delay {delay}",
            frame as f64 / f_sys * 1e6, period as f64 / f_sys * 1e6, f_sys / period as f64 / 1e3);
    }
    Ok(s)
}

/// One slave's part of a decoded frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DecodedSlave {
    /// Chain position.
    pub slave: usize,
    /// CDS bit.
    pub cds: bool,
    /// Data.
    pub position: u64,
    /// nE was 0.
    pub error: bool,
    /// nW was 0.
    pub warning: bool,
    /// CRC matched.
    pub crc_ok: bool,
    /// Section bits as sampled.
    pub bits: String,
}

/// One decoded frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DecodedFrame {
    /// 0-based.
    pub index: usize,
    /// Time of the first falling MA edge, ps.
    pub start_ps: u64,
    /// Second rising MA edge to the ack, ps.
    pub delay_ps: Option<u64>,
    /// Slaves in chain order.
    pub slaves: Vec<DecodedSlave>,
    /// `no_ack`, `no_start_bit`, `short_frame`, `crc_error_slave<i>`.
    pub errors: Vec<String>,
}

/// A decoded capture.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Decoded {
    /// Format marker.
    pub format: &'static str,
    /// The VCD file.
    pub file: String,
    /// MA and SLO signal names.
    pub signals: [String; 2],
    /// Frames in order.
    pub frames: Vec<DecodedFrame>,
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
/// read half an MA period after its rising edge plus that delay.
pub fn decode(path: &Path, ma: &str, slo: &str, layout: &Layout) -> Result<Decoded> {
    let signals = capture::read(path, &[(ma, "--ma"), (slo, "--slo")])?;
    let (ma_line, slo_line) = (&signals[0], &signals[1]);
    let edges = ma_line.edges();
    // Frames: a falling edge after a quiet MA high, and the rising edges that follow it.
    let mut frames = Vec::new();
    let mut i = 0;
    while i < edges.len() {
        let (t0, level) = edges[i];
        if level {
            i += 1;
            continue;
        }
        let mut rises = Vec::new();
        let mut j = i + 1;
        let mut half = None;
        while j < edges.len() {
            let gap = edges[j].0 - edges[j - 1].0;
            let h = *half.get_or_insert(gap);
            if gap > 3 * h {
                break;
            }
            if edges[j].1 {
                rises.push(edges[j].0);
            }
            j += 1;
        }
        frames.push(decode_frame(frames.len(), t0, &rises, slo_line, layout));
        i = j;
    }
    Ok(Decoded { format: "tbgen-biss-decode 1", file: path.display().to_string(), signals: [ma.into(), slo.into()], frames })
}

fn decode_frame(index: usize, t0: u64, rises: &[u64], slo: &capture::Signal, layout: &Layout) -> DecodedFrame {
    let mut f = DecodedFrame { index, start_ps: t0, delay_ps: None, slaves: Vec::new(), errors: Vec::new() };
    if rises.len() < 3 {
        f.errors.push("short_frame".into());
        return f;
    }
    let period = rises[2] - rises[1];
    let r2 = rises[1];
    // The ack is SLO falling after the second rising edge; a line already low
    // there (stuck low) has no ack.
    let ack = slo.changes.iter().find(|&&(ct, v)| ct >= r2 && !v).map(|&(ct, _)| ct);
    let Some(ack) = ack else {
        f.errors.push("no_ack".into());
        return f;
    };
    let delay = ack - r2;
    f.delay_ps = Some(delay);
    // Cell m (m >= 1) follows rising edge 2 + m; read it in its middle.
    let mut m = 1u64;
    let cell = |m: u64| slo.level_at(r2 + m * period + delay + period / 2);
    while !cell(m) {
        m += 1;
        if m > 10_000 {
            f.errors.push("no_start_bit".into());
            return f;
        }
    }
    for s in 0..layout.bits.len() {
        let n = layout.bits[s];
        let w = layout.crc_width[s];
        let section: Vec<bool> = (1..=(1 + n + 2 + w) as u64).map(|k| cell(m + k)).collect();
        m += (1 + n + 2 + w) as u64;
        let covered = &section[1..(1 + n + 2) as usize];
        let alg = data_crc(w, layout.crc_poly[s]);
        let crc_ok = alg.crc_from_wire_bits(&section[(1 + n + 2) as usize..]) == Some(alg.checksum_bits(covered));
        let position = covered[..n as usize].iter().fold(0u64, |a, &b| (a << 1) | b as u64);
        if !crc_ok {
            f.errors.push(format!("crc_error_slave{s}"));
        }
        f.slaves.push(DecodedSlave {
            slave: s,
            cds: section[0],
            position,
            error: !covered[n as usize],
            warning: !covered[n as usize + 1],
            crc_ok,
            bits: section.iter().map(|&b| if b { '1' } else { '0' }).collect(),
        });
    }
    f
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

    #[test]
    fn decoding_the_generated_waveform_gives_back_the_model_transcript() {
        // The seed example (seed 001, BiSS-C): 35555 with nW = 0, then the chain with its corrupted section.
        for (name, layout) in [
            ("biss_seed_16bit", Layout { bits: vec![16], crc_width: vec![6], crc_poly: vec![3] }),
            ("biss_chain_3slaves", Layout { bits: vec![12, 26, 32], crc_width: vec![6, 6, 8], crc_poly: vec![3, 3, 7] }),
            ("biss_clock_1mhz_100m", Layout { bits: vec![16], crc_width: vec![6], crc_poly: vec![3] }),
        ] {
            let (s, cfg) = biss(name);
            let dir = tempfile::tempdir().unwrap();
            let summary = generate::generate(&s, dir.path()).unwrap();
            let decoded = decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &layout).unwrap();
            let model = testbench::run_to_end(cfg.bench().unwrap()).transactions;
            assert_eq!(decoded.frames.len(), model.len(), "{name}");
            for (d, m) in decoded.frames.iter().zip(&model) {
                let dp: Vec<(u64, bool)> = d.slaves.iter().map(|x| (x.position, x.crc_ok)).collect();
                let mp: Vec<(u64, bool)> = m.slaves.iter().map(|x| (x.position, x.crc_ok)).collect();
                assert_eq!(dp, mp, "{name} frame {}", d.index);
            }
        }
    }

    #[test]
    fn an_absent_slave_decodes_as_no_ack() {
        let (s, _) = biss("biss_fault_no_ack");
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let layout = Layout { bits: vec![16], crc_width: vec![6], crc_poly: vec![3] };
        let decoded = decode(&summary.files[1], "top.line.ma_master", "top.line.slo_master", &layout).unwrap();
        assert!(decoded.frames.iter().all(|f| f.errors == vec!["no_ack"]));
    }

    #[test]
    fn timing_budget_of_the_seed_scenario_follows_the_ti_formula() {
        let (s, cfg) = biss("biss_seed_16bit");
        let r = timing_report(&cfg, &s.name).unwrap();
        // 100 ns x 28 bits + 120 ns (10 m both ways + 20 ns output delay) + 200 ns busy + 16 us timeout.
        assert!(r.contains("= 19.120 us"), "{r}");
        assert!(r.contains("52.30 kHz"), "{r}");
    }
}
