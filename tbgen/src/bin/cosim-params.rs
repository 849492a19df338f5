//! `cosim-params [--part core|harness] <closed loop> <scenario.toml>`: the
//! Verilog parameters of our own master core for a closed-loop scenario
//! (`hdl/tb_cosim/<closed loop>/`, `tbgen protocols` lists them), one
//! `NAME=value` per line, first `F_SYS_HZ`, then the testbench harness's.
//! `scripts/cosim.sh` builds the closed-loop testbench with all of them, so
//! the core and the emulator read one file (the emulator its device, cable
//! and fault tables, this tool the master's); cocotb (`hdl/cocotb/run.py`)
//! builds the core with `--part core` and hands the harness's to the test.

use std::process::ExitCode;

const USAGE: &str =
    "usage: cosim-params [--part core|harness] <closed loop> <scenario.toml> (closed loops: tbgen protocols)";

fn run(args: &[String]) -> Result<Vec<(String, u64)>, String> {
    let (part, rest) = match args {
        [flag, part, rest @ ..] if flag == "--part" => (part.as_str(), rest),
        _ => ("all", args),
    };
    let [name, path] = rest else {
        return Err(USAGE.into());
    };
    let p = tbgen::closed_loop::parameters(name, path)?;
    match part {
        "all" => Ok([p.core, p.harness].concat()),
        "core" => Ok(p.core),
        "harness" => Ok(p.harness),
        other => Err(format!("--part {other}: give core or harness; {USAGE}")),
    }
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
