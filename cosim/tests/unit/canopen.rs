use cosim::canopen::*;
use cosim::{Emulator, Pins};
use model::can::emulator::NodeSettings;
use model::can::frame::Frame;
use model::canopen::NodeTiming;
use model::Timebase;

const ONE: &str = "[canopen]\nbit_rate_kbps = 1000\ntq_per_bit = 8\nsample_point = 0.75\n\
    [[canopen.encoders]]\nname = \"enc\"\nposition_m = 10\n[canopen.encoders.encoder]\nnode_switch = 5\nbit_rate_switch = 7\nraw_position = 321\n";

/// A recessive master: the encoder's boot-up (0x85, no data) reaches the
/// master's RXD; nobody acknowledges it, so it stays the only frame sent.
#[test]
fn the_boot_up_reaches_the_master() {
    let mut emu = CanopenEmulator::from_toml(ONE, "one.toml", 8_000_000).unwrap();
    let mut dominant = 0;
    for _ in 0..2000 {
        dominant += (emu.step(Pins(2)).0 & 1 == 0) as u32;
    }
    assert!(dominant > 5);
    assert_eq!(emu.count(), 0);
    assert_eq!(
        emu.last_value(32),
        Some(127),
        "pre-operational after its boot-up"
    );
}

#[test]
fn positions_and_bad_configurations() {
    let mut emu = CanopenEmulator::from_toml(ONE, "one.toml", 8_000_000).unwrap();
    emu.set_position(0, 1000).unwrap();
    assert!(emu.set_position(0, 1 << 25).is_err());
    assert!(emu.set_position(3, 1).is_err());
    assert!(emu.set_status(0, "busy", true).is_err());
    let err = CanopenEmulator::from_toml("[canopen]\n", "c.toml", 8_000_000)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.starts_with("c.toml: ") && err.contains("encoders"),
        "{err}"
    );
}

/// A scenario file's emulator settings are `[canopen.emulator]`; a
/// top-level `[emulator]` beside `[canopen]` is refused, not ignored, and
/// the one under `[canopen]` is read.
#[test]
fn a_top_level_emulator_table_beside_the_protocol_is_refused_with_its_fix() {
    let slow = ONE
        .replace("bit_rate_kbps = 1000\n", "bit_rate_kbps = 250\n")
        .replace("bit_rate_switch = 7", "bit_rate_switch = 4");
    let top = format!("[emulator]\nmax_line_clock_khz = 250\n{slow}");
    let err = CanopenEmulator::from_toml(&top, "top.toml", 2_500_000)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.starts_with("top.toml: ")
            && err.contains("emulator")
            && err.contains("[canopen.emulator]"),
        "{err}"
    );
    let under = format!("{slow}[canopen.emulator]\nmax_line_clock_khz = 250\n");
    assert!(CanopenEmulator::from_toml(&under, "under.toml", 2_500_000).is_ok());
    let err = CanopenEmulator::from_toml(&slow, "none.toml", 2_500_000)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("too slow"), "{err}");
}

const SAR: &str = "[canopen]\nbit_rate_kbps = 250\n\
    [[canopen.sar]]\nname = \"sar\"\nposition_m = 10\n[canopen.sar.encoder]\nnode = 0x20\nbits = 14\nraw_position = 9799\n";

/// A host node (our model's controller) at the master's pins, on the emulator clock.
struct Host {
    emu: CanopenEmulator,
    host: model::can::Emulator,
    rx: bool,
}

impl Host {
    fn new(text: &str) -> Host {
        let f = 8_000_000;
        let emu = CanopenEmulator::from_toml(text, "t.toml", f).unwrap();
        let tb = Timebase::new(f).unwrap();
        let cc = NodeTiming::default().controller(&tb, 250).unwrap();
        let s = NodeSettings {
            name: "host".into(),
            position_m: 0.0,
            loop_delay_ns: 150.0,
            ppm: 0.0,
            ack: true,
            frames: Vec::new(),
        };
        Host {
            emu,
            host: model::can::Emulator::new(&s, cc, &tb).unwrap(),
            rx: true,
        }
    }

    fn run(&mut self, cycles: u64) {
        for _ in 0..cycles {
            let tx = self.host.step(self.rx);
            self.rx = self.emu.step(Pins((tx as u32) << 1)).0 & 1 != 0;
        }
    }

    /// Sends `data` on `id` and runs 2 ms (8 MHz: 16 000 cycles): the frame and its answer.
    fn send(&mut self, id: u32, data: [u8; 8]) -> Vec<Frame> {
        let before = self.host.received().len();
        assert!(self.host.load(&Frame::data(id, &data)));
        self.run(16_000);
        self.host.received()[before..].to_vec()
    }
}

/// Seed 001 §3.4 (5): "80 20" to the factory node 0x20 is answered on
/// 0x120 with `47 26` = 9799 (14 bits, 215.3100°), through the emulator.
#[test]
fn a_sar58k24_alone_answers_the_seeds_click() {
    let mut h = Host::new(SAR);
    h.run(1000);
    let got = h.send(0x220, [0x80, 0x20, 0, 0, 0, 0, 0, 0]);
    assert_eq!(
        got,
        vec![Frame::data(0x120, &[0x47, 0x26, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!((h.emu.count(), h.emu.last_value(0)), (1, Some(9799)));
    assert_eq!(h.emu.last_value(4 * 16), Some(0x4726 << 48));
    assert_eq!(h.emu.last_value(5 * 16), Some(0x120));
    assert_eq!(
        (h.emu.last_value(2 * 16), h.emu.last_value(3 * 16)),
        (Some(0x20), Some(250))
    );
    let t = h.emu.transcript();
    let sent: Vec<&serde_json::Value> = t["frames"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["what"] == "sent")
        .collect();
    assert_eq!(sent.len(), 1);
    assert_eq!(sent[0]["position"], 9799);
    assert_eq!(sent[0]["meaning"], "SAR58K24 node 0x20: position 9799");
    assert!(h.emu.violations().is_empty(), "{:?}", h.emu.violations());
}

/// The zero's acknowledgement `20 00 ..` has the bytes of position 32:
/// the emulator counts the answer to a click as a position and the
/// acknowledgement not; after the zero the click answers 0, after a
/// direction toggle the negated count.
#[test]
fn acknowledgements_are_not_positions_and_zero_and_direction_apply() {
    let mut h = Host::new(SAR);
    h.run(1000);
    h.emu.set_position(0, 32).unwrap();
    assert_eq!(
        h.send(0x220, [0x80, 0x20, 0, 0, 0, 0, 0, 0]),
        vec![Frame::data(0x120, &[0x20, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!((h.emu.count(), h.emu.last_value(0)), (1, Some(32)));
    assert_eq!(
        h.send(0x220, [0x20, 0x20, 0, 0, 0, 0, 0, 0]),
        vec![Frame::data(0x120, &[0x20, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(h.emu.count(), 1, "the acknowledgement is no position");
    h.emu.set_position(0, 42).unwrap();
    h.send(0x220, [0x80, 0x20, 0, 0, 0, 0, 0, 0]);
    assert_eq!(h.emu.last_value(0), Some(10));
    h.send(0x220, [0x22, 0x20, 0, 0, 0, 0, 0, 0]);
    assert!(h.emu.last_status(0, "reversed").unwrap());
    h.send(0x220, [0x80, 0x20, 0, 0, 0, 0, 0, 0]);
    assert_eq!(
        (h.emu.count(), h.emu.last_value(0)),
        (3, Some((1 << 14) - 10))
    );
    assert!(h.emu.set_position(0, 1 << 14).is_err());
}

/// Timed send `31 20 TT`: a position every 1/TT s, and the same bytes stop it.
#[test]
fn timed_send_and_its_stop() {
    let mut h = Host::new(SAR);
    h.run(1000);
    h.emu
        .set_motion(
            0,
            "[motion]\nkind = \"constant\"\nstart = 0\ncounts_per_ms = 100\n",
        )
        .unwrap();
    // 250 times a second: every 4 ms.
    assert_eq!(
        h.send(0x220, [0x31, 0x20, 250, 0, 0, 0, 0, 0]),
        vec![Frame::data(0x120, &[0x31, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert!(h.emu.last_status(0, "sending").unwrap());
    h.run(8 * 8000);
    let n = h.emu.count();
    assert!((2..=3).contains(&n), "{n} positions in 10 ms");
    let p = h.emu.last_value(0).unwrap();
    assert!(
        p > 400 && p < 1200,
        "a moving shaft at 100 counts per ms, 4 to 12 ms after the start: {p}"
    );
    h.send(0x220, [0x31, 0x20, 250, 0, 0, 0, 0, 0]);
    assert!(!h.emu.last_status(0, "sending").unwrap());
    let n = h.emu.count();
    h.run(8 * 8000);
    assert_eq!(h.emu.count(), n, "stopped");
}

/// 0x7E5: enter configuration, new node, bit rate; effective after a power cycle.
#[test]
fn configuration_channel_and_a_power_cycle() {
    let mut h = Host::new(SAR);
    h.run(1000);
    assert!(h.send(0x7E5, [0x04, 0x01, 0, 0, 0, 0, 0, 0]).is_empty());
    assert!(h.emu.last_status(0, "config_mode").unwrap());
    assert_eq!(
        h.send(0x7E5, [0x11, 0x35, 0, 0, 0, 0, 0, 0]),
        vec![Frame::data(0x7E5, &[0x11, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(
        h.send(0x7E5, [0x13, 0x00, 0x02, 0, 0, 0, 0, 0]),
        vec![Frame::data(0x7E5, &[0x13, 0, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(
        (h.emu.last_value(6 * 16), h.emu.last_value(7 * 16)),
        (Some(0x35), Some(500))
    );
    assert_eq!(h.send(0x7E5, [0x13, 0x00, 0x03, 0, 0, 0, 0, 0]).len(), 1);
    h.emu.set_status(0, "power", false).unwrap();
    h.run(1000);
    assert!(!h.emu.last_status(0, "powered").unwrap());
    h.emu.set_status(0, "power", true).unwrap();
    h.run(1000);
    assert_eq!(
        (h.emu.last_value(2 * 16), h.emu.last_value(3 * 16)),
        (Some(0x35), Some(250))
    );
    assert!(!h.emu.last_status(0, "config_mode").unwrap());
    assert!(
        h.send(0x220, [0x80, 0x20, 0, 0, 0, 0, 0, 0]).is_empty(),
        "the old node is gone"
    );
    assert_eq!(h.send(0x235, [0x80, 0x35, 0, 0, 0, 0, 0, 0])[0].id, 0x135);
    assert_eq!(
        h.emu.last_value(16),
        Some(4),
        "frames sent over the power cycle: 11, 13, 13 and a position"
    );
    assert!(h
        .emu
        .set_status(0, "busy", true)
        .unwrap_err()
        .to_string()
        .contains("power"));
}

/// A DS 406 encoder and a SAR58K24 share the bus: the SAR58K24 is device 1.
#[test]
fn a_ds406_encoder_and_a_sar58k24_on_one_bus() {
    let text = format!("{SAR}[[canopen.encoders]]\nname = \"enc\"\nposition_m = 20\n[canopen.encoders.encoder]\nnode_switch = 5\nbit_rate_switch = 4\n");
    let mut h = Host::new(&text);
    h.run(8000);
    assert_eq!(
        h.host.received(),
        &[Frame::data(0x85, &[])],
        "the encoder's boot-up"
    );
    assert_eq!(
        h.send(0x220, [0x80, 0x20, 0, 0, 0, 0, 0, 0]),
        vec![Frame::data(0x120, &[0x47, 0x26, 0, 0, 0, 0, 0, 0])]
    );
    assert_eq!(
        (h.emu.last_value(1), h.emu.last_value(0)),
        (Some(9799), None)
    );
    assert_eq!(
        h.emu.last_value(32),
        Some(127),
        "device 0: the DS 406 encoder, pre-operational"
    );
    assert!(h.emu.last_status(1, "operational").is_err());
    assert!(h.emu.set_status(0, "power", false).is_err());
}

/// Bad input names the file, the field and the fix.
#[test]
fn bad_sar58k24_configurations_are_refused_by_field() {
    let err = |text: &str| {
        CanopenEmulator::from_toml(text, "s.toml", 8_000_000)
            .err()
            .unwrap()
            .to_string()
    };
    let e = err(&SAR.replace("node = 0x20", "node = 0"));
    assert!(
        e.starts_with("s.toml: ") && e.contains("sar[0].encoder.node") && e.contains("give a node"),
        "{e}"
    );
    let e = err(&SAR
        .replace("bits = 14", "bits = 14\nanswer_base = 0x180\n")
        .replace("node = 0x20", "node = 0x90"));
    assert!(e.contains("sar[0].encoder.node"), "{e}");
    let e = err(&SAR.replace("bit_rate_kbps = 250\n[[", "bit_rate_kbps = 500\n[["));
    assert!(
        e.contains("sar[0].encoder.bit_rate_kbps") && e.contains("250"),
        "{e}"
    );
    let e = err(&format!("{SAR}[[canopen.encoders]]\n[canopen.encoders.encoder]\nnode_switch = 32\nbit_rate_switch = 4\n"));
    assert!(
        e.contains("sar[0].encoder.node") && e.contains("0x220") && e.contains("encoders[0]"),
        "{e}"
    );
    let e = err(&format!("{SAR}[canopen.tool]\nname = \"tool\"\n"));
    assert!(
        e.contains("tool") && e.contains("remove [canopen.tool]"),
        "{e}"
    );
    let e = err(&SAR
        .replace("[[canopen.sar]]", "[[canopen.sar58k24]]")
        .replace("[canopen.sar.encoder]", "[canopen.sar58k24.encoder]"));
    assert!(e.starts_with("s.toml: ") && e.contains("sar58k24"), "{e}");
    let e = err(&SAR.replace("bits = 14", "bits = 14\nspeed = 3"));
    assert!(e.contains("speed"), "{e}");
}
