//! SSI in `tbgen`: the read budget (`tbgen timing ssi`), the reads of a
//! capture (`tbgen decode ssi`); sigrok's `spi` decoder reads the line at
//! the encoder's pins in the tests.

pub mod decode;
pub mod timing;

use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::ssi::BenchConfig;

use crate::registry::{self, Protocol, SigrokCheck, TransactionSignals, WaveNames};
use crate::{Error, Result};

/// SSI: the reads on clock and data at the master.
#[derive(Parser)]
#[command(
    name = "ssi",
    after_help = "Examples:\n  tbgen decode ssi vectors/ssi_master/ssi_seed_12bit.vcd --bits 12\n  make sim SCENARIO=ssi_seed_12bit WAVES=1 && \\\n    tbgen decode ssi build/waves/ssi_seed_12bit.icarus.vcd --clk tb_ssi_master.o_ssi_clk --data tb_ssi_master.i_ssi_data --bits 12"
)]
pub struct DecodeArgs {
    /// The VCD file.
    file: PathBuf,
    /// Dotted path of the SSI clock at the master.
    #[arg(long, default_value = "top.line.ssi_clk_master")]
    clk: String,
    /// Dotted path of the data line at the master's receiver.
    #[arg(long, default_value = "top.line.ssi_data_master")]
    data: String,
    /// Value bits per read (`[ssi.master] bits`); default: every clocked bit.
    #[arg(long)]
    bits: Option<u32>,
    /// The value is Gray-coded (`code = "gray"`).
    #[arg(long)]
    gray: bool,
    /// Each read carries the value twice (`double_read`).
    #[arg(long)]
    double_read: bool,
    /// Each read carries one more bit that must be 0 (`wire_check`).
    #[arg(long, conflicts_with = "double_read")]
    wire_check: bool,
}

/// SSI: the read cycle and the position-read rate.
#[derive(Parser)]
#[command(name = "ssi", after_help = "Examples:\n  tbgen timing ssi                  # the seed scenario ssi_seed_12bit\n  tbgen timing ssi ssi_long_cable_1mhz")]
pub struct TimingArgs {
    /// Built-in scenario name or scenario .toml file with an [ssi] table.
    #[arg(default_value = "ssi_seed_12bit")]
    scenario: String,
}

impl Protocol for BenchConfig {
    /// The monitor's i_ssi_clk, i_ssi_data: the clock and the data at the reader.
    const MONITOR_PINS: &'static [&'static str] = &["line.ssi_clk_master", "line.ssi_data_master"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_done"], "o_position", "position");

    /// The state register's values by the model's [`model::ssi::State`] (the RTL's state names).
    fn wave_names() -> WaveNames {
        use model::ssi::State as S;
        let names = vec![("state", crate::registry::enum_names(&[S::Idle, S::Latch, S::High, S::Low, S::Pause], |s| s as u64))];
        names
    }
    const SIGROK_DECODER: Option<&'static str> = Some("spi");
    const SIGROK_MINIMUM: (usize, usize) = (10, 25);

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, clk, data, bits, gray, double_read, wire_check } = registry::parse_args(args)?;
        if bits.is_some_and(|b| !(1..=64).contains(&b)) {
            return Err(Error::Decode(format!("decode ssi: --bits {}: give 1 to 64 bits", bits.unwrap_or_default())));
        }
        let layout = decode::Layout { bits, gray, double_read, wire_check };
        let reads = decode::decode(&file, &clk, &data, &layout)?;
        let decoded = crate::transcript::Decoded::new("ssi", &file, &[("clk", &clk), ("data", &data)], &reads);
        serde_json::to_string_pretty(&decoded).map_err(|e| Error::Decode(e.to_string()))
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { scenario } = registry::parse_args(args)?;
        let (s, cfg) = registry::scenario_of::<BenchConfig>(&scenario, "timing ssi", "an SSI")?;
        Ok(timing::timing_report(&cfg, &s.name).map_err(|e| s.value_error(e))? + &crate::rule_verdict::of_scenario(&s)?)
    }

    /// One SPI word per read that clocked, at the encoder's pins: the level
    /// at the storing edge (the idle line, 1) followed by every sampled bit;
    /// a read the reader flagged (a fault between encoder and reader) is not compared.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        let words: Vec<(String, bool)> = transcript["transactions"]
            .as_array()?
            .iter()
            .filter_map(|t| {
                let bits = t["received_bits"].as_str().filter(|b| !b.is_empty())?;
                Some((format!("1{bits}"), t["errors"].as_array().is_some_and(|e| e.is_empty())))
            })
            .collect();
        let wordsize = words.first()?.0.len();
        Some(SigrokCheck {
            decoder: format!("spi:clk=ssi_clk_encoder:miso=ssi_data_encoder:cpol=1:cpha=0:wordsize={wordsize}"),
            annotation: "spi=miso-data",
            expected: words.iter().map(|(w, clean)| clean.then(|| u128::from_str_radix(w, 2).ok()).flatten()).collect(),
        })
    }
}
