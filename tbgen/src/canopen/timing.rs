//! The numbers of `tbgen timing canopen` (to be wired in with the
//! protocol's registry line): PDO frame time with worst-case stuffing, bus
//! load per encoder, the worst-case position latency, and how many encoders
//! fit one SYNC cycle, at every bit rate of the gateway (seed 003 §5.5).
//!
//! ```text
//!  frame bits (standard, n data bytes, SOF to EOF) = 44 + 8n, worst-case stuff bits = (34 + 8n − 1) / 4   (crate::can::timing)
//!  slot        = frame bits + stuff bits + 3 (intermission)
//!  TPDO (4 B)  = 76 + 16 + 3 = 95 bits;   SYNC (0 B) = 44 + 8 + 3 = 55 bits;   longest frame (8 B) = 108 + 24 + 3 = 135 bits
//!  latency     = one longest frame already on the bus (non-preemptive) + the TPDO itself
//!  encoders per cycle = ⌊(cycle bits − SYNC slot) / TPDO slot⌋
//! ```

use std::fmt::Write as _;

use crate::can::timing::frame_bits;
use model::canopen::encoder::BIT_RATES_KBPS;

/// Bits a standard frame of `n` data bytes can take on the bus, with worst-case stuffing and the intermission.
pub fn slot_bits(n: u32) -> u32 {
    let (bits, stuff) = frame_bits(false, n);
    bits + stuff + 3
}

/// Encoders whose TPDO (4 bytes) fits one cycle of `cycle_us` after its SYNC, at `kbps`.
pub fn encoders_per_cycle(kbps: u32, cycle_us: f64) -> u32 {
    let bits = (cycle_us * kbps as f64 / 1e3).floor() as u32;
    bits.saturating_sub(slot_bits(0)) / slot_bits(4)
}

/// The table for a cyclic period `period_ms` (bus load of one encoder) and a SYNC cycle `cycle_us`.
pub fn report(period_ms: f64, cycle_us: f64) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "TPDO 4 bytes: {} bits worst case (stuffing, intermission); SYNC {} bits; longest frame {} bits", slot_bits(4), slot_bits(0), slot_bits(8));
    let _ = writeln!(o, "{:>10} {:>12} {:>14} {:>16} {:>18}", "kbit/s", "TPDO µs", "latency µs", format!("load/enc @{period_ms} ms"), format!("encoders/{cycle_us} µs"));
    for k in BIT_RATES_KBPS {
        let bit_us = 1e3 / k as f64;
        let pdo = slot_bits(4) as f64 * bit_us;
        let lat = (slot_bits(8) + slot_bits(4)) as f64 * bit_us;
        let load = pdo / (period_ms * 1e3) * 100.0;
        let _ = writeln!(o, "{k:>10} {pdo:>12.1} {lat:>14.1} {load:>15.3}% {:>18}", encoders_per_cycle(k, cycle_us));
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The slot lengths, from the frame layout; at 1 Mbit/s a 1 ms SYNC cycle holds (1000 − 55) / 95 = 9 encoders.
    #[test]
    fn slots_and_encoders_per_millisecond() {
        assert_eq!((slot_bits(4), slot_bits(0), slot_bits(8)), (95, 55, 135));
        assert_eq!(encoders_per_cycle(1000, 1000.0), 9);
        assert_eq!(encoders_per_cycle(500, 1000.0), 4);
        assert_eq!(encoders_per_cycle(250, 1000.0), 2);
        assert_eq!(encoders_per_cycle(125, 1000.0), 0);
        let r = report(10.0, 1000.0);
        // The seed's 10 ms at 250 kbit/s: 380 µs per TPDO, 3.8 % of the bus.
        assert!(r.contains("       250        380.0"), "{r}");
        assert!(r.contains("3.800%"), "{r}");
    }
}
