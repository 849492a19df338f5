use model::angle::angle_deg;

#[test]
fn seed_001_ssi_495_of_12_bits_is_43_5058_degrees() {
    assert_eq!(angle_deg(495, 12), 43.5058);
}

#[test]
fn seed_001_ssi_8_clocks_on_12_bits_give_at_most_22_4121_degrees() {
    assert_eq!(angle_deg(255, 12), 22.4121);
}

#[test]
fn seed_001_biss_35555_of_16_bits_is_195_3094_degrees() {
    assert_eq!(angle_deg(0b1000101011100011, 16), 195.3094);
}

#[test]
fn seed_001_can_reply_47_26_is_9799_low_byte_first_and_215_3100_degrees() {
    // The CAN data bytes come low byte first: 47 26 is 0x2647 (the
    // asynchronous frames, by contrast, send the high byte first).
    let value = u16::from_le_bytes([0x47, 0x26]);
    assert_eq!(value, 9799);
    assert_eq!(angle_deg(value as u64, 14), 215.31);
}

#[test]
fn seed_001_async_frame_data_017f_is_383_of_14_bits_and_8_4155_degrees() {
    assert_eq!(angle_deg(0x017F, 14), 8.4155);
}

#[test]
fn cutting_differs_from_rounding_where_the_seed_shows_it() {
    // 43.505859… rounds to 43.5059 but the seed prints 43.5058.
    assert_ne!(
        (360.0 * 495.0 / 4096.0 * 1e4_f64).round() / 1e4,
        angle_deg(495, 12)
    );
}
