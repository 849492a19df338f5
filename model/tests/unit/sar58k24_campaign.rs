/// Fast-forward changes no frame's outcome: the same trials stepped
/// every cycle give the same counts.
#[test]
fn fast_forward_gives_the_stepped_campaign() {
    assert_eq!(
        model::sar58k24::campaign::run_with(300, 8, 7, true),
        model::sar58k24::campaign::run_with(300, 8, 7, false)
    );
}
