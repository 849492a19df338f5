//! Judging a simulator's run of the exported probes: each probe's
//! transcripts read into a `cosim::probe::Outcome` and judged by
//! `cosim::probe::verdict`, the library run's own judgement; its log must
//! hold no error and at most one warning of X or Z (a master's driver
//! enable unknown reads as not driving: one warning, never a report).

use std::fmt::Write as _;
use std::fs;
use std::path::Path;

use cosim::probe;
use serde_json::Value;

use super::export::pad;
use super::{description, folder, stimulus, MANIFEST, SIMULATORS};
use crate::{Error, Result};

/// The result of a check: one line per probe and a summary; `ok` when every
/// probe passed.
#[derive(Debug, Clone)]
pub struct Report {
    /// What each probe showed, then the summary.
    pub text: String,
    /// Every probe passed.
    pub ok: bool,
}

/// Reads a file of the export, naming it when it cannot.
fn read(path: &Path) -> Result<String> {
    fs::read_to_string(path).map_err(|e| Error::io(path, e))
}

/// Why a probe's run in `run` (its simulator's folder) failed, or what it
/// showed when it passed.
fn judge(p: &probe::Probe, run: &Path) -> std::result::Result<String, String> {
    let transcript = |f: &str| -> std::result::Result<Value, String> {
        let path = run.join(f);
        let text = fs::read_to_string(&path).map_err(|e| {
            format!(
                "{}: {e} (the simulator did not finish: see sim.log)",
                path.display()
            )
        })?;
        serde_json::from_str(&text).map_err(|e| format!("{}: not JSON: {e}", path.display()))
    };
    let log = fs::read_to_string(run.join("sim.log")).unwrap_or_default();
    let errors: Vec<&str> = log
        .lines()
        .filter(|l| l.contains("ERROR") || l.to_lowercase().contains("fatal"))
        .collect();
    if !errors.is_empty() {
        return Err(format!("its log has errors: {}", errors.join(" | ")));
    }
    let x = log.lines().filter(|l| l.contains("X or Z")).count();
    if x > 1 {
        return Err(format!(
            "{x} warnings of X or Z in its log, not at most one"
        ));
    }
    let o = probe::outcome(&transcript("emulator.json")?, &transcript("monitor.json")?)?;
    probe::verdict(p, &o)?;
    Ok(if p.legal {
        format!("quiet; X warnings: {x}")
    } else {
        format!(
            "flagged: {} x {} by each; X warnings: {x}",
            o.monitor.len(),
            p.rule
        )
    })
}

/// Judges simulator `sim`'s runs of the probes exported into `dir`. An
/// export that differs from the probes tbgen has now is an error (export
/// again), not a failed probe.
pub fn check(dir: &Path, sim: &str) -> Result<Report> {
    if !SIMULATORS.contains(&sim) {
        return Err(Error::Probes(format!(
            "--sim {sim}: give one of {}",
            SIMULATORS.join(", ")
        )));
    }
    let manifest = fs::read_to_string(dir.join(MANIFEST)).map_err(|e| {
        Error::Probes(format!(
            "{}: {e}: export the probes there first (tbgen probes --out {})",
            dir.join(MANIFEST).display(),
            dir.display()
        ))
    })?;
    let mut text = String::new();
    let (mut passed, mut total) = (0, 0);
    let mut per_kind: Vec<(String, usize, usize)> = Vec::new();
    for (n, line) in manifest
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.starts_with('#'))
    {
        let rel = line.split('\t').nth(3).ok_or_else(|| {
            Error::Probes(format!(
                "{}:{}: not `kind<TAB>f_hz<TAB>depth<TAB>folder`: export again (tbgen probes --out)",
                dir.join(MANIFEST).display(),
                n + 1
            ))
        })?;
        let pd = dir.join(rel);
        let json: Value = serde_json::from_str(&read(&pd.join("probe.json"))?).map_err(|e| {
            Error::Probes(format!(
                "{}: not JSON: {e}",
                pd.join("probe.json").display()
            ))
        })?;
        let kind = json["protocol"].as_str().unwrap_or_default();
        let index = json["index"].as_u64().unwrap_or(u64::MAX) as usize;
        let stale = || {
            Error::Probes(format!(
                "{}: exported from other probes than tbgen's now: export again (tbgen probes --out {})",
                pd.display(),
                dir.display()
            ))
        };
        let p = probe::kit(kind)
            .and_then(|k| (k.probes)().into_iter().nth(index))
            .ok_or_else(stale)?;
        let depth = line
            .split('\t')
            .nth(2)
            .and_then(|d| d.parse().ok())
            .unwrap_or(0);
        if json != description(index, &p)
            || !rel.ends_with(&folder(index, &p))
            || read(&pd.join("stimulus.mem"))? != pad(stimulus(&p)?.0, depth)
        {
            return Err(stale());
        }
        total += 1;
        let k = match per_kind.iter().position(|(k, _, _)| k == kind) {
            Some(i) => i,
            None => {
                per_kind.push((kind.to_string(), 0, 0));
                per_kind.len() - 1
            }
        };
        per_kind[k].2 += 1;
        match judge(&p, &pd.join(sim)) {
            Ok(what) => {
                passed += 1;
                per_kind[k].1 += 1;
                let _ = writeln!(text, "{sim} {rel}: pass, {what}");
            }
            Err(why) => {
                let _ = writeln!(text, "{sim} {rel}: FAIL: {why}");
            }
        }
    }
    let kinds: Vec<String> = per_kind
        .iter()
        .map(|(k, p, t)| format!("{k} {p}/{t}"))
        .collect();
    let _ = writeln!(
        text,
        "probes {sim}: {passed} of {total} passed ({}): {}",
        kinds.join(", "),
        if passed == total && total > 0 {
            "pass"
        } else {
            "FAIL"
        }
    );
    Ok(Report {
        text,
        ok: passed == total && total > 0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_that_left_no_transcripts_fails_and_a_stale_export_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("probes");
        let hdl = Path::new(env!("CARGO_MANIFEST_DIR")).join("../hdl/emu");
        let n = super::super::export(&out, &hdl).unwrap();
        let r = check(&out, "icarus").unwrap();
        assert!(!r.ok);
        assert_eq!(r.text.matches("FAIL: ").count(), n, "{}", r.text);
        assert!(
            r.text.contains("the simulator did not finish"),
            "{}",
            r.text
        );
        let e = check(&out, "modelsim").unwrap_err().to_string();
        assert!(e.contains("icarus, verilator, cocotb"), "{e}");
        let first = fs::read_to_string(out.join(MANIFEST)).unwrap();
        let rel = first
            .lines()
            .nth(1)
            .unwrap()
            .split('\t')
            .nth(3)
            .unwrap()
            .to_string();
        fs::write(out.join(&rel).join("stimulus.mem"), "0000000100000001\n").unwrap();
        let e = check(&out, "icarus").unwrap_err().to_string();
        assert!(e.contains(&rel) && e.contains("export again"), "{e}");
        let e = check(&dir.path().join("none"), "icarus")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("probes.tsv") && e.contains("tbgen probes --out"),
            "{e}"
        );
    }
}
