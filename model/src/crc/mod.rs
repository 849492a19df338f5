//! The CRC catalogue: every checksum the encoder interfaces use, as named
//! constants in the shape of the `crc` / `crc-catalogue` crates, plus the one
//! bit-serial engine ([`BitSerial`]) that all of them run on.
//!
//! ```
//! use model::crc::{self, BitSerial, BISS_CRC6, ENDAT_CRC5, MODBUS_CRC16};
//!
//! // BiSS-C example of seed 001: 16 data bits, nE = 1, nW = 0, in wire order.
//! let bits: Vec<bool> = "100010101110001110".chars().map(|c| c == '1').collect();
//! let crc = BISS_CRC6.checksum_bits(&bits);
//! assert_eq!(crc, 0b110101); // the value as the seed states it
//! let wire: String = BISS_CRC6.wire_bits(crc).iter().map(|&b| if b { '1' } else { '0' }).collect();
//! assert_eq!(wire, "001010"); // what the scope shows on SLO, first bit first
//!
//! // The same, one bit per clock, as the RTL LFSR does it.
//! let mut lfsr = BitSerial::new(&BISS_CRC6);
//! for &b in &bits {
//!     lfsr.push(b);
//! }
//! assert_eq!(lfsr.value(), 0b110101);
//!
//! // Byte-oriented protocols: Modbus request `01 03 00 00 00 01 84 0A` of seed 001.
//! let crc = MODBUS_CRC16.checksum_bytes(&[0x01, 0x03, 0x00, 0x00, 0x00, 0x01]);
//! assert_eq!(MODBUS_CRC16.wire_bytes(crc), Some(vec![0x84, 0x0A]));
//!
//! // Look-up by the CLI name.
//! assert_eq!(crc::by_name("endat-crc5"), Some(&ENDAT_CRC5));
//! ```
//!
//! # The model every entry follows
//!
//! The parameters (`width`, `poly`, `init`, `refin`, `refout`, `xorout`,
//! `check`, `residue`) mean exactly what they mean in the `crc-catalogue`
//! (Rocksoft) model, so that [`Algorithm::checksum_bytes`] equals the `crc`
//! crate for the same parameters. On top of that every entry says how its
//! bits meet the cable:
//!
//! * **Into the CRC** ([`Algorithm::checksum_bits`]): the covered bits in
//!   *wire order*, the order they cross the cable, first bit first. The
//!   engine is a Galois LFSR of `width` stages; stage `i` holds the
//!   coefficient of `x^i`. Per bit `d`: `fb = stage[width-1] ^ d`, shift every
//!   stage up by one, stage 0 takes 0, then XOR `poly` into the register if
//!   `fb`. Stages are preset to `init`. This is the EnDat appendix's circuit
//!   (`ff[i]` of `MakeCrcPos` is stage `i`) and the shape of the one
//!   parameterised LFSR the RTL uses. `refin` only says how
//!   [`Algorithm::checksum_bytes`] turns a byte into wire-order bits
//!   (`true`: bit 0 first, as a UART sends it; `false`: bit 7 first).
//! * **Out of the CRC** ([`Algorithm::checksum_bits`]'s result, and
//!   [`BitSerial::value`]): the register, bit-reversed if `refout`, XOR
//!   `xorout`. This is "the CRC as the seed states it" (EnDat: what
//!   `MakeCrcPos` returns; BiSS: `110101` in the seed's example).
//! * **Onto the wire** ([`Algorithm::wire_bits`]): the stated value XOR
//!   [`Algorithm::wire_xor`] (BiSS: the CRC is sent inverted), then its bits
//!   in [`Algorithm::wire_order`]. The CRC field only: UART start and stop
//!   bits, CAN stuff bits and delimiters are the framer's business.
//!
//! For every entry the wire order is the one that makes message + CRC field
//! a codeword: feeding the CRC field's wire bits into the same LFSR after the
//! message leaves the register at [`Algorithm::wire_residue`], whatever the
//! message. A receiver in RTL can therefore check a frame with the same LFSR
//! and one comparator.
//!
//! The seeds write polynomials in different hex notations (ESL's `8'h97` is
//! Koopman notation); [`notation`] converts between them and explains the
//! ESL case. `docs/crc.md` has the catalogue as a table.

mod catalogue;
pub mod notation;

pub use catalogue::*;
pub use notation::PolyNotation;

/// How the bits of a CRC field follow each other on the cable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum WireOrder {
    /// Highest bit of the CRC first (`crc[width-1]` first, `crc[0]` last).
    /// EnDat, BiSS-C, CAN.
    MsbFirst,
    /// Lowest bit of the CRC first (`crc[0]` first). For CRCs of 16 bits on a
    /// UART this is "low byte first, each byte LSB first": ESL CRC-16
    /// (`CRCx.1` = `crc[7:0]` then `CRCx.2` = `crc[15:8]`), Modbus (low byte
    /// first). T-format, ESL CRC-8.
    LsbFirst,
}

/// A hex value the seed prints for the polynomial, and the notation it is
/// written in (see [`PolyNotation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub struct StatedHex {
    /// The value exactly as printed (`0x97` for ESL's `8'h97`).
    pub value: u64,
    /// The notation in which that value denotes the generator polynomial.
    pub notation: PolyNotation,
}

/// One CRC algorithm: the Rocksoft / `crc-catalogue` parameters, its check
/// values, where the seeds define it, and how it is put on the wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub struct Algorithm {
    /// Kebab-case name used on the command line and in scenario files,
    /// e.g. `"endat-crc5"`.
    pub name: &'static str,
    /// Human-readable title, e.g. `"EnDat 2.2 CRC-5"`.
    pub title: &'static str,
    /// Number of CRC bits (the degree of the generator polynomial).
    pub width: u32,
    /// Generator polynomial in normal notation: bit `i` is the coefficient of
    /// `x^i`, the `x^width` term implicit (crc-catalogue `poly`).
    pub poly: u64,
    /// Preset of the LFSR stages before the first covered bit (stage `i` =
    /// bit `i`), as in crc-catalogue.
    pub init: u64,
    /// `true`: [`Algorithm::checksum_bytes`] feeds each byte bit 0 first (as a
    /// UART sends it); `false`: bit 7 first.
    pub refin: bool,
    /// `true`: the stated CRC is the LFSR register bit-reversed (stage
    /// `width-1` becomes bit 0).
    pub refout: bool,
    /// XORed onto the (possibly reflected) register to give the CRC as the
    /// seed states it.
    pub xorout: u64,
    /// CRC of the nine ASCII bytes `"123456789"` through
    /// [`Algorithm::checksum_bytes`] (the crc-catalogue check value).
    pub check: u64,
    /// crc-catalogue residue: the register after an error-free codeword
    /// (message, then the stated CRC in the algorithm's natural order),
    /// reflected if `refout`, without `xorout`. For what an RTL checker sees
    /// on the wire, use [`Algorithm::wire_residue`].
    pub residue: u64,
    /// XORed onto the stated CRC before it is transmitted (BiSS-C: `0x3F`,
    /// the CRC is sent inverted; all others 0).
    pub wire_xor: u64,
    /// Order of the CRC field's bits on the wire.
    pub wire_order: WireOrder,
    /// The covered bits are zero-padded at the end to a multiple of this many
    /// bits before the CRC is computed (ESL CRC-16: 16, "If # of field is odd
    /// number, the last 8-bit will be padded with 0's"); 1 means no padding.
    /// Applied by [`Algorithm::checksum_frame_bits`], not by
    /// [`Algorithm::checksum_bits`].
    pub pad_to_multiple: u32,
    /// The generator as an equation, as the seed writes it (or, for EnDat, as
    /// read off the seed's shift code). Parsed by
    /// [`notation::parse_polynomial`] in the tests.
    pub poly_equation: &'static str,
    /// The hex value the specification prints for the polynomial, if any,
    /// with its notation (the seed's; for CAN, ISO 11898-1's `0x4599`).
    pub stated_hex: Option<StatedHex>,
    /// Which bits the CRC covers, in which order.
    pub covers: &'static str,
    /// The seed file and section the algorithm comes from.
    pub source: &'static str,
}

/// Every algorithm of the catalogue, in the order of `docs/crc.md`.
pub const CATALOGUE: &[&Algorithm] = &[
    &ENDAT_CRC5,
    &BISS_CRC6,
    &BISS_CTRL_CRC4,
    &TFORMAT_CRC8,
    &ESL_CRC8,
    &ESL_CRC16_CH1,
    &ESL_CRC16_CH2,
    &MODBUS_CRC16,
    &CAN_CRC15,
];

/// The catalogue entry with this kebab-case name (`"biss-crc6"`), if any.
pub fn by_name(name: &str) -> Option<&'static Algorithm> {
    CATALOGUE.iter().copied().find(|a| a.name == name)
}

/// All-ones mask of `width` bits (`width` in 1..=64).
pub const fn mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

/// The low `width` bits of `value` in reverse order (`width` in 1..=64).
pub const fn reflect(value: u64, width: u32) -> u64 {
    (value & mask(width)).reverse_bits() >> (64 - width)
}

impl Algorithm {
    /// CRC over `bits` given in wire order (the order they cross the cable,
    /// first bit first), computed bit-serially exactly as the RTL LFSR does
    /// (see [`BitSerial`]). Returns the CRC as the seed states it: register,
    /// reflected if `refout`, XOR `xorout`; *before* [`Algorithm::wire_xor`]
    /// (BiSS: `0b110101` for the seed example, which the cable carries as
    /// `001010`).
    pub fn checksum_bits(&self, bits: &[bool]) -> u64 {
        let mut lfsr = BitSerial::new(self);
        lfsr.push_bits(bits);
        lfsr.value()
    }

    /// CRC over whole bytes, each byte turned into wire-order bits by `refin`
    /// (bit 0 first if `refin`, else bit 7 first). Equals the `crc` crate for
    /// the same parameters.
    pub fn checksum_bytes(&self, bytes: &[u8]) -> u64 {
        let mut lfsr = BitSerial::new(self);
        for &byte in bytes {
            lfsr.push_byte(byte);
        }
        lfsr.value()
    }

    /// [`Algorithm::checksum_bits`] after the seed's padding rule
    /// ([`Algorithm::pad_to_multiple`]): pass all covered bits of one frame
    /// set (fields without start and stop bits, in wire order). Equal to
    /// `checksum_bits` for every entry but ESL CRC-16.
    pub fn checksum_frame_bits(&self, covered: &[bool]) -> u64 {
        self.checksum_bits(&self.padded(covered))
    }

    /// `covered` with zeros appended up to a multiple of
    /// [`Algorithm::pad_to_multiple`] bits.
    pub fn padded(&self, covered: &[bool]) -> Vec<bool> {
        let mut bits = covered.to_vec();
        let unit = self.pad_to_multiple.max(1) as usize;
        bits.resize(bits.len().div_ceil(unit) * unit, false);
        bits
    }

    /// The bits of the CRC field in wire order, as transmitted: `crc` (the
    /// stated value, as [`Algorithm::checksum_bits`] returns it) XOR
    /// [`Algorithm::wire_xor`], then bit `width-1` first
    /// ([`WireOrder::MsbFirst`]) or bit 0 first ([`WireOrder::LsbFirst`]).
    /// For the 16-bit UART CRCs (ESL, Modbus) `LsbFirst` is the low byte's
    /// bits 0..7 then the high byte's bits 0..7: exactly the data bits of
    /// the two UART characters, without their start and stop bits.
    pub fn wire_bits(&self, crc: u64) -> Vec<bool> {
        let v = (crc ^ self.wire_xor) & mask(self.width);
        let w = self.width;
        match self.wire_order {
            WireOrder::MsbFirst => (0..w).rev().map(|i| (v >> i) & 1 == 1).collect(),
            WireOrder::LsbFirst => (0..w).map(|i| (v >> i) & 1 == 1).collect(),
        }
    }

    /// The inverse of [`Algorithm::wire_bits`]: the stated CRC from the
    /// received CRC field (wire order). `None` unless `bits.len() == width`.
    pub fn crc_from_wire_bits(&self, bits: &[bool]) -> Option<u64> {
        if bits.len() != self.width as usize {
            return None;
        }
        let w = self.width;
        let v = bits.iter().enumerate().fold(0u64, |acc, (k, &b)| {
            let i = match self.wire_order {
                WireOrder::MsbFirst => w - 1 - k as u32,
                WireOrder::LsbFirst => k as u32,
            };
            acc | (u64::from(b) << i)
        });
        Some(v ^ self.wire_xor)
    }

    /// For byte-oriented protocols (width a multiple of 8, LSB first): the
    /// CRC bytes in the order they are sent, each to be sent LSB first by the
    /// UART. Modbus: `[low, high]`; ESL CRC-16: `[CRCx.1, CRCx.2]`. `None` for
    /// bit-oriented CRCs.
    pub fn wire_bytes(&self, crc: u64) -> Option<Vec<u8>> {
        if self.wire_order != WireOrder::LsbFirst || self.width & 7 != 0 {
            return None;
        }
        let v = crc ^ self.wire_xor;
        Some((0..self.width / 8).map(|k| (v >> (8 * k)) as u8).collect())
    }

    /// The raw LFSR register (stage `i` = bit `i`, no reflection, no XOR)
    /// after any message followed by its correct CRC field as
    /// [`Algorithm::wire_bits`] sends it. Message-independent; an RTL
    /// receiver that clocks the CRC field through its LFSR compares against
    /// this constant.
    pub fn wire_residue(&self) -> u64 {
        let mut lfsr = BitSerial::new(self);
        let crc = lfsr.value();
        lfsr.push_bits(&self.wire_bits(crc));
        lfsr.register()
    }

    /// The generator polynomial with its `x^width` term: bit `i` is the
    /// coefficient of `x^i`.
    pub fn generator(&self) -> u128 {
        (1u128 << self.width) | u128::from(self.poly)
    }

    /// This algorithm's generator in another hex notation.
    pub fn poly_in(&self, notation: PolyNotation) -> u64 {
        notation.encode(self.generator(), self.width)
    }
}

/// The CRC shift register, stepped one bit at a time: what the RTL mirrors,
/// one [`BitSerial::push`] per bit clock.
///
/// Stage `i` of the register holds the coefficient of `x^i`; a push of bit
/// `d` computes `fb = stage[width-1] ^ d`, shifts the stages up by one
/// (stage 0 takes 0) and, if `fb`, XORs the generator's `poly` into the
/// register. For EnDat this is, stage for stage, the `ff[0..4]` update of the
/// seed's `MakeCrcPos`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BitSerial {
    alg: Algorithm,
    reg: u64,
}

impl BitSerial {
    /// A register preset to the algorithm's `init`.
    pub fn new(alg: &Algorithm) -> Self {
        BitSerial {
            alg: *alg,
            reg: alg.init & mask(alg.width),
        }
    }

    /// Preset the register to `init` again (the start of the next frame).
    pub fn reset(&mut self) {
        self.reg = self.alg.init & mask(self.alg.width);
    }

    /// Shift in one covered bit (one clock of the LFSR).
    pub fn push(&mut self, bit: bool) {
        let w = self.alg.width;
        let fb = ((self.reg >> (w - 1)) & 1 == 1) ^ bit;
        self.reg = if w >= 64 {
            self.reg << 1
        } else {
            (self.reg << 1) & mask(w)
        };
        if fb {
            self.reg ^= self.alg.poly;
        }
    }

    /// Shift in several bits, first element first.
    pub fn push_bits(&mut self, bits: &[bool]) {
        for &b in bits {
            self.push(b);
        }
    }

    /// Shift in one byte in the algorithm's byte order (`refin`: bit 0
    /// first, else bit 7 first).
    pub fn push_byte(&mut self, byte: u8) {
        for k in 0..8 {
            let i = if self.alg.refin { k } else { 7 - k };
            self.push((byte >> i) & 1 == 1);
        }
    }

    /// The raw register: bit `i` = stage `i` (no reflection, no XOR). This is
    /// what a waveform of the RTL LFSR shows.
    pub fn register(&self) -> u64 {
        self.reg
    }

    /// The CRC as the seed states it for the bits pushed so far: the
    /// register, reflected if `refout`, XOR `xorout`.
    pub fn value(&self) -> u64 {
        let a = &self.alg;
        let r = if a.refout {
            reflect(self.reg, a.width)
        } else {
            self.reg
        };
        (r ^ a.xorout) & mask(a.width)
    }

    /// The algorithm this register runs.
    pub fn algorithm(&self) -> &Algorithm {
        &self.alg
    }
}
