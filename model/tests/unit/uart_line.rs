use model::uart::line::*;
use model::uart::Parity;
use model::wire::Signal;
fn line_of(levels: &[bool], bit_ps: u64) -> Signal {
    let mut changes = vec![(0, true)];
    for (i, &b) in levels.iter().enumerate() {
        let t = 1_000_000 + i as u64 * bit_ps;
        if changes.last().unwrap().1 != b {
            changes.push((t, b));
        }
    }
    if !changes.last().unwrap().1 {
        changes.push((1_000_000 + levels.len() as u64 * bit_ps, true));
    }
    Signal {
        name: "line".into(),
        changes,
    }
}

#[test]
fn every_byte_with_even_parity_reads_back_and_a_flipped_parity_or_stop_bit_is_named() {
    let bit_ps = 8_680_000;
    let mut levels = Vec::new();
    for v in 0..=255u8 {
        levels.extend(Parity::Even.levels(v));
    }
    let mut bad = Parity::Even.levels(0x81);
    bad[9] = !bad[9];
    levels.extend(&bad);
    let mut stop = Parity::Even.levels(0x55);
    stop[10] = false;
    levels.extend(&stop);
    levels.extend([true; 3]);
    let got = chars(&line_of(&levels, bit_ps), None, bit_ps, Parity::Even);
    assert_eq!(got.len(), 258);
    assert!(got[..256]
        .iter()
        .enumerate()
        .all(|(v, c)| c.value == v as u8 && !c.parity_error && !c.framing_error));
    assert!(got[256].parity_error && !got[256].framing_error && got[256].value == 0x81);
    assert!(got[257].framing_error && got[257].value == 0x55);
}
