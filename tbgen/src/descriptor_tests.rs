//! The protocol descriptors (`model::protocol`) against the tree: each
//! name they give is a file or folder that exists, each protocol's names
//! follow its stem (or are declared historical, with the reason), and every
//! per-protocol folder of the tree belongs to a descriptor, so that no list
//! elsewhere can know of a protocol the descriptors do not.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use model::protocol::{closed_loops, PROTOCOLS};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn exists(path: &str) -> Result<(), String> {
    match root().join(path).exists() {
        true => Ok(()),
        false => Err(format!("{path}: no such file or folder")),
    }
}

/// The names in `dir` (relative to the root) that end in `suffix`, without it.
fn listed(dir: &str, suffix: &str) -> BTreeSet<String> {
    std::fs::read_dir(root().join(dir))
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .filter_map(|e| {
            let name = e.expect("a directory entry").file_name();
            name.to_str()?.strip_suffix(suffix).map(String::from)
        })
        .collect()
}

/// The problems of every descriptor's names against the files.
fn missing_files() -> Vec<String> {
    let mut problems = Vec::new();
    for p in PROTOCOLS {
        let mut paths = vec![
            format!("model/src/{}/mod.rs", p.module),
            format!("tbgen/src/{}/mod.rs", p.stem),
            format!("scenarios/{}", p.stem),
            format!("scenarios/bench/{}_bench.toml", p.stem),
            format!("hdl/rtl/{}.v", p.core),
            format!("vectors/{}", p.core),
        ];
        if let Some(e) = &p.emulator {
            paths.push(format!("hdl/emu/{}.v", e.module));
            paths.push(format!("hdl/emu/{}.v", e.monitor_module));
        }
        for l in p.closed_loops {
            paths.push(format!("hdl/tb_cosim/{0}/tb_cosim_{0}.v", l.name));
            paths.push(format!("hdl/tb_cosim/{}/configs/{}.toml", l.name, l.quick));
            paths.push(format!("hdl/rtl/{}.v", l.top));
            if let Some(c) = l.cocotb {
                paths.push(format!("hdl/cocotb/test_{c}.py"));
                paths.push(format!("hdl/cocotb/configs/{c}.toml"));
            }
        }
        if let Some(d) = &p.diagram {
            paths.push(format!("vectors/{}/{}.vcd", p.core, d.scenario));
        }
        problems.extend(
            paths
                .iter()
                .filter_map(|f| exists(f).err())
                .map(|e| format!("{}: {e}", p.stem)),
        );
    }
    problems
}

#[test]
fn every_name_in_a_descriptor_is_a_file_of_the_tree() {
    let problems = missing_files();
    assert!(problems.is_empty(), "{problems:#?}");
}

#[test]
fn each_verilog_wrapper_opens_the_kind_its_descriptor_names() {
    // The wrapper hands libcosim its kind (`localparam EMU_KIND = "ssi";`):
    // read from the Verilog, not from the descriptor.
    for p in PROTOCOLS {
        let Some(e) = &p.emulator else { continue };
        let monitor = p.monitor_kind().unwrap();
        for (module, kind) in [(e.module, e.kind), (e.monitor_module, monitor.as_str())] {
            let text = std::fs::read_to_string(root().join(format!("hdl/emu/{module}.v"))).unwrap();
            let decl = format!("localparam EMU_KIND = \"{kind}\";");
            assert!(text.contains(&decl), "hdl/emu/{module}.v: no `{decl}`");
        }
    }
}

/// The names of protocol `p` that neither are its stem nor begin with
/// `<stem>_` and are not declared historical; and the historical ones it
/// does not use.
fn off_stem(p: &model::protocol::Protocol) -> (Vec<&'static str>, Vec<&'static str>) {
    let names = p.names();
    let historical: Vec<&str> = p.historical.iter().map(|h| h.name).collect();
    let follows = |n: &str| n == p.stem || n.starts_with(&format!("{}_", p.stem));
    let stray = names
        .iter()
        .copied()
        .filter(|n| !follows(n) && !historical.contains(n))
        .collect();
    let stale = historical
        .iter()
        .copied()
        .filter(|h| !names.contains(h) || follows(h))
        .collect();
    (stray, stale)
}

#[test]
fn each_protocol_has_one_name_stem_and_says_why_of_every_other_name() {
    let mut stems = BTreeSet::new();
    for p in PROTOCOLS {
        assert!(
            stems.insert(p.stem),
            "{}: two protocols with one stem",
            p.stem
        );
        let (stray, stale) = off_stem(p);
        assert!(
            stray.is_empty(),
            "{}: {stray:?} neither are the stem nor begin with `{}_`: rename them, or say in the descriptor's `historical` why they stay",
            p.stem,
            p.stem
        );
        assert!(
            stale.is_empty(),
            "{}: historical names it no longer has: {stale:?}",
            p.stem
        );
        for h in p.historical {
            assert!(!h.why.is_empty(), "{}: {} without a reason", p.stem, h.name);
        }
    }
}

#[test]
fn the_stem_check_refuses_an_undeclared_name_and_a_stale_declaration() {
    use model::protocol::{Historical, Protocol};
    let undeclared = Protocol {
        historical: &[],
        ..model::sar58k24::descriptor::PROTOCOL
    };
    assert!(off_stem(&undeclared).0.contains(&"sar58k24"));
    let stale = Protocol {
        historical: &[Historical {
            name: "sar_old",
            why: "gone",
        }],
        ..model::sar58k24::descriptor::PROTOCOL
    };
    assert!(off_stem(&stale).1.contains(&"sar_old"));
}

#[test]
fn every_per_protocol_folder_and_file_of_the_tree_has_its_descriptor() {
    let set = |names: Vec<&str>| names.into_iter().map(String::from).collect::<BTreeSet<_>>();
    let stems = set(PROTOCOLS.iter().map(|p| p.stem).collect());
    let mut scenario_folders = listed("scenarios", "");
    scenario_folders.remove("bench");
    assert_eq!(scenario_folders, stems, "scenarios/");
    assert_eq!(
        listed("scenarios/bench", "_bench.toml"),
        stems,
        "scenarios/bench/"
    );
    let cores = set(PROTOCOLS.iter().map(|p| p.core).collect());
    assert_eq!(listed("vectors", ""), cores, "vectors/");
    let loops: BTreeSet<String> = listed("hdl/tb_cosim", "")
        .into_iter()
        .filter(|d| {
            root()
                .join(format!("hdl/tb_cosim/{d}/tb_cosim_{d}.v"))
                .exists()
        })
        .collect();
    assert_eq!(
        loops,
        set(closed_loops().map(|(_, l)| l.name).collect()),
        "hdl/tb_cosim/"
    );
    assert_eq!(
        listed("hdl/cocotb", ".py")
            .into_iter()
            .filter_map(|t| t.strip_prefix("test_").map(String::from))
            .collect::<BTreeSet<_>>(),
        set(closed_loops().filter_map(|(_, l)| l.cocotb).collect()),
        "hdl/cocotb/test_*.py"
    );
    let wrappers = set(PROTOCOLS
        .iter()
        .filter_map(|p| p.emulator.as_ref())
        .flat_map(|e| [e.module, e.monitor_module])
        .collect());
    let emu_files: BTreeSet<String> = listed("hdl/emu", ".v");
    assert_eq!(emu_files, wrappers, "hdl/emu/*.v");
}
