//! Writes golden vectors for a `[sar]` or `[modbus]` table of a TOML file,
//! until the protocol registry lets `tbgen gen` do it:
//!
//! ```sh
//! cargo run -p tbgen --example sar_modbus_vectors -- scenarios/sar/seed_timed_14bit.toml out/
//! scripts/sim.sh sar_async_host icarus out/sar_seed_timed_14bit.hex
//! ```

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use model::testbench::{self, Testbench};
use model::trace::{Sample, Sink};
use model::Setup;
use tbgen::vectors::{Header, VectorWriter};
use tbgen::wave::Waves;

/// Vectors and waves from one run.
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

#[derive(serde::Deserialize)]
struct File_ {
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    #[allow(dead_code)]
    description: Option<String>,
    #[serde(default)]
    sar: Option<model::sar58k24::BenchConfig>,
    #[serde(default)]
    modbus: Option<model::modbus::BenchConfig>,
}

fn write<S: Setup>(cfg: &S, name: &str, out: &Path) -> Result<(), String> {
    cfg.validate().map_err(|e| e.to_string())?;
    let tb = cfg.timebase().map_err(|e| e.to_string())?;
    let params = cfg.verilog_parameters().map_err(|e| e.to_string())?;
    let bench = cfg.bench().map_err(|e| e.to_string())?;
    let layout = bench.layout().clone();
    let mut vectors = VectorWriter::new(&layout.inputs, &layout.outputs);
    std::fs::create_dir_all(out).map_err(|e| e.to_string())?;
    let vcd = BufWriter::new(File::create(out.join(format!("{name}.vcd"))).map_err(|e| e.to_string())?);
    let mut waves = Waves::new(vcd, S::CORE, &layout, tb.period_ps(), name).map_err(|e| e.to_string())?;
    let run = testbench::run(bench, &mut Both { vectors: &mut vectors, waves: &mut waves }).map_err(|e| e.to_string())?;
    waves.finish(run.cycles).map_err(|e| e.to_string())?;
    let header = Header { core: S::CORE.to_string(), scenario: name.to_string(), f_sys_hz: tb.f_sys_hz(), params: params.iter().map(|(k, v)| (k.to_string(), *v)).collect() };
    std::fs::create_dir_all(out).map_err(|e| e.to_string())?;
    let path = out.join(format!("{name}.hex"));
    let mut f = BufWriter::new(File::create(&path).map_err(|e| e.to_string())?);
    vectors.finish(&header, &mut f).and_then(|_| f.flush()).map_err(|e| e.to_string())?;
    let json = out.join(format!("{name}.json"));
    std::fs::write(&json, serde_json::to_string_pretty(&run.transactions).map_err(|e| e.to_string())?).map_err(|e| e.to_string())?;
    println!("{}: {} cycles, {} transactions", path.display(), run.cycles, run.transactions.len());
    Ok(())
}

/// Writes `<name>.hex`, `.vcd` and `.json` of the scenario `file` into `out`.
pub fn generate_file(file: &str, out: &Path) -> Result<(), String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("{file}: {e}"))?;
    let parsed: File_ = toml::from_str(&text).map_err(|e| format!("{file}: {e}"))?;
    let name = parsed.name.clone().unwrap_or_else(|| Path::new(file).file_stem().and_then(|s| s.to_str()).unwrap_or("scenario").to_string());
    match (parsed.sar, parsed.modbus) {
        (Some(cfg), None) => write(&cfg, &name, out),
        (None, Some(cfg)) => write(&cfg, &name, out),
        _ => Err("give exactly one [sar] or [modbus] table".into()),
    }
    .map_err(|e| format!("{file}: {e}"))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let [_, file, out] = args.as_slice() else {
        eprintln!("usage: sar_modbus_vectors <scenario.toml> <out-dir>");
        std::process::exit(2);
    };
    if let Err(e) = generate_file(file, Path::new(out)) {
        eprintln!("{e}");
        std::process::exit(2);
    }
}
