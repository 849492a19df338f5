//! How the probe testbench connects a protocol's emulator and monitor
//! wrappers, read from the wrappers themselves (`hdl/emu/<module>.v`), so
//! that no port list is written a second time: the line of each emulator
//! wrapper that hands its input ports to the library
//! (`wire emu_line_in = i_ma;`, `wire emu_clk_in/emu_data_in/emu_oe_in = ...;`
//! or `wire [3:0] emu_pins_in = {...};`, the library's input layout), the
//! lines that drive its outputs (`assign o_slo = emu_line_out;`), and the
//! monitor's `localparam MON_PIN_NAMES = "...";` (its pin order).
//!
//! From them [`Wiring::include`] writes the Verilog instantiation the
//! testbench `hdl/tb_probe/tb_probe.v` includes, and [`Wiring::pins_module`]
//! the cocotb top level whose ports carry the master's pins under the
//! emulator's port names.

use std::fmt::Write as _;
use std::path::Path;

use cosim::probe::Src;

use crate::{Error, Result};

/// A protocol's two wrappers as the probe testbench wires them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Wiring {
    /// The emulator wrapper's module.
    pub emulator: String,
    /// The monitor wrapper's module.
    pub monitor: String,
    /// The emulator's input ports: `(bit of the library's input layout, port)`.
    pub inputs: Vec<(u32, String)>,
    /// The emulator's output ports: `(bit of its answer, port)` (bit 0 its
    /// data at the master's end, bit 1 its driver enable, bit 2 the resolved
    /// line).
    pub outputs: Vec<(u32, String)>,
    /// The monitor's ports, pin 0 first.
    pub monitor_pins: Vec<String>,
}

/// The text of a Verilog file without its comments (`//` and `/* */`).
fn code(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find("/*") {
        out.push_str(&rest[..i]);
        rest = rest[i..].split_once("*/").map_or("", |(_, r)| r);
    }
    out.push_str(rest);
    out.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The statements of `code` (split at `;`), each without the preprocessor
/// lines (`` `include ``) before it.
fn statements(code: &str) -> impl Iterator<Item = &str> {
    code.split(';').map(|stmt| {
        let mut s = stmt.trim_start();
        while s.starts_with('`') {
            s = s.split_once('\n').map_or("", |(_, r)| r).trim_start();
        }
        s.trim_end()
    })
}

/// The right-hand side of `wire [...] <name> = <rhs>;` in `code`.
fn wire_value<'a>(code: &'a str, name: &str) -> Option<&'a str> {
    statements(code).find_map(|s| {
        let rest = s.strip_prefix("wire")?.trim_start();
        let rest = if rest.starts_with('[') {
            rest.split_once(']')?.1.trim_start()
        } else {
            rest
        };
        let (lhs, rhs) = rest.split_once('=')?;
        (lhs.trim() == name).then(|| rhs.trim())
    })
}

/// The string of `localparam <name> = "<value>";` in `code`.
fn localparam_string<'a>(code: &'a str, name: &str) -> Option<&'a str> {
    statements(code).find_map(|s| {
        let rest = s.strip_prefix("localparam")?.trim_start();
        let (lhs, rhs) = rest.split_once('=')?;
        (lhs.trim() == name).then(|| rhs.trim().strip_prefix('"')?.strip_suffix('"'))?
    })
}

/// The items of a concatenation `{a, b, c}`, last (bit 0) first.
fn concat_lsb_first(rhs: &str) -> Option<Vec<String>> {
    let inner = rhs.trim().strip_prefix('{')?.strip_suffix('}')?;
    Some(
        inner
            .split(',')
            .rev()
            .map(|s| s.trim().to_string())
            .collect(),
    )
}

/// The input (or output) ports a module declares.
fn ports(code: &str, dir: &str) -> Vec<String> {
    code.split([',', '(', ')', ';', '\n'])
        .filter_map(|d| {
            let mut w = d.split_whitespace();
            (w.next()? == dir).then_some(())?;
            w.rfind(|t| *t != "wire" && *t != "reg").map(str::to_string)
        })
        .collect()
}

/// Reads `<hdl>/<emulator>.v` and `<hdl>/<monitor>.v`.
pub fn read(hdl: &Path, emulator: &str, monitor: &str) -> Result<Wiring> {
    let load = |m: &str| {
        let path = hdl.join(format!("{m}.v"));
        std::fs::read_to_string(&path)
            .map(|t| (code(&t), path.display().to_string()))
            .map_err(|e| {
                Error::Probes(format!(
                    "{}: {e}: run from the repository's root, or give --hdl the folder of the wrappers (hdl/emu)",
                    path.display()
                ))
            })
    };
    let (emu, emu_file) = load(emulator)?;
    let (mon, mon_file) = load(monitor)?;
    let emu_in = ports(&emu, "input");
    let emu_out = ports(&emu, "output");
    let mon_in = ports(&mon, "input");
    let port_or_constant = |item: &str, file: &str, known: &[String]| -> Result<Option<String>> {
        if known.iter().any(|p| p == item) {
            Ok(Some(item.to_string()))
        } else if item.contains('\'') {
            Ok(None)
        } else {
            Err(Error::Probes(format!(
                "{file}: `{item}` in its pin list is neither an input port of the module nor a constant: \
                 the probe testbench wires only ports"
            )))
        }
    };
    // The library's input layout, in the three forms of hdl/emu's bodies.
    let mut layout: Vec<(u32, &str)> = Vec::new();
    if let Some(v) = wire_value(&emu, "emu_line_in") {
        layout.push((0, v));
    }
    for (bit, name) in [(0, "emu_clk_in"), (1, "emu_data_in"), (2, "emu_oe_in")] {
        if let Some(v) = wire_value(&emu, name) {
            layout.push((bit, v));
        }
    }
    let concat;
    if let Some(v) = wire_value(&emu, "emu_pins_in") {
        concat = concat_lsb_first(v).ok_or_else(|| {
            Error::Probes(format!(
                "{emu_file}: `emu_pins_in = {v}` is not a concatenation {{...}}"
            ))
        })?;
        layout.extend(
            concat
                .iter()
                .enumerate()
                .map(|(i, s)| (i as u32, s.as_str())),
        );
    }
    if layout.is_empty() {
        return Err(Error::Probes(format!(
            "{emu_file}: no `wire emu_line_in`, `emu_clk_in`/`emu_data_in`/`emu_oe_in` or `emu_pins_in` line: \
             the probe testbench reads the emulator's input layout from it (hdl/emu/emu_*.vh say how a wrapper declares it)"
        )));
    }
    let mut inputs = Vec::new();
    for (bit, item) in layout {
        if let Some(p) = port_or_constant(item, &emu_file, &emu_in)? {
            inputs.push((bit, p));
        }
    }
    let mut outputs = Vec::new();
    for stmt in statements(&emu) {
        let Some((lhs, rhs)) = stmt.strip_prefix("assign").and_then(|s| s.split_once('=')) else {
            continue;
        };
        let (port, rhs) = (lhs.trim(), rhs.trim().replace(' ', ""));
        let bit = match rhs.as_str() {
            "emu_line_out" | "emu_data_out" => 0,
            "emu_oe_out" => 1,
            r => match r.strip_prefix("emu_out[").and_then(|r| r.strip_suffix(']')) {
                Some(k) => k.parse().map_err(|_| {
                    Error::Probes(format!(
                        "{emu_file}: `assign {port} = {r}`: a bit of emu_out is a number"
                    ))
                })?,
                None => continue,
            },
        };
        if !emu_out.iter().any(|p| p == port) {
            return Err(Error::Probes(format!(
                "{emu_file}: `assign {port} = {rhs}`: {port} is not an output port of the module"
            )));
        }
        outputs.push((bit, port.to_string()));
    }
    if outputs.is_empty() {
        return Err(Error::Probes(format!(
            "{emu_file}: no output port assigned from emu_line_out, emu_data_out, emu_oe_out or emu_out[k]: \
             the probe testbench reads the emulator's answer from them"
        )));
    }
    // The monitor's pins in order, bit 0 first, as the wrapper declares them
    // for its own messages (`localparam MON_PIN_NAMES = "a, b, ...";`): its
    // `mon_pins_now` may read a pin through a wire (an enable whose X reads
    // as 0), the names are the ports.
    let pins: Vec<String> = localparam_string(&mon, "MON_PIN_NAMES")
        .map(|names| names.split(',').map(|n| n.trim().to_string()).collect())
        .ok_or_else(|| {
            Error::Probes(format!(
                "{mon_file}: no `localparam MON_PIN_NAMES = \"...\";` line: the probe testbench reads the \
                 monitor's pin order from it (hdl/emu/emu_monitor.vh)"
            ))
        })?;
    let mut monitor_pins = Vec::new();
    for (i, item) in pins.iter().enumerate() {
        match port_or_constant(item, &mon_file, &mon_in)? {
            Some(p) => monitor_pins.push(p),
            // The zero padding above the pins, and only there.
            None if pins[i..].iter().all(|s| s.contains('\'')) => break,
            None => {
                return Err(Error::Probes(format!(
                    "{mon_file}: `{item}` is pin {i} of MON_PIN_NAMES: the probe testbench wires only ports there"
                )))
            }
        }
    }
    Ok(Wiring {
        emulator: emulator.to_string(),
        monitor: monitor.to_string(),
        inputs,
        outputs,
        monitor_pins,
    })
}

/// One byte per source, as `hdl/tb_probe/tb_probe.v` decodes it: the kind
/// in the high nibble (0 a master pin, 1 an emulator pin, 2 the half-duplex
/// bus, 3 a wired-AND bus), the pin in the low one.
pub fn src_byte(s: Src) -> u8 {
    let (kind, n) = match s {
        Src::Master(n) => (0, n),
        Src::Emulator(n) => (1, n),
        Src::Bus => (2, 0),
        Src::WiredAnd(n) => (3, n),
    };
    (kind << 4) | (n as u8 & 0xf)
}

impl Wiring {
    /// The instantiation `hdl/tb_probe/tb_probe.v` includes: the emulator on
    /// the master's pins (`master[k]`, k its input layout's bit), its answer
    /// into `answer[k]` (bits it has no port for held 0, as the library's
    /// answer has them), the monitor on `mon_pins[i]` (pin i, which the
    /// testbench wires by the kit's table).
    pub fn include(&self, kind: &str) -> String {
        let mut s = format!(
            "// {kind}: the probe testbench's wrappers, written by `tbgen probes` from\n\
             // hdl/emu/{}.v and hdl/emu/{}.v (their pin lists); do not edit.\n\n",
            self.emulator, self.monitor
        );
        let list = |s: &mut String, clk: &str, pins: Vec<String>| {
            let _ = write!(s, "    .{clk}(clk)");
            for p in pins {
                let _ = write!(s, ",\n    {p}");
            }
            s.push_str("\n);\n");
        };
        let _ = writeln!(
            s,
            "{} #(.CONFIG(CONFIG), .F_EMU_HZ(F_HZ), .TRANSCRIPT(EMU_TRANSCRIPT), .STOP_ON_X(1)) u_emu (",
            self.emulator
        );
        let mut pins: Vec<String> = self
            .inputs
            .iter()
            .map(|(b, p)| format!(".{p}(master[{b}])"))
            .collect();
        pins.extend(
            self.outputs
                .iter()
                .map(|(b, p)| format!(".{p}(answer[{b}])")),
        );
        list(&mut s, "i_emu_clk", pins);
        for b in 0..4 {
            if !self.outputs.iter().any(|(o, _)| *o == b) {
                let _ = writeln!(s, "assign answer[{b}] = 1'b0;");
            }
        }
        let _ = writeln!(
            s,
            "\n{} #(.CONFIG(CONFIG), .F_MON_HZ(F_HZ), .TRANSCRIPT(MON_TRANSCRIPT), .STOP_ON_X(1)) u_mon (",
            self.monitor
        );
        let pins = self
            .monitor_pins
            .iter()
            .enumerate()
            .map(|(i, p)| format!(".{p}(mon_pins[{i}])"))
            .collect();
        list(&mut s, "i_mon_clk", pins);
        s
    }

    /// The same wiring as a VHDL entity `probe_wiring`, which
    /// `hdl/tb_probe/tb_probe.vhd` instantiates: the VHDL twins of the two
    /// wrappers (`hdl/emu/vhdl/`, the same ports) on `master`, `answer` and
    /// `mon_pins`.
    pub fn vhdl(&self, kind: &str) -> String {
        let mut s = format!(
            "-- {kind}: the VHDL probe testbench's wrappers, written by `tbgen probes` from\n\
             -- hdl/emu/{}.v and hdl/emu/{}.v (their pin lists); do not edit.\n\n\
             library ieee;\nuse ieee.std_logic_1164.all;\n\n\
             entity probe_wiring is\n    generic (F_HZ : natural);\n    port (\n        clk : in std_logic;\n        \
             master : in std_logic_vector(15 downto 0);\n        answer : out std_logic_vector(3 downto 0);\n        \
             mon_pins : in std_logic_vector(7 downto 0)\n    );\nend entity;\n\n\
             architecture probe of probe_wiring is\nbegin\n",
            self.emulator, self.monitor
        );
        let mut pins: Vec<String> = self
            .inputs
            .iter()
            .map(|(b, p)| format!("{p} => master({b})"))
            .collect();
        pins.extend(
            self.outputs
                .iter()
                .map(|(b, p)| format!("{p} => answer({b})")),
        );
        let _ = writeln!(
            s,
            "    u_emu : entity work.{}\n        generic map (CONFIG => \"../probe.toml\", F_EMU_HZ => F_HZ, \
             TRANSCRIPT => \"emulator.json\", STOP_ON_X => 1)\n        port map (i_emu_clk => clk, {});",
            self.emulator,
            pins.join(", ")
        );
        for b in 0..4 {
            if !self.outputs.iter().any(|(o, _)| *o == b) {
                let _ = writeln!(s, "    answer({b}) <= '0';");
            }
        }
        let pins: Vec<String> = self
            .monitor_pins
            .iter()
            .enumerate()
            .map(|(i, p)| format!("{p} => mon_pins({i})"))
            .collect();
        let _ = writeln!(
            s,
            "    u_mon : entity work.{}\n        generic map (CONFIG => \"../probe.toml\", F_MON_HZ => F_HZ, \
             TRANSCRIPT => \"monitor.json\", STOP_ON_X => 1)\n        port map (i_mon_clk => clk, {});\nend architecture;",
            self.monitor,
            pins.join(", ")
        );
        s
    }

    /// The cocotb top level of the kit's probes: the master's pins as
    /// ports named as the emulator's (so that `emu_common.bit` knows a
    /// driver enable by its name), nothing else.
    pub fn pins_module(&self, kind: &str) -> String {
        let ports: Vec<String> = self
            .inputs
            .iter()
            .map(|(_, p)| format!("    input wire {p}"))
            .collect();
        format!(
            "// probe_pins: the master's pins of the {kind} probes under the emulator's port names\n\
             // (hdl/emu/{}.v), for the cocotb probe run (hdl/cocotb/rule_probes.py); written by\n\
             // `tbgen probes`, do not edit.\n\n\
             `default_nettype none\n\n\
             module probe_pins (\n{}\n);\nendmodule\n\n\
             `default_nettype wire\n",
            self.emulator,
            ports.join(",\n")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hdl() -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../hdl/emu")
    }

    #[test]
    fn every_layout_of_hdl_emu_is_read() {
        let w = read(&hdl(), "biss_slave_emu", "biss_monitor").unwrap();
        assert_eq!(w.inputs, vec![(0, "i_ma".to_string())]);
        assert_eq!(w.outputs, vec![(0, "o_slo".to_string())]);
        assert_eq!(w.monitor_pins, vec!["i_ma", "i_slo"]);
        let w = read(&hdl(), "endat_encoder_emu", "endat_monitor").unwrap();
        let names = |v: &[(u32, String)]| {
            v.iter()
                .map(|(b, p)| format!("{b}:{p}"))
                .collect::<Vec<_>>()
        };
        assert_eq!(
            names(&w.inputs),
            ["0:i_endat_clk", "1:i_endat_data", "2:i_endat_data_oe"]
        );
        assert_eq!(names(&w.outputs), ["0:o_endat_data", "1:o_endat_data_oe"]);
        assert_eq!(
            w.monitor_pins,
            [
                "i_endat_clk",
                "i_endat_data",
                "i_endat_data_oe",
                "i_endat_data_in"
            ]
        );
        // Constants in the layout are not ports: T-format has no clock.
        let w = read(&hdl(), "tformat_encoder_emu", "tformat_monitor").unwrap();
        assert_eq!(names(&w.inputs), ["1:i_tf_data", "2:i_tf_data_oe"]);
        let w = read(&hdl(), "sar58k24_encoder_emu", "sar58k24_monitor").unwrap();
        assert_eq!(
            names(&w.inputs),
            ["0:i_trigger", "1:i_line", "2:i_line_en", "3:i_clr"]
        );
        assert_eq!(names(&w.outputs), ["0:o_line", "1:o_line_en", "2:o_bus"]);
        let w = read(&hdl(), "can_node_emu", "can_monitor").unwrap();
        assert_eq!(names(&w.inputs), ["1:i_can_tx"]);
        assert_eq!(w.monitor_pins, ["i_can_rx", "i_can_tx"]);
    }

    #[test]
    fn a_wrapper_without_its_pin_list_is_refused_with_the_file_and_the_line_it_needs() {
        let dir = tempfile::tempdir().unwrap();
        let write = |f: &str, t: &str| std::fs::write(dir.path().join(f), t).unwrap();
        write(
            "e.v",
            "module e(input wire i_a, output wire o_b);\nendmodule\n",
        );
        write("m.v", "module m(input wire i_a);\nendmodule\n");
        let e = read(dir.path(), "e", "m").unwrap_err().to_string();
        assert!(e.contains("e.v") && e.contains("emu_line_in"), "{e}");
        write(
            "e.v",
            "module e(input wire i_a, output wire o_b);\nwire emu_line_in = i_typo;\nendmodule\n",
        );
        let e = read(dir.path(), "e", "m").unwrap_err().to_string();
        assert!(e.contains("e.v") && e.contains("`i_typo`"), "{e}");
        let e = read(dir.path(), "nope", "m").unwrap_err().to_string();
        assert!(e.contains("nope.v") && e.contains("--hdl"), "{e}");
    }
}
