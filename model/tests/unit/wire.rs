use model::wire::*;

#[test]
fn a_signal_keeps_its_levels_and_a_tail_starts_at_the_level_then() {
    let mut s = Signal::named("clk");
    for (t, v) in [
        (0, true),
        (10, false),
        (10, false),
        (20, true),
        (30, true),
        (40, false),
    ] {
        s.push(t, v);
    }
    assert_eq!(
        s.changes,
        vec![(0, true), (10, false), (20, true), (40, false)]
    );
    assert_eq!(s.edges(), vec![(10, false), (20, true), (40, false)]);
    assert!(!s.level_at(15) && s.level_at(25) && s.level_at(5));
    assert_eq!(s.next_level(21, false), Some(40));
    let tail = s.tail(25);
    assert_eq!(tail.changes, vec![(25, true), (40, false)]);
    assert_eq!(tail.edges(), vec![(40, false)]);
    s.forget_before(15);
    assert_eq!(s.changes, vec![(15, false), (20, true), (40, false)]);
}
