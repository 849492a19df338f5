//! Tamagawa T-format in `tbgen`: `tbgen decode tformat` ([`decode`]),
//! `tbgen timing tformat` ([`timing`]) and the sigrok check of the line at
//! the host.

pub mod decode;
pub mod timing;

use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::tformat::BenchConfig;

use crate::registry::{self, Protocol, SigrokCheck, TransactionSignals, WaveNames};
use crate::{Error, Result};

/// T-format: the line and the driver enable at the host (the bytes alone
/// cannot tell a request from its answer).
#[derive(Parser)]
#[command(name = "tformat", after_help = "Examples:\n  tbgen decode tformat vectors/tformat_host/tformat_readout_all_ids.vcd\n  tbgen decode tformat capture.vcd --line top.ro --tx-en top.de --timeout-us 20")]
pub struct DecodeArgs {
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
}

/// T-format: the request-to-answer budget of one Data ID.
#[derive(Parser)]
#[command(name = "tformat", after_help = "Example:\n  tbgen timing tformat tformat_readout_all_ids --data-id 3")]
pub struct TimingArgs {
    /// Built-in scenario name or scenario .toml file with a [tformat] table.
    #[arg(default_value = "tformat_readout_all_ids")]
    scenario: String,
    /// The Data ID to budget (0, 1, 2, 3, 6, 7, 8, 0xC, 0xD).
    #[arg(long, default_value = "0", value_parser = registry::parse_data_id)]
    data_id: u8,
}

impl Protocol for BenchConfig {
    /// The monitor's i_tf_rx, i_tf_data, i_tf_data_oe: the line at the host is its own data while it drives.
    const MONITOR_PINS: &'static [&'static str] = &["line.line_at_host", "line.line_at_host", "line.tx_en_host"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_done"], "o_abs", "abs");

    /// The state register's values by the model's [`model::tformat::State`] (the RTL's state names).
    fn wave_names() -> WaveNames {
        use model::tformat::State as S;
        let names = vec![("state", crate::registry::enum_names(&[S::Idle, S::Send, S::Wait, S::Recv, S::Gap, S::Quiet], |s| s as u64))];
        names
    }
    const SIGROK_DECODER: Option<&'static str> = Some("uart");
    const SIGROK_MINIMUM: (usize, usize) = (15, 300);

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, line, tx_en, baud, timeout_us } = registry::parse_args(args)?;
        if !((1_000..=100_000_000).contains(&baud) && timeout_us > 0.0 && timeout_us < 1e7) {
            return Err(Error::Decode(format!("decode tformat: --baud {baud} or --timeout-us {timeout_us}: give a bit rate from 1000 to 100000000 bit/s and a positive timeout in µs")));
        }
        let options = decode::Options { line, tx_en, baud, timeout_us };
        let transactions = decode::decode(&file, &options)?;
        decode::to_json(&file, &options, &transactions)
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { scenario, data_id } = registry::parse_args(args)?;
        let (s, cfg) = registry::scenario_of::<BenchConfig>(&scenario, "timing tformat", "a T-format")?;
        Ok(timing::timing_report(&cfg, &s.name, data_id).map_err(|e| registry::tool_error("timing tformat", &s, &[("data_id", "--data-id")], e))? + &crate::rule_verdict::of_scenario(&s)?)
    }

    /// sigrok's `uart` decoder at 2.5 Mbps on the line at the host must find,
    /// in order, every character the transcript says was on the wire.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        crate::transcript::sigrok_wire_bytes(transcript, self.baud)
    }

    /// The emulator's `motion` is no field of the host.
    fn closed_loop(name: &str, table: toml::Table, origin: &str) -> std::result::Result<crate::closed_loop::LoopParameters, String> {
        let _ = name;
        Ok(crate::closed_loop::LoopParameters { core: crate::closed_loop::core::<Self>(table, origin, &["motion"])?, harness: Vec::new() })
    }
}
