use model::endat::{MasterConfig, DELAY_COUNTER_MAX};

#[test]
fn the_delay_limit_never_exceeds_the_16_bit_delay_counter() {
    // 100 kHz from 257 MHz: by_gap is 26 x 2570 - 1285 = 65535 exactly.
    assert_eq!(MasterConfig::delay_limit(2570, 25, 26), 65535);
    // 100 kHz from 300 MHz: by_stop 89 998 and by_gap 76 500 would not fit 16 bits.
    assert_eq!(MasterConfig::delay_limit(3000, 25, 26), DELAY_COUNTER_MAX);
    // 8 MHz from 64 MHz: the schedule's bound, far below the counter's.
    assert_eq!(MasterConfig::delay_limit(8, 25, 2), 12);
}
