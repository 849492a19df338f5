//! CANopen in `tbgen`: the [`Protocol`] of `model::canopen::BenchConfig`
//! (core `canopen_master`), `tbgen decode canopen` ([`decode`]: the CAN
//! decoder's frames read as NMT, SYNC, EMCY/boot-up, PDO, SDO with object
//! names, node guarding and heartbeat), `tbgen timing canopen` ([`timing`])
//! and the electronic data sheet of the emulated encoder (`tbgen eds`, [`eds`]).

pub mod decode;
pub mod eds;
pub mod timing;

use std::path::PathBuf;

use clap::{ArgMatches, CommandFactory, Parser};
use model::canopen::BenchConfig;

use crate::registry::{self, Protocol, SigrokCheck, TransactionSignals};
use crate::{Error, Result};

/// CANopen: the CAN line read as CANopen frames.
#[derive(Parser)]
#[command(name = "canopen", after_help = "Examples:\n  tbgen decode canopen vectors/canopen_master/canopen_setup_example.vcd\n  tbgen decode canopen capture.vcd --line top.rxd --bit-rate 500000")]
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

/// CANopen: PDO frame time, latency, bus load per encoder and encoders per SYNC cycle at every bit rate.
#[derive(Parser)]
#[command(name = "canopen", after_help = "Examples:\n  tbgen timing canopen\n  tbgen timing canopen --period-ms 1 --cycle-us 500")]
pub struct TimingArgs {
    /// Cyclic timer (6200h) of each encoder, ms, for the bus load.
    #[arg(long, default_value_t = 10.0)]
    period_ms: f64,
    /// SYNC cycle, µs, for the encoders that fit one.
    #[arg(long, default_value_t = 1000.0)]
    cycle_us: f64,
}

/// sigrok's `can` decoder option for a scenario: the master's nominal bit rate and sample point.
pub fn sigrok_decoder(cfg: &BenchConfig) -> Option<String> {
    let t = cfg.master_config().ok()?.can.timing;
    let tb = model::Setup::timebase(cfg).ok()?;
    let rate = tb.f_sys_hz() / t.clocks_per_bit();
    Some(format!("can:can_rx=can_rx:nominal_bitrate={rate}:sample_point={}", t.sample_point() * 100.0))
}

impl Protocol for BenchConfig {
    const TRANSACTION_SIGNALS: TransactionSignals = (&["o_booted", "o_config_done", "o_sdo_abort", "o_node_lost", "o_pos_valid", "o_pos_timeout", "o_emcy_valid", "o_sync_sent"], "o_position", "position");
    const SIGROK_DECODER: Option<&'static str> = Some("can");
    const SIGROK_MINIMUM: (usize, usize) = (6, 300);

    /// The master's state and its controller's (and the monitor's) by the RTL's names.
    fn wave_names() -> Vec<(&'static str, Vec<(u64, String)>)> {
        use model::canopen::master::State as M;
        let master = registry::enum_names(&[M::WaitBoot, M::SdoSend, M::SdoWait, M::NmtSend, M::Run, M::Failed], |s| s as u64)
            .into_iter()
            .map(|(v, _)| (v, ["WAIT_BOOT", "SDO_SEND", "SDO_WAIT", "NMT_SEND", "RUN", "FAILED"][v as usize].to_string()))
            .collect();
        let can: Vec<(u64, String)> = <model::can::BenchConfig as Protocol>::wave_names().remove(0).1;
        vec![("state", master), ("can_state", can.clone()), ("monitor_state", can)]
    }

    fn decode_command() -> Option<clap::Command> {
        Some(DecodeArgs::command())
    }

    fn decode(args: &ArgMatches) -> Result<String> {
        let DecodeArgs { file, line, bit_rate, sample_point } = registry::parse_args(args)?;
        if !(1_000..=1_000_000).contains(&bit_rate) || !(0.5..0.95).contains(&sample_point) {
            return Err(Error::Decode(format!("decode canopen: --bit-rate {bit_rate} or --sample-point {sample_point}: give 1000 to 1000000 bit/s and a sample point between 0.5 and 0.95")));
        }
        let frames = decode::decode(&file, &line, bit_rate, sample_point)?;
        decode::to_json(&file, &line, bit_rate, sample_point, &frames)
    }

    fn timing_command() -> Option<clap::Command> {
        Some(TimingArgs::command())
    }

    fn timing(args: &ArgMatches) -> Result<String> {
        let TimingArgs { period_ms, cycle_us } = registry::parse_args(args)?;
        if !(period_ms > 0.0 && period_ms <= 65_535.0) || !(cycle_us > 0.0 && cycle_us <= 1e7) {
            return Err(Error::Decode(format!("timing canopen: --period-ms {period_ms} or --cycle-us {cycle_us}: give a cyclic timer of 1 to 65535 ms (6200h) and a SYNC cycle above 0 µs")));
        }
        Ok(timing::report(period_ms, cycle_us))
    }

    /// sigrok's `can` decoder on `can_rx` must print, frame by frame, the
    /// identifier, DLC, data bytes, CRC sequence and ACK of every frame the
    /// transcript lists (in every transaction, in order). A scenario with a
    /// damaged frame (errors, another bit rate on the bus) is not compared:
    /// sigrok decodes error flags as frames of their own.
    fn sigrok(&self, transcript: &serde_json::Value) -> Option<SigrokCheck> {
        let decoder = sigrok_decoder(self)?;
        let mut expected = Vec::new();
        for tr in transcript["transactions"].as_array()? {
            for f in tr["frames"].as_array()? {
                if !f["complete"].as_bool()? || !f["errors"].as_array()?.is_empty() {
                    return None;
                }
                expected.push(Some(f["id"].as_u64()? as u128));
                expected.push(Some(f["dlc"].as_u64()? as u128));
                expected.extend(f["data"].as_array()?.iter().map(|b| b.as_u64().map(|v| v as u128)));
                expected.push(Some(f["crc"].as_u64()? as u128));
                expected.push(Some(f["ack"].as_bool()? as u128));
            }
        }
        Some(SigrokCheck { decoder, annotation: "can=id:ext-id:dlc:data:crc-sequence:ack-slot", expected })
    }
}
