use model::tformat::frames::*;

#[test]
fn control_fields_carry_table_1_codes_and_parities() {
    // Seed 002, Table 1: cc0..cc3 and parity cc4 for each Data ID.
    let table = [
        (DataId::Id0, [0, 0, 0, 0, 0]),
        (DataId::Id1, [1, 0, 0, 0, 1]),
        (DataId::Id2, [0, 1, 0, 0, 1]),
        (DataId::Id3, [1, 1, 0, 0, 0]),
        (DataId::Id6, [0, 1, 1, 0, 0]),
        (DataId::IdD, [1, 0, 1, 1, 1]),
        (DataId::Id7, [1, 1, 1, 0, 1]),
        (DataId::Id8, [0, 0, 0, 1, 1]),
        (DataId::IdC, [0, 0, 1, 1, 0]),
    ];
    for (id, cc) in table {
        let cf = id.control_field();
        let got: Vec<u8> = (3..8).map(|b| (cf >> b) & 1).collect();
        assert_eq!(got, cc, "{id:?}");
        let parsed = parse_control_field(cf);
        assert!(parsed.sink_ok && parsed.parity_ok && DataId::from_code(parsed.code) == Some(id));
    }
}

#[test]
fn data_id_0_and_3_are_requested_with_0x02_and_0x1a() {
    assert_eq!(DataId::Id0.control_field(), 0x02);
    assert_eq!(DataId::Id3.control_field(), 0x1A);
}

#[test]
fn a_flipped_parity_or_sink_bit_is_seen() {
    let cf = DataId::Id1.control_field();
    assert!(!parse_control_field(cf ^ 0x80).parity_ok);
    assert!(
        !parse_control_field(cf ^ 0x08).parity_ok,
        "a code bit flip breaks parity"
    );
    assert!(!parse_control_field(cf ^ 0x01).sink_ok);
}

#[test]
fn the_crc_is_the_xor_of_the_fields_as_in_a_published_capture() {
    // A published Data ID 0 answer: CF 02, SF 20, ABS 1C BD B4, CRC 37.
    let set = [0x02, 0x20, 0xB4, 0xBD, 0x1C, 0x37];
    assert!(crc_ok(&set));
    assert_eq!(with_crc(&set[..5]), set);
    let mut bad = set;
    bad[2] ^= 0x04;
    assert!(!crc_ok(&bad));
}

#[test]
fn alarms_map_onto_almc_and_the_status_field() {
    let a = Alarms {
        battery_alarm: true,
        ..Alarms::default()
    };
    assert_eq!(a.byte(), 0x80);
    assert_eq!(a.status().byte(), 0x20);
    let a = Alarms {
        counting_error: true,
        over_speed: true,
        ..Alarms::default()
    };
    assert_eq!(a.byte(), 0x05);
    assert_eq!(
        a.status(),
        Status {
            ea0: true,
            ..Status::default()
        }
    );
    assert_eq!(
        Status::from_byte(0xF0),
        Status {
            ea0: true,
            ea1: true,
            ca0: true,
            ca1: true
        }
    );
}

#[test]
fn eeprom_requests_end_in_their_crc() {
    let w = request(DataId::Id6, 5, 0xA5);
    assert_eq!(w.len(), 4);
    assert!(crc_ok(&w));
    let r = request(DataId::IdD, 79, 0);
    assert_eq!(r, with_crc(&[0xEA, 79]));
}
