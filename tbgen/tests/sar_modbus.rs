//! SAR58K24 and Modbus scenarios end to end, ahead of the protocol
//! registry: every file under `scenarios/sar/` and `scenarios/modbus/` is
//! run through the model, its vectors replayed against the core in Icarus
//! and in Verilator, and its line read back with sigrok-cli's `uart`
//! decoder (and, for Modbus, its `modbus` decoder stacked on it), which must
//! find the bytes and the Modbus fields of the transcript.

#[allow(dead_code)]
#[path = "../examples/sar_modbus_vectors.rs"]
mod writer;

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

fn scenarios(proto: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join("scenarios").join(proto)).unwrap().map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|e| e == "toml")).collect();
    v.sort();
    v
}

/// Generates `file` into `dir`; returns (name, transcript, baud, parity, f_sys).
fn generate(file: &Path, dir: &Path) -> (String, serde_json::Value, toml::Value) {
    let text = std::fs::read_to_string(file).unwrap();
    let doc: toml::Value = toml::from_str(&text).unwrap();
    let name = doc["name"].as_str().unwrap().to_string();
    writer::generate_file(file.to_str().unwrap(), dir).unwrap();
    let transcript: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(dir.join(format!("{name}.json"))).unwrap()).unwrap();
    (name, transcript, doc)
}

fn replay(core: &str, hex: &Path) {
    for sim in ["icarus", "verilator"] {
        let out = Command::new(root().join("scripts/sim.sh")).args([core, sim, hex.to_str().unwrap()]).output().expect("scripts/sim.sh runs");
        assert!(out.status.success(), "{core} {sim} {}: {}{}", hex.display(), String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    }
}

/// sigrok-cli on the scalars of `vcd`, one sample per system clock.
fn sigrok(vcd: &Path, f_sys_hz: u64, decoders: &str, annotations: &str) -> Vec<String> {
    let scalars = vcd.with_extension("scalars.vcd");
    std::fs::write(&scalars, tbgen::wave::scalars_only(&std::fs::read_to_string(vcd).unwrap())).unwrap();
    let out = Command::new("sigrok-cli")
        .args(["-I", &format!("vcd:downsample={}", 1_000_000_000_000 / f_sys_hz), "-i", scalars.to_str().unwrap()])
        .args(["-P", decoders, "-A", annotations])
        .output()
        .expect("sigrok-cli runs (make deps installs it)");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap().lines().map(str::to_string).collect()
}

fn uart_options(doc: &toml::Value, table: &str) -> (u64, String, u64) {
    let t = &doc[table];
    let baud = t.get("baud").and_then(|b| b.as_float()).unwrap_or(if table == "sar" { 115_200.0 } else { 19_200.0 }) as u64;
    let parity = t.get("parity").and_then(|p| p.as_str()).unwrap_or("none").to_string();
    let f_sys = (t.get("f_sys_mhz").and_then(|f| f.as_float()).unwrap_or(10.0) * 1e6) as u64;
    (baud, parity, f_sys)
}

/// The transcript's wire bytes at the host, in order.
fn wire_bytes(transcript: &serde_json::Value) -> Vec<u64> {
    let mut v = Vec::new();
    for t in transcript.as_array().unwrap() {
        for (rq, an) in t["wire_requests"].as_array().unwrap().iter().zip(t["wire_answers"].as_array().unwrap()) {
            v.extend(rq.as_array().unwrap().iter().map(|b| b.as_u64().unwrap()));
            v.extend(an.as_array().unwrap().iter().map(|b| b.as_u64().unwrap()));
        }
    }
    v
}

fn uart_bytes(lines: &[String]) -> Vec<u64> {
    lines.iter().filter_map(|l| l.strip_prefix("uart-1: ")).filter_map(|h| u64::from_str_radix(h.trim(), 16).ok()).collect()
}

#[test]
fn every_sar_scenario_matches_in_both_simulators_and_sigrok_reads_its_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let files = scenarios("sar");
    assert!(files.len() >= 4);
    for file in files {
        let (name, transcript, doc) = generate(&file, dir.path());
        replay("sar_async_host", &dir.path().join(format!("{name}.hex")));
        let (baud, parity, f_sys) = uart_options(&doc, "sar");
        let lines = sigrok(&dir.path().join(format!("{name}.vcd")), f_sys, &format!("uart:rx=line_at_host:baudrate={baud}:parity={parity}"), "uart=rx-data");
        assert_eq!(uart_bytes(&lines), wire_bytes(&transcript), "{name}: sigrok uart vs the transcript's wire bytes");
    }
}

#[test]
fn every_modbus_scenario_matches_in_both_simulators_and_sigrok_reads_its_bytes_and_fields() {
    let dir = tempfile::tempdir().unwrap();
    let files = scenarios("modbus");
    assert!(files.len() >= 2);
    for file in files {
        let (name, transcript, doc) = generate(&file, dir.path());
        replay("modbus_master", &dir.path().join(format!("{name}.hex")));
        let (baud, parity, f_sys) = uart_options(&doc, "modbus");
        let vcd = dir.path().join(format!("{name}.vcd"));
        let lines = sigrok(&vcd, f_sys, &format!("uart:rx=line_at_master:baudrate={baud}:parity={parity}"), "uart=rx-data");
        assert_eq!(uart_bytes(&lines), wire_bytes(&transcript), "{name}: sigrok uart vs the transcript's wire bytes");
        // The modbus decoder on the two directions apart: every good read's
        // request and answer, field by field, with its CRC verdict.
        let fields = sigrok(&vcd, f_sys, &format!("uart:rx=tx_device:tx=o_tx:baudrate={baud}:parity={parity},modbus"), "modbus");
        let text = fields.join("\n");
        for t in transcript.as_array().unwrap() {
            if t["op"] == "read" && t["errors"].as_array().unwrap().is_empty() {
                let v = t["value"].as_u64().unwrap();
                let count = t["count"].as_u64().unwrap();
                assert!(text.contains(&format!("Read {count} units of data")), "{name}: {text}");
                assert!(text.contains(&format!("Byte count: {}", 2 * count)), "{name}: {text}");
                let low = format!("0x{:04X} / {}", v & 0xFFFF, v & 0xFFFF);
                assert!(text.contains(&low), "{name}: {low} not in {text}");
            }
        }
        let crc_ok = fields.iter().filter(|l| l.contains("CRC correct")).count();
        let crc_bad = fields.iter().filter(|l| l.contains("CRC should be")).count();
        let flagged_crc = transcript.as_array().unwrap().iter().filter(|t| t["errors"].as_array().unwrap().iter().any(|e| e == "crc")).count();
        assert!(crc_bad >= flagged_crc, "{name}: sigrok sees {crc_bad} bad CRCs, the master flagged {flagged_crc}");
        assert!(crc_ok > 0, "{name}");
        // Every exception answer the master decoded, with its code.
        for t in transcript.as_array().unwrap() {
            if let Some(code) = t["exception"].as_u64() {
                assert!(text.contains(&format!("Error {code}: ")), "{name}: exception {code} not in {text}");
            }
        }
    }
}
