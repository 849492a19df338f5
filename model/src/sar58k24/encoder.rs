//! The SAR58K24 encoder emulator in its six asynchronous modes (seed 001,
//! 3.1.1 to 3.1.6; 3.2.x and 3.3.x are the same protocol on RS-232/TTL and
//! RS-422 wiring). Modbus RTU, the seventh, is `model::modbus::Device`.
//!
//! The emulator is not an RTL twin: it is the device the host is tested
//! against, stepped once per system clock, sending its characters through a
//! [`Transmitter`] that places every edge at its exact time for the
//! encoder's own (possibly wrong) baud rate, and listening for bus commands
//! with the model receiver.

use serde::{Deserialize, Serialize};

use super::frames::{self, AnswerTag, Command};
use crate::gray::to_gray;
use crate::line::Drive;
use crate::uart::{self, FaultKind, FrameFault, Parity, Receiver, ReceiverConfig, Transmitter};
use crate::{ConfigError, Result};

/// The six asynchronous modes of 2.4 ("timed send, timed + clear, pulse
/// handshake, handshake + clear, bus command, bus + clear").
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Mode {
    /// 3.1.1: a frame every refresh period.
    #[default]
    TimedSend,
    /// 3.1.2: timed send, and a low pulse on CLR zeroes the position.
    TimedClear,
    /// 3.1.3: a falling edge on the trigger input (CLK) starts an
    /// acquisition of T3, then one frame.
    Handshake,
    /// 3.1.4: handshake, and CLR zeroes.
    HandshakeClear,
    /// 3.1.5: `BC AA Bx` on the shared line, answered by encoder x only.
    Bus,
    /// 3.1.6: bus commands, and `BC AA Cx` zeroes encoder x.
    BusClear,
}

impl Mode {
    /// The Verilog `MODE` parameter (0..5, in the order of 2.4).
    pub fn code(self) -> u64 {
        self as u64
    }

    /// Timed send, with or without clear.
    pub fn is_timed(self) -> bool {
        matches!(self, Mode::TimedSend | Mode::TimedClear)
    }

    /// Pulse handshake, with or without clear.
    pub fn is_handshake(self) -> bool {
        matches!(self, Mode::Handshake | Mode::HandshakeClear)
    }

    /// Bus commands, with or without zeroing.
    pub fn is_bus(self) -> bool {
        matches!(self, Mode::Bus | Mode::BusClear)
    }

    /// The CLR input is wired (3.1.2, 3.1.4; "NC" in the other tables).
    pub fn has_clr(self) -> bool {
        matches!(self, Mode::TimedClear | Mode::HandshakeClear)
    }
}

/// The output code (2.4: "Binary code, Gray code").
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum OutputCode {
    /// Plain binary.
    #[default]
    Binary,
    /// Reflected binary.
    Gray,
}

/// The refresh rates of 2.4, in Hz.
pub const REFRESH_RATES_HZ: [f64; 8] = [2000.0, 1000.0, 500.0, 400.0, 200.0, 100.0, 50.0, 20.0];

/// The baud rates of 2.4.
pub const BAUD_RATES: [f64; 7] = [
    115_200.0, 57_600.0, 38_400.0, 19_200.0, 9_600.0, 4_800.0, 2_400.0,
];

/// The emulator's settings in a scenario's units (`[sar.encoder]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderSettings {
    /// Bus address x of `BC AA Bx` (0..15).
    pub address: u8,
    /// Resolution in bits (10..32).
    pub bits: u32,
    /// Binary or Gray.
    pub code: OutputCode,
    /// The second byte of a bus answer.
    pub answer_tag: AnswerTag,
    /// Raw positions the encoder reads, one per acquisition; the last holds.
    pub positions: Vec<u64>,
    /// Timed modes: frames per second (2.4: 20 Hz to 2 kHz).
    pub refresh_hz: f64,
    /// Handshake: T3, acquisition time from the trigger's falling edge to
    /// the start bit of the frame ("vary according to ... customers").
    pub acquisition_us: f64,
    /// Handshake: T2, the shortest low trigger pulse taken ("T2 ≥ 10 µs").
    pub trigger_min_low_us: f64,
    /// CLR: the shortest low pulse that zeroes. The manual gives the level
    /// (`V_L < 0.5 V`) and no width; 10 µs, as T2, is this project's choice.
    pub clr_min_low_us: f64,
    /// Bus: from the command's stop bit to the answer's start bit (not in
    /// the manual; 100 µs, about one character at 115200 baud).
    pub answer_delay_us: f64,
    /// Bus: idle bit times between two characters of a command after which
    /// the command is dropped (the Modbus t1.5 rule, 15 bits).
    pub command_gap_bits: f64,
    /// Bus + clear: the zeroing command is answered with a frame of the new
    /// position (the manual gives no answer; the Modbus note's "send a
    /// return data match to indicate that the setting is successful").
    pub answer_zeroing: bool,
    /// The encoder's baud error in percent (positive = fast).
    pub baud_error_percent: f64,
    /// Frame faults.
    pub faults: Vec<FrameFault>,
}

impl Default for EncoderSettings {
    fn default() -> Self {
        EncoderSettings {
            address: 1,
            bits: 14,
            code: OutputCode::Binary,
            answer_tag: AnswerTag::Address,
            positions: vec![383],
            refresh_hz: 100.0,
            acquisition_us: 20.0,
            trigger_min_low_us: 10.0,
            clr_min_low_us: 10.0,
            answer_delay_us: 100.0,
            command_gap_bits: 15.0,
            answer_zeroing: true,
            baud_error_percent: 0.0,
            faults: Vec::new(),
        }
    }
}

/// The emulator's configuration in cycles.
#[derive(Debug, Clone, PartialEq)]
pub struct EncoderConfig {
    /// The mode.
    pub mode: Mode,
    /// The character format.
    pub parity: Parity,
    /// System clock period, ps.
    pub period_ps: u64,
    /// Nominal baud.
    pub baud: f64,
    /// Receiver clocks per bit (bus commands).
    pub clocks_per_bit: u64,
    /// Cycles between timed frames.
    pub refresh_clocks: u64,
    /// T3 in cycles.
    pub acquisition_clocks: u64,
    /// T2 in cycles.
    pub trigger_min_low: u64,
    /// CLR width in cycles.
    pub clr_min_low: u64,
    /// Bus answer delay in cycles.
    pub answer_delay: u64,
    /// Command gap in cycles.
    pub command_gap: u64,
    /// The rest, as given.
    pub settings: EncoderSettings,
}

impl EncoderSettings {
    /// Checks what does not depend on the clock; `mode`, `baud` and
    /// `parity` are the set-up's.
    pub fn validate(&self, mode: Mode, baud: f64, parity: Parity) -> Result<()> {
        if !(10..=32).contains(&self.bits) {
            return Err(ConfigError::invalid(
                "encoder.bits",
                format!("{}", self.bits),
                "give a resolution of 10 to 32 bits",
            ));
        }
        if self.address > 15 {
            return Err(ConfigError::invalid(
                "encoder.address",
                format!("{}", self.address),
                "give 0 to 15: the x of BC AA Bx is one hex digit",
            ));
        }
        if self.positions.is_empty() || self.positions.len() > 1_000_000 {
            return Err(ConfigError::invalid(
                "encoder.positions",
                "empty or longer than 10^6",
                "list 1 to 10^6 raw positions",
            ));
        }
        if let Some(p) = self.positions.iter().find(|&&p| p >> self.bits != 0) {
            return Err(ConfigError::invalid(
                "encoder.positions",
                format!("{p} does not fit {} bits", self.bits),
                "give positions below 2^bits",
            ));
        }
        for (f, v) in [
            ("encoder.acquisition_us", self.acquisition_us),
            ("encoder.trigger_min_low_us", self.trigger_min_low_us),
            ("encoder.clr_min_low_us", self.clr_min_low_us),
            ("encoder.answer_delay_us", self.answer_delay_us),
        ] {
            if !(0.0..1e7).contains(&v) {
                return Err(ConfigError::invalid(
                    f,
                    format!("{v}"),
                    "give a time from 0 to 10^7 µs",
                ));
            }
        }
        if self.acquisition_us < self.trigger_min_low_us {
            return Err(ConfigError::invalid(
                "encoder.acquisition_us",
                format!(
                    "T3 = {} µs is shorter than T2 = {} µs",
                    self.acquisition_us, self.trigger_min_low_us
                ),
                "the encoder can only send after it has seen the trigger low for T2: give T3 ≥ T2",
            ));
        }
        if !(1.0..=1000.0).contains(&self.command_gap_bits) {
            return Err(ConfigError::invalid(
                "encoder.command_gap_bits",
                format!("{}", self.command_gap_bits),
                "give 1 to 1000 bit times",
            ));
        }
        if !(-10.0..=10.0).contains(&self.baud_error_percent) {
            return Err(ConfigError::invalid(
                "encoder.baud_error_percent",
                format!("{}", self.baud_error_percent),
                "give −10 to +10 %",
            ));
        }
        if mode.is_timed() {
            if !(1.0..=2000.0).contains(&self.refresh_hz) {
                return Err(ConfigError::invalid(
                    "encoder.refresh_hz",
                    format!("{}", self.refresh_hz),
                    "give 1 to 2000 Hz (the manual lists 20 Hz to 2 kHz)",
                ));
            }
            let frame_s = frame_seconds(self.bits, baud, parity);
            let period_s = 1.0 / self.refresh_hz;
            if frame_s > period_s {
                return Err(ConfigError::invalid(
                    "encoder.refresh_hz",
                    format!(
                        "a {}-byte frame takes {:.1} µs at {} baud, longer than the {:.1} µs refresh period of {} Hz",
                        frames::frame_len(self.bits),
                        frame_s * 1e6,
                        baud,
                        period_s * 1e6,
                        self.refresh_hz
                    ),
                    format!("use at most {:.0} Hz at this baud rate, or a faster baud rate", max_refresh_hz(self.bits, baud, parity)),
                ));
            }
        }
        let len = frames::frame_len(self.bits);
        for (i, f) in self.faults.iter().enumerate() {
            if f.kind == FaultKind::Insert {
                return Err(ConfigError::invalid(
                    format!("encoder.faults[{i}].kind"),
                    "insert",
                    "a SAR58K24 frame has one length: use flip, truncate, gap, noise, silent, retag or replace",
                ));
            }
            f.validate(len, parity)
                .map_err(|e| ConfigError::invalid(format!("encoder.faults[{i}]"), e.0, e.1))?;
        }
        Ok(())
    }
}

/// Seconds one position frame of `bits` takes at `baud`, characters back to back.
pub fn frame_seconds(bits: u32, baud: f64, parity: Parity) -> f64 {
    (frames::frame_len(bits) * parity.frame_bits()) as f64 / baud
}

/// The highest refresh rate whose period holds one frame.
pub fn max_refresh_hz(bits: u32, baud: f64, parity: Parity) -> f64 {
    1.0 / frame_seconds(bits, baud, parity)
}

/// A frame the emulator sent.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SentFrame {
    /// Cycle the frame was queued (its first start bit follows at once, or
    /// after the noise bytes).
    pub cycle: u64,
    /// The bytes as meant (before a flip or truncation).
    pub bytes: Vec<u8>,
    /// The position in it (after zeroing, before Gray coding).
    pub position: u64,
}

/// What the emulator sees at one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EncoderIn {
    /// The line at the encoder (bus commands).
    pub rx: bool,
    /// The trigger input (CLK), idle high.
    pub trigger: bool,
    /// The CLR input, idle high.
    pub clr: bool,
}

/// The emulator.
#[derive(Debug, Clone)]
pub struct Encoder {
    cfg: EncoderConfig,
    tx: Transmitter,
    rx: Receiver,
    cycle: u64,
    acquisitions: usize,
    offset: u64,
    frames_sent: usize,
    next_timed: u64,
    trigger_before: bool,
    trigger_low: u64,
    pending_send: Option<(u64, u64)>,
    clr_low: u64,
    command: Vec<u8>,
    since_byte: u64,
    driving_until_ps: f64,
    sent: Vec<SentFrame>,
    zeroings: usize,
    position_now: Option<u64>,
    glitches: usize,
}

impl Encoder {
    /// An emulator in its power-on state.
    pub fn new(cfg: EncoderConfig) -> Result<Self> {
        let tx = Transmitter::new(
            cfg.period_ps,
            cfg.baud,
            cfg.settings.baud_error_percent,
            0.0,
            1,
        )
        .with_parity(cfg.parity);
        let rx = Receiver::with_parity(
            ReceiverConfig {
                clocks_per_bit: cfg.clocks_per_bit,
            },
            cfg.parity,
        )?;
        Ok(Encoder {
            next_timed: cfg.refresh_clocks,
            tx,
            rx,
            cycle: 0,
            acquisitions: 0,
            offset: 0,
            frames_sent: 0,
            trigger_before: true,
            trigger_low: 0,
            pending_send: None,
            clr_low: 0,
            command: Vec::new(),
            since_byte: 0,
            driving_until_ps: -1.0,
            sent: Vec::new(),
            zeroings: 0,
            position_now: None,
            glitches: 0,
            cfg,
        })
    }

    /// Frames sent so far.
    pub fn sent(&self) -> &[SentFrame] {
        &self.sent
    }

    /// Zeroings done (CLR pulses and zeroing commands).
    pub fn zeroings(&self) -> usize {
        self.zeroings
    }

    /// Trigger pulses shorter than T2, ignored.
    pub fn glitches(&self) -> usize {
        self.glitches
    }

    fn mask(&self) -> u64 {
        if self.cfg.settings.bits == 64 {
            u64::MAX
        } else {
            (1u64 << self.cfg.settings.bits) - 1
        }
    }

    /// The raw position the next acquisition reads: the one given to
    /// [`Encoder::set_position`], else the next entry of `positions`.
    fn raw_now(&self) -> u64 {
        if let Some(p) = self.position_now {
            return p;
        }
        let p = &self.cfg.settings.positions;
        p[self.acquisitions.min(p.len() - 1)]
    }

    /// Sets the raw position every acquisition from now on reads, in place
    /// of the `positions` list (a closed-loop bench moving the shaft): the
    /// next frame carries it, minus the zero offset. Refused when it does
    /// not fit the resolution.
    pub fn set_position(&mut self, raw: u64) -> Result<()> {
        if raw & !self.mask() != 0 {
            return Err(ConfigError::invalid(
                "position",
                format!("{raw} does not fit {} bits", self.cfg.settings.bits),
                "give a position below 2^bits",
            ));
        }
        self.position_now = Some(raw);
        Ok(())
    }

    /// Reads the position (one acquisition): raw minus the zero offset.
    fn acquire(&mut self) -> u64 {
        let v = self.raw_now().wrapping_sub(self.offset) & self.mask();
        self.acquisitions += 1;
        v
    }

    fn zero(&mut self) {
        self.offset = self.raw_now();
        self.zeroings += 1;
    }

    /// Queues one frame for `position` now, with this frame's faults.
    fn send_frame(&mut self, position: u64) {
        let s = &self.cfg.settings;
        let index = self.frames_sent;
        self.frames_sent += 1;
        let coded = match s.code {
            OutputCode::Binary => position,
            OutputCode::Gray => to_gray(position),
        };
        let faults: Vec<FrameFault> = s
            .faults
            .iter()
            .filter(|f| f.frame == index)
            .cloned()
            .collect();
        let mut tag = frames::tag_byte(s.answer_tag, self.cfg.mode.is_bus(), s.address);
        if let Some(f) = faults.iter().find(|f| f.kind == FaultKind::Retag) {
            tag = f.bytes[0];
        }
        let mut bytes = frames::encode_tagged(coded as u32, s.bits, tag);
        let n = bytes.len();
        for f in faults
            .iter()
            .filter(|f| f.kind == FaultKind::Replace && f.byte + 1 < n)
        {
            bytes[f.byte] = f.bytes[0];
            bytes[n - 1] = frames::checksum(&bytes[..n - 1]);
        }
        self.sent.push(SentFrame {
            cycle: self.cycle,
            bytes: bytes.clone(),
            position,
        });
        if faults.iter().any(|f| f.kind == FaultKind::Silent) {
            return;
        }
        let now_ps = (self.cycle * self.cfg.period_ps) as f64;
        uart::send_with_faults(&mut self.tx, &bytes, &faults, self.cfg.parity, now_ps);
        self.driving_until_ps = self.tx.idle_from_ps();
    }

    /// How many of the next steps with `input` change nothing but counters
    /// (fast-forward): no acquisition, frame, zeroing, character or edge,
    /// and the same drive. 0 while the trigger or CLR input is moving.
    pub fn quiet(&self, input: &EncoderIn) -> u64 {
        let mode = self.cfg.mode;
        let c = self.cycle;
        let mut q = self.tx.quiet();
        if mode.has_clr() {
            // A CLR edge (the count starts or resets) is stepped.
            if input.clr == (self.clr_low != 0) {
                return 0;
            }
            let m = self.cfg.clr_min_low.max(1);
            if !input.clr && self.clr_low < m {
                q = q.min(m - self.clr_low - 1);
            }
        }
        if mode.is_timed() {
            q = q.min(self.next_timed.saturating_sub(c));
        }
        if mode.is_handshake() && (self.trigger_low > 0 || input.trigger != self.trigger_before) {
            return 0;
        }
        if let Some((at, _)) = self.pending_send {
            q = q.min(at.saturating_sub(c));
        }
        if mode.is_bus() {
            // The drive enable falls at `driving_until_ps`, the receiver's
            // own-driver blanking one cycle later.
            // A quiet cycle repeats the last step's drive, so the window ends
            // where the level that step saw changes (at once when it changed
            // at this cycle).
            let period = self.cfg.period_ps as f64;
            let now_ps = (c * self.cfg.period_ps) as f64;
            let last_ps = (c.saturating_sub(1) * self.cfg.period_ps) as f64;
            for edge in [self.driving_until_ps, self.driving_until_ps + period] {
                if last_ps < edge {
                    q = q.min(uart::first_cycle_at(c, self.cfg.period_ps, edge) - c);
                }
            }
            let driving = now_ps < self.driving_until_ps + period;
            q = q.min(self.rx.quiet(&uart::In {
                i_rx: input.rx || driving,
            }));
        }
        q
    }

    /// The same as `n` steps with the last input, for `n` up to [`Encoder::quiet`].
    pub fn skip(&mut self, n: u64) {
        if self.cfg.mode.has_clr() && self.clr_low != 0 {
            // The CLR input stays low (a high one keeps the count at 0).
            self.clr_low += n;
        }
        if self.cfg.mode.is_bus() {
            self.rx.skip(n);
            self.since_byte += n;
        }
        self.tx.skip(n);
        self.cycle += n;
    }

    /// One system clock; returns what the encoder drives on its TXD pair.
    pub fn step(&mut self, input: &EncoderIn) -> Drive {
        let mode = self.cfg.mode;
        // CLR: a low level held for the chosen width zeroes once per pulse.
        if mode.has_clr() {
            if input.clr {
                self.clr_low = 0;
            } else {
                self.clr_low += 1;
                if self.clr_low == self.cfg.clr_min_low.max(1) {
                    self.zero();
                }
            }
        }
        if mode.is_timed() && self.cycle == self.next_timed {
            self.next_timed += self.cfg.refresh_clocks;
            let p = self.acquire();
            self.send_frame(p);
        }
        if mode.is_handshake() {
            if !input.trigger && self.trigger_before && self.pending_send.is_none() {
                // Falling edge: the acquisition starts (the position is read now).
                self.trigger_low = 1;
                let p = self.acquire();
                self.pending_send = Some((self.cycle + self.cfg.acquisition_clocks, p));
            } else if !input.trigger && self.trigger_low > 0 {
                self.trigger_low += 1;
            } else if input.trigger && self.trigger_low > 0 {
                if self.trigger_low < self.cfg.trigger_min_low && self.pending_send.is_some() {
                    // Shorter than T2: not a trigger.
                    self.pending_send = None;
                    self.acquisitions -= 1;
                    self.glitches += 1;
                }
                self.trigger_low = 0;
            }
            self.trigger_before = input.trigger;
        }
        if let Some((at, p)) = self.pending_send {
            if self.cycle >= at
                && (!mode.is_handshake()
                    || self.trigger_low == 0
                    || self.trigger_low >= self.cfg.trigger_min_low)
            {
                self.pending_send = None;
                self.send_frame(p);
            }
        }
        let now_ps = (self.cycle * self.cfg.period_ps) as f64;
        let driving = mode.is_bus() && now_ps < self.driving_until_ps + self.cfg.period_ps as f64;
        if mode.is_bus() {
            // The receiver hears the line only while the encoder's own driver is off.
            let r = self.rx.step(&uart::In {
                i_rx: input.rx || driving,
            });
            self.since_byte += 1;
            if r.o_valid || r.o_frame_err || r.o_parity_err {
                if self.since_byte > self.cfg.command_gap + self.cfg.clocks_per_bit * 11 {
                    self.command.clear();
                }
                self.since_byte = 0;
                if r.o_valid {
                    self.command.push(r.o_data);
                } else {
                    self.command.clear();
                }
                if self.command.len() > 3 {
                    self.command.remove(0);
                }
                if let Some(cmd) = frames::parse_command(&self.command) {
                    self.command.clear();
                    let me = self.cfg.settings.address;
                    let delay = self.cfg.answer_delay;
                    match cmd {
                        Command::Read(a) if a == me => {
                            let p = self.acquire();
                            self.pending_send = Some((self.cycle + delay, p));
                        }
                        Command::Zero(a) if a == me && mode == Mode::BusClear => {
                            self.zero();
                            if self.cfg.settings.answer_zeroing {
                                let p = self.acquire();
                                self.pending_send = Some((self.cycle + delay, p));
                            }
                        }
                        _ => {}
                    }
                }
            }
        }
        let level = self.tx.step();
        self.cycle += 1;
        let enable = if mode.is_bus() {
            now_ps < self.driving_until_ps
        } else {
            true
        };
        Drive { enable, level }
    }
}
