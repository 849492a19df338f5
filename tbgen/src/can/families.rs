//! The CAN scenario families, each held to what its name says
//! (`cargo test -p tbgen can::families`): the model's transcript of every
//! built-in CAN scenario, run here, must show the behaviour the scenario
//! exists for. The RTL replays the same vectors, so the core is held to it too.

#[cfg(test)]
pub(crate) mod tests {
    use crate::builtin;
    use crate::compliance::{exercise, Exercise};
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
    /// and good frames (`scenarios/can/rec_*_good.toml`), then receives one
    /// frame. REC 128 is error-passive only after the last error's flag,
    /// so every transaction before the good frame is error-active.
    #[test]
    fn a_good_reception_at_rec_126_127_and_128() {
        // Each error only the core flags: + 1 at its pulse, + 8 after its flag.
        for (name, before, after) in [("can_rec_126_good", 126, 125), ("can_rec_127_good", 127, 126), ("can_rec_128_good", 128, 119)] {
            let (_, t) = run(name);
            let (last, rest) = t.split_last().unwrap();
            let err = rest.last().unwrap();
            assert_eq!((err.outcome, err.rec + 8), ("err_stuff", before), "{name}: REC after the last error's flag");
            assert!(rest.iter().all(|t| t.tec == 0 && t.err_state == 0 && t.rec <= 127), "{name}: error-active throughout: {:?}", counters(&t));
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
    /// (no transaction), the exact one accepted. The first frame meets an
    /// error first (`scenarios/can/filter_extended.toml` says why).
    #[test]
    fn the_filter_compares_every_bit_of_an_extended_identifier() {
        let (cfg, t) = run("can_filter_extended");
        let sent = &cfg.nodes[0].frames;
        assert_eq!(sent.len(), 8);
        let want = sent.last().unwrap().id;
        assert!(sent[..7].iter().all(|f| f.id != want));
        assert!(t[0].outcome.starts_with("err_"), "the first frame's error (for the sigrok check): {:?}", outcomes(&t));
        let got: Vec<_> = t[1..].iter().map(|t| (t.outcome, t.rx_id, t.ide)).collect();
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

    /// The outputs `ports` of the core, cycle by cycle, as the vectors hold them.
    fn trace(name: &str, ports: &[&str]) -> (BenchConfig, Vec<Vec<u64>>) {
        use model::testbench::Testbench;
        let s = builtin::find(name).unwrap();
        let cfg = s.setup.get::<BenchConfig>().unwrap().clone();
        let mut bench = model::Setup::bench(&cfg).unwrap();
        let layout = bench.layout().clone();
        let cols: Vec<usize> = ports.iter().map(|p| layout.outputs.iter().position(|o| o.name == *p).unwrap()).collect();
        let mut sample = model::trace::Sample::for_layout(&layout);
        let mut rows = Vec::new();
        while !bench.finished() {
            bench.step(Some(&mut sample));
            rows.push(cols.iter().map(|&c| sample.outputs[c]).collect());
        }
        (cfg, rows)
    }

    /// The rules naming one role, held against the other with that role's
    /// counter above 0 (`scenarios/can/confinement_counterparts.toml`), and
    /// rule 11 for a transmitter: TEC 128, then 127 after a frame sent.
    #[test]
    fn fault_confinement_counterparts_with_both_counts_above_0() {
        let (_, t) = run("can_confinement_counterparts");
        let (errs, rest) = t.split_at(16);
        assert_eq!(errs.iter().map(|t| (t.outcome, t.tec, t.rec)).collect::<Vec<_>>(), (1..=16).map(|k| ("err_bit", 8 * k, 0)).collect::<Vec<_>>(), "rule 3: + 8 per bit error");
        assert_eq!(errs[15].err_state, 1, "rule 9: error-passive at TEC 128");
        assert_eq!(
            rest.iter().map(|t| (t.outcome, t.tec, t.rec, t.err_state)).collect::<Vec<_>>(),
            [
                ("tx_done", 127, 0, 0),  // rule 7, and rule 11: error-active again at 127
                ("err_stuff", 127, 1, 0), // rule 1 as receiver; rule 3 is a transmitter's: TEC unchanged
                ("rx_valid", 127, 8, 0), // rule 2 (+ 8), rule 8 (− 1); rule 7 is a transmitter's: TEC unchanged
                ("tx_done", 126, 8, 0),  // rule 7; rule 8 is a receiver's: REC unchanged
            ]
        );
    }

    /// Rule 6 for a receiver, and rule 10 names TEC alone: REC driven to 255
    /// by a stuck bus leaves the receiver error-passive, never bus-off
    /// (`can_rec_saturates`; `can_stuck_dominant` is the shorter stuck bus).
    #[test]
    fn a_receivers_rec_saturates_and_it_is_never_bus_off() {
        let (_, rows) = trace("can_rec_saturates", &["o_rec", "o_tec", "o_err_state"]);
        let top = rows.iter().map(|r| r[0]).max().unwrap();
        assert_eq!(top, 255, "REC climbs by 8 per 8 dominant bits to 255");
        assert!(rows.iter().all(|r| r[1] == 0 && r[2] < 2), "TEC 0, never bus-off");
        assert!(rows.iter().any(|r| r[0] == 255 && r[2] == 1), "error-passive at 255");
        let (_, t) = run("can_rec_saturates");
        assert_eq!((t.last().unwrap().outcome, t.last().unwrap().rec), ("rx_valid", 119));
        let (_, t) = run("can_stuck_dominant");
        assert_eq!(counters(&t), [("err_stuff", 0, 1), ("rx_valid", 0, 119)], "from REC 1 only rules 2 and 6 can pass 127");
    }

    /// Rule 12 with other nodes' frames on the bus: their dominant bits
    /// restart the 11, the core (bus-off) neither acknowledges nor reports
    /// them, and recovers later than on a quiet bus.
    #[test]
    fn bus_off_recovery_counts_recessive_bits_between_other_nodes_frames() {
        let (cfg, t) = run("can_bus_off_traffic");
        let bit = cfg.bit_timing().unwrap().clocks_per_bit();
        let off = t.iter().position(|t| t.err_state == 2).expect("bus-off");
        assert_eq!((t[off].outcome, t[off].tec), ("err_bit", 256));
        let back = &t[off + 1];
        assert_eq!((back.outcome, back.tec, back.rec, back.err_state), ("tx_done", 0, 0, 0), "recovered: nothing reported while bus-off");
        let during = cfg.nodes[0].frames.iter().filter(|f| {
            let at = (f.at_us * cfg.f_sys_mhz) as u64;
            at > t[off].cycle && at < back.sof_cycle
        });
        let n = during.count() as u64;
        assert!(n >= 4, "{n} frames of node a while bus-off");
        // Each frame holds a dominant bit at least every 11 bits over its 44
        // bits from SOF to the CRC (stuffing), so it adds at least 44 bits.
        assert!(back.sof_cycle - t[off].cycle >= (128 * 11 + 44 * n) * bit, "recovery after 128 x 11 recessive bits between the frames");
        assert!(t[off + 2..].iter().all(|t| t.outcome == "rx_valid"), "frames after recovery received");
    }

    /// §7.2: the flag of a CRC error "starts at the bit following the ACK
    /// DELIMITER": in `can_err_crc` the core's first dominant bit (it does
    /// not acknowledge) is the first EOF bit of the frame.
    #[test]
    fn a_crc_error_is_flagged_after_the_ack_delimiter() {
        let (cfg, rows) = trace("can_err_crc", &["o_can_tx"]);
        let (_, t) = run("can_err_crc");
        let bit = cfg.bit_timing().unwrap().clocks_per_bit();
        let f = &cfg.nodes[0].frames[0];
        let wire = model::can::frame::Frame::data(f.id, &f.data).wire_bits(true).len() as u64;
        let flag = rows.iter().position(|r| r[0] == 0).expect("a flag") as u64;
        // `sof_cycle` is the listener's sample point of SOF: the bit starts a sample point earlier.
        let sp = (cfg.bit_timing().unwrap().sample_point() * bit as f64).round() as u64;
        let at_bit = (flag + sp - t[0].sof_cycle + bit / 2) / bit;
        assert_eq!(at_bit, wire - 7, "the flag at the first of the 7 EOF bits");
        assert_eq!(t[0].outcome, "err_crc");
    }

    /// Part A §3.1.4: a dominant third intermission bit is a start of frame.
    /// Node a's overload flag reaches the core there: the core reads it as
    /// SOF and identifier bits (no overload frame) and detects a stuff error
    /// at its sixth dominant bit.
    #[test]
    fn a_dominant_third_intermission_bit_is_a_start_of_frame() {
        let (cfg, t) = run("can_sof_in_intermission");
        let bit = cfg.bit_timing().unwrap().clocks_per_bit();
        assert_eq!(outcomes(&t), ["rx_valid", "err_stuff"]);
        assert_eq!(t[1].overloads, 0, "not an overload");
        assert_eq!((t[1].cycle - t[1].sof_cycle + bit / 2) / bit, 5, "the stuff error at the sixth dominant bit from that SOF");
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

    /// The clauses of `model::can::clauses` each test above exercises
    /// (`docs/compliance/can.md` is written from this list). A rule naming
    /// one role is exercised in the other by a counter that must not move.
    pub(crate) const EXERCISES: &[Exercise] = &[
        exercise!(every_bit_rate_of_the_gateway_sends_and_receives_cleanly, ["can_rate_10k", "can_rate_20k", "can_rate_50k", "can_rate_125k", "can_rate_250k", "can_rate_500k", "can_rate_800k", "can_rate_1000k"], "frames both ways without error at every bit rate, eight 0x00 (a stuff bit every five) among them", [("bit-stuffing", Any), ("bit-time", Any), ("sync-3", Any)]),
        exercise!(the_longest_bus_of_each_timing_arbitrates_cleanly_and_a_longer_one_does_not, ["can_bus_longest", "can_bus_longest_10k", "can_bus_longest_500k", "can_bus_longest_1000k", "can_bus_too_long"], "the far node at the longest bus PROP_SEG covers wins arbitration against the core, both frames clean; a longer bus gives errors", [("prop-seg", Any), ("bit-error", Any)]),
        exercise!(oscillators_inside_the_tolerance_work_and_beyond_it_fail, ["can_osc_inside", "can_osc_beyond"], "a node 5000 ppm fast received and receiving cleanly (resynchronisation); 25 000 ppm gives stuff errors", [("bit-time", Any), ("sync-4", Any)]),
        exercise!(every_error_type_is_injected_and_detected, ["can_err_bit"], "the first outcome is a bit error", [("bit-error", Any), ("active-error-flag", Any), ("error-delimiter", Any)]),
        exercise!(every_error_type_is_injected_and_detected, ["can_err_stuff"], "the first outcome is a stuff error", [("stuff-error", Any)]),
        exercise!(every_error_type_is_injected_and_detected, ["can_err_crc"], "the first outcome is a CRC error", [("crc-error", Any)]),
        exercise!(every_error_type_is_injected_and_detected, ["can_err_form"], "the first outcome is a form error", [("form-error", Any)]),
        exercise!(every_error_type_is_injected_and_detected, ["can_err_ack"], "the first outcome is an ACK error", [("ack-error", Any)]),
        exercise!(every_error_type_is_injected_and_detected, ["can_err_in_flags"], "outcome and REC of every transaction: a bit error at its ACK and in its flag, dominant EOF and delimiter bits, an overload at the last delimiter bit", [("fc-1", Receiver), ("fc-5", Receiver), ("fc-8", Receiver), ("form-error-last-eof", Any), ("overload-delimiter", Any)]),
        exercise!(every_error_type_is_injected_and_detected, ["can_err_in_flags_tx"], "TEC of every transaction: a bit error in its own flag (+ 8), 8 dominant bits after it (+ 8 each)", [("fc-4", Transmitter), ("fc-6", Transmitter)]),
        exercise!(every_error_type_is_injected_and_detected, ["can_overload"], "a dominant first intermission bit: an overload frame, no counter moves", [("overload-2", Any)]),
        exercise!(rec_127_is_still_error_active_and_128_is_not, ["can_err_rec_127"], "REC at each of 15 stuff errors (1 + 8 each), error-active at 127, error-passive at 135, 119 after a frame received whole", [("fc-1", Receiver), ("fc-2", Receiver), ("fc-9", Receiver), ("fc-11", Receiver)]),
        exercise!(a_good_reception_at_rec_126_127_and_128, ["can_rec_126_good", "can_rec_127_good", "can_rec_128_good"], "REC at every error, then after a frame received whole at REC 126, 127 and 128: 125, 126, 119", [("fc-8", Receiver), ("fc-9", Receiver), ("fc-11", Receiver), ("fc-1", Receiver)]),
        exercise!(the_stuff_exemption_ends_at_the_rtr_bit, ["can_stuff_exempt_last_id_bit", "can_stuff_after_rtr"], "(outcome, TEC, REC): a stuff error at the stuff bit after ID0 not counted, after RTR + 8", [("fc-3", Transmitter), ("stuff-error", Any)]),
        exercise!(error_passive_bus_off_and_recovery, ["can_passive_suspend"], "TEC 128 from ACK errors: error-passive; a frame of another node received in its suspend; a dominant bit in its passive flag after an ACK error: + 8", [("fc-3", Transmitter), ("fc-9", Transmitter), ("suspend", Any), ("passive-error-flag", Any)]),
        exercise!(error_passive_bus_off_and_recovery, ["can_bus_off_recovery"], "bus-off, then a clean frame with TEC = REC = 0 at least 128 x 11 bits later", [("fc-10", Transmitter), ("fc-12", Transmitter)]),
        exercise!(fault_confinement_exceptions_and_bus_off_from_a_flag, ["can_stuff_exempt_arbitration"], "a stuff error on its own arbitration stuff bit: TEC unchanged", [("fc-3", Transmitter)]),
        exercise!(fault_confinement_exceptions_and_bus_off_from_a_flag, ["can_bus_off_passive_ack", "can_bus_off_rule6"], "TEC 248 error-passive, then a dominant bit in the passive flag after an ACK error, or 8 dominant bits after the flag: bus-off, recovery", [("fc-3", Transmitter), ("fc-6", Transmitter), ("fc-10", Transmitter), ("fc-12", Transmitter)]),
        exercise!(fault_confinement_as_transmitter_counter_by_counter, ["can_confinement_tx"], "(outcome, TEC, REC) of every transaction, the core sending: REC stays 0 at every error", [("transmitter", Transmitter), ("fc-1", Transmitter), ("fc-2", Transmitter), ("fc-3", Transmitter), ("fc-4", Transmitter), ("fc-5", Transmitter), ("fc-6", Transmitter), ("fc-7", Transmitter), ("overload-2", Any)]),
        exercise!(fault_confinement_as_receiver_counter_by_counter, ["can_confinement_rx"], "(outcome, TEC, REC) of every transaction, the core receiving: TEC stays 0 at every error", [("transmitter", Receiver), ("fc-1", Receiver), ("fc-2", Receiver), ("fc-3", Receiver), ("fc-4", Receiver), ("fc-5", Receiver), ("fc-6", Receiver), ("fc-8", Receiver), ("overload-2", Any)]),
        exercise!(the_error_that_makes_the_core_error_passive_sends_an_active_flag, ["can_passive_suspend"], "six dominant bits on TXD after the ACK error that takes TEC to 128", [("fc-9", Transmitter), ("active-error-flag", Any)]),
        exercise!(bus_off_while_the_frame_waits_to_be_sent_again, ["can_bus_off_retransmit"], "TEC + 8 per bit error to 248, a bit error in the overload flag after the last error frame: 256, bus-off; recovery; the pending frame sent", [("transmitter", Transmitter), ("fc-4", Transmitter), ("fc-10", Transmitter), ("fc-12", Transmitter)]),
        exercise!(three_nodes_arbitrate_and_extended_frames_are_received_with_ide, ["can_arbitration_3_nodes", "can_extended_frames", "can_brp1_1000k"], "a lost arbitration without error; extended frames received and acknowledged; BRP 1 clean", [("bit-error", Any), ("sync-3", Any)]),
        exercise!(fault_confinement_counterparts_with_both_counts_above_0, ["can_confinement_counterparts"], "(outcome, TEC, REC, state) of every transaction: TEC 128 passive, 127 active after a frame sent; with TEC 127 an error and a reception leave TEC alone, with REC 8 a transmission leaves REC alone", [("fc-1", Receiver), ("fc-2", Receiver), ("fc-3", Receiver), ("fc-3", Transmitter), ("fc-7", Receiver), ("fc-7", Transmitter), ("fc-8", Transmitter), ("fc-8", Receiver), ("fc-9", Transmitter), ("fc-11", Transmitter)]),
        exercise!(a_receivers_rec_saturates_and_it_is_never_bus_off, ["can_rec_saturates", "can_stuck_dominant"], "o_rec, o_tec and o_err_state every cycle: REC up by 8 per 8 dominant bits to 255, error-passive, never bus-off, TEC 0; 119 after a frame received whole", [("fc-6", Receiver), ("fc-10", Receiver), ("fc-9", Receiver)]),
        exercise!(bus_off_recovery_counts_recessive_bits_between_other_nodes_frames, ["can_bus_off_traffic"], "bus-off at TEC 256; other nodes' frames meanwhile not reported; recovery (TEC = REC = 0) after 128 x 11 bits plus the frames' own", [("fc-10", Transmitter), ("fc-12", Receiver)]),
        exercise!(a_crc_error_is_flagged_after_the_ack_delimiter, ["can_err_crc"], "o_can_tx every cycle: no ACK, the first dominant bit at the first EOF bit of the frame", [("crc-error", Any), ("crc-error-flag", Any)]),
        exercise!(a_dominant_third_intermission_bit_is_a_start_of_frame, ["can_sof_in_intermission"], "another node's overload flag in the third intermission bit read as SOF: a stuff error 5 bits after it, no overload", [("intermission-third-bit", Any), ("sync-3", Any)]),
    ];
}
