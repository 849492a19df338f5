use model::can::frame::Frame;
use model::canopen::cob::Service;
use model::canopen::interpret::*;

/// Seed 003 §8, frame by frame.
#[test]
fn setup_example_in_words() {
    let t = |id: u32, d: &[u8]| interpret(&Frame::data(id, d)).text;
    assert_eq!(t(0x8C, &[]), "boot-up of node 12 (gateway form)");
    assert_eq!(
        t(0x60C, &[0x22, 0x00, 0x62, 0x00, 0x0A, 0, 0, 0]),
        "SDO write 6200h sub 0 (Cyclic timer) = 10 (0xA)"
    );
    assert_eq!(
        t(0x58C, &[0x60, 0x00, 0x62, 0x00, 0, 0, 0, 0]),
        "SDO write confirmed 6200h sub 0 (Cyclic timer)"
    );
    assert_eq!(t(0x000, &[0x01, 0x0C]), "NMT start remote node to node 12");
    assert_eq!(t(0x18C, &[0x92, 0x10, 0, 0]), "position 4242");
    assert_eq!(t(0x58C, &[0x80, 0x01, 0x60, 0x00, 0x32, 0x00, 0x09, 0x06]), "SDO abort 6001h sub 0 (Measuring units per revolution): 06090032h value of parameter written too low");
    assert_eq!(
        t(0x58C, &[0x4B, 0x00, 0x65, 0x00, 0x04, 0x00, 0, 0]),
        "SDO read 6500h sub 0 (Operating status) = 4 (0x4)"
    );
    assert_eq!(t(0x080, &[]), "SYNC");
    assert_eq!(t(0x70C, &[0x85]), "state Operational, toggle 1");
    assert_eq!(
        interpret(&Frame::data(0x18C, &[1, 0, 0, 0])).service,
        Service::Tpdo1(12)
    );
}

/// DS 301: an EMCY is 8 bytes (error code, error register, 5 manufacturer
/// bytes); a frame of another length on the EMCY identifier is not one.
#[test]
fn only_an_eight_byte_frame_on_the_emcy_identifier_is_an_emcy() {
    let t = |d: &[u8]| interpret(&Frame::data(0x85, d)).text;
    assert_eq!(
        t(&[0x00, 0x10, 0x01, 0, 0, 0, 0, 0]),
        "EMCY code 1000h, error register 01h"
    );
    assert_eq!(
        t(&[0x00, 0x10, 0x01, 0x00]),
        "not an EMCY: 4 bytes on node 5's EMCY identifier (an EMCY has 8)"
    );
    assert_eq!(t(&[]), "boot-up of node 5 (gateway form)");
}
