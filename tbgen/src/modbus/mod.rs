//! Modbus RTU (SAR58K24) in `tbgen`: `tbgen decode modbus` ([`decode`]),
//! `tbgen timing modbus` (the poll budget beside the cycle model's
//! measurement) and the sigrok check of the line at the master. The `modbus` decoder stacked on `uart` is checked in
//! `tbgen/tests/sar_modbus.rs`.

pub mod decode;
pub mod sigrok_fields;
mod silence;

use std::path::PathBuf;

use std::fmt::Write as _;

use clap::{ArgMatches, CommandFactory, Parser};
use model::modbus::{timing, BenchConfig, OpKind, Operation};
use model::testbench;
use model::uart::Parity;
use model::Setup;

use crate::registry::{self, Protocol, SigrokCheck, TransactionSignals, WaveNames};
use crate::{Error, Result};

/// Modbus: the line and the driver enable at the master.
#[derive(Parser)]
#[command(name = "modbus", after_help = "Examples:\n  tbgen decode modbus vectors/modbus_master/modbus_seed_19200.vcd\n  tbgen decode modbus capture.vcd --line top.ro --tx-en top.de --baud 115200 --parity even")]
pub struct DecodeArgs {
    /// The VCD file.
    file: PathBuf,
    /// Dotted path of the RS-485 line (receiver output) at the master.
    #[arg(long, default_value = "top.line.line_at_master")]
    line: String,
    /// Dotted path of the master's RS-485 driver enable.
    #[arg(long, default_value = "top.line.tx_en_master")]
    tx_en: String,
    /// Baud (factory default 19200).
    #[arg(long, default_value_t = 19_200.0)]
    baud: f64,
    /// Parity: none (factory default), odd or even.
    #[arg(long, default_value = "none", value_parser = crate::uart::line::parse_parity)]
    parity: Parity,
    /// The master's answer timeout in µs (`[modbus.master] timeout_us`).
    #[arg(long, default_value_t = 5000.0)]
    timeout_us: f64,
    /// The devices send the position in Gray code.
    #[arg(long)]
    gray: bool,
}

/// Modbus: the poll budget of a scenario's set-up.
#[derive(Parser)]
#[command(name = "modbus", after_help = "Example:\n  tbgen timing modbus modbus_seed_19200 --registers 2")]
pub struct TimingArgs {
    /// Built-in scenario name or scenario .toml file with a [modbus] table.
    #[arg(default_value = "modbus_seed_19200")]
    scenario: String,
    /// Registers per read (1: up to 16 bits, 2: 17 to 32 bits).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=2))]
    registers: u8,
}

/// The budget table for every listed baud rate, then the scenario's own
/// poll: budget and what the cycle model measures for two back-to-back polls.
pub fn timing_report(cfg: &BenchConfig, name: &str, registers: u8) -> std::result::Result<String, model::ConfigError> {
    let tb = cfg.timebase()?;
    let delay = cfg.devices[0].answer_delay_us;
    let mut s = timing::table(cfg.parity, delay);
    let row = timing::poll(cfg.baud, cfg.parity, registers, delay);
    let _ = writeln!(s, "\nscenario: {name}, {} baud, parity {:?}, {registers} register(s)", cfg.baud, cfg.parity);
    let _ = writeln!(s, "budget: poll {:.1} µs = {:.0} polls/s", row.poll_us, row.poll_hz());
    let mut two = cfg.clone();
    two.ops = vec![Operation { op: OpKind::Read, address: cfg.devices[0].address, count: registers, gap_us: 0.0, new_address: 0 }; 2];
    two.devices.truncate(1);
    two.devices[0].faults.clear();
    if registers == 1 && two.devices[0].bits > 16 {
        two.devices[0].bits = 16;
        two.devices[0].positions = vec![0];
    }
    let run = testbench::run_to_end(two.bench()?);
    if let [a, b, ..] = run.transactions.as_slice() {
        let us = |c: u64| c as f64 * tb.period_ps() as f64 / 1e6;
        let _ = writeln!(
            s,
            "model: start to o_done {:.1} µs, start to start {:.1} µs = {:.0} polls/s (the master ends an answer t3.5 after its last stop-bit sample, half a bit before the stop bit ends){}",
            us(a.done_cycle - a.start_cycle),
            us(b.start_cycle - a.start_cycle),
            1e6 / us(b.start_cycle - a.start_cycle),
            if a.errors.is_empty() { String::new() } else { format!(", errors {:?}", a.errors) }
        );
    }
    Ok(s)
}

impl Protocol for BenchConfig {
    /// The monitor's i_rx, i_line, i_line_en: the line at the master is its own data while it drives.
    const MONITOR_PINS: &'static [&'static str] = &["line.line_at_master", "line.line_at_master", "line.tx_en_master"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_done"], "o_value", "value");
    const SIGROK_DECODER: Option<&'static str> = Some("uart");
    const SIGROK_MINIMUM: (usize, usize) = (2, 100);

    fn wave_names() -> WaveNames {
        use model::modbus::State as S;
        vec![("state", crate::registry::enum_names(&[S::Idle, S::Silence, S::Send, S::Wait, S::Recv], |s| s as u64))]
    }

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, line, tx_en, baud, parity, timeout_us, gray } = registry::parse_args(args)?;
        if !((300.0..=10e6).contains(&baud) && timeout_us > 0.0 && timeout_us < 1e7) {
            return Err(Error::Decode(format!("decode modbus: --baud {baud} or --timeout-us {timeout_us}: give a baud rate from 300 to 10000000 and a positive timeout in µs")));
        }
        let options = decode::Options { line, tx_en, baud, parity, timeout_us, gray };
        let transactions = decode::decode(&file, &options)?;
        decode::to_json(&file, &options, &transactions)
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { scenario, registers } = registry::parse_args(args)?;
        let (s, cfg) = registry::scenario_of::<BenchConfig>(&scenario, "timing modbus", "a Modbus")?;
        Ok(timing_report(&cfg, &s.name, registers).map_err(|e| s.value_error(e))? + &crate::rule_verdict::of_scenario(&s)?)
    }

    /// sigrok's `uart` decoder on the line at the master must find, in
    /// order, every character the transcript says was on the wire.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        let parity = match self.parity {
            Parity::None => "none",
            Parity::Odd => "odd",
            Parity::Even => "even",
        };
        Some(SigrokCheck {
            decoder: format!("uart:rx=line_at_master:baudrate={}:parity={parity}", self.baud as u64),
            annotation: "uart=rx-data",
            expected: crate::transcript::wire_bytes(transcript)?.into_iter().map(|b| Some(b as u128)).collect(),
        })
    }

    /// The harness reads the first operation's station and register count.
    fn closed_loop(name: &str, table: toml::Table, origin: &str) -> std::result::Result<crate::closed_loop::LoopParameters, String> {
        let _ = name;
        let harness = crate::closed_loop::first_op(&table, &[("address", "ADDRESS", 1), ("count", "COUNT", 1)]);
        let core = crate::closed_loop::core::<Self>(table, origin, &[])?;
        Ok(crate::closed_loop::LoopParameters { core, harness })
    }
}
