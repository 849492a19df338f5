//! CAN in `tbgen`: `tbgen decode can` ([`decode`]), `tbgen timing can`
//! ([`timing`]) and the sigrok check of the `can_rx` line at the core.

pub mod decode;
#[cfg(test)]
pub(crate) mod families;
pub mod sigrok_errors;
pub mod timing;

use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::can::BenchConfig;

use crate::registry::{self, Protocol, SigrokCheck, TransactionSignals, WaveNames};
use crate::{Error, Result};

/// CAN: one line, the transceiver's RXD.
#[derive(Parser)]
#[command(name = "can", after_help = "Examples:\n  tbgen decode can vectors/can_controller/can_rate_250k.vcd --bit-rate 250000 --sample-point 0.8125\n  tbgen decode can capture.vcd --line top.rxd --bit-rate 500000")]
pub struct DecodeArgs {
    /// The VCD file.
    file: PathBuf,
    /// Dotted path of the receive line.
    #[arg(long, default_value = "top.line.can_rx")]
    line: String,
    /// Nominal bit rate, bit/s.
    #[arg(long, default_value_t = 250_000)]
    bit_rate: u64,
    /// Sample point, fraction of the bit.
    #[arg(long, default_value_t = 0.875)]
    sample_point: f64,
}

/// CAN: frame lengths, bus load and the longest bus of a scenario's bit timing.
#[derive(Parser)]
#[command(name = "can", after_help = "Examples:\n  tbgen timing can can_rate_250k\n  tbgen timing can can_rate_1000k --frames-per-s 2000 --dlc 8")]
pub struct TimingArgs {
    /// Built-in scenario name or scenario .toml file with a [can] table.
    #[arg(default_value = "can_rate_250k")]
    scenario: String,
    /// Data bytes of the frame budgeted (0 to 8).
    #[arg(long, default_value_t = 8)]
    dlc: u8,
    /// Frames per second for the bus load.
    #[arg(long, default_value_t = 1000.0)]
    frames_per_s: f64,
}

/// sigrok's `can` decoder option for a scenario (nominal bit rate and
/// sample point of its timing), its bit time and its sample point's offset
/// in f_sys cycles.
pub fn sigrok_decoder(cfg: &BenchConfig) -> Option<(String, u64, u64)> {
    let t = cfg.controller_config().ok()?.timing;
    let tb = model::Setup::timebase(cfg).ok()?;
    let bit = t.clocks_per_bit();
    let rate = tb.f_sys_hz() / bit;
    let sample = (1 + t.tseg1() as u64) * t.brp as u64;
    Some((format!("can:can_rx=can_rx:nominal_bitrate={rate}:sample_point={}", t.sample_point() * 100.0), bit, sample))
}

/// Whether every node of the scenario is inside the limits its bit timing
/// allows: the bus no longer than [`model::can::BitTiming::max_bus_length_m`]
/// and each oscillator inside [`model::can::BitTiming::oscillator_tolerance`]
/// (the core's clock is nominal, so a node may deviate by twice it).
pub fn within_timing_limits(cfg: &BenchConfig) -> Option<bool> {
    let t = cfg.bit_timing().ok()?;
    let f_sys = model::Setup::timebase(cfg).ok()?.f_sys_hz();
    let t_loop = cfg.dut.loop_delay_ns + cfg.sync_stages as f64 * 1e9 / f_sys as f64;
    let span = cfg.nodes.iter().map(|n| (n.position_m - cfg.dut.position_m).abs()).fold(0.0, f64::max);
    let ppm = cfg.nodes.iter().map(|n| n.ppm.abs()).fold(0.0, f64::max);
    Some(span <= t.max_bus_length_m(f_sys, t_loop, cfg.ns_per_m) && ppm * 1e-6 <= 2.0 * t.oscillator_tolerance())
}

/// can_controller's states by the RTL's `localparam` names, which keep the
/// underscores (`CRC_DELIM`): the CAN layouts' and the CANopen layouts'
/// (whose `can_state` and `monitor_state` are can_controller's).
pub fn state_names() -> Vec<(u64, String)> {
    use model::can::State as S;
[
        (S::Integrate, "INTEGRATE"),
        (S::Idle, "IDLE"),
        (S::Frame, "FRAME"),
        (S::CrcDelim, "CRC_DELIM"),
        (S::AckSlot, "ACK_SLOT"),
        (S::AckDelim, "ACK_DELIM"),
        (S::Eof, "EOF"),
        (S::Intermission, "INTERMISSION"),
        (S::Suspend, "SUSPEND"),
        (S::ErrFlag, "ERR_FLAG"),
        (S::OvlFlag, "OVL_FLAG"),
        (S::ErrWait, "ERR_WAIT"),
        (S::ErrDelim, "ERR_DELIM"),
        (S::BusOff, "BUS_OFF"),
    ]
    .iter()
    .map(|&(s, n)| (s as u64, n.to_string()))
    .collect()
}

impl Protocol for BenchConfig {
    /// The monitor's i_can_rx, i_can_tx: the bus and the node's own TX.
    const MONITOR_PINS: &'static [&'static str] = &["line.can_rx", "line.can_tx"];

    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_tx_done", "o_rx_valid", "o_err_bit", "o_err_stuff", "o_err_crc", "o_err_form", "o_err_ack"], "o_rx_id", "rx_id");
    const SIGROK_DECODER: Option<&'static str> = Some("can");
    const SIGROK_MINIMUM: (usize, usize) = (17, 330);

    /// The controller's state (and the listen-only monitor's) by name.
    fn wave_names() -> WaveNames {
        vec![("state", state_names()), ("monitor_state", state_names())]
    }

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, line, bit_rate, sample_point } = registry::parse_args(args)?;
        if !(1_000..=1_000_000).contains(&bit_rate) || !(0.5..0.95).contains(&sample_point) {
            return Err(Error::Decode(format!("decode can: --bit-rate {bit_rate} or --sample-point {sample_point}: give 1000 to 1000000 bit/s and a sample point between 0.5 and 0.95")));
        }
        let frames = decode::decode(&file, &line, bit_rate, sample_point)?;
        decode::to_json(&file, bit_rate, sample_point, &frames)
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { scenario, dlc, frames_per_s } = registry::parse_args(args)?;
        if dlc > 8 || !(0.0..1e7).contains(&frames_per_s) {
            return Err(Error::Decode(format!("timing can: --dlc {dlc} or --frames-per-s {frames_per_s}: give 0 to 8 bytes and a rate ≥ 0")));
        }
        let (s, cfg) = registry::scenario_of::<BenchConfig>(&scenario, "timing can", "a CAN")?;
        Ok(timing::timing_report(&cfg, &s.name, dlc, frames_per_s).map_err(|e| s.value_error(e))? + &crate::rule_verdict::of_scenario(&s)?)
    }

    /// sigrok's `can` decoder on `can_rx` (nominal bit rate and sample
    /// point of the scenario) must print, frame by frame, the identifier
    /// (and extension), DLC, data bytes, CRC sequence and ACK the
    /// transcript holds. Scenarios with errors or overload frames are
    /// compared by [`sigrok_errors`] instead: sigrok decodes error and
    /// overload flags as frames of their own, which no transcript holds. A remote frame with a DLC above 0 is compared up to its DLC
    /// and ends the comparison (sigrok's decoder expects data bits in it).
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        let (decoder, _, _) = sigrok_decoder(self)?;
        let mut expected = Vec::new();
        for tr in transcript["transactions"].as_array()? {
            let outcome = tr["outcome"].as_str()?;
            if !(outcome == "tx_done" || outcome == "rx_valid") || !tr["complete"].as_bool()? || tr["overloads"].as_u64()? > 0 {
                return None;
            }
            let id = tr["id"].as_u64()? as u128;
            if tr["ide"].as_bool()? {
                expected.push(Some(id >> 18));
                expected.push(Some(id & 0x3FFFF));
            } else {
                expected.push(Some(id));
            }
            let dlc = tr["dlc"].as_u64()?;
            expected.push(Some(dlc as u128));
            if tr["rtr"].as_bool()? && dlc > 0 {
                // sigrok's decoder reads DLC × 8 data bits even in a remote
                // frame, so it loses this frame after the DLC (and reads on
                // into whatever follows): compare up to here.
                break;
            }
            expected.extend(tr["data"].as_array()?.iter().map(|b| b.as_u64().map(|v| v as u128)));
            expected.push(Some(tr["crc"].as_u64()? as u128));
            expected.push(Some(tr["ack"].as_bool()? as u128));
        }
        Some(SigrokCheck {
            decoder,
            annotation: "can=id:ext-id:dlc:data:crc-sequence:ack-slot",
            expected,
        })
    }

    /// The harness has one controller per emulated node (`NODES`).
    fn closed_loop(name: &str, table: toml::Table, origin: &str) -> std::result::Result<crate::closed_loop::LoopParameters, String> {
        let _ = name;
        let nodes = table.get("nodes").and_then(|v| v.as_array()).map_or(0, |a| a.len());
        let core = crate::closed_loop::core::<Self>(table, origin, &[])?;
        Ok(crate::closed_loop::LoopParameters { core, harness: vec![("NODES".to_string(), nodes as u64)] })
    }
}
