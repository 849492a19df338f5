//! The port half of every replay testbench, written from the model.
//!
//! A core's ports are listed once, in its model (`input_ports` and
//! `output_ports`, in vector-file order). The replay testbench
//! `hdl/tb/<core>/tb_<core>.v` includes `tb_<core>_ports.vh`, which this
//! module writes from those lists: the port counts the vector player needs,
//! a `reg` per input at its idle level and a `wire` per output, the task
//! that drives the inputs from a record, the concatenation and the task that
//! compare the outputs, and `DUT_PORTS`, the instance's port connections.
//! The testbench keeps only what is its own: parameters, the instance's
//! clock, reset and parameter list, and its reset-state check.
//!
//! The test below holds every committed file to what this module writes
//! (`WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports`
//! rewrites them), so a port added to a model without its testbench, or the
//! other way round, fails `make test` before any simulator runs.

use std::fmt::Write as _;

use model::Port;

use crate::registry::{Protocol, Visitor};
use crate::{builtin, Result};

/// A core and its ports in vector-file order, as its bench lays them out.
#[derive(Debug, Clone)]
pub struct CorePorts {
    /// The Verilog module name (`ssi_master`).
    pub core: &'static str,
    /// Inputs, in vector-file order.
    pub inputs: Vec<Port>,
    /// Outputs, in vector-file order.
    pub outputs: Vec<Port>,
}

/// Every core's ports, from the first built-in scenario of each core (the
/// port lists do not depend on the scenario; their widths may, and those
/// are written with their parameter).
pub fn all() -> Result<Vec<CorePorts>> {
    let mut cores: Vec<CorePorts> = Vec::new();
    for scenario in builtin::all()? {
        if cores.iter().any(|c| c.core == scenario.core()) {
            continue;
        }
        cores.push(scenario.setup.accept(PortsOf)?);
    }
    Ok(cores)
}

struct PortsOf;

impl Visitor for PortsOf {
    type Output = Result<CorePorts>;
    fn visit<S: Protocol>(self, cfg: &S) -> Result<CorePorts> {
        use model::Testbench as _;
        let bench = cfg
            .bench()
            .map_err(|e| crate::Error::Decode(format!("{}: {e}", S::CORE)))?;
        let layout = bench.layout();
        Ok(CorePorts {
            core: S::CORE,
            inputs: layout.inputs.clone(),
            outputs: layout.outputs.clone(),
        })
    }
}

/// The file's path in the tree, from the repository root.
pub fn path(core: &str) -> String {
    format!("hdl/tb/{core}/tb_{core}_ports.vh")
}

/// `[W-1:0] ` for a port wider than one bit (by its parameter where it has
/// one), nothing for a single bit.
fn range(p: &Port) -> String {
    match (p.width_param, p.width) {
        (Some(param), _) => format!("[{param}-1:0] "),
        (None, 1) => String::new(),
        (None, w) => format!("[{}:0] ", w - 1),
    }
}

/// The total width of `ports` as a Verilog expression: the fixed widths
/// summed, then each parameter.
fn width_sum(ports: &[Port]) -> String {
    let fixed: u32 = ports
        .iter()
        .filter(|p| p.width_param.is_none())
        .map(|p| p.width)
        .sum();
    let mut terms = vec![fixed.to_string()];
    terms.extend(ports.iter().filter_map(|p| p.width_param.map(String::from)));
    terms.join(" + ")
}

/// The width's mask, as the drivers apply it to a 64-bit vector word.
fn mask(p: &Port) -> String {
    match p.width_param {
        Some(param) => format!("{{{param}{{1'b1}}}}"),
        None => format!("{}'h{:X}", p.width, p.mask()),
    }
}

/// The include file of `ports`' testbench.
pub fn render(ports: &CorePorts) -> String {
    let core = ports.core;
    let mut v = String::new();
    let mut line = |s: String| {
        v.push_str(&s);
        v.push('\n');
    };
    line(format!(
        "// tb_{core}_ports.vh: the ports of {core} in vector-file order, from the model's port lists."
    ));
    line(
        "// Written by tbgen (tbgen/src/testbench_ports.rs); do not edit: change the model's"
            .into(),
    );
    line("// input_ports/output_ports and run".into());
    line("//   WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports".into());
    line(format!(
        "// Included by tb_{core}.v after its parameters; it includes the vector player."
    ));
    line(String::new());
    line(format!("localparam N_IN = {};", ports.inputs.len()));
    line(format!("localparam N_OUT = {};", ports.outputs.len()));
    line(format!(
        "localparam OUT_BITS = {};",
        width_sum(&ports.outputs)
    ));
    line(String::new());
    line("`include \"vector_player.vh\"".into());
    line(String::new());
    line("// Inputs rest at their idle level until the first record drives them.".into());
    for p in &ports.inputs {
        line(format!("reg {}{} = {};", range(p), p.name, p.idle));
    }
    for p in &ports.outputs {
        line(format!("wire {}{};", range(p), p.name));
    }
    line(String::new());
    line("task apply_inputs;".into());
    line("    begin".into());
    for (k, p) in ports.inputs.iter().enumerate() {
        line(format!("        {} = `IN_WORD({k}) & {};", p.name, mask(p)));
    }
    line("    end".into());
    line("endtask".into());
    line(String::new());
    line("// Every output in one vector, in check_outputs' order: the player runs".into());
    line("// check_outputs again only when this or the expected record changes.".into());
    line("wire [OUT_BITS-1:0] all_outputs = {".into());
    let names: Vec<String> = ports
        .outputs
        .iter()
        .map(|p| format!("    {}", p.name))
        .collect();
    line(names.join(",\n"));
    line("};".into());
    line(String::new());
    line("task check_outputs;".into());
    line("    begin".into());
    for (k, p) in ports.outputs.iter().enumerate() {
        line(format!("        `CHECK({k}, \"{0}\", {0})", p.name));
    }
    line("    end".into());
    line("endtask".into());
    line(String::new());
    line("// The instance's connections of these ports, each to its namesake.".into());
    let mut connections = String::new();
    let all: Vec<&Port> = ports.inputs.iter().chain(&ports.outputs).collect();
    for (i, p) in all.iter().enumerate() {
        let sep = if i + 1 < all.len() { ", \\" } else { "" };
        let _ = write!(connections, "\n    .{0}({0}){sep}", p.name);
    }
    line(format!("`define DUT_PORTS \\{connections}"));
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every replay testbench includes the port file this module writes for
    /// its core, and the committed file is that file.
    #[test]
    fn testbench_ports_are_current() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let write = std::env::var_os("WRITE_TESTBENCH_PORTS").is_some();
        let cores = all().unwrap();
        if write {
            for ports in &cores {
                std::fs::write(root.join(path(ports.core)), render(ports)).unwrap();
            }
        }
        let mut stale = Vec::new();
        for ports in &cores {
            let committed = std::fs::read_to_string(root.join(path(ports.core)));
            if committed.unwrap_or_default() != render(ports) {
                stale.push(path(ports.core));
            }
            let tb = root.join(format!("hdl/tb/{0}/tb_{0}.v", ports.core));
            let text = std::fs::read_to_string(&tb).unwrap();
            assert!(
                text.contains(&format!("`include \"tb_{}_ports.vh\"", ports.core))
                    && text.contains("`DUT_PORTS"),
                "{}: include tb_{}_ports.vh and connect the instance with `DUT_PORTS",
                tb.display(),
                ports.core
            );
        }
        assert!(
            stale.is_empty(),
            "{stale:?} differ from the model's port lists: run \
             `WRITE_TESTBENCH_PORTS=1 cargo test --release -p tbgen testbench_ports` and commit them"
        );
    }

    /// A parameter-sized port is declared, driven and summed by its
    /// parameter, and an idle-high input starts at 1.
    #[test]
    fn widths_by_parameter_and_idle_levels_are_written() {
        let ports = CorePorts {
            core: "x_core",
            inputs: vec![Port::new("i_a", 1), Port::new("i_line", 1).idle_high()],
            outputs: vec![
                Port::new("o_word", 12).width_from("BITS"),
                Port::new("o_byte", 8),
                Port::new("o_flag", 1),
            ],
        };
        let v = render(&ports);
        for want in [
            "localparam OUT_BITS = 9 + BITS;",
            "reg i_line = 1;",
            "reg i_a = 0;",
            "wire [BITS-1:0] o_word;",
            "wire [7:0] o_byte;",
            "i_line = `IN_WORD(1) & 1'h1;",
            "`CHECK(1, \"o_byte\", o_byte)",
            "    .o_flag(o_flag)\n",
        ] {
            assert!(v.contains(want), "missing {want:?} in\n{v}");
        }
    }
}
