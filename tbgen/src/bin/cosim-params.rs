//! `cosim-params <ssi|biss|endat|tformat|esl|sar|modbus|can|canopen|sar_can> <scenario.toml>`: the Verilog parameters of our
//! own master core for a closed-loop scenario, one `NAME=value` per line,
//! first `F_SYS_HZ`. `scripts/cosim.sh` builds the closed-loop testbench with
//! them, so the core and the emulator read one file (the emulator its
//! device, cable and fault tables, this tool the master's).

use std::process::ExitCode;

use model::Setup;

fn params<S: Setup + serde::de::DeserializeOwned>(
    table: toml::Table,
    origin: &str,
) -> Result<Vec<(String, u64)>, String> {
    let cfg: S = toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| format!("{origin}: {}", e.to_string().trim()))?;
    let err = |e: model::ConfigError| format!("{origin}: {e}");
    cfg.validate().map_err(err)?;
    let tb = cfg.timebase().map_err(err)?;
    let mut out = vec![("F_SYS_HZ".to_string(), tb.f_sys_hz())];
    out.extend(
        cfg.verilog_parameters()
            .map_err(err)?
            .into_iter()
            .map(|(k, v)| (k.to_string(), v)),
    );
    Ok(out)
}

fn run(args: &[String]) -> Result<Vec<(String, u64)>, String> {
    let [proto, path] = args else {
        return Err("usage: cosim-params <ssi|biss|endat|tformat|esl|sar|modbus|can|canopen|sar_can> <scenario.toml>".into());
    };
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let root: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| format!("{path}: {}", e.to_string().trim()))?;
    // `sar_can` reads the [canopen] table (the SAR58K24's CAN mode shares the CANopen bus).
    let table_name = if proto == "sar_can" {
        "canopen"
    } else {
        proto.as_str()
    };
    let Some(toml::Value::Table(table)) = root.get(table_name) else {
        return Err(format!(
            "{path}: no [{table_name}] table; a closed-loop configuration is a scenario file"
        ));
    };
    let mut table = table.clone();
    table.remove("emulator");
    table.remove("checks");
    table.remove("random");
    match proto.as_str() {
        "ssi" => params::<model::ssi::BenchConfig>(table, path),
        "biss" => params::<model::biss::BenchConfig>(table, path),
        "sar" => {
            let harness = first_op(&table, &[("address", "ADDRESS", 1)]);
            params::<model::sar58k24::BenchConfig>(table, path).map(|p| [p, harness].concat())
        }
        "modbus" => {
            let harness = first_op(&table, &[("address", "ADDRESS", 1), ("count", "COUNT", 1)]);
            params::<model::modbus::BenchConfig>(table, path).map(|p| [p, harness].concat())
        }
        "can" => {
            let nodes = table.get("nodes").and_then(|v| v.as_array()).map_or(0, |a| a.len());
            params::<model::can::BenchConfig>(table, path)
                .map(|p| [p, vec![("NODES".to_string(), nodes as u64)]].concat())
        }
        "canopen" => params::<model::canopen::BenchConfig>(table, path),
        "sar_can" => sar_can(table, path),
        "tformat" => {
            table.remove("motion");
            params::<model::tformat::BenchConfig>(table, path)
        }
        "endat" => {
            table.remove("motion");
            params::<model::endat::BenchConfig>(table, path)
        }
        "esl" => {
            table.remove("motion");
            table.remove("broadcast_address");
            let harness = first_op(&table, &[("address", "ADDRESS", 0)]);
            params::<model::esl::BenchConfig>(table, path).map(|p| [p, harness].concat())
        }
        other => Err(format!("no protocol `{other}`; give ssi, biss, endat, tformat, esl, sar, modbus, can, canopen or sar_can")),
    }
}

/// `sar_can`: a `[canopen]` scenario with a SAR58K24 in CAN mode, read by
/// `can_controller` and a command sequencer (hdl/tb_cosim/sar58k24_can):
/// the controller's bit timing (the master's, from `bit_rate_kbps`) and
/// the first `[[canopen.sar]]` device as harness parameters (`SAR_DEVICE`
/// its emulator device number: the DS 406 encoders come first).
fn sar_can(table: toml::Table, origin: &str) -> Result<Vec<(String, u64)>, String> {
    use model::canopen::sar58k24::Direction;
    let all = params::<model::canopen::BenchConfig>(table.clone(), origin)?;
    let cfg: model::canopen::BenchConfig = toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| format!("{origin}: {}", e.to_string().trim()))?;
    let Some(sar) = cfg.sar.first() else {
        return Err(format!("{origin}: field `sar`: no [[canopen.sar]]; give the SAR58K24 the testbench commands ([[canopen.sar]] with [canopen.sar.encoder] node = 0x20)"));
    };
    let timing = [
        "F_SYS_HZ",
        "BRP",
        "PROP_SEG",
        "PHASE_SEG1",
        "PHASE_SEG2",
        "SJW",
        "SYNC_STAGES",
    ];
    let mut out: Vec<(String, u64)> = all
        .into_iter()
        .filter(|(k, _)| timing.contains(&k.as_str()))
        .collect();
    let e = &sar.encoder;
    let rate_code = match cfg.bit_rate_kbps {
        1000 => 0,
        500 => 2,
        250 => 3,
        other => return Err(format!("{origin}: field `bit_rate_kbps`: {other} kbit/s is no SAR58K24 rate; give 1000, 500 or 250 (seed 001 §3.4 ③)")),
    };
    out.extend(
        [
            ("SAR_DEVICE", cfg.encoders.len() as u64),
            ("SAR_NODE", e.node as u64),
            ("SAR_BITS", e.bits as u64),
            ("SAR_ANSWER_BASE", e.answer_base as u64),
            ("SAR_CYCLE_MS", e.cycle_ms as u64),
            (
                "SAR_DIRECTION_CODES",
                (e.direction == Direction::Codes22And23) as u64,
            ),
            ("SAR_RATE_CODE", rate_code),
        ]
        .map(|(k, v)| (k.to_string(), v)),
    );
    Ok(out)
}

/// Harness parameters of the closed-loop testbench from the scenario's first
/// operation (`[[ops]]`): the station it polls, the registers it reads.
fn first_op(table: &toml::Table, keys: &[(&str, &str, i64)]) -> Vec<(String, u64)> {
    let op = table
        .get("ops")
        .and_then(|v| v.as_array())
        .and_then(|a| a.first())
        .and_then(|v| v.as_table());
    keys.iter()
        .map(|(key, name, default)| {
            let v = op
                .and_then(|t| t.get(*key))
                .and_then(|v| v.as_integer())
                .unwrap_or(*default);
            (name.to_string(), v.max(0) as u64)
        })
        .collect()
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(list) => {
            for (k, v) in list {
                println!("{k}={v}");
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("cosim-params: {e}");
            ExitCode::from(2)
        }
    }
}
