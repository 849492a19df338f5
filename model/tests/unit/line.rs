use model::line::*;
use model::Timebase;

fn run(line: &mut DelayLine, inputs: &[bool]) -> Vec<bool> {
    inputs.iter().map(|&i| line.step(i)).collect()
}

#[test]
fn a_line_without_delay_passes_the_level_in_the_same_cycle() {
    let mut line = DelayLine::new(0, true);
    assert_eq!(
        run(&mut line, &[true, false, false, true]),
        vec![true, false, false, true]
    );
}

#[test]
fn a_line_of_three_cycles_shifts_every_edge_by_three() {
    let mut line = DelayLine::new(3, true);
    let input = [true, false, false, true, false, true, true, true, true];
    let out = run(&mut line, &input);
    assert_eq!(
        out,
        vec![true, true, true, true, false, false, true, false, true]
    );
}

#[test]
fn a_hundred_metre_cable_at_fifty_megahertz_delays_twenty_five_cycles() {
    let tb = Timebase::from_mhz(50.0).unwrap();
    let cable = CableConfig {
        length_m: 100.0,
        ..CableConfig::default()
    };
    assert_eq!(cable.delay_cycles(&tb), 25);
}

#[test]
fn jittered_edges_stay_in_order_and_within_the_bound() {
    let mut line = DelayLine::with_jitter(10, 4, 7, false);
    let mut input_edges = vec![];
    let mut output_edges = vec![];
    let (mut last_in, mut last_out) = (false, false);
    for t in 0..2000u64 {
        let level = t < 1900 && (t / 13) % 2 == 1; // quiet at the end so every edge comes out
        if level != last_in {
            input_edges.push(t);
            last_in = level;
        }
        let out = line.step(level);
        if out != last_out {
            output_edges.push(t);
            last_out = out;
        }
    }
    assert_eq!(input_edges.len(), output_edges.len());
    let mut moved = 0;
    for (i, o) in input_edges.iter().zip(&output_edges) {
        assert!(*o >= i + 6 && *o <= i + 14, "edge at {i} came out at {o}");
        moved += (*o != i + 10) as u32;
    }
    assert!(moved > 0, "jitter moved no edge");
}

#[test]
fn half_duplex_receivers_see_the_far_driver_late_and_flag_two_drivers() {
    let mut pair = HalfDuplexLine::new(2, true);
    let master = Drive {
        enable: true,
        level: false,
    };
    let device_off = Drive::default();
    let (a, b) = pair.step(master, device_off);
    assert_eq!(
        (a.level, b.level),
        (false, true),
        "device sees the master two cycles late"
    );
    pair.step(master, device_off);
    let (_, b) = pair.step(master, device_off);
    assert!(!b.level);
    let device_on = Drive {
        enable: true,
        level: true,
    };
    let (a, b) = pair.step(master, device_on);
    assert!(b.contention && !a.contention);
    assert_eq!(pair.contention_cycles(), 1);
    let off = Drive::default();
    let (a, b) = pair.step(off, device_on);
    assert!(
        !a.contention && b.contention,
        "the master's last driven bits are still on their way to the device"
    );
    assert_eq!(pair.contention_cycles(), 2);
    let (a, _) = pair.step(off, device_on);
    assert!(
        a.level && !a.contention,
        "the device's answer reaches the master two cycles after it drove"
    );
}
