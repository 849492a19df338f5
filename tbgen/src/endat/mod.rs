//! EnDat 2.1 / 2.2 in `tbgen`: `tbgen decode endat` ([`decode`]) and
//! `tbgen timing endat` ([`timing`]).

pub mod decode;
pub mod timing;

use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::endat::BenchConfig;

use crate::registry::{self, Protocol, TransactionSignals, WaveNames};
use crate::{builtin, Error, Result};

/// EnDat 2.1 / 2.2: clock and data at the master.
#[derive(Parser)]
#[command(name = "endat", after_help = "Examples:\n  tbgen decode endat vectors/endat_master/endat_params_22_2mhz.vcd\n  tbgen decode endat vectors/endat_master/endat_pos22_ad_8mhz_100m.vcd --meas-khz 200\n  tbgen decode endat capture.vcd --clk tb.clk_pin --data tb.data_pin --pos-bits 13")]
pub struct DecodeArgs {
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
}

/// EnDat: the cycle budget of one mode command, phase by phase.
#[derive(Parser)]
#[command(name = "endat", after_help = "Examples:\n  tbgen timing endat endat_pos22_ad_8mhz_100m --ads 2\n  tbgen timing endat my.toml --command pos21 --diagram")]
pub struct TimingArgs {
    /// Built-in scenario name or scenario .toml file with an [endat] table.
    #[arg(default_value = "endat_pos22_ad_8mhz_100m")]
    scenario: String,
    /// Mode command to budget (`pos22`, `pos21`, `send21`, ...).
    #[arg(long, default_value = "pos22")]
    command: String,
    /// Additional data selected (0, 1 or 2; type 2.2 commands).
    #[arg(long, default_value_t = 0)]
    ads: u64,
    /// Also print the model's waveform of the budgeted command (the scenario's first such request, else one on its set-up).
    #[arg(long)]
    diagram: bool,
}

impl Protocol for BenchConfig {
    /// The monitor's i_endat_clk, i_endat_data, i_endat_data_oe, i_endat_data_in: the line at the master is its own data while it drives, the encoder's answer otherwise.
    const MONITOR_PINS: &'static [&'static str] = &["line.endat_clk_master", "line.endat_data_master", "line.master_oe", "line.endat_data_master"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_done", "o_meas_done"], "o_position", "position");

    /// The state register's values by the model's [`model::endat::State`] (the RTL's state names).
    fn wave_names() -> WaveNames {
        use model::endat::State as S;
        let mut names = vec![("state", crate::registry::enum_names(&[S::Idle, S::First, S::High, S::Low, S::Pause], |s| s as u64))];
        use model::endat::RxPhase as P;
        let phases = [P::Idle, P::Turn, P::Poll, P::FBit, P::Data, P::Crc, P::Ad2, P::Ad2Crc, P::Ad1, P::Ad1Crc];
        names.push(("rx_phase", phases.iter().map(|&p| (p as u64, format!("RX_{p:?}").to_uppercase())).collect()));
        names
    }

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, clk, data, pos_bits, meas_khz } = registry::parse_args(args)?;
        let opts = decode::Options { pos_bits, meas_khz };
        let mut notes = Vec::new();
        let transactions = decode::decode(&file, &clk, &data, &opts, &mut notes)?;
        for n in notes {
            eprintln!("NOTE: {n}");
        }
        let envelope = crate::transcript::Decoded::new("endat", &file, &[("clk", clk.as_str()), ("data", data.as_str())], &transactions);
        serde_json::to_string_pretty(&envelope).map_err(|e| Error::Decode(e.to_string()))
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { scenario, command, ads, diagram } = registry::parse_args(args)?;
        let s = builtin::resolve(&scenario)?;
        Ok(timing::report(&s, &command, ads, diagram)? + &crate::rule_verdict::of_scenario(&s)?)
    }

    /// The emulator's `motion` is no field of the master.
    fn closed_loop(name: &str, table: toml::Table, origin: &str) -> std::result::Result<crate::closed_loop::LoopParameters, String> {
        let _ = name;
        Ok(crate::closed_loop::LoopParameters { core: crate::closed_loop::core::<Self>(table, origin, &["motion"])?, harness: Vec::new() })
    }
}
