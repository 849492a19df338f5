use model::ssi::decode::*;
use model::wire::Signal;

/// A 250 kHz read (2 us half periods, T_cs 4 us) of `bits`, the data
/// changing on each rising edge.
fn line(bits: &str) -> (Signal, Signal) {
    let (mut clk, mut data) = (Signal::named("clk"), Signal::named("data"));
    clk.push(0, true);
    data.push(0, true);
    let us = 1_000_000;
    clk.push(10 * us, false);
    let mut t = 14 * us;
    for b in bits.chars() {
        clk.push(t, true);
        data.push(t + 100_000, b == '1');
        clk.push(t + 2 * us, false);
        t += 4 * us;
    }
    clk.push(t, true);
    data.push(t + 100_000, false);
    (clk, data)
}

/// The seed's example (SAR58K24 manual, SSI section (4)): 0 0 0 1 1 1 1 0 1 1 1 1 = 495.
#[test]
fn the_seed_example_reads_495_and_a_wrong_width_says_what_fits() {
    let (clk, data) = line("000111101111");
    let layout = Layout {
        bits: Some(12),
        gray: false,
        double_read: false,
        wire_check: false,
    };
    let reads = decode(&clk, &data, &layout).unwrap();
    assert_eq!(reads.len(), 1);
    assert_eq!(reads[0].received_bits, "000111101111");
    assert_eq!(reads[0].position, Some(495));
    assert_eq!(reads[0].start_ps, 10_000_000);
    let e = decode(
        &clk,
        &data,
        &Layout {
            bits: Some(13),
            ..layout
        },
    )
    .unwrap_err();
    assert_eq!(
        e,
        "read 0 at 10000000 ps carries 12 bits, but --bits 13 reads 13: --bits 12 would fit"
    );
    let gray = decode(
        &clk,
        &data,
        &Layout {
            bits: Some(12),
            gray: true,
            ..layout
        },
    )
    .unwrap();
    assert_eq!(model::gray::to_gray(gray[0].position.unwrap()), 495);
}
