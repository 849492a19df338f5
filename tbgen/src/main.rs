//! The `tbgen` command line. See `tbgen --help`.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, Subcommand};
use tbgen::scenario::Visitor;
use tbgen::scenario::Setup;
use tbgen::{biss_tools, builtin, crc_cmd, esl_tools, generate, tformat_decode, tformat_tools, timing_cmd, Error};

/// `println!` that hands a closed stdout back as an error instead of
/// panicking: `tbgen decode ... | head` must end quietly, not with a panic.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout(), $($arg)*).map_err(|e| Error::io("<stdout>", e))?;
    }};
}

/// `print!` with the same care as [`outln!`].
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        write!(std::io::stdout(), $($arg)*).map_err(|e| Error::io("<stdout>", e))?;
    }};
}

#[derive(Parser)]
#[command(
    name = "tbgen",
    version,
    about = "Golden vectors, waveforms and transcripts for encoder-interface cores",
    long_about = "Runs the cycle-accurate model of an encoder-interface master, its encoder and the cable \
between them, and writes what the Verilog core in hdl/ must reproduce cycle for cycle."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the built-in scenarios.
    #[command(after_help = "Example:\n  tbgen list")]
    List,
    /// Generate <name>.hex, .vcd, .json and .gtkw for scenarios.
    #[command(after_help = "Examples:\n  tbgen gen ssi_seed_12bit --out build/out\n  tbgen gen my_scenario.toml --out build/out\n  tbgen gen --all --out vectors        # every built-in, into vectors/<core>/")]
    Gen {
        /// Built-in scenario names or paths to scenario .toml files.
        scenarios: Vec<String>,
        /// Every built-in scenario, each into <out>/<core>/.
        #[arg(long, conflicts_with = "scenarios")]
        all: bool,
        /// Output folder.
        #[arg(long, short)]
        out: PathBuf,
    },
    /// Compute a CRC of the catalogue over a bit string given in wire order.
    #[command(after_help = "Examples:\n  tbgen crc biss-crc6 100010101110001110     # the seed's BiSS-C example: CRC 110101, wire 001010\n  tbgen crc --list")]
    Crc {
        /// Algorithm name (see --list).
        #[arg(required_unless_present = "list")]
        algorithm: Option<String>,
        /// Bits as a 0/1 string in wire order.
        #[arg(required_unless_present = "list")]
        bits: Option<String>,
        /// List the catalogue.
        #[arg(long)]
        list: bool,
    },
    /// Print a protocol's cycle budget, phase by phase, and its position-read rate.
    #[command(after_help = "Examples:\n  tbgen timing tformat tformat_readout_all_ids --data-id 3\n  tbgen timing esl                           # Data ID 1 of esl_readout_all_ids\n  tbgen timing esl esl_readout_all_ids --data-id 4\n  tbgen timing biss                          # the seed scenario biss_seed_16bit\n  tbgen timing biss biss_clock_1mhz_100m\n  tbgen timing endat endat_pos22_ad_8mhz_100m --ads 2\n  tbgen timing endat my.toml --command pos21 --diagram")]
    Timing {
        /// Protocol: `biss`, `endat`, `esl` or `tformat`.
        protocol: String,
        /// Built-in scenario name or scenario .toml file of that protocol
        /// (default: biss_seed_16bit, endat_pos22_ad_8mhz_100m, tformat_readout_all_ids).
        scenario: Option<String>,
        /// EnDat: mode command to budget (`pos22`, `pos21`, `send21`, ...).
        #[arg(long, default_value = "pos22")]
        command: String,
        /// EnDat: additional data selected (0, 1 or 2; type 2.2 commands).
        #[arg(long, default_value_t = 0)]
        ads: u64,
        /// EnDat: also print the model's waveform of the scenario's first request.
        #[arg(long)]
        diagram: bool,
        /// T-format: the Data ID to budget (0, 1, 2, 3, 6, 7, 8, 0xC, 0xD); ESL: a Table 3 code (0 = Data ID 1).
        #[arg(long, default_value = "0", value_parser = parse_data_id)]
        data_id: u8,
    },
    /// Decode a captured waveform (VCD) into a JSON transcript on stdout.
    #[command(subcommand)]
    Decode(Decode),
    /// Time the model alone on a scenario (used by `make bench`).
    #[command(after_help = "Example:\n  tbgen bench scenarios/bench/ssi_bench.toml")]
    Bench {
        /// Built-in scenario name or scenario .toml file.
        scenario: String,
    },
}

/// One decoder per protocol: each reads the line-level scalars of a capture
/// (signal names are options, defaulting to those `tbgen gen` writes).
#[derive(Subcommand)]
enum Decode {
    /// BiSS-C: MA and SLO at the master.
    #[command(after_help = "Examples:\n  tbgen decode biss vectors/biss_master/biss_seed_16bit.vcd --bits 16\n  tbgen decode biss vectors/biss_master/biss_chain_3slaves.vcd --bits 12,26,32 --crc-width 6,6,8 --crc-poly 3,3,7")]
    Biss {
        /// The VCD file.
        file: PathBuf,
        /// Dotted path of the MA scalar at the master.
        #[arg(long, default_value = "top.line.ma_master")]
        ma: String,
        /// Dotted path of the SLO scalar at the master.
        #[arg(long, default_value = "top.line.slo_master")]
        slo: String,
        /// Data bits of each slave, comma-separated, chain order.
        #[arg(long, value_delimiter = ',', default_value = "16")]
        bits: Vec<u32>,
        /// CRC width of each slave (default 6 for all).
        #[arg(long, value_delimiter = ',')]
        crc_width: Vec<u32>,
        /// CRC polynomial of each slave without the top term (default 3 = x^6 + x + 1).
        #[arg(long, value_delimiter = ',')]
        crc_poly: Vec<u64>,
    },
    /// T-format: the line and the driver enable at the host (the bytes alone
    /// cannot tell a request from its answer).
    #[command(after_help = "Examples:\n  tbgen decode tformat vectors/tformat_host/tformat_readout_all_ids.vcd\n  tbgen decode tformat capture.vcd --line top.ro --tx-en top.de --timeout-us 20")]
    Tformat {
        /// The VCD file.
        file: PathBuf,
        /// Dotted path of the RS-485 line (receiver output) at the host.
        #[arg(long, default_value = "top.line.line_at_host")]
        line: String,
        /// Dotted path of the host's RS-485 driver enable.
        #[arg(long, default_value = "top.line.tx_en_host")]
        tx_en: String,
        /// Bit rate in bit/s (seed: 2.5 Mbps).
        #[arg(long, default_value_t = 2_500_000)]
        baud: u64,
        /// The host's answer timeout in µs (`[tformat.host] timeout_us`).
        #[arg(long, default_value_t = 10.0)]
        timeout_us: f64,
    },
    /// EnDat 2.1 / 2.2: clock and data at the master.
    #[command(after_help = "Examples:\n  tbgen decode endat vectors/endat_master/endat_params_22_2mhz.vcd\n  tbgen decode endat vectors/endat_master/endat_pos22_ad_8mhz_100m.vcd --meas-khz 200\n  tbgen decode endat capture.vcd --clk tb.clk_pin --data tb.data_pin --pos-bits 13")]
    Endat {
        /// The VCD file.
        file: PathBuf,
        /// Dotted path of the clock scalar at the master.
        #[arg(long, default_value = "top.line.endat_clk_master")]
        clk: String,
        /// Dotted path of the data scalar at the master's receiver (both directions).
        #[arg(long, default_value = "top.line.endat_data_master")]
        data: String,
        /// Position bits of the encoder.
        #[arg(long, default_value_t = 25)]
        pos_bits: u32,
        /// Clock of the master's delay measurement in kHz, if it measures (000111 bursts at it are measurement frames).
        #[arg(long)]
        meas_khz: Option<f64>,
    },
    /// ESL: the host's driver enable and the line at the host.
    #[command(after_help = "Example:\n  tbgen decode esl vectors/esl_host/esl_readout_all_ids.vcd")]
    Esl {
        /// The VCD file.
        file: PathBuf,
        /// Dotted path of the host's RS-485 driver enable.
        #[arg(long, default_value = "top.line.tx_en_host")]
        tx_en: String,
        /// Dotted path of the line level at the host's receiver.
        #[arg(long, default_value = "top.line.line_at_host")]
        line: String,
        /// Bit rate in bit/s.
        #[arg(long, default_value_t = 10e6)]
        baud: f64,
        /// The broadcast address of the host that made the capture.
        #[arg(long, default_value_t = 7)]
        broadcast_address: u8,
        /// Requests a memory access may take while busy.
        #[arg(long, default_value_t = 3)]
        busy_tries: u64,
        /// Largest RS difference from channel 1, in RS LSBs.
        #[arg(long, default_value_t = 1)]
        rs_tolerance: u16,
    },
}

/// A Data ID as written on the command line: decimal or 0x-prefixed hex.
fn parse_data_id(text: &str) -> Result<u8, String> {
    let value = match text.strip_prefix("0x").or_else(|| text.strip_prefix("0X")) {
        Some(hex) => u8::from_str_radix(hex, 16),
        None => text.parse::<u8>(),
    };
    value.ok().filter(|v| *v <= 0xF).ok_or_else(|| format!("`{text}`: give a Data ID from 0 to 15 (e.g. 3 or 0xD)"))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of our output went away (`| head`): nothing is lost
        // that anyone will read, so end the way Unix tools do, quietly.
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("tbgen: error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn run(command: Command) -> Result<(), Error> {
    match command {
        Command::List => {
            for s in builtin::all()? {
                outln!("{:<28} {:<12} {}", s.name, s.core(), s.description);
            }
        }
        Command::Gen { scenarios, all, out } => {
            let chosen = if all {
                builtin::all()?
            } else if scenarios.is_empty() {
                return Err(Error::UnknownScenario("(none given: name one, or pass --all)".into()));
            } else {
                scenarios.iter().map(|s| builtin::resolve(s)).collect::<Result<Vec<_>, _>>()?
            };
            for s in &chosen {
                let dir = if all { out.join(s.core()) } else { out.clone() };
                let summary = generate::generate(s, &dir)?;
                outln!(
                    "{}: {} cycles, {} records, {} transactions -> {}",
                    s.name,
                    summary.cycles,
                    summary.records,
                    summary.transactions,
                    dir.join(&s.name).display()
                );
            }
        }
        Command::Crc { algorithm, bits, list } => {
            if list {
                for a in model::crc::CATALOGUE {
                    outln!("{:<16} {:>2}-bit  {}", a.name, a.width, a.source);
                }
            } else {
                out!("{}", crc_cmd::report(algorithm.as_deref().unwrap_or(""), bits.as_deref().unwrap_or(""))?);
            }
        }
        Command::Bench { scenario } => bench(&scenario)?,
        Command::Timing { protocol, scenario, command, ads, diagram, data_id } => match protocol.as_str() {
            "tformat" => {
                let s = builtin::resolve(scenario.as_deref().unwrap_or("tformat_readout_all_ids"))?;
                let Setup::Tformat(cfg) = &s.setup else {
                    return Err(Error::Decode(format!("timing tformat: scenario `{}` is not a T-format scenario", s.name)));
                };
                out!("{}", tformat_tools::timing_report(cfg, &s.name, data_id).map_err(|e| s.value_error(e))?);
            }
            "esl" => {
                let s = builtin::resolve(scenario.as_deref().unwrap_or("esl_readout_all_ids"))?;
                let Setup::Esl(cfg) = &s.setup else {
                    return Err(Error::Decode(format!("timing esl: scenario `{}` is not an ESL scenario", s.name)));
                };
                let id = if data_id == 0 { 1 } else { data_id };
                out!("{}", esl_tools::timing_report(cfg, &s.name, id).map_err(|e| s.value_error(e))?);
            }
            "biss" => {
                let s = builtin::resolve(scenario.as_deref().unwrap_or("biss_seed_16bit"))?;
                let Setup::Biss(cfg) = &s.setup else {
                    return Err(Error::Decode(format!("timing biss: scenario `{}` is not a BiSS-C scenario", s.name)));
                };
                out!("{}", biss_tools::timing_report(cfg, &s.name).map_err(|e| s.value_error(e))?);
            }
            "endat" => {
                let s = builtin::resolve(scenario.as_deref().unwrap_or("endat_pos22_ad_8mhz_100m"))?;
                out!("{}", timing_cmd::report(&s, &command, ads, diagram)?);
            }
            other => return Err(Error::Decode(format!("timing: protocol `{other}` has no cycle budget yet; use `biss`, `endat`, `esl` or `tformat`"))),
        },
        Command::Decode(Decode::Biss { file, ma, slo, bits, crc_width, crc_poly }) => {
            let n = bits.len();
            let crc_width = if crc_width.is_empty() { vec![6; n] } else { crc_width };
            let crc_poly = if crc_poly.is_empty() { vec![3; n] } else { crc_poly };
            if crc_width.len() != n || crc_poly.len() != n || bits.iter().any(|b| !(1..=64).contains(b)) || crc_width.iter().any(|w| !(1..=8).contains(w)) {
                return Err(Error::Decode("decode biss: give --bits (1..64 each) and, if any, one --crc-width (1..8) and --crc-poly per slave".into()));
            }
            let layout = biss_tools::Layout { bits, crc_width, crc_poly };
            let frames = biss_tools::decode(&file, &ma, &slo, &layout)?;
            let decoded = tbgen::transcript::Decoded::new("biss", &file, &[("ma", &ma), ("slo", &slo)], &frames);
            outln!("{}", serde_json::to_string_pretty(&decoded).map_err(|e| Error::Decode(e.to_string()))?);
        }
        Command::Decode(Decode::Tformat { file, line, tx_en, baud, timeout_us }) => {
            if !(1_000..=100_000_000).contains(&baud) || !(timeout_us > 0.0 && timeout_us < 1e7) {
                return Err(Error::Decode(format!("decode tformat: --baud {baud} or --timeout-us {timeout_us}: give a bit rate from 1000 to 100000000 bit/s and a positive timeout in µs")));
            }
            let options = tformat_decode::Options { line, tx_en, baud, timeout_us };
            let transactions = tformat_decode::decode(&file, &options)?;
            outln!("{}", tformat_decode::to_json(&file, &options, &transactions)?);
        }
        Command::Decode(Decode::Endat { file, clk, data, pos_bits, meas_khz }) => {
            let opts = tbgen::endat_decode::Options { pos_bits, meas_khz };
            let transactions = tbgen::endat_decode::decode(&file, &clk, &data, &opts)?;
            let envelope = tbgen::transcript::Decoded::new("endat", &file, &[("clk", clk.as_str()), ("data", data.as_str())], &transactions);
            outln!("{}", serde_json::to_string_pretty(&envelope).map_err(|e| Error::Decode(e.to_string()))?);
        }
        Command::Decode(Decode::Esl { file, tx_en, line, baud, broadcast_address, busy_tries, rs_tolerance }) => {
            if broadcast_address > 7 || !(1..=15).contains(&busy_tries) {
                return Err(Error::Decode("decode esl: give --broadcast-address 0..7 and --busy-tries 1..15".into()));
            }
            let opt = esl_tools::DecodeOptions { baud, broadcast_address, busy_tries, rs_tolerance };
            let mut ops = esl_tools::decode(&file, &tx_en, &line, &opt)?;
            esl_tools::sort_errors(&mut ops);
            let decoded = tbgen::transcript::Decoded::new("esl", &file, &[("tx_en", &tx_en), ("line", &line)], &ops);
            outln!("{}", serde_json::to_string_pretty(&decoded).map_err(|e| Error::Decode(e.to_string()))?);
        }
    }
    Ok(())
}

/// Model-only speed, and the speed of writing the waveform as well.
fn bench(arg: &str) -> Result<(), Error> {
    let s = builtin::resolve(arg)?;
    let (cycles, model_s) = s.setup.accept(TimeModel).map_err(|e| s.value_error(e))?;
    let dir = std::env::temp_dir().join(format!("tbgen-bench-{}", std::process::id()));
    let started = Instant::now();
    let summary = generate::generate(&s, &dir)?;
    let gen_s = started.elapsed().as_secs_f64();
    let vcd_bytes = std::fs::metadata(&summary.files[1]).map(|m| m.len()).unwrap_or(0);
    let _ = std::fs::remove_dir_all(&dir);
    outln!("scenario: {}", s.name);
    outln!("cycles: {cycles}");
    outln!("model_seconds: {model_s:.6}");
    outln!("model_cycles_per_second: {:.0}", cycles as f64 / model_s);
    outln!("gen_seconds: {gen_s:.6}");
    outln!("gen_cycles_per_second: {:.0}", cycles as f64 / gen_s);
    outln!("vcd_bytes: {vcd_bytes}");
    outln!("vcd_bytes_per_second: {:.0}", vcd_bytes as f64 / gen_s);
    Ok(())
}

/// Runs a scenario's model alone, recording nothing: (cycles, seconds).
struct TimeModel;
impl Visitor for TimeModel {
    type Output = model::Result<(u64, f64)>;
    fn visit<S: model::Setup>(self, cfg: &S) -> Self::Output {
        let bench = cfg.bench()?;
        let started = Instant::now();
        let run = model::testbench::run_to_end(bench);
        Ok((run.cycles, started.elapsed().as_secs_f64()))
    }
}
