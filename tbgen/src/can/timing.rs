//! `tbgen timing can`: the length of a frame with worst-case stuffing, the
//! bus load of a frame rate, the oscillator tolerance and the longest bus
//! of a scenario's bit timing, and the same for every bit rate of the
//! gateway's table (seed 003) at the scenario's f_sys and sample point.

use std::fmt::Write as _;

use model::can::frame::Frame;
use model::can::{BenchConfig, BitTiming};
use model::Setup;

/// Bits of a frame from SOF to the end of EOF with no stuff bits, and the
/// most stuff bits it can carry: the stuffed part (SOF to the last CRC bit)
/// is 34 + 8n bits (standard) or 54 + 8n (extended), then the CRC
/// delimiter, the ACK slot and delimiter and 7 EOF bits; the first stuff
/// bit needs five bits, each further one four (R. Davis et al., "Controller
/// Area Network (CAN) schedulability analysis", Real-Time Systems 35, 2007,
/// whose 47 + 8n adds the 3-bit intermission to these 44 + 8n).
pub fn frame_bits(ide: bool, n: u32) -> (u32, u32) {
    let stuffed = if ide { 54 } else { 34 } + 8 * n;
    (stuffed + 10, (stuffed - 1) / 4)
}

/// The report.
pub fn timing_report(cfg: &BenchConfig, name: &str, dlc: u8, frames_per_s: f64) -> Result<String, model::ConfigError> {
    let tb = cfg.timebase()?;
    let t = cfg.bit_timing()?;
    let rate = tb.f_sys_hz() as f64 / t.clocks_per_bit() as f64;
    let t_loop = cfg.dut.loop_delay_ns + cfg.sync_stages as f64 * 1e9 / tb.f_sys_hz() as f64;
    let mut s = String::new();
    let _ = writeln!(s, "scenario {name}: {} kbit/s at f_sys {} MHz", rate / 1e3, tb.f_sys_hz() as f64 / 1e6);
    let _ = writeln!(s, "bit timing: BRP {}, SYNC_SEG 1 + PROP_SEG {} + PHASE_SEG1 {} + PHASE_SEG2 {} = {} quanta, SJW {}, sample point {:.2} %", t.brp, t.prop_seg, t.phase_seg1, t.phase_seg2, t.ntq(), t.sjw, t.sample_point() * 100.0);
    let _ = writeln!(s, "oscillator tolerance: {:.4} % per node (min(PS1, PS2) / (2 (13 NTQ - PS2)) and SJW / (20 NTQ))", t.oscillator_tolerance() * 100.0);
    let _ = writeln!(s, "longest bus: {:.1} m (PROP_SEG covers 2 × (cable + loop delay {t_loop:.0} ns incl. {} synchroniser flops), {} ns/m)", t.max_bus_length_m(tb.f_sys_hz(), t_loop, cfg.ns_per_m), cfg.sync_stages, cfg.ns_per_m);
    let n = dlc.min(8) as u32;
    for ide in [false, true] {
        let (bits, stuff) = frame_bits(ide, n);
        let worst = bits + stuff;
        let _ = writeln!(
            s,
            "{} frame, {n} data bytes: {bits} bits + up to {stuff} stuff bits = {worst} bits = {:.1} µs; 3-bit intermission after; at {frames_per_s} frames/s the bus is {:.1} % loaded",
            if ide { "extended" } else { "standard" },
            worst as f64 / rate * 1e6,
            frames_per_s * (worst + 3) as f64 / rate * 100.0
        );
    }
    // The heaviest stuffing a real frame reaches: eight bytes of 0x00 to identifier 0.
    let zeros = Frame::data(0, &[0; 8]).wire_bits(true).len();
    let _ = writeln!(s, "check: identifier 0x000 with eight 0x00 bytes is {zeros} bits on the wire (SOF to EOF)");
    let _ = writeln!(s, "\nevery bit rate of the gateway (seed 003) at this f_sys, sample point and SJW, quanta per bit: of those with an integer BRP, the longest bus:");
    let _ = writeln!(s, "{:>6}  {:>4} {:>4}  {:>7}  {:>9}  {:>10}", "kbit/s", "BRP", "NTQ", "SP %", "tol. %", "longest m");
    for kbps in [10.0, 20.0, 50.0, 125.0, 250.0, 500.0, 800.0, 1000.0] {
        // Of the quanta per bit that give an integer prescaler, the one with the longest bus.
        let found = (8..=25)
            .filter_map(|ntq| BitTiming::for_rate(tb.f_sys_hz(), kbps * 1e3, ntq, t.sample_point(), t.sjw).ok())
            .max_by(|a, b| a.max_bus_length_m(tb.f_sys_hz(), t_loop, cfg.ns_per_m).total_cmp(&b.max_bus_length_m(tb.f_sys_hz(), t_loop, cfg.ns_per_m)));
        match found {
            Some(r) => {
                let _ = writeln!(s, "{kbps:>6}  {:>4} {:>4}  {:>7.2}  {:>9.4}  {:>10.1}", r.brp, r.ntq(), r.sample_point() * 100.0, r.oscillator_tolerance() * 100.0, r.max_bus_length_m(tb.f_sys_hz(), t_loop, cfg.ns_per_m));
            }
            None => {
                let _ = writeln!(s, "{kbps:>6}  no integer prescaler at this f_sys");
            }
        }
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn worst_case_frame_lengths_are_the_published_ones() {
        // Davis et al. 2007: 135 bits for 8 bytes standard, 160 extended,
        // each with its 3-bit intermission.
        let (b, s) = frame_bits(false, 8);
        assert_eq!(b + s + 3, 135);
        let (b, s) = frame_bits(true, 8);
        assert_eq!(b + s + 3, 160);
    }

    #[test]
    fn a_frame_on_the_wire_is_within_the_bounds_and_an_unstuffed_one_at_the_lower() {
        // The model's frames, SOF to EOF: never shorter than the unstuffed
        // length nor longer than the worst case, and one of them (no run of
        // five equal bits) exactly the unstuffed length.
        for n in [0u8, 1, 8] {
            let (bits, stuff) = frame_bits(false, n as u32);
            let lengths: Vec<u32> = (0..2048)
                .flat_map(|id| [0x55u8, 0xAA, 0x2A, 0xD5, 0x4A, 0xB5].map(|b| (id, b)))
                .map(|(id, b)| Frame::data(id, &vec![b; n as usize]).wire_bits(true).len() as u32)
                .collect();
            assert!(lengths.iter().all(|&w| (bits..=bits + stuff).contains(&w)), "{n} bytes");
            if n == 8 {
                // (Below 8 bytes DLC starts with a 0 after RTR, IDE and r0,
                // five dominant bits in a row: every such frame has a stuff
                // bit.)
                assert_eq!(lengths.iter().min(), Some(&bits), "{n} bytes");
            }
        }
        let w = Frame::data(0, &[0; 8]).wire_bits(true).len() as u32;
        assert_eq!(w, 124);
    }

    #[test]
    fn the_bus_load_counts_the_intermission_once() {
        // can_rate_250k: 250 kbit/s, 8 bytes at 1000 frames/s: 132 bits of
        // worst-case frame and 3 of intermission, 4 µs each, per millisecond.
        let (s, cfg) = crate::registry::scenario_of::<BenchConfig>("can_rate_250k", "timing can", "a CAN").unwrap();
        let report = timing_report(&cfg, &s.name, 8, 1000.0).unwrap();
        assert!(report.contains("108 bits + up to 24 stuff bits = 132 bits = 528.0 µs"), "{report}");
        assert!(report.contains("the bus is 54.0 % loaded"), "{report}");
    }
}
