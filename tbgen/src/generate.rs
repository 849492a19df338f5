//! `tbgen gen`: run a scenario and write its four files, all or nothing.
//!
//! Every file is first written under a temporary name in the output folder
//! and renamed into place only when all four are complete, so a failed run
//! (bad scenario, full disk) leaves the folder as it was.

use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use model::testbench::{self, Testbench, Transaction as _};
use model::trace::{Sample, Sink};

use crate::scenario::{Scenario, Visitor};
use crate::vectors::{Header, VectorWriter};
use crate::wave::{signal_names, Waves};
use crate::{gtkw, transcript, Error, Result};

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
    fn new(dir: &Path, name: &str) -> Staged {
        let pairs = ["hex", "vcd", "json", "gtkw"]
            .iter()
            .map(|ext| (dir.join(format!(".{name}.{ext}.partial")), dir.join(format!("{name}.{ext}"))))
            .collect();
        Staged { pairs, committed: false }
    }

    fn temp(&self, i: usize) -> &Path {
        &self.pairs[i].0
    }

    fn create(&self, i: usize) -> Result<BufWriter<File>> {
        let path = self.temp(i);
        File::create(path).map(|f| BufWriter::with_capacity(1 << 20, f)).map_err(|e| Error::io(path, e))
    }

    fn commit(mut self) -> Result<Vec<PathBuf>> {
        for (temp, dest) in &self.pairs {
            fs::rename(temp, dest).map_err(|e| Error::io(dest, e))?;
        }
        self.committed = true;
        Ok(self.pairs.iter().map(|(_, d)| d.clone()).collect())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            for (temp, _) in &self.pairs {
                let _ = fs::remove_file(temp);
            }
        }
    }
}

/// Feeds one sample to the vector writer and the waveform writer.
struct Both<'a, W: Write> {
    vectors: &'a mut VectorWriter,
    waves: &'a mut Waves<W>,
}

impl<W: Write> Sink for Both<'_, W> {
    type Error = std::io::Error;
    fn sample(&mut self, cycle: u64, s: &Sample) -> std::io::Result<()> {
        self.vectors.sample(cycle, s)?;
        self.waves.sample(cycle, s)
    }
}

/// Runs `scenario` and writes `<name>.hex`, `.vcd`, `.json` and `.gtkw` into `out_dir`.
pub fn generate(scenario: &Scenario, out_dir: &Path) -> Result<Summary> {
    scenario.setup.accept(Generate { scenario, out_dir })
}

struct Generate<'a> {
    scenario: &'a Scenario,
    out_dir: &'a Path,
}

impl Visitor for Generate<'_> {
    type Output = Result<Summary>;
    fn visit<S: crate::registry::Protocol>(self, cfg: &S) -> Result<Summary> {
        write_outputs(self.scenario, cfg, self.out_dir)
    }
}

fn write_outputs<S: model::Setup>(scenario: &Scenario, cfg: &S, out_dir: &Path) -> Result<Summary> {
    let value_error = |source| scenario.value_error(source);
    let tb = cfg.timebase().map_err(value_error)?;
    let params = cfg.verilog_parameters().map_err(value_error)?;
    let bench = cfg.bench().map_err(value_error)?;
    fs::create_dir_all(out_dir).map_err(|e| Error::io(out_dir, e))?;
    let staged = Staged::new(out_dir, &scenario.name);
    let layout = bench.layout().clone();
    let core = S::CORE;

    let mut vectors = VectorWriter::new(&layout.inputs, &layout.outputs);
    let comment = format!("tbgen {}: scenario {} for {core}, f_sys {} Hz", env!("CARGO_PKG_VERSION"), scenario.name, tb.f_sys_hz());
    let vcd_path = staged.temp(1).to_path_buf();
    let mut waves = Waves::new(staged.create(1)?, core, &layout, tb.period_ps(), &comment).map_err(|e| Error::io(&vcd_path, e))?;
    let run = testbench::run(bench, &mut Both { vectors: &mut vectors, waves: &mut waves }).map_err(|e| Error::io(&vcd_path, e))?;
    waves.finish(run.cycles).map_err(|e| Error::io(&vcd_path, e))?;

    let header = Header {
        core: core.to_string(),
        scenario: scenario.name.clone(),
        f_sys_hz: tb.f_sys_hz(),
        params: params.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
    };
    let mut hex = staged.create(0)?;
    let records = vectors.finish(&header, &mut hex).and_then(|r| hex.flush().map(|_| r)).map_err(|e| Error::io(staged.temp(0), e))?;

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
        .map_err(|e| Error::io(staged.temp(2), e))?;

    // Frame the first transaction, with a little idle line on either side.
    let window = match run.transactions.first().map(|t| t.span()) {
        Some((start, end)) => {
            let lead = (end - start) / 20 + 10;
            (start.saturating_sub(lead) * tb.period_ps(), (end + lead) * tb.period_ps())
        }
        None => (0, run.cycles * tb.period_ps()),
    };
    let groups = signal_names(core, &layout);
    let mut gtkw_out = staged.create(3)?;
    let dumpfile = format!("{}.vcd", scenario.name);
    gtkw::write(&mut gtkw_out, &gtkw::Layout { dumpfile: &dumpfile, groups: &groups, window_ps: window, scenario: &scenario.name })
        .and_then(|_| gtkw_out.flush())
        .map_err(|e| Error::io(staged.temp(3), e))?;

    drop((hex, json, gtkw_out));
    let files = staged.commit()?;
    Ok(Summary { cycles: run.cycles, records, transactions: run.transactions.len(), files })
}
