//! The CAN scenario families, each held to what its name says
//! (`cargo test -p tbgen can::families`): the model's transcript of every
//! built-in CAN scenario, run here, must show the behaviour the scenario
//! exists for. The RTL replays the same vectors, so the core is held to it too.

#[cfg(test)]
mod tests {
    use crate::builtin;
    use crate::scenario::Setup;
    use model::can::{BenchConfig, Transaction};

    fn run(name: &str) -> (BenchConfig, Vec<Transaction>) {
        let s = builtin::find(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        let Setup::Can(cfg) = &s.setup else { panic!("{name} is not a CAN scenario") };
        let run = model::testbench::run_to_end(model::Setup::bench(cfg).unwrap());
        (cfg.clone(), run.transactions)
    }

    fn outcomes(t: &[Transaction]) -> Vec<&'static str> {
        t.iter().map(|t| t.outcome).collect()
    }

    fn clean(t: &[Transaction]) -> bool {
        t.iter().all(|t| (t.outcome == "tx_done" || t.outcome == "rx_valid") && t.errors.is_empty() && t.tec == 0 && t.rec == 0)
    }

    #[test]
    fn every_bit_rate_of_the_gateway_sends_and_receives_cleanly() {
        for kbps in [10, 20, 50, 125, 250, 500, 800, 1000] {
            let (cfg, t) = run(&format!("can_rate_{kbps}k"));
            assert_eq!(cfg.timing.bit_rate_kbps, kbps as f64);
            assert!(clean(&t) && t.iter().any(|t| t.outcome == "tx_done") && t.iter().any(|t| t.outcome == "rx_valid"), "{kbps}k: {:?}", outcomes(&t));
            // Heavy stuffing (runs of 0x00 / 0xFF) and a remote frame.
            assert!(t.iter().any(|t| t.data.iter().all(|&b| b == 0) && t.data.len() == 8), "{kbps}k: a frame of eight 0x00");
            assert!(t.iter().any(|t| t.rtr), "{kbps}k: a remote frame");
        }
        let points: std::collections::BTreeSet<u64> = builtin::all().unwrap().iter().filter_map(|s| s.setup.get::<BenchConfig>()).map(|c| (c.bit_timing().unwrap().sample_point() * 1e4).round() as u64).collect();
        assert!(points.len() >= 4, "several sample points: {points:?}");
    }

    #[test]
    fn the_longest_bus_of_each_timing_arbitrates_cleanly_and_a_longer_one_does_not() {
        for name in ["can_bus_longest", "can_bus_longest_10k", "can_bus_longest_500k", "can_bus_longest_1000k"] {
            let (cfg, t) = run(name);
            assert!(super::super::within_timing_limits(&cfg).unwrap(), "{name} is within the limits");
            let far = cfg.nodes.iter().map(|n| n.position_m).fold(0.0, f64::max);
            let bt = cfg.bit_timing().unwrap();
            let longest = bt.max_bus_length_m(40_000_000, cfg.dut.loop_delay_ns + cfg.sync_stages as f64 * 25.0, cfg.ns_per_m);
            assert!(far <= longest && far >= longest - 1.0, "{name}: {far} m is the longest bus ({longest:.1} m)");
            assert_eq!(outcomes(&t), ["rx_valid", "tx_done"], "{name}: the far node wins arbitration, then the core sends");
            assert!(clean(&t) && t[0].arb_lost, "{name}: the core lost arbitration in the first frame");
        }
        let (cfg, t) = run("can_bus_too_long");
        assert!(!super::super::within_timing_limits(&cfg).unwrap());
        assert!(t.iter().any(|t| !t.errors.is_empty() || t.outcome.starts_with("err_")), "beyond the longest bus: errors");
    }

    #[test]
    fn oscillators_inside_the_tolerance_work_and_beyond_it_fail() {
        let (cfg, t) = run("can_osc_inside");
        assert!(super::super::within_timing_limits(&cfg).unwrap() && clean(&t) && t.len() >= 2, "{:?}", outcomes(&t));
        let (cfg, t) = run("can_osc_beyond");
        assert!(!super::super::within_timing_limits(&cfg).unwrap());
        assert!(t.iter().filter(|t| t.outcome == "err_stuff").count() >= 5, "{:?}", outcomes(&t));
    }

    #[test]
    fn every_error_type_is_injected_and_detected() {
        for (name, outcome) in [("can_err_bit", "err_bit"), ("can_err_stuff", "err_stuff"), ("can_err_crc", "err_crc"), ("can_err_form", "err_form"), ("can_err_ack", "err_ack")] {
            let (_, t) = run(name);
            assert_eq!(t[0].outcome, outcome, "{name}: {:?}", outcomes(&t));
        }
        // Errors inside flags and delimiters (the core receiving, then sending).
        let (_, t) = run("can_err_in_flags");
        assert_eq!(outcomes(&t)[..7], ["err_bit", "err_bit", "err_form", "err_form", "err_form", "err_bit", "rx_valid"]);
        assert_eq!([t[0].rec, t[1].rec], [1, 9], "a bit error in its own error flag: REC + 8 (rule 5)");
        // Frame 1 acknowledged (REC − 1 at the ACK slot, rule 8), then a dominant EOF bit (+ 1):
        // 9, not the 10 of a decrement at the sixth EOF bit the error never reaches.
        let recs: Vec<u16> = t[..7].iter().map(|t| t.rec).collect();
        assert_eq!(recs, [1, 9, 9, 18, 26, 42, 41], "REC after every outcome");
        assert_eq!(t[5].overloads, 1, "a dominant last error delimiter bit: overload");
        let (_, t) = run("can_err_in_flags_tx");
        assert_eq!([t[0].tec, t[1].tec, t[2].tec], [8, 16, 15], "a bit error in its own error flag: TEC + 8 (rule 4)");
        assert_eq!((t[3].outcome, t[4].tec), ("err_stuff", 38), "stuck dominant: 8 dominant bits after the flag, TEC + 8 each (rule 6)");
        let (_, t) = run("can_overload");
        assert_eq!(t[1].overloads, 1);
    }

    #[test]
    fn rec_127_is_still_error_active_and_128_is_not() {
        // ISO 11898-1: error-passive above 127. Each stuff error costs the
        // receiving core 1, the dominant bit after its flag 8: the 15th error
        // reaches exactly 127 and still sends an active flag (the RTL replay
        // compares the flag's bits on TXD); the 8 after it make it passive.
        let (_, t) = run("can_err_rec_127");
        // A transaction shows REC at its error, before the 8 of the next flag.
        assert_eq!(t.len(), 16, "{:?}", outcomes(&t));
        assert!(t[..15].iter().all(|t| t.outcome == "err_stuff"), "{:?}", outcomes(&t));
        let recs: Vec<u32> = t[..15].iter().map(|t| t.rec as u32).collect();
        assert_eq!(recs, (0..15).map(|k| 9 * k + 1).collect::<Vec<_>>(), "1 + 8 per error");
        assert_eq!((t[14].rec, t[14].err_state), (127, 0), "REC 127 at the 15th error: error-active");
        // 135 after that flag: passive; a frame received whole sets REC to 119 (CAN 2.0 fault confinement, rule 8).
        assert_eq!((t[15].outcome, t[15].rec, t[15].err_state), ("rx_valid", 119, 0));
    }

    /// Rule 8 at its boundary: a frame received whole at REC 126, 127 and
    /// 128 ("decreased by 1, if it was between 1 and 127 ... if it was
    /// greater than 127, then it will be set to a value between 119 and
    /// 127", the core's 119). Each scenario walks REC up with stuff errors
    /// (`scenarios/can/rec_*_good.toml`), then receives one frame.
    #[test]
    fn a_good_reception_at_rec_126_127_and_128() {
        // REC at each error pulse: 14 errors only the core flags (+ 1, then + 8 after
        // its flag: 9k + 1 at the pulse, 126 after the 14th), then errors every node
        // flags at once (+ 1 alone); the good frame's REC (`.., 125`, `.., 126`, `.., 119`).
        for (name, shared, after) in [("can_rec_126_good", &[][..], 125), ("can_rec_127_good", &[127][..], 126), ("can_rec_128_good", &[127, 128][..], 119)] {
            let (_, t) = run(name);
            let (last, errs) = t.split_last().unwrap();
            assert!(errs.iter().all(|t| t.outcome == "err_stuff" && t.tec == 0), "{name}: {:?}", outcomes(&t));
            let recs: Vec<u16> = errs.iter().map(|t| t.rec).collect();
            let want: Vec<u16> = (0..14).map(|k| 9 * k + 1).chain(shared.iter().copied()).collect();
            assert_eq!(recs, want, "{name}: REC at every error");
            assert_eq!(errs.last().unwrap().err_state, u8::from(recs.last() == Some(&128)), "{name}: error-passive from 128 only");
            assert_eq!((last.outcome, last.rec, last.tec, last.err_state), ("rx_valid", after, 0, 0), "{name}: REC after the good frame");
        }
    }

    /// Rule 3 exception 2 ends at RTR: "whereby the STUFFBIT is located
    /// before the RTR bit". A recessive stuff bit after ID0 read dominant is
    /// not counted; one right after RTR is (TEC + 8, then − 1 when sent).
    #[test]
    fn the_stuff_exemption_ends_at_the_rtr_bit() {
        let (_, t) = run("can_stuff_exempt_last_id_bit");
        assert_eq!(counters(&t), [("err_stuff", 0, 0), ("tx_done", 0, 0)]);
        let (_, t) = run("can_stuff_after_rtr");
        assert_eq!(counters(&t), [("err_stuff", 8, 0), ("tx_done", 7, 0)]);
    }

    /// The acceptance filter compares all 29 bits of an extended
    /// identifier: identifiers one bit away from the filter's (bits 28, 18,
    /// 17, 11, 10, 0) and a standard frame of its low 11 bits are rejected
    /// (no transaction), the exact one accepted.
    #[test]
    fn the_filter_compares_every_bit_of_an_extended_identifier() {
        let (cfg, t) = run("can_filter_extended");
        let sent = &cfg.nodes[0].frames;
        assert_eq!(sent.len(), 8);
        let want = sent.last().unwrap().id;
        assert!(sent[..7].iter().all(|f| f.id != want));
        let got: Vec<_> = t.iter().map(|t| (t.outcome, t.rx_id, t.ide)).collect();
        assert_eq!(got, [("rx_valid", Some(want), true)], "only the exact identifier is accepted");
        assert_eq!(cfg.dut.filter_mask, 0x1FFF_FFFF);
    }

    #[test]
    fn error_passive_bus_off_and_recovery() {
        let (_, t) = run("can_passive_suspend");
        let passive = t.iter().position(|t| t.err_state == 1).expect("error-passive");
        assert_eq!(t[passive].tec, 128);
        assert!(t.iter().any(|t| t.outcome == "rx_valid" && t.err_state == 1), "receives while passive (another node starts during its suspend)");
        assert!(t.windows(2).any(|w| w[0].outcome == "err_ack" && w[1].outcome == "err_ack" && w[1].tec == w[0].tec + 8 && w[0].tec >= 128), "a dominant bit in the passive flag after an ACK error: TEC + 8");
        let (cfg, t) = run("can_bus_off_recovery");
        assert!(t.iter().any(|t| t.tec >= 256 || t.err_state == 2), "bus-off");
        let last = t.last().unwrap();
        assert_eq!((last.outcome, last.tec, last.rec, last.err_state), ("tx_done", 0, 0, 0), "recovered");
        let bit = cfg.bit_timing().unwrap().clocks_per_bit();
        let off = t.iter().rev().nth(1).unwrap().cycle;
        assert!(last.sof_cycle - off >= 128 * 11 * bit, "recovery after 128 × 11 recessive bits");
    }

    #[test]
    fn fault_confinement_exceptions_and_bus_off_from_a_flag() {
        // Rule 3 exception 2: a recessive stuff bit in arbitration read dominant is not counted.
        let (_, t) = run("can_stuff_exempt_arbitration");
        assert_eq!(outcomes(&t), ["err_stuff", "tx_done"]);
        assert_eq!((t[0].tec, t[1].tec), (0, 0), "a stuff error on its own arbitration stuff bit: TEC unchanged");
        // TEC 248, an ACK error (not counted while passive), then a dominant bit in the passive flag: bus-off.
        // Rule 6 at the limit: TEC 248 after a bit error, 8 dominant bits after the flag: bus-off.
        for (name, last_err, outcome) in [("can_bus_off_passive_ack", 31, "err_ack"), ("can_bus_off_rule6", 30, "err_bit")] {
            let (cfg, t) = run(name);
            let bit = cfg.bit_timing().unwrap().clocks_per_bit();
            assert_eq!(t.len(), last_err + 2, "{name}: {:?}", outcomes(&t));
            assert!(t[..last_err].iter().all(|t| t.outcome == "err_bit"), "{name}: {:?}", outcomes(&t));
            let e = &t[last_err];
            assert_eq!((e.outcome, e.tec, e.err_state), (outcome, 248, 1), "{name}: error-passive at TEC 248 in the last error");
            let last = t.last().unwrap();
            assert_eq!((last.outcome, last.tec, last.rec, last.err_state), ("tx_done", 0, 0, 0), "{name}: recovered after bus-off");
            assert!(last.sof_cycle - e.cycle >= 128 * 11 * bit, "{name}: bus-off, then 128 x 11 recessive bits");
        }
    }

    /// (outcome, TEC, REC) of every transaction: the counters at each outcome pulse.
    fn counters(t: &[Transaction]) -> Vec<(&'static str, u16, u16)> {
        t.iter().map(|t| (t.outcome, t.tec, t.rec)).collect()
    }

    /// The fault confinement rules of CAN 2.0 part B §8 (ISO 11898-1), as
    /// transmitter: each expected count below is the previous one plus what
    /// the rule named beside it adds, read off the scenario's faults (the
    /// comment of `scenarios/can/confinement_tx.toml` places them).
    #[test]
    fn fault_confinement_as_transmitter_counter_by_counter() {
        let (_, t) = run("can_confinement_tx");
        assert_eq!(
            counters(&t),
            [
                ("err_bit", 8, 0),    // rule 3: a transmitter sends an error flag
                ("err_bit", 16, 0),   // rule 4: a bit error in its own active error flag
                ("tx_done", 15, 0),   // rule 7: the retransmission succeeds
                ("err_bit", 23, 0),   // rule 4: a bit error in its overload flag, still the transmitter
                ("err_form", 31, 0),  // rule 3: a form error in its error delimiter, still the transmitter
                ("err_stuff", 39, 0), // rule 3 (rule 2 before it counted nothing: a transmitter)
                ("tx_done", 54, 0),   // rule 6 twice (+ 16), rule 7 (− 1)
            ]
        );
        assert_eq!(t[3].overloads, 1, "the dominant first intermission bit is an overload");
    }

    /// The same rules as receiver (`scenarios/can/confinement_rx.toml`).
    #[test]
    fn fault_confinement_as_receiver_counter_by_counter() {
        let (_, t) = run("can_confinement_rx");
        assert_eq!(
            counters(&t),
            [
                ("err_bit", 0, 1),    // rule 1: its own ACK read recessive
                ("err_bit", 0, 9),    // rule 5: a bit error in its own active error flag
                ("rx_valid", 0, 8),   // rule 8: received and acknowledged
                ("err_bit", 0, 16),   // rule 5: a bit error in its overload flag
                ("err_form", 0, 17),  // rule 1: a dominant error delimiter bit
                ("err_form", 0, 25),  // rule 2 (+ 8), rule 8 at the ACK slot (− 1), rule 1 at an EOF bit (+ 1)
                ("rx_valid", 0, 32),  // rule 2 (+ 8), rule 8 (− 1)
                ("err_stuff", 0, 33), // rule 1: the bus stuck dominant
                ("rx_valid", 0, 56),  // rule 2 (+ 8), rule 6 twice (+ 16), rule 8 (− 1)
            ]
        );
        assert_eq!(t[3].overloads, 1, "the dominant first intermission bit is an overload");
    }

    /// Rule 9: "An error condition letting a node become 'error passive'
    /// causes the node to send an ACTIVE ERROR FLAG." In `can_passive_suspend`
    /// the ACK error that takes TEC from 120 to 128 is followed on the core's
    /// TXD by six dominant bits (a passive flag would be recessive).
    #[test]
    fn the_error_that_makes_the_core_error_passive_sends_an_active_flag() {
        use model::testbench::Testbench;
        let s = builtin::find("can_passive_suspend").unwrap();
        let cfg = s.setup.get::<BenchConfig>().unwrap();
        let bit = cfg.bit_timing().unwrap().clocks_per_bit() as usize;
        let mut bench = model::Setup::bench(cfg).unwrap();
        let layout = bench.layout().clone();
        let col = |name: &str| layout.outputs.iter().position(|p| p.name == name).unwrap();
        let (tx, tec) = (col("o_can_tx"), col("o_tec"));
        let mut sample = model::trace::Sample::for_layout(&layout);
        let mut after: Option<Vec<bool>> = None;
        while !bench.finished() {
            bench.step(Some(&mut sample));
            match after.as_mut() {
                None if sample.outputs[tec] == 128 => after = Some(Vec::new()),
                Some(levels) if levels.len() < 8 * bit => levels.push(sample.outputs[tx] != 0),
                _ => {}
            }
        }
        let levels = after.expect("TEC reaches 128");
        let longest = levels.split(|&l| l).map(<[bool]>::len).max().unwrap();
        assert_eq!(longest, 6 * bit, "a flag of six dominant bits after the error that made the core error-passive");
    }

    /// Bus-off reached between two attempts of one frame, through an overload
    /// frame the core sends as its transmitter (rules 4 and 10), then rule 12.
    #[test]
    fn bus_off_while_the_frame_waits_to_be_sent_again() {
        let (cfg, t) = run("can_bus_off_retransmit");
        assert_eq!(t.len(), 33, "{:?}", outcomes(&t));
        let tecs: Vec<u16> = t[..31].iter().map(|t| t.tec).collect();
        assert_eq!(tecs, (1..=31).map(|k| 8 * k).collect::<Vec<_>>(), "rule 3: + 8 per bit error");
        assert!(t[..31].iter().all(|t| t.outcome == "err_bit" && t.rec == 0));
        let off = &t[31];
        assert_eq!((off.outcome, off.tec, off.rec, off.err_state, off.overloads), ("err_bit", 256, 0, 2, 1), "the overload flag's bit error takes TEC to 256: bus-off");
        let last = &t[32];
        assert_eq!((last.outcome, last.tec, last.rec, last.err_state), ("tx_done", 0, 0, 0), "the pending frame sent after recovery");
        let bit = cfg.bit_timing().unwrap().clocks_per_bit();
        assert!(last.sof_cycle - off.cycle >= 128 * 11 * bit, "bus-off, then 128 x 11 recessive bits");
    }

    #[test]
    fn three_nodes_arbitrate_and_extended_frames_are_received_with_ide() {
        let (cfg, t) = run("can_arbitration_3_nodes");
        assert!(cfg.nodes.len() >= 2 && clean(&t) && t.iter().any(|t| t.arb_lost), "{:?}", outcomes(&t));
        let (_, t) = run("can_extended_frames");
        assert!(t.iter().any(|t| t.outcome == "rx_valid" && t.ide && t.ack), "{:?}", outcomes(&t));
        let (cfg, t) = run("can_brp1_1000k");
        assert_eq!(cfg.bit_timing().unwrap().brp, 1);
        assert!(clean(&t) && t.len() == 2);
    }
}
