//! Every Verilog emulator and monitor has a VHDL twin, and the VHDL
//! emulators and monitors (`hdl/emu/vhdl/<name>.vhd`) have the
//! generics and ports of their Verilog twins (`hdl/emu/<name>.v`): the same
//! names in the same order, the same defaults and directions. The Verilog
//! module is the truth; this reads both headers as text (no simulator) and
//! names the first difference.

use std::fs;
use std::path::{Path, PathBuf};

/// A module's or entity's header: its generics as (name, default) and its
/// ports as (name, direction), in order.
struct Header {
    generics: Vec<(String, String)>,
    ports: Vec<(String, String)>,
}

fn hdl_emu() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../hdl/emu")
}

/// The header of a Verilog module: `parameter NAME = V` and `input|output wire name` lines.
fn verilog_header(text: &str) -> Header {
    let mut generics = Vec::new();
    let mut ports = Vec::new();
    let header = text
        .split_once("\nmodule ")
        .and_then(|(_, rest)| rest.split_once("\n);"))
        .map_or("", |(head, _)| head);
    for line in header.lines().map(|l| l.trim().trim_end_matches(',')) {
        if let Some(p) = line.strip_prefix("parameter ") {
            if let Some((name, value)) = p.split_once('=') {
                generics.push((name.trim().to_string(), value.trim().to_string()));
            }
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        if let [dir @ ("input" | "output"), "wire", name] = words[..] {
            ports.push((name.to_string(), dir[..dir.len() - 3].to_string()));
        }
    }
    Header { generics, ports }
}

/// The same of a VHDL entity: `NAME : type := V;` in its generic list and
/// `name : in|out std_logic` in its port list.
fn vhdl_header(text: &str) -> Header {
    let mut generics = Vec::new();
    let mut ports = Vec::new();
    let entity = text
        .split_once("\nentity ")
        .and_then(|(_, rest)| rest.split_once("\nend entity;"))
        .map_or("", |(head, _)| head);
    let (gen_part, port_part) = entity.split_once("port (").unwrap_or((entity, ""));
    for line in gen_part.lines().map(|l| l.trim().trim_end_matches(';')) {
        if let Some((name, rest)) = line.split_once(" : ") {
            if let Some((_, value)) = rest.split_once(":=") {
                generics.push((name.trim().to_string(), value.trim().to_string()));
            }
        }
    }
    for line in port_part.lines().map(|l| l.trim()) {
        if let Some((name, rest)) = line.split_once(" : ") {
            if let Some(dir) = rest.split_whitespace().next() {
                ports.push((name.trim().to_string(), dir.to_string()));
            }
        }
    }
    Header { generics, ports }
}

#[test]
fn each_vhdl_wrapper_has_the_generics_and_ports_of_its_verilog_module() {
    let mut compared = Vec::new();
    for entry in fs::read_dir(hdl_emu().join("vhdl")).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        let verilog = hdl_emu().join(format!("{name}.v"));
        if path.extension().is_none_or(|e| e != "vhd") || !verilog.exists() {
            continue; // the packages
        }
        let v = verilog_header(&fs::read_to_string(&verilog).unwrap());
        let h = vhdl_header(&fs::read_to_string(&path).unwrap());
        assert!(
            !v.generics.is_empty() && !v.ports.is_empty(),
            "{name}.v: no header read"
        );
        assert_eq!(
            h.generics, v.generics,
            "{name}.vhd's generics (left) differ from {name}.v's parameters (right)"
        );
        assert_eq!(
            h.ports, v.ports,
            "{name}.vhd's ports (left) differ from {name}.v's (right)"
        );
        compared.push(name);
    }
    // Every Verilog emulator and monitor has its VHDL twin.
    for entry in fs::read_dir(hdl_emu()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        if path.extension().is_some_and(|e| e == "v") {
            assert!(
                compared.contains(&name),
                "hdl/emu/{name}.v has no VHDL twin hdl/emu/vhdl/{name}.vhd"
            );
        }
    }
}

/// The readers above, on a header written here: a parameter or port that
/// one side lacks is seen (the test must not pass on two empty lists).
#[test]
fn the_header_readers_see_a_missing_generic_and_a_port_direction() {
    let v = verilog_header("x\nmodule m #(\n    parameter A = 1,\n    parameter B = \"s\"\n) (\n    input  wire i_a,\n    output wire o_b\n);\n");
    assert_eq!(
        v.generics,
        [("A".into(), "1".into()), ("B".into(), "\"s\"".into())]
    );
    assert_eq!(
        v.ports,
        [("i_a".into(), "in".into()), ("o_b".into(), "out".into())]
    );
    let h = vhdl_header("x\nentity m is\n    generic (\n        A : integer := 1\n    );\n    port (\n        i_a : in std_logic;\n        o_b : in std_logic\n    );\nend entity;\n");
    assert_eq!(h.generics, [("A".into(), "1".into())]);
    assert_ne!(h.ports, v.ports);
}
