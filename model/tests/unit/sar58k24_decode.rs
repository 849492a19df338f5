use model::sar58k24::decode::*;
use model::sar58k24::frames::{self, AnswerTag};
use model::uart::line;
use model::uart::Parity;
use model::wire::Signal;

/// The line and driver enable of 8N1 characters at 115200 baud: the
/// host's `command`, then, 20 bit times later, the encoder's `answer`.
fn line(command: &[u8], answer: &[u8], bit_ps: u64) -> (Signal, Signal) {
    let (mut line_sig, mut tx_en) = (Signal::named("line"), Signal::named("tx_en"));
    line_sig.push(0, true);
    tx_en.push(0, false);
    let mut t = 10 * bit_ps;
    for (i, bytes) in [command, answer].into_iter().enumerate() {
        tx_en.push(t - bit_ps, i == 0);
        for &b in bytes {
            let bits = std::iter::once(false)
                .chain((0..8).map(|k| b >> k & 1 == 1))
                .chain(std::iter::once(true));
            for level in bits {
                line_sig.push(t, level);
                t += bit_ps;
            }
        }
        tx_en.push(t, false);
        t += 20 * bit_ps;
    }
    line_sig.push(t, true);
    (line_sig, tx_en)
}

fn options(answer_tag: AnswerTag) -> Options {
    Options {
        baud: 115_200.0,
        parity: Parity::None,
        bits: 16,
        gray: false,
        gap_bits: 15.0,
        answer_tag,
    }
}

#[test]
fn a_bus_answer_tagged_81_is_a_frame_only_when_the_answer_tag_is_fixed81() {
    // Seed 001, 3.1.5: BC AA B2 reads encoder 2; the tables show its answer
    // as FF 81 <data> <sum>, the text as FF B2 <data> <sum> (frames::AnswerTag).
    let bit_ps = (1e12f64 / 115_200.0).round() as u64;
    let answer81 = frames::encode_tagged(8738, 16, 0x81);
    assert_eq!(answer81, [0xFF, 0x81, 0x22, 0x22, 0xC4]);
    let (l, de) = line(&frames::read_command(2), &answer81, bit_ps);
    let fixed = decode(&l, &de, &options(AnswerTag::Fixed81));
    assert_eq!(
        fixed
            .iter()
            .map(|b| (b.kind, b.command, b.position, b.errors.clone()))
            .collect::<Vec<_>>(),
        [
            ("command", Some("read"), None, vec![]),
            ("frame", None, Some(8738), vec![])
        ]
    );
    assert_eq!(fixed[1].bytes, answer81);
    // The text's reading expects FF B2: the same answer is a header fault.
    let address = decode(&l, &de, &options(AnswerTag::Address));
    assert_eq!(
        address
            .iter()
            .map(|b| (b.kind, b.position, b.errors.clone()))
            .collect::<Vec<_>>(),
        [("command", None, vec![]), ("fault", None, vec!["frame"])]
    );
    // And FF B2 is a frame under the text's reading, a header fault under the tables'.
    let (l, de) = line(
        &frames::read_command(2),
        &frames::encode_tagged(8738, 16, 0xB2),
        bit_ps,
    );
    assert_eq!(
        decode(&l, &de, &options(AnswerTag::Address))[1].position,
        Some(8738)
    );
    assert_eq!(
        decode(&l, &de, &options(AnswerTag::Fixed81))[1].errors,
        ["frame"]
    );
}

/// A line of 8N1 characters at `bit_ps`: each part is (host drives,
/// bytes, idle bits after it); the encoder's byte `bad_stop` has its stop
/// bit low, and `spaced` puts one idle bit after each of its characters.
fn line_of(
    parts: &[(bool, &[u8], u64)],
    bad_stop: u8,
    spaced: bool,
    bit_ps: u64,
) -> (Signal, Signal) {
    let (mut line_sig, mut tx_en) = (Signal::named("line"), Signal::named("tx_en"));
    line_sig.push(0, true);
    tx_en.push(0, false);
    let mut t = 10 * bit_ps;
    for &(host, bytes, idle) in parts {
        tx_en.push(t - bit_ps, host);
        for &b in bytes {
            let stop = b != bad_stop || host;
            let bits = std::iter::once(false)
                .chain((0..8).map(|k| b >> k & 1 == 1))
                .chain(std::iter::once(stop));
            for level in bits {
                line_sig.push(t, level);
                t += bit_ps;
            }
            line_sig.push(t, true);
            if spaced && !host {
                t += bit_ps;
            }
        }
        tx_en.push(t, false);
        t += idle * bit_ps;
    }
    (line_sig, tx_en)
}

/// Cutting the line after each of the encoder's characters
/// ([`Decoder::feed_carrying`]) gives the events of decoding it whole:
/// frames, a checksum fault, a character with a low stop bit, and the
/// finder out of step across a command (after that character the next
/// answer's bad checksum is noise, not a checksum fault). A plain
/// [`Decoder::feed`] at the same cuts, which ends each piece with a gap,
/// does not.
#[test]
fn cuts_between_the_encoder_s_characters_change_no_event() {
    let bit_ps = (1e12f64 / 115_200.0).round() as u64;
    let cmd = frames::read_command(2);
    let mut bad_sum = frames::encode_tagged(8738, 16, 0x81);
    bad_sum[4] ^= 1;
    let good = frames::encode_tagged(4660, 16, 0x81);
    // Two idle bits between an answer and the next command: less than the gap.
    let parts: [(bool, &[u8], u64); 8] = [
        (true, &cmd, 4),
        (false, &good, 2),
        (true, &cmd, 4),
        (false, &[0xFF, 0x81, 0x5A], 2),
        (true, &cmd, 4),
        (false, &bad_sum, 2),
        (true, &cmd, 4),
        (false, &good, 20),
    ];
    for spaced in [false, true] {
        let (l, de) = line_of(&parts, 0x5A, spaced, bit_ps);
        let o = options(AnswerTag::Fixed81);
        let whole = decode(&l, &de, &o);
        let summary = |v: &[Burst]| {
            v.iter()
                .map(|b| {
                    (
                        b.index,
                        b.kind,
                        b.start_ps,
                        b.bytes.clone(),
                        b.position,
                        b.errors.clone(),
                    )
                })
                .collect::<Vec<_>>()
        };
        let kinds: Vec<_> = whole.iter().map(|b| (b.kind, b.errors.clone())).collect();
        assert_eq!(
            kinds.iter().filter(|k| k.0 == "command").count(),
            4,
            "{kinds:?}"
        );
        assert_eq!(
            kinds.iter().filter(|k| k.0 == "frame").count(),
            2,
            "{kinds:?}"
        );
        assert!(kinds.contains(&("fault", vec!["frame"])), "{kinds:?}");
        // Half a bit after each of the encoder's characters, where the line is idle.
        let chars = line::chars(&l, Some(&de), bit_ps, Parity::None);
        let cuts: Vec<u64> = chars
            .iter()
            .enumerate()
            .filter(|(_, c)| !c.from_host)
            .map(|(k, c)| (k, c.start_ps + 10 * bit_ps + bit_ps / 2))
            .filter(|&(k, t)| chars.get(k + 1).is_none_or(|n| n.start_ps > t))
            .map(|(_, t)| t)
            .collect();
        // After each answer only when its characters follow back to back; after each character when spaced.
        assert_eq!(
            cuts.len(),
            if spaced { 5 + 3 + 5 + 5 } else { 4 },
            "{cuts:?}"
        );
        let piecewise = |carry: bool| {
            let mut d = Decoder::new(o.clone());
            let mut from = 0;
            let mut out = Vec::new();
            for &c in &cuts {
                let (l_piece, de_piece) =
                    (cut_before(&l.tail(from), c), cut_before(&de.tail(from), c));
                out.extend(if carry {
                    d.feed_carrying(&l_piece, &de_piece)
                } else {
                    d.feed(&l_piece, &de_piece)
                });
                from = c;
            }
            out.extend(d.feed(&l.tail(from), &de.tail(from)));
            out
        };
        assert_eq!(summary(&piecewise(true)), summary(&whole));
        assert_ne!(
            summary(&piecewise(false)),
            summary(&whole),
            "the carried finder made no difference: the test line does not test it"
        );
    }
}

/// `s` up to (not including) `t_ps`.
fn cut_before(s: &Signal, t_ps: u64) -> Signal {
    Signal {
        name: s.name.clone(),
        changes: s.changes.iter().copied().filter(|c| c.0 < t_ps).collect(),
    }
}
