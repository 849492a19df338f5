//! `tbgen gen`: run a scenario and write its four files, all or nothing.
//!
//! Every file is first written under a temporary name in the output folder
//! and renamed into place only when all four are complete, so a failed run
//! (bad scenario, full disk) leaves the folder as it was; so does an
//! interrupted one (Ctrl-C, SIGTERM: see [`crate::interrupt`]).

use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use model::testbench::{self, Testbench, Transaction as _};
use model::trace::{Sample, Sink};

use crate::scenario::{Scenario, Visitor};
use crate::vectors::{Header, VectorWriter};
use crate::wave::{signal_names, Waves};
use crate::{gtkw, interrupt, progress, transcript, Error, Result};

/// What a generation produced.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Summary {
    /// Cycles simulated.
    pub cycles: u64,
    /// Vector records written.
    pub records: u64,
    /// Transactions in the transcript.
    pub transactions: usize,
    /// The four files, in the order `.hex`, `.vcd`, `.json`, `.gtkw`.
    pub files: Vec<PathBuf>,
}

/// Files being written under temporary names; removed on drop unless committed.
struct Staged {
    pairs: Vec<(PathBuf, PathBuf)>,
    committed: bool,
}

impl Staged {
    /// The four files of scenario `name` alone (the tests' case).
    #[cfg(test)]
    fn new(dir: &Path, name: &str) -> Staged {
        Staged::with_extra(dir, name, &[])
    }

    /// The four files of scenario `name`, then the `extra` files (filters).
    fn with_extra(dir: &Path, name: &str, extra: &[String]) -> Staged {
        let files = ["hex", "vcd", "json", "gtkw"]
            .iter()
            .map(|ext| format!("{name}.{ext}"))
            .chain(extra.iter().cloned());
        let pairs = files
            .map(|f| (dir.join(format!(".{f}.partial")), dir.join(f)))
            .collect();
        Staged {
            pairs,
            committed: false,
        }
    }

    fn temp(&self, i: usize) -> &Path {
        &self.pairs[i].0
    }

    /// The file the user asked for, which errors name (not the hidden
    /// temporary one being written).
    fn dest(&self, i: usize) -> &Path {
        &self.pairs[i].1
    }

    fn create(&self, i: usize) -> Result<BufWriter<File>> {
        interrupt::locked(|pending| pending.create(self.temp(i)))
            .map(|f| BufWriter::with_capacity(1 << 20, f))
            .map_err(|e| Error::io(self.dest(i), e))
    }

    /// Renames the four files into place, all or none: a destination taken
    /// by a folder is refused before anything moves, and a rename that fails
    /// midway puts back the files already replaced. An interrupt waits
    /// for the renames to finish.
    fn commit(mut self) -> Result<Vec<PathBuf>> {
        interrupt::locked(|pending| self.rename_all(pending))?;
        self.committed = true;
        Ok(self.pairs.iter().take(4).map(|(_, d)| d.clone()).collect())
    }

    fn rename_all(&self, pending: &mut interrupt::Pending) -> Result<()> {
        for (_, dest) in &self.pairs {
            if dest.is_dir() {
                return Err(Error::io(dest, std::io::Error::other("is a folder, where tbgen writes a file: move the folder or choose another --out")));
            }
        }
        let mut done: Vec<(&Path, Option<PathBuf>)> = Vec::new();
        for (temp, dest) in &self.pairs {
            let backup = dest.exists().then(|| {
                dest.with_file_name(format!(
                    ".{}.old",
                    dest.file_name().unwrap_or_default().to_string_lossy()
                ))
            });
            let moved = match &backup {
                Some(b) => fs::rename(dest, b),
                None => Ok(()),
            };
            if let Err(e) = moved.and_then(|_| fs::rename(temp, dest)) {
                if let Some(b) = backup.as_ref().filter(|_| !dest.exists()) {
                    let _ = fs::rename(b, dest);
                }
                for (d, b) in done.iter().rev() {
                    let _ = match b {
                        Some(b) => fs::rename(b, d),
                        None => fs::remove_file(d),
                    };
                }
                return Err(Error::io(dest, e));
            }
            done.push((dest, backup));
        }
        for b in done.into_iter().filter_map(|(_, b)| b) {
            let _ = fs::remove_file(b);
        }
        for (temp, _) in &self.pairs {
            pending.forget(temp);
        }
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            interrupt::locked(|pending| {
                for (temp, _) in &self.pairs {
                    let _ = fs::remove_file(temp);
                    pending.forget(temp);
                }
            });
        }
    }
}

/// Feeds one sample to the vector writer and the waveform writer.
struct Both<'a> {
    vectors: &'a mut VectorWriter,
    waves: &'a mut Waves,
}

impl Sink for Both<'_> {
    type Error = std::io::Error;
    fn sample(&mut self, cycle: u64, s: &Sample) -> std::io::Result<()> {
        self.vectors.sample(cycle, s)?;
        self.waves.sample(cycle, s)
    }
}

/// Runs `scenario` and writes `<name>.hex`, `.vcd`, `.json` and `.gtkw` into `out_dir`.
pub fn generate(scenario: &Scenario, out_dir: &Path) -> Result<Summary> {
    generate_with(scenario, out_dir, progress::Mode::Off)
}

/// [`generate`], showing its progress as `mode` says.
pub fn generate_with(scenario: &Scenario, out_dir: &Path, mode: progress::Mode) -> Result<Summary> {
    scenario.setup.accept(Generate {
        scenario,
        out_dir,
        mode,
    })
}

struct Generate<'a> {
    scenario: &'a Scenario,
    out_dir: &'a Path,
    mode: progress::Mode,
}

impl Visitor for Generate<'_> {
    type Output = Result<Summary>;
    fn visit<S: crate::registry::Protocol>(self, cfg: &S) -> Result<Summary> {
        write_outputs(self.scenario, cfg, self.out_dir, self.mode)
    }
}

fn write_outputs<S: crate::registry::Protocol>(
    scenario: &Scenario,
    cfg: &S,
    out_dir: &Path,
    mode: progress::Mode,
) -> Result<Summary> {
    let value_error = |source| scenario.value_error(source);
    let tb = cfg.timebase().map_err(value_error)?;
    let params = cfg.verilog_parameters().map_err(value_error)?;
    let bench = cfg.bench().map_err(value_error)?;
    if out_dir.exists() && !out_dir.is_dir() {
        return Err(Error::io(
            out_dir,
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "--out names a file, not a folder: give a folder (it is created if missing)",
            ),
        ));
    }
    interrupt::create_dir_all(out_dir).map_err(|e| Error::io(out_dir, e))?;
    let layout = bench.layout().clone();
    let core = S::CORE;
    // State registers shown by name: one filter file per signal and core.
    let filters: Vec<(String, String, String)> = S::wave_names()
        .into_iter()
        .filter_map(|(signal, names)| {
            let port = layout.decoded.iter().find(|p| p.name == signal)?;
            let full = if port.width == 1 {
                format!("top.decoded.{signal}")
            } else {
                format!("top.decoded.{signal}[{}:0]", port.width - 1)
            };
            Some((
                full,
                gtkw::filter_name(core, signal),
                gtkw::filter_file(&names),
            ))
        })
        .collect();
    let staged = Staged::with_extra(
        out_dir,
        &scenario.name,
        &filters.iter().map(|f| f.1.clone()).collect::<Vec<_>>(),
    );

    let mut vectors = VectorWriter::new(&layout.inputs, &layout.outputs);
    let comment = waveform_comment(&scenario.name, core, tb.f_sys_hz());
    let vcd_path = staged.dest(1).to_path_buf();
    let mut waves = Waves::new(staged.create(1)?, core, &layout, tb, &comment)
        .map_err(|e| Error::io(&vcd_path, e))?;
    let mut both = Both {
        vectors: &mut vectors,
        waves: &mut waves,
    };
    let run = if mode == progress::Mode::Off {
        testbench::run(bench, &mut both)
    } else {
        let mut shown = progress::Progress::new(
            both,
            mode,
            &scenario.name,
            tb.f_sys_hz(),
            progress::Counter::start(cfg),
            staged.temp(1).to_path_buf(),
        );
        let run = testbench::run(bench, &mut shown);
        shown.finish();
        run
    }
    .map_err(|e| Error::io(&vcd_path, e))?;
    waves
        .finish(run.cycles)
        .map_err(|e| Error::io(&vcd_path, e))?;

    let header = Header {
        core: core.to_string(),
        scenario: scenario.name.clone(),
        f_sys_hz: tb.f_sys_hz(),
        params: params.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
    };
    let mut hex = staged.create(0)?;
    let records = vectors
        .finish(&header, &mut hex)
        .and_then(|r| hex.flush().map(|_| r))
        .map_err(|e| Error::io(staged.dest(0), e))?;

    let doc = transcript::Transcript {
        format: transcript::FORMAT,
        scenario: &scenario.name,
        core,
        f_sys_hz: tb.f_sys_hz(),
        cycles: run.cycles,
        parameters: params.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
        transactions: &run.transactions,
    };
    let mut json = staged.create(2)?;
    serde_json::to_writer_pretty(&mut json, &doc)
        .map_err(std::io::Error::from)
        .and_then(|_| json.write_all(b"\n"))
        .and_then(|_| json.flush())
        .map_err(|e| Error::io(staged.dest(2), e))?;

    // Frame the first transaction that lasts (not a zero-length one such as
    // EnDat's delay measurement), with a little idle line on either side; a
    // run without one is shown whole.
    let window = match run
        .transactions
        .iter()
        .map(|t| t.span())
        .find(|(start, end)| end > start)
    {
        Some((start, end)) => {
            let lead = (end - start) / 20 + 10;
            (tb.ps_at(start.saturating_sub(lead)), tb.ps_at(end + lead))
        }
        None => (0, tb.ps_at(run.cycles)),
    };
    let groups = signal_names(core, &layout);
    let mut gtkw_out = staged.create(3)?;
    let dumpfile = format!("{}.vcd", scenario.name);
    let shown: Vec<(String, String)> = filters
        .iter()
        .map(|(signal, file, _)| (signal.clone(), file.clone()))
        .collect();
    gtkw::write(
        &mut gtkw_out,
        &gtkw::Layout {
            dumpfile: &dumpfile,
            groups: &groups,
            window_ps: window,
            dump_end_ps: tb.ps_at(run.cycles),
            scenario: &scenario.name,
            filters: &shown,
        },
    )
    .and_then(|_| gtkw_out.flush())
    .map_err(|e| Error::io(staged.dest(3), e))?;
    for (i, (_, _, text)) in filters.iter().enumerate() {
        staged.create(4 + i).and_then(|mut f| {
            f.write_all(text.as_bytes())
                .and_then(|_| f.flush())
                .map_err(|e| Error::io(staged.dest(4 + i), e))
        })?;
    }

    drop((hex, json, gtkw_out));
    let files = staged.commit()?;
    Ok(Summary {
        cycles: run.cycles,
        records,
        transactions: run.transactions.len(),
        files,
    })
}

/// The `$comment` of the waveform `tbgen gen` writes of scenario `name`
/// for `core` ([`scenario_of_comment`] reads it back).
pub fn waveform_comment(name: &str, core: &str, f_sys_hz: u64) -> String {
    format!(
        "tbgen {}: scenario {name} for {core}, f_sys {f_sys_hz} Hz",
        env!("CARGO_PKG_VERSION")
    )
}

/// The scenario a [`waveform_comment`] names, if `comment` is one.
pub fn scenario_of_comment(comment: &str) -> Option<&str> {
    let (_, rest) = comment
        .trim()
        .strip_prefix("tbgen ")?
        .split_once(": scenario ")?;
    rest.split_once(" for ").map(|(name, _)| name)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seed() -> Scenario {
        crate::builtin::find("ssi_seed_12bit").unwrap()
    }

    #[test]
    fn a_destination_taken_by_a_folder_leaves_no_file_behind() {
        let dir = tempfile::tempdir().unwrap();
        fs::create_dir(dir.path().join("ssi_seed_12bit.vcd")).unwrap();
        let msg = generate(&seed(), dir.path()).unwrap_err().to_string();
        assert!(msg.contains("ssi_seed_12bit.vcd: is a folder"), "{msg}");
        let mut left: Vec<_> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        assert_eq!(left, vec!["ssi_seed_12bit.vcd"]);
    }

    #[test]
    fn a_failed_rename_midway_puts_back_the_files_it_replaced() {
        let dir = tempfile::tempdir().unwrap();
        generate(&seed(), dir.path()).unwrap();
        let old_hex = fs::read(dir.path().join("ssi_seed_12bit.hex")).unwrap();
        // The .json's temporary file is missing when the commit comes: the
        // .hex and .vcd already renamed must be rolled back.
        let staged = Staged::new(dir.path(), "ssi_seed_12bit");
        fs::write(staged.temp(0), "new hex").unwrap();
        fs::write(staged.temp(1), "new vcd").unwrap();
        assert!(staged.commit().is_err());
        assert_eq!(
            fs::read(dir.path().join("ssi_seed_12bit.hex")).unwrap(),
            old_hex
        );
        let names: Vec<_> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(
            names.len(),
            5,
            "the four files and the state filter: {names:?}"
        );
    }

    #[test]
    fn an_out_that_is_a_file_is_named_as_such() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("afile");
        fs::write(&file, "").unwrap();
        let e = generate(&seed(), &file).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("--out names a file, not a folder"), "{msg}");
        assert_eq!(e.exit_code(), 2, "bad input, like every other");
    }

    #[test]
    fn a_file_that_cannot_be_written_is_named_as_the_user_asked_for_it() {
        // A folder where the vector file's hidden temporary one would go
        // makes its creation fail: the error names the .hex the user wants.
        let dir = tempfile::tempdir().unwrap();
        fs::create_dir(dir.path().join(".ssi_seed_12bit.hex.partial")).unwrap();
        let msg = generate(&seed(), dir.path()).unwrap_err().to_string();
        assert!(msg.contains("ssi_seed_12bit.hex: is a folder"), "{msg}");
        assert!(!msg.contains(".partial"), "{msg}");
    }
}
