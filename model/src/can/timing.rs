//! CAN bit timing in time quanta of `f_sys` cycles, and the bit clock that
//! hard-synchronises at SOF and resynchronises within SJW.
//!
//! ```text
//!  one bit = NTQ time quanta, one quantum = BRP f_sys cycles
//!  |SYNC|<-- PROP_SEG -->|<- PHASE_SEG1 ->|<- PHASE_SEG2 ->|
//!  | tq0|  tq1 ..                   tqTSEG1|               |
//!                                           ^ sample point (end of tq TSEG1)
//!  edge in tq1..TSEG1 (late):   PHASE_SEG1 lengthened by min(e, SJW)
//!  edge in PHASE_SEG2 (early):  PHASE_SEG2 shortened by min(|e|, SJW);
//!                               |e| <= SJW: the edge cycle starts the next bit
//! ```
//! `e` is the phase error in quanta: the quantum the edge falls in (late), or
//! the quanta left in the bit (early). Only recessive-to-dominant edges after
//! a recessive sample synchronise, once between two sample points; a node
//! sending a dominant bit does not resynchronise on its own edge.

use crate::{ConfigError, Result};

/// The bit timing of one node; each field is the Verilog parameter of the
/// same name in upper case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BitTiming {
    /// Baud-rate prescaler: f_sys cycles per time quantum (1 to 1024).
    pub brp: u32,
    /// Propagation segment, quanta (1 to 8).
    pub prop_seg: u32,
    /// Phase segment 1, quanta (1 to 8).
    pub phase_seg1: u32,
    /// Phase segment 2, quanta (2 to 8, at least SJW).
    pub phase_seg2: u32,
    /// Synchronisation jump width, quanta (1 to 4, at most both phase segments).
    pub sjw: u32,
}

impl BitTiming {
    /// Quanta per bit: SYNC_SEG + PROP_SEG + PHASE_SEG1 + PHASE_SEG2.
    pub fn ntq(&self) -> u32 {
        1 + self.prop_seg + self.phase_seg1 + self.phase_seg2
    }

    /// Quanta before the sample point after SYNC_SEG (PROP_SEG + PHASE_SEG1).
    pub fn tseg1(&self) -> u32 {
        self.prop_seg + self.phase_seg1
    }

    /// f_sys cycles per nominal bit.
    pub fn clocks_per_bit(&self) -> u64 {
        self.brp as u64 * self.ntq() as u64
    }

    /// The sample point as a fraction of the bit.
    pub fn sample_point(&self) -> f64 {
        (1 + self.tseg1()) as f64 / self.ntq() as f64
    }

    /// Checks the ranges of Bosch CAN 2.0 part A §8 (8 to 25 quanta per bit) with the
    /// scenario's field names (`[can.timing]`).
    pub fn validate(&self) -> Result<()> {
        let range = |f: &str, v: u32, lo: u32, hi: u32| {
            if (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(ConfigError::invalid(
                    format!("timing.{f}"),
                    format!("{v} is outside {lo} to {hi}"),
                    format!("give {f} from {lo} to {hi} quanta"),
                ))
            }
        };
        range("brp", self.brp, 1, 1024)?;
        range("prop_seg", self.prop_seg, 1, 8)?;
        range("phase_seg1", self.phase_seg1, 1, 8)?;
        range("phase_seg2", self.phase_seg2, 2, 8)?;
        range("sjw", self.sjw, 1, 4)?;
        if self.sjw > self.phase_seg1 || self.sjw > self.phase_seg2 {
            return Err(ConfigError::invalid(
                "timing.sjw",
                format!("SJW {} exceeds a phase segment", self.sjw),
                "give SJW at most min(phase_seg1, phase_seg2)",
            ));
        }
        if !(8..=25).contains(&self.ntq()) {
            return Err(ConfigError::invalid(
                "timing",
                format!("{} quanta per bit", self.ntq()),
                "make 1 + prop_seg + phase_seg1 + phase_seg2 between 8 and 25",
            ));
        }
        Ok(())
    }

    /// The oscillator tolerance the timing allows, as a fraction (both
    /// nodes may deviate by it in opposite directions): the smaller of
    /// `min(PS1, PS2) / (2·(13·NTQ − PS2))` (resynchronisation must absorb
    /// the drift over 13 bits: 10 bits of an error flag plus a stuffed run,
    /// the worst case between two resynchronising edges after an error) and
    /// `SJW / (20·NTQ)` (10 bits between edges in a stuffed frame, drift of
    /// both nodes). Source: ISO 11898-1 bit-timing requirements as derived in
    /// F. Hartwig, A. Bassemir, "The Configuration of the CAN Bit Timing"
    /// (Bosch, 6th iCC 1999), conditions I and II.
    pub fn oscillator_tolerance(&self) -> f64 {
        let (ps1, ps2, ntq) = (
            self.phase_seg1 as f64,
            self.phase_seg2 as f64,
            self.ntq() as f64,
        );
        let a = ps1.min(ps2) / (2.0 * (13.0 * ntq - ps2));
        let b = self.sjw as f64 / (20.0 * ntq);
        a.min(b)
    }

    /// The longest bus (metres) this timing allows: PROP_SEG must cover the
    /// round trip between the two farthest nodes, `2·(L·ns_per_m + t_loop)`,
    /// where `t_loop_ns` is one node's transceiver loop delay (driver plus
    /// receiver) plus its input synchroniser, and the hard-sync quantisation
    /// of one f_sys cycle is taken from PROP_SEG (`f_sys_hz`).
    pub fn max_bus_length_m(&self, f_sys_hz: u64, t_loop_ns: f64, ns_per_m: f64) -> f64 {
        let tq_ns = self.brp as f64 * 1e9 / f_sys_hz as f64;
        let prop_ns = self.prop_seg as f64 * tq_ns - 1e9 / f_sys_hz as f64;
        ((prop_ns / 2.0 - t_loop_ns) / ns_per_m).max(0.0)
    }

    /// The timing for `bit_rate` at `f_sys_hz` with `ntq` quanta per bit and
    /// the sample point nearest `sample_point`, and `sjw` quanta (clipped to
    /// the phase segments).
    pub fn for_rate(
        f_sys_hz: u64,
        bit_rate: f64,
        ntq: u32,
        sample_point: f64,
        sjw: u32,
    ) -> Result<BitTiming> {
        if !(8..=25).contains(&ntq) {
            return Err(ConfigError::invalid(
                "timing.tq_per_bit",
                format!("{ntq}"),
                "give 8 to 25 quanta per bit (Bosch CAN 2.0 part A §8)",
            ));
        }
        let brp_f = f_sys_hz as f64 / bit_rate / ntq as f64;
        if !(brp_f.is_finite() && (brp_f - brp_f.round()).abs() < 1e-6 && brp_f >= 1.0) {
            return Err(ConfigError::invalid(
                "bit_rate_kbps",
                format!("f_sys / (bit rate × {ntq} quanta) = {brp_f:.4}"),
                "choose a bit rate and tq_per_bit whose product divides f_sys",
            ));
        }
        let after = ((1.0 - sample_point) * ntq as f64).round() as u32;
        let phase_seg2 = after.clamp(2, 8);
        let tseg1 = ntq - 1 - phase_seg2;
        // PHASE_SEG1 as long as PHASE_SEG2 (symmetric resynchronisation
        // range), PROP_SEG the rest, neither above 8.
        let phase_seg1 = phase_seg2
            .min(tseg1 - 1)
            .max(tseg1.saturating_sub(8))
            .min(8);
        let prop_seg = tseg1 - phase_seg1;
        let t = BitTiming {
            brp: brp_f.round() as u32,
            prop_seg,
            phase_seg1,
            phase_seg2,
            sjw: sjw.min(phase_seg1).min(phase_seg2),
        };
        t.validate()?;
        Ok(t)
    }
}

/// What the bit clock says about one f_sys cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Tick {
    /// This cycle is the sample point: the engine reads the bus.
    pub sample: bool,
    /// The next cycle starts a bit (or this one did, after a restart): the
    /// transmitter loads its next bit at this edge.
    pub load_tx: bool,
}

/// The bit clock's registers (`pre_cnt`, `tq_cnt`, `ext`, `short`, `synced` in the RTL).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BitClock {
    /// f_sys cycle within the quantum, 0 to BRP − 1.
    pub pre_cnt: u32,
    /// Quantum within the bit, 0 = SYNC_SEG.
    pub tq_cnt: u32,
    /// Quanta PHASE_SEG1 is lengthened by in this bit.
    pub ext: u32,
    /// PHASE_SEG2 is shortened by SJW in this bit.
    pub short: bool,
    /// A synchronisation happened since the last sample point.
    pub synced: bool,
}

impl BitClock {
    /// One f_sys cycle. `edge`: a qualified recessive-to-dominant edge at
    /// the synchroniser's output this cycle; `hard`: hard synchronisation is
    /// allowed (bus idle, SOF); `resync`: resynchronisation is allowed.
    pub fn step(&mut self, t: &BitTiming, edge: bool, hard: bool, resync: bool) -> Tick {
        let tseg1 = t.tseg1();
        let last_tq = t.ntq() - 1;
        let edge = edge && !self.synced;
        let restart;
        if edge && hard {
            restart = true;
        } else if edge && resync && self.tq_cnt != 0 {
            if self.tq_cnt <= tseg1 + self.ext {
                // Late edge: lengthen PHASE_SEG1.
                self.ext = self.tq_cnt.min(t.sjw);
                self.synced = true;
                restart = false;
            } else {
                // Early edge: quanta left in the bit, this one included.
                let left = last_tq + self.ext - self.tq_cnt + 1;
                self.synced = true;
                if left <= t.sjw {
                    restart = true;
                } else {
                    self.short = true;
                    restart = false;
                }
            }
        } else {
            restart = false;
        }
        if restart {
            // This cycle is the first of SYNC_SEG.
            self.ext = 0;
            self.short = false;
            self.synced = true;
            if t.brp == 1 {
                self.pre_cnt = 0;
                self.tq_cnt = 1;
            } else {
                self.pre_cnt = 1;
                self.tq_cnt = 0;
            }
            return Tick {
                sample: false,
                load_tx: true,
            };
        }
        let end_tq = self.end_tq(t);
        let tq_last_cycle = self.pre_cnt == t.brp - 1;
        let sample = tq_last_cycle && self.tq_cnt == tseg1 + self.ext;
        let bit_end = tq_last_cycle && self.tq_cnt == end_tq;
        if sample {
            self.synced = false;
        }
        if tq_last_cycle {
            self.pre_cnt = 0;
            if bit_end {
                self.tq_cnt = 0;
                self.ext = 0;
                self.short = false;
            } else {
                self.tq_cnt += 1;
            }
        } else {
            self.pre_cnt += 1;
        }
        Tick {
            sample,
            load_tx: bit_end,
        }
    }

    /// Advances `n` cycles without an edge, exactly as `n` calls of
    /// [`BitClock::step`] with `edge = false` would (the sample points and
    /// bit ends they pass are the caller's to know uneventful). Short of
    /// the next sample point or bit end ([`BitClock::cycles_to_event`]) the
    /// counters are advanced in one go. Past it, a bit lengthened or
    /// shortened by a resynchronisation, or one with a synchronisation
    /// still recorded, is stepped to its end; from there the clock is
    /// periodic, `TQ × BRP` cycles a bit, and is advanced in one go.
    pub fn skip(&mut self, t: &BitTiming, mut n: u64) {
        let brp = t.brp as u64;
        if n <= self.cycles_to_event(t) {
            // Within the bit and before its next sample point or end: the
            // counters only count, whatever the bit's length.
            let at = self.tq_cnt as u64 * brp + self.pre_cnt as u64 + n;
            self.tq_cnt = (at / brp) as u32;
            self.pre_cnt = (at % brp) as u32;
            return;
        }
        while n > 0 && (self.ext != 0 || self.short || self.synced) {
            self.step(t, false, false, false);
            n -= 1;
        }
        let at = (self.tq_cnt as u64 * brp + self.pre_cnt as u64 + n) % (t.ntq() as u64 * brp);
        self.tq_cnt = (at / brp) as u32;
        self.pre_cnt = (at % brp) as u32;
    }

    /// Cycles from now before the next one whose step is a sample point or
    /// the end of the bit (no edge): they only count `pre_cnt`/`tq_cnt`.
    /// The bit's own length counts: PHASE_SEG1 as lengthened (`ext`),
    /// PHASE_SEG2 as shortened (`short`).
    pub fn cycles_to_event(&self, t: &BitTiming) -> u64 {
        let brp = t.brp as u64;
        let sample_tq = t.tseg1() + self.ext;
        let end_tq = self.end_tq(t);
        let next = if self.tq_cnt <= sample_tq {
            sample_tq
        } else {
            end_tq
        };
        (next - self.tq_cnt) as u64 * brp + (brp - 1 - self.pre_cnt as u64)
    }

    /// Cycles from now before the next one whose step is a sample point
    /// (no edge), past the end of this bit if that comes first: the next
    /// bit then starts unlengthened, its sample point TSEG1 quanta in.
    pub fn cycles_to_sample(&self, t: &BitTiming) -> u64 {
        let brp = t.brp as u64;
        let sample_tq = t.tseg1() + self.ext;
        if self.tq_cnt <= sample_tq {
            return (sample_tq - self.tq_cnt) as u64 * brp + (brp - 1 - self.pre_cnt as u64);
        }
        let end_tq = self.end_tq(t);
        let to_end = (end_tq - self.tq_cnt) as u64 * brp + (brp - 1 - self.pre_cnt as u64);
        to_end + 1 + (t.tseg1() as u64 + 1) * brp - 1
    }

    /// The bit's last quantum: PHASE_SEG2 ends TSEG1 + PHASE_SEG2 quanta in,
    /// lengthened by `ext`, shortened by SJW when `short`.
    fn end_tq(&self, t: &BitTiming) -> u32 {
        t.ntq() - 1 + self.ext - if self.short { t.sjw } else { 0 }
    }

    /// Cycles from now in which `tq_cnt` keeps its value (no edge).
    pub fn quantum_left(&self, t: &BitTiming) -> u64 {
        (t.brp - 1 - self.pre_cnt) as u64
    }
}
