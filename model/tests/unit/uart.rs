//! Behaviour of the frame receiver: every byte, back-to-back frames, glitches,
//! breaks, and the baud-error tolerance measured against the formula.

use model::testbench::run_to_end;
use model::uart::*;
use model::Setup;

fn receive(cfg: &BenchConfig) -> Vec<Transaction> {
    run_to_end(cfg.bench().unwrap()).transactions
}

fn all_bytes() -> BenchConfig {
    BenchConfig {
        bytes: (0..=255).collect(),
        ..BenchConfig::default()
    }
}

#[test]
fn every_byte_arrives_back_to_back_at_10_mbps() {
    // Seed 000: 10 Mbps, 10-bit frames (start 0, 8 bits LSB first, stop 1).
    let events = receive(&all_bytes());
    assert_eq!(events.len(), 256);
    for (i, e) in events.iter().enumerate() {
        assert_eq!(
            (e.kind, e.received, e.sent),
            ("byte", Some(i as u8), Some(i as u8))
        );
    }
}

#[test]
fn a_byte_is_received_one_frame_after_its_start_bit() {
    let events = receive(&BenchConfig {
        bytes: vec![0xA5],
        ..BenchConfig::default()
    });
    let e = &events[0];
    // 9.5 bits to mid-stop, plus 2 synchroniser cycles and 1 output register.
    let latency = e.cycle - e.sent_cycle.unwrap();
    assert!((96..=99).contains(&latency), "latency {latency}");
}

#[test]
fn a_glitch_shorter_than_half_a_bit_is_rejected_and_a_break_is_one_framing_error() {
    let cfg = BenchConfig {
        bytes: vec![0x3C, 0x3C],
        gap_bits: 50.0,
        low: vec![
            LowPulse {
                at_us: 0.1,
                width_ns: 30.0,
            },
            LowPulse {
                at_us: 20.0,
                width_ns: 3000.0,
            },
        ],
        ..BenchConfig::default()
    };
    let kinds: Vec<_> = receive(&cfg).iter().map(|e| e.kind).collect();
    assert_eq!(kinds, vec!["start_error", "byte", "byte", "frame_error"]);
}

#[test]
fn t_format_rate_with_its_permissible_jitter_loses_nothing() {
    // Seed 002: 2.5 Mbps, permissible jitter ±100 ns.
    let cfg = BenchConfig {
        baud: 2.5e6,
        jitter_ns: 100.0,
        ..all_bytes()
    };
    let events = receive(&cfg);
    assert_eq!(events.len(), 256);
    assert!(events
        .iter()
        .all(|e| e.kind == "byte" && e.received == e.sent));
}

#[test]
fn the_tolerance_formula_at_10_clocks_per_bit() {
    let (low, high) = tolerance(10, 0.0);
    assert!((low + 5.263).abs() < 0.01, "{low}");
    assert!((high - 4.167).abs() < 0.01, "{high}");
}

#[test]
fn inside_the_tolerance_no_byte_is_lost_and_well_outside_every_frame_is_hurt() {
    // Sweep the sender's baud error; compare with `tolerance`, which allows
    // one cycle of edge quantisation. Inside (with a margin of 0.25 %) every
    // byte must arrive intact; 1.5 % beyond the bound no byte may.
    let (low, high) = tolerance(10, 0.0);
    let mut step = -80;
    while step <= 80 {
        let error = step as f64 / 10.0;
        let cfg = BenchConfig {
            error_percent: error,
            ..all_bytes()
        };
        let events = receive(&cfg);
        let intact = events
            .iter()
            .filter(|e| e.kind == "byte" && e.received == e.sent)
            .count();
        if error > low + 0.25 && error < high - 0.25 {
            assert_eq!(intact, 256, "error {error} %: only {intact} of 256 intact");
        }
        if error < low - 1.5 || error > high + 1.5 {
            assert!(
                intact < 256 / 4,
                "error {error} %: {intact} of 256 intact outside the tolerance"
            );
        }
        step += 5;
    }
}

/// Runs a transmitter into a receiver, both with `parity`, until the line
/// has been idle for a frame; returns (byte, valid, parity error, frame error) per character.
fn parity_loop(
    parity: Parity,
    queue: impl FnOnce(&mut Transmitter, f64),
) -> Vec<(u8, bool, bool, bool)> {
    // 100 MHz, 1 Mbps: 100 clocks per bit.
    let mut tx = Transmitter::new(10_000, 1e6, 0.0, 0.0, 1).with_parity(parity);
    let bit = tx.bit_ps();
    queue(&mut tx, bit);
    let mut rx = Receiver::with_parity(
        ReceiverConfig {
            clocks_per_bit: 100,
        },
        parity,
    )
    .unwrap();
    let end = (tx.idle_from_ps() / 10_000.0) as u64 + 2_000;
    let mut got = Vec::new();
    for _ in 0..end {
        let out = rx.step(&In { i_rx: tx.step() });
        if out.o_valid || out.o_parity_err || out.o_frame_err {
            got.push((out.o_data, out.o_valid, out.o_parity_err, out.o_frame_err));
        }
    }
    got
}

#[test]
fn every_byte_with_odd_or_even_parity_arrives_and_a_wrong_parity_bit_is_flagged() {
    // Seed 001, "Product communication": 8N1, "parity check or even check can
    // be added according to customer requirements".
    for parity in [Parity::Odd, Parity::Even] {
        let got = parity_loop(parity, |tx, _| {
            (0..=255u8).for_each(|b| tx.send(b, 0.0, 0.0))
        });
        assert_eq!(got.len(), 256);
        for (i, g) in got.iter().enumerate() {
            assert_eq!(*g, (i as u8, true, false, false), "{parity:?} byte {i}");
        }
        // The same byte with its parity bit inverted, then a good one.
        let mut bad = parity.levels(0x5A);
        bad[9] = !bad[9];
        let got = parity_loop(parity, |tx, _| {
            tx.send_levels(&bad, 0.0, 0.0);
            tx.send(0x5A, 0.0, 2.0);
        });
        assert_eq!(
            got,
            vec![(0x5A, false, true, false), (0x5A, true, false, false)],
            "{parity:?}"
        );
    }
    assert!(Parity::Odd.levels(0x00)[9]);
    assert!(Parity::Even.levels(0x01)[9]);
    assert_eq!(Parity::None.levels(0x01).len(), 10);
}

#[test]
fn an_eleven_bit_frame_narrows_the_tolerance_and_ten_bits_keep_the_old_figure() {
    assert_eq!(tolerance_for(10, 0.0, Parity::None), tolerance(10, 0.0));
    let (lo10, hi10) = tolerance_for(434, 0.0, Parity::None);
    let (lo11, hi11) = tolerance_for(434, 0.0, Parity::Even);
    assert!(lo11 > lo10 && hi11 < hi10, "{lo10} {hi10} {lo11} {hi11}");
    assert!(lo11 < -4.0 && hi11 > 4.0, "{lo11} {hi11}");
}

#[test]
fn the_cycle_sender_feeds_the_receiver_every_byte_with_and_without_parity() {
    for parity in [Parity::None, Parity::Odd, Parity::Even] {
        let mut tx = Tx::new(TxConfig {
            clocks_per_bit: 16,
            parity,
        })
        .unwrap();
        let mut rx = Receiver::with_parity(ReceiverConfig { clocks_per_bit: 16 }, parity).unwrap();
        let mut next = 0u16;
        let mut got = Vec::new();
        let mut first_busy = None;
        for cycle in 0..300_000u64 {
            let offer = next < 256 && !tx.out().o_busy;
            let out = tx.step(&TxIn {
                i_valid: offer,
                i_data: next as u8,
            });
            if offer {
                next += 1;
            }
            if out.o_busy && first_busy.is_none() {
                first_busy = Some(cycle);
            }
            let r = rx.step(&In { i_rx: out.o_tx });
            assert!(
                !r.o_frame_err && !r.o_parity_err && !r.o_start_err,
                "{parity:?} cycle {cycle}"
            );
            if r.o_valid {
                got.push(r.o_data);
            }
        }
        assert_eq!(got, (0..=255).collect::<Vec<u8>>(), "{parity:?}");
    }
}
