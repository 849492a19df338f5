use model::time::*;

#[test]
fn fifty_megahertz_has_a_twenty_nanosecond_period() {
    let tb = Timebase::from_mhz(50.0).unwrap();
    assert_eq!(tb.period_ps(), 20_000);
    assert_eq!(tb.cycles_at_least_ns(4000.0), 200);
    assert_eq!(tb.cycles_at_least_ns(4001.0), 201);
    assert_eq!(tb.cycles_nearest_ns(29.0), 1);
}

#[test]
fn a_zero_negative_or_non_finite_clock_is_refused_as_such_not_as_a_fraction() {
    for mhz in [0.0, -5.0, 1e-9, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let err = Timebase::from_mhz(mhz).unwrap_err().to_string();
        assert!(
            err.contains("must be above 0") && !err.contains("whole number"),
            "{mhz}: {err}"
        );
    }
}

/// The fabric clocks boards have, whose periods are no
/// whole number of picoseconds, are accepted; each cycle's time is the
/// exact one rounded, never more than 0.5 ps off, with no drift.
#[test]
fn any_fabric_clock_is_accepted_with_cycle_times_within_half_a_picosecond() {
    for mhz in [48.0, 60.0, 120.0, 150.0, 3.0, 33.333333, 50.0, 100.0] {
        let tb = Timebase::from_mhz(mhz).unwrap_or_else(|e| panic!("{mhz} MHz refused: {e}"));
        let f = tb.f_sys_hz() as f64;
        for n in [0u64, 1, 2, 3, 7, 1_000, 123_456_789, 4_294_967_295, 1 << 40] {
            let exact = n as f64 * 1e12 / f;
            let err = (tb.ps_at(n) as f64 - exact).abs();
            // f64 holds these products to well under 0.01 ps.
            assert!(
                err <= 0.5 + exact * 1e-15,
                "{mhz} MHz cycle {n}: {} ps vs {exact}",
                tb.ps_at(n)
            );
        }
        assert_eq!(
            tb.period_is_whole_ps(),
            (1e6 / mhz).fract() == 0.0 && mhz == mhz.round(),
            "{mhz}"
        );
    }
    let tb = Timebase::from_mhz(48.0).unwrap();
    assert_eq!(tb.period_ps(), 20_833);
    assert_eq!(
        (tb.ps_at(1), tb.ps_at(2), tb.ps_at(3)),
        (20_833, 41_667, 62_500)
    );
    // Durations become cycles from the exact period: 4 µs at 48 MHz is 192 cycles.
    assert_eq!(tb.cycles_at_least_ns(4000.0), 192);
    let tb = Timebase::from_mhz(150.0).unwrap();
    assert_eq!((tb.period_ps(), tb.ps_at(3)), (6_667, 20_000));
    assert_eq!(tb.cycles_at_least_ns(20.0), 3);
    // Whole-picosecond clocks keep exact times.
    let tb = Timebase::from_mhz(80.0).unwrap();
    assert_eq!(tb.ps_at(1_000_001), 12_500_012_500);
}

#[test]
fn bit_clock_dividers_must_be_exact_and_at_least_the_minimum() {
    let tb = Timebase::from_mhz(50.0).unwrap();
    assert_eq!(
        tb.divider(250e3, "master.clock_khz", 8).unwrap(),
        BitClock {
            period: 200,
            high: 100,
            low: 100
        }
    );
    let err = tb.divider(300e3, "master.clock_khz", 8).unwrap_err();
    assert_eq!(err.field(), "master.clock_khz");
    assert!(err.to_string().contains("use "), "{}", err);
}

/// A line clock that needs an odd divider (4 MHz from
/// 100 MHz is f_sys / 25) is accepted, the high phase one cycle longer;
/// a divider below the core's minimum is still refused, naming the
/// field and the fastest clock that would do.
#[test]
fn odd_dividers_are_accepted_with_the_extra_cycle_high_and_small_ones_refused() {
    let tb = Timebase::from_mhz(100.0).unwrap();
    assert_eq!(
        tb.divider(4e6, "master.clock_khz", 8).unwrap(),
        BitClock {
            period: 25,
            high: 13,
            low: 12
        }
    );
    let tb = Timebase::from_mhz(90.0).unwrap();
    assert_eq!(
        tb.divider(10e6, "master.clock_khz", 8).unwrap(),
        BitClock {
            period: 9,
            high: 5,
            low: 4
        }
    );
    for (mhz, khz) in [(100.0, 50_000.0), (100.0, 100_000.0), (50.0, 12_500.0)] {
        let tb = Timebase::from_mhz(mhz).unwrap();
        let err = tb.divider(khz * 1e3, "master.clock_khz", 8).unwrap_err();
        assert_eq!(err.field(), "master.clock_khz");
        let text = err.to_string();
        assert!(
            text.contains("at least 8") && text.contains("f_sys / 8"),
            "{text}"
        );
    }
}
