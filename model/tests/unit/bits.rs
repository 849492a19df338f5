#[test]
fn strings_are_in_wire_order_and_msb_first() {
    assert_eq!(model::bits::string(&[true, false, true, true]), "1011");
    assert_eq!(model::bits::string_of(5, 4), "0101");
    assert_eq!(model::bits::string_of(u128::MAX, 0), "");
}
