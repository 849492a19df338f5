//! `make sim` as a new user types it: a scenario file of
//! one's own and a vector file replay in both simulators, a name that is not
//! a core lists the cores, an unknown simulator names the supported ones, and
//! a scenario name that matches nothing says what would. Needs make and the
//! simulators that `make deps` installs.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// Runs `make -s sim ARGS...` in the repository and returns (exit code, stdout + stderr).
fn make_sim(args: &[&str]) -> (i32, String) {
    let out = Command::new("make")
        .arg("-s")
        .arg("-C")
        .arg(root())
        .arg("sim")
        .args(args)
        // Under `make test` the outer make's jobserver must not leak in.
        .env_remove("MAKEFLAGS")
        .env_remove("MAKELEVEL")
        .env_remove("MFLAGS")
        .output()
        .expect("make runs");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.code().unwrap_or(-1), text)
}

/// The seed SSI scenario under another name and with other positions: a
/// scenario no committed vector file holds.
fn custom_ssi(dir: &Path, name: &str) -> PathBuf {
    let seed = fs::read_to_string(root().join("scenarios/ssi/seed_12bit.toml")).unwrap();
    let text = seed
        .replace("name = \"ssi_seed_12bit\"", &format!("name = \"{name}\""))
        .replace(
            "positions = [495, 0, 4095, 2730]",
            "positions = [1, 2047, 3000]",
        );
    assert_ne!(
        text, seed,
        "the seed scenario changed shape; update this test"
    );
    let path = dir.join(format!("{name}.toml"));
    fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_scenario_file_of_ones_own_replays_in_both_simulators_without_naming_the_core() {
    let dir = tempfile::tempdir().unwrap();
    let name = "sim_cli_custom_ssi";
    let toml = custom_ssi(dir.path(), name);
    for sim in ["icarus", "verilator"] {
        let (code, text) = make_sim(&[
            &format!("SIM={sim}"),
            &format!("SCENARIO={}", toml.display()),
        ]);
        assert_eq!(code, 0, "{sim}: {text}");
        assert!(
            text.contains(&format!("PASS  {sim:<10} ssi_master   {name}")),
            "{sim}: {text}"
        );
        assert!(text.contains("hdl: 1 passed, 0 failed"), "{sim}: {text}");
    }
    // Generated where the layout and the vectors can be found again.
    let hex = root().join(format!("build/custom/{name}/{name}.hex"));
    assert!(hex.is_file(), "{} written", hex.display());
}

#[test]
fn a_vector_file_replays_from_its_path_and_its_core_must_agree() {
    let hex = root().join("vectors/biss_master/biss_register_read.hex");
    let (code, text) = make_sim(&["SIM=icarus", &format!("SCENARIO={}", hex.display())]);
    assert_eq!(code, 0, "{text}");
    assert!(
        text.contains("PASS  icarus     biss_master  biss_register_read"),
        "{text}"
    );

    let (code, text) = make_sim(&[
        "CORE=ssi_master",
        "SIM=icarus",
        &format!("SCENARIO={}", hex.display()),
    ]);
    assert_eq!(code, 2, "{text}");
    assert!(
        text.contains("is a scenario of core 'biss_master', not 'ssi_master'"),
        "{text}"
    );

    let (code, text) = make_sim(&["SIM=icarus", "SCENARIO=/nonexistent/x.hex"]);
    assert_eq!(code, 2, "{text}");
    assert!(
        text.contains("no vector file '/nonexistent/x.hex'"),
        "{text}"
    );
}

#[test]
fn a_name_that_is_not_a_core_lists_the_cores() {
    let (code, text) = make_sim(&["CORE=endat", "SIM=icarus"]);
    assert_eq!(code, 2, "{text}");
    assert!(text.contains("unknown core 'endat'"), "{text}");
    for tb in fs::read_dir(root().join("hdl/tb")).unwrap() {
        let core = tb.unwrap().file_name().into_string().unwrap();
        if root().join(format!("hdl/tb/{core}/tb_{core}.v")).is_file() {
            assert!(text.contains(&core), "{core} listed: {text}");
        }
    }
    assert!(text.contains("Did you mean endat_master?"), "{text}");
}

#[test]
fn an_unknown_simulator_names_the_supported_ones() {
    let (code, text) = make_sim(&["CORE=ssi_master", "SIM=modelsim", "SCENARIO=ssi_seed_12bit"]);
    assert_eq!(code, 2, "{text}");
    assert!(
        text.contains(
            "unknown simulator 'modelsim'; the supported simulators are: icarus verilator"
        ),
        "{text}"
    );
}

#[test]
fn a_scenario_name_that_matches_nothing_says_what_would() {
    let (code, text) = make_sim(&["CORE=ssi_master", "SIM=icarus", "SCENARIO=my_ssi"]);
    assert_eq!(code, 2, "{text}");
    assert!(
        text.contains("no scenario named 'my_ssi' in vectors/ssi_master/"),
        "{text}"
    );
    assert!(text.contains("SCENARIO=path/to/my_ssi.toml"), "{text}");
    assert!(
        text.contains("ssi_seed_12bit"),
        "the core's scenarios listed: {text}"
    );

    let (code, text) = make_sim(&[
        "CORE=ssi_master",
        "SIM=icarus",
        "SCENARIO=biss_register_read",
    ]);
    assert_eq!(code, 2, "{text}");
    assert!(
        text.contains("It is a scenario of core 'biss_master' (CORE=biss_master)"),
        "{text}"
    );
}

/// The newcomer's last step: the RTL's own waves
/// from `make sim WAVES=1` (femtosecond timescale) decode with `tbgen
/// decode ssi` to the seed's 495 (SAR58K24 manual, SSI section (4)).
#[test]
fn the_rtl_waves_of_make_sim_decode_to_the_seed_position() {
    let (code, text) = make_sim(&[
        "CORE=ssi_master",
        "SIM=icarus",
        "SCENARIO=ssi_seed_12bit",
        "WAVES=1",
    ]);
    assert_eq!(code, 0, "{text}");
    let vcd = root().join("build/waves/ssi_seed_12bit.icarus.vcd");
    let out = Command::new(env!("CARGO_BIN_EXE_tbgen"))
        .args([
            "decode",
            "ssi",
            vcd.to_str().unwrap(),
            "--clk",
            "tb_ssi_master.o_ssi_clk",
            "--data",
            "tb_ssi_master.i_ssi_data",
            "--bits",
            "12",
        ])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let positions: Vec<u64> = json["transactions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["position"].as_u64().unwrap())
        .collect();
    assert_eq!(positions, [495, 0, 4095, 2730], "{stdout}");
    assert_eq!(json["transactions"][0]["received_bits"], "000111101111");
}

/// The fabric clocks boards have (48, 60, 120, 150 MHz,
/// periods of no whole number of picoseconds) generate and replay; the
/// waves' times are each cycle's exact time rounded to the picosecond.
#[test]
fn fabric_clocks_without_a_whole_picosecond_period_generate_and_replay() {
    let dir = tempfile::tempdir().unwrap();
    for mhz in [48, 60, 120, 150] {
        let name = format!("sim_cli_ssi_{mhz}mhz");
        let toml = custom_ssi(dir.path(), &name);
        let text = fs::read_to_string(&toml)
            .unwrap()
            .replace("f_sys_mhz = 50", &format!("f_sys_mhz = {mhz}"));
        fs::write(&toml, text).unwrap();
        let (code, text) = make_sim(&["SIM=icarus", &format!("SCENARIO={}", toml.display())]);
        assert_eq!(code, 0, "{mhz} MHz: {text}");
        assert!(
            text.contains(&format!("PASS  icarus     ssi_master   {name}")),
            "{mhz} MHz: {text}"
        );
        let vcd =
            fs::read_to_string(root().join(format!("build/custom/{name}/{name}.vcd"))).unwrap();
        let hex =
            fs::read_to_string(root().join(format!("build/custom/{name}/{name}.hex"))).unwrap();
        let cycles: u128 = hex
            .lines()
            .find_map(|l| l.strip_prefix("// cycles: "))
            .unwrap()
            .parse()
            .unwrap();
        let last: u128 = vcd
            .lines()
            .filter_map(|l| l.strip_prefix('#'))
            .next_back()
            .unwrap()
            .parse()
            .unwrap();
        let f = mhz as u128 * 1_000_000;
        assert_eq!(
            last,
            (cycles * 1_000_000_000_000 + f / 2) / f,
            "{mhz} MHz: the closing timestamp is the run's exact end, rounded"
        );
    }
}

/// A capture that is not there is bad input (exit status 2) named as such,
/// not an I/O failure (exit status 1).
#[test]
fn decoding_a_missing_capture_says_so_with_exit_status_2() {
    let out = Command::new(env!("CARGO_BIN_EXE_tbgen"))
        .args(["decode", "ssi", "nothere.vcd"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("nothere.vcd: no such capture file; give the path to a VCD"),
        "{err}"
    );
}
