use model::modbus::timing::*;
use model::uart::Parity;

#[test]
fn the_poll_budget_of_the_docs_table() {
    let r = poll(19_200.0, Parity::None, 1, 100.0);
    assert!((r.poll_us - 11_558.3).abs() < 0.1, "{}", r.poll_us);
    assert_eq!(r.poll_hz().round(), 87.0);
    let r = poll(115_200.0, Parity::None, 2, 100.0);
    assert_eq!((r.t15_us, r.t35_us), (750.0, 1750.0));
    assert!((r.poll_us - 5075.7).abs() < 0.1, "{}", r.poll_us);
    assert!(table(Parity::None, 100.0)
        .contains("| 19200 | 1 | 520.8 µs | 781.2 µs | 1822.9 µs | 11.56 ms | 87 Hz |"));
}
