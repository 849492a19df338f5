use model::angle::angle_deg;
use model::sar58k24::frames::*;

#[test]
fn seed_001_bus_commands_bc_aa_b1_and_c1_and_the_answer_tag() {
    // Seed 001, 3.1.5/3.1.6: BC AA B1 reads product 1, BC AA C1 zeroes it;
    // "the second byte of the return data is the product address number".
    assert_eq!(read_command(1), [0xBC, 0xAA, 0xB1]);
    assert_eq!(zero_command(3), [0xBC, 0xAA, 0xC3]);
    assert_eq!(parse_command(&[0xBC, 0xAA, 0xB2]), Some(Command::Read(2)));
    assert_eq!(parse_command(&[0xBC, 0xAA, 0xC2]), Some(Command::Zero(2)));
    // The garbled row of 3.2.5 is no command.
    assert_eq!(parse_command(&[0xAA, 0x81, 0xCC]), None);
    assert_eq!(tag_byte(AnswerTag::Address, true, 2), 0xB2);
    assert_eq!(tag_byte(AnswerTag::Fixed81, true, 2), 0x81);
    assert_eq!(tag_byte(AnswerTag::Address, false, 2), 0x81);
    let f = encode_tagged(383, 14, 0xB1);
    assert_eq!(f, [0xFF, 0xB1, 0x01, 0x7F, 0x30]);
    assert_eq!(decode_tagged(&f, 14, 0xB1), Ok(383));
    assert_eq!(
        decode_tagged(&f, 14, 0xB2),
        Err(FrameError::Header(0xFF, 0xB1))
    );
}

#[test]
fn seed_001_frame_ff_81_01_7f_00_is_383_and_8_4155_degrees_for_14_bits() {
    // Seed 001, "Asynchronous serial": FF 81 01 7F 00, checksum 00 = low byte of FF+81+01+7F.
    let frame = [0xFF, 0x81, 0x01, 0x7F, 0x00];
    assert_eq!(checksum(&frame[..4]), 0x00);
    assert_eq!(decode(&frame, 14), Ok(383));
    assert_eq!(encode(383, 14), frame);
    assert_eq!(angle_deg(383, 14), 8.4155);
}

#[test]
fn frames_grow_with_resolution_as_the_seed_lists() {
    assert_eq!(encode(0x12_3456, 24).len(), 6);
    assert_eq!(encode(0x0123_4567, 25).len(), 7);
    assert_eq!(decode(&encode(0x0123_4567, 25), 25), Ok(0x0123_4567));
}

#[test]
fn a_corrupted_byte_is_caught_by_the_checksum() {
    let mut frame = encode(383, 14);
    frame[3] ^= 0x10;
    assert!(matches!(
        decode(&frame, 14),
        Err(FrameError::Checksum { .. })
    ));
    assert_eq!(
        decode(&frame[..4], 14),
        Err(FrameError::Length {
            bits: 14,
            expected: 5,
            got: 4
        })
    );
    assert_eq!(
        decode(&[0xFE, 0x81, 1, 0x7F, 0], 14),
        Err(FrameError::Header(0xFE, 0x81))
    );
}
