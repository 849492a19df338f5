/// Fast-forward changes no answer's outcome: the same trials stepped
/// every cycle give the same counts.
#[test]
fn fast_forward_gives_the_stepped_campaign() {
    assert_eq!(
        model::modbus::campaign::run_with(300, 8, 7, true),
        model::modbus::campaign::run_with(300, 8, 7, false)
    );
}
