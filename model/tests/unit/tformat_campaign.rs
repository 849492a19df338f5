/// Fast-forward changes no operation's outcome: the same trials stepped
/// every cycle give the same counts.
#[test]
fn fast_forward_gives_the_stepped_campaign() {
    assert_eq!(
        model::tformat::campaign::run_with(3_000, 8, 7, true),
        model::tformat::campaign::run_with(3_000, 8, 7, false)
    );
}
