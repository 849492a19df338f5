use model::half_duplex::{End, Event, Link, LinkConfig, State, Then};

const C: u64 = 8;

fn link(answer_limit_bits: Option<u64>) -> Link<4> {
    Link::new(LinkConfig {
        clocks_per_bit: C,
        timeout_clocks: 50,
        repeat_gap_clocks: 100,
        answer_limit_bits,
        quiet_limit_bits: None,
    })
    .unwrap()
}

/// Starts sending `request` as a host does: the step of the start edge, then `start`.
fn started(answer_limit_bits: Option<u64>, request: &[u8]) -> Link<4> {
    let mut l = link(answer_limit_bits);
    assert_eq!(l.step(true), Event::None);
    l.start(request, 1);
    l
}

/// Steps until the driver is off, with `rx(cycle)` the receiver's input in
/// each cycle of the request; returns the level driven in each cycle the
/// driver was on.
fn send(l: &mut Link<4>, rx: impl Fn(usize) -> bool) -> String {
    let mut levels = String::new();
    while l.line().o_tx_en {
        levels.push(if l.line().o_tx { '1' } else { '0' });
        assert_eq!(l.step(rx(levels.len() - 1)), Event::None);
    }
    levels
}

#[test]
fn a_request_field_is_start_data_lsb_first_and_stop_each_a_bit_long_under_the_driver_enable() {
    // 0xA5 = 1010_0101: LSB first 1 0 1 0 0 1 0 1, between start 0 and stop 1.
    let mut l = started(None, &[0xA5]);
    let bits: String = "0101001011"
        .chars()
        .flat_map(|b| std::iter::repeat_n(b, C as usize))
        .collect();
    assert_eq!(send(&mut l, |_| true), bits);
    assert_eq!(l.state(), State::Wait);
    assert!(l.line().o_tx && l.line().o_busy);
}

#[test]
fn without_a_start_bit_the_wait_ends_in_a_timeout_timeout_clocks_after_the_driver_went_off() {
    let mut l = started(None, &[0x12, 0x34]);
    assert_eq!(send(&mut l, |_| true).len() as u64, 20 * C);
    let mut cycles = 0;
    loop {
        cycles += 1;
        if let Event::End(end) = l.step(true) {
            assert_eq!(end, End::Timeout);
            break;
        }
    }
    assert_eq!(cycles, 50);
}

#[test]
fn the_line_is_not_heard_while_the_host_drives() {
    // Low from the stop bit on while the driver is on (a second driver, a
    // fault): heard, it would be an answer's start bit; unheard, the line
    // is idle once the driver is off and the wait times out.
    let mut l = started(None, &[0x0F]);
    send(&mut l, |cycle| cycle < 9 * C as usize);
    let events: Vec<Event> = (0..50).map(|_| l.step(true)).collect();
    assert_eq!(events.last(), Some(&Event::End(End::Timeout)));
    assert!(events[..49].iter().all(|e| *e == Event::None));
}

/// The levels of one answer field, each a bit long.
fn field(byte: u8) -> Vec<bool> {
    model::uart::Parity::None
        .levels(byte)
        .into_iter()
        .flat_map(|b| std::iter::repeat_n(b, C as usize))
        .collect()
}

#[test]
fn an_answer_ends_a_bit_of_idle_line_after_its_last_field_and_keeps_its_fields() {
    let mut l = started(None, &[0x01]);
    send(&mut l, |_| true);
    let mut line: Vec<bool> = vec![true; 3];
    line.extend(field(0x5A));
    line.extend(field(0xC3));
    line.extend(vec![true; 100]);
    let mut got = Vec::new();
    for (cycle, &rx) in line.iter().enumerate() {
        match l.step(rx) {
            Event::None => {}
            Event::Field(b) => got.push((cycle, Some(b))),
            Event::End(end) => {
                assert_eq!(end, End::Answer);
                got.push((cycle, None));
                break;
            }
        }
    }
    assert_eq!(got.len(), 3, "{got:?}");
    assert_eq!((got[0].1, got[1].1), (Some(0x5A), Some(0xC3)));
    // The fields come a field apart; the end a bit after the last one.
    assert_eq!(got[1].0 - got[0].0, 10 * C as usize);
    assert_eq!(got[2].0 - got[1].0, C as usize);
    assert_eq!(l.fields(), [0x5A, 0xC3]);
    assert!(!l.frame_err());
    l.then(Then::Checked {
        flawed: false,
        settle: 0,
    });
    assert_eq!(l.state(), State::Idle);
    assert!(l.line().o_done && !l.line().o_busy);
}

#[test]
fn a_line_held_low_ends_the_answer_at_its_limit_and_only_with_one() {
    for limit in [Some(3), None] {
        let mut l = started(limit, &[0x01]);
        send(&mut l, |_| true);
        let mut recv_at = None;
        let mut end = None;
        for cycle in 0..1000 {
            let e = l.step(false);
            if recv_at.is_none() && l.state() == State::Recv {
                recv_at = Some(cycle);
            }
            if let Event::End(e) = e {
                end = Some((cycle, e));
                break;
            }
        }
        match limit {
            Some(bits) => {
                assert_eq!(end, Some((recv_at.unwrap() + bits * C, End::Overlong)));
            }
            None => assert_eq!(end, None),
        }
    }
}
