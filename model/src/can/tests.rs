use super::bench::{DutSettings, Fault, FaultKind, TimingSettings};
use super::bus::Place;
use super::controller::{crc_step, ERROR_ACTIVE, ERROR_PASSIVE};
use super::emulator::{NodeSettings, Scripted};
use super::frame::{self, stuff, Frame, FrameError};
use super::*;
use crate::testbench::run_to_end;
use crate::Setup;

fn node(name: &str, pos: f64, frames: Vec<(f64, Frame)>) -> NodeSettings {
    NodeSettings { name: name.into(), place: Place { position_m: pos, loop_delay_ns: 150.0 }, ppm: 0.0, ack: true, frames: frames.into_iter().map(|(at_us, frame)| Scripted { at_us, frame }).collect() }
}

fn cfg(dut_frames: Vec<(f64, Frame)>, nodes: Vec<NodeSettings>) -> BenchConfig {
    BenchConfig {
        dut: DutSettings { frames: dut_frames.into_iter().map(|(at_us, frame)| Scripted { at_us, frame }).collect(), ..DutSettings::default() },
        nodes,
        ..BenchConfig::default()
    }
}

#[test]
fn crc_step_equals_the_catalogue_register() {
    let f = Frame::data(0x123, &[0xDE, 0xAD]);
    let r = f.covered_bits().iter().fold(0u16, |c, &b| crc_step(c, b));
    assert_eq!(r, f.crc());
}

#[test]
fn stuffing_inserts_after_five_equal_bits_and_the_parser_removes_them() {
    assert_eq!(stuff(&[false; 5]), vec![false, false, false, false, false, true]);
    assert_eq!(stuff(&[true, true, true, true, true, false]), vec![true, true, true, true, true, false, false]);
    // Data of zeros stuffs heavily; the parser gives the frame back.
    let f = Frame::data(0x000, &[0; 8]);
    let w = f.wire_bits(true);
    assert!(w.len() > f.destuffed_bits().len() + 13 + 10);
    let p = frame::parse(&w).unwrap();
    assert_eq!(p.frame, f);
    assert_eq!(p.crc, f.crc());
    assert!(p.ack);
}

#[test]
fn parser_reports_a_flipped_stuff_bit_as_a_stuff_error() {
    let f = Frame::data(0x000, &[0; 2]);
    let mut w = f.wire_bits(true);
    // Bits 0..=4: SOF and ID10..ID7 all dominant, bit 5 the stuff bit.
    assert!(w[5]);
    w[5] = false;
    assert_eq!(frame::parse(&w).unwrap_err().0, FrameError::Stuff);
}

#[test]
fn a_frame_from_a_node_is_received_acknowledged_and_reported() {
    let f = Frame::data(0x2A5, &[0x00, 0xFF, 0x00, 0xFF]);
    let c = cfg(vec![], vec![node("a", 10.0, vec![(10.0, f.clone())])]);
    let b = c.bench().unwrap();
    let run = run_to_end(b);
    assert_eq!(run.transactions.len(), 1, "{:?}", run.transactions);
    let t = &run.transactions[0];
    assert!(t.complete && t.ack);
    assert_eq!((t.id, t.dlc, t.data.clone(), t.crc), (f.id, f.dlc, f.data.clone(), Some(f.crc())));
    assert_eq!(t.dut_events, vec!["rx_valid"]);
    assert!(t.errors.is_empty());
}

#[test]
fn the_core_sends_a_frame_a_node_acknowledges() {
    let f = Frame { id: 0x7FF, ide: false, rtr: true, dlc: 2, data: vec![] };
    let c = cfg(vec![(5.0, f.clone())], vec![node("a", 40.0, vec![])]);
    let run = run_to_end(c.bench().unwrap());
    assert_eq!(run.transactions.len(), 1);
    let t = &run.transactions[0];
    assert_eq!((t.id, t.rtr, t.dlc, t.ack), (0x7FF, true, 2, true));
    assert_eq!(t.dut_events, vec!["tx_done"]);
}
