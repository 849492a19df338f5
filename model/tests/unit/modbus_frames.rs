use model::modbus::frames::*;

#[test]
fn seed_001_read_requests_for_one_and_two_registers() {
    // Seed 001, 3.1.7 (5) ① and ②: 01 03 00 00 00 01 84 0A and 01 03 00 00 00 02 C4 0B.
    assert_eq!(
        read_request(1, 1),
        [0x01, 0x03, 0x00, 0x00, 0x00, 0x01, 0x84, 0x0A]
    );
    assert_eq!(
        read_request(1, 2),
        [0x01, 0x03, 0x00, 0x00, 0x00, 0x02, 0xC4, 0x0B]
    );
    assert!(crc_ok(&read_request(1, 2)));
}

#[test]
fn seed_001_address_query_ff_a0_40_38_is_ff_a0_with_its_crc() {
    // Seed 001, 3.1.7 (5) ③: "The host is down FF A0 40 38"; the answer FF A0 01 XX XX.
    assert_eq!(address_query(), [0xFF, 0xA0, 0x40, 0x38]);
    let a = address_answer(1);
    assert_eq!(a[..3], [0xFF, 0xA0, 0x01]);
    assert!(crc_ok(&a));
    assert_eq!(a[3..], [0xF8, 0x30]);
}

#[test]
fn answers_carry_byte_count_2_or_4_high_byte_first() {
    // Seed 001, 3.1.7 (5): 01 03 02 XX XX CRC and 01 03 04 XX XX XX XX CRC.
    let a = read_answer(1, 1, 383);
    assert_eq!(a[..5], [0x01, 0x03, 0x02, 0x01, 0x7F]);
    assert!(crc_ok(&a));
    let a = read_answer(1, 2, 0x0012_3456);
    assert_eq!(a[..7], [0x01, 0x03, 0x04, 0x00, 0x12, 0x34, 0x56]);
    assert!(crc_ok(&a));
    let e = exception_answer(1, 0x03, Exception::IllegalDataAddress);
    assert_eq!(e[..3], [0x01, 0x83, 0x02]);
    assert!(crc_ok(&e));
}

#[test]
fn t35_and_t15_follow_the_serial_line_specification() {
    // 19200 baud, 10-bit characters: 3.5 × 520.8 µs = 1822.9 µs; above 19200: 1750 µs and 750 µs.
    assert!((t35_seconds(19_200.0, 10) * 1e6 - 1822.9).abs() < 0.1);
    assert!((t15_seconds(19_200.0, 10) * 1e6 - 781.25).abs() < 0.01);
    assert_eq!(t35_seconds(115_200.0, 10), 1750e-6);
    assert_eq!(t15_seconds(115_200.0, 11), 750e-6);
}
