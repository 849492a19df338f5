//! SAR58K24 asynchronous serial in `tbgen`: `tbgen decode sar` ([`decode`]),
//! `tbgen timing sar` (frame time
//! per baud rate, the highest refresh rate that fits, trigger-to-position
//! latency, beside the cycle model's measurement) and the sigrok check of
//! the line at the host.

pub mod decode;

use std::fmt::Write as _;
use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::sar58k24::{timing, AnswerTag, BenchConfig, Mode, OpKind, Operation};
use model::testbench;
use model::uart::Parity;
use model::Setup;

use crate::registry::{self, Protocol, SigrokCheck, TransactionSignals, WaveNames};
use crate::{Error, Result};

/// SAR58K24: the line and the host's driver enable.
#[derive(Parser)]
#[command(name = "sar", after_help = "Examples:\n  tbgen decode sar vectors/sar_async_host/sar_seed_timed_14bit.vcd --bits 14\n  tbgen decode sar capture.vcd --line top.ro --tx-en top.de --baud 9600 --bits 24 --gray\n  tbgen decode sar vectors/sar_async_host/sar_bus_fixed81.vcd --answer-tag fixed81")]
pub struct DecodeArgs {
    /// The VCD file.
    file: PathBuf,
    /// Dotted path of the line (receiver output) at the host.
    #[arg(long, default_value = "top.line.line_at_host")]
    line: String,
    /// Dotted path of the host's driver enable (bus commands).
    #[arg(long, default_value = "top.line.tx_en_host")]
    tx_en: String,
    /// Baud (2400 to 115200).
    #[arg(long, default_value_t = 115_200.0)]
    baud: f64,
    /// Parity: none, odd or even.
    #[arg(long, default_value = "none", value_parser = crate::uart::line::parse_parity)]
    parity: Parity,
    /// Resolution, 10 to 32 bits (2, 3 or 4 data bytes).
    #[arg(long, default_value_t = 16)]
    bits: u32,
    /// Positions are sent in Gray code.
    #[arg(long)]
    gray: bool,
    /// Idle bit times that end a frame (`[sar.host] gap_bits`).
    #[arg(long, default_value_t = 15.0)]
    gap_bits: f64,
    /// Second byte of a bus answer, as the encoders' `answer_tag` (RTL
    /// `TAG_ADDRESS`): address (`FF Bx` after `BC AA Bx`, TAG_ADDRESS = 1) or
    /// fixed81 (`FF 81` after a command too, TAG_ADDRESS = 0).
    #[arg(long, default_value = "address", value_parser = parse_answer_tag)]
    answer_tag: AnswerTag,
}

/// `--answer-tag`: the scenario field's spellings.
fn parse_answer_tag(s: &str) -> std::result::Result<AnswerTag, String> {
    match s {
        "address" => Ok(AnswerTag::Address),
        "fixed81" => Ok(AnswerTag::Fixed81),
        _ => Err(format!("`{s}`: give address (bus answers FF Bx, TAG_ADDRESS = 1) or fixed81 (FF 81, TAG_ADDRESS = 0)")),
    }
}

/// SAR58K24: the frame and latency budget of a scenario's set-up.
#[derive(Parser)]
#[command(name = "sar", after_help = "Example:\n  tbgen timing sar sar_seed_timed_14bit --t3-us 20")]
pub struct TimingArgs {
    /// Built-in scenario name or scenario .toml file with a [sar] table.
    #[arg(default_value = "sar_seed_timed_14bit")]
    scenario: String,
    /// T3, the acquisition time of the handshake modes, µs.
    #[arg(long, default_value_t = 20.0)]
    t3_us: f64,
}

/// The budget table, then what the model measures: frame to frame in the
/// timed modes, trigger (or command) to `o_done` in the others.
pub fn timing_report(cfg: &BenchConfig, name: &str, t3_us: f64) -> std::result::Result<String, model::ConfigError> {
    let tb = cfg.timebase()?;
    let e = &cfg.encoders[0];
    let mut s = timing::table(e.bits, cfg.parity, t3_us);
    let _ = writeln!(s, "\nscenario: {name}, mode {:?}, {} baud, {} bits", cfg.mode, cfg.baud, e.bits);
    let mut two = cfg.clone();
    two.ops = vec![Operation { op: OpKind::Read, address: e.address, gap_us: 0.0, repeat: 2 }];
    two.encoders.truncate(1);
    two.encoders[0].faults.clear();
    two.encoders[0].acquisition_us = t3_us.max(two.encoders[0].trigger_min_low_us);
    two.second_drivers.clear();
    let run = testbench::run_to_end(two.bench()?);
    let us = |c: u64| c as f64 * tb.period_ps() as f64 / 1e6;
    if let [a, b, ..] = run.transactions.as_slice() {
        let what = if cfg.mode.is_timed() { "read start (waiting) to o_done" } else if cfg.mode == Mode::Handshake || cfg.mode == Mode::HandshakeClear { "trigger to o_done" } else { "command to o_done" };
        let _ = writeln!(
            s,
            "model: {what} {:.1} µs, start to start {:.1} µs = {:.0} positions/s{}",
            us(a.done_cycle - a.start_cycle),
            us(b.start_cycle - a.start_cycle),
            1e6 / us(b.start_cycle - a.start_cycle),
            if a.errors.is_empty() { String::new() } else { format!(", errors {:?}", a.errors) }
        );
    }
    Ok(s)
}

impl Protocol for BenchConfig {
    /// The monitor's i_rx, i_line, i_line_en, i_trigger, i_clr: the line at the host is its own data while it drives; TRIGGER and CLR at the host's ports.
    const MONITOR_PINS: &'static [&'static str] = &["line.line_at_host", "line.line_at_host", "line.tx_en_host", "sar_async_host.o_trigger", "sar_async_host.o_clr"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_done"], "o_position", "position");
    const SIGROK_DECODER: Option<&'static str> = Some("uart");
    const SIGROK_MINIMUM: (usize, usize) = (4, 100);

    fn wave_names() -> WaveNames {
        use model::sar58k24::State as S;
        vec![("state", crate::registry::enum_names(&[S::Idle, S::Trigger, S::Clr, S::Send, S::Wait], |s| s as u64))]
    }

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, line, tx_en, baud, parity, bits, gray, gap_bits, answer_tag } = registry::parse_args(args)?;
        if !(300.0..=10e6).contains(&baud) || !(10..=32).contains(&bits) || !(1.0..=1e6).contains(&gap_bits) {
            return Err(Error::Decode(format!(
                "decode sar: --baud {baud}, --bits {bits} or --gap-bits {gap_bits}: give a baud rate from 300 to 10000000, 10 to 32 bits and 1 to 1000000 idle bit times"
            )));
        }
        let options = decode::Options { line, tx_en, baud, parity, bits, gray, gap_bits, answer_tag };
        let bursts = decode::decode(&file, &options)?;
        decode::to_json(&file, &options, &bursts)
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { scenario, t3_us } = registry::parse_args(args)?;
        let (s, cfg) = registry::scenario_of::<BenchConfig>(&scenario, "timing sar", "a SAR58K24")?;
        Ok(timing_report(&cfg, &s.name, t3_us).map_err(|e| s.value_error(e))? + &crate::rule_verdict::of_scenario(&s)?)
    }

    /// sigrok's `uart` decoder on the line at the host must find, in order,
    /// every character the transcript says was on the wire.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        let parity = match self.parity {
            Parity::None => "none",
            Parity::Odd => "odd",
            Parity::Even => "even",
        };
        Some(SigrokCheck {
            decoder: format!("uart:rx=line_at_host:baudrate={}:parity={parity}", self.baud as u64),
            annotation: "uart=rx-data",
            expected: crate::transcript::wire_bytes(transcript)?.into_iter().map(|b| Some(b as u128)).collect(),
        })
    }

    /// The harness polls the first operation's station.
    fn closed_loop(name: &str, table: toml::Table, origin: &str) -> std::result::Result<crate::closed_loop::LoopParameters, String> {
        let _ = name;
        let harness = crate::closed_loop::first_op(&table, &[("address", "ADDRESS", 1)]);
        let core = crate::closed_loop::core::<Self>(table, origin, &[])?;
        Ok(crate::closed_loop::LoopParameters { core, harness })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::registry::Protocol;

    /// `tbgen decode sar FILE --answer-tag fixed81`, as a user types it.
    fn decode_cli(args: &[&str]) -> Result<String> {
        let m = DecodeArgs::command().try_get_matches_from(std::iter::once("sar").chain(args.iter().copied())).map_err(|e| Error::Decode(e.to_string()))?;
        <BenchConfig as Protocol>::decode(&m)
    }

    #[test]
    fn the_command_line_reads_bus_answers_tagged_81_with_answer_tag_fixed81() {
        let dir = tempfile::tempdir().unwrap();
        let (_, vcd, _) = crate::uart::line::generated("sar_bus_fixed81", dir.path());
        let vcd = vcd.to_str().unwrap();
        let read = |args: &[&str]| -> Vec<(Option<u64>, Vec<String>)> {
            let json: serde_json::Value = serde_json::from_str(&decode_cli(args).unwrap()).unwrap();
            let events = json["transactions"].as_array().unwrap().iter().filter(|e| e["kind"] != "command");
            events.map(|e| (e["position"].as_u64(), e["errors"].as_array().unwrap().iter().map(|f| f.as_str().unwrap().to_string()).collect())).collect()
        };
        assert_eq!(read(&[vcd, "--answer-tag", "fixed81"]), [(Some(8738), vec![]), (Some(0), vec![]), (Some(12), vec![])]);
        // The default (address) flags each answer; a misspelt tag names the choices.
        assert_eq!(read(&[vcd]), vec![(None, vec!["frame".to_string()]); 3]);
        let e = decode_cli(&[vcd, "--answer-tag", "fixed_81"]).unwrap_err().to_string();
        assert!(e.contains("fixed_81") && e.contains("address") && e.contains("fixed81"), "{e}");
        assert!(DecodeArgs::command().render_long_help().to_string().contains("--answer-tag"));
    }
}
