use model::endat::decode::*;
use model::endat::{crc_pos, crc_wire};
use model::wire::Signal;

const P: u64 = 125_000; // 8 MHz
const RT: u64 = 180_000; // a round trip of more than a period

/// A type 2.1 position request (`000111`, 25 position bits) answered with `pos`; the answer's edge `k`
/// (the start bit's is 0) arrives `jitter(k)` ps off its place one round trip after its rising edge.
fn pos21_line(pos: u64, jitter: impl Fn(usize) -> i64) -> (Signal, Signal) {
    let (n, j) = (44usize, 10usize); // clock periods; the start bit leaves at R_j
    let f1 = 1_000_000u64;
    let rise = |k: usize| f1 + 2 * P + (k as u64 - 1) * P; // R_k, t_ST = 2 periods
    let (mut clk, mut data) = (Signal::named("clk"), Signal::named("data"));
    for k in 1..=n {
        clk.push(if k == 1 { f1 } else { rise(k - 1) + P / 2 }, false);
        clk.push(rise(k), true);
    }
    for (k, bit) in [false, false, false, true, true, true]
        .into_iter()
        .enumerate()
    {
        data.push(rise(k + 2) - P / 2, bit); // the master drives the mode bits at F2..F7
    }
    data.push(rise(8) + RT, false); // the encoder drives low from R8
    let mut cells = vec![true, false]; // start bit, F1
    cells.extend((0..25).map(|i| pos >> i & 1 == 1));
    cells.extend(crc_wire(crc_pos(false, None, pos, 25)));
    cells.push(false); // the line low after the frame
    let mut edge = 0;
    let mut last = false;
    for (c, &bit) in cells.iter().enumerate() {
        if bit != last {
            data.push(
                (rise(j + c) + RT).checked_add_signed(jitter(edge)).unwrap(),
                bit,
            );
            edge += 1;
            last = bit;
        }
    }
    data.push(rise(n) + 10 * P, true); // recovered
    (clk, data)
}

fn position_read(clk: &Signal, data: &Signal) -> (Option<u64>, Option<Vec<String>>) {
    let t = decode(
        clk,
        data,
        &Options {
            pos_bits: 25,
            meas_khz: None,
        },
    )
    .unwrap();
    assert_eq!(t.len(), 1, "{t:#?}");
    (t[0].position, t[0].errors.clone())
}

#[test]
fn an_answer_jittered_by_less_than_half_a_cell_reads_right() {
    let pos = 0x1A5_C3E7;
    // Unjittered: the exact position, no error.
    let (clk, data) = pos21_line(pos, |_| 0);
    assert_eq!(position_read(&clk, &data), (Some(pos), Some(vec![])));
    // The start bit 0.3 period late and the third edge after it 0.25 period early, the others in place: each
    // edge stays inside its cell, as a master sampling at its measured delay sees it, but read from the start
    // bit's own edge the cell ending at the early edge is read 0.8 period after its start, past its end (0.75),
    // so that edge's bit is read twice and every bit after it one place late.
    let (late, early) = ((3 * P / 10) as i64, -((P / 4) as i64));
    let (clk, data) = pos21_line(pos, |k| [late, 0, 0, early].get(k).copied().unwrap_or(0));
    assert_eq!(position_read(&clk, &data), (Some(pos), Some(vec![])));
}
