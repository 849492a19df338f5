use model::angle::angle_deg;
use model::can::frame::Frame;
use model::canopen::node::Device;
use model::canopen::sar58k24::*;

fn dev() -> SarCan {
    let mut s = SarCan::new(&SarCanConfig::default()).unwrap();
    s.power_on(0);
    s
}

/// Seed 001 §3.4 (5): a 14-bit encoder answers `47 26 00 …` on frame ID 0120H (factory node 0x20): 9799, 215.3100°.
#[test]
fn seed_reply_47_26_is_215_3100_degrees() {
    let mut s = dev();
    s.set_raw(9799, 0);
    let a = s.on_frame(&Frame::data(0x220, &[0x80, 0x20, 0, 0, 0, 0, 0, 0]), 0);
    assert_eq!(a, vec![Frame::data(0x120, &[0x47, 0x26, 0, 0, 0, 0, 0, 0])]);
    let v = a[0].data[0] as u64 | (a[0].data[1] as u64) << 8;
    assert_eq!(v, 9799);
    assert_eq!(format!("{:.4}", angle_deg(v, 14)), "215.3100");
}

/// Seed 001 §3.4 (1): node 0xFF's capture `02 2B 00 …` on 0x1FF is 0x2B02 = 11010, low byte first.
#[test]
fn capture_table_02_2b_is_11010() {
    let d = [0x02u8, 0x2B];
    assert_eq!(d[0] as u64 | (d[1] as u64) << 8, 11010);
}

/// Seed 001 §3.4 ①: start sends the position at once and every cycle (factory 100 ms).
#[test]
fn start_sends_every_cycle() {
    let mut s = dev();
    s.set_raw(5, 0);
    assert_eq!(
        s.on_frame(&Frame::data(0x220, &[0x01, 0x20, 0, 0, 0, 0, 0, 0]), 0)
            .len(),
        1
    );
    assert!(s.poll(99_999_999).is_empty());
    assert_eq!(
        s.poll(100_000_000),
        vec![Frame::data(0x120, &[5, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert!(
        s.on_frame(&Frame::data(0x221, &[0x01, 0x21, 0, 0, 0, 0, 0, 0]), 0)
            .is_empty(),
        "another node's command"
    );
}

/// ④ ⑤ ⑥ ⑦ ⑧: direction, zero, timed send and its stop, each answered with its code and 00.
#[test]
fn command_set() {
    let mut s = dev();
    s.set_raw(1000, 0);
    assert_eq!(
        s.on_frame(&Frame::data(0x220, &[0x20, 0x20, 0, 0, 0, 0, 0, 0]), 0),
        vec![Frame::data(0x120, &[0x20, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(s.position(0), 0);
    s.set_raw(1010, 0);
    assert_eq!(s.position(0), 10);
    assert_eq!(
        s.on_frame(&Frame::data(0x220, &[0x22, 0x20, 0, 0, 0, 0, 0, 0]), 0),
        vec![Frame::data(0x120, &[0x22, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(s.position(0), (1 << 14) - 10);
    s.on_frame(&Frame::data(0x220, &[0x22, 0x20, 0, 0, 0, 0, 0, 0]), 0);
    assert_eq!(s.position(0), 10);
    assert_eq!(
        s.on_frame(&Frame::data(0x220, &[0x31, 0x20, 50, 0, 0, 0, 0, 0]), 0),
        vec![Frame::data(0x120, &[0x31, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert!(s.poll(19_999_999).is_empty());
    assert_eq!(s.poll(20_000_000).len(), 1, "50 times a second");
    assert_eq!(s.poll(40_000_000).len(), 1);
    s.on_frame(
        &Frame::data(0x220, &[0x31, 0x20, 50, 0, 0, 0, 0, 0]),
        40_000_000,
    );
    assert!(s.poll(1_000_000_000).is_empty(), "the same bytes stop it");
}

/// ② ③: configuration on 0x7E5: enter, new node, new bit rate; effective at the next power-on.
#[test]
fn configuration_channel() {
    let mut s = dev();
    assert!(
        s.on_frame(&Frame::data(0x7E5, &[0x11, 0x21, 0, 0, 0, 0, 0, 0]), 0)
            .is_empty(),
        "not in configuration mode"
    );
    assert!(s
        .on_frame(&Frame::data(0x7E5, &[0x04, 0x01, 0, 0, 0, 0, 0, 0]), 0)
        .is_empty());
    assert_eq!(
        s.on_frame(&Frame::data(0x7E5, &[0x11, 0x21, 0, 0, 0, 0, 0, 0]), 0),
        vec![Frame::data(0x7E5, &[0x11, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(
        s.on_frame(&Frame::data(0x7E5, &[0x13, 0x00, 0x02, 0, 0, 0, 0, 0]), 0),
        vec![Frame::data(0x7E5, &[0x13, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert!(
        s.on_frame(&Frame::data(0x7E5, &[0x13, 0x00, 0x01, 0, 0, 0, 0, 0]), 0)
            .is_empty(),
        "code 01 is not in the table"
    );
    assert_eq!((s.node(), s.bit_rate_kbps()), (0x20, 250));
    s.power_on(0);
    assert_eq!((s.node(), s.bit_rate_kbps()), (0x21, 500));
    assert_eq!(
        s.on_frame(&Frame::data(0x221, &[0x80, 0x21, 0, 0, 0, 0, 0, 0]), 0)[0].id,
        0x121
    );
    assert_eq!(bit_rate_of_code(0x00), Some(1000));
    assert_eq!(bit_rate_of_code(0x03), Some(250));
}

/// The capture's node 0xFF answers on 0x1FF; `answer_base = 0x180` answers on 0x180 + node and refuses nodes above 0x7F.
#[test]
fn answer_identifier_readings() {
    let mut s = SarCan::new(&SarCanConfig {
        node: 0xFF,
        ..Default::default()
    })
    .unwrap();
    s.power_on(0);
    assert_eq!(
        s.on_frame(&Frame::data(0x2FF, &[0x01, 0xFF, 0, 0, 0, 0, 0, 0]), 0)[0].id,
        0x1FF
    );
    let mut s = SarCan::new(&SarCanConfig {
        answer_base: 0x180,
        ..Default::default()
    })
    .unwrap();
    s.power_on(0);
    assert_eq!(
        s.on_frame(&Frame::data(0x220, &[0x80, 0x20, 0, 0, 0, 0, 0, 0]), 0)[0].id,
        0x1A0
    );
    let e = SarCan::new(&SarCanConfig {
        answer_base: 0x180,
        node: 0xFF,
        ..Default::default()
    })
    .unwrap_err();
    assert_eq!(e.field(), "sar_can.node");
}

/// The named reading `codes22_and23`.
#[test]
fn direction_codes_reading() {
    let mut s = SarCan::new(&SarCanConfig {
        direction: Direction::Codes22And23,
        ..Default::default()
    })
    .unwrap();
    s.power_on(0);
    s.set_raw(3, 0);
    s.on_frame(&Frame::data(0x220, &[0x23, 0x20, 0, 0, 0, 0, 0, 0]), 0);
    assert_eq!(s.position(0), (1 << 14) - 3);
    s.on_frame(&Frame::data(0x220, &[0x22, 0x20, 0, 0, 0, 0, 0, 0]), 0);
    assert_eq!(s.position(0), 3);
}

/// On the bit-level bus at 250 kbit/s: the example's click and its answer.
#[test]
fn click_on_the_bus() {
    use model::can::emulator::{NodeSettings, Scripted};
    use model::can::{Bus, Emulator};
    use model::Timebase;
    let tb = Timebase::from_mhz(40.0).unwrap();
    let timing = model::canopen::NodeTiming::default();
    let mut d = SarCan::new(&SarCanConfig::default()).unwrap();
    d.set_raw(9799, 0);
    let s = NodeSettings {
        name: "sar".into(),
        position_m: 3.0,
        loop_delay_ns: 150.0,
        ppm: 0.0,
        ack: true,
        frames: vec![],
    };
    let mut node = model::canopen::DeviceNode::with(d, &s, timing, &tb).unwrap();
    let frames = vec![Scripted::new(
        200.0,
        Frame::data(0x220, &[0x80, 0x20, 0, 0, 0, 0, 0, 0]),
    )];
    let mut host = Emulator::new(
        &NodeSettings {
            name: "host".into(),
            frames,
            ..s.clone()
        },
        timing.controller(&tb, 250).unwrap(),
        &tb,
    )
    .unwrap();
    let places = [
        model::can::bus::Place {
            position_m: 0.0,
            loop_delay_ns: 150.0,
        },
        s.place(),
    ];
    let mut bus = Bus::new(&places, 5.0, &tb);
    for _ in 0..tb.cycles_nearest_ns(1.5e6) {
        let t = [host.step(bus.rx(0)), node.step(bus.rx(1))];
        bus.push(&t);
    }
    assert_eq!(
        host.received(),
        &[Frame::data(0x120, &[0x47, 0x26, 0, 0, 0, 0, 0, 0])]
    );
}
