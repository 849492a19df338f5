//! The named algorithms. Each doc comment says what is covered, in which
//! order the bits enter the LFSR and how the CRC field leaves it; the numbers
//! are pinned by `tests.rs` against the seeds' examples, ported seed code and
//! the `crc` crate.

use super::{Algorithm, PolyNotation, StatedHex, WireOrder};

/// EnDat 2.1/2.2 CRC-5 (seed 004, appendix A4).
///
/// **Generator** `x^5 + x^3 + x + 1` (normal `0x0B`), read off the shift code
/// of `MakeCrcNorm` / `MakeCrcPos`: `ex = ff[4] ^ bit; ff[4] = ff[3];
/// ff[3] = ff[2] ^ ex; ff[2] = ff[1]; ff[1] = ff[0] ^ ex; ff[0] = ex;` feeds
/// back into stages 0, 1 and 3. `ff[i]` is stage `i` of [`BitSerial`](super::BitSerial).
/// **Preset** all flip-flops to 1 (`init = 0x1F`, "Preload flip-flops via Set
/// with a logical 1"). **Output** inverted (`xorout = 0x1F`), `ff[4]` as the
/// MSB of the returned value (`refout = false`). The value this catalogue
/// returns is the one the seed's functions return (`MakeCrcNorm(13, 32793)
/// = 14`, `MakeCrcPos(25, 0, 1, 1, 0, 104462) = 3`).
///
/// **Covered bits, in wire order** (the order the encoder sends them and the
/// C code loads `code[]`; the start bit is never covered):
/// * position value (`MakeCrcPos`): EnDat 2.2 mode commands: F1 (error 1),
///   F2 (error 2), then the `clocks` position (or test value) bits
///   **LSB first**; EnDat 2.1: F1, then the position bits LSB first.
/// * everything else (`MakeCrcNorm`: parameters, memory-area selection,
///   reset/test acknowledgements, each 24-bit additional datum): the 8-bit
///   part **MSB first** then the 16-bit part **MSB first**, i.e. for
///   additional data WRN, RM, Busy, I4..I0, then D15..D0.
///
/// **On the wire** the 5 CRC bits follow the last covered bit, CRC bit 4
/// (the inverted `ff[4]`) first ([`WireOrder::MsbFirst`]). The seed's
/// timing figures are lost in the text extraction; this is the order in
/// which the appendix's generator shifts its register out ("3. Output CRC
/// code") and the one that makes data + CRC a codeword
/// ([`Algorithm::wire_residue`] = `0x08`).
pub const ENDAT_CRC5: Algorithm = Algorithm {
    name: "endat-crc5",
    title: "EnDat 2.2 CRC-5",
    width: 5,
    poly: 0x0B,
    init: 0x1F,
    refin: false,
    refout: false,
    xorout: 0x1F,
    check: 0x19,
    residue: 0x08,
    wire_xor: 0,
    wire_order: WireOrder::MsbFirst,
    pad_to_multiple: 1,
    poly_equation: "x^5 + x^3 + x + 1",
    stated_hex: None,
    covers: "position frames: F1, F2 (type 2.2 only), position LSB first; \
             parameter / additional-data frames: 8-bit part MSB first, then 16-bit part MSB first",
    source:
        "seed 004 (HEIDENHAIN EnDat 2.2, D297403), appendix A4 'Cyclic redundancy check': \
             4.4.1 Hardware CRC generation, 4.4.2 Software CRC generation (MakeCrcNorm, MakeCrcPos)",
};

/// BiSS-C CRC-6 (seed 001, BiSS-C section).
///
/// **Generator** `x^6 + x + 1` (normal `0x03`; the seed's extracted text
/// reads "g(x)=xA^6 + xM + xA0"). **Initial value** 0, no reflection: the
/// seed's example (16-bit data `1000101011100011`, nE = 1, nW = 0, "the
/// calculated CRC check code is 110101") is only reproduced with init 0.
/// The value returned is that "CRC check code" (`xorout = 0`).
///
/// **Covered bits, in wire order:** the position data MSB first, then nE
/// (error, active low), then nW (warning, active low). Not covered: the ack
/// low phase, the start bit and the CDS bit.
///
/// **On the wire** the CRC is sent inverted ("6-bit negative logic CRC
/// check code": [`Algorithm::wire_xor`] = `0x3F`), MSB first: `110101` goes
/// out as `001010`.
pub const BISS_CRC6: Algorithm = Algorithm {
    name: "biss-crc6",
    title: "BiSS-C CRC-6",
    width: 6,
    poly: 0x03,
    init: 0x00,
    refin: false,
    refout: false,
    xorout: 0x00,
    check: 0x11,
    residue: 0x00,
    wire_xor: 0x3F,
    wire_order: WireOrder::MsbFirst,
    pad_to_multiple: 1,
    poly_equation: "x^6 + x + 1",
    stated_hex: None,
    covers: "position data MSB first, then nE, then nW (not the start and CDS bits)",
    source: "seed 001 (SAR58K24 manual), BiSS-C section: 'Following the position signal are error bits, \
             warning bits, and a 6-bit negative logic CRC check code' and the 16-bit example",
};

/// BiSS-C control-frame CRC-4 (register access).
///
/// **Generator** `x^4 + x + 1` (normal `0x03`), initial value 0, no
/// reflection, sent **inverted**, MSB first: the same conventions as
/// [`BISS_CRC6`] with a 4-bit generator. Seed 001 names BiSS-C and its CDS bit
/// but not the control frame; the CRC-4 comes from the public BiSS C protocol
/// description (register access), as encoder manuals restate it
/// ("Polynomial: X^4 + X^1 + 1 (binary: 10011)", "inverted output") and as
/// `docs/timing/biss.md` records.
///
/// **Covered bits, in wire order:** for the address part CTS, ID2..ID0,
/// ADR6..ADR0 (11 bits, not the start bit); for the data part D7..D0.
///
/// **On the wire** 4 bits, MSB first, inverted ([`Algorithm::wire_xor`] = `0xF`).
pub const BISS_CTRL_CRC4: Algorithm = Algorithm {
    name: "biss-ctrl-crc4",
    title: "BiSS-C control-frame CRC-4",
    width: 4,
    poly: 0x03,
    init: 0x00,
    refin: false,
    refout: false,
    xorout: 0x00,
    check: 0x0E,
    residue: 0x00,
    wire_xor: 0x0F,
    wire_order: WireOrder::MsbFirst,
    pad_to_multiple: 1,
    poly_equation: "x^4 + x + 1",
    stated_hex: None,
    covers: "control frame: CTS, ID2..ID0, ADR6..ADR0 MSB first; or D7..D0 MSB first (not the start bits)",
    source: "seed 001 (SAR58K24 manual) BiSS-C section for the frame; control-frame CRC from the public \
             BiSS C protocol description (register access), see docs/timing/biss.md",
};

/// Tamagawa T-format CRC-8 (seed 002, 6.3.4 "CRC Field (CRC)", Figure 7).
///
/// **Generator** `G(X) = X^8 + 1` (normal `0x01`), initial value 0 (the seed
/// names none), no output XOR. "The code is calculated from all bits
/// without Start bit and Delimiter of all fields except CRC field."
///
/// **Covered bits, in wire order:** the 8 data bits of every 10-bit
/// character of the frame before the CRC field, each character bit 0 first
/// ("arranged with LSB first"): CF (sink code, data ID cc0..cc3, parity
/// cc4), SF, then DF0.. (readout) or ADF, EDF (EEPROM access).
///
/// **On the wire** the CRC character's data bits, LSB first ("The data is
/// arranged in LSB first"; `refin = refout = true`, the UART convention).
/// Since `x^8 ≡ 1 (mod G)`, the CRC is simply the XOR of the covered bytes
/// (a test pins this); the reflection flags do not change the value, they
/// only keep the convention uniform with the other UART protocols.
pub const TFORMAT_CRC8: Algorithm = Algorithm {
    name: "tformat-crc8",
    title: "Tamagawa T-format CRC-8 (X^8 + 1)",
    width: 8,
    poly: 0x01,
    init: 0x00,
    refin: true,
    refout: true,
    xorout: 0x00,
    check: 0x31,
    residue: 0x00,
    wire_xor: 0,
    wire_order: WireOrder::LsbFirst,
    pad_to_multiple: 1,
    poly_equation: "X^8 + 1",
    stated_hex: None,
    covers: "all fields before the CRC field (CF, SF, DFn or ADF, EDF) without start bits and delimiters, \
             each field LSB first",
    source: "seed 002 (Tamagawa TS5669 N127), 6.3.4 CRC Field (CRC), Figure 7",
};

/// ESL CRC-8, the non-safety CRC (seed 000, "Cyclic Redundancy Check Frame
/// (CRC)", note "8 Bit", Figure 11; Table 1).
///
/// **Generator** `X^8 + X^5 + X^3 + X^2 + X + 1`, printed by the seed as
/// `Poly = 8'h97`: that is **Koopman** notation (`x^8 … x^1` in bits 7..0,
/// the `+1` implicit); normal notation `0x2F`. See
/// [`notation`](super::notation) for the derivation. (The seed's heading of
/// this line says "CRC-16 Polynomial"; a typo, the equation is of degree 8.)
/// **Initial value** `8'h00` (the seed's garbled line "CH1 CRC initial value;
/// CH2 CRC initial value = 8'h00"). No output XOR.
///
/// **Covered bits, in wire order:** "all bits without Start and Stop bit of
/// all fields except CRC field": the 8 data bits of each 10-bit character
/// before the CRC (CF, SF, DFn, or ADF, EDF), each LSB first as sent.
///
/// **On the wire** "CRC Field is transmitted from LSB first" (cr0 first).
/// The seed gives no worked example and does not say how the register maps
/// onto cr0..cr7; this entry takes the convention in which message + CRC is
/// a codeword (`refin = refout = true`, as for Modbus and T-format): cr0 is
/// the register stage of `x^7`. Verify against a capture of a real encoder.
pub const ESL_CRC8: Algorithm = Algorithm {
    name: "esl-crc8",
    title: "ESL CRC-8 (non-safety)",
    width: 8,
    poly: 0x2F,
    init: 0x00,
    refin: true,
    refout: true,
    xorout: 0x00,
    check: 0x43,
    residue: 0x00,
    wire_xor: 0,
    wire_order: WireOrder::LsbFirst,
    pad_to_multiple: 1,
    poly_equation: "X^8 + X^5 + X^3 + X^2 + X + 1",
    stated_hex: Some(StatedHex {
        value: 0x97,
        notation: PolyNotation::Koopman,
    }),
    covers: "all fields before the CRC field without start and stop bits, each field LSB first",
    source:
        "seed 000 (QS35 ESL Safety protocol), 'Cyclic Redundancy Check Frame (CRC)', note '8 Bit', \
             Figure 11; Table 1",
};

/// ESL CRC-16 of safety channel 1 (seed 000, "Cyclic Redundancy Check Frame
/// (CRC)", note "16 Bit", Figure 10).
///
/// **Generator** `X^16 + X^14 + X^12 + X^11 + X^8 + X^5 + X^4 + X^2 + 1`,
/// printed as `Poly = 16'hAC9A`: **Koopman** notation (this generator is a
/// palindrome, so 0xAC9A is also its reversed notation; the CRC-8 line
/// settles that the seed writes Koopman). Normal notation `0x5935`.
/// **Initial value** `16'h0000` ("CH1 CRC initial value = 16'h0000").
///
/// **Covered bits, in wire order:** "all bits without Start and Stop bit of
/// all fields except CRC field", each field LSB first; "If # of field is
/// odd number, the last 8-bit will be padded with 0's"
/// ([`Algorithm::pad_to_multiple`] = 16, applied by
/// [`Algorithm::checksum_frame_bits`]). For the safety frame sets of
/// Table 12 the channel-1 CRC follows CF1, SF1, DF0..DFn, SC1.
///
/// **On the wire** "CRC Field is transmitted from LSB first", as two 10-bit
/// characters: "Full CRC (16b) = {CRCx.2, CRCx.1}", so `CRCx.1` = bits 7..0
/// goes first, then `CRCx.2` = bits 15..8, each LSB first. (Table 12 prints
/// the pair as `{CRC1.1, CRC1.2}` for CH1 and `{CRC2.2, CRC2.1}` for CH2; the
/// note's definition is taken as authoritative.) As for [`ESL_CRC8`], the
/// register-to-cr mapping is the codeword convention (`refin = refout =
/// true`); the seed gives no worked example.
pub const ESL_CRC16_CH1: Algorithm = Algorithm {
    name: "esl-crc16-ch1",
    title: "ESL CRC-16, safety channel 1",
    width: 16,
    poly: 0x5935,
    init: 0x0000,
    refin: true,
    refout: true,
    xorout: 0x0000,
    check: 0xFAD9,
    residue: 0x0000,
    wire_xor: 0,
    wire_order: WireOrder::LsbFirst,
    pad_to_multiple: 16,
    poly_equation: "X^{16} + X^{14} + X^{12} + X^{11} + X^8 + X^5 + X^4 + X^2 + 1",
    stated_hex: Some(StatedHex { value: 0xAC9A, notation: PolyNotation::Koopman }),
    covers: "channel-1 fields before CRC1 (CF1, SF1, DFn, SC1) without start and stop bits, each LSB first, \
             zero-padded to a whole number of 16-bit pairs",
    source: "seed 000 (QS35 ESL Safety protocol), 'Cyclic Redundancy Check Frame (CRC)', note '16 Bit', \
             Figure 10; Table 12",
};

/// ESL CRC-16 of safety channel 2: [`ESL_CRC16_CH1`] with initial value
/// `16'hFFFF` ("CH2 CRC initial value = 16'hFFFF"), seed 000 note "16 Bit".
///
/// **Covered bits:** as for channel 1, over the channel-2 fields of Table 12
/// (CF2, SF2, ALM2, RS0, RS1, SC2), each LSB first, zero-padded to a whole
/// number of 16-bit pairs. **On the wire** `CRC2.1` (bits 7..0) then `CRC2.2`
/// (bits 15..8), each LSB first.
pub const ESL_CRC16_CH2: Algorithm = Algorithm {
    name: "esl-crc16-ch2",
    title: "ESL CRC-16, safety channel 2",
    init: 0xFFFF,
    check: 0x328D,
    covers:
        "channel-2 fields before CRC2 (CF2, SF2, ALM2, RS0, RS1, SC2) without start and stop bits, \
             each LSB first, zero-padded to a whole number of 16-bit pairs",
    ..ESL_CRC16_CH1
};

/// Modbus RTU CRC-16 (seed 001, Modbus RTU: "(4) Function code 03",
/// "(5) data frame format", "The steps to calculate CRC code are").
///
/// **Generator** printed as `A001 (1010 0000 0000 0001)` for a right-shifting
/// register: **reversed** notation of `x^16 + x^15 + x^2 + 1` (normal
/// `0x8005`). Preset `FFFF`, no output XOR; identical to crc-catalogue
/// CRC-16/MODBUS. (The seed's step 2 says the byte is "OR"ed into the
/// register; it means XOR, as the seed's own example frames prove.)
///
/// **Covered bits:** every byte of the RTU frame before the CRC (address,
/// function code, data), each byte LSB first as the UART sends it.
///
/// **On the wire** "the high and low bits are exchanged, with the low bits
/// in front": low byte first, then high byte, each LSB first (the CRC value
/// `0x0A84` of the request `01 03 00 00 00 01` is sent as `84 0A`).
pub const MODBUS_CRC16: Algorithm = Algorithm {
    name: "modbus-crc16",
    title: "Modbus RTU CRC-16",
    width: 16,
    poly: 0x8005,
    init: 0xFFFF,
    refin: true,
    refout: true,
    xorout: 0x0000,
    check: 0x4B37,
    residue: 0x0000,
    wire_xor: 0,
    wire_order: WireOrder::LsbFirst,
    pad_to_multiple: 1,
    poly_equation: "x^16 + x^15 + x^2 + 1",
    stated_hex: Some(StatedHex {
        value: 0xA001,
        notation: PolyNotation::Reversed,
    }),
    covers:
        "all bytes of the RTU frame before the CRC (address, function, data), each byte LSB first",
    source: "seed 001 (SAR58K24 manual), Modbus RTU: (4) Function code 03, (5) data frame format, \
             'The steps to calculate CRC code are'",
};

/// CAN (classical, ISO 11898-1) CRC-15.
///
/// **Generator** `x^15 + x^14 + x^10 + x^8 + x^7 + x^4 + x^3 + 1` (normal
/// `0x4599`), initial value 0, no reflection, no output XOR; identical to
/// crc-catalogue CRC-15/CAN. The seeds carry CAN/CANopen frames (seed 001
/// CAN mode, seed 003 CANopen gateway) only at the byte level; the CRC is
/// ISO 11898-1's.
///
/// **Covered bits, in wire order:** the destuffed bit stream from SOF
/// through the end of the data field: SOF, arbitration field (identifier
/// MSB first, RTR; for extended frames SRR, IDE, the 18-bit extension),
/// control field (IDE/r1, r0, DLC MSB first), data bytes each MSB first.
///
/// **On the wire** the 15-bit CRC sequence MSB first, followed by the
/// recessive CRC delimiter. In classical CAN the CRC sequence is itself
/// subject to bit stuffing; [`Algorithm::wire_bits`] returns it unstuffed.
pub const CAN_CRC15: Algorithm = Algorithm {
    name: "can-crc15",
    title: "CAN CRC-15 (ISO 11898-1)",
    width: 15,
    poly: 0x4599,
    init: 0x0000,
    refin: false,
    refout: false,
    xorout: 0x0000,
    check: 0x059E,
    residue: 0x0000,
    wire_xor: 0,
    wire_order: WireOrder::MsbFirst,
    pad_to_multiple: 1,
    poly_equation: "x^15 + x^14 + x^10 + x^8 + x^7 + x^4 + x^3 + 1",
    stated_hex: Some(StatedHex {
        value: 0x4599,
        notation: PolyNotation::Normal,
    }),
    covers: "SOF, arbitration, control and data fields, destuffed, MSB first",
    source: "ISO 11898-1 CRC field (not restated in the seeds); CAN frames of seed 001 (CAN mode) \
             and seed 003 (Leine & Linde CANopen gateway)",
};
