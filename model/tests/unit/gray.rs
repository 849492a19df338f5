use model::gray::*;
use proptest::prelude::*;

#[test]
fn gray_of_small_values_matches_the_textbook_table() {
    let table = [0b000, 0b001, 0b011, 0b010, 0b110, 0b111, 0b101, 0b100];
    for (binary, gray) in table.iter().enumerate() {
        assert_eq!(to_gray(binary as u64), *gray);
        assert_eq!(from_gray(*gray), binary as u64);
    }
}

proptest! {
    #[test]
    fn gray_round_trips(x in any::<u64>()) {
        prop_assert_eq!(from_gray(to_gray(x)), x);
    }

    #[test]
    fn neighbours_differ_in_one_gray_bit(x in 0u64..u64::MAX) {
        prop_assert_eq!((to_gray(x) ^ to_gray(x + 1)).count_ones(), 1);
    }
}
