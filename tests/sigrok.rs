//! An independent decoder reads the line: for every built-in scenario of a
//! protocol that names one in the registry (`tbgen protocols`, the
//! `sigrok` column), sigrok-cli runs on the scalars of the scenario's VCD
//! and must print what the protocol's folder says the line carries
//! (`Protocol::sigrok` in `tbgen/src/<table>/`): for SSI, sigrok's SPI
//! decoder at the encoder's pins finds exactly the bits the reader sampled
//! (cable and all); for the shared frame receiver, the `uart` decoder finds
//! the bytes it received; at the ESL and T-format hosts, every character
//! the transcript says was on the wire. It proves the waveforms are
//! decodable by a scalar-only reader. Needs sigrok-cli, which `make deps`
//! installs.

use std::collections::BTreeMap;
use std::fs;
use std::process::Command;

use tbgen::registry::SigrokCheck;
use tbgen::{builtin, generate, wave, PROTOCOLS};

/// What sigrok-cli prints for `check` on the VCD `vcd` (one sample per
/// system clock at `f_sys_hz`): the annotation values in order.
fn run_sigrok(
    dir: &std::path::Path,
    vcd: &std::path::Path,
    f_sys_hz: u64,
    check: &SigrokCheck,
) -> Vec<u128> {
    let scalars = dir.join("scalars.vcd");
    fs::write(
        &scalars,
        wave::scalars_only(&fs::read_to_string(vcd).unwrap()),
    )
    .unwrap();
    let downsample = 1_000_000_000_000 / f_sys_hz; // 1 ps timescale -> one sample per system clock
    let out = Command::new("sigrok-cli")
        .args([
            "-I",
            &format!("vcd:downsample={downsample}"),
            "-i",
            scalars.to_str().unwrap(),
        ])
        .args(["-P", &check.decoder])
        .args(["-A", check.annotation])
        .output()
        .expect("sigrok-cli runs (make deps installs it)");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let prefix = check.prefix();
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix(prefix.as_str()))
        .map(|v| {
            SigrokCheck::value(v).unwrap_or_else(|| panic!("sigrok printed `{v}`, not a value"))
        })
        .collect()
}

#[test]
fn sigrok_reads_on_the_line_of_every_scenario_what_the_model_says_is_there() {
    let dir = tempfile::tempdir().unwrap();
    // Per table: (scenarios checked, values compared).
    let mut counts: BTreeMap<&str, (usize, usize)> = BTreeMap::new();
    for scenario in builtin::all().unwrap() {
        let summary = generate::generate(&scenario, dir.path()).unwrap();
        let transcript: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        let Some(check) = scenario.setup.sigrok(&transcript) else {
            continue;
        };
        let table = scenario.table();
        let registered = tbgen::registry::by_table(table).unwrap().sigrok_decoder;
        assert_eq!(
            registered,
            check.decoder.split(':').next(),
            "{}: the registry names the decoder its check runs",
            scenario.name
        );
        let decoded = run_sigrok(
            dir.path(),
            &summary.files[1],
            transcript["f_sys_hz"].as_u64().unwrap(),
            &check,
        );
        assert_eq!(
            decoded.len(),
            check.expected.len(),
            "{}: values sigrok found ({}) vs the model's",
            scenario.name,
            check.decoder
        );
        let count = counts.entry(table).or_default();
        for (i, (got, want)) in decoded.iter().zip(&check.expected).enumerate() {
            if let Some(want) = want {
                assert_eq!(
                    got, want,
                    "{} value {i}: sigrok ({}) vs the model",
                    scenario.name, check.decoder
                );
                count.1 += 1;
            }
        }
        count.0 += 1;
    }
    for p in PROTOCOLS.iter().filter(|p| p.sigrok_decoder.is_some()) {
        let (scenarios, values) = counts.get(p.table).copied().unwrap_or_default();
        println!(
            "{:<10} {scenarios:>3} scenarios, {values:>5} values compared with sigrok's {}",
            p.table,
            p.sigrok_decoder.unwrap()
        );
        let (min_scenarios, min_values) = p.sigrok_minimum;
        assert!(
            scenarios >= min_scenarios && values >= min_values,
            "{}: {scenarios} scenarios, {values} values checked",
            p.table
        );
    }
}

#[test]
fn sigrok_modbus_reads_the_fields_of_every_modbus_transcript() {
    // The independent check for Modbus: sigrok's `modbus` decoder
    // stacked on `uart`, the two directions apart, must find every good
    // read's register count, byte count and value, every exception code,
    // and a bad CRC wherever the master flagged one.
    let mut checked = 0;
    for scenario in builtin::all()
        .unwrap()
        .into_iter()
        .filter(|s| s.core() == "modbus_master")
    {
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&scenario, dir.path()).unwrap();
        let transcript: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        let cfg = scenario.setup.get::<model::modbus::BenchConfig>().unwrap();
        let parity = format!("{:?}", cfg.parity).to_lowercase();
        let scalars = dir.path().join("scalars.vcd");
        fs::write(
            &scalars,
            wave::scalars_only(&fs::read_to_string(&summary.files[1]).unwrap()),
        )
        .unwrap();
        let downsample = 1_000_000_000_000 / transcript["f_sys_hz"].as_u64().unwrap();
        let out = Command::new("sigrok-cli")
            .args([
                "-I",
                &format!("vcd:downsample={downsample}"),
                "-i",
                scalars.to_str().unwrap(),
            ])
            .args([
                "-P",
                &tbgen::modbus::sigrok_fields::decoder(cfg.baud as u64, &parity),
            ])
            .args(["-A", "modbus"])
            .output()
            .expect("sigrok-cli runs (make deps installs it)");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let lines: Vec<String> = String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .map(str::to_string)
            .collect();
        tbgen::modbus::sigrok_fields::check(&lines, transcript["transactions"].as_array().unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", scenario.name));
        checked += 1;
    }
    assert!(checked >= 2, "the Modbus scenarios were checked");
}

#[test]
fn sigrok_can_reads_the_frames_of_the_error_scenarios() {
    // The CAN scenarios with errors and overload frames, which the
    // check above leaves out. sigrok's `can` decoder reports no errors and
    // reads flags as frames, so each of its frames is matched to the
    // transaction starting at the same SOF (tbgen/src/can/sigrok_errors.rs).
    let mut total = tbgen::can::sigrok_errors::Counts::default();
    let mut scenarios = 0;
    for scenario in builtin::all()
        .unwrap()
        .into_iter()
        .filter(|s| s.core() == "can_controller")
    {
        let dir = tempfile::tempdir().unwrap();
        let summary = generate::generate(&scenario, dir.path()).unwrap();
        let transcript: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        if scenario.setup.sigrok(&transcript).is_some() {
            continue; // error-free: compared value by value above
        }
        let cfg = scenario.setup.get::<model::can::BenchConfig>().unwrap();
        let (decoder, bit, sample) = tbgen::can::sigrok_decoder(cfg).unwrap();
        let scalars = dir.path().join("scalars.vcd");
        fs::write(
            &scalars,
            wave::scalars_only(&fs::read_to_string(&summary.files[1]).unwrap()),
        )
        .unwrap();
        let downsample = 1_000_000_000_000 / transcript["f_sys_hz"].as_u64().unwrap();
        let out = Command::new("sigrok-cli")
            .args([
                "-I",
                &format!("vcd:downsample={downsample}"),
                "-i",
                scalars.to_str().unwrap(),
            ])
            .args(["-P", &decoder, "--protocol-decoder-samplenum"])
            .args(["-A", tbgen::can::sigrok_errors::ANNOTATIONS])
            .output()
            .expect("sigrok-cli runs (make deps installs it)");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let lines: Vec<String> = String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .map(str::to_string)
            .collect();
        let c = tbgen::can::sigrok_errors::check(
            &lines,
            transcript["transactions"].as_array().unwrap(),
            bit,
            sample,
            tbgen::can::within_timing_limits(cfg).unwrap(),
        )
        .unwrap_or_else(|e| panic!("{}: {e}", scenario.name));
        println!("{:<28} {:>3} frames {:>4} values, {:>3} cut frames' SOF, {:>3} missed while out of step, {:>3} flags read as frames", scenario.name, c.frames, c.values, c.cut, c.missed, c.flags);
        total.frames += c.frames;
        total.values += c.values;
        total.cut += c.cut;
        total.missed += c.missed;
        total.flags += c.flags;
        scenarios += 1;
    }
    println!("can errors: {scenarios} scenarios, {total:?}");
    assert!(
        scenarios >= 15 && total.frames >= 81 && total.values >= 404 && total.cut >= 13,
        "{scenarios} scenarios, {total:?}"
    );
}
