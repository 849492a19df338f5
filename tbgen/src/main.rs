//! The `tbgen` command line. See `tbgen --help`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use tbgen::progress::Mode;
use tbgen::registry;
use tbgen::{builtin, crc_cmd, generate, Error};

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
    /// List the built-in scenarios, of every protocol or of one.
    #[command(after_help = "Examples:\n  tbgen list\n  tbgen list endat")]
    List {
        /// Only this protocol's (its table, as `tbgen protocols` names it).
        protocol: Option<String>,
    },
    /// Generate <name>.hex, .vcd, .json and .gtkw for scenarios.
    #[command(
        after_help = "Examples:\n  tbgen gen ssi_seed_12bit --out build/out\n  tbgen gen my_scenario.toml --out build/out\n  tbgen gen --all --out vectors        # every built-in, into vectors/<core>/"
    )]
    Gen {
        /// Built-in scenario names or paths to scenario .toml files.
        scenarios: Vec<String>,
        /// Every built-in scenario, each into <out>/<core>/.
        #[arg(long, conflicts_with = "scenarios")]
        all: bool,
        /// Output folder.
        #[arg(long, short)]
        out: PathBuf,
        /// Show progress and an estimate of size and time on stderr even when it is not a
        /// terminal (a terminal always gets them).
        #[arg(long)]
        progress: bool,
    },
    /// Compute a CRC of the catalogue over a bit string given in wire order.
    #[command(
        after_help = "Examples:\n  tbgen crc biss-crc6 100010101110001110     # the seed's BiSS-C example: CRC 110101, wire 001010\n  tbgen crc modbus-crc16 --bytes 01 03 00 00 00 01   # byte-oriented: CRC 0x0A84, sent 84 0A\n  tbgen crc --list"
    )]
    Crc {
        /// Algorithm name (see --list).
        #[arg(required_unless_present = "list")]
        algorithm: Option<String>,
        /// Bits as a 0/1 string in wire order.
        #[arg(required_unless_present_any = ["list", "bytes"], conflicts_with = "bytes")]
        bits: Option<String>,
        /// Whole bytes in hex instead of bits (Modbus, T-format, ESL), in the order sent.
        #[arg(long, num_args = 1..)]
        bytes: Vec<String>,
        /// List the catalogue.
        #[arg(long)]
        list: bool,
    },
    /// Print a protocol's cycle budget, phase by phase, and its position-read rate.
    #[command(
        subcommand,
        after_help = "Each protocol has its own options and examples: tbgen timing <protocol> --help.\nThe protocols: tbgen protocols."
    )]
    Timing(registry::Timing),
    /// Decode a captured waveform (VCD, sigrok session .sr, logic-analyser CSV) into a JSON transcript on stdout.
    #[command(
        subcommand,
        after_help = "Each protocol has its own options and examples: tbgen decode <protocol> --help.\nThe protocols: tbgen protocols."
    )]
    Decode(registry::Decode),
    /// A GTKWave Transaction Filter Process: the frames of a protocol's lines, decoded, as a trace beside them.
    #[command(
        name = "gtkwave-filter",
        after_help = "GTKWave starts it (Edit > Data Format > Transaction Filter Process) on the highlighted lines, grouped with Combine Down;
it reads GTKWave's blocks on stdin and answers each with a trace on stdout. GTKWave runs a filter without arguments,
so give it a one-line script, e.g. ssi-frames.sh:
  #!/bin/sh
  exec tbgen gtkwave-filter ssi --bits 12"
    )]
    GtkwaveFilter {
        /// The protocol (its table name, as `tbgen protocols` lists it).
        protocol: String,
        /// Options of the protocol's decoder (`tbgen decode <protocol> --help`), e.g. --bits 12 --map clk=D0,data=D1.
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        decoder_args: Vec<String>,
    },
    /// Time the model alone on a scenario, or `tbgen decode` on a logic-analyser capture it makes (used by `make bench`).
    #[command(
        after_help = "Examples:\n  tbgen bench scenarios/bench/ssi_bench.toml\n  tbgen bench --capture sr --samples 100000000"
    )]
    Bench {
        /// Built-in scenario name or scenario .toml file.
        #[arg(required_unless_present = "capture", conflicts_with = "capture")]
        scenario: Option<String>,
        /// Decode a capture of this format instead (sr or csv), made of the SSI seed scenario's lines repeated.
        #[arg(long, requires = "samples")]
        capture: Option<String>,
        /// Samples in the capture.
        #[arg(long)]
        samples: Option<u64>,
    },
    /// Write the electronic data sheet (CiA 306 EDS) of the emulated CANopen DS 406 encoder.
    #[command(
        after_help = "Examples:\n  tbgen eds                          # multiturn 25-bit, to stdout\n  tbgen eds --kind singleturn13 --out enc.eds"
    )]
    Eds {
        /// Encoder type (seed 003 §7): multiturn25, singleturn13, angle20, angle23, linear.
        #[arg(long, default_value = "multiturn25")]
        kind: String,
        /// Gateway serial number (5500h, 1018h sub 4).
        #[arg(long, default_value_t = 0xFFFF_FFFF)]
        serial: u32,
        /// Output file (default: stdout).
        #[arg(long, short)]
        out: Option<PathBuf>,
    },
    /// Print the reference of a protocol's scenario fields: unit, default, values, meaning.
    #[command(
        after_help = "Examples:\n  tbgen fields ssi\n  tbgen fields endat --markdown\n  tbgen fields --all > docs/scenarios.md   # the committed reference"
    )]
    Fields {
        /// The protocol's table (tbgen protocols).
        #[arg(required_unless_present = "all")]
        protocol: Option<String>,
        /// Every protocol: docs/scenarios.md (Markdown).
        #[arg(long, conflicts_with = "protocol")]
        all: bool,
        /// Markdown tables, as the docs hold them, instead of plain text wrapped to the
        /// terminal's width ($COLUMNS, else 100).
        #[arg(long)]
        markdown: bool,
    },
    /// List the registered protocols: stem, core, emulator, closed loops,
    /// decoder, budget, sigrok decoder; with --json every descriptor whole
    /// (what the scripts read their lists from).
    #[command(after_help = "Examples:\n  tbgen protocols\n  tbgen protocols --json")]
    Protocols {
        /// The descriptors as JSON: an array, one object per protocol.
        #[arg(long)]
        json: bool,
    },
    /// Write the rule probes (cosim/src/probe/) for the simulators, or judge a simulator's run of them.
    #[command(
        after_help = "The probe testbench hdl/tb_probe/ replays them in Icarus and Verilator, hdl/cocotb/rule_probes.py from cocotb;\nhdl/tb_probe/run.sh does all three.\n\nExamples:\n  tbgen probes --out build/probes\n  tbgen probes --check build/probes --sim icarus"
    )]
    Probes {
        /// Write every kit's probes into this folder (new, empty, or an earlier export, which is replaced).
        #[arg(
            long,
            short,
            required_unless_present = "check",
            conflicts_with = "check"
        )]
        out: Option<PathBuf>,
        /// The emulator and monitor wrappers, which the probe testbench is wired to.
        #[arg(long, default_value = "hdl/emu")]
        hdl: PathBuf,
        /// Judge the runs of the probes exported into this folder: exit 1 unless every probe passed.
        #[arg(long, requires = "sim")]
        check: Option<PathBuf>,
        /// The simulator whose runs --check judges: icarus, verilator or cocotb.
        #[arg(long, requires = "check")]
        sim: Option<String>,
    },
    /// Compare what a master did (a VCD of any timescale, or a transcript) with what was expected, transaction by transaction; exit 1 at the first difference.
    #[command(
        after_help = "Timing fields (index, *_ps, *_ns, *_us, cycles, delays) are left out: another latency or clock rate passes.\n\nExamples:\n  tbgen check biss --expect vectors/biss_master/biss_seed_16bit.json capture.vcd -- --bits 16 --ma tb.ma --slo tb.slo\n  tbgen check ssi --expect expected.json emulator_transcript.json --timeout-us 600"
    )]
    Check {
        /// The protocol (its table name, as `tbgen protocols` lists it).
        protocol: String,
        /// The expected transcript (`tbgen gen`/`tbgen decode` JSON, or an emulator's).
        #[arg(long)]
        expect: PathBuf,
        /// What the master did: a capture (VCD, .sr, CSV; decoded by `tbgen decode <protocol>`) or a JSON transcript.
        capture: PathBuf,
        /// Longest time between the starts of two transactions, µs (a late frame is a difference).
        #[arg(long)]
        timeout_us: Option<f64>,
        /// Options of the protocol's decoder for a capture (port names, --map, bits), after `--`.
        #[arg(last = true)]
        decoder_args: Vec<String>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of our output went away (`| head`): nothing is lost
        // that anyone will read, so end the way Unix tools do, quietly.
        Err(Error::Io { source, .. }) if source.kind() == std::io::ErrorKind::BrokenPipe => {
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("tbgen: error: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn run(command: Command) -> Result<(), Error> {
    match command {
        Command::List { protocol } => {
            let all = builtin::all()?;
            if let Some(p) = &protocol {
                if !all.iter().any(|s| s.table() == p) {
                    let mut tables: Vec<&str> = all.iter().map(|s| s.table()).collect();
                    tables.dedup();
                    return Err(Error::Decode(format!(
                        "list: no protocol `{p}`; give one of: {}",
                        tables.join(", ")
                    )));
                }
            }
            for s in all
                .iter()
                .filter(|s| protocol.as_deref().is_none_or(|p| s.table() == p))
            {
                outln!("{:<28} {:<12} {}", s.name, s.core(), s.description);
            }
        }
        Command::Gen {
            scenarios,
            all,
            out,
            progress,
        } => {
            let chosen = if all {
                builtin::all()?
            } else if scenarios.is_empty() {
                return Err(Error::UnknownScenario(
                    "(none given: name one, or pass --all)".into(),
                    String::new(),
                ));
            } else {
                builtin::resolve_all(&scenarios)?
            };
            for s in &chosen {
                let dir = if all { out.join(s.core()) } else { out.clone() };
                let summary = generate::generate_with(s, &dir, Mode::choose(progress))?;
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
        Command::Crc {
            algorithm,
            bits,
            bytes,
            list,
        } => {
            if !bytes.is_empty() {
                out!(
                    "{}",
                    crc_cmd::report_bytes(algorithm.as_deref().unwrap_or(""), &bytes)?
                );
            } else if list {
                for a in model::crc::CATALOGUE {
                    outln!("{:<16} {:>2}-bit  {}", a.name, a.width, a.source);
                }
            } else {
                out!(
                    "{}",
                    crc_cmd::report(
                        algorithm.as_deref().unwrap_or(""),
                        bits.as_deref().unwrap_or("")
                    )?
                );
            }
        }
        Command::GtkwaveFilter {
            protocol,
            decoder_args,
        } => tbgen::gtkwave_filter::serve(
            &protocol,
            &decoder_args,
            std::io::stdin().lock(),
            std::io::stdout().lock(),
        )?,
        Command::Bench {
            scenario,
            capture,
            samples,
        } => match (scenario, capture) {
            (_, Some(format)) => out!(
                "{}",
                tbgen::bench::capture::report(&format, samples.unwrap_or_default())?
            ),
            (Some(scenario), None) => bench(&scenario)?,
            (None, None) => unreachable!("clap requires a scenario or --capture"),
        },
        Command::Timing(call) => out!("{}", call.run()?),
        Command::Decode(call) => outln!("{}", call.run()?),
        Command::Fields {
            protocol,
            all,
            markdown,
        } => match protocol {
            Some(p) if !all && markdown => out!("{}", tbgen::fields::protocol(&p)?),
            Some(p) if !all => {
                let width = std::env::var("COLUMNS")
                    .ok()
                    .and_then(|c| c.parse().ok())
                    .unwrap_or(100);
                out!("{}", tbgen::fields::plain(&p, width)?)
            }
            _ => out!("{}", tbgen::fields::document()?),
        },
        Command::Protocols { json: false } => out!("{}", registry::table()),
        Command::Protocols { json: true } => out!("{}", registry::json()),
        Command::Eds { kind, serial, out } => {
            let kind: model::canopen::EncoderKind =
                serde_json::from_value(serde_json::Value::String(kind.clone())).map_err(|_| {
                    Error::Decode(format!(
                        "--kind {kind}: give multiturn25, singleturn13, angle20, angle23 or linear"
                    ))
                })?;
            let text = tbgen::canopen::eds::write(&model::canopen::EncoderConfig {
                kind,
                serial_number: serial,
                ..Default::default()
            });
            match out {
                Some(p) => {
                    std::fs::write(&p, text).map_err(|e| Error::io(p.display().to_string(), e))?
                }
                None => out!("{text}"),
            }
        }
        Command::Probes {
            out,
            hdl,
            check,
            sim,
        } => match (out, check) {
            (Some(out), _) => {
                let n = tbgen::probes::export(&out, &hdl)?;
                outln!("{n} probes -> {}", out.display());
            }
            (None, Some(dir)) => {
                let r = tbgen::probes::check(&dir, sim.as_deref().unwrap_or_default())?;
                out!("{}", r.text);
                if !r.ok {
                    std::process::exit(1);
                }
            }
            (None, None) => unreachable!("clap requires --out or --check"),
        },
        Command::Check {
            protocol,
            expect,
            capture,
            timeout_us,
            decoder_args,
        } => {
            let r = tbgen::check::check(&protocol, &expect, &capture, &decoder_args, timeout_us)?;
            outln!("{}", r.text);
            if !r.ok {
                std::process::exit(1);
            }
        }
    }
    Ok(())
}

/// `tbgen bench`: the model's and the VCD writer's speed (tbgen::bench).
fn bench(arg: &str) -> Result<(), Error> {
    out!("{}", tbgen::bench::report(arg)?);
    Ok(())
}
