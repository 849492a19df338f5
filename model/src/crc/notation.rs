//! Hex notations of a CRC generator polynomial, and a parser for the
//! equations the seeds print.
//!
//! A generator of degree `w` has `w + 1` coefficients, one too many for a
//! `w`-bit number, so every hex notation drops one term and orders the rest:
//!
//! | notation | bits `w-1` … `0` hold | dropped | ESL CRC-8 | ESL CRC-16 |
//! |---|---|---|---|---|
//! | [`Normal`](PolyNotation::Normal) (crc-catalogue `poly`) | `x^(w-1)` … `x^0` | `x^w` | `0x2F` | `0x5935` |
//! | [`Reversed`](PolyNotation::Reversed) (Modbus `A001`) | `x^0` … `x^(w-1)` | `x^w` | `0xF4` | `0xAC9A` |
//! | [`Koopman`](PolyNotation::Koopman) (= reversed reciprocal) | `x^w` … `x^1` | `1` | `0x97` | `0xAC9A` |
//! | [`Reciprocal`](PolyNotation::Reciprocal) | `x^1` … `x^w` (normal notation of `x^w·G(1/x)`) | `1` | `0xE9` | `0x5935` |
//!
//! Koopman notation and the *reversed reciprocal* notation are the same
//! number for every polynomial (both hold `x^i` in bit `i-1`).
//!
//! # The ESL case (seed 000, "Cyclic Redundancy Check Frame (CRC)")
//!
//! Seed 000 writes `X^8 + X^5 + X^3 + X^2 + X + 1` with `Poly = 8'h97`, and
//! `X^16 + X^14 + X^12 + X^11 + X^8 + X^5 + X^4 + X^2 + 1` with
//! `Poly = 16'hAC9A`. Written out, the generators are `1_0010_1111` (0x12F)
//! and `1_0101_1001_0011_0101` (0x15935). Dropping the `+1` and shifting
//! right by one gives `1001_0111` = 0x97 and `1010_1100_1001_1010` = 0xAC9A:
//! both printed values are in **Koopman** notation (equivalently reversed
//! reciprocal). The CRC-16 generator is a palindrome (its own reciprocal), so
//! 0xAC9A is also its reversed notation; the CRC-8 one is not, and only
//! Koopman fits 0x97, so Koopman is the one notation consistent with both
//! lines. In the normal notation the catalogue uses they are `0x2F` and
//! `0x5935`. Read as normal notation, `0x97` and `0xAC9A` would be other
//! polynomials (`x^8 + x^7 + x^4 + x^2 + x + 1`, and
//! `x^16 + x^15 + x^13 + x^11 + x^10 + x^7 + x^4 + x^3 + x`, which lacks the
//! `+1` and is no CRC generator at all).

/// A way of writing a degree-`w` generator polynomial as a `w`-bit number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum PolyNotation {
    /// Bit `i` = coefficient of `x^i`, `x^w` implicit. The crc-catalogue
    /// `poly` field; CAN's `0x4599`.
    Normal,
    /// The normal notation bit-reversed in `w` bits: bit `w-1-i` = coefficient
    /// of `x^i`, `x^w` implicit. The right-shifting table code's constant;
    /// Modbus's `A001`.
    Reversed,
    /// Bit `i-1` = coefficient of `x^i` for `i` in `1..=w`, the `+1`
    /// implicit (Koopman's tables). Numerically equal to the reversed
    /// reciprocal notation. ESL's `8'h97` and `16'hAC9A`.
    Koopman,
    /// The normal notation of the reciprocal polynomial `x^w · G(1/x)`.
    Reciprocal,
}

impl PolyNotation {
    /// Every notation, for searching which one a printed value is in.
    pub const ALL: [PolyNotation; 4] = [
        PolyNotation::Normal,
        PolyNotation::Reversed,
        PolyNotation::Koopman,
        PolyNotation::Reciprocal,
    ];

    /// Write the full generator `generator` (bit `i` = coefficient of `x^i`,
    /// including `x^width`) in this notation.
    pub fn encode(self, generator: u128, width: u32) -> u64 {
        let low = (generator & ((1u128 << width) - 1)) as u64;
        match self {
            PolyNotation::Normal => low,
            PolyNotation::Reversed => super::reflect(low, width),
            PolyNotation::Koopman => (generator >> 1) as u64,
            PolyNotation::Reciprocal => {
                (reflect_u128(generator, width + 1) & ((1u128 << width) - 1)) as u64
            }
        }
    }

    /// The full generator (bit `i` = coefficient of `x^i`, including
    /// `x^width`) that `value` denotes in this notation.
    pub fn decode(self, value: u64, width: u32) -> u128 {
        let top = 1u128 << width;
        let v = u128::from(value) & (top - 1);
        match self {
            PolyNotation::Normal => top | v,
            PolyNotation::Reversed => top | u128::from(super::reflect(value, width)),
            PolyNotation::Koopman => (v << 1) | 1,
            PolyNotation::Reciprocal => reflect_u128(top | v, width + 1),
        }
    }
}

/// The low `width` bits of `value` reversed (`width` in 1..=128).
fn reflect_u128(value: u128, width: u32) -> u128 {
    value.reverse_bits() >> (128 - width)
}

/// The generator with exactly these exponents (`[8, 5, 3, 2, 1, 0]` is
/// `x^8 + x^5 + x^3 + x^2 + x + 1`); bit `i` = coefficient of `x^i`.
pub fn generator_from_exponents(exponents: &[u32]) -> u128 {
    exponents.iter().fold(0u128, |g, &e| g ^ (1u128 << e))
}

/// Parse a polynomial as the seeds print it: terms joined by `+`, each `1`,
/// `X`/`x`, or `X^n` / `X^{n}` / `x^n`; `$` signs and spaces ignored
/// (`"$X^{16} + X^{14} + X^2 + 1$"`, `"x^6 + x + 1"`). Returns the generator
/// (bit `i` = coefficient of `x^i`), or `None` if a term is not one of those
/// forms or an exponent repeats.
pub fn parse_polynomial(text: &str) -> Option<u128> {
    let cleaned: String = text
        .chars()
        .filter(|c| !matches!(c, '$' | '{' | '}' | ' ' | '\t'))
        .collect();
    let mut g = 0u128;
    for term in cleaned.split('+') {
        let e = match term {
            "1" => 0,
            "X" | "x" => 1,
            t => {
                let rest = t.strip_prefix("X^").or_else(|| t.strip_prefix("x^"))?;
                let e: u32 = rest.parse().ok()?;
                if e >= 128 {
                    return None;
                }
                e
            }
        };
        if g & (1u128 << e) != 0 {
            return None;
        }
        g |= 1u128 << e;
    }
    Some(g)
}

/// The generator written as an equation, highest term first:
/// `"x^8 + x^5 + x^3 + x^2 + x + 1"`.
pub fn format_polynomial(generator: u128) -> String {
    let terms: Vec<String> = (0..128u32)
        .rev()
        .filter(|&e| generator & (1u128 << e) != 0)
        .map(|e| match e {
            0 => "1".to_string(),
            1 => "x".to_string(),
            e => format!("x^{e}"),
        })
        .collect();
    if terms.is_empty() {
        "0".to_string()
    } else {
        terms.join(" + ")
    }
}
