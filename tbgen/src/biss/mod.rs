//! BiSS-C in `tbgen`: `tbgen decode biss` and `tbgen timing biss` ([`tools`]).

pub mod tools;

use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::biss::BenchConfig;

use crate::registry::{self, Protocol, TransactionSignals, WaveNames};
use crate::{Error, Result};

/// BiSS-C: MA and SLO at the master.
#[derive(Parser)]
#[command(name = "biss", after_help = "Examples:\n  tbgen decode biss vectors/biss_master/biss_seed_16bit.vcd --bits 16\n  tbgen decode biss vectors/biss_master/biss_chain_3slaves.vcd --bits 12,26,32 --crc-width 6,6,8 --crc-poly 3,3,7")]
pub struct DecodeArgs {
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
}

/// BiSS-C: the cycle budget and the position-read rate.
#[derive(Parser)]
#[command(name = "biss", after_help = "Examples:\n  tbgen timing biss                          # the seed scenario biss_seed_16bit\n  tbgen timing biss biss_clock_1mhz_100m")]
pub struct TimingArgs {
    /// Built-in scenario name or scenario .toml file with a [biss] table.
    #[arg(default_value = "biss_seed_16bit")]
    scenario: String,
}

impl Protocol for BenchConfig {
    /// The monitor's i_ma, i_slo: MA and SLO at the master.
    const MONITOR_PINS: &'static [&'static str] = &["line.ma_master", "line.slo_master"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_done"], "o_delay", "delay_cycles");

    /// The state register's values by the model's [`model::biss::State`] (the RTL's state names).
    fn wave_names() -> WaveNames {
        use model::biss::State as S;
        let names = vec![("state", crate::registry::enum_names(&[S::Idle, S::Ack, S::Start, S::Cds, S::Data, S::Err, S::Warn, S::Crc, S::Stop, S::Timeout, S::NoAck], |s| s as u64))];
        names
    }

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, ma, slo, bits, crc_width, crc_poly } = registry::parse_args(args)?;
        let n = bits.len();
        let crc_width = if crc_width.is_empty() { vec![6; n] } else { crc_width };
        let crc_poly = if crc_poly.is_empty() { vec![3; n] } else { crc_poly };
        if crc_width.len() != n || crc_poly.len() != n || bits.iter().any(|b| !(1..=64).contains(b)) || crc_width.iter().any(|w| !(1..=8).contains(w)) {
            return Err(Error::Decode("decode biss: give --bits (1..64 each) and, if any, one --crc-width (1..8) and --crc-poly per slave".into()));
        }
        let layout = tools::Layout { bits, crc_width, crc_poly, timeout_ps: None };
        let frames = tools::decode(&file, &ma, &slo, &layout)?;
        let decoded = crate::transcript::Decoded::new("biss", &file, &[("ma", &ma), ("slo", &slo)], &frames);
        serde_json::to_string_pretty(&decoded).map_err(|e| Error::Decode(e.to_string()))
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { scenario } = registry::parse_args(args)?;
        let (s, cfg) = registry::scenario_of::<BenchConfig>(&scenario, "timing biss", "a BiSS-C")?;
        Ok(tools::timing_report(&cfg, &s.name).map_err(|e| s.value_error(e))? + &crate::rule_verdict::of_scenario(&s)?)
    }
}
