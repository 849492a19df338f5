//! The Verilog parameters of a closed loop (`hdl/tb_cosim/<loop>/`) from
//! its scenario file, as `cosim-params` prints them: the core's, from the
//! protocol's table as the vectors' headers list them, and the harness's
//! (the station it polls, the nodes on the bus), from the protocol's
//! [`Protocol::closed_loop`](crate::registry::Protocol::closed_loop).

use model::Setup;

/// A closed loop's parameters: the core's (first `F_SYS_HZ`), then the
/// testbench harness's.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct LoopParameters {
    /// `F_SYS_HZ` and the core's parameters.
    pub core: Vec<(String, u64)>,
    /// The testbench's own (`ADDRESS`, `NODES`, `SAR_NODE`).
    pub harness: Vec<(String, u64)>,
}

/// The parameters of closed loop `name` (`sar58k24_can`) of the scenario
/// file `path`: its protocol's table, read by the protocol.
pub fn parameters(name: &str, path: &str) -> Result<LoopParameters, String> {
    let loops: Vec<&str> = model::protocol::closed_loops()
        .map(|(_, l)| l.name)
        .collect();
    let (protocol, _) = model::protocol::closed_loop(name).ok_or_else(|| {
        format!(
            "no closed loop `{name}`; give one of {} (tbgen protocols)",
            loops.join(", ")
        )
    })?;
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let root: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| format!("{path}: {}", e.to_string().trim()))?;
    let table_name = protocol.stem;
    let Some(toml::Value::Table(table)) = root.get(table_name) else {
        return Err(format!(
            "{path}: no [{table_name}] table; a closed-loop configuration is a scenario file"
        ));
    };
    let mut table = table.clone();
    // The emulator's own tables: the master's configuration has none of them.
    for emulator_only in ["emulator", "checks", "random"] {
        table.remove(emulator_only);
    }
    let entry = crate::registry::by_table(table_name)
        .unwrap_or_else(|| panic!("{table_name}: a descriptor tbgen does not register"));
    (entry.closed_loop)(name, table, path)
}

/// The core's parameters, first `F_SYS_HZ`, from the protocol table
/// `table` (without `ignored`: the emulator's fields in it), checked as
/// `tbgen gen` checks a scenario.
pub fn core<S: Setup + serde::de::DeserializeOwned>(
    mut table: toml::Table,
    origin: &str,
    ignored: &[&str],
) -> Result<Vec<(String, u64)>, String> {
    for key in ignored {
        table.remove(*key);
    }
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

/// Harness parameters from the scenario's first operation (`[[ops]]`): the
/// station it polls, the registers it reads, as `(key, PARAMETER, default)`.
pub fn first_op(table: &toml::Table, keys: &[(&str, &str, i64)]) -> Vec<(String, u64)> {
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
