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

/// Parses bytes given in hex (`01 03 0A`, `0x01,0x03`, or `01030A`).
pub fn parse_bytes(words: &[String]) -> Result<Vec<u8>> {
    let bad = || Error::BadBytes(words.join(" "));
    let mut bytes = Vec::new();
    for word in words
        .iter()
        .flat_map(|w| w.split([',', ' ']))
        .filter(|w| !w.is_empty())
    {
        let hex = word
            .strip_prefix("0x")
            .or_else(|| word.strip_prefix("0X"))
            .unwrap_or(word);
        if hex.is_empty() || hex.len() % 2 != 0 {
            return Err(bad());
        }
        for i in (0..hex.len()).step_by(2) {
            bytes.push(
                u8::from_str_radix(hex.get(i..i + 2).ok_or_else(bad)?, 16).map_err(|_| bad())?,
            );
        }
    }
    if bytes.is_empty() {
        return Err(bad());
    }
    Ok(bytes)
}

fn algorithm(name: &str) -> Result<&'static crc::Algorithm> {
    crc::by_name(name).ok_or_else(|| {
        let names: Vec<&str> = crc::CATALOGUE.iter().map(|a| a.name).collect();
        Error::UnknownCrc(name.to_string(), names.join(", "))
    })
}

/// The report `tbgen crc <algorithm> --bytes ...` prints: the CRC over whole
/// bytes, each sent bit 0 first if the algorithm reflects its input (the
/// UART convention of Modbus, T-format, ESL), else bit 7 first.
pub fn report_bytes(name: &str, words: &[String]) -> Result<String> {
    let alg = algorithm(name)?;
    let bytes = parse_bytes(words)?;
    let bits: Vec<bool> = bytes
        .iter()
        .flat_map(|&b| {
            (0..8).map(move |i| {
                if alg.refin {
                    b >> i & 1 == 1
                } else {
                    b >> (7 - i) & 1 == 1
                }
            })
        })
        .collect();
    let value = alg.checksum_bytes(&bytes);
    debug_assert_eq!(value, alg.checksum_bits(&bits));
    Ok(format_report(
        alg,
        &format!(
            "{} bytes ({} bits, each {})",
            bytes.len(),
            bits.len(),
            if alg.refin {
                "bit 0 first"
            } else {
                "bit 7 first"
            }
        ),
        value,
    ))
}

/// The report `tbgen crc` prints.
pub fn report(algorithm_name: &str, bits_text: &str) -> Result<String> {
    let alg = algorithm(algorithm_name)?;
    let bits = parse_bits(bits_text)?;
    let value = alg.checksum_bits(&bits);
    Ok(format_report(alg, &format!("{} bits", bits.len()), value))
}

fn format_report(alg: &crc::Algorithm, input: &str, value: u64) -> String {
    let wire = model::bits::string(&alg.wire_bits(value));
    let digits = (alg.width as usize).div_ceil(4);
    let mut out = String::new();
    let _ = writeln!(
        out,
        "algorithm: {} ({}-bit, poly 0x{:X}, init 0x{:X})",
        alg.name, alg.width, alg.poly, alg.init
    );
    let _ = writeln!(out, "source:    {}", alg.source);
    let _ = writeln!(out, "input:     {input}");
    let _ = writeln!(
        out,
        "crc:       0x{:0d$X} ({:0w$b})",
        value,
        value,
        d = digits,
        w = alg.width as usize
    );
    let _ = writeln!(out, "wire:      {wire}");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_of_the_modbus_example_give_its_crc() {
        // seed 001, Modbus RTU (4): request 01 03 00 00 00 01 ends with CRC 84 0A
        // (low byte first), i.e. the CRC value 0x0A84.
        let r = report_bytes("modbus-crc16", &["01 03 00 00 00 01".into()]).unwrap();
        assert!(r.contains("crc:       0x0A84"), "{r}");
        assert!(r.contains("6 bytes (48 bits, each bit 0 first)"), "{r}");
        assert_eq!(
            report_bytes("modbus-crc16", &["0x01,0x03".into(), "00000001".into()])
                .unwrap()
                .lines()
                .nth(3),
            r.lines().nth(3)
        );
    }

    #[test]
    fn bad_bytes_say_how_to_write_them() {
        for bad in ["1", "0G", "", "0x"] {
            let e = report_bytes("modbus-crc16", &[bad.into()])
                .unwrap_err()
                .to_string();
            assert!(e.contains("hex"), "{bad}: {e}");
        }
    }
}
