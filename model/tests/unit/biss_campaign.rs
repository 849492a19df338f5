/// Fast-forward changes no frame's outcome: the same trials stepped
/// every cycle give the same counts.
#[test]
fn fast_forward_gives_the_stepped_campaign() {
    assert_eq!(
        model::biss::campaign::run_with(3_000, 16, 6, 7, true),
        model::biss::campaign::run_with(3_000, 16, 6, 7, false)
    );
}
