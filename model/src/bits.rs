//! Bits as the transcripts write them: a string of `0` and `1` in wire
//! order, the form engineers compare with a scope capture.

/// `bits` in order, e.g. `[true, false, true]` → `"101"`.
pub fn string(bits: &[bool]) -> String {
    bits.iter().map(|&b| if b { '1' } else { '0' }).collect()
}

/// The low `width` bits of `value`, MSB first (`string_of(5, 4)` → `"0101"`).
pub fn string_of(value: u128, width: u32) -> String {
    (0..width)
        .rev()
        .map(|i| if (value >> i) & 1 == 1 { '1' } else { '0' })
        .collect()
}

/// Bytes in wire order as two hex digits each, space-separated
/// (`[0xFF, 0x81, 0x01]` → `"FF 81 01"`), as the byte-oriented transcripts
/// (SAR58K24, Modbus, CAN data) write them.
pub fn hex(bytes: &[u8]) -> String {
    bytes
        .iter()
        .map(|b| format!("{b:02X}"))
        .collect::<Vec<_>>()
        .join(" ")
}
