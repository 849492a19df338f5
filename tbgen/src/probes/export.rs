//! Writing the probes for the simulators: into a hidden folder beside the
//! one asked for, renamed into place when every file is written, so that a
//! failed export (a wrapper that cannot be wired, a full disk) leaves the
//! folder as it was.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use cosim::probe::{self, Probe};

use super::{description, folder, wiring, MANIFEST};
use crate::{Error, Result};

/// The pins a stimulus word carries (its levels and its unknown mask are
/// 16 bits each).
const PINS: u32 = 16;

/// The stimulus file of `p`: the master's pins sampled as the library
/// samples them ([`probe::samples`]), in runs of equal samples, one 64-bit
/// hex word a line: bits 63..32 the run's length in emulator cycles, 31..16
/// the pins unknown (X) in it, 15..0 their levels; a zero word ends it.
/// Returns the text and its number of lines (the zero word's included).
pub fn stimulus(p: &Probe) -> Result<(String, usize)> {
    if p.line.iter().any(|s| s.0 >> PINS != 0) || p.unknown >> PINS != 0 {
        return Err(Error::Probes(format!(
            "{} {} `{}`: a pin above bit {} (the stimulus file carries {PINS} pins)",
            p.protocol,
            p.rule,
            p.what,
            PINS - 1
        )));
    }
    let mut runs: Vec<(u64, u32, u32)> = Vec::new();
    for (levels, unknown) in probe::samples(p) {
        let mask = if unknown { p.unknown } else { 0 };
        match runs.last_mut() {
            Some((n, l, m)) if (*l, *m) == (levels, mask) && *n < u64::from(u32::MAX) => *n += 1,
            _ => runs.push((1, levels, mask)),
        }
    }
    let mut s = String::new();
    for (n, levels, mask) in &runs {
        let _ = writeln!(s, "{n:08x}{mask:04x}{levels:04x}");
    }
    s.push_str("0000000000000000\n");
    Ok((s, runs.len() + 1))
}

/// `stim` with zero words up to `depth` lines.
pub(super) fn pad(stim: String, depth: usize) -> String {
    let lines = stim.lines().count();
    stim + &"0000000000000000\n".repeat(depth.saturating_sub(lines))
}

/// Files to write, relative to the export folder.
type Files = Vec<(PathBuf, String)>;

/// Every file of the export, each kit's wrappers read from `hdl`.
fn files(hdl: &Path) -> Result<Files> {
    let mut out: Files = Vec::new();
    let mut manifest =
        String::from("# kind\tf_hz\tdepth\tfolder  (tbgen probes; hdl/tb_probe/run.sh reads it)\n");
    for kit in probe::kits() {
        let d = model::protocol::PROTOCOLS
            .iter()
            .find_map(|p| p.emulator.as_ref().filter(|e| e.kind == kit.protocol))
            .ok_or_else(|| {
                Error::Probes(format!(
                    "probe kit `{}`: no protocol descriptor has an emulator of that kind (model/src/*/descriptor.rs)",
                    kit.protocol
                ))
            })?;
        let w = wiring::read(hdl, d.module, d.monitor_module)?;
        if w.monitor_pins.len() != kit.monitor.len() {
            return Err(Error::Probes(format!(
                "{}: the monitor has {} pins ({}), the {} kit's wiring table {}: give the table one source per pin \
                 (cosim/src/probe/{}.rs)",
                hdl.join(format!("{}.v", d.monitor_module)).display(),
                w.monitor_pins.len(),
                w.monitor_pins.join(", "),
                kit.protocol,
                kit.monitor.len(),
                kit.protocol
            )));
        }
        let dir = PathBuf::from(kit.protocol);
        out.push((dir.join("probe_wiring.vh"), w.include(kit.protocol)));
        out.push((dir.join("probe_wiring.vhd"), w.vhdl(kit.protocol)));
        out.push((dir.join("probe_pins.v"), w.pins_module(kit.protocol)));
        let table: Vec<u8> = kit.monitor.iter().map(|s| wiring::src_byte(*s)).collect();
        let json = serde_json::json!({
            "emulator": w.emulator,
            "monitor": w.monitor,
            "inputs": w.inputs.iter().map(|(b, p)| serde_json::json!({"bit": b, "port": p})).collect::<Vec<_>>(),
            "monitor_sources": table,
            "idle": kit.idle.0,
        });
        out.push((dir.join("wiring.json"), format!("{json:#}\n")));
        // Padded to the testbench's 8 pins (0xff: none) and its stimulus
        // depth, so that $readmemh finds every word it reads.
        let mem: String = (0..8)
            .map(|i| format!("{:02x}\n", table.get(i).copied().unwrap_or(0xff)))
            .collect();
        let probes = (kit.probes)();
        let mut stims = Vec::new();
        for p in &probes {
            stims.push(stimulus(p)?);
        }
        let depth = stims.iter().map(|s| s.1).max().unwrap_or(1);
        for (i, (p, (stim, _))) in probes.iter().zip(stims).enumerate() {
            let pd = dir.join(folder(i, p));
            out.push((pd.join("probe.toml"), p.toml.to_string()));
            out.push((pd.join("stimulus.mem"), pad(stim, depth)));
            out.push((pd.join("monitor.mem"), mem.clone()));
            out.push((pd.join("probe.json"), format!("{:#}\n", description(i, p))));
            let _ = writeln!(
                manifest,
                "{}\t{}\t{depth}\t{}",
                kit.protocol,
                p.f_hz,
                pd.display()
            );
        }
    }
    out.push((PathBuf::from(MANIFEST), manifest));
    Ok(out)
}

/// A folder being written; removed on drop unless renamed into place.
struct Partial(PathBuf, bool);

impl Drop for Partial {
    fn drop(&mut self) {
        if !self.1 {
            let _ = fs::remove_dir_all(&self.0);
        }
    }
}

/// Writes every kit's probes into `out`, all or nothing, the wrappers read
/// from `hdl` (`hdl/emu`). `out` must be new, empty or an earlier export
/// (it is replaced whole, the simulators' runs in it with it). Returns the
/// number of probes.
pub fn export(out: &Path, hdl: &Path) -> Result<usize> {
    if out.exists() {
        if !out.is_dir() {
            return Err(Error::Probes(format!(
                "{}: is a file; give --out a folder (new, empty, or an earlier export)",
                out.display()
            )));
        }
        let empty = fs::read_dir(out)
            .map_err(|e| Error::io(out, e))?
            .next()
            .is_none();
        if !empty && !out.join(MANIFEST).is_file() {
            return Err(Error::Probes(format!(
                "{}: a folder with files but no {MANIFEST}, so not an earlier export, which tbgen would replace: \
                 give --out a new or empty folder",
                out.display()
            )));
        }
    }
    let files = files(hdl)?;
    let name = out
        .file_name()
        .ok_or_else(|| Error::Probes(format!("{}: give --out a folder name", out.display())))?
        .to_string_lossy()
        .to_string();
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    fs::create_dir_all(parent).map_err(|e| Error::io(parent, e))?;
    let mut partial = Partial(parent.join(format!(".{name}.partial")), false);
    let _ = fs::remove_dir_all(&partial.0);
    for (rel, text) in &files {
        let path = partial.0.join(rel);
        if let Some(d) = path.parent() {
            fs::create_dir_all(d).map_err(|e| Error::io(out.join(rel), e))?;
        }
        fs::write(&path, text).map_err(|e| Error::io(out.join(rel), e))?;
    }
    let old = parent.join(format!(".{name}.old"));
    let _ = fs::remove_dir_all(&old);
    if out.exists() {
        fs::rename(out, &old).map_err(|e| Error::io(out, e))?;
    }
    if let Err(e) = fs::rename(&partial.0, out) {
        let _ = fs::rename(&old, out);
        return Err(Error::io(out, e));
    }
    partial.1 = true;
    let _ = fs::remove_dir_all(&old);
    Ok(files
        .iter()
        .filter(|(p, _)| p.ends_with("probe.json"))
        .count())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hdl() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../hdl/emu")
    }

    #[test]
    fn the_stimulus_replays_the_librarys_samples() {
        // Sample n at n x 5 ns: 1 at 0, 5 and 10 ns (the first two unknown),
        // 0 at 15 and 20 ns, 5 at 25 ns.
        let p = Probe {
            protocol: "biss",
            rule: "TMAS",
            legal: true,
            what: "",
            toml: "",
            f_hz: 200_000_000,
            line: vec![(1, 12_000), (0, 10_000), (5, 6_000)],
            unknown: 4,
            unknown_ps: 6_000,
            reads: &[],
        };
        let (s, n) = stimulus(&p).unwrap();
        assert_eq!(s, "0000000200040001\n0000000100000001\n0000000200000000\n0000000100000005\n0000000000000000\n");
        assert_eq!(n, 5);
        let wide = Probe {
            line: vec![(1 << 16, 1_000)],
            ..p
        };
        assert!(stimulus(&wide)
            .unwrap_err()
            .to_string()
            .contains("above bit 15"));
    }

    #[test]
    fn an_export_is_whole_or_not_at_all_and_never_replaces_a_folder_of_other_files() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("probes");
        let n = export(&out, &hdl()).unwrap();
        assert_eq!(n, probe::all().len());
        assert!(out.join(MANIFEST).is_file());
        // Again over the earlier export: replaced.
        fs::write(out.join("stale"), "").unwrap();
        export(&out, &hdl()).unwrap();
        assert!(!out.join("stale").exists());
        // Wrappers that cannot be read: nothing changes, nothing is left beside.
        let e = export(&out, &dir.path().join("nowhere"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("nowhere") && e.contains("--hdl"), "{e}");
        assert!(out.join(MANIFEST).is_file());
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
        // A folder of someone's files is not replaced.
        let mine = dir.path().join("mine");
        fs::create_dir(&mine).unwrap();
        fs::write(mine.join("notes.txt"), "").unwrap();
        let e = export(&mine, &hdl()).unwrap_err().to_string();
        assert!(e.contains("mine") && e.contains("no probes.tsv"), "{e}");
        let e = export(&mine.join("notes.txt"), &hdl())
            .unwrap_err()
            .to_string();
        assert!(e.contains("notes.txt: is a file"), "{e}");
    }
}
