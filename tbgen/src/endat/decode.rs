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
use crate::{Error, Result};

/// Decodes the clock and data scalars (`clk`, `data`: dotted paths of the master's pins) of a VCD file.
pub fn decode(path: &Path, clk: &str, data: &str, opts: &Options) -> Result<Vec<Transaction>> {
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
    model::endat::decode::decode(&signals[0], &signals[1], opts).map_err(Error::Decode)
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
            let decoded = decode(&summary.files[1], "top.line.endat_clk_master", "top.line.endat_data_master", &opts).unwrap();
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
            let _ = decode(&path, "top.line.endat_clk_master", "top.line.endat_data_master", &opts);
        }
    }

    #[test]
    fn a_missing_signal_is_named_with_the_option_that_fixes_it() {
        let dir = tempfile::tempdir().unwrap();
        let s = builtin::find("endat_pos21_1mhz").unwrap();
        let summary = generate::generate(&s, dir.path()).unwrap();
        let opts = Options { pos_bits: 25, meas_khz: None };
        let e = decode(&summary.files[1], "top.line.clk", "top.line.endat_data_master", &opts).unwrap_err().to_string();
        assert!(e.contains("top.line.clk") && e.contains("--clk") && e.contains(".vcd"), "{e}");
        let e = decode(&summary.files[1], "top.line.endat_clk_master", "top.endat_master.o_position", &opts).unwrap_err().to_string();
        assert!(e.contains("--data") && e.contains("bits wide"), "{e}");
    }
}
