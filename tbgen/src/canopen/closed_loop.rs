//! The closed loop `sar58k24_can`: a `[canopen]` scenario with a SAR58K24 in
//! CAN mode, read by `can_controller` and a command sequencer
//! (`hdl/tb_cosim/sar58k24_can/`).

use model::canopen::BenchConfig;

use crate::closed_loop::LoopParameters;

/// The controller's bit timing (the master's, from `bit_rate_kbps`) as the
/// core's parameters, and the first `[[canopen.sar]]` device as the
/// harness's (`SAR_DEVICE` its emulator device number: the DS 406 encoders
/// come first).
pub(super) fn sar58k24_can(table: toml::Table, origin: &str) -> Result<LoopParameters, String> {
    use model::canopen::sar58k24::Direction;
    let all = crate::closed_loop::core::<BenchConfig>(table.clone(), origin, &[])?;
    let cfg: BenchConfig = toml::Value::Table(table)
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
    let core = all
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
    let harness = [
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
    .map(|(k, v)| (k.to_string(), v))
    .to_vec();
    Ok(LoopParameters { core, harness })
}
