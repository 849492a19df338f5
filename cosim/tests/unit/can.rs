use cosim::can::*;
use cosim::{Emulator, Pins};

const TWO: &str = "[can]\ntiming = { bit_rate_kbps = 1000, tq_per_bit = 10, sample_point = 0.8, sjw = 2 }\n\
    [[can.nodes]]\nname = \"a\"\nposition_m = 5\n\
    [[can.nodes]]\nname = \"b\"\nposition_m = 10\nframes = [{ at_us = 5, id = 0x123, dlc = 2, data = [0xAB, 0xCD] }]\n";

#[test]
fn a_nodes_frame_reaches_the_other_node_through_a_recessive_master() {
    let mut emu = CanEmulator::from_toml(TWO, "two.toml", 10_000_000).unwrap();
    let mut dominant = 0;
    for _ in 0..3000 {
        dominant += (emu.step(Pins(2)).0 & 1 == 0) as u32;
    }
    // Node a received b's frame (and acknowledged it); the master's RXD saw it.
    assert_eq!(emu.count(), 1);
    assert_eq!(emu.last_value(16), Some(0x123));
    assert_eq!(emu.last_value(32), Some(2));
    assert_eq!(emu.last_value(0), Some(0xABCD << 48));
    assert_eq!(emu.last_value(1 + 48), Some(1));
    assert!(dominant > 10);
    assert!(emu.violations().is_empty(), "{:?}", emu.violations());
}

#[test]
fn a_frame_scripted_at_run_time_is_sent() {
    let mut emu = CanEmulator::from_toml(TWO, "two.toml", 10_000_000).unwrap();
    emu.schedule_fault("[[send]]\nnode = 0\nid = 0x42\ndlc = 1\ndata = [7]\n")
        .unwrap();
    for _ in 0..6000 {
        emu.step(Pins(2));
    }
    assert_eq!(emu.last_value(48), Some(1), "node a sent its frame");
    assert_eq!(emu.last_value(1 + 16), Some(0x42), "node b received it");
    let err = emu
        .schedule_fault("[[send]]\nnode = 5\nid = 1\n")
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("send[0].node"), "{err}");
}

#[test]
fn a_master_holding_the_bus_dominant_is_reported() {
    let mut emu = CanEmulator::from_toml(TWO, "two.toml", 10_000_000).unwrap();
    for k in 0..3000 {
        // A dominant pulse every 30 bits: a form or stuff error at the nodes.
        let tx = k % 300 >= 70;
        emu.step(Pins((tx as u32) << 1));
    }
    // The master's TXD dominant for 23 bits: longer than an error flag.
    assert!(!emu.violations().is_empty());
    assert_eq!(
        emu.violations()[0].rule,
        model::can::rules::DOMINANT.label()
    );
}

#[test]
fn faults_and_missing_nodes_are_refused_by_name() {
    let err = CanEmulator::from_toml("[can]\n", "c.toml", 10_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.starts_with("c.toml: ") && err.contains("nodes"),
        "{err}"
    );
    let err = CanEmulator::from_toml("", "c.toml", 3_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("at least 4000000 Hz"), "{err}");
}
