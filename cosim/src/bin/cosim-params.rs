//! `cosim-params <ssi|biss|endat|tformat|esl|sar|modbus|can|canopen> <scenario.toml>`: the Verilog parameters of our
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
        return Err("usage: cosim-params <ssi|biss|endat|tformat|esl|sar|modbus|can|canopen> <scenario.toml>".into());
    };
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let root: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| format!("{path}: {}", e.to_string().trim()))?;
    let Some(toml::Value::Table(table)) = root.get(proto.as_str()) else {
        return Err(format!(
            "{path}: no [{proto}] table; a closed-loop configuration is a scenario file"
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
        other => Err(format!("no protocol `{other}`; give ssi, biss, endat, tformat, esl, sar, modbus, can or canopen")),
    }
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
