//! An independent decoder reads the line: sigrok-cli's SPI decoder, run on
//! the line-level signals of each SSI scenario's VCD at the encoder's pins,
//! must find exactly the bits the reader model sampled at its own pins. It
//! proves the waveform is decodable by a scalar-only reader, and that what
//! left the encoder is what the master decoded, cable and all. The `uart`
//! decoder does the same for the 10-bit frame protocols: on the shared
//! receiver's line, and on the line at the ESL and T-format hosts, where it
//! must find every character the transcript says was on the wire. Needs
//! sigrok-cli, which `make deps` installs.

use std::fs;
use std::process::Command;

use tbgen::{builtin, generate, wave};

#[test]
fn sigrok_reads_at_the_encoder_what_the_ssi_reader_sampled() {
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for scenario in builtin::all().unwrap().into_iter().filter(|s| s.core() == "ssi_master") {
        let summary = generate::generate(&scenario, dir.path()).unwrap();
        let transcript: serde_json::Value = serde_json::from_str(&fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        // One SPI word per read that clocked: the level at the storing edge
        // (the idle line, 1) followed by every sampled bit; and whether the
        // reader flagged the read (a fault injected between encoder and reader).
        let expected: Vec<(String, bool)> = transcript["transactions"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|t| {
                let bits = t["received_bits"].as_str().filter(|b| !b.is_empty())?;
                Some((format!("1{bits}"), t["errors"].as_array().unwrap().is_empty()))
            })
            .collect();
        let wordsize = expected[0].0.len();
        assert!(expected.iter().all(|(w, _)| w.len() == wordsize));

        let scalars = dir.path().join(format!("{}.scalars.vcd", scenario.name));
        fs::write(&scalars, wave::scalars_only(&fs::read_to_string(&summary.files[1]).unwrap())).unwrap();
        let f_sys_hz = transcript["f_sys_hz"].as_u64().unwrap();
        let downsample = 1_000_000_000_000 / f_sys_hz; // 1 ps timescale -> one sample per system clock
        let out = Command::new("sigrok-cli")
            .args(["-I", &format!("vcd:downsample={downsample}"), "-i", scalars.to_str().unwrap()])
            .args(["-P", &format!("spi:clk=ssi_clk_encoder:miso=ssi_data_encoder:cpol=1:cpha=0:wordsize={wordsize}")])
            .args(["-A", "spi=miso-data"])
            .output()
            .expect("sigrok-cli runs (make deps installs it)");
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let decoded: Vec<String> = String::from_utf8(out.stdout)
            .unwrap()
            .lines()
            .filter_map(|l| l.strip_prefix("spi-1: "))
            .map(|hex| format!("{:0wordsize$b}", u128::from_str_radix(hex.trim(), 16).unwrap()))
            .collect();
        assert_eq!(decoded.len(), expected.len(), "{}: reads", scenario.name);
        for (i, (got, (want, clean))) in decoded.iter().zip(&expected).enumerate() {
            if *clean {
                assert_eq!(got, want, "{} read {i}: sigrok at the encoder vs the reader's samples", scenario.name);
                checked += 1;
            }
        }
    }
    assert!(checked >= 25, "only {checked} reads checked");
}

#[test]
fn sigrok_uart_decodes_the_bytes_the_frame_receiver_received() {
    // Issue 5's independent check, on the shared receiver: sigrok's `uart`
    // decoder at the nominal rate must find the bytes the model received in
    // every scenario where the receiver got every byte right.
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for scenario in builtin::all().unwrap().into_iter().filter(|s| s.core() == "uart_rx") {
        let tbgen::scenario::Setup::Uart(cfg) = &scenario.setup else { unreachable!() };
        let summary = generate::generate(&scenario, dir.path()).unwrap();
        let transcript: serde_json::Value = serde_json::from_str(&fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        let events = transcript["transactions"].as_array().unwrap();
        let clean = events.iter().all(|e| e["kind"] == "byte" && e["received"] == e["sent"]);
        if !clean {
            continue;
        }
        let received: Vec<u64> = events.iter().map(|e| e["received"].as_u64().unwrap()).collect();
        let decoded = sigrok_uart_bytes(dir.path(), &summary, &transcript, "rx_line", cfg.baud as u64);
        assert_eq!(decoded, received, "{}: sigrok uart vs the model's receiver", scenario.name);
        checked += decoded.len();
    }
    assert!(checked >= 300, "only {checked} bytes checked");
}

#[test]
fn sigrok_uart_reads_at_the_tformat_host_every_request_and_answer_byte_of_the_transcript() {
    // Issue 5's independent check for T-format: sigrok's `uart` decoder at
    // 2.5 Mbps on the line at the host must find, in order, every character
    // the transcript says was on the wire: each request, then what followed
    // it (faults included: the transcript's wire bytes are read by a
    // receiver that never goes deaf, as sigrok never does).
    let (scenarios, checked) = check_wire_bytes_with_sigrok("tformat_host", |setup| match setup {
        tbgen::scenario::Setup::Tformat(cfg) => cfg.baud as u64,
        _ => unreachable!(),
    });
    assert!(scenarios >= 15 && checked >= 300, "{scenarios} scenarios, {checked} bytes checked");
}

#[test]
fn sigrok_uart_reads_on_the_esl_line_the_bytes_of_every_transcript() {
    // Issue 5's independent check for ESL: sigrok's `uart` decoder at
    // 10 Mbps on the line at the host must find, in order, every character
    // the transcript says was on the wire in EVERY scenario: each request,
    // then what followed it, faults included (bit flips, baud error, a second
    // driver, truncation, flipped requests). The transcript's wire bytes are
    // read by a receiver that never goes deaf and samples at the nominal
    // rate, as sigrok does; the host's own `sent`/`received` may differ
    // where the line does.
    let (scenarios, checked) = check_wire_bytes_with_sigrok("esl_host", |setup| match setup {
        tbgen::scenario::Setup::Esl(cfg) => cfg.baud as u64,
        _ => unreachable!(),
    });
    assert!(scenarios >= 13 && checked >= 1000, "{scenarios} scenarios, {checked} bytes checked");
}

/// What sigrok-cli's `uart` decoder reads on `line` (a scalar of the run's
/// VCD) at `baud`, one sample per system clock: the data bytes in order.
fn sigrok_uart_bytes(dir: &std::path::Path, summary: &generate::Summary, transcript: &serde_json::Value, line: &str, baud: u64) -> Vec<u64> {
    let scalars = dir.join("scalars.vcd");
    fs::write(&scalars, wave::scalars_only(&fs::read_to_string(&summary.files[1]).unwrap())).unwrap();
    let downsample = 1_000_000_000_000 / transcript["f_sys_hz"].as_u64().unwrap();
    let out = Command::new("sigrok-cli")
        .args(["-I", &format!("vcd:downsample={downsample}"), "-i", scalars.to_str().unwrap()])
        .args(["-P", &format!("uart:rx={line}:baudrate={baud}")])
        .args(["-A", "uart=rx-data"])
        .output()
        .expect("sigrok-cli runs (make deps installs it)");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("uart-1: "))
        .map(|hex| u64::from_str_radix(hex.trim(), 16).unwrap())
        .collect()
}

/// The bytes a transcript of a half-duplex host says were on the wire at the
/// host, in order: each request's `wire_requests`, then its `wire_answers`.
fn wire_bytes(name: &str, transcript: &serde_json::Value) -> Vec<u64> {
    let bytes = |set: &serde_json::Value| -> Vec<u64> { set.as_array().unwrap().iter().map(|b| b.as_u64().unwrap()).collect() };
    let mut expected = Vec::new();
    for t in transcript["transactions"].as_array().unwrap() {
        let (requests, answers) = (t["wire_requests"].as_array().unwrap(), t["wire_answers"].as_array().unwrap());
        assert_eq!(requests.len(), answers.len(), "{name}: one answer list per request");
        if let Some(sent) = t["requests"].as_u64() {
            assert_eq!(requests.len() as u64, sent, "{name}: one wire request per request sent");
        }
        for (request, answer) in requests.iter().zip(answers) {
            expected.extend(bytes(request));
            expected.extend(bytes(answer));
        }
    }
    expected
}

/// Runs every scenario of `core` and requires sigrok's bytes on the line at
/// the host to equal the transcript's wire bytes; returns (scenarios, bytes).
fn check_wire_bytes_with_sigrok(core: &str, baud: impl Fn(&tbgen::scenario::Setup) -> u64) -> (usize, usize) {
    let dir = tempfile::tempdir().unwrap();
    let (mut scenarios, mut checked) = (0, 0);
    for scenario in builtin::all().unwrap().into_iter().filter(|s| s.core() == core) {
        let summary = generate::generate(&scenario, dir.path()).unwrap();
        let transcript: serde_json::Value = serde_json::from_str(&fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
        let expected = wire_bytes(&scenario.name, &transcript);
        let decoded = sigrok_uart_bytes(dir.path(), &summary, &transcript, "line_at_host", baud(&scenario.setup));
        assert_eq!(decoded, expected, "{}: sigrok uart at the host vs the transcript's wire bytes", scenario.name);
        checked += decoded.len();
        scenarios += 1;
    }
    (scenarios, checked)
}
