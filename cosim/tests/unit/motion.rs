use cosim::motion::*;

#[test]
fn constant_speed_steps_and_reversal_give_the_expected_positions() {
    let m = Motion::from_toml(
        "[motion]\nkind = \"constant\"\nstart = 100\ncounts_per_ms = 1000\n",
        "m",
    )
    .unwrap();
    assert_eq!(m.position_at(0.0, 16), 100);
    assert_eq!(m.position_at(1e6, 16), 1100); // 1 ms later
    assert_eq!(m.position_at(66e6, 16), (100 + 66_000) % 65_536); // wraps at 16 bits
    let back = Motion::Constant {
        start: 5,
        counts_per_ms: -10.0,
    };
    assert_eq!(back.position_at(1e6, 8), 251); // 5 - 10 wraps to 251
    let s = Motion::from_toml(
        "[motion]\nkind = \"steps\"\nstart = 0\nstep = 7\nevery_us = 10\n",
        "m",
    )
    .unwrap();
    assert_eq!(s.position_at(9_999.0, 12), 0);
    assert_eq!(s.position_at(10_000.0, 12), 7);
    assert_eq!(s.position_at(35_000.0, 12), 21);
    let r = Motion::from_toml(
        "[motion]\nkind = \"reversal\"\nstart = 1000\ncounts_per_ms = 100\nhalf_period_ms = 2\n",
        "m",
    )
    .unwrap();
    assert_eq!(r.position_at(1e6, 16), 1100);
    assert_eq!(r.position_at(2e6, 16), 1200); // turning point
    assert_eq!(r.position_at(3e6, 16), 1100); // on the way back
    assert_eq!(r.position_at(4e6, 16), 1000);
    let run = Running {
        motion: m,
        since: 1000,
    };
    assert_eq!(run.position(1000 + 64_000, 15_625, 16), 1100); // 64 MHz: 64 000 cycles = 1 ms
}

#[test]
fn a_bad_profile_names_the_field_and_the_fix() {
    let e = Motion::from_toml(
        "[motion]\nkind = \"steps\"\nstart = 0\nstep = 1\nevery_us = 0\n",
        "tb",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("motion.every_us") && e.contains("more than 0"),
        "{e}"
    );
    let e = Motion::from_toml("[motion]\nkind = \"warp\"\n", "tb")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("tb:") && e.contains("warp"), "{e}");
}
