use model::sar58k24::timing::*;
use model::uart::Parity;

#[test]
fn the_budget_of_the_docs_table() {
    let b = budget(16, Parity::None, 20.0);
    assert_eq!(b[0].baud, 115_200.0);
    assert!((b[0].frame_us - 434.03).abs() < 0.01);
    assert_eq!(b[0].max_listed_refresh_hz, 2000.0);
    assert_eq!(b[6].max_listed_refresh_hz, 20.0);
    let b = budget(17, Parity::None, 20.0);
    assert!((b[0].trigger_to_position_us - 536.5).abs() < 0.1);
    assert_eq!(
        budget(32, Parity::Even, 0.0)[0].max_listed_refresh_hz,
        1000.0
    );
    assert!(table(14, Parity::None, 20.0).contains("| 2400 | 20833.3 µs | 20 Hz |"));
}
