use model::esl::frames::Field::*;
use model::esl::frames::*;

#[test]
fn control_fields_carry_table_3_codes_and_odd_parity() {
    // Seed 000, Table 3: CC0..CC3 per Data ID, parity <odd>.
    let table: [(DataId, [u8; 4]); 12] = [
        (DataId::Id1, [1, 0, 0, 0]),
        (DataId::Id2, [0, 1, 0, 0]),
        (DataId::Id4, [0, 0, 1, 0]),
        (DataId::Id5, [1, 0, 1, 0]),
        (DataId::Id8, [0, 0, 0, 1]),
        (DataId::Id9, [1, 0, 0, 1]),
        (DataId::IdA, [0, 1, 0, 1]),
        (DataId::IdB, [1, 1, 0, 1]),
        (DataId::IdC, [0, 0, 1, 1]),
        (DataId::IdD, [1, 0, 1, 1]),
        (DataId::IdE, [0, 1, 1, 1]),
        (DataId::IdF, [1, 1, 1, 1]),
    ];
    for (id, cc) in table {
        for address in 0..8 {
            let cf = id.control_field(address);
            let got: Vec<u8> = (3..7).map(|b| (cf >> b) & 1).collect();
            assert_eq!(got, cc, "{id:?}");
            assert_eq!(
                (cf >> 3).count_ones() % 2,
                1,
                "{id:?}: CC0..CC3 and parity odd"
            );
            assert_eq!(cf & 7, address, "EAD0..2 in bits 0..2");
            let p = parse_control_field(cf);
            assert!(p.parity_ok && DataId::from_code(p.code) == Some(id) && p.address == address);
        }
    }
    // Data ID 1 at address 0: CC = 1000, parity 0 (one 1 already odd).
    assert_eq!(DataId::Id1.control_field(0), 0x08);
    assert_eq!(DataId::IdF.control_field(0), 0xF8, "four ones: parity 1");
}

#[test]
fn frame_sizes_are_those_of_table_12() {
    // Seed 000, Table 12, column "Frame Size".
    let sizes = [
        (DataId::Id1, 11, 7),
        (DataId::Id2, 9, 7),
        (DataId::Id4, 8, 0),
        (DataId::Id5, 6, 0),
        (DataId::Id6, 6, 5),
        (DataId::Id8, 6, 6),
        (DataId::Id9, 4, 0),
        (DataId::IdA, 4, 4),
        (DataId::IdB, 9, 7),
        (DataId::IdC, 7, 6),
        (DataId::IdD, 6, 0),
        (DataId::IdE, 4, 0),
        (DataId::IdF, 4, 0),
    ];
    for (id, ch1, ch2) in sizes {
        assert_eq!(id.channel1().len(), ch1, "{id:?} CH1");
        assert_eq!(id.channel2().map_or(0, |c| c.len()), ch2, "{id:?} CH2");
    }
    let safety: Vec<DataId> = DataId::ALL.into_iter().filter(|d| d.is_safety()).collect();
    assert_eq!(
        safety,
        [DataId::Id1, DataId::Id2, DataId::Id8, DataId::IdB],
        "Table 12 'Safety Related? Yes'"
    );
}

#[test]
#[allow(clippy::unusual_byte_groupings)] // grouped as the seed's {safety, MT bytes, ST bits}
fn enid_examples_of_table_6() {
    // Table 6: ST={1, 00, 11000}, MT={1, 10, 11000}.
    assert_eq!(enid(true, 0b00, 24), 0b1_00_11000);
    assert_eq!(enid(true, 0b10, 24), 0b1_10_11000);
}

#[test]
fn alarm_bits_follow_table_7_and_status_bits_table_5() {
    assert_eq!(
        Alarms {
            xc: true,
            ..Alarms::default()
        }
        .byte(),
        0x01
    );
    assert_eq!(
        Alarms {
            ov: true,
            ..Alarms::default()
        }
        .byte(),
        0x80
    );
    assert_eq!(
        Alarms {
            lis: true,
            ..Alarms::default()
        }
        .byte(),
        0x04
    );
    assert_eq!(
        Alarms {
            led: true,
            ..Alarms::default()
        }
        .ea(),
        (true, false)
    );
    assert_eq!(
        Alarms {
            lis: true,
            ..Alarms::default()
        }
        .ea(),
        (false, true)
    );
    assert_eq!(
        Alarms {
            xc: true,
            mt: true,
            uv: true,
            ..Alarms::default()
        }
        .after_clear(),
        Alarms {
            uv: true,
            ..Alarms::default()
        }
    );
    let s = Status {
        ca1: true,
        ready: true,
        ..Status::default()
    };
    assert_eq!(s.byte(), 0x42);
    assert_eq!(Status::from_byte(0x42), s);
}

#[test]
fn both_crc16_channels_differ_only_by_their_init() {
    let data = [0x08, 0x40, 0x00, 0x56, 0x34, 0x12, 0x02, 0x01, 0x07];
    let a = with_crc(&data, CrcKind::Crc16, false);
    let b = with_crc(&data, CrcKind::Crc16, true);
    assert_ne!(a, b);
    assert!(channel_crc_ok(&a, CrcKind::Crc16, false) && !channel_crc_ok(&a, CrcKind::Crc16, true));
    assert!(channel_crc_ok(&b, CrcKind::Crc16, true));
    // Nine fields are padded with 8 zero bits: the same as a tenth 0x00 field.
    assert_eq!(
        crc16(CRC16_CH1, &data),
        crc16(CRC16_CH1, &[&data[..], &[0]].concat())
    );
}

#[test]
fn every_answer_checks_clean_and_decodes_what_was_sent() {
    for id in DataId::ALL {
        let cf = id.control_field(3);
        let abs = 0xAB_CDEF;
        let d = AnswerData {
            cf,
            status: Status {
                ready: true,
                ..Status::default()
            },
            alm1: 0x10,
            alm2: 0x10,
            abs,
            abm: 0x1234,
            rs: redundant(abs, id),
            sc1: 0x55,
            sc2: 0x2A,
            enid: 0xD8,
            temp: 37,
            adf: adf(0x12, false),
            edf: 0x99,
        };
        let bytes = answer(id, &d);
        assert_eq!(bytes.len(), id.answer_fields());
        assert_eq!(check(id, cf, &bytes, false, 1), Checks::default(), "{id:?}");
        let got = decode(id, &bytes);
        assert_eq!(got.cf, cf);
        if id.channel1().fields.contains(&Abs(2)) {
            assert_eq!(got.abs, abs, "{id:?}");
        }
        for bit in 0..8 * bytes.len() {
            let mut bad = bytes.clone();
            bad[bit / 8] ^= 1 << (bit % 8);
            assert!(check(id, cf, &bad, false, 1).any(), "{id:?} bit {bit}");
        }
    }
}

#[test]
fn a_channel_disagreement_is_flagged() {
    let id = DataId::Id1;
    let abs = 0x80_0000;
    let d = AnswerData {
        cf: id.control_field(0),
        abs,
        rs: redundant(abs, id) + 2,
        ..AnswerData::default()
    };
    assert!(check(id, d.cf, &answer(id, &d), false, 1).rs);
    let d = AnswerData {
        rs: redundant(abs, id) + 1,
        ..d
    };
    assert!(
        !check(id, d.cf, &answer(id, &d), false, 1).rs,
        "one LSB is within tolerance"
    );
    assert!(channels_agree(0, 511, id, 1), "modulo one turn");
}

#[test]
fn requests_end_in_their_crc8() {
    let r = request(2, 0xE, 0x7F, 0);
    assert_eq!(r.len(), 3);
    assert_eq!(r[1], 0xFE);
    assert!(channel_crc_ok(&r, CrcKind::Crc8, false));
    assert_eq!(request(0, 1, 0, 0).len(), 2, "CF and its CRC frame");
    assert_eq!(request(0, 0xF, 1, 2).len(), 4);
}
