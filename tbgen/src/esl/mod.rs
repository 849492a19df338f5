//! ESL in `tbgen`: `tbgen decode esl` and `tbgen timing esl` ([`tools`]),
//! and the sigrok check of the line at the host.

pub mod tools;

use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::esl::BenchConfig;

use crate::registry::{self, Protocol, SigrokCheck, TransactionSignals, WaveNames};
use crate::{Error, Result};

/// ESL: the host's driver enable and the line at the host.
#[derive(Parser)]
#[command(name = "esl", after_help = "Example:\n  tbgen decode esl vectors/esl_host/esl_readout_all_ids.vcd")]
pub struct DecodeArgs {
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
}

/// ESL: the request-to-answer budget of one Data ID and the read rate.
#[derive(Parser)]
#[command(name = "esl", after_help = "Examples:\n  tbgen timing esl                           # Data ID 1 of esl_readout_all_ids\n  tbgen timing esl esl_readout_all_ids --data-id 4")]
pub struct TimingArgs {
    /// Built-in scenario name or scenario .toml file with an [esl] table.
    #[arg(default_value = "esl_readout_all_ids")]
    scenario: String,
    /// A Table 3 code (0 = Data ID 1).
    #[arg(long, default_value = "0", value_parser = registry::parse_data_id)]
    data_id: u8,
}

impl Protocol for BenchConfig {
    /// The monitor's i_esl_rx, i_esl_data, i_esl_data_oe: the line at the host is its own data while it drives.
    const MONITOR_PINS: &'static [&'static str] = &["line.line_at_host", "line.line_at_host", "line.tx_en_host"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_done"], "o_abs", "abs");

    /// The state register's values by the model's [`model::esl::State`] (the RTL's state names).
    fn wave_names() -> WaveNames {
        use model::esl::State as S;
        let names = vec![("state", crate::registry::enum_names(&[S::Idle, S::Send, S::Wait, S::Recv, S::Gap, S::Settle, S::Quiet], |s| s as u64))];
        names
    }
    const SIGROK_DECODER: Option<&'static str> = Some("uart");
    const SIGROK_MINIMUM: (usize, usize) = (13, 1000);

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, tx_en, line, baud, broadcast_address, busy_tries, rs_tolerance } = registry::parse_args(args)?;
        if broadcast_address > 7 || !(1..=15).contains(&busy_tries) {
            return Err(Error::Decode("decode esl: give --broadcast-address 0..7 and --busy-tries 1..15".into()));
        }
        let opt = tools::DecodeOptions { baud, broadcast_address, busy_tries, rs_tolerance };
        let mut ops = tools::decode(&file, &tx_en, &line, &opt)?;
        tools::sort_errors(&mut ops);
        let decoded = crate::transcript::Decoded::new("esl", &file, &[("tx_en", &tx_en), ("line", &line)], &ops);
        serde_json::to_string_pretty(&decoded).map_err(|e| Error::Decode(e.to_string()))
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { scenario, data_id } = registry::parse_args(args)?;
        let (s, cfg) = registry::scenario_of::<BenchConfig>(&scenario, "timing esl", "an ESL")?;
        let id = if data_id == 0 { 1 } else { data_id };
        Ok(tools::timing_report(&cfg, &s.name, id).map_err(|e| registry::tool_error("timing esl", &s, &[("data_id", "--data-id")], e))? + &crate::rule_verdict::of_scenario(&s)?)
    }

    /// sigrok's `uart` decoder at 10 Mbps on the line at the host must find,
    /// in order, every character the transcript says was on the wire, in
    /// every scenario, faults included.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        crate::transcript::sigrok_wire_bytes(transcript, self.baud)
    }

    /// The emulator's `motion` and `broadcast_address` are no fields of the
    /// host; the harness polls the first operation's address.
    fn closed_loop(name: &str, table: toml::Table, origin: &str) -> std::result::Result<crate::closed_loop::LoopParameters, String> {
        let _ = name;
        let harness = crate::closed_loop::first_op(&table, &[("address", "ADDRESS", 0)]);
        let core = crate::closed_loop::core::<Self>(table, origin, &["motion", "broadcast_address"])?;
        Ok(crate::closed_loop::LoopParameters { core, harness })
    }
}
