//! The EnDat probes: the master's clock (bit 0 of the stimulus), its data
//! driver's level (bit 1) and enable (bit 2); the emulator sees those, the
//! monitor those and the encoder's data at the master (bit 3), as the
//! wrappers `endat_encoder_emu` and `endat_monitor` wire them.
//!
//! The encoder answers at once (no cable, no output delay, `t_cal` 0: its
//! start bit at `R11`), so the master clocks exactly the frame: a type 2.2
//! position frame is the start bit and 32 bits, the last sampled at `F44`; a
//! type 2.1 one 31 bits, the last at `F43`. The encoder's recovery time I is
//! its default 15 µs, its line rising at the master 15.01 µs after the last
//! clock edge (two emulator cycles after its t_m).

use super::{Kit, Probe, Src, Stimulus, NS, US};
use crate::Pins;

/// EnDat's kit.
pub const KIT: Kit = Kit {
    protocol: "endat",
    monitor: &[
        Src::Master(0),
        Src::Master(1),
        Src::Master(2),
        Src::Emulator(0),
    ],
    idle: Pins(1),
    probes,
};

/// A 25-bit encoder answering at once; 200 MHz (5 ns); no delay
/// compensation: the fastest clock 2 MHz.
const PLAIN: &str = "positions = [104462, 33554431, 0, 4242]\n[encoder]\nt_cal_us = 0\noutput_delay_ns = 0\n[cable]\nlength_m = 0\n";
const PLAIN_HZ: u64 = 200_000_000;
/// The same with delay compensation (the fastest clock 8 MHz); 64 MHz
/// (15.625 ns: 62.5 ns, an 8 MHz phase, is four samples).
const COMP: &str = "positions = [104462, 33554431, 0, 4242]\n[master]\ndelay_comp = true\n[encoder]\nt_cal_us = 0\noutput_delay_ns = 0\n[cable]\nlength_m = 0\n";
const COMP_HZ: u64 = 64_000_000;
/// With delay compensation at the 16 MHz of special applications.
const SPECIAL: &str = "positions = [104462, 33554431, 0, 4242]\n[emulator]\nmax_line_clock_khz = 16000\n[checks]\nmax_clock_khz = 16000\n[master]\ndelay_comp = true\n[encoder]\nt_cal_us = 0\noutput_delay_ns = 0\n[cable]\nlength_m = 0\n";

/// The plain encoder behind 30 m of cable: a round trip of 300 ns.
const CABLE: &str = "positions = [104462, 33554431, 0, 4242]\n[encoder]\nt_cal_us = 0\noutput_delay_ns = 0\n[cable]\nlength_m = 30\n";

/// Falling edges of a type 2.2 position read (`111000`), the last sampling the CRC's last bit.
const POS22_FALLS: u32 = 44;
/// The same of a type 2.1 one (`000111`).
const POS21_FALLS: u32 = 43;

/// One transfer as the master clocks it.
#[derive(Debug, Clone)]
struct Xfer {
    mode: u8,
    /// The first low phase, `F1` to `R1`.
    t_st: u64,
    /// The high and low phase of every other period.
    high: u64,
    low: u64,
    /// Falling edges.
    falls: u32,
    /// The clock high after the last rising edge.
    rest: u64,
    /// Phases replaced: `(k, high, ps)`, the high phase after `R_k` or the low phase after `F_k`.
    phases: Vec<(u32, bool, u64)>,
    /// The driver on from `F_a`, off at `F_b`, each shifted by ps (`(a, shift_a, b, shift_b)`).
    driver: (u32, i64, u32, i64),
}

impl Xfer {
    /// A read with `mode` at a clock of `high` + `low` ps, t_ST `t_st`.
    fn new(mode: u8, t_st: u64, high: u64, low: u64, rest: u64) -> Self {
        let falls = if mode == 0b111000 {
            POS22_FALLS
        } else {
            POS21_FALLS
        };
        Xfer {
            mode,
            t_st,
            high,
            low,
            falls,
            rest,
            phases: Vec::new(),
            driver: (2, 0, 8, 0),
        }
    }

    fn phase(mut self, k: u32, high: bool, ps: u64) -> Self {
        self.phases.push((k, high, ps));
        self
    }

    fn driver(mut self, driver: (u32, i64, u32, i64)) -> Self {
        self.driver = driver;
        self
    }

    /// The master's pins, as `(time, clk, d, de)` edges from 0, and the length.
    fn line(&self) -> Stimulus {
        // Every change of a pin, (ps from F1, bit, level).
        let mut ev: Vec<(u64, u32, bool)> = Vec::new();
        let mut t = 0;
        let (a, sa, b, sb) = self.driver;
        let at = |t: u64, s: i64| t.saturating_add_signed(s);
        for k in 1..=self.falls {
            ev.push((t, 0, false));
            if (2..=7).contains(&k) {
                ev.push((t, 1, self.mode >> (7 - k) & 1 != 0));
            } else if k == 8 {
                ev.push((t, 1, true));
            }
            if k == a {
                ev.push((at(t, sa), 2, true));
            }
            if k == b {
                ev.push((at(t, sb), 2, false));
            }
            let low = if k == 1 { self.t_st } else { self.low };
            t += self.pick(k, false, low);
            ev.push((t, 0, true));
            let high = if k == self.falls {
                self.rest
            } else {
                self.high
            };
            t += self.pick(k, true, high);
        }
        ev.sort_by_key(|e| e.0);
        let mut out = Vec::new();
        let mut level = 0b011u32;
        let mut from = 0;
        for (when, bit, v) in ev {
            if when > from {
                out.push((level, when - from));
                from = when;
            }
            level = if v {
                level | 1 << bit
            } else {
                level & !(1 << bit)
            };
        }
        out.push((level, t - from));
        out
    }

    fn pick(&self, k: u32, high: bool, dflt: u64) -> u64 {
        self.phases
            .iter()
            .rev()
            .find(|p| p.0 == k && p.1 == high)
            .map_or(dflt, |p| p.2)
    }
}

/// The clock idle 20 µs, then the transfers.
fn endat(xfers: &[Xfer]) -> Stimulus {
    let mut l = vec![(0b011, 20 * US)];
    for x in xfers {
        l.extend(x.line());
    }
    l
}

/// A type 2.2 read at 2 MHz (t_ST 2 µs), then `rest` of clock high.
fn pos22(rest: u64) -> Xfer {
    Xfer::new(0b111000, 2 * US, 250 * NS, 250 * NS, rest)
}

/// A type 2.2 read at 8 MHz (t_ST 2 µs).
fn pos22_8mhz(rest: u64) -> Xfer {
    Xfer::new(0b111000, 2 * US, 62_500, 62_500, rest)
}

/// The delay measurement: `n` type 2.1 reads at 200 kHz (or `high` +
/// `low`), each followed by 1.01 ms (t_b).
fn measurement(n: usize, high: u64, low: u64) -> Vec<Xfer> {
    vec![Xfer::new(0b000111, low, high, low, 1_010 * US); n]
}

/// The line high at the master again (t_m, 15 µs, and two emulator cycles) and t_R (500 ns) past the last edge.
const T_M_T_R: u64 = 15_510 * NS;

fn probes() -> Vec<Probe> {
    let p = |rule, legal, what, line, reads: &'static [u64]| Probe {
        protocol: "endat",
        rule,
        legal,
        what,
        toml: PLAIN,
        f_hz: PLAIN_HZ,
        line,
        unknown: 0,
        unknown_ps: 0,
        reads,
    };
    let comp = |rule, legal, what, mut xfers: Vec<Xfer>, reads: &'static [u64]| {
        let mut all = measurement(3, 2_500 * NS, 2_500 * NS);
        all.append(&mut xfers);
        Probe {
            toml: COMP,
            f_hz: COMP_HZ,
            ..p(rule, legal, what, endat(&all), reads)
        }
    };
    let special = |rule, legal, what, xfers: Vec<Xfer>| Probe {
        toml: SPECIAL,
        ..comp(rule, legal, what, xfers, &[])
    };
    let wait = 40 * US;
    vec![
        p("f_c", true, "2 MHz without delay compensation, the fastest clock: phases of exactly 250 ns", endat(&[pos22(wait), pos22(wait)]), &[104462, 33554431]),
        p("f_c", true, "1 MHz with the clock high 550 ns, low 450 ns", endat(&[Xfer::new(0b111000, 450 * NS, 550 * NS, 450 * NS, wait)]), &[104462]),
        p("f_c", false, "4 MHz without delay compensation", endat(&[Xfer::new(0b111000, 2 * US, 125 * NS, 125 * NS, wait)]), &[]),
        p("f_c", false, "2 MHz with one low phase of 245 ns, its high phase 255 ns", endat(&[pos22(wait).phase(20, false, 245 * NS).phase(20, true, 255 * NS)]), &[]),
        comp("f_c", true, "8 MHz with delay compensation: phases of exactly 62.5 ns", vec![pos22_8mhz(wait)], &[]),
        Probe {
            f_hz: 400_000_000,
            ..comp("f_c", false, "8 MHz with delay compensation, one low phase of 60 ns, its high 65 ns (400 MHz sampling)", vec![pos22_8mhz(wait).phase(20, false, 60 * NS).phase(20, true, 65 * NS)], &[])
        },
        p("f_c min", true, "100 kHz, the slowest clock: periods of exactly 10 us", endat(&[Xfer::new(0b111000, 5 * US, 5 * US, 5 * US, wait)]), &[104462]),
        p("f_c min", false, "100 kHz with one period of 10.02 us", endat(&[Xfer::new(0b111000, 5 * US, 5 * US, 5 * US, wait).phase(20, true, 5_020 * NS)]), &[]),
        p("on-off ratio", true, "500 kHz with the clock high 1.1 us, low 0.9 us (10 % apart)", endat(&[Xfer::new(0b111000, 900 * NS, 1_100 * NS, 900 * NS, wait)]), &[104462]),
        p("on-off ratio", false, "500 kHz with one period high 1.105 us, low 0.895 us", endat(&[Xfer::new(0b111000, US, US, US, wait).phase(20, false, 895 * NS).phase(20, true, 1_105 * NS)]), &[]),
        p("t_ST", true, "1.6 MHz with a first low phase of 312.5 ns (below 2 MHz the phase rule alone)", endat(&[Xfer::new(0b111000, 312_500, 312_500, 312_500, wait)]), &[104462]),
        p("t_ST", false, "2 MHz with a first low phase of 1.995 us", endat(&[Xfer::new(0b111000, 1_995 * NS, 250 * NS, 250 * NS, wait)]), &[]),
        comp("t_ST", false, "8 MHz with delay compensation and a first low phase of 1.984 us", vec![Xfer::new(0b111000, 1_984_375, 62_500, 62_500, wait)], &[]),
        special("t_ST", true, "16 MHz (special applications) with a first low phase of 1 us", vec![Xfer::new(0b111000, US, 31_250, 31_250, wait)]),
        special("t_ST", false, "16 MHz with a first low phase of 0.984 us", vec![Xfer::new(0b111000, 984_375, 31_250, 31_250, wait)]),
        Probe {
            unknown: 0b100,
            unknown_ps: 10 * US,
            ..p("send block", true, "the driver enable X from time 0 to 10 us (a master in reset), then on from F2 to F8", endat(&[pos22(wait), pos22(wait)]), &[104462, 33554431])
        },
        p("send block", false, "the driver on 50 ns before F2", endat(&[pos22(wait).driver((2, -50_000, 8, 0))]), &[]),
        p("send block", false, "the driver off 50 ns after R8", endat(&[pos22(wait).driver((2, 0, 8, 300_000))]), &[]),
        p("t_m", true, "the next read 15.51 us after the last clock edge (the line high at the master from 15.01 us, then t_R)", endat(&[pos22(T_M_T_R), pos22(wait)]), &[104462, 33554431]),
        p("t_m", false, "the next read 14.99 us after the last clock edge", endat(&[pos22(14_990 * NS), pos22(wait)]), &[]),
        p("t_m", false, "a read restarted 0.6 us after the last clock edge", endat(&[pos22(600 * NS), pos22(wait)]), &[]),
        Probe {
            unknown: 0b110,
            unknown_ps: 30 * US,
            ..p("t_m", true, "a master holding its clock low in reset for 30 us from time 0 (data and driver enable X), then reads", {
                let mut l = vec![(0b110, 30 * US)];
                l.extend(endat(&[pos22(wait), pos22(wait)]));
                l
            }, &[104462, 33554431])
        },
        p("t_R", false, "the line high at the master (no cable) 495 ns before the next read", endat(&[pos22(T_M_T_R - 5 * NS), pos22(wait)]), &[]),
        p("t_R", false, "a t_R of 0: the next read as the line rises at the master (no cable)", endat(&[pos22(T_M_T_R - 500 * NS), pos22(wait)]), &[]),
        p("t_R", true, "the line high at the master (no cable) exactly 500 ns before the next read", endat(&[pos22(T_M_T_R), pos22(wait)]), &[104462, 33554431]),
        Probe {
            toml: CABLE,
            ..p("t_R", true, "behind 30 m of cable (a round trip of 300 ns): the line high at the master 200 ns before the next read, 500 ns at the encoder", endat(&[pos22(T_M_T_R), pos22(wait)]), &[])
        },
        Probe {
            toml: CABLE,
            ..p("t_R", false, "a t_R of 0 at the master behind 30 m of cable: 300 ns at the encoder", endat(&[pos22(T_M_T_R - 200 * NS), pos22(wait)]), &[])
        },
        p("t_m after an error", true, "after a mode word that is no command (no start bit), the next read 30 us after the last clock edge", endat(&[Xfer::new(0, 2 * US, 250 * NS, 250 * NS, 30 * US), pos22(wait)]), &[]),
        p("t_m after an error", false, "after a mode word that is no command, the next read 29.99 us after the last clock edge", endat(&[Xfer::new(0, 2 * US, 250 * NS, 250 * NS, 29_990 * NS), pos22(wait)]), &[]),
        p("t_b", true, "after a type 2.1 read (000111), the next 1.00001 ms after the last clock edge", endat(&[Xfer::new(0b000111, 2 * US, 250 * NS, 250 * NS, 1_000_010 * NS), pos22(wait)]), &[104462, 33554431]),
        p("t_b", false, "after a type 2.1 read, the next exactly 1 ms after the last clock edge", endat(&[Xfer::new(0b000111, 2 * US, 250 * NS, 250 * NS, 1_000 * US), pos22(wait)]), &[]),
        comp("measurement clock", true, "three frames at 200 kHz with the clock high 2.75 us, low 2.25 us, then 8 MHz", {
            let mut v = measurement(3, 2_750 * NS, 2_250 * NS);
            v.push(pos22_8mhz(wait));
            v
        }, &[]),
        comp("measurement clock", true, "three more frames at 100 kHz, then 8 MHz", {
            let mut v = measurement(3, 5 * US, 5 * US);
            v.push(pos22_8mhz(wait));
            v
        }, &[]),
        comp("measurement clock", false, "a frame at 200 kHz with one low phase of 2.234 us", {
            let mut v = measurement(1, 2_500 * NS, 2_500 * NS);
            v[0] = v[0].clone().phase(20, false, 2_234_375);
            v.push(pos22_8mhz(wait));
            v
        }, &[]),
        Probe {
            toml: COMP,
            f_hz: COMP_HZ,
            ..p("delay measurement", false, "two measurement frames, then 8 MHz", endat(&{
                let mut v = measurement(2, 2_500 * NS, 2_500 * NS);
                v.push(pos22_8mhz(wait));
                v
            }), &[])
        },
        Probe {
            toml: COMP,
            f_hz: COMP_HZ,
            ..p("delay measurement", false, "no measurement before 8 MHz", endat(&[pos22_8mhz(wait)]), &[])
        },
        comp("delay measurement", true, "three measurement frames, then 8 MHz", vec![pos22_8mhz(wait), pos22_8mhz(wait)], &[]),
    ]
}

#[cfg(test)]
mod tests {
    use crate::open;

    /// A bound a configuration sets outside the seed's range is refused with
    /// that range, naming the file and the field, by the emulator and the
    /// monitor alike.
    #[test]
    fn an_endat_bound_outside_the_seeds_range_is_refused_with_the_range() {
        for (kind, toml, field) in [
            ("endat", "[checks]\nt_b_us = 900\n", "checks.t_b_us"),
            (
                "endat_monitor",
                "[monitor]\nt_b_us = 1000\n[checks]\nt_b_us = 5000\n",
                "",
            ),
            (
                "endat_monitor",
                "[monitor]\nmax_clock_khz = 4000\n",
                "monitor.max_clock_khz",
            ),
            (
                "endat",
                "[monitor]\nmax_clock_khz = 4000\n",
                "monitor.max_clock_khz",
            ),
            (
                "endat",
                "[master]\ndelay_comp = true\n[checks]\nmax_clock_khz = 20000\n",
                "checks.max_clock_khz",
            ),
            (
                "endat_monitor",
                "[monitor]\nt_r_us = 0.4\n",
                "monitor.t_r_us",
            ),
            (
                "endat",
                "[monitor]\non_off_percent = 12\n",
                "monitor.on_off_percent",
            ),
            (
                "endat_monitor",
                "[monitor]\nt_err_us = 20\n",
                "monitor.t_err_us",
            ),
            (
                "endat",
                "[monitor]\nmeas_frames_min = 2\n",
                "monitor.meas_frames_min",
            ),
            (
                "endat_monitor",
                "[monitor]\nmin_clock_khz = 90\n",
                "monitor.min_clock_khz",
            ),
        ] {
            let r = open(kind, toml, "r.toml", 200_000_000);
            if field.is_empty() {
                // At the bound: t_b is more than 1 ms, a setting of 1000 us is that.
                assert!(r.is_ok(), "{kind} {toml}");
                continue;
            }
            let e = r.err().unwrap().to_string();
            assert!(
                e.contains("r.toml")
                    && e.contains(field)
                    && e.contains("outside the seed's range")
                    && e.contains("seed 004"),
                "{kind}: {e}"
            );
        }
        assert!(open(
            "endat",
            "[master]\ndelay_comp = true\n[checks]\nmax_clock_khz = 16000\n",
            "r.toml",
            200_000_000
        )
        .is_ok());
    }
}
