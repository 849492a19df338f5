//! The pin-level monitors in the simulators: a hand-written master
//! (`hdl/tb_cosim/monitor_rules/`) breaks each timing rule of seed 001 once,
//! in Icarus and Verilator, and each monitor reports it with the seed's
//! rule and stays silent on the clean master; the transcript the simulator
//! writes at the end is a capture `tbgen check` reads, and a planted
//! difference (a flipped position bit) is found. The closed loops of our
//! cores with the monitors are in `tests/hdl.rs` (`scripts/cosim.sh`).

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
}

fn run(cmd: &mut Command) -> (bool, String) {
    let out = cmd.output().expect("the command runs (make deps installs the simulators)");
    (out.status.success(), format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr)))
}

/// Builds the rules bench in `sim`; returns a command that runs it.
fn bench(sim: &str) -> Command {
    let (ok, vars) = run(&mut Command::new(root().join("scripts/emu_lib.sh")));
    assert!(ok, "{vars}");
    let var = |name: &str| vars.lines().find_map(|l| l.strip_prefix(&format!("{name}="))).unwrap().to_string();
    let (lib, vpi, hdl) = (var("EMU_LIB_DIR"), var("EMU_VPI_DIR"), var("EMU_HDL_DIR"));
    let build = root().join(format!("build/cosim/monitor_rules/{sim}"));
    std::fs::create_dir_all(&build).unwrap();
    let tb = root().join("hdl/tb_cosim/monitor_rules/tb_monitor_rules.v");
    if sim == "icarus" {
        let vvp = build.join("tb.vvp");
        let (ok, out) = run(Command::new("iverilog").args(["-g2005", "-Wno-timescale", "-I", &hdl, "-o"]).arg(&vvp).arg(&tb));
        assert!(ok, "{out}");
        let mut cmd = Command::new("vvp");
        cmd.args(["-n", "-M", &vpi, "-m", "emu"]).arg(vvp);
        return cmd;
    }
    let (ok, out) = run(Command::new("verilator")
        .args(["--binary", "--timing", "-j", "2", "-Wno-fatal", "-Wno-lint", "-Wno-style", "--top-module", "tb_monitor_rules"])
        .arg(format!("-I{hdl}"))
        .args(["-LDFLAGS", &format!("-L{lib} -lcosim -Wl,-rpath,{lib}"), "--Mdir"])
        .arg(build.join("obj"))
        .args(["-o", "Vtb"])
        .arg(&tb));
    assert!(ok, "{out}");
    Command::new(build.join("obj/Vtb"))
}

/// `tbgen check` (the workspace's binary) on two transcripts.
fn tbgen_check(proto: &str, expect: &Path, capture: &Path) -> (bool, String) {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    run(Command::new(cargo).current_dir(root()).args(["run", "-q", "-j", "2", "-p", "tbgen", "--", "check", proto, "--expect"]).arg(expect).arg(capture))
}

fn each_rule_fires_once_and_the_clean_master_passes(sim: &str) {
    let dir = root().join(format!("build/cosim/monitor_rules/{sim}/run"));
    std::fs::create_dir_all(&dir).unwrap();
    let ssi = dir.join("ssi.toml");
    std::fs::write(&ssi, "[encoder]\nbits = 12\nmonoflop_us = 20\n").unwrap();
    let biss = dir.join("biss.toml");
    std::fs::write(&biss, "[[slaves]]\nbits = 16\n").unwrap();
    let cmd = bench(sim);
    let cases: [(u32, usize, usize, &[&str]); 7] = [
        (0, 0, 0, &[]),
        (1, 1, 0, &["T_cs (seed 001 SAR58K24 manual, SSI (2): T_cs > 4 us): first low phase 2.500 us"]),
        (2, 1, 0, &["T_m (seed 001 SAR58K24 manual, SSI (2): T_m > 500 us"]),
        (3, 1, 0, &["clock range (seed 001 SAR58K24 manual, SSI (2): 100 kHz < f_clk < 250 kHz): clock high for 1.000 us"]),
        (4, 0, 2, &["TMASH (seed 001 SAR58K24 manual, BiSS-C timing: MA high > 25 ns): MA high for 10.0 ns", "TMAS (seed 001"]),
        (5, 0, 2, &["TMASL (seed 001 SAR58K24 manual, BiSS-C timing: MA low > 25 ns): MA low for 10.0 ns", "TMAS (seed 001"]),
        (6, 0, 1, &["timeout (seed 001 SAR58K24 manual, BiSS-C timing: BiSS timeout 16 us"]),
    ];
    for (case, n_ssi, n_biss, rules) in cases {
        let (mon_s, mon_b) = (dir.join(format!("ssi_{case}.json")), dir.join(format!("biss_{case}.json")));
        let (ok, out) = run(Command::new(cmd.get_program()).args(cmd.get_args()).args([
            format!("+case={case}"),
            format!("+ssi_monitor_config={}", ssi.display()),
            format!("+biss_monitor_config={}", biss.display()),
            format!("+ssi_monitor_transcript={}", mon_s.display()),
            format!("+biss_monitor_transcript={}", mon_b.display()),
        ]));
        assert!(ok, "case {case} in {sim}:\n{out}");
        assert!(out.contains(&format!("violations ssi {n_ssi} biss {n_biss}")), "case {case} in {sim}:\n{out}");
        assert_eq!(out.matches("PROTOCOL VIOLATION by the master on").count(), n_ssi + n_biss, "case {case} in {sim}:\n{out}");
        for r in rules {
            assert!(out.contains(r), "case {case} in {sim}: no `{r}` in\n{out}");
        }
        // The transcripts the simulator wrote at the end: two reads, two frames, the violations.
        let t: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&mon_s).unwrap()).unwrap();
        assert_eq!(t["transactions"].as_array().unwrap().len(), 2, "{t}");
        assert_eq!(t["violations"].as_array().unwrap().len(), n_ssi, "{t}");
        let t: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&mon_b).unwrap()).unwrap();
        assert_eq!(t["transactions"].as_array().unwrap().len(), 2, "{t}");
        assert_eq!(t["violations"].as_array().unwrap().len(), n_biss, "{t}");
    }
    // The clean run's SSI transcript as a capture of `tbgen check`: the data
    // line stayed high, so both reads are 4095; a flipped bit is found.
    let expect = dir.join("expect.json");
    std::fs::write(&expect, r#"{"transactions": [{"position": 4095, "errors": []}, {"position": 4095, "errors": []}]}"#).unwrap();
    let (ok, out) = tbgen_check("ssi", &expect, &dir.join("ssi_0.json"));
    assert!(ok && out.contains("PASS: 2 transactions of ssi equal"), "{out}");
    std::fs::write(&expect, r#"{"transactions": [{"position": 4095, "errors": []}, {"position": 4091, "errors": []}]}"#).unwrap();
    let (ok, out) = tbgen_check("ssi", &expect, &dir.join("ssi_0.json"));
    assert!(!ok && out.contains("DIFFERENCE in transaction 1 at ") && out.contains("position expected 4091, captured 4095"), "{out}");
}

#[test]
fn each_monitor_rule_fires_in_icarus() {
    each_rule_fires_once_and_the_clean_master_passes("icarus");
}

#[test]
fn each_monitor_rule_fires_in_verilator() {
    each_rule_fires_once_and_the_clean_master_passes("verilator");
}

/// A pure closed loop (emulator and monitor stepped together), its two
/// transcripts compared by `tbgen check`: the emulator's `reads` against the
/// monitor's `transactions`; then one position bit flipped in the expected list.
#[test]
fn tbgen_check_takes_a_monitor_transcript_and_finds_a_flipped_position_bit() {
    use cosim::{open, Pins};
    let toml = "[encoder]\nbits = 16\nmonoflop_us = 20\n[cable]\nlength_m = 30\n";
    let (mut emu, mut mon) = (open("ssi", toml, "t.toml", 4_000_000).unwrap(), open("ssi_monitor", toml, "t.toml", 4_000_000).unwrap());
    let mut data = true;
    for read in 0..20u64 {
        emu.set_position(0, read * 3001 % 65536).unwrap();
        // 120 idle cycles, T_cs 18, 16 bits of 8 + 8 cycles, high after.
        let clk: Vec<bool> = (0..120 + 18 + 16 * 16 + 40).map(|c| c < 120 || c >= 138 + 16 * 16 || (c >= 138 && (c - 138) % 16 < 8)).collect();
        for l in clk {
            mon.step(Pins(l as u32 | (data as u32) << 1));
            data = emu.step(Pins::line(l)).data();
        }
    }
    let dir = root().join("build/cosim/monitor_rules/check");
    std::fs::create_dir_all(&dir).unwrap();
    let (expect, capture) = (dir.join("emulator.json"), dir.join("monitor.json"));
    std::fs::write(&capture, mon.transcript().to_string()).unwrap();
    let mut sent = emu.transcript();
    std::fs::write(&expect, sent.to_string()).unwrap();
    let (ok, out) = tbgen_check("ssi", &expect, &capture);
    assert!(ok && out.contains("PASS: 20 transactions of ssi equal"), "{out}");
    let p = &mut sent["reads"][7]["position"];
    *p = serde_json::Value::from(p.as_u64().unwrap() ^ 1);
    std::fs::write(&expect, sent.to_string()).unwrap();
    let (ok, out) = tbgen_check("ssi", &expect, &capture);
    assert!(!ok && out.contains("DIFFERENCE in transaction 7 at ") && out.contains("position expected"), "{out}");
}

/// The same for BiSS-C: the emulator's `frames` (position, error and
/// warning of each slave) against the monitor's decoded frames.
#[test]
fn tbgen_check_takes_a_biss_monitor_transcript_and_finds_a_flipped_position_bit() {
    use cosim::{open, Pins};
    let toml = "[[slaves]]\nbits = 16\n[cable]\nlength_m = 20\n";
    let (mut emu, mut mon) = (open("biss", toml, "t.toml", 80_000_000).unwrap(), open("biss_monitor", toml, "t.toml", 80_000_000).unwrap());
    let mut slo = true;
    for frame in 0..12u64 {
        emu.set_position(0, frame * 7919 % 65536).unwrap();
        emu.set_status(0, "error", frame % 3 == 0).unwrap();
        emu.set_status(0, "warning", frame % 4 == 1).unwrap();
        // 1700 idle cycles (21 us, beyond the 16 us timeout), then 40 MA periods of 4 + 4 cycles.
        let ma: Vec<bool> = (0..1700 + 320).map(|c| c < 1700 || (c - 1700) % 8 >= 4).collect();
        for l in ma {
            mon.step(Pins(l as u32 | (slo as u32) << 1));
            slo = emu.step(Pins::line(l)).data();
        }
    }
    let dir = root().join("build/cosim/monitor_rules/check_biss");
    std::fs::create_dir_all(&dir).unwrap();
    let (expect, capture) = (dir.join("emulator.json"), dir.join("monitor.json"));
    std::fs::write(&capture, mon.transcript().to_string()).unwrap();
    let mut sent = emu.transcript();
    std::fs::write(&expect, sent.to_string()).unwrap();
    let (ok, out) = tbgen_check("biss", &expect, &capture);
    assert!(ok && out.contains("PASS: 12 transactions of biss equal"), "{out}");
    let p = &mut sent["frames"][5]["slaves"][0]["position"];
    *p = serde_json::Value::from(p.as_u64().unwrap() ^ 8);
    std::fs::write(&expect, sent.to_string()).unwrap();
    let (ok, out) = tbgen_check("biss", &expect, &capture);
    assert!(!ok && out.contains("DIFFERENCE in transaction 5 at ") && out.contains("slaves[0].position expected"), "{out}");
}
