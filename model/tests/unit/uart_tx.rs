use model::uart::{Parity, Tx, TxConfig, TxIn, TxState};

/// Skipping [`Tx::quiet`] steps leaves the sender where stepping does:
/// the same line, cycle for cycle, through a whole character (each
/// skipped cycle holds the last output), and the same state after it.
#[test]
fn skipping_the_quiet_steps_of_a_character_matches_stepping() {
    let cfg = TxConfig {
        clocks_per_bit: 7,
        parity: Parity::Even,
    };
    let go = TxIn {
        i_valid: true,
        i_data: 0xA5,
    };
    let idle = TxIn {
        i_valid: false,
        i_data: 0,
    };
    let cycles = 7 * 11 + 3;
    let mut stepped = Tx::new(cfg).unwrap();
    let mut line = vec![stepped.step(&go)];
    while line.len() < cycles {
        line.push(stepped.step(&idle));
    }
    let mut skipping = Tx::new(cfg).unwrap();
    let mut line_ff = vec![skipping.step(&go)];
    let mut skips = 0;
    while line_ff.len() < cycles {
        let q = skipping.quiet().min((cycles - line_ff.len()) as u64);
        if skipping.state() == TxState::Send && q > 0 {
            let held = skipping.out();
            skipping.skip(q);
            line_ff.extend(std::iter::repeat_n(held, q as usize));
            skips += 1;
        } else {
            line_ff.push(skipping.step(&idle));
        }
    }
    assert_eq!(line, line_ff);
    assert!(skips >= 11, "a skip in each of the 11 bits: {skips}");
    assert_eq!(
        (stepped.state(), stepped.out()),
        (skipping.state(), skipping.out())
    );
}
