//! Logic-analyser captures of our own waves, read by every decoder.
//!
//! For every protocol with a decoder, the smallest committed VCD of its core
//! that decodes to two or more transactions with the decoder's defaults is
//! turned into what a logic analyser would have saved: a sigrok session
//! (`.sr`, converted by sigrok-cli, which `make deps` installs) and
//! sigrok-cli's CSV exports of it, a Saleae
//! Logic 2 CSV (one row per change, channels `Channel 0`.., read with
//! `--map`) and a sigrok-cli CSV (one row per sample), sampled on the VCD's
//! own time grid (every edge where it was), at just enough rate and too low
//! a rate, with glitches, starting mid-frame, and cut short. What the
//! decoder reads from each is held to what it reads from the VCD.

use std::path::{Path, PathBuf};
use std::process::Command;

use model::wire::Signal;
use serde_json::Value;
use tbgen::registry::Entry;

/// Samples a line's median pulse must span (the reader's rule, restated:
/// the tests sample at exactly this and at half of it).
const ENOUGH: u64 = 4;

/// One protocol's capture, read from its VCD.
struct Case {
    p: &'static Entry,
    vcd: PathBuf,
    /// `(long option, default dotted path)` of each line the decoder reads.
    lines: Vec<(String, String)>,
    signals: Vec<Signal>,
    /// The VCD's transactions, as the decoder reads them.
    transactions: Vec<Value>,
    /// The time grid of the VCD: every change is a multiple of it.
    grid_ps: u64,
}

fn decoders() -> Vec<&'static Entry> {
    let all: Vec<_> = tbgen::PROTOCOLS
        .iter()
        .filter(|p| (p.decode_command)().is_some())
        .collect();
    assert!(all.len() >= 9, "{} decoders", all.len());
    all
}

/// `tbgen decode <table> <path> <args>`, in-process.
fn decode(p: &Entry, path: &Path, args: &[String]) -> Result<Value, String> {
    let argv = [p.table.to_string(), path.display().to_string()]
        .into_iter()
        .chain(args.iter().cloned());
    let m = (p.decode_command)()
        .unwrap()
        .try_get_matches_from(argv)
        .map_err(|e| e.to_string())?;
    (p.decode)(&m)
        .map(|s| serde_json::from_str(&s).unwrap())
        .map_err(|e| e.to_string())
}

/// A decoder's transactions (CAN's and CANopen's: `frames`).
fn transactions(v: &Value) -> Vec<Value> {
    v.get("transactions")
        .or_else(|| v.get("frames"))
        .and_then(Value::as_array)
        .unwrap()
        .clone()
}

/// The decoder's line options: those whose default is a signal of the
/// waveform's `top.line` scope.
fn line_options(p: &Entry) -> Vec<(String, String)> {
    (p.decode_command)()
        .unwrap()
        .get_arguments()
        .filter_map(|a| {
            let d = a.get_default_values().first()?.to_str()?.to_string();
            d.starts_with("top.line.")
                .then(|| (a.get_long().unwrap().to_string(), d))
        })
        .collect()
}

fn case(p: &'static Entry) -> Case {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../vectors")
        .join(p.core);
    let mut vcds: Vec<(u64, PathBuf)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|f| f.extension().is_some_and(|x| x == "vcd"))
        .map(|f| (std::fs::metadata(&f).unwrap().len(), f))
        .collect();
    vcds.sort();
    let lines = line_options(p);
    assert!(!lines.is_empty(), "{}: no line options", p.table);
    for (_, vcd) in vcds {
        let Ok(t) = decode(p, &vcd, &[]) else {
            continue;
        };
        let transactions = transactions(&t);
        if transactions.len() < 2 {
            continue;
        }
        let names: Vec<(String, String)> = lines
            .iter()
            .map(|(l, d)| (d.clone(), format!("--{l}")))
            .collect();
        let names: Vec<(&str, &str)> = names
            .iter()
            .map(|(d, o)| (d.as_str(), o.as_str()))
            .collect();
        let signals = tbgen::capture::read(&vcd, &names).unwrap();
        let grid_ps = signals
            .iter()
            .flat_map(|s| &s.changes)
            .fold(0, |g, &(t, _)| gcd(g, t));
        return Case {
            p,
            vcd,
            lines,
            signals,
            transactions,
            grid_ps,
        };
    }
    panic!(
        "{}: no committed VCD decodes to two transactions with the defaults",
        p.table
    );
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// The shortest median pulse (time between two edges) of the case's lines.
fn fastest_median_ps(c: &Case) -> u64 {
    c.signals
        .iter()
        .filter_map(|s| {
            let mut w: Vec<u64> = s
                .changes
                .windows(2)
                .skip(1)
                .map(|w| w[1].0 - w[0].0)
                .collect();
            w.sort();
            w.get(w.len().saturating_sub(1) / 2).copied()
        })
        .min()
        .unwrap()
}

/// The levels of every line, sampled every `period_ps` from 0 to past the
/// last change, as `(sample, levels)` at the first sample and at each sample
/// where a level differs from the one before; a glitch `(line, sample)`
/// inverts one line for that one sample.
fn sample(c: &Case, period_ps: u64, glitches: &[(usize, u64)]) -> Vec<(u64, Vec<bool>)> {
    let mut at: Vec<u64> = c
        .signals
        .iter()
        .flat_map(|s| &s.changes)
        .map(|&(t, _)| t.div_ceil(period_ps))
        .collect();
    at.extend(glitches.iter().flat_map(|&(_, k)| [k, k + 1]));
    at.push(0);
    let end = *at.iter().max().unwrap() + 10;
    at.push(end);
    at.sort();
    at.dedup();
    let mut rows: Vec<(u64, Vec<bool>)> = Vec::new();
    for k in at {
        let levels: Vec<bool> = c
            .signals
            .iter()
            .enumerate()
            .map(|(i, s)| s.level_at(k * period_ps) ^ glitches.contains(&(i, k)))
            .collect();
        if rows.last().is_none_or(|(_, l)| *l != levels) || k == end {
            rows.push((k, levels));
        }
    }
    rows
}

/// A Saleae Logic 2 export: `Time [s],Channel 0,...`, a row per change.
fn saleae_csv(path: &Path, rows: &[(u64, Vec<bool>)], period_ps: u64) {
    let n = rows[0].1.len();
    let mut text = format!(
        "Time [s],{}\n",
        (0..n)
            .map(|i| format!("Channel {i}"))
            .collect::<Vec<_>>()
            .join(",")
    );
    for (k, levels) in rows {
        let ps = k * period_ps;
        text += &format!(
            "{}.{:012},{}\n",
            ps / 1_000_000_000_000,
            ps % 1_000_000_000_000,
            bits(levels)
        );
    }
    std::fs::write(path, text).unwrap();
}

/// A sigrok-cli `-O csv` export: comments, the channel names, a row per sample.
fn sigrok_csv(path: &Path, c: &Case, rows: &[(u64, Vec<bool>)], period_ps: u64) {
    let names: Vec<&str> = c
        .lines
        .iter()
        .map(|(_, d)| d.rsplit('.').next().unwrap())
        .collect();
    let mut text = format!(
        "; CSV generated by libsigrok 0.5.2\n; Channels ({0}/{0}): {1}\n; Samplerate: {2} Hz\n{3}\n",
        names.len(),
        names.join(", "),
        1_000_000_000_000 / period_ps,
        names.iter().map(|_| "logic").collect::<Vec<_>>().join(",")
    );
    for w in rows.windows(2) {
        for _ in w[0].0..w[1].0 {
            text += &bits(&w[0].1);
            text.push('\n');
        }
    }
    text += &bits(&rows.last().unwrap().1);
    text.push('\n');
    std::fs::write(path, text).unwrap();
}

fn bits(levels: &[bool]) -> String {
    levels
        .iter()
        .map(|&l| if l { "1" } else { "0" })
        .collect::<Vec<_>>()
        .join(",")
}

/// `--map line=Channel i` for each line, in the order of `c.lines`.
fn channel_map(c: &Case) -> Vec<String> {
    let pairs: Vec<String> = c
        .lines
        .iter()
        .enumerate()
        .map(|(i, (l, _))| format!("{l}=Channel {i}"))
        .collect();
    vec!["--map".into(), pairs.join(",")]
}

/// The capture of `c` converted to a sigrok session by sigrok-cli, one
/// sample per grid step.
fn sigrok_session(c: &Case, dir: &Path) -> PathBuf {
    let scalars = dir.join(format!("{}_scalars.vcd", c.p.table));
    std::fs::write(
        &scalars,
        tbgen::wave::scalars_only(&std::fs::read_to_string(&c.vcd).unwrap()),
    )
    .unwrap();
    let sr = dir.join(format!("{}.sr", c.p.table));
    let out = Command::new("sigrok-cli")
        .args(["-I", &format!("vcd:downsample={}", c.grid_ps), "-i"])
        .arg(&scalars)
        .arg("-o")
        .arg(&sr)
        .output()
        .expect("sigrok-cli runs (make deps installs it)");
    assert!(
        out.status.success() && sr.exists(),
        "{}: sigrok-cli: {}",
        c.p.table,
        String::from_utf8_lossy(&out.stderr)
    );
    sr
}

/// `tbgen check <table> --expect <the VCD's transcript> <capture> -- args`.
fn check(c: &Case, dir: &Path, capture: &Path, args: &[String]) -> tbgen::check::Report {
    let expect = dir.join(format!("{}_expect.json", c.p.table));
    let key = if c.p.table.starts_with("can") {
        "frames"
    } else {
        "transactions"
    };
    std::fs::write(
        &expect,
        serde_json::to_string(&serde_json::json!({ key: c.transactions })).unwrap(),
    )
    .unwrap();
    tbgen::check::check(c.p.table, &expect, capture, args, None).unwrap()
}

/// A transaction without what moves when the capture starts later: its
/// index and its absolute times.
fn untimed(t: &Value) -> Value {
    let mut t = t.clone();
    if let Some(o) = t.as_object_mut() {
        o.retain(|k, _| k != "index" && !k.ends_with("_ps"));
    }
    t
}

#[test]
fn a_sigrok_session_converted_from_each_decoders_wave_decodes_as_the_wave() {
    let dir = tempfile::tempdir().unwrap();
    for p in decoders() {
        let c = case(p);
        let sr = sigrok_session(&c, dir.path());
        let got = decode(p, &sr, &[]).unwrap_or_else(|e| panic!("{}: {e}", p.table));
        assert_eq!(
            transactions(&got),
            c.transactions,
            "{}: {} as .sr",
            p.table,
            c.vcd.display()
        );
        let r = check(&c, dir.path(), &sr, &[]);
        assert!(r.ok, "{}: {}", p.table, r.text);
        // sigrok-cli's own CSV of the session: a row per sample, timed by
        // its sample rate, reads the very same; a row per change reads the
        // same but for the times (its time column is in whole units of its
        // choosing, nanoseconds at these rates: 12.5 ns samples are cut).
        for (options, timed) in [("csv", true), ("csv:time=true:dedup=true", false)] {
            let csv = dir.path().join(format!("{}_sigrok_cli.csv", p.table));
            let out = Command::new("sigrok-cli")
                .arg("-i")
                .arg(&sr)
                .args(["-O", options, "-o"])
                .arg(&csv)
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            let got =
                decode(p, &csv, &[]).unwrap_or_else(|e| panic!("{} -O {options}: {e}", p.table));
            let (got, want): (Vec<Value>, Vec<Value>) = match timed {
                true => (transactions(&got), c.transactions.clone()),
                false => (
                    transactions(&got).iter().map(untimed).collect(),
                    c.transactions.iter().map(untimed).collect(),
                ),
            };
            assert_eq!(got, want, "{}: sigrok-cli -O {options}", p.table);
        }
    }
}

#[test]
fn csv_exports_decode_as_the_wave_on_its_grid_and_at_just_enough_rate() {
    let dir = tempfile::tempdir().unwrap();
    for p in decoders() {
        let c = case(p);
        // Every edge where the VCD has it: the very same transactions, times and all.
        let csv = dir.path().join(format!("{}_saleae.csv", p.table));
        saleae_csv(&csv, &sample(&c, c.grid_ps, &[]), c.grid_ps);
        let got = decode(p, &csv, &channel_map(&c)).unwrap_or_else(|e| panic!("{}: {e}", p.table));
        assert_eq!(
            transactions(&got),
            c.transactions,
            "{}: Saleae CSV on the grid",
            p.table
        );
        // The transcript names the channel each line was read from.
        if let Some(signals) = got.get("signals").and_then(Value::as_object) {
            let mut named: Vec<&str> = signals.values().map(|v| v.as_str().unwrap()).collect();
            named.sort();
            let channels: Vec<String> =
                (0..c.lines.len()).map(|i| format!("Channel {i}")).collect();
            assert_eq!(named, channels, "{}: {signals:?}", p.table);
        }
        // Four samples to the fastest line's median pulse: the same transactions, times aside.
        let enough = fastest_median_ps(&c) / ENOUGH;
        let csv = dir.path().join(format!("{}_sigrok.csv", p.table));
        sigrok_csv(&csv, &c, &sample(&c, enough, &[]), enough);
        let r = check(&c, dir.path(), &csv, &[]);
        assert!(r.ok, "{}: sampled every {enough} ps: {}", p.table, r.text);
    }
}

#[test]
fn a_capture_sampled_too_slowly_is_refused_with_the_rate_it_needs() {
    let dir = tempfile::tempdir().unwrap();
    for p in decoders() {
        let c = case(p);
        let slow = fastest_median_ps(&c) / 2;
        let csv = dir.path().join(format!("{}_slow.csv", p.table));
        saleae_csv(&csv, &sample(&c, slow, &[]), slow);
        let e = decode(p, &csv, &channel_map(&c)).unwrap_err();
        assert!(
            e.contains(&format!("{}: sampled at", csv.display()))
                && e.contains("too slowly for line")
                && e.contains("or faster"),
            "{}: {e}",
            p.table
        );
    }
}

#[test]
fn glitches_shorter_than_a_bit_on_the_lines_into_the_master_change_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mut glitched = Vec::new();
    for p in decoders() {
        let c = case(p);
        // A one-sample spike in the middle of every stretch longer than a
        // character (12 pulses) at the level the line opened with (idle) on
        // each line the encoder drives; not on the master's clock or driver
        // enable, where an edge is a real event, nor on a line held at the
        // other level (a UART line held low reads a spike as a start bit).
        // Where a clock samples the data, a spike on the data in the middle
        // of every fifth half period of the clock, between two of its edges.
        let mut glitches = Vec::new();
        let bit = fastest_median_ps(&c);
        let clock = c
            .lines
            .iter()
            .position(|(l, _)| ["clk", "ma"].contains(&l.as_str()));
        // Sampled at an eighth of a pulse or finer, on the VCD's grid (a
        // line whose edges are all on bit boundaries has a grid of a bit).
        let period = c.grid_ps / (8 * c.grid_ps).div_ceil(bit);
        for (i, (l, _)) in c.lines.iter().enumerate() {
            if ["clk", "ma", "tx-en"].contains(&l.as_str()) {
                continue;
            }
            // Few enough that the line's own pulses stay the most (a line of
            // mostly spikes is a line sampled too slowly).
            let most = c.signals[i].changes.len() / 8;
            let mut spots = Vec::new();
            let changes = &c.signals[clock.unwrap_or(i)].changes;
            for (j, w) in changes.windows(2).enumerate().skip(1) {
                let quiet = match clock {
                    Some(_) => j % 5 == 0 && w[1].0 - w[0].0 <= bit * 3 / 2,
                    None => w[0].1 == changes[0].1 && w[1].0 - w[0].0 > 12 * bit,
                };
                if quiet {
                    spots.push((i, (w[0].0 + w[1].0) / 2 / period));
                }
            }
            let every = spots.len().div_ceil(most.max(1)).max(1);
            glitches.extend(spots.into_iter().step_by(every).take(most));
        }
        glitched.push(format!("{} {}", p.table, glitches.len()));
        let csv = dir.path().join(format!("{}_glitch.csv", p.table));
        saleae_csv(&csv, &sample(&c, period, &glitches), period);
        let got = decode(p, &csv, &channel_map(&c)).unwrap_or_else(|e| panic!("{}: {e}", p.table));
        assert_eq!(
            transactions(&got),
            c.transactions,
            "{}: {} glitches of {period} ps",
            p.table,
            glitches.len()
        );
    }
    println!("glitches per decoder: {}", glitched.join(", "));
    assert!(
        glitched.iter().filter(|g| !g.ends_with(" 0")).count() >= 7,
        "{glitched:?}"
    );
}

#[test]
fn a_capture_that_starts_mid_frame_reads_the_frames_after_it() {
    let dir = tempfile::tempdir().unwrap();
    for p in decoders() {
        let c = case(p);
        // Cut just after the first edge inside the first transaction.
        let start = c.transactions[0]["start_ps"].as_u64().unwrap_or(0);
        let cut = c
            .signals
            .iter()
            .flat_map(|s| &s.changes)
            .map(|&(t, _)| t)
            .filter(|&t| t > start)
            .min()
            .unwrap()
            + c.grid_ps;
        let rows = sample(&c, c.grid_ps, &[]);
        let k0 = cut / c.grid_ps;
        let mut cut_rows: Vec<(u64, Vec<bool>)> =
            vec![(k0, c.signals.iter().map(|s| s.level_at(cut)).collect())];
        cut_rows.extend(rows.into_iter().filter(|(k, _)| *k > k0));
        let csv = dir.path().join(format!("{}_mid.csv", p.table));
        saleae_csv(&csv, &cut_rows, c.grid_ps);
        let got = transactions(
            &decode(p, &csv, &channel_map(&c)).unwrap_or_else(|e| panic!("{}: {e}", p.table)),
        );
        let rest: Vec<Value> = c.transactions[1..].iter().map(untimed).collect();
        assert!(
            got.len() == rest.len() || got.len() == rest.len() + 1,
            "{}: {} transactions after the cut at {cut} ps, {} expected: {got:?}\n{rest:?}",
            p.table,
            got.len(),
            rest.len()
        );
        let tail: Vec<Value> = got[got.len() - rest.len()..].iter().map(untimed).collect();
        assert_eq!(tail, rest, "{}: the frames after the cut", p.table);
    }
}

#[test]
fn a_cut_short_capture_is_refused_with_the_file_and_the_byte() {
    let dir = tempfile::tempdir().unwrap();
    let p = tbgen::registry::by_table("ssi").unwrap();
    let c = case(p);
    let sr = sigrok_session(&c, dir.path());
    let bytes = std::fs::read(&sr).unwrap();
    let cut = dir.path().join("cut.sr");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let e = decode(p, &cut, &[]).unwrap_err();
    assert!(
        e.starts_with(&format!("{}: byte {}", cut.display(), bytes.len() / 2))
            && e.contains("cut short"),
        "{e}"
    );
    // Whole, but the samples damaged: the chunk's CRC (or its deflate
    // stream) refuses them, with the byte where the chunk's data starts.
    let chunk = bytes.windows(9).position(|w| w == b"logic-1-1").unwrap() + 9 + 8;
    let mut damaged = bytes.clone();
    for b in &mut damaged[chunk..chunk + 16] {
        *b ^= 0x5A;
    }
    let bad = dir.path().join("damaged.sr");
    std::fs::write(&bad, &damaged).unwrap();
    let e = decode(p, &bad, &[]).unwrap_err();
    assert!(
        e.starts_with(&format!("{}: byte ", bad.display()))
            && e.contains("chunk `logic-1-1`")
            && e.contains("damaged"),
        "{e}"
    );
    let csv = dir.path().join("cut.csv");
    saleae_csv(&csv, &sample(&c, c.grid_ps, &[]), c.grid_ps);
    let text = std::fs::read_to_string(&csv).unwrap();
    let half = text.len() / 2;
    std::fs::write(&csv, &text[..half]).unwrap();
    let e = decode(p, &csv, &channel_map(&c)).unwrap_err();
    let line_start = text[..half].rfind('\n').unwrap() + 1;
    let line = text[..half].matches('\n').count() + 1;
    assert_eq!(e, format!("{}:{line}: byte {line_start}: the last row ends without a line break: the file is cut short; export the capture again", csv.display()));
}

#[test]
fn a_misnamed_channel_lists_the_channels_present() {
    let dir = tempfile::tempdir().unwrap();
    let p = tbgen::registry::by_table("ssi").unwrap();
    let c = case(p);
    let csv = dir.path().join("named.csv");
    saleae_csv(&csv, &sample(&c, c.grid_ps, &[]), c.grid_ps);
    let e = decode(p, &csv, &["--map".into(), "clk=Channel 0,data=D1".into()]).unwrap_err();
    assert_eq!(e, format!("{}: no channel `D1` for --data; the capture's channels: Channel 0, Channel 1; name one with --data <channel> or --map data=<channel>", csv.display()));
    let sr = sigrok_session(&c, dir.path());
    let e = decode(p, &sr, &[])
        .map(|_| ())
        .and_then(|_| decode(p, &sr, &["--clk".into(), "D0".into()]).map(|_| ()))
        .unwrap_err();
    assert!(
        e.contains("no channel `D0` for --clk; the capture's channels: ssi_clk_master, "),
        "{e}"
    );
}

/// The lines of `c` as GTKWave hands a Combine Down group of them to a
/// Transaction Filter Process (gtkwave's vcd_saver.c, the docs' example):
/// the `$comment` header, one `$var` per line numbered from 1 under its
/// scopes, the changes, `$comment data_end`.
fn gtkwave_block(c: &Case, id: &str) -> String {
    let mut text = format!(
        "$comment data_start {id} $end\n$comment name #{{{}}} $end\n$timescale 1ps $end\n$comment min_time 0 $end\n$comment max_time {} $end\n$comment max_seqn {} $end\n$scope module top $end\n$scope module line $end\n",
        c.lines.iter().map(|(_, d)| d.as_str()).collect::<Vec<_>>().join(" "),
        c.signals.iter().flat_map(|s| s.changes.last()).map(|&(t, _)| t).max().unwrap(),
        c.lines.len()
    );
    for (i, (_, d)) in c.lines.iter().enumerate() {
        text += &format!(
            "$comment seqn {} {d} $end\n$var wire 1 {} {} $end\n",
            i + 1,
            i + 1,
            d.rsplit('.').next().unwrap()
        );
    }
    text += "$upscope $end\n$upscope $end\n$enddefinitions $end\n#0\n$dumpvars\n";
    let mut changes: Vec<(u64, usize, bool)> = c
        .signals
        .iter()
        .enumerate()
        .flat_map(|(i, s)| s.changes.iter().map(move |&(t, l)| (t, i, l)))
        .collect();
    changes.sort();
    let mut now = 0;
    for (k, (t, i, l)) in changes.into_iter().enumerate() {
        if t != now {
            text += &format!("{}#{t}\n", if now == 0 && k > 0 { "$end\n" } else { "" });
            now = t;
        }
        text += &format!("{}{}\n", l as u8, i + 1);
    }
    text + &format!("$comment data_end {id} $end\n")
}

/// GTKWave's side of the filter: a block written, the trace read back to
/// `$finish` before the next block (a filter that waits for more input, or
/// does not flush, hangs GTKWave: so does this test, up to its timeout).
fn gtkwave_exchange(table: &str, args: &[&str], blocks: &[String]) -> Vec<String> {
    use std::io::{BufRead, BufReader, Write};
    let mut child = Command::new(env!("CARGO_BIN_EXE_tbgen"))
        .args(["gtkwave-filter", table])
        .args(args)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    let watchdog = std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_secs(60));
        let _ = Command::new("kill").arg(pid.to_string()).status();
    });
    let mut stdin = child.stdin.take().unwrap();
    let mut stdout = BufReader::new(child.stdout.take().unwrap());
    let mut traces = Vec::new();
    for b in blocks {
        stdin.write_all(b.as_bytes()).unwrap();
        stdin.flush().unwrap();
        let mut trace = String::new();
        loop {
            let mut line = String::new();
            assert!(
                stdout.read_line(&mut line).unwrap() > 0,
                "the filter ended before $finish: {trace}"
            );
            trace += &line;
            if line == "$finish\n" {
                break;
            }
        }
        traces.push(trace);
    }
    drop(stdin);
    assert!(child.wait().unwrap().success());
    drop(watchdog);
    traces
}

#[test]
fn the_gtkwave_filter_answers_each_block_with_the_decoded_frames_at_their_times() {
    for table in ["ssi", "can"] {
        let c = case(tbgen::registry::by_table(table).unwrap());
        let blocks = [gtkwave_block(&c, "0x1"), gtkwave_block(&c, "0x2")];
        let traces = gtkwave_exchange(table, &[], &blocks);
        assert_eq!(
            traces[0], traces[1],
            "{table}: the same block, the same trace"
        );
        let lines: Vec<&str> = traces[0].lines().collect();
        assert_eq!(
            lines[..2],
            [format!("$name {table} (tbgen)").as_str(), "#0"],
            "{table}"
        );
        // One labelled line per transaction, at its start, in ps (the block's timescale).
        let labelled: Vec<&str> = lines
            .iter()
            .copied()
            .filter(|l| l.starts_with('#') && l.contains(' '))
            .collect();
        assert_eq!(
            labelled.len(),
            c.transactions.len(),
            "{table}: {}",
            traces[0]
        );
        for (l, t) in labelled.iter().zip(&c.transactions) {
            let start = t.get("start_ps").or_else(|| t.get("sof_ps")).unwrap();
            assert!(l.starts_with(&format!("#{start} ")), "{table}: {l} for {t}");
            let errors = t
                .get("errors")
                .and_then(Value::as_array)
                .is_some_and(|e| !e.is_empty())
                || t.get("error").is_some_and(|e| !e.is_null());
            assert_eq!(l.contains(" ?red?"), errors, "{table}: {l} for {t}");
        }
    }
    let c = case(tbgen::registry::by_table("ssi").unwrap());
    let ssi = gtkwave_exchange("ssi", &["--bits", "13"], &[gtkwave_block(&c, "0x3")]);
    assert!(
        ssi[0].starts_with("$name ssi (tbgen)\n#0 ?red?")
            && ssi[0].contains("--bits 13")
            && ssi[0].ends_with("\n$finish\n"),
        "{}",
        ssi[0]
    );
}

/// GTKWave itself (headless, under xvfb-run, driven by Tcl) runs the filter
/// on a saved layout that groups the SSI lines under a Transaction Filter
/// Process (`^<1` and the flags word with TR_TTRANSLATED, bit 28, as
/// GTKWave's savefile writes them) and shows each read's position on the
/// trace beside the lines, and nothing between reads.
#[test]
fn gtkwave_shows_the_decoded_frames_beside_the_lines() {
    let dir = tempfile::tempdir().unwrap();
    let c = case(tbgen::registry::by_table("ssi").unwrap());
    let filter = dir.path().join("ssi-frames.sh");
    std::fs::write(
        &filter,
        format!(
            "#!/bin/sh\nexec '{}' gtkwave-filter ssi\n",
            env!("CARGO_BIN_EXE_tbgen")
        ),
    )
    .unwrap();
    let mut mode = std::fs::metadata(&filter).unwrap().permissions();
    std::os::unix::fs::PermissionsExt::set_mode(&mut mode, 0o755);
    std::fs::set_permissions(&filter, mode).unwrap();
    let lines: Vec<&str> = c.lines.iter().map(|(_, d)| d.as_str()).collect();
    let gtkw = dir.path().join("frames.gtkw");
    std::fs::write(
        &gtkw,
        format!(
            "[dumpfile] \"{}\"\n@28\n{}\n@10000028\n^<1 {}\n#{{ssi_frames}} {}\n",
            c.vcd.canonicalize().unwrap().display(),
            lines.join("\n"),
            filter.display(),
            lines.join(" ")
        ),
    )
    .unwrap();
    // A marker inside each read, and one after the last read's end.
    let mut at: Vec<(u64, Option<u64>)> = c
        .transactions
        .iter()
        .map(|t| (t["start_ps"].as_u64().unwrap() + 1, t["position"].as_u64()))
        .collect();
    at.push((
        c.transactions.last().unwrap()["end_ps"].as_u64().unwrap() + 1,
        None,
    ));
    let mut tcl = String::new();
    for (k, (t, _)) in at.iter().enumerate() {
        tcl += &format!("gtkwave::setMarker {t}\nputs \"at {k}: [gtkwave::getTraceValueAtMarkerFromIndex 2]\"\n");
    }
    tcl += "puts \"trace: [gtkwave::getTraceNameFromIndex 2]\"\ngtkwave::/File/Quit\n";
    let script = dir.path().join("q.tcl");
    std::fs::write(&script, tcl).unwrap();
    let out = Command::new("timeout")
        .args(["120", "xvfb-run", "-a", "gtkwave", "-S"])
        .arg(&script)
        .arg(&gtkw)
        .output()
        .expect("xvfb-run and gtkwave run (make deps installs them)");
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(text.contains("trace: ssi (tbgen)"), "{text}");
    for (k, (_, position)) in at.iter().enumerate() {
        let shown = text
            .lines()
            .find_map(|l| l.strip_prefix(&format!("at {k}: ")))
            .unwrap_or_else(|| panic!("no answer {k}: {text}"));
        match position {
            Some(p) => assert!(
                shown
                    .split_whitespace()
                    .any(|w| w == format!("position={p}")),
                "read {k}: `{shown}`"
            ),
            None => assert_eq!(shown.trim(), "", "after the last read"),
        }
    }
}
