//! The emulators in the simulators: our cores pass closed-loop in Icarus and
//! Verilator, a planted misread fails, a bad configuration stops the run at
//! time 0 naming file, field and fix, an emulator clock too slow is refused
//! with the minimum, and X on an emulator input is reported with time and
//! pin. Needs the simulators that `make deps` installs.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

mod common;

/// One Verilator build at a time (the machine is shared; builds are cached).
static SERIAL: Mutex<()> = Mutex::new(());

/// The error benches this test process has built already (sim, f_emu).
static BUILT: Mutex<Vec<(String, u64)>> = Mutex::new(Vec::new());

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

fn cosim(core: &str, sim: &str, extra: &[&str]) -> (bool, String) {
    let _one = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    run(Command::new(root().join("scripts/cosim.sh"))
        .args([core, sim, "--transactions", "90"])
        .args(extra))
}

fn closed_loop_passes_and_a_misread_fails(core: &str, sim: &str) {
    let (ok, out) = cosim(core, sim, &[]);
    assert!(ok, "{core} in {sim}:\n{out}");
    assert_eq!(out.matches("PASS").count(), 3, "{out}");
    assert!(
        out.contains("90 transactions over 3 configuration(s), pass"),
        "{out}"
    );
    // The testbench flips bit 2 of the core's position before comparing.
    let (ok, out) = cosim(core, sim, &["--flip-bit", "2"]);
    assert!(!ok, "a planted misread passed in {sim}:\n{out}");
    assert!(out.contains("core read"), "{out}");
}

#[test]
fn ssi_master_closed_loop_in_icarus() {
    closed_loop_passes_and_a_misread_fails("ssi_master", "icarus");
}

#[test]
fn ssi_master_closed_loop_in_verilator() {
    closed_loop_passes_and_a_misread_fails("ssi_master", "verilator");
}

/// The loop closes on a fabric clock without a whole-
/// picosecond period (f_sys = f_emu = 60 MHz) with a line clock that needs
/// an odd divider (160 kHz = 60 MHz / 375: HIGH_CLOCKS 188, LOW_CLOCKS 187),
/// and a planted misread still fails.
#[test]
fn ssi_master_closes_the_loop_at_a_60_mhz_emulator_clock_with_an_odd_divider_in_verilator() {
    let cfg = root().join("hdl/tb_cosim/ssi_master/fabric/fabric_60mhz_160khz.toml");
    let cfg = cfg.to_str().expect("a UTF-8 path");
    let (ok, out) = cosim("ssi_master", "verilator", &["--config", cfg]);
    assert!(ok, "60 MHz in verilator:\n{out}");
    assert!(
        out.contains("fabric_60mhz_160khz.toml: 90 transactions")
            && out.matches("PASS").count() == 1,
        "{out}"
    );
    let (ok, out) = cosim(
        "ssi_master",
        "verilator",
        &["--config", cfg, "--flip-bit", "2"],
    );
    assert!(
        !ok && out.contains("core read"),
        "a planted misread passed:\n{out}"
    );
}

#[test]
fn biss_master_closed_loop_in_icarus() {
    closed_loop_passes_and_a_misread_fails("biss_master", "icarus");
}

#[test]
fn biss_master_closed_loop_in_verilator() {
    closed_loop_passes_and_a_misread_fails("biss_master", "verilator");
}

/// A closed loop over `configs` configurations passes, and a planted
/// misread (bit 2 flipped before the comparison) fails with `misread`.
/// Returns the passing run's output.
fn closed_loop_of(core: &str, sim: &str, configs: usize, misread: &str) -> String {
    let (ok, passed) = cosim(core, sim, &[]);
    assert!(ok, "{core} in {sim}:\n{passed}");
    assert_eq!(passed.matches("PASS").count(), configs, "{passed}");
    let (ok, out) = cosim(core, sim, &["--flip-bit", "2"]);
    assert!(!ok, "a planted misread passed in {sim}:\n{out}");
    assert!(out.contains(misread), "{out}");
    passed
}

#[test]
fn sar_async_host_closed_loop_in_icarus_and_verilator() {
    closed_loop_of("sar_async_host", "icarus", 3, "core read");
    closed_loop_of("sar_async_host", "verilator", 3, "core read");
}

#[test]
fn modbus_master_closed_loop_in_icarus_and_verilator() {
    closed_loop_of("modbus_master", "icarus", 3, "core read");
    closed_loop_of("modbus_master", "verilator", 3, "core read");
}

#[test]
fn can_controller_closed_loop_in_icarus_and_verilator() {
    closed_loop_of("can_controller", "icarus", 3, "node 0 received");
    closed_loop_of("can_controller", "verilator", 3, "node 0 received");
}

/// The SAR58K24 CAN mode: can_controller and the testbench's command
/// sequencer against canopen_encoder_emu (four configurations); a flipped
/// bit of a received frame fails.
#[test]
fn sar58k24_can_closed_loop_in_icarus_and_verilator() {
    closed_loop_of("sar58k24_can", "verilator", 4, "core read");
    closed_loop_of("sar58k24_can", "icarus", 4, "core read");
}

/// Builds tb_emu_errors in `sim` with F_EMU_HZ = `f_emu`; returns a command that runs it.
fn errors_bench(sim: &str, f_emu: u64) -> Command {
    let _one = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let vars = run(&mut Command::new(root().join("scripts/emu_lib.sh")));
    assert!(vars.0, "{}", vars.1);
    let var = |name: &str| {
        vars.1
            .lines()
            .find_map(|l| l.strip_prefix(&format!("{name}=")))
            .unwrap()
            .to_string()
    };
    let (lib, vpi, hdl) = (var("EMU_LIB_DIR"), var("EMU_VPI_DIR"), var("EMU_HDL_DIR"));
    let build = root().join(format!("build/cosim/emu_errors/{sim}_{f_emu}"));
    std::fs::create_dir_all(&build).unwrap();
    let tb = root().join("hdl/tb_cosim/emu_errors/tb_emu_errors.v");
    let emu = format!("{hdl}/ssi_encoder_emu.v");
    let key = (sim.to_string(), f_emu);
    let built = BUILT.lock().unwrap().contains(&key);
    BUILT.lock().unwrap().push(key);
    match sim {
        "icarus" => {
            let vvp = build.join("tb.vvp");
            let (ok, out) = if built {
                (true, String::new())
            } else {
                run(Command::new("iverilog")
                    .args([
                        "-g2005",
                        "-Wno-timescale",
                        "-I",
                        &hdl,
                        &format!("-Ptb_emu_errors.F_EMU_HZ={f_emu}"),
                        "-o",
                    ])
                    .arg(&vvp)
                    .arg(&tb)
                    .arg(&emu))
            };
            assert!(ok, "{out}");
            let mut cmd = Command::new("vvp");
            cmd.args(["-n", "-M", &vpi, "-m", "emu"]).arg(vvp);
            cmd
        }
        _ => {
            let (ok, out) = if built {
                (true, String::new())
            } else {
                run(common::verilator(&root())
                    .args([
                        "--binary",
                        "--timing",
                        "-j",
                        "2",
                        "-Wno-fatal",
                        "-Wno-lint",
                        "-Wno-style",
                        "--top-module",
                        "tb_emu_errors",
                    ])
                    .args(common::verilator_make_flags(&root()))
                    .arg(format!(
                        "-I{}",
                        common::in_repo(&root(), Path::new(&hdl)).display()
                    ))
                    .arg(format!("-GF_EMU_HZ={f_emu}"))
                    .args([
                        "-LDFLAGS",
                        &format!("-L{lib} -lcosim -Wl,-rpath,{lib}"),
                        "--Mdir",
                    ])
                    .arg(build.join("obj"))
                    .args(["-o", "Vtb"])
                    .arg(common::in_repo(&root(), &tb))
                    .arg(common::in_repo(&root(), Path::new(&emu))))
            };
            assert!(ok, "{out}");
            Command::new(build.join("obj/Vtb"))
        }
    }
}

fn bad_configuration_stops_at_time_zero(sim: &str) {
    let dir = tempdir(sim);
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[encoder]\nbits = 65\n").unwrap();
    let good = dir.join("good.toml");
    std::fs::write(&good, "[encoder]\nbits = 12\n").unwrap();
    let mut tb = errors_bench(sim, 50_000_000);
    let (ok, out) = run(tb.arg(format!("+ssi_emu_config={}", bad.display())));
    assert!(!ok, "{out}");
    assert!(
        out.contains(&format!(
            "{}:2: field `encoder.bits`: 65 bits; give 1 to 64 bits",
            bad.display()
        )),
        "{out}"
    );
    assert!(out.contains("time 0"), "{out}");
    assert!(!out.contains("no error"), "{out}");
    let mut tb = errors_bench(sim, 50_000_000);
    let (ok, out) = run(tb.arg("+ssi_emu_config=/no/such/file.toml"));
    assert!(
        !ok && out.contains("/no/such/file.toml: cannot read"),
        "{out}"
    );
    let mut tb = errors_bench(sim, 50_000_000);
    let (ok, out) = run(&mut tb);
    assert!(!ok && out.contains("no configuration file"), "{out}");
    // An emulator clock of 800 kHz cannot follow a 250 kHz SSI clock.
    let mut tb = errors_bench(sim, 800_000);
    let (ok, out) = run(tb.arg(format!("+ssi_emu_config={}", good.display())));
    assert!(!ok && out.contains("at least 1000000 Hz"), "{out}");
    let mut tb = errors_bench(sim, 50_000_000);
    let (ok, out) = run(tb.arg(format!("+ssi_emu_config={}", good.display())));
    assert!(ok && out.contains("no error"), "{out}");
    // The bench's clock goes low for 100 ns and high again: a read with a
    // first low phase far below the seed's T_cs, reported by the checker.
    assert!(out.contains("PROTOCOL VIOLATION by the master on"), "{out}");
    assert!(
        out.contains("T_cs (seed 001 SAR58K24 manual, SSI (2): first low phase >= 4 us): first low phase 0.100 us"),
        "{out}"
    );
}

fn tempdir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("cosim_hdl_{tag}_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_bad_configuration_stops_icarus_at_time_zero_with_file_field_and_fix() {
    bad_configuration_stops_at_time_zero("icarus");
}

#[test]
fn a_bad_configuration_stops_verilator_at_time_zero_with_file_field_and_fix() {
    bad_configuration_stops_at_time_zero("verilator");
}

#[test]
fn x_on_an_emulator_input_is_reported_with_time_and_pin_in_icarus() {
    // Verilator is two-state: an X cannot reach the emulator there.
    let dir = tempdir("x");
    let good = dir.join("good.toml");
    std::fs::write(&good, "[encoder]\nbits = 12\n").unwrap();
    let mut tb = errors_bench("icarus", 50_000_000);
    let (ok, out) = run(tb
        .arg(format!("+ssi_emu_config={}", good.display()))
        .arg("+x_at=500"));
    assert!(!ok, "{out}");
    // The X arrives at 500 ns and is seen at the next emulator clock edge, 510 ns (in ps).
    assert!(
        out.contains("X or Z on emulator input i_ssi_clk at time 510000, emulator cycle 25"),
        "{out}"
    );
}

/// The masters we did not write (`examples/<dir>/`: a master, a copyable
/// testbench and Makefile, and a cocotb test `test_<dir>.py`), with the
/// reads of each HDL run and of each cocotb run. Adding an example is one
/// line here: its Makefile's `SIM=icarus`, `SIM=verilator` and `cocotb`
/// targets are what the tests below run.
const EXAMPLES: [(&str, u32, u32); 8] = [
    ("ssi_reader_other", 100, 20),
    ("biss_reader_other", 100, 20),
    // Each EnDat 2.1 read rests t_b > 1 ms (4,400 cycles): fewer reads.
    ("endat_reader_other", 30, 5),
    ("tformat_reader_other", 100, 20),
    ("esl_reader_other", 100, 20),
    ("sar58k24_reader_other", 100, 10),
    ("modbus_reader_other", 100, 6),
    ("canopen_reader_other", 100, 6),
];

/// `make -C examples/<dir> <args>` with `env`, one at a time.
fn make_example(dir: &str, args: &[String], env: &[(&str, String)]) -> (bool, String) {
    let _one = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let mut cmd = Command::new("make");
    cmd.arg("-C")
        .arg(root().join("examples").join(dir))
        .args(args);
    for (k, v) in env {
        cmd.env(k, v);
    }
    run(&mut cmd)
}

/// The masters we did not write, each with its copyable Makefile, pass in both simulators.
#[test]
fn the_independent_examples_pass_in_icarus_and_verilator() {
    for (example, reads, _) in EXAMPLES {
        for sim in ["icarus", "verilator"] {
            // Verilator compiles as our own benches do (the Makefiles leave the options to the user).
            let vflags = format!(
                "VERILATOR_FLAGS={}",
                common::verilator_make_flags(&root()).join(" ")
            );
            // The wrappers' folder (emu_lib.sh's EMU_HDL_DIR) named relative
            // to the example, as any clone names it: Verilator writes the
            // names into its C++, so ccache then finds the build another
            // clone made (scripts/verilator_ccache.sh).
            let hdl = "EMU_HDL_DIR=../../hdl/emu".to_string();
            let base = ("CCACHE_BASEDIR", root().display().to_string());
            let (ok, out) = make_example(
                example,
                &[format!("SIM={sim}"), format!("READS={reads}"), vflags, hdl],
                &[base],
            );
            assert!(ok, "{example} in {sim}:\n{out}");
            assert!(
                out.contains("PASS") && out.contains(&format!(": {reads} ")),
                "{example} in {sim}:\n{out}"
            );
        }
    }
}

/// Each of them passes from cocotb (`make cocotb`: the master against the
/// emulator driven from Python), and its test fails when a read differs
/// (`COSIM_FLIP_BIT` flips a bit of what the master read before the
/// comparison).
#[test]
fn the_independent_examples_pass_from_cocotb_and_a_flipped_bit_fails() {
    for (example, _, reads) in EXAMPLES {
        let n = ("COSIM_TRANSACTIONS", reads.to_string());
        let (ok, out) = make_example(example, &["cocotb".into()], std::slice::from_ref(&n));
        assert!(ok, "{example} from cocotb:\n{out}");
        // Every cocotb module of the example reports "1 of 1 passed".
        assert!(
            out.contains("1 of 1 passed") && !out.contains(" 0 of 1 passed"),
            "{example} from cocotb:\n{out}"
        );
        let (ok, out) = make_example(
            example,
            &["cocotb".into()],
            &[n, ("COSIM_FLIP_BIT", "2".into())],
        );
        assert!(!ok, "{example}: a planted misread passed cocotb:\n{out}");
        assert!(out.contains("0 of 1 passed"), "{example}:\n{out}");
    }
}

/// T-format and ESL closed loops with the pin-level monitor attached: every
/// readout's transaction the monitor decodes off the host's pins equals the
/// host's outputs (and its errors the host's), it sees no violation of the
/// seed, and a planted misread fails.
fn closed_loop_with_monitor(core: &str) {
    for sim in ["verilator", "icarus"] {
        let out = closed_loop_of(core, sim, 3, "ABS host");
        assert_eq!(
            out.matches("equal to the emulator's and to the monitor's")
                .count(),
            3,
            "{core} in {sim}:\n{out}"
        );
    }
}

#[test]
fn tformat_host_closed_loop_with_its_monitor_in_verilator_and_icarus() {
    closed_loop_with_monitor("tformat_host");
}

#[test]
fn esl_host_closed_loop_with_its_monitor_in_verilator_and_icarus() {
    closed_loop_with_monitor("esl_host");
}

/// The examples' testbenches drive and sample on the falling clock edge
/// with blocking assignments, so that a copy runs the same cycles in Icarus
/// and Verilator: a non-blocking assignment in an initial block (Verilator's
/// INITIALDLY) ran a cycle apart in the two. Verilator's lint of each
/// testbench with its master and the wrappers reports no INITIALDLY.
#[test]
fn the_examples_testbenches_assign_no_delayed_values_in_initial_blocks() {
    let root = root();
    for (example, _, _) in EXAMPLES {
        let dir = root.join("examples").join(example);
        let mut sources: Vec<PathBuf> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "v"))
            .collect();
        sources.sort();
        let (tbs, masters): (Vec<_>, Vec<_>) = sources
            .iter()
            .partition(|p| p.file_name().unwrap().to_str().unwrap().starts_with("tb_"));
        for tb in tbs {
            let top = tb.file_stem().unwrap().to_str().unwrap();
            let (_, out) = run(Command::new("verilator")
                .args([
                    "--lint-only",
                    "--timing",
                    "-Wall",
                    "-Wno-fatal",
                    "--top-module",
                    top,
                ])
                .arg(format!("-I{}", root.join("hdl/emu").display()))
                .arg("-y")
                .arg(root.join("hdl/emu"))
                .arg(tb)
                .args(&masters));
            assert!(
                !out.contains("%Error"),
                "{example}/{top}: the lint did not run:\n{out}"
            );
            assert!(
                !out.contains("INITIALDLY"),
                "{example}/{top}: a delayed assignment in an initial block:\n{out}"
            );
        }
    }
}

/// An example copied out of the tree without `ENCODER_TB` stops at once,
/// naming the variable and the fix (it used to stop at "No rule to make
/// target '/ssi_encoder_emu.v'", the wrappers' folder empty).
#[test]
fn an_example_without_its_checkout_names_encoder_tb() {
    for (example, _, _) in EXAMPLES {
        let (ok, out) = make_example(example, &["ENCODER_TB=/nonexistent".into()], &[]);
        assert!(!ok, "{example}:\n{out}");
        assert!(
            out.contains("ENCODER_TB=/nonexistent is not an encoder-tb checkout")
                && out.contains("make ENCODER_TB=/path/to/encoder-tb"),
            "{example}:\n{out}"
        );
    }
}
