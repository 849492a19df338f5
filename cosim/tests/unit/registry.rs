//! The emulator registry against the descriptors: every protocol with an
//! emulator has its line, every kind `open` names opens, and each emulator
//! calls itself what its descriptor calls it.

use cosim::registry::KINDS;
use cosim::{open, Error};
use model::protocol::{closed_loops, PROTOCOLS};

/// The first configuration of each closed loop, by its protocol's stem.
fn config_of(stem: &str) -> (String, String) {
    let (_, l) = closed_loops()
        .find(|(p, _)| p.stem == stem)
        .unwrap_or_else(|| panic!("{stem}: no closed loop to take a configuration from"));
    let dir = format!(
        "{}/../hdl/tb_cosim/{}/configs",
        env!("CARGO_MANIFEST_DIR"),
        l.name
    );
    let path = format!("{dir}/{}.toml", l.quick);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    (path, text)
}

#[test]
fn every_protocol_with_an_emulator_has_one_registry_line_in_listing_order() {
    let with: Vec<&str> = PROTOCOLS
        .iter()
        .filter(|p| p.emulator.is_some())
        .map(|p| p.stem)
        .collect();
    let registered: Vec<&str> = KINDS.iter().map(|k| k.protocol.stem).collect();
    assert_eq!(registered, with);
}

#[test]
fn each_emulator_and_monitor_opens_under_its_kind_and_aliases_and_says_its_kind() {
    for k in KINDS {
        let e = k.protocol.emulator.as_ref().unwrap();
        let (origin, text) = config_of(k.protocol.stem);
        for name in std::iter::once(e.kind).chain(e.aliases.iter().copied()) {
            let emu = open(name, &text, &origin, 50_000_000)
                .unwrap_or_else(|err| panic!("{name}: {err}"));
            assert_eq!(emu.kind(), e.kind, "{name}");
            let monitor = format!("{name}_monitor");
            let mon = open(&monitor, &text, &origin, 50_000_000)
                .unwrap_or_else(|err| panic!("{monitor}: {err}"));
            assert_eq!(
                Some(mon.kind().to_string()),
                k.protocol.monitor_kind(),
                "{monitor}"
            );
        }
    }
}

#[test]
fn an_unknown_kind_lists_kinds_that_each_open() {
    let Err(Error::Usage(message)) = open("nope", "", "t.toml", 50_000_000) else {
        panic!("`nope` opened");
    };
    // "no emulator `nope`; give one of: ssi, ..., sar58k24 (alias sar), ..., or a monitor: ssi_monitor, ..."
    let (emulators, monitors) = message
        .split_once("give one of: ")
        .and_then(|(_, rest)| rest.split_once(", or a monitor: "))
        .unwrap_or_else(|| panic!("{message}"));
    let mut listed: Vec<String> = Vec::new();
    for item in emulators.split(", ") {
        match item.split_once(" (alias ") {
            Some((kind, aliases)) => {
                listed.push(kind.into());
                listed.extend(aliases.trim_end_matches(')').split(", ").map(String::from));
            }
            None => listed.push(item.into()),
        }
    }
    listed.extend(monitors.split(", ").map(String::from));
    assert!(listed.len() >= 2 * KINDS.len(), "{message}");
    for name in &listed {
        let stem = KINDS
            .iter()
            .find(|k| {
                let e = k.protocol.emulator.as_ref().unwrap();
                let base = name.trim_end_matches("_monitor");
                e.kind == base || e.aliases.contains(&base)
            })
            .unwrap_or_else(|| panic!("`{name}` listed, no descriptor names it"))
            .protocol
            .stem;
        let (origin, text) = config_of(stem);
        open(name, &text, &origin, 50_000_000).unwrap_or_else(|err| panic!("{name}: {err}"));
    }
}
