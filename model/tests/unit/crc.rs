//! Tests of the CRC catalogue. Seed examples cite the seed section they come
//! from; the differential tests run the catalogue engine against the seeds'
//! own code (ported in `seed_reference.rs`), the `crc` crate and a
//! polynomial long division.

use crate::seed_reference::{make_crc_norm, make_crc_pos, modbus_crc_seed_steps};
use model::crc::notation::{format_polynomial, generator_from_exponents, parse_polynomial};
use model::crc::*;
use proptest::prelude::*;

/// `"1010"` → bits, first character first.
fn bits(s: &str) -> Vec<bool> {
    s.chars()
        .filter(|c| !c.is_whitespace())
        .map(|c| c == '1')
        .collect()
}

/// Bits → `"1010"`, first bit first.
fn bit_string(b: &[bool]) -> String {
    b.iter().map(|&x| if x { '1' } else { '0' }).collect()
}

/// Bytes as a UART (refin) or an MSB-first shifter (!refin) puts them on the wire.
fn byte_bits(bytes: &[u8], lsb_first: bool) -> Vec<bool> {
    bytes
        .iter()
        .flat_map(|&byte| {
            (0..8).map(move |k| {
                if lsb_first {
                    (byte >> k) & 1 == 1
                } else {
                    (byte >> (7 - k)) & 1 == 1
                }
            })
        })
        .collect()
}

/// Independent reference: the register after `bits` is
/// `(init(x)·x^n + M(x)·x^w) mod G(x)`, with `M(x) = Σ bit_k·x^(n-1-k)`;
/// computed here by schoolbook long division over GF(2), then reflected and
/// XORed as the algorithm says.
fn long_division(alg: &Algorithm, bits: &[bool]) -> u64 {
    let w = alg.width as usize;
    let n = bits.len();
    // dividend[d] = coefficient of x^d, degree up to n + w - 1
    let mut dividend = vec![false; n + w];
    for (k, &b) in bits.iter().enumerate() {
        dividend[n - 1 - k + w] ^= b;
    }
    for i in 0..w {
        dividend[n + i] ^= (alg.init >> i) & 1 == 1;
    }
    let generator: Vec<bool> = (0..=w).map(|i| (alg.generator() >> i) & 1 == 1).collect();
    for d in (w..n + w).rev() {
        if dividend[d] {
            for (i, &g) in generator.iter().enumerate() {
                dividend[d - w + i] ^= g;
            }
        }
    }
    let reg = (0..w).fold(0u64, |acc, i| acc | (u64::from(dividend[i]) << i));
    let out = if alg.refout {
        reflect(reg, alg.width)
    } else {
        reg
    };
    out ^ alg.xorout
}

// ---------------------------------------------------------------------------
// The catalogue as a whole
// ---------------------------------------------------------------------------

#[test]
fn every_check_value_is_the_crc_of_ascii_123456789() {
    for alg in CATALOGUE {
        assert_eq!(
            alg.checksum_bytes(b"123456789"),
            alg.check,
            "{}: check value",
            alg.name
        );
    }
}

#[test]
fn every_residue_follows_the_crc_catalogue_definition() {
    for alg in CATALOGUE {
        // Definition 1: register after an error-free codeword (here: the empty
        // message and its stated CRC in the algorithm's natural bit order),
        // reflected if refout, without xorout.
        let mut lfsr = BitSerial::new(alg);
        let crc = lfsr.value();
        for k in 0..alg.width {
            let i = if alg.refout { k } else { alg.width - 1 - k };
            lfsr.push((crc >> i) & 1 == 1);
        }
        let by_codeword = if alg.refout {
            reflect(lfsr.register(), alg.width)
        } else {
            lfsr.register()
        };
        // Definition 2 (crc-catalogue): register preset to xorout (reflected
        // if refout), `width` zero bits read, reflected if refin.
        let mut lfsr = BitSerial::new(&Algorithm {
            init: if alg.refout {
                reflect(alg.xorout, alg.width)
            } else {
                alg.xorout
            },
            ..**alg
        });
        lfsr.push_bits(&vec![false; alg.width as usize]);
        let by_zeros = if alg.refin {
            reflect(lfsr.register(), alg.width)
        } else {
            lfsr.register()
        };
        assert_eq!(
            by_codeword, alg.residue,
            "{}: residue by codeword",
            alg.name
        );
        assert_eq!(by_zeros, alg.residue, "{}: residue by zero bits", alg.name);
    }
}

#[test]
fn catalogue_entries_are_well_formed_and_found_by_name() {
    let mut names = std::collections::HashSet::new();
    for alg in CATALOGUE {
        assert!(names.insert(alg.name), "{}: duplicate name", alg.name);
        assert!(
            alg.name
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'),
            "{}: not kebab-case",
            alg.name
        );
        assert_eq!(by_name(alg.name), Some(*alg), "{}: by_name", alg.name);
        assert!((1..=64).contains(&alg.width), "{}: width", alg.name);
        let m = mask(alg.width);
        for (field, v) in [
            ("poly", alg.poly),
            ("init", alg.init),
            ("xorout", alg.xorout),
            ("check", alg.check),
            ("residue", alg.residue),
            ("wire_xor", alg.wire_xor),
        ] {
            assert_eq!(v & !m, 0, "{}: {field} wider than the CRC", alg.name);
        }
        assert_eq!(
            alg.poly & 1,
            1,
            "{}: a generator without the +1 term",
            alg.name
        );
        assert_eq!(
            alg.refin, alg.refout,
            "{}: crossed-endian models are not used by any seed",
            alg.name
        );
        assert!(alg.pad_to_multiple >= 1, "{}: pad_to_multiple", alg.name);
        assert!(
            alg.source.contains("seed 0"),
            "{}: source must cite a seed",
            alg.name
        );
        assert!(
            !alg.covers.is_empty() && !alg.title.is_empty(),
            "{}: covers/title",
            alg.name
        );
    }
    assert_eq!(by_name("crc-32"), None);
    assert_eq!(CATALOGUE.len(), 9);
}

#[test]
fn every_equation_and_stated_hex_denote_the_catalogue_generator() {
    for alg in CATALOGUE {
        let from_equation = parse_polynomial(alg.poly_equation)
            .unwrap_or_else(|| panic!("{}: unparsable equation", alg.name));
        assert_eq!(
            from_equation,
            alg.generator(),
            "{}: equation {} vs poly {:#x}",
            alg.name,
            alg.poly_equation,
            alg.poly
        );
        if let Some(h) = alg.stated_hex {
            assert_eq!(
                h.notation.decode(h.value, alg.width),
                alg.generator(),
                "{}: stated hex {:#x}",
                alg.name,
                h.value
            );
            assert_eq!(alg.poly_in(h.notation), h.value, "{}: poly_in", alg.name);
        }
    }
}

// ---------------------------------------------------------------------------
// Cross-check against the `crc` crate (crc-catalogue parameters)
// ---------------------------------------------------------------------------

// Written from the seeds, not from the catalogue constants, so that a typo in
// either shows up.
const CRATE_ENDAT: crc::Algorithm<u8> = crc::Algorithm {
    width: 5,
    poly: 0x0B,
    init: 0x1F,
    refin: false,
    refout: false,
    xorout: 0x1F,
    check: 0x19,
    residue: 0x08,
};
const CRATE_BISS: crc::Algorithm<u8> = crc::Algorithm {
    width: 6,
    poly: 0x03,
    init: 0x00,
    refin: false,
    refout: false,
    xorout: 0x00,
    check: 0x11,
    residue: 0x00,
};
const CRATE_BISS_CTRL: crc::Algorithm<u8> = crc::Algorithm {
    width: 4,
    poly: 0x03,
    init: 0x00,
    refin: false,
    refout: false,
    xorout: 0x00,
    check: 0x0E,
    residue: 0x00,
};
const CRATE_TFORMAT: crc::Algorithm<u8> = crc::Algorithm {
    width: 8,
    poly: 0x01,
    init: 0x00,
    refin: true,
    refout: true,
    xorout: 0x00,
    check: 0x31,
    residue: 0x00,
};
const CRATE_ESL8: crc::Algorithm<u8> = crc::Algorithm {
    width: 8,
    poly: 0x2F,
    init: 0x00,
    refin: true,
    refout: true,
    xorout: 0x00,
    check: 0x43,
    residue: 0x00,
};
const CRATE_ESL16_CH1: crc::Algorithm<u16> = crc::Algorithm {
    width: 16,
    poly: 0x5935,
    init: 0x0000,
    refin: true,
    refout: true,
    xorout: 0x0000,
    check: 0xFAD9,
    residue: 0x0000,
};
const CRATE_ESL16_CH2: crc::Algorithm<u16> = crc::Algorithm {
    width: 16,
    poly: 0x5935,
    init: 0xFFFF,
    refin: true,
    refout: true,
    xorout: 0x0000,
    check: 0x328D,
    residue: 0x0000,
};

/// The `crc` crate's answer for a catalogue entry: the crate's own named
/// algorithm where it has the same one (Modbus, CAN), else a custom one.
fn crate_checksum(alg: &Algorithm, data: &[u8]) -> u64 {
    match alg.name {
        "endat-crc5" => crc::Crc::<u8>::new(&CRATE_ENDAT).checksum(data).into(),
        "biss-crc6" => crc::Crc::<u8>::new(&CRATE_BISS).checksum(data).into(),
        "biss-ctrl-crc4" => crc::Crc::<u8>::new(&CRATE_BISS_CTRL).checksum(data).into(),
        "tformat-crc8" => crc::Crc::<u8>::new(&CRATE_TFORMAT).checksum(data).into(),
        "esl-crc8" => crc::Crc::<u8>::new(&CRATE_ESL8).checksum(data).into(),
        "esl-crc16-ch1" => crc::Crc::<u16>::new(&CRATE_ESL16_CH1).checksum(data).into(),
        "esl-crc16-ch2" => crc::Crc::<u16>::new(&CRATE_ESL16_CH2).checksum(data).into(),
        "modbus-crc16" => crc::Crc::<u16>::new(&crc::CRC_16_MODBUS)
            .checksum(data)
            .into(),
        "can-crc15" => crc::Crc::<u16>::new(&crc::CRC_15_CAN).checksum(data).into(),
        other => panic!("{other}: add a crc-crate counterpart for this catalogue entry"),
    }
}

#[test]
fn crate_named_algorithms_have_the_catalogue_parameters() {
    let m = crc::CRC_16_MODBUS;
    assert_eq!(
        (
            u64::from(m.poly),
            u64::from(m.init),
            m.refin,
            m.refout,
            u64::from(m.xorout),
            u64::from(m.check)
        ),
        (
            MODBUS_CRC16.poly,
            MODBUS_CRC16.init,
            MODBUS_CRC16.refin,
            MODBUS_CRC16.refout,
            MODBUS_CRC16.xorout,
            MODBUS_CRC16.check
        )
    );
    let c = crc::CRC_15_CAN;
    assert_eq!(
        (
            u32::from(c.width),
            u64::from(c.poly),
            u64::from(c.init),
            c.refin,
            u64::from(c.xorout),
            u64::from(c.check)
        ),
        (
            CAN_CRC15.width,
            CAN_CRC15.poly,
            CAN_CRC15.init,
            CAN_CRC15.refin,
            CAN_CRC15.xorout,
            CAN_CRC15.check
        )
    );
}

#[test]
fn crate_agrees_on_the_check_string_for_every_entry() {
    for alg in CATALOGUE {
        assert_eq!(crate_checksum(alg, b"123456789"), alg.check, "{}", alg.name);
    }
}

proptest! {
    #[test]
    fn checksum_bytes_agrees_with_the_crc_crate(data in proptest::collection::vec(any::<u8>(), 0..64)) {
        for alg in CATALOGUE {
            prop_assert_eq!(alg.checksum_bytes(&data), crate_checksum(alg, &data), "{}", alg.name);
        }
    }

    #[test]
    fn checksum_bits_agrees_with_checksum_bytes_fed_in_byte_order(data in proptest::collection::vec(any::<u8>(), 0..48)) {
        for alg in CATALOGUE {
            let wire = byte_bits(&data, alg.refin);
            prop_assert_eq!(alg.checksum_bits(&wire), alg.checksum_bytes(&data), "{}", alg.name);
        }
    }

    #[test]
    fn checksum_bits_agrees_with_polynomial_long_division(b in proptest::collection::vec(any::<bool>(), 0..200)) {
        for alg in CATALOGUE {
            prop_assert_eq!(alg.checksum_bits(&b), long_division(alg, &b), "{}", alg.name);
        }
    }

    #[test]
    fn message_plus_wire_bits_leaves_the_wire_residue(b in proptest::collection::vec(any::<bool>(), 0..120)) {
        for alg in CATALOGUE {
            let mut lfsr = BitSerial::new(alg);
            lfsr.push_bits(&b);
            let crc = lfsr.value();
            lfsr.push_bits(&alg.wire_bits(crc));
            prop_assert_eq!(lfsr.register(), alg.wire_residue(), "{}", alg.name);
        }
    }

    #[test]
    fn a_single_flipped_bit_changes_the_crc(b in proptest::collection::vec(any::<bool>(), 1..120), pick in any::<prop::sample::Index>()) {
        for alg in CATALOGUE {
            let mut flipped = b.clone();
            let k = pick.index(flipped.len());
            flipped[k] = !flipped[k];
            prop_assert_ne!(alg.checksum_bits(&b), alg.checksum_bits(&flipped), "{}", alg.name);
        }
    }

    #[test]
    fn wire_bits_round_trip_through_crc_from_wire_bits(v in any::<u64>()) {
        for alg in CATALOGUE {
            let crc = v & mask(alg.width);
            let wire = alg.wire_bits(crc);
            prop_assert_eq!(wire.len(), alg.width as usize);
            prop_assert_eq!(alg.crc_from_wire_bits(&wire), Some(crc), "{}", alg.name);
        }
    }
}

#[test]
fn wire_residues_are_the_documented_constants() {
    // What an RTL receiver compares its LFSR against after the CRC field.
    let expected = [
        ("endat-crc5", 0x08),
        ("biss-crc6", 0x02),
        ("biss-ctrl-crc4", 0x02),
        ("tformat-crc8", 0),
        ("esl-crc8", 0),
        ("esl-crc16-ch1", 0),
        ("esl-crc16-ch2", 0),
        ("modbus-crc16", 0),
        ("can-crc15", 0),
    ];
    for (name, residue) in expected {
        assert_eq!(by_name(name).unwrap().wire_residue(), residue, "{name}");
    }
}

#[test]
fn biss_control_crc4_is_x4_x_1_from_zero_sent_inverted() {
    // Public BiSS C protocol description (register access), restated in docs/timing/biss.md:
    // x^4 + x + 1, start value 0, transmitted inverted, MSB first.
    // x^3 * x^4 = x^7 = x^3 + x + 1 (mod x^4 + x + 1): the message 1000 leaves 1011.
    let crc = BISS_CTRL_CRC4.checksum_bits(&bits("1000"));
    assert_eq!(crc, 0b1011);
    assert_eq!(bit_string(&BISS_CTRL_CRC4.wire_bits(crc)), "0100");
    // x^4 = x + 1: the message 0001 leaves 0011.
    assert_eq!(BISS_CTRL_CRC4.checksum_bits(&bits("0001")), 0b0011);
}

#[test]
fn bit_serial_reset_presets_the_register_to_init() {
    let mut lfsr = BitSerial::new(&ENDAT_CRC5);
    assert_eq!(lfsr.register(), 0x1F);
    lfsr.push_bits(&bits("1010011"));
    assert_ne!(lfsr.register(), 0x1F);
    lfsr.reset();
    assert_eq!(lfsr.register(), 0x1F);
    assert_eq!(lfsr.algorithm(), &ENDAT_CRC5);
}

// ---------------------------------------------------------------------------
// EnDat (seed 004, appendix A4, 4.4.2 Software CRC generation)
// ---------------------------------------------------------------------------

/// The bits `MakeCrcNorm` covers, in wire order: 8-bit part MSB first, then
/// 16-bit part MSB first.
fn endat_norm_bits(param8: u32, param16: u32) -> Vec<bool> {
    (0..8)
        .rev()
        .map(|i| (param8 >> i) & 1 == 1)
        .chain((0..16).rev().map(|i| (param16 >> i) & 1 == 1))
        .collect()
}

/// The bits `MakeCrcPos` covers, in wire order: F1, F2 (EnDat 2.2 only),
/// then `clocks` position bits LSB first.
fn endat_pos_bits(
    clocks: u32,
    error1: bool,
    error2: bool,
    endat22: bool,
    position: u64,
) -> Vec<bool> {
    let mut b = vec![error1];
    if endat22 {
        b.push(error2);
    }
    b.extend((0..clocks).map(|i| (position >> i) & 1 == 1));
    b
}

#[test]
fn endat_make_crc_norm_seed_example_is_14() {
    // Seed 004, 4.4.2, MakeCrcNorm: param8 = 13, param16 = 32793, return value 14.
    assert_eq!(make_crc_norm(13, 32793), 14);
    assert_eq!(ENDAT_CRC5.checksum_bits(&endat_norm_bits(13, 32793)), 14);
    // The 24 covered bits are three whole bytes, MSB first.
    assert_eq!(
        ENDAT_CRC5.checksum_bytes(&[13, (32793u32 >> 8) as u8, 32793u32 as u8]),
        14
    );
}

#[test]
fn endat_make_crc_pos_seed_example_is_3() {
    // Seed 004, 4.4.2, MakeCrcPos: clocks 25, error1 0, error2 1, EnDat 2.2, position 104462: 3.
    assert_eq!(make_crc_pos(25, 0, 1, 1, 0, 104_462), 3);
    assert_eq!(
        ENDAT_CRC5.checksum_bits(&endat_pos_bits(25, false, true, true, 104_462)),
        3
    );
}

#[test]
fn endat_crc_goes_on_the_wire_msb_first() {
    // 14 = 0b01110: CRC bit 4 (the inverted ff[4]) first.
    assert_eq!(bit_string(&ENDAT_CRC5.wire_bits(14)), "01110");
    assert_eq!(bit_string(&ENDAT_CRC5.wire_bits(3)), "00011");
}

proptest! {
    #[test]
    fn endat_engine_agrees_with_ported_make_crc_norm(param8 in 0u32..256, param16 in 0u32..65536) {
        prop_assert_eq!(ENDAT_CRC5.checksum_bits(&endat_norm_bits(param8, param16)) as u32, make_crc_norm(param8, param16));
    }

    #[test]
    fn endat_engine_agrees_with_ported_make_crc_pos(
        clocks in 1u32..=64, error1 in any::<bool>(), error2 in any::<bool>(), endat22 in any::<bool>(), position in any::<u64>(),
    ) {
        let position = if clocks == 64 { position } else { position & ((1u64 << clocks) - 1) };
        let reference = make_crc_pos(clocks, error1.into(), error2.into(), endat22.into(), (position >> 32) as u32, position as u32);
        prop_assert_eq!(ENDAT_CRC5.checksum_bits(&endat_pos_bits(clocks, error1, error2, endat22, position)) as u32, reference);
    }
}

// ---------------------------------------------------------------------------
// BiSS-C (seed 001, BiSS-C section)
// ---------------------------------------------------------------------------

#[test]
fn biss_seed_example_crc_is_110101_sent_inverted_as_001010() {
    // Seed 001, BiSS-C: data 1000101011100011, nE = 1 (no error), nW = 0
    // (warning): "the calculated CRC check code is 110101, with its negative
    // logic being 001010".
    let mut covered = bits("1000101011100011");
    covered.push(true); // nE
    covered.push(false); // nW
    assert_eq!(bit_string(&covered), "100010101110001110"); // the seed's "complete data information code"
    let crc = BISS_CRC6.checksum_bits(&covered);
    assert_eq!(crc, 0b110101);
    assert_eq!(bit_string(&BISS_CRC6.wire_bits(crc)), "001010");
    assert_eq!(
        BISS_CRC6.crc_from_wire_bits(&bits("001010")),
        Some(0b110101)
    );
}

#[test]
fn biss_seed_example_needs_initial_value_zero() {
    // Seed 001 says the example's CRC is 110101; a preset of all ones (one
    // reading of "set to high levels") would give another value.
    let covered = bits("100010101110001110");
    let ones = Algorithm {
        init: 0x3F,
        ..BISS_CRC6
    };
    assert_ne!(ones.checksum_bits(&covered), 0b110101);
}

// ---------------------------------------------------------------------------
// Modbus RTU (seed 001, Modbus RTU (5) data frame format, CRC steps)
// ---------------------------------------------------------------------------

#[test]
fn modbus_seed_request_frames_end_in_their_crc_low_byte_first() {
    // Seed 001, (5) ① and ②: host calls `01 03 00 00 00 01 84 0A` and
    // `01 03 00 00 00 02 C4 0B`; (5) ③ address query `FF A0 40 38`.
    let frames: [&[u8]; 3] = [
        &[0x01, 0x03, 0x00, 0x00, 0x00, 0x01, 0x84, 0x0A],
        &[0x01, 0x03, 0x00, 0x00, 0x00, 0x02, 0xC4, 0x0B],
        &[0xFF, 0xA0, 0x40, 0x38],
    ];
    for frame in frames {
        let (body, crc_bytes) = frame.split_at(frame.len() - 2);
        let crc = MODBUS_CRC16.checksum_bytes(body);
        assert_eq!(
            MODBUS_CRC16.wire_bytes(crc).as_deref(),
            Some(crc_bytes),
            "{frame:02X?}"
        );
        assert_eq!(u64::from(modbus_crc_seed_steps(body)), crc, "{frame:02X?}");
        // The whole frame, CRC included, leaves the residue (0).
        assert_eq!(
            MODBUS_CRC16.checksum_bytes(frame),
            MODBUS_CRC16.residue,
            "{frame:02X?}"
        );
    }
    assert_eq!(
        MODBUS_CRC16.checksum_bytes(&[0x01, 0x03, 0x00, 0x00, 0x00, 0x01]),
        0x0A84
    );
}

#[test]
fn modbus_crc_bits_on_the_wire_are_low_byte_lsb_first_then_high_byte() {
    // 0x0A84 is sent as the UART characters 84 then 0A, each bit 0 first.
    assert_eq!(
        bit_string(&MODBUS_CRC16.wire_bits(0x0A84)),
        "00100001".to_owned() + "01010000"
    );
}

#[test]
fn modbus_seed_step_2_or_must_be_read_as_xor() {
    // Seed 001 step ② says the byte is "OR"ed into the register; taken
    // literally it does not reproduce the seed's frame `... 84 0A`.
    let mut crc: u16 = 0xFFFF;
    for &byte in &[0x01u8, 0x03, 0x00, 0x00, 0x00, 0x01] {
        crc |= u16::from(byte);
        for _ in 0..8 {
            let out = crc & 1;
            crc >>= 1;
            if out == 1 {
                crc ^= 0xA001;
            }
        }
    }
    assert_ne!(crc, 0x0A84);
}

proptest! {
    #[test]
    fn modbus_engine_agrees_with_the_seed_step_procedure(data in proptest::collection::vec(any::<u8>(), 0..64)) {
        prop_assert_eq!(MODBUS_CRC16.checksum_bytes(&data), u64::from(modbus_crc_seed_steps(&data)));
    }
}

// ---------------------------------------------------------------------------
// ESL (seed 000, "Cyclic Redundancy Check Frame (CRC)")
// ---------------------------------------------------------------------------

/// Split a seed line into its `$…$` equation and the hex after `'h`.
fn equation_and_hex(line: &str) -> (u128, u64) {
    let mut parts = line.split('$');
    let equation = parts.nth(1).expect("equation between $ signs");
    let hex = line.split("'h").nth(1).expect("Verilog hex literal");
    let hex: String = hex.chars().take_while(|c| c.is_ascii_hexdigit()).collect();
    (
        parse_polynomial(equation).expect("parsable equation"),
        u64::from_str_radix(&hex, 16).unwrap(),
    )
}

const SEED_000_CRC8_LINE: &str =
    "CRC-16 Polynomial =  $X^8 + X^5 + X^3 + X^2 + X + 1$  (X = CRC0 to CRC7, Poly = 8'h97)";
const SEED_000_CRC16_LINE: &str =
    "CRC-16 Polynomial =  $X^{16} + X^{14} + X^{12} + X^{11} + X^8 + X^5 + X^4 + X^2 + 1$  (X = CRC0 to CRC15, Poly = 16'hAC9A)";

#[test]
fn esl_crc8_equation_and_8h97_are_one_generator_in_koopman_notation() {
    // Seed 000, note "8 Bit": the equation and the printed hex value.
    let (from_equation, hex) = equation_and_hex(SEED_000_CRC8_LINE);
    assert_eq!(hex, 0x97);
    assert_eq!(from_equation, generator_from_exponents(&[8, 5, 3, 2, 1, 0]));
    assert_eq!(PolyNotation::Koopman.decode(hex, 8), from_equation);
    assert_eq!(from_equation, ESL_CRC8.generator());
    assert_eq!(ESL_CRC8.poly, 0x2F);
    // Read as the catalogue's normal notation, 0x97 would be another polynomial.
    assert_eq!(
        format_polynomial(PolyNotation::Normal.decode(hex, 8)),
        "x^8 + x^7 + x^4 + x^2 + x + 1"
    );
    assert_ne!(PolyNotation::Normal.decode(hex, 8), from_equation);
}

#[test]
fn esl_crc16_equation_and_16hac9a_are_one_generator_in_koopman_notation() {
    // Seed 000, note "16 Bit".
    let (from_equation, hex) = equation_and_hex(SEED_000_CRC16_LINE);
    assert_eq!(hex, 0xAC9A);
    assert_eq!(
        from_equation,
        generator_from_exponents(&[16, 14, 12, 11, 8, 5, 4, 2, 0])
    );
    assert_eq!(PolyNotation::Koopman.decode(hex, 16), from_equation);
    assert_eq!(from_equation, ESL_CRC16_CH1.generator());
    assert_eq!(from_equation, ESL_CRC16_CH2.generator());
    assert_eq!(ESL_CRC16_CH1.poly, 0x5935);
    // Read as normal notation, 0xAC9A lacks the +1 term: no CRC generator.
    assert_eq!(PolyNotation::Normal.decode(hex, 16) & 1, 0);
}

#[test]
fn koopman_is_the_only_notation_that_reads_both_esl_hex_values_as_their_equations() {
    let fits = |line: &str, width: u32| -> Vec<PolyNotation> {
        let (g, hex) = equation_and_hex(line);
        PolyNotation::ALL
            .into_iter()
            .filter(|n| n.decode(hex, width) == g)
            .collect()
    };
    // The CRC-8 line alone settles it ...
    assert_eq!(fits(SEED_000_CRC8_LINE, 8), vec![PolyNotation::Koopman]);
    // ... the CRC-16 generator is a palindrome, so reversed notation fits it too.
    assert_eq!(
        fits(SEED_000_CRC16_LINE, 16),
        vec![PolyNotation::Reversed, PolyNotation::Koopman]
    );
    assert_eq!(ESL_CRC8.stated_hex.unwrap().notation, PolyNotation::Koopman);
    assert_eq!(
        ESL_CRC16_CH1.stated_hex.unwrap().notation,
        PolyNotation::Koopman
    );
}

#[test]
fn esl_channels_differ_only_in_the_initial_value() {
    // Seed 000: "CH1 CRC initial value = 16'h0000 ; CH2 CRC initial value = 16'hFFFF".
    assert_eq!(ESL_CRC16_CH1.init, 0x0000);
    assert_eq!(ESL_CRC16_CH2.init, 0xFFFF);
    assert_eq!(
        Algorithm {
            init: 0xFFFF,
            name: "",
            check: 0,
            covers: "",
            title: "",
            ..ESL_CRC16_CH1
        },
        Algorithm {
            name: "",
            check: 0,
            covers: "",
            title: "",
            ..ESL_CRC16_CH2
        }
    );
    assert_eq!(ESL_CRC8.init, 0x00);
}

#[test]
fn esl_crc16_pads_an_odd_number_of_fields_with_a_zero_byte() {
    // Seed 000, note "16 Bit": "If # of field is odd number, the last 8-bit
    // will be padded with 0's".
    let three_fields = byte_bits(&[0x5A, 0x12, 0x34], true);
    let mut padded = three_fields.clone();
    padded.extend([false; 8]);
    for alg in [&ESL_CRC16_CH1, &ESL_CRC16_CH2] {
        assert_eq!(
            alg.checksum_frame_bits(&three_fields),
            alg.checksum_bits(&padded),
            "{}",
            alg.name
        );
        assert_ne!(
            alg.checksum_frame_bits(&three_fields),
            alg.checksum_bits(&three_fields),
            "{}",
            alg.name
        );
        let four_fields = byte_bits(&[0x5A, 0x12, 0x34, 0x56], true);
        assert_eq!(
            alg.checksum_frame_bits(&four_fields),
            alg.checksum_bits(&four_fields),
            "{}",
            alg.name
        );
    }
    // The 8-bit CRC is not padded.
    assert_eq!(
        ESL_CRC8.checksum_frame_bits(&three_fields),
        ESL_CRC8.checksum_bits(&three_fields)
    );
}

#[test]
fn esl_crc16_is_sent_crcx1_low_byte_first_each_lsb_first() {
    // Seed 000: "Full CRC (16b) = {CRCx.2, CRCx.1}", "CRC Field is transmitted from LSB first".
    assert_eq!(ESL_CRC16_CH1.wire_bytes(0xABCD), Some(vec![0xCD, 0xAB]));
    assert_eq!(
        bit_string(&ESL_CRC16_CH1.wire_bits(0xABCD)),
        "10110011".to_owned() + "11010101"
    );
    assert_eq!(bit_string(&ESL_CRC8.wire_bits(0x43)), "11000010");
}

// ---------------------------------------------------------------------------
// T-format (seed 002, 6.3.4 CRC Field)
// ---------------------------------------------------------------------------

// Seed 002 prints no worked CRC example; these pin what G(X) = X^8 + 1 implies.

proptest! {
    #[test]
    fn tformat_crc_is_the_xor_of_the_covered_fields(fields in proptest::collection::vec(any::<u8>(), 0..12)) {
        // x^8 = 1 (mod X^8 + 1): the remainder folds the message into bytes.
        let xor = fields.iter().fold(0u8, |a, &b| a ^ b);
        prop_assert_eq!(TFORMAT_CRC8.checksum_bytes(&fields), u64::from(xor));
        prop_assert_eq!(TFORMAT_CRC8.checksum_bits(&byte_bits(&fields, true)), u64::from(xor));
    }
}

#[test]
fn tformat_crc_character_is_sent_lsb_first() {
    // Seed 002, 6.3.4: "The data is arranged in LSB first."
    assert_eq!(bit_string(&TFORMAT_CRC8.wire_bits(0x11)), "10001000");
    assert_eq!(TFORMAT_CRC8.wire_bytes(0x11), Some(vec![0x11]));
}

// ---------------------------------------------------------------------------
// Notation helpers
// ---------------------------------------------------------------------------

#[test]
fn modbus_a001_is_reversed_and_can_4599_is_normal_notation() {
    assert_eq!(
        PolyNotation::Reversed.decode(0xA001, 16),
        parse_polynomial("x^16 + x^15 + x^2 + 1").unwrap()
    );
    assert_eq!(MODBUS_CRC16.poly_in(PolyNotation::Reversed), 0xA001);
    assert_eq!(CAN_CRC15.poly_in(PolyNotation::Normal), 0x4599);
    assert_eq!(
        format_polynomial(CAN_CRC15.generator()),
        "x^15 + x^14 + x^10 + x^8 + x^7 + x^4 + x^3 + 1"
    );
}

#[test]
fn parse_polynomial_rejects_what_it_cannot_read() {
    assert_eq!(parse_polynomial("x^6 + x + 1"), Some(0b100_0011));
    assert_eq!(parse_polynomial("xA^6 + xM + xA0"), None); // seed 001's garbled BiSS-C text
    assert_eq!(parse_polynomial("x^2 + x^2 + 1"), None);
}

proptest! {
    #[test]
    fn every_notation_round_trips(width in 3u32..=32, low in any::<u64>()) {
        // A generator with both the x^width and the +1 term.
        let g = (1u128 << width) | u128::from(low & mask(width)) | 1;
        for n in PolyNotation::ALL {
            prop_assert_eq!(n.decode(n.encode(g, width), width), g, "{:?}", n);
        }
        // Koopman is reversed reciprocal.
        let reciprocal = PolyNotation::Reciprocal.encode(g, width);
        prop_assert_eq!(PolyNotation::Koopman.encode(g, width), reflect(reciprocal, width));
    }
}
