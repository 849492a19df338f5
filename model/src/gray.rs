//! Reflected binary (Gray) code, as SSI and BiSS encoders send it.

/// Binary to Gray: adjacent positions differ in one bit on the wire.
pub fn to_gray(binary: u64) -> u64 {
    binary ^ (binary >> 1)
}

/// Gray to binary: each binary bit is the XOR of all Gray bits at or above it.
pub fn from_gray(gray: u64) -> u64 {
    let mut binary = gray;
    let mut shift = 1;
    while shift < 64 {
        binary ^= binary >> shift;
        shift <<= 1;
    }
    binary
}
