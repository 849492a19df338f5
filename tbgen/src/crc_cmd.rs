//! `tbgen crc <algorithm> <bits>`: the CRC of a bit string as the seed
//! states it, and the CRC field's bits as they go on the wire.

use std::fmt::Write as _;

use model::crc;

use crate::{Error, Result};

/// Parses a string of `0` and `1` (spaces and `_` allowed as separators).
pub fn parse_bits(text: &str) -> Result<Vec<bool>> {
    let mut bits = Vec::new();
    for c in text.chars() {
        match c {
            '0' => bits.push(false),
            '1' => bits.push(true),
            ' ' | '_' => {}
            _ => return Err(Error::BadBits(text.to_string())),
        }
    }
    if bits.is_empty() {
        return Err(Error::BadBits(text.to_string()));
    }
    Ok(bits)
}

/// The report `tbgen crc` prints.
pub fn report(algorithm: &str, bits_text: &str) -> Result<String> {
    let alg = crc::by_name(algorithm).ok_or_else(|| {
        let names: Vec<&str> = crc::CATALOGUE.iter().map(|a| a.name).collect();
        Error::UnknownCrc(algorithm.to_string(), names.join(", "))
    })?;
    let bits = parse_bits(bits_text)?;
    let value = alg.checksum_bits(&bits);
    let wire = model::bits::string(&alg.wire_bits(value));
    let digits = (alg.width as usize).div_ceil(4);
    let mut out = String::new();
    let _ = writeln!(out, "algorithm: {} ({}-bit, poly 0x{:X}, init 0x{:X})", alg.name, alg.width, alg.poly, alg.init);
    let _ = writeln!(out, "source:    {}", alg.source);
    let _ = writeln!(out, "input:     {} bits", bits.len());
    let _ = writeln!(out, "crc:       0x{:0d$X} ({:0w$b})", value, value, d = digits, w = alg.width as usize);
    let _ = writeln!(out, "wire:      {wire}");
    Ok(out)
}
