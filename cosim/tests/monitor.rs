//! The pin-level monitors in the simulators: a hand-written master
//! (`hdl/tb_cosim/monitor_rules/`) breaks each timing rule of seed 001 once,
//! in Icarus and Verilator, and each monitor reports it with the seed's
//! rule and stays silent on the clean master; the transcript the simulator
//! writes at the end is a capture `tbgen check` reads, and a planted
//! difference (a flipped position bit) is found. The closed loops of our
//! cores with the monitors are in `tests/hdl.rs` (`scripts/cosim.sh`).

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

fn run(cmd: &mut Command) -> (bool, String) {
    let out = cmd
        .output()
        .expect("the command runs (make deps installs the simulators)");
    (
        out.status.success(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ),
    )
}

/// Builds the rules bench in `sim`; returns a command that runs it.
fn bench(sim: &str) -> Command {
    bench_of(sim, "tb_monitor_rules")
}

/// Builds the rules bench `hdl/tb_cosim/monitor_rules/<top>.v` in `sim`; returns a command that runs it.
fn bench_of(sim: &str, top: &str) -> Command {
    let (ok, vars) = run(&mut Command::new(root().join("scripts/emu_lib.sh")));
    assert!(ok, "{vars}");
    let var = |name: &str| {
        vars.lines()
            .find_map(|l| l.strip_prefix(&format!("{name}=")))
            .unwrap()
            .to_string()
    };
    let (lib, vpi, hdl) = (var("EMU_LIB_DIR"), var("EMU_VPI_DIR"), var("EMU_HDL_DIR"));
    let build = root()
        .join(format!("build/cosim/monitor_rules/{sim}"))
        .join(if top == "tb_monitor_rules" { "" } else { top });
    std::fs::create_dir_all(&build).unwrap();
    let tb = root().join(format!("hdl/tb_cosim/monitor_rules/{top}.v"));
    if sim == "icarus" {
        let vvp = build.join("tb.vvp");
        let (ok, out) = run(Command::new("iverilog")
            .args(["-g2005", "-Wno-timescale", "-I", &hdl, "-o"])
            .arg(&vvp)
            .arg(&tb));
        assert!(ok, "{out}");
        let mut cmd = Command::new("vvp");
        // The release library emu_lib.sh built, not a debug one cargo test's LD_LIBRARY_PATH would find first.
        cmd.args(["-n", "-M", &vpi, "-m", "emu"])
            .arg(vvp)
            .env("LD_LIBRARY_PATH", &lib);
        return cmd;
    }
    let (ok, out) = run(common::verilator(&root())
        .args([
            "--binary",
            "--timing",
            "-j",
            "2",
            "-Wno-fatal",
            "-Wno-lint",
            "-Wno-style",
            "--top-module",
            top,
        ])
        .args(common::verilator_make_flags(&root()))
        .arg(format!(
            "-I{}",
            common::in_repo(&root(), Path::new(&hdl)).display()
        ))
        .args([
            "-LDFLAGS",
            &format!("-L{lib} -lcosim -Wl,-rpath,{lib}"),
            "--Mdir",
        ])
        .arg(build.join("obj"))
        .args(["-o", "Vtb"])
        .arg(common::in_repo(&root(), &tb)));
    assert!(ok, "{out}");
    let mut cmd = Command::new(build.join("obj/Vtb"));
    cmd.env("LD_LIBRARY_PATH", &lib);
    cmd
}

/// `tbgen check` (the workspace's binary) on two transcripts, built in this
/// test's own profile: `make test` has built it already (a release
/// `cargo run` only checks it is up to date), where the default profile
/// compiled tbgen and its dependencies a second time, for debug.
fn tbgen_check(proto: &str, expect: &Path, capture: &Path) -> (bool, String) {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    // This test runs as target/<profile>/deps/monitor-<hash>.
    let exe = std::env::current_exe().expect("the test knows its path");
    let profile = exe
        .parent()
        .and_then(Path::parent)
        .and_then(Path::file_name)
        .and_then(|p| p.to_str())
        .unwrap_or("debug")
        .to_string();
    let profile = if profile == "debug" {
        "dev".to_string()
    } else {
        profile
    };
    run(Command::new(cargo)
        .current_dir(root())
        .args([
            "run",
            "-q",
            "-j",
            "2",
            "--locked",
            "--profile",
            &profile,
            "-p",
            "tbgen",
            "--",
            "check",
            proto,
            "--expect",
        ])
        .arg(expect)
        .arg(capture))
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
        (1, 1, 0, &["T_cs (seed 001 SAR58K24 manual, SSI (2): first low phase >= 4 us): first low phase 2.500 us"]),
        (2, 1, 0, &["T_m (seed 001 SAR58K24 manual, SSI (2): clock high before a new read >= 500 us): read started 10.000 us"]),
        (3, 1, 0, &["f_clk (seed 001 SAR58K24 manual, SSI (2): clock 100 to 250 kHz): clock period 3.000 us"]),
        (4, 0, 2, &["TMASH (seed 001 SAR58K24 manual, BiSS-C timing: MA high > 25 ns): MA high for 10.0 ns", "TMAS (seed 001"]),
        (5, 0, 2, &["TMASL (seed 001 SAR58K24 manual, BiSS-C timing: MA low > 25 ns): MA low for 10.0 ns", "TMAS (seed 001"]),
        // More clocks 5 us after the last: for the slave (no SLO answer,
        // its timeout not over) the same frame, which the seed allows.
        (6, 0, 0, &[]),
    ];
    for (case, n_ssi, n_biss, rules) in cases {
        let (mon_s, mon_b) = (
            dir.join(format!("ssi_{case}.json")),
            dir.join(format!("biss_{case}.json")),
        );
        let (ok, out) = run(Command::new(cmd.get_program())
            .args(cmd.get_args())
            .envs(cmd.get_envs().filter_map(|(k, v)| Some((k, v?))))
            .args([
                format!("+case={case}"),
                format!("+ssi_monitor_config={}", ssi.display()),
                format!("+biss_monitor_config={}", biss.display()),
                format!("+ssi_monitor_transcript={}", mon_s.display()),
                format!("+biss_monitor_transcript={}", mon_b.display()),
            ]));
        assert!(ok, "case {case} in {sim}:\n{out}");
        assert!(
            out.contains(&format!("violations ssi {n_ssi} biss {n_biss}")),
            "case {case} in {sim}:\n{out}"
        );
        assert_eq!(
            out.matches("PROTOCOL VIOLATION by the master on").count(),
            n_ssi + n_biss,
            "case {case} in {sim}:\n{out}"
        );
        for r in rules {
            assert!(out.contains(r), "case {case} in {sim}: no `{r}` in\n{out}");
        }
        // The transcripts the simulator wrote at the end: two reads, two frames, the violations.
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&mon_s).unwrap()).unwrap();
        assert_eq!(t["transactions"].as_array().unwrap().len(), 2, "{t}");
        assert_eq!(t["violations"].as_array().unwrap().len(), n_ssi, "{t}");
        // Case 6's second burst comes before the slave's timeout: one frame.
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&mon_b).unwrap()).unwrap();
        let frames = if case == 6 { 1 } else { 2 };
        assert_eq!(t["transactions"].as_array().unwrap().len(), frames, "{t}");
        assert_eq!(t["violations"].as_array().unwrap().len(), n_biss, "{t}");
    }
    // The clean run's SSI transcript as a capture of `tbgen check`: the data
    // line stayed high, so both reads are 4095; a flipped bit is found.
    let expect = dir.join("expect.json");
    std::fs::write(
        &expect,
        r#"{"transactions": [{"position": 4095, "errors": []}, {"position": 4095, "errors": []}]}"#,
    )
    .unwrap();
    let (ok, out) = tbgen_check("ssi", &expect, &dir.join("ssi_0.json"));
    assert!(
        ok && out.contains("PASS: 2 transactions of ssi equal"),
        "{out}"
    );
    std::fs::write(
        &expect,
        r#"{"transactions": [{"position": 4095, "errors": []}, {"position": 4091, "errors": []}]}"#,
    )
    .unwrap();
    let (ok, out) = tbgen_check("ssi", &expect, &dir.join("ssi_0.json"));
    assert!(
        !ok && out.contains("DIFFERENCE in transaction 1 at ")
            && out.contains("position expected 4091, captured 4095"),
        "{out}"
    );
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
    let (mut emu, mut mon) = (
        open("ssi", toml, "t.toml", 4_000_000).unwrap(),
        open("ssi_monitor", toml, "t.toml", 4_000_000).unwrap(),
    );
    let mut data = true;
    for read in 0..20u64 {
        emu.set_position(0, read * 3001 % 65536).unwrap();
        // 120 idle cycles, T_cs 18, 16 bits of 8 + 8 cycles, high after.
        let clk: Vec<bool> = (0..120 + 18 + 16 * 16 + 40)
            .map(|c| !(120..138 + 16 * 16).contains(&c) || (c >= 138 && (c - 138) % 16 < 8))
            .collect();
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
    assert!(
        ok && out.contains("PASS: 20 transactions of ssi equal"),
        "{out}"
    );
    let p = &mut sent["reads"][7]["position"];
    *p = serde_json::Value::from(p.as_u64().unwrap() ^ 1);
    std::fs::write(&expect, sent.to_string()).unwrap();
    let (ok, out) = tbgen_check("ssi", &expect, &capture);
    assert!(
        !ok && out.contains("DIFFERENCE in transaction 7 at ") && out.contains("position expected"),
        "{out}"
    );
}

/// The same for BiSS-C: the emulator's `frames` (position, error and
/// warning of each slave) against the monitor's decoded frames.
#[test]
fn tbgen_check_takes_a_biss_monitor_transcript_and_finds_a_flipped_position_bit() {
    use cosim::{open, Pins};
    let toml = "[[slaves]]\nbits = 16\n[cable]\nlength_m = 20\n";
    let (mut emu, mut mon) = (
        open("biss", toml, "t.toml", 80_000_000).unwrap(),
        open("biss_monitor", toml, "t.toml", 80_000_000).unwrap(),
    );
    let mut slo = true;
    for frame in 0..12u64 {
        emu.set_position(0, frame * 7919 % 65536).unwrap();
        emu.set_status(0, "error", frame % 3 == 0).unwrap();
        emu.set_status(0, "warning", frame % 4 == 1).unwrap();
        // 1700 idle cycles (21 us, beyond the 16 us timeout), then 40 MA periods of 4 + 4 cycles.
        let ma: Vec<bool> = (0..1700 + 320)
            .map(|c| c < 1700 || (c - 1700) % 8 >= 4)
            .collect();
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
    assert!(
        ok && out.contains("PASS: 12 transactions of biss equal"),
        "{out}"
    );
    let p = &mut sent["frames"][5]["slaves"][0]["position"];
    *p = serde_json::Value::from(p.as_u64().unwrap() ^ 8);
    std::fs::write(&expect, sent.to_string()).unwrap();
    let (ok, out) = tbgen_check("biss", &expect, &capture);
    assert!(
        !ok && out.contains("DIFFERENCE in transaction 5 at ")
            && out.contains("slaves[0].position expected"),
        "{out}"
    );
}

/// The T-format and ESL monitors in the simulators: a hand-written host of
/// each (`hdl/tb_cosim/monitor_rules/tb_half_duplex_rules.v`) breaks each
/// rule once (cases 1 to 11) or none (case 0); each violation is reported
/// once with its seed's rule, and the transcripts hold the transactions.
fn each_half_duplex_rule_fires_once(sim: &str) {
    use model::tformat::frames::DataId;
    let dir = root().join(format!(
        "build/cosim/monitor_rules/{sim}/tb_half_duplex_rules/run"
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let (tf, esl) = (dir.join("tformat.toml"), dir.join("esl.toml"));
    std::fs::write(&tf, "baud = 2.5e6\n").unwrap();
    std::fs::write(&esl, "baud = 10e6\n[[encoders]]\naddress = 3\n").unwrap();
    let hex = |b: &[u8]| b.iter().map(|x| format!("{x:02x}")).collect::<String>();
    let bytes = [
        format!(
            "+tf_id0={}",
            hex(&model::tformat::frames::request(DataId::Id0, 0, 0))
        ),
        format!(
            "+tf_id7={}",
            hex(&model::tformat::frames::request(DataId::Id7, 0, 0))
        ),
        format!(
            "+tf_idd={}",
            hex(&model::tformat::frames::request(DataId::IdD, 5, 0))
        ),
        format!("+esl_id1={}", hex(&model::esl::frames::request(3, 1, 0, 0))),
        format!(
            "+esl_idb={}",
            hex(&model::esl::frames::request(3, 0xB, 0, 0))
        ),
        format!(
            "+esl_ide={}",
            hex(&model::esl::frames::request(3, 0xE, 0x10, 0))
        ),
    ];
    let cmd = bench_of(sim, "tb_half_duplex_rules");
    use model::esl::rules as e;
    use model::tformat::rules as t;
    let cases: [(u32, usize, usize, String); 12] = [
        (0, 0, 0, String::new()),
        (
            1,
            1,
            0,
            format!(
                "{}: an edge 1400.0 ns after the field's start edge, 3.50 bits",
                t::JITTER.label()
            ),
        ),
        (2, 1, 0, format!("{}: 2.00 bits", t::END_OF_FRAME.label())),
        (3, 1, 0, format!("{}: driver enable on", t::RELEASE.label())),
        (
            4,
            1,
            0,
            format!(
                "{}: the host switched its driver on 2.00 bits",
                t::ANSWER.label()
            ),
        ),
        (
            5,
            1,
            0,
            format!("{}: request 2 of reset Data ID 7 0.104", t::RESET.label()),
        ),
        (
            6,
            0,
            1,
            format!(
                "{}: an edge 350.0 ns after the field's start edge",
                e::BIT_RATE.label()
            ),
        ),
        (
            7,
            0,
            1,
            format!("{}: 1.50 bits", e::END_OF_FRAME_SET.label()),
        ),
        (
            8,
            0,
            1,
            format!(
                "{}: a request of 1 frame(s) for Data ID 1, which takes 2",
                e::FRAMES.label()
            ),
        ),
        (9, 0, 1, format!("{}: driver enable on", e::RELEASE.label())),
        (
            10,
            0,
            1,
            format!(
                "{}: Data ID B sent 1 time(s) to address 3, then Data ID 1",
                e::REPEAT.label()
            ),
        ),
        (
            11,
            0,
            1,
            format!(
                "{}: the host switched its driver on 2.00 bits",
                e::HALF_DUPLEX.label()
            ),
        ),
    ];
    for (case, n_tf, n_esl, rule) in cases {
        let (mon_t, mon_e) = (
            dir.join(format!("tformat_{case}.json")),
            dir.join(format!("esl_{case}.json")),
        );
        let (ok, out) = run(Command::new(cmd.get_program())
            .args(cmd.get_args())
            .envs(cmd.get_envs().filter_map(|(k, v)| Some((k, v?))))
            .args(&bytes)
            .args([
                format!("+case={case}"),
                format!("+tformat_monitor_config={}", tf.display()),
                format!("+esl_monitor_config={}", esl.display()),
                format!("+tformat_monitor_transcript={}", mon_t.display()),
                format!("+esl_monitor_transcript={}", mon_e.display()),
            ]));
        assert!(ok, "case {case} in {sim}:\n{out}");
        assert!(
            out.contains(&format!("violations tformat {n_tf} esl {n_esl}")),
            "case {case} in {sim}:\n{out}"
        );
        assert_eq!(
            out.matches("PROTOCOL VIOLATION by the master on").count(),
            n_tf + n_esl,
            "case {case} in {sim}:\n{out}"
        );
        assert!(
            out.contains(&rule),
            "case {case} in {sim}: no `{rule}` in\n{out}"
        );
        // The transcripts: two transactions each (a reset's requests and B then a readout are one).
        let (want_t, want_e) = (
            if case == 5 { 1 } else { 2 },
            if case == 10 { 1 } else { 2 },
        );
        assert!(
            out.contains(&format!("transactions tformat {want_t} esl {want_e}")),
            "case {case} in {sim}:\n{out}"
        );
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&mon_t).unwrap()).unwrap();
        assert_eq!(
            (
                t["transactions"].as_array().unwrap().len(),
                t["violations"].as_array().unwrap().len()
            ),
            (want_t, n_tf),
            "{t}"
        );
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&mon_e).unwrap()).unwrap();
        assert_eq!(
            (
                t["transactions"].as_array().unwrap().len(),
                t["violations"].as_array().unwrap().len()
            ),
            (want_e, n_esl),
            "{t}"
        );
        if case == 0 {
            assert_eq!(
                t["transactions"][1]["wire_requests"][0],
                serde_json::json!(model::esl::frames::request(3, 0xE, 0x10, 0)),
                "{t}"
            );
        }
    }
}

/// The EnDat monitor in the simulators: `tb_endat_monitor_rules.v` breaks each
/// rule of seed 004 the monitor checks once (cases 1 to 10) or none (case 0);
/// the transcript written at the end holds the decoded transfers.
fn each_endat_rule_fires_once_and_the_clean_master_passes(sim: &str) {
    let dir = root().join(format!("build/cosim/monitor_rules/{sim}/endat_run"));
    std::fs::create_dir_all(&dir).unwrap();
    let plain = dir.join("endat.toml");
    std::fs::write(
        &plain,
        "[emulator]\nmax_line_clock_khz = 1000\n[encoder]\noutput_delay_ns = 0\n",
    )
    .unwrap();
    let fc = dir.join("endat_fc.toml");
    std::fs::write(
        &fc,
        "[emulator]\nmax_line_clock_khz = 1000\n[monitor]\nmax_clock_khz = 1000\n",
    )
    .unwrap();
    let comp = dir.join("endat_comp.toml");
    std::fs::write(
        &comp,
        "[emulator]\nmax_line_clock_khz = 1000\n[master]\ndelay_comp = true\n",
    )
    .unwrap();
    let cmd = bench_of(sim, "tb_endat_monitor_rules");
    // The rule texts as the rule book prints them.
    use model::endat::rules as r;
    let at =
        |rule: &'static model::rules::Rule, detail: &str| format!("{}: {detail}", rule.label());
    let cases: [(u32, usize, usize, Vec<String>); 11] = [
        (0, 0, 2, vec![]),
        (
            1,
            2,
            2,
            vec![
                at(&r::F_C, "clock high for 0.250 us"),
                "clock low for 0.250 us".into(),
            ],
        ),
        (
            2,
            1,
            2,
            vec![at(&r::ON_OFF, "clock high 0.750 us and low 0.250 us")],
        ),
        (
            3,
            1,
            2,
            vec![at(&r::T_ST, "first low phase 0.250 us at a 2000 kHz clock")],
        ),
        (
            4,
            2,
            2,
            vec![
                r::SEND_BLOCK.label().into(),
                "switched its data driver on outside a transfer".into(),
                "still on at R8".into(),
            ],
        ),
        (5, 1, 2, vec![at(&r::T_M, "next transfer 10.500 us after")]),
        (
            6,
            1,
            2,
            vec![at(&r::T_R, "the line rose at the master 0.250 us before")],
        ),
        (
            7,
            1,
            2,
            vec![at(&r::T_ERR, "next transfer 20.500 us after")],
        ),
        (8, 1, 2, vec![at(&r::T_B, "next transfer 500.500 us after")]),
        (9, 3, 4, vec![r::MEAS_CLOCK.label().into()]),
        (
            10,
            1,
            2,
            vec![
                r::MEAS_COUNT.label().into(),
                "a delay measurement of 2 frame(s)".into(),
            ],
        ),
    ];
    for (case, n, transfers, rules) in cases {
        let t = dir.join(format!("endat_{case}.json"));
        let cfg = match case {
            1 => &fc,
            9 | 10 => &comp,
            _ => &plain,
        };
        let (ok, out) = run(Command::new(cmd.get_program())
            .args(cmd.get_args())
            .envs(cmd.get_envs().filter_map(|(k, v)| Some((k, v?))))
            .args([
                format!("+case={case}"),
                format!("+endat_monitor_config={}", cfg.display()),
                format!("+endat_monitor_transcript={}", t.display()),
            ]));
        assert!(ok, "case {case} in {sim}:\n{out}");
        assert!(
            out.contains(&format!("violations endat {n}")),
            "case {case} in {sim}:\n{out}"
        );
        assert_eq!(
            out.matches("PROTOCOL VIOLATION by the master on").count(),
            n,
            "case {case} in {sim}:\n{out}"
        );
        for r in &rules {
            assert!(
                out.contains(r.as_str()),
                "case {case} in {sim}: no `{r}` in\n{out}"
            );
        }
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&t).unwrap()).unwrap();
        assert_eq!(
            t["transactions"].as_array().unwrap().len(),
            transfers,
            "case {case} in {sim}: {t}"
        );
        assert_eq!(t["violations"].as_array().unwrap().len(), n, "{t}");
    }
}

#[test]
fn each_tformat_and_esl_monitor_rule_fires_in_icarus() {
    each_half_duplex_rule_fires_once("icarus");
}

#[test]
fn each_tformat_and_esl_monitor_rule_fires_in_verilator() {
    each_half_duplex_rule_fires_once("verilator");
}

#[test]
fn each_endat_monitor_rule_fires_in_icarus() {
    each_endat_rule_fires_once_and_the_clean_master_passes("icarus");
}

#[test]
fn each_endat_monitor_rule_fires_in_verilator() {
    each_endat_rule_fires_once_and_the_clean_master_passes("verilator");
}

/// The SAR58K24 and Modbus RTU monitors in the simulators: a hand-written
/// Modbus master and SAR58K24 bus host
/// (`hdl/tb_cosim/monitor_rules/tb_uart_monitor_rules.v`) break each rule
/// once (cases 1 to 14) or none (case 0); each violation is reported once
/// with its rule; the clean transcripts are captures `tbgen check` reads
/// (pass, and a flipped register or position bit is found).
fn each_uart_rule_fires_once(sim: &str) {
    use model::modbus::rules as mb;
    use model::sar58k24::rules as sar;
    let dir = root().join(format!(
        "build/cosim/monitor_rules/{sim}/tb_uart_monitor_rules/run"
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let (mbt, sart) = (dir.join("modbus.toml"), dir.join("sar.toml"));
    std::fs::write(&mbt, "[modbus]\nbaud = 15625.0\nparity = \"even\"\n[modbus.master]\ntimeout_us = 5000.0\n[[modbus.devices]]\naddress = 1\nbits = 32\n").unwrap();
    std::fs::write(&sart, "[sar]\nbaud = 15625.0\nmode = \"bus\"\n[sar.host]\ntimeout_us = 5000.0\n[[sar.encoders]]\naddress = 1\nbits = 32\n").unwrap();
    let cmd = bench_of(sim, "tb_uart_monitor_rules");
    let cases: [(u32, usize, usize, &str); 15] = [
        (0, 0, 0, ""),
        (1, 1, 0, mb::CHARACTER.label()),
        (2, 1, 0, mb::CHARACTER.label()),
        (3, 1, 0, mb::T15.label()),
        (4, 1, 0, mb::T35.label()),
        (5, 1, 0, mb::RELEASE.label()),
        (6, 1, 0, mb::ANSWER.label()),
        (7, 1, 0, mb::TIMEOUT.label()),
        (8, 0, 1, sar::CHARACTER.label()),
        (9, 0, 1, sar::GAP.label()),
        (10, 0, 1, sar::RELEASE.label()),
        (11, 0, 1, sar::ANSWER.label()),
        (12, 0, 1, sar::WAIT.label()),
        (13, 0, 1, sar::T2.label()),
        (14, 0, 1, sar::TRIGGER_BUSY.label()),
    ];
    for (case, n_mb, n_sar, rule) in cases {
        let (mon_m, mon_s) = (
            dir.join(format!("modbus_{case}.json")),
            dir.join(format!("sar_{case}.json")),
        );
        let (ok, out) = run(Command::new(cmd.get_program())
            .args(cmd.get_args())
            .envs(cmd.get_envs().filter_map(|(k, v)| Some((k, v?))))
            .args([
                format!("+case={case}"),
                format!("+modbus_monitor_config={}", mbt.display()),
                format!("+sar58k24_monitor_config={}", sart.display()),
                format!("+modbus_monitor_transcript={}", mon_m.display()),
                format!("+sar58k24_monitor_transcript={}", mon_s.display()),
            ]));
        assert!(ok, "case {case} in {sim}:\n{out}");
        assert!(
            out.contains(&format!("violations modbus {n_mb} sar {n_sar}")),
            "case {case} in {sim}:\n{out}"
        );
        assert_eq!(
            out.matches("PROTOCOL VIOLATION by the master on").count(),
            n_mb + n_sar,
            "case {case} in {sim}:\n{out}"
        );
        assert!(
            out.contains(rule),
            "case {case} in {sim}: no `{rule}` in\n{out}"
        );
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&mon_m).unwrap()).unwrap();
        assert_eq!(t["violations"].as_array().unwrap().len(), n_mb, "{t}");
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&mon_s).unwrap()).unwrap();
        assert_eq!(t["violations"].as_array().unwrap().len(), n_sar, "{t}");
    }
    // The clean transcripts: two polls of 0x12345678, two frames of 0x01020304.
    let expect = dir.join("expect_modbus.json");
    let poll = r#"{"op": "read", "address": 1, "count": 2, "value": VALUE, "errors": []}"#;
    std::fs::write(
        &expect,
        format!(
            "{{\"transactions\": [{}, {}]}}",
            poll.replace("VALUE", "305419896"),
            poll.replace("VALUE", "305419896")
        ),
    )
    .unwrap();
    let (ok, out) = tbgen_check("modbus", &expect, &dir.join("modbus_0.json"));
    assert!(
        ok && out.contains("PASS: 2 transactions of modbus equal"),
        "{out}"
    );
    std::fs::write(
        &expect,
        format!(
            "{{\"transactions\": [{}, {}]}}",
            poll.replace("VALUE", "305419896"),
            poll.replace("VALUE", "305419900")
        ),
    )
    .unwrap();
    let (ok, out) = tbgen_check("modbus", &expect, &dir.join("modbus_0.json"));
    assert!(
        !ok && out.contains("DIFFERENCE in transaction 1 at ")
            && out.contains("value expected 305419900, captured 305419896"),
        "{out}"
    );
    let expect = dir.join("expect_sar.json");
    let ev =
        |kind: &str, pos: &str| format!(r#"{{"kind": "{kind}", "position": {pos}, "errors": []}}"#);
    let list = |p: &str| {
        format!(
            "{{\"transactions\": [{}, {}, {}, {}]}}",
            ev("command", "null"),
            ev("frame", "16909060"),
            ev("command", "null"),
            ev("frame", p)
        )
    };
    std::fs::write(&expect, list("16909060")).unwrap();
    let (ok, out) = tbgen_check("sar", &expect, &dir.join("sar_0.json"));
    assert!(
        ok && out.contains("PASS: 4 transactions of sar equal"),
        "{out}"
    );
    std::fs::write(&expect, list("16909061")).unwrap();
    let (ok, out) = tbgen_check("sar", &expect, &dir.join("sar_0.json"));
    assert!(
        !ok && out.contains("DIFFERENCE in transaction 3 at ")
            && out.contains("position expected 16909061, captured 16909060"),
        "{out}"
    );
}

#[test]
fn each_sar58k24_and_modbus_monitor_rule_fires_in_icarus() {
    each_uart_rule_fires_once("icarus");
}

#[test]
fn each_sar58k24_and_modbus_monitor_rule_fires_in_verilator() {
    each_uart_rule_fires_once("verilator");
}

/// A CAN line as `tb_can_monitor_rules.v` plays it: one character per bit
/// (`'0' + 2 × TXD + RXD`), `I`/`i` for 100/10 idle bits, `f`/`n` 3 % short / nominal bits.
#[derive(Default)]
struct CanLine(String);

impl CanLine {
    fn bits(&mut self, tx: &[bool], rx: &[bool]) -> &mut Self {
        for (&t, &r) in tx.iter().zip(rx) {
            self.0.push(char::from(b'0' + 2 * t as u8 + r as u8));
        }
        self
    }
    fn idle(&mut self, n: usize) -> &mut Self {
        self.0.push_str(&"I".repeat(n / 100));
        self.0.push_str(&"i".repeat(n % 100 / 10));
        self.0.push_str(&"3".repeat(n % 10));
        self
    }
    /// A frame the master sends, acknowledged by another node, and 3 bits of intermission.
    fn sent(&mut self, f: &model::can::frame::Frame) -> &mut Self {
        self.bits(&f.wire_bits(false), &f.wire_bits(true)).idle(3)
    }
    /// A frame another node sends, acknowledged by the master.
    fn heard(&mut self, f: &model::can::frame::Frame) -> &mut Self {
        let rx = f.wire_bits(true);
        let tx: Vec<bool> = (0..rx.len()).map(|k| k != rx.len() - 9).collect();
        self.bits(&tx, &rx).idle(3)
    }
}

/// The CAN and CANopen monitors in the simulators: `tb_can_monitor_rules.v`
/// plays a line the model's frames make, breaking each rule once (cases 1
/// to 10) or none (case 0); each violation is reported once, by the CAN
/// monitor (CAN rules) and the CANopen monitor (CAN and CANopen rules); the
/// clean transcript passes `tbgen check can`, a flipped data bit is found
/// with its time.
fn each_can_rule_fires_once(sim: &str) {
    use model::can::frame::Frame;
    let dir = root().join(format!(
        "build/cosim/monitor_rules/{sim}/tb_can_monitor_rules/run"
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let (can, canopen) = (dir.join("can.toml"), dir.join("canopen.toml"));
    std::fs::write(&can, "[can]\nf_sys_mhz = 8\ntiming = { bit_rate_kbps = 500, tq_per_bit = 16, sample_point = 0.75, sjw = 1 }\n").unwrap();
    std::fs::write(&canopen, "[canopen]\nf_sys_mhz = 8\nbit_rate_kbps = 500\ntq_per_bit = 16\nsample_point = 0.75\n[canopen.master]\nsdo_timeout_us = 1000\nsync_period_us = 2000\n[[canopen.sar]]\n[canopen.sar.encoder]\nnode = 0x20\nbit_rate_kbps = 500\n").unwrap();
    let f = Frame::data(0x123, &[0xDE, 0xAD]);
    let sdo = |index: u16, v: u16| {
        Frame::data(
            0x605,
            &model::canopen::sdo::download(index, 0, &v.to_le_bytes()),
        )
    };
    let confirm = |index: u16| {
        Frame::data(
            0x585,
            &[0x60, index as u8, (index >> 8) as u8, 0, 0, 0, 0, 0],
        )
    };
    let (start, sync) = (Frame::data(0, &[1, 5]), Frame::data(0x80, &[]));
    let guard = Frame {
        id: 0x705,
        ide: false,
        rtr: true,
        dlc: 1,
        data: vec![],
    };
    let click = Frame::data(0x220, &[0x80, 0x20, 0, 0, 0, 0, 0, 0]);
    let mut cases: Vec<(CanLine, usize, usize, String)> = Vec::new();
    // 0 clean: boot-up, SDO and answer, start, guarding at 10 ms, SYNC at 2 ms, a click and its answer.
    let mut l = CanLine::default();
    l.idle(20)
        .heard(&Frame::data(0x85, &[]))
        .sent(&sdo(0x100C, 10))
        .heard(&confirm(0x100C))
        .sent(&start);
    for _ in 0..2 {
        l.sent(&guard).heard(&Frame::data(0x705, &[0x05])).idle(800);
        for _ in 0..4 {
            l.sent(&sync).idle(940);
        }
        l.sent(&sync).idle(35);
    }
    l.sent(&click)
        .heard(&Frame::data(0x120, &[0x47, 0x26, 0, 0, 0, 0, 0, 0]))
        .sent(&f)
        .idle(20);
    cases.push((l, 0, 0, String::new()));
    // 1 stuffing: six recessive identifier bits with no stuff bit.
    let raw = Frame::data(0x7E5, &[0x55]).destuffed_bits();
    let mut l = CanLine::default();
    l.idle(20).bits(&raw, &raw).idle(30);
    cases.push((
        l,
        1,
        1,
        format!(
            "{}: six equal bits in the master's frame ending at wire bit 6",
            model::can::rules::STUFF.label()
        ),
    ));
    // 2 form: the master's CRC delimiter dominant.
    let (mut tx, mut rx) = (f.wire_bits(false), f.wire_bits(true));
    let n = tx.len();
    tx[n - 10] = false;
    rx[n - 10] = false;
    let mut l = CanLine::default();
    l.idle(20).bits(&tx, &rx).idle(30);
    cases.push((
        l,
        1,
        1,
        format!(
            "{}: TXD dominant in the CRC delimiter, ACK delimiter or EOF (wire bit",
            model::can::rules::FORM.label()
        ),
    ));
    // 3 intermission: the next SOF after 2 bits of it.
    let mut l = CanLine::default();
    l.idle(20)
        .bits(&f.wire_bits(false), &f.wire_bits(true))
        .idle(2)
        .sent(&f)
        .idle(20);
    cases.push((
        l,
        1,
        1,
        format!(
            "{}: the master's SOF 10.00 bits after",
            model::can::rules::INTERMISSION.label()
        ),
    ));
    // 4 bit time: a frame 3 % fast.
    let mut l = CanLine::default();
    l.idle(20);
    l.0.push('f');
    l.bits(&f.wire_bits(false), &f.wire_bits(true));
    l.0.push('n');
    l.idle(30);
    cases.push((
        l,
        1,
        1,
        format!("{}: a TXD edge", model::can::rules::BIT_TIME.label()),
    ));
    // 5 dominant length: an error flag of 8 bits.
    let mut l = CanLine::default();
    l.idle(20).bits(&[false; 8], &[false; 8]).idle(30);
    cases.push((
        l,
        1,
        1,
        format!(
            "{}: TXD dominant for more than 6.00 bits",
            model::can::rules::DOMINANT.label()
        ),
    ));
    // 6 SDO: a second request 100 us after the first, unanswered.
    let mut l = CanLine::default();
    l.idle(20)
        .sent(&sdo(0x6200, 1))
        .idle(50)
        .sent(&sdo(0x6200, 2))
        .idle(20);
    cases.push((
        l,
        0,
        1,
        format!(
            "{}: SDO request to node 5",
            model::canopen::rules::SDO.label()
        ),
    ));
    // 7 NMT start twice.
    let mut l = CanLine::default();
    l.idle(20).sent(&start).idle(50).sent(&start).idle(20);
    cases.push((
        l,
        0,
        1,
        format!(
            "{}: NMT start (node 5) while node 5 was already started",
            model::canopen::rules::NMT.label()
        ),
    ));
    // 8 guarding: 10 ms guard time, the third request 16 ms after the second.
    let mut l = CanLine::default();
    l.idle(20).sent(&sdo(0x100C, 10)).heard(&confirm(0x100C));
    for gap in [4900, 7900, 100] {
        l.sent(&guard).heard(&Frame::data(0x705, &[0x05])).idle(gap);
    }
    cases.push((
        l,
        0,
        1,
        format!(
            "{}: guard request to node 5 16.",
            model::canopen::rules::GUARD.label()
        ),
    ));
    // 9 SYNC every 2 ms, one after 3 ms.
    let mut l = CanLine::default();
    l.idle(20);
    for gap in [940, 1440, 940] {
        l.sent(&sync).idle(gap);
    }
    l.sent(&sync).idle(20);
    cases.push((
        l,
        0,
        1,
        format!(
            "{}: SYNC 2982.000 us after the previous one; the period is 2000.000 us",
            model::canopen::rules::SYNC.label()
        ),
    ));
    // 10 SAR58K24: a click answered, then two clicks 100 us apart.
    let mut l = CanLine::default();
    l.idle(20)
        .sent(&click)
        .heard(&Frame::data(0x120, &[0x47, 0x26, 0, 0, 0, 0, 0, 0]))
        .sent(&click)
        .idle(50)
        .sent(&click)
        .idle(20);
    cases.push((
        l,
        0,
        1,
        format!(
            "{}: command 80 to SAR58K24 node 0x20",
            model::canopen::rules::SAR.label()
        ),
    ));
    let cmd = bench_of(sim, "tb_can_monitor_rules");
    for (case, (line, n_can, n_canopen, rule)) in cases.iter().enumerate() {
        let (t_can, t_co) = (
            dir.join(format!("can_{case}.json")),
            dir.join(format!("canopen_{case}.json")),
        );
        let (ok, out) = run(Command::new(cmd.get_program())
            .args(cmd.get_args())
            .envs(cmd.get_envs().filter_map(|(k, v)| Some((k, v?))))
            .args([
                format!("+bits={}", line.0),
                format!("+n={}", line.0.len()),
                format!("+can_monitor_config={}", can.display()),
                format!("+canopen_monitor_config={}", canopen.display()),
                format!("+can_monitor_transcript={}", t_can.display()),
                format!("+canopen_monitor_transcript={}", t_co.display()),
            ]));
        assert!(ok, "case {case} in {sim}:\n{out}");
        assert!(
            out.contains(&format!("violations can {n_can} canopen {n_canopen}")),
            "case {case} in {sim}:\n{out}"
        );
        assert_eq!(
            out.matches("PROTOCOL VIOLATION by the master on").count(),
            n_can + n_canopen,
            "case {case} in {sim}:\n{out}"
        );
        assert!(
            out.contains(rule),
            "case {case} in {sim}: no `{rule}` in\n{out}"
        );
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&t_can).unwrap()).unwrap();
        assert_eq!(t["violations"].as_array().unwrap().len(), *n_can, "{t}");
        let t: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&t_co).unwrap()).unwrap();
        assert_eq!(t["violations"].as_array().unwrap().len(), *n_canopen, "{t}");
        if case == 0 {
            // 4 + 2 × 7 + 3 frames, each read as CANopen too.
            assert_eq!(t["transactions"].as_array().unwrap().len(), 21, "{t}");
            assert_eq!(
                t["transactions"][0]["meaning"], "boot-up of node 5 (gateway form)",
                "{t}"
            );
            assert_eq!(
                t["transactions"][1]["meaning"], "SDO write 100Ch sub 0 (Guard time) = 10 (0xA)",
                "{t}"
            );
            assert_eq!(t["transactions"][1]["sender"], "master", "{t}");
        }
    }
    // The clean run's CAN transcript against the frames played, by `tbgen check can`; then one data bit flipped.
    let t: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("can_0.json")).unwrap()).unwrap();
    let mut want: Vec<serde_json::Value> = t["transactions"].as_array().unwrap().iter().map(|v| serde_json::json!({"id": v["id"], "dlc": v["dlc"], "data": v["data"], "error": null})).collect();
    assert_eq!(want.len(), 21);
    assert_eq!(
        want[20],
        serde_json::json!({"id": 0x123, "dlc": 2, "data": [0xDE, 0xAD], "error": null})
    );
    let expect = dir.join("expect.json");
    std::fs::write(
        &expect,
        serde_json::json!({ "transactions": want }).to_string(),
    )
    .unwrap();
    let (ok, out) = tbgen_check("can", &expect, &dir.join("can_0.json"));
    assert!(
        ok && out.contains("PASS: 21 transactions of can equal"),
        "{out}"
    );
    want[20]["data"][1] = serde_json::Value::from(0xAD ^ 4);
    std::fs::write(
        &expect,
        serde_json::json!({ "transactions": want }).to_string(),
    )
    .unwrap();
    let (ok, out) = tbgen_check("can", &expect, &dir.join("can_0.json"));
    let sof = t["transactions"][20]["sof_ps"].as_u64().unwrap() as f64 / 1e6;
    assert!(
        !ok && out.contains(&format!(
            "DIFFERENCE in transaction 20 at {sof:.3} us: data[1] expected 169, captured 173"
        )),
        "{out}"
    );
}

#[test]
fn each_can_monitor_rule_fires_in_icarus() {
    each_can_rule_fires_once("icarus");
}

#[test]
fn each_can_monitor_rule_fires_in_verilator() {
    each_can_rule_fires_once("verilator");
}

/// X or Z on an input of a monitor or of a clock/data/enable emulator
/// (`tb_wrapper_x`) stops the run with time, pin and cycle; with no X the
/// run goes on. Icarus only: Verilator is two-state.
#[test]
fn x_on_a_monitor_or_data_pair_emulator_input_is_reported_in_icarus() {
    let dir = root().join("build/cosim/monitor_rules/icarus/wrapper_x");
    std::fs::create_dir_all(&dir).unwrap();
    let ssi = dir.join("ssi.toml");
    std::fs::write(&ssi, "[encoder]\nbits = 12\n").unwrap();
    let endat = root().join("hdl/tb_cosim/endat_master/configs/pos22_1mhz_20m.toml");
    let cmd = bench_of("icarus", "tb_wrapper_x");
    // The X arrives at 500 ns and is seen at the next clock edge, 510 ns
    // (in ps), after 25 cycles (edges at 10, 30, ..., 490 ns).
    let cases = [
        ("none", true, "no error"),
        (
            "monitor",
            false,
            "X or Z on monitor input 1 of (i_ssi_clk, i_ssi_data) at time 510000, monitor cycle 25",
        ),
        (
            "pair",
            false,
            "X or Z on emulator input i_endat_data at time 510000, emulator cycle 25",
        ),
    ];
    for (x_on, passes, want) in cases {
        let (ok, out) = run(Command::new(cmd.get_program())
            .args(cmd.get_args())
            .envs(cmd.get_envs().filter_map(|(k, v)| Some((k, v?))))
            .args([
                format!("+x_on={x_on}"),
                format!("+ssi_monitor_config={}", ssi.display()),
                format!("+endat_emu_config={}", endat.display()),
            ]));
        assert_eq!(ok, passes, "x on {x_on}:\n{out}");
        assert!(out.contains(want), "x on {x_on}: no `{want}` in\n{out}");
    }
}
