#[test]
fn strings_are_in_wire_order_and_msb_first() {
    assert_eq!(model::bits::string(&[true, false, true, true]), "1011");
    assert_eq!(model::bits::string_of(5, 4), "0101");
    assert_eq!(model::bits::string_of(u128::MAX, 0), "");
}

#[test]
fn bytes_are_two_upper_case_hex_digits_each_in_wire_order() {
    // Seed 001, 3.1.1: 383 at 14 bits is the frame FF 81 01 7F 00.
    assert_eq!(
        model::bits::hex(&[0xFF, 0x81, 0x01, 0x7F, 0x00]),
        "FF 81 01 7F 00"
    );
    assert_eq!(model::bits::hex(&[0x0A]), "0A");
    assert_eq!(model::bits::hex(&[]), "");
}
