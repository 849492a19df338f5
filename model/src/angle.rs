//! Position to angle, as the SAR58K24 manual (seed 001) converts it:
//! `θ = 360° × a / 2^n`, printed to four decimals by cutting, not rounding
//! (495 of 4096 is 43.505859…°, which the seed writes 43.5058°).

/// `360° × position / 2^bits`, cut to four decimals.
pub fn angle_deg(position: u64, bits: u32) -> f64 {
    let angle = 360.0 * position as f64 / 2f64.powi(bits as i32);
    // The tiny bias keeps exact four-decimal values (22.4121…) from falling
    // one step short through binary rounding.
    (angle * 1e4 + 1e-7).floor() / 1e4
}
