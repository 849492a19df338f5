//! `tbgen decode endat`: the transactions of a captured EnDat waveform, read
//! at the master's pins (clock and data), in the shape of the `gen`
//! transcript.
//!
//! The decode core (bursts, mode bits, the master's judge of each frame) is
//! [`model::endat::decode`], shared with the co-simulation monitor
//! `endat_monitor`; what it reads and leaves out is described there.

use std::path::Path;

pub use model::endat::decode::{Options, Transaction};

use crate::capture;
use model::wire::Signal;
use crate::{Error, Result};

/// Decodes the clock and data scalars (`clk`, `data`: dotted paths of the master's pins) of a VCD file.
/// Without `opts.meas_khz`, a power-on delay measurement the capture opens
/// with ([`opening_measurement`]) is read at its own clock, and `notes` says so.
pub fn decode(path: &Path, clk: &str, data: &str, opts: &Options, notes: &mut Vec<String>) -> Result<Vec<Transaction>> {
    let range = model::endat::POSITION_BITS;
    if !range.contains(&opts.pos_bits) {
        return Err(Error::Decode(format!(
            "decode endat: --pos-bits {} is not {} to {}",
            opts.pos_bits,
            range.start(),
            range.end()
        )));
    }
    let signals = capture::read(path, &[(clk, "--clk"), (data, "--data")])?;
    let mut opts = opts.clone();
    if opts.meas_khz.is_none() {
        match opening_measurement(&signals[0], &signals[1]) {
            Some(m) if m.next_khz.is_none() => notes.push(format!(
                "decode endat: {}: every one of the capture's {} frames is mode 000111 at {:.0} kHz, the clock of a delay measurement (seed 2.1.2): read as pos21 reads; if they are the master's power-on measurement (nothing follows it), give --meas-khz {:.0}",
                path.display(),
                m.frames,
                m.khz,
                m.khz
            )),
            Some(m) => {
                notes.push(format!(
                "decode endat: {}: the capture opens with {} frames of mode 000111 at {:.0} kHz before transfers at {:.0} kHz: the master's power-on delay measurement (seed 2.1.2), read as such at --meas-khz {:.0}; give --meas-khz to set its clock",
                path.display(),
                    m.frames,
                    m.khz,
                    m.next_khz.unwrap_or_default(),
                    m.khz
                ));
                opts.meas_khz = Some(m.khz);
            }
            None => {}
        }
    }
    model::endat::decode::decode(&signals[0], &signals[1], &opts).map_err(Error::Decode)
}

/// A power-on delay measurement as a capture shows it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    /// Its clock, kHz (the first frame's, to the nearest kHz).
    pub khz: f64,
    /// Its frames.
    pub frames: usize,
    /// The clock of the first transfer after it, kHz (`None`: the capture
    /// holds nothing else, and may as well be `pos21` reads at that clock).
    pub next_khz: Option<f64>,
}

/// The delay measurement a capture opens with: a run of `000111` frames
/// (mode `pos21`) at a clock within the seed's measurement clock
/// (`model::endat::rules::MEAS_CLOCK`, 100 to 200 kHz, 3 % off it as the
/// decoder reads a measurement clock) followed by a transfer at a clock at
/// least twice as fast, or by nothing (then it may be `pos21` reads at that
/// clock as well). A capture that starts after the measurement shows none.
pub fn opening_measurement(clk: &Signal, data: &Signal) -> Option<Measurement> {
    use model::rules::Bound;
    let Bound::Within(lo, hi, _) = model::endat::rules::MEAS_CLOCK.bound else {
        return None;
    };
    let khz = |b: &model::endat::decode::Burst| b.period().map(|p| 1e9 / p.max(1) as f64);
    let bursts = model::endat::decode::bursts(clk);
    let in_range = |k: f64| k >= lo * 0.97 && k <= hi * 1.03;
    let run = bursts
        .iter()
        .take_while(|b| b.mode(data) == Some(model::endat::Command::Pos21.code()) && khz(b).is_some_and(in_range))
        .count();
    let first = khz(bursts.first()?)?;
    let next = match bursts.get(run) {
        None => None,
        Some(b) => Some(khz(b).filter(|&k| k >= 2.0 * first)?),
    };
    (run > 0).then_some(Measurement { khz: first.round(), frames: run, next_khz: next })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Setup;
    use crate::{builtin, generate};

    /// Errors only the master can see (see the module docs): a refused start has no clock burst, and
    /// `delay_drift` is judged against the delay inside the master.
    const REFUSED: [&str; 2] = ["line_not_idle", "not_calibrated"];

    #[test]
    fn decoding_the_waves_of_every_endat_scenario_gives_the_gen_transcript() {
        // Every field the decoder emits equals gen's field of the same name, faulty scenarios included.
        let dir = tempfile::tempdir().unwrap();
        let mut compared = 0;
        let mut scenarios = 0;
        let mut without_flag = 0;
        for s in builtin::all().unwrap() {
            let Setup::Endat(cfg) = &s.setup else { continue };
            scenarios += 1;
            let summary = generate::generate(&s, dir.path()).unwrap();
            let gen: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&summary.files[2]).unwrap()).unwrap();
            let measures = cfg.master.delay_comp || cfg.commands.iter().any(|c| c.measure);
            let opts = Options {
                pos_bits: cfg.encoder.singleturn_bits + cfg.encoder.multiturn_bits,
                meas_khz: measures.then_some(cfg.master.meas_clock_khz),
            };
            let decoded = decode(&summary.files[1], "top.line.endat_clk_master", "top.line.endat_data_master", &opts, &mut Vec::new()).unwrap();
            // Without --meas-khz: a master with delay compensation opens
            // with its measurement, found at its clock and said so; one
            // without reads the same with or without the flag.
            // A capture of nothing but measurement frames (a measurement
            // that never succeeds) could be pos21 reads at 200 kHz: it is
            // read as such, and the note names the flag.
            if cfg.master.delay_comp || !measures {
                let mut notes = Vec::new();
                let found = decode(&summary.files[1], "top.line.endat_clk_master", "top.line.endat_data_master", &Options { meas_khz: None, ..opts.clone() }, &mut notes).unwrap();
                let only = decoded.iter().all(|t| t.kind == "delay_measurement");
                if only {
                    assert!(notes.len() == 1 && notes[0].contains("give --meas-khz 200"), "{}: {notes:?}", s.name);
                } else {
                    assert_eq!(found, decoded, "{}: without --meas-khz", s.name);
                    assert_eq!(notes.len(), cfg.master.delay_comp as usize, "{}: {notes:?}", s.name);
                }
                without_flag += 1;
            }
            let expected: Vec<&serde_json::Value> = gen["transactions"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|t| !t["errors"].as_array().unwrap().iter().any(|e| REFUSED.contains(&e.as_str().unwrap())))
                .collect();
            assert_eq!(decoded.len(), expected.len(), "{}: decoded {decoded:#?}", s.name);
            for (i, (d, g)) in decoded.iter().zip(&expected).enumerate() {
                let d = serde_json::to_value(d).unwrap();
                for (key, value) in d.as_object().unwrap() {
                    // A data line stuck at the master's receiver hides the mode bits the master drives.
                    let stuck = cfg.faults.line.stuck_level.is_some() && g["request"].as_u64().is_some_and(|r| r as usize >= cfg.faults.line.stuck_from);
                    let want = if key == "start_ps" || (stuck && key == "mode") {
                        continue;
                    } else if key == "errors" {
                        let errors: Vec<&serde_json::Value> = g["errors"].as_array().unwrap().iter().filter(|e| *e != "delay_drift").collect();
                        serde_json::to_value(errors).unwrap()
                    } else {
                        g[key].clone()
                    };
                    assert_eq!(value, &want, "{} transaction {i}: field `{key}`\ndecoded {d:#}\ngen {g:#}", s.name);
                    compared += 1;
                }
            }
        }
        assert!(scenarios >= 24 && compared > 2000, "{scenarios} scenarios, {compared} fields");
        assert!(without_flag >= 20, "{without_flag} scenarios decoded without --meas-khz");
        println!("{scenarios} EnDat scenarios, {compared} decoded fields equal to gen's");
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
        #[test]
        fn any_clock_and_data_edges_decode_without_a_panic(
            changes in proptest::collection::vec((1u64..1 << 42, proptest::bool::ANY, proptest::bool::ANY), 0..400),
            scale in 0usize..3,
            pos_bits in 1u32..=48,
            meas in proptest::bool::ANY,
        ) {
            // A captured waveform can hold anything: random edges on both lines, random spacing.
            let dir = tempfile::tempdir().unwrap();
            let path = dir.path().join("random.vcd");
            let mut text = String::from("$timescale 1ps $end\n$scope module top $end\n$scope module line $end\n$var wire 1 ! endat_clk_master $end\n$var wire 1 \" endat_data_master $end\n$upscope $end\n$upscope $end\n$enddefinitions $end\n");
            let mut t = 0u64;
            for (step, on_clk, level) in changes {
                t += step >> [32, 20, 0][scale];
                text += &format!("#{t}\n{}{}\n", level as u8, if on_clk { '!' } else { '"' });
            }
            std::fs::write(&path, text).unwrap();
            let opts = Options { pos_bits, meas_khz: meas.then_some(200.0) };
            let _ = decode(&path, "top.line.endat_clk_master", "top.line.endat_data_master", &opts, &mut Vec::new());
        }
    }

    #[test]
    fn a_missing_signal_is_named_with_the_option_that_fixes_it() {
        let dir = tempfile::tempdir().unwrap();
        let s = builtin::find("endat_pos21_1mhz").unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let opts = Options { pos_bits: 25, meas_khz: None };
        let e = decode(&summary.files[1], "top.line.clk", "top.line.endat_data_master", &opts, &mut Vec::new()).unwrap_err().to_string();
        assert!(e.contains("top.line.clk") && e.contains("--clk") && e.contains(".vcd"), "{e}");
        let e = decode(&summary.files[1], "top.line.endat_clk_master", "top.endat_master.o_position", &opts, &mut Vec::new()).unwrap_err().to_string();
        assert!(e.contains("--data") && e.contains("bits wide"), "{e}");
    }
}
