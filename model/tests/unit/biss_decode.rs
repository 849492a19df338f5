use model::biss::decode::*;
use model::wire::Signal;

/// Found by the emulators' sweep on random pins (`cosim/tests/unit/bad_values.rs`):
/// a frame the master stops three clocks after the ack, the start bit
/// already seen, made the decoder subtract past zero when it counted the
/// cells clocked after the start bit. A capture can hold such a frame (a
/// master reset mid-frame); it is decoded as clocking no cell, not a panic.
#[test]
fn a_frame_stopped_just_after_its_start_bit_counts_no_cells_and_does_not_panic() {
    let (mut ma, mut slo) = (Signal::named("ma"), Signal::named("slo"));
    let us = 1_000_000;
    ma.push(0, true);
    slo.push(0, true);
    // Four MA periods of 1 µs, then MA high (idle).
    for k in 0..4 {
        ma.push(10 * us + k * us, false);
        ma.push(10 * us + k * us + us / 2, true);
    }
    // Ack low after the second rising edge, the start bit high a cell later.
    slo.push(11 * us + us / 2 + 100_000, false);
    slo.push(12 * us + us / 2 + 100_000, true);
    let layout = Layout {
        bits: vec![12],
        crc_width: vec![6],
        crc_poly: vec![0x43],
        timeout_ps: None,
    };
    let frames = Decoder::default().feed(&ma, &slo, &layout);
    assert_eq!(frames.len(), 1, "{frames:?}");
    assert_eq!(frames[0].cells, Some((0, 1 + 12 + 2 + 6)), "{frames:?}");
}
