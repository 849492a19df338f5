//! `tbgen timing endat`: the cycle-time budget of a configuration, phase by
//! phase, and the resulting position-read rate; with `--diagram`, the
//! model's own waveform of the scenario's first request as ASCII.

use model::endat::{budget, diagram, Command};

use crate::scenario::{Scenario, Setup};
use crate::{Error, Result};

/// The report for `scenario` (an EnDat one) and `command`, with `ads` additional data selected.
pub fn report(scenario: &Scenario, command: &str, ads: u64, with_diagram: bool) -> Result<String> {
    let Setup::Endat(cfg) = &scenario.setup else {
        return Err(Error::Scenario { file: scenario.origin.clone(), message: "not an EnDat scenario: `tbgen timing endat` needs an [endat] table".into() });
    };
    let cmd = Command::ALL.iter().copied().find(|c| c.name() == command).ok_or_else(|| Error::Scenario {
        file: scenario.origin.clone(),
        message: format!(
            "unknown command `{command}`: use one of {}",
            Command::ALL.iter().map(|c| c.name()).collect::<Vec<_>>().join(", ")
        ),
    })?;
    let b = budget::budget_for(cfg, cmd, ads).map_err(|e| scenario.value_error(e))?;
    let mut out = format!("scenario {}: {}\n", scenario.name, scenario.description);
    out += &b.render();
    if with_diagram {
        let m = cfg.master_config().map_err(|e| scenario.value_error(e))?;
        let start = diagram::first_start(cfg).map_err(|e| scenario.value_error(e))?;
        let step = (m.clocks_per_bit / 2).max(1);
        let width = (b.cycle_clocks.min(200 * step) / step) as usize;
        out += &format!("\nwaveform of the first request, one character per half clock period ({step} cycles), from cycle {start}:\n");
        out += &diagram::render(cfg, step, start, width).map_err(|e| scenario.value_error(e))?;
        out += "rx phase: 0 idle, 1 turnaround, 2 polling, 3 F bits, 4 data, 5 CRC, 6/7 additional datum 2 and CRC, 8/9 additional datum 1 and CRC\n";
    }
    Ok(out)
}
