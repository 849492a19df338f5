//! An EnDat 2.2 encoder: mode commands, memory areas selected by MRS code,
//! write protection, busy bit, error and warning words, datum shift,
//! additional data, and every answer appendix A2 prescribes for a faulty
//! request. Behavioural (not a model of any RTL): it reacts to the clock and
//! data levels at its own pins, one call per system-clock cycle.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::{crc_norm, crc_pos, crc_wire, frame_kind, Command, FrameKind, TEST_VALUE_BITS};
use crate::line::{DelayLine, Drive};
use crate::{ConfigError, Result};

/// What kind of encoder the emulator is (word 14 of the manufacturer parameters).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum EncoderKind {
    /// Singleturn rotary encoder (`1100` in word 14).
    Singleturn,
    /// Multiturn rotary encoder with gears (`1110`).
    #[default]
    Multiturn,
    /// Absolute linear encoder (`0100`).
    Linear,
}

/// Where the 16 bits of an additional datum come from (for the transcript).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum AdSource {
    /// I = 0 / 16.
    Nop,
    /// Anything else: its 5-bit code.
    Code(u8),
}

/// The encoder's configuration, in cycles.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EncoderConfig {
    /// Rotary or linear.
    pub kind: EncoderKind,
    /// Measuring-step bits per revolution (rotary) or of the whole length (linear).
    pub singleturn_bits: u32,
    /// Bits of distinguishable revolutions (multiturn only; 0 otherwise).
    pub multiturn_bits: u32,
    /// Calculation time `t_cal` from the latching edge to the earliest start bit.
    pub t_cal_clocks: u64,
    /// Time to answer a reset (start bit of the acknowledgement).
    pub reset_clocks: u64,
    /// Memory access time `t_ac`: the busy bit stays set this long after a write.
    pub t_ac_clocks: u64,
    /// Recovery time I `t_m` after type 2.2 frames (1.25 to 3.75 µs with the short setting of word 3, else 10 to 30 µs).
    pub t_m_clocks: u64,
    /// Recovery time I after type 2.1 frames, always 10 to 30 µs (seed 2.3.2 note 3).
    pub t_m21_clocks: u64,
    /// Recovery time I after type 2.2 frames with the other setting of word 3 than at power-on (it takes effect
    /// with a reset after word 3 is written).
    pub t_m_other_clocks: u64,
    /// Power-on value of word 3 bit 0: `t_m` of 1.25 to 3.75 µs for type 2.2 commands.
    pub recovery_short: bool,
    /// Clock edge to data output, including both transceivers (`0.2 µs` of the seed's `t_D`).
    pub output_delay_clocks: u64,
    /// Clocks between the last bit of a type 2.2 frame and the master's parameter block (`BLOCK_GAP`).
    pub block_gap: u64,
    /// Low bits inserted between values with a continuous clock, 1 to 7.
    pub cont_low_bits: u64,
    /// Whether the type 2.2 command set is supported (word 37).
    pub endat22: bool,
    /// Additional data supported, as I codes (word 0 and 1 of the EnDat 2.2 parameters).
    pub ad_supported: Vec<u8>,
    /// Blocks of the section 2 memory area (word 24).
    pub section2_blocks: u16,
    /// Maximum clock frequency in kHz (word 25).
    pub max_clock_khz: u16,
    /// Time unit of the calculation time in word 39 (µs).
    pub t_cal_us: u16,
}

/// The position's width, `singleturn_bits + multiturn_bits` as a scenario's
/// `[endat.encoder]` gives them: at least one measuring-step bit and
/// [`super::master::POSITION_BITS`] in all. Checked before anything derived
/// from them (the master's `pos_bits`), so that the error names the field
/// the user wrote.
pub fn check_position_bits(singleturn_bits: u32, multiturn_bits: u32) -> Result<()> {
    let range = super::master::POSITION_BITS;
    if singleturn_bits == 0 || !range.contains(&(singleturn_bits + multiturn_bits)) {
        return Err(ConfigError::invalid(
            "encoder.singleturn_bits",
            format!("{singleturn_bits} + {multiturn_bits} bits"),
            format!(
                "give at least 1 singleturn bit and {} to {} position bits in total",
                range.start(),
                range.end()
            ),
        ));
    }
    Ok(())
}

impl EncoderConfig {
    /// Position bits (word 13).
    pub fn pos_bits(&self) -> u32 {
        self.singleturn_bits + self.multiturn_bits
    }

    /// Checks the configuration; field names are those of `[endat.encoder]`.
    pub fn validate(&self) -> Result<()> {
        check_position_bits(self.singleturn_bits, self.multiturn_bits)?;
        if self.kind != EncoderKind::Multiturn && self.multiturn_bits != 0 {
            return Err(ConfigError::invalid(
                "encoder.multiturn_bits",
                "set on a non-multiturn encoder",
                "set it to 0 or kind = \"multiturn\"",
            ));
        }
        if self.multiturn_bits > 16 {
            return Err(ConfigError::invalid(
                "encoder.multiturn_bits",
                format!("{}", self.multiturn_bits),
                "give at most 16 (word 17)",
            ));
        }
        if !(1..=7).contains(&self.cont_low_bits) {
            return Err(ConfigError::invalid(
                "encoder.cont_low_bits",
                format!("{}", self.cont_low_bits),
                "give 1 to 7 (seed 2.3.1.1)",
            ));
        }
        if self.t_m_clocks == 0 {
            return Err(ConfigError::invalid(
                "encoder.t_m_us",
                "zero",
                "give the encoder's recovery time t_m",
            ));
        }
        Ok(())
    }
}

/// MRS codes of the memory areas (seed 2.4.1, 2.4.2.1).
mod mrs {
    pub const STATUS: u8 = 0xB9;
    pub const MFR_A: u8 = 0xA1;
    pub const MFR_B: u8 = 0xA3;
    pub const MFR_C: u8 = 0xA5;
    pub const OPERATING: u8 = 0xA7;
    pub const OEM: [u8; 4] = [0xA9, 0xAB, 0xAD, 0xAF];
    pub const COMP: [u8; 4] = [0xB1, 0xB3, 0xB5, 0xB7];
    pub const MFR22: u8 = 0xBD;
    pub const SECTION2: u8 = 0xBF;
    pub const OPERATING2: u8 = 0xBB;
}

/// The encoder's memory: one vector of words per MRS code, plus section 2.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Memory {
    /// Areas by MRS code; an absent code is not available in this encoder.
    pub areas: BTreeMap<u8, Vec<u16>>,
    /// Section 2 blocks, 256 words each.
    pub section2: Vec<Vec<u16>>,
}

impl Memory {
    /// The realistic default contents for `cfg` (seed chapter 3).
    pub fn new(cfg: &EncoderConfig) -> Memory {
        let mut areas = BTreeMap::new();
        let mut status = vec![0u16; 4];
        status[2] = 0x0039; // manufacturer and compensation values protected (3.4.3)
        status[3] = 0x10A8 | if cfg.recovery_short { 0x0001 } else { 0x0002 }; // 3.4.4
        areas.insert(mrs::STATUS, status);
        // Manufacturer parameters, words 4..47 (3.5); word w lives in A1 at w (4..15), A3 at w-16, A5 at w-32.
        let mut m = [0u16; 48];
        m[8] = 0x8002;
        m[9] = 0x2020; // OEM areas A9 and AB: words 0..63
        m[10] = 0xFFFF; // AD, AF not available
        m[11] = 0xFF20; // compensation B1: 0..63, B3 not available
        m[12] = 0xFFFF;
        m[13] = 0x8000 | cfg.pos_bits() as u16;
        m[14] = match cfg.kind {
            EncoderKind::Singleturn => 0xC001,
            EncoderKind::Multiturn => 0xE001,
            EncoderKind::Linear => 0x4001,
        };
        m[17] = if cfg.multiturn_bits == 0 {
            0
        } else {
            ((1u32 << cfg.multiturn_bits) - 1).min(0xFFFF) as u16
                + if cfg.multiturn_bits < 16 { 1 } else { 0 }
        };
        let steps: u64 = if cfg.kind == EncoderKind::Linear {
            10
        } else {
            1u64 << cfg.singleturn_bits.min(32)
        };
        m[20] = steps as u16;
        m[21] = (steps >> 16) as u16;
        m[24] = 0x0007;
        m[25] = 0x4A2B;
        m[26] = 0x0001;
        m[28] = 0x1234;
        m[29] = 0x0056;
        m[30] = 0x8000;
        m[31] = 0x8000;
        m[32] = 15000;
        m[33] = 0x0A01;
        m[34] = 0x0132;
        m[35] = 0x007F;
        m[36] = 0x01FF;
        m[37] = if cfg.endat22 { 0x0019 } else { 0x001A };
        m[39] = 0x2000 | cfg.t_cal_us.min(0x1FFF);
        m[40] = 0x3232; // "22"
        m[47] = m[4..47].iter().fold(0u16, |a, w| a.wrapping_add(*w));
        let mut a1 = vec![0u16; 16];
        a1[4..16].copy_from_slice(&m[4..16]);
        areas.insert(mrs::MFR_A, a1);
        areas.insert(mrs::MFR_B, m[16..32].to_vec());
        areas.insert(mrs::MFR_C, m[32..48].to_vec());
        let mut op = vec![0u16; 16];
        op[7] = 0x4240; // cycle time 1 ms = 1 000 000 ns
        op[8] = 0x000F;
        areas.insert(mrs::OPERATING, op);
        areas.insert(mrs::OEM[0], vec![0; 64]);
        areas.insert(mrs::OEM[1], vec![0; 64]);
        areas.insert(mrs::COMP[0], (0..64).map(|i| (i * 0x0101) as u16).collect());
        if cfg.endat22 {
            let mut w = vec![0u16; 64];
            for &i in &cfg.ad_supported {
                if i < 16 {
                    w[0] |= 1 << i;
                } else if i < 32 {
                    w[1] |= 1 << (i - 16);
                }
            }
            w[4] = 0x8000;
            w[24] = cfg.section2_blocks;
            w[25] = cfg.max_clock_khz;
            w[63] = w[..63].iter().fold(0u16, |a, x| a.wrapping_add(*x));
            areas.insert(mrs::MFR22, w);
            areas.insert(mrs::OPERATING2, vec![0; 256]);
        }
        let section2 = (0..cfg.section2_blocks).map(|_| vec![0u16; 256]).collect();
        Memory { areas, section2 }
    }

    /// The word a manufacturer-parameter number (4..47) is stored in.
    pub fn mfr_word(&self, word: usize) -> u16 {
        match word {
            4..=15 => self.areas[&mrs::MFR_A][word],
            16..=31 => self.areas[&mrs::MFR_B][word - 16],
            _ => self.areas[&mrs::MFR_C][word - 32],
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Ready,
    Mode,
    Block21,
    Wait,
    Send,
    Release,
    TypeOne,
    Recovery,
}

/// Why the last request was answered as it was (for the transcript and tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Answer {
    /// Answered normally.
    Ok,
    /// Error handling type I: no start bit.
    TypeI,
    /// Error handling type II: address or parameter returned inverted.
    TypeII,
    /// A type 2.2 parameter access ignored because the encoder is busy.
    Ignored,
}

/// The encoder emulator. One [`Encoder::step`] is one system-clock cycle.
#[derive(Debug, Clone)]
pub struct Encoder {
    cfg: EncoderConfig,
    mem: Memory,
    now: u64,
    phase: Phase,
    last_clk: bool,
    last_edge: u64,
    rise: u64,
    mode: u8,
    kind: FrameKind,
    block: u64,
    block_bits: u64,
    earliest: u64,
    ready_at: u64,
    queue: std::collections::VecDeque<bool>,
    recovery_until: u64,
    drive: Drive,
    en_line: DelayLine,
    lvl_line: DelayLine,
    // state of the protocol
    position: u64,
    latched: u64,
    datum_shift: u64,
    selected: Option<u8>,
    block_addr: u16,
    ad1: Option<u8>,
    ad2: Option<u8>,
    busy_until: u64,
    last_mem: (u8, u16, bool),
    last_mrs: (u8, u16, bool),
    test_port: u8,
    test_port22: u8,
    sensor_addr: u8,
    diag_addr: u8,
    pos2: u64,
    test_value: u64,
    errors_f1: bool,
    pending_ack: Option<(u8, u16)>,
    /// Word 3 selected the short recovery time I at the last reset (or power-on).
    short_tm: bool,
    /// Position added after each latch (a moving shaft, for continuous-clock runs).
    pub advance_per_latch: u64,
    /// Every frame sent (latched position, bits after the start bit), oldest first; the bench takes them.
    pub frames: std::collections::VecDeque<(u64, Vec<bool>)>,
    /// Answer to the last request.
    pub answer: Answer,
    /// Frame bit indices (after the start bit) to invert in the next frame.
    pub flips: Vec<u64>,
    /// XOR into the address and data of the next type 2.1 acknowledgement,
    /// before its CRC is computed (a CRC-valid answer with other content);
    /// cleared when a frame is built.
    pub ack_xor: (u8, u16),
    /// Return NOP instead of the selected additional data (type IV) while set.
    pub ad_stale: bool,
    /// Never send a start bit again (encoder dead, line held low).
    pub dead: bool,
    /// Never drive the line (encoder absent).
    pub absent: bool,
    /// Fault: the start bit goes this many rising edges after `R_off` (1 or 2), before `t_cal` and the earliest
    /// edge `R_off + 3` of a conforming encoder; 0 for none.
    pub early_start: u64,
    /// The frame bits sent last (after the start bit), for the transcript.
    pub sent: Vec<bool>,
    /// The position latched for the last frame.
    pub latched_position: u64,
    /// Falling edges that came during the recovery time.
    pub violations: u64,
    /// Error message 2 from its separate detection unit (seed 2.3.1, 4.2.2: "generated with a separate
    /// error detection unit"): `Some(e)` sends F2 = !e (low active) whatever F1 is; `None` (default)
    /// keeps F2 the complement of F1, as the error word alone sets both (seed 3.4.1).
    pub error2: Option<bool>,
    /// The busy bit of the additional data set whatever the memory is doing (a testbench's status).
    pub busy_forced: bool,
    /// Transfers begun (latching falling edges) since power-on.
    pub latches: u64,
    /// Mode words decoded since power-on (the last one is [`Encoder::mode`]).
    pub decodes: u64,
}

impl Encoder {
    /// An encoder at power-on, holding position 0.
    pub fn new(cfg: EncoderConfig) -> Result<Self> {
        cfg.validate()?;
        let mem = Memory::new(&cfg);
        let d = cfg.output_delay_clocks;
        Ok(Encoder {
            mem,
            now: 0,
            phase: Phase::Ready,
            last_clk: true,
            last_edge: 0,
            rise: 0,
            mode: 0,
            kind: FrameKind::Pos21,
            block: 0,
            block_bits: 0,
            earliest: 0,
            ready_at: 0,
            queue: Default::default(),
            recovery_until: 0,
            drive: Drive {
                enable: true,
                level: true,
            },
            en_line: DelayLine::new(d, true),
            lvl_line: DelayLine::new(d, true),
            position: 0,
            latched: 0,
            datum_shift: 0,
            selected: None,
            block_addr: 0,
            ad1: None,
            ad2: None,
            busy_until: 0,
            last_mem: (0, 0, false),
            last_mrs: (0, 0, false),
            test_port: 0,
            test_port22: 0,
            sensor_addr: 0,
            diag_addr: 0,
            pos2: 0,
            test_value: 0,
            errors_f1: false,
            pending_ack: None,
            short_tm: cfg.recovery_short,
            advance_per_latch: 0,
            frames: Default::default(),
            answer: Answer::Ok,
            flips: Vec::new(),
            ack_xor: (0, 0),
            ad_stale: false,
            dead: false,
            absent: false,
            early_start: 0,
            sent: Vec::new(),
            latched_position: 0,
            violations: 0,
            error2: None,
            busy_forced: false,
            latches: 0,
            decodes: 0,
            cfg,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &EncoderConfig {
        &self.cfg
    }

    /// The memory.
    pub fn memory(&self) -> &Memory {
        &self.mem
    }

    /// The memory, for scenario set-up (error words, protection).
    pub fn memory_mut(&mut self) -> &mut Memory {
        &mut self.mem
    }

    /// The shaft or scale moves: the raw position the next latch stores.
    pub fn set_position(&mut self, p: u64) {
        self.position = p & self.mask();
    }

    /// The raw position.
    pub fn position(&self) -> u64 {
        self.position
    }

    /// The position the encoder outputs for a raw position (datum shift applied).
    pub fn output_position(&self, raw: u64) -> u64 {
        raw.wrapping_add(self.datum_shift) & self.mask()
    }

    /// Changes the output delay (drift of the transceivers after calibration); takes effect at once.
    pub fn set_output_delay(&mut self, cycles: u64) {
        self.en_line = DelayLine::new(cycles, self.drive.enable);
        self.lvl_line = DelayLine::new(cycles, self.drive.level);
    }

    /// Sets the error word (operating status word 0): F1 = 1, F2 = 0 while non-zero.
    pub fn set_errors(&mut self, word0: u16) {
        self.mem.areas.get_mut(&mrs::STATUS).expect("status area")[0] = word0;
    }

    /// Sets the warning word (operating status word 1): WRN in the additional data.
    pub fn set_warnings(&mut self, word1: u16) {
        self.mem.areas.get_mut(&mrs::STATUS).expect("status area")[1] = word1;
    }

    /// Whether the encoder is busy (memory access under way).
    pub fn busy(&self) -> bool {
        self.now < self.busy_until
    }

    /// How the last request was answered: `ok`, `type_i`, `type_ii` or `ignored`.
    pub fn answer_name(&self) -> &'static str {
        match self.answer {
            Answer::Ok => "ok",
            Answer::TypeI => "type_i",
            Answer::TypeII => "type_ii",
            Answer::Ignored => "ignored",
        }
    }

    /// The six mode bits of the current (or last) transfer.
    pub fn mode(&self) -> u8 {
        self.mode
    }

    /// Additional data selected (I codes) as the encoder holds them.
    pub fn ad_selection(&self) -> (Option<u8>, Option<u8>) {
        (self.ad1, self.ad2)
    }

    fn mask(&self) -> u64 {
        let b = self.cfg.pos_bits();
        if b >= 64 {
            u64::MAX
        } else {
            (1u64 << b) - 1
        }
    }

    fn status(&self) -> &[u16] {
        &self.mem.areas[&mrs::STATUS]
    }

    /// How many of the next steps with the clock at `clk` leave the drive
    /// and the phase as they are (fast-forward): none on a clock edge; with
    /// the clock high, up to the end of `t_m` in a transfer or of the
    /// recovery time; and up to the next edge in flight on the output delay.
    pub fn quiet(&self, clk: bool) -> u64 {
        if clk != self.last_clk {
            return 0;
        }
        let phase = match self.phase {
            Phase::Ready
                if self.drive
                    == (Drive {
                        enable: true,
                        level: true,
                    }) =>
            {
                u64::MAX
            }
            Phase::Ready => 0,
            Phase::Recovery => self.recovery_until.saturating_sub(self.now),
            _ if !clk => u64::MAX,
            _ => (self.last_edge + self.t_m() + 1).saturating_sub(self.now),
        };
        let d = Drive {
            enable: self.drive.enable && !self.absent,
            level: self.drive.level,
        };
        phase
            .min(self.en_line.quiet(d.enable))
            .min(self.lvl_line.quiet(d.level))
    }

    /// The same as `n` steps with the last clock level, for `n` up to [`Encoder::quiet`].
    pub fn skip(&mut self, n: u64) {
        if !self.last_clk {
            self.last_edge = self.now + n - 1;
        }
        self.now += n;
        self.en_line.skip(n);
        self.lvl_line.skip(n);
    }

    /// What the encoder drives onto the cable after the last step.
    pub fn drive(&self) -> Drive {
        Drive {
            enable: self.en_line.output(),
            level: self.lvl_line.output(),
        }
    }

    /// One cycle with the clock and the data line (as driven by the master) at the encoder's pins;
    /// returns what the encoder drives onto the cable.
    pub fn step(&mut self, clk: bool, din: bool) -> Drive {
        let fell = self.last_clk && !clk;
        let rose = !self.last_clk && clk;
        self.last_clk = clk;
        if fell || rose || !clk {
            self.last_edge = self.now;
        }
        // How long the clock has stayed high: past t_m the master has ended the transfer.
        let quiet = self.now - self.last_edge;
        match self.phase {
            Phase::Ready => {
                self.drive = Drive {
                    enable: true,
                    level: true,
                };
                if fell {
                    self.latch();
                    self.drive.enable = false; // t_ST: the send block is switched off with the first falling edge
                    self.rise = 0;
                    self.mode = 0;
                    self.phase = Phase::Mode;
                    self.ready_at = self.now + self.cfg.t_cal_clocks;
                }
            }
            Phase::Mode => {
                if rose {
                    self.rise += 1;
                    if (2..=7).contains(&self.rise) {
                        self.mode = (self.mode << 1) | din as u8;
                    }
                    if self.rise == 7 {
                        self.decode_mode();
                    }
                } else if quiet > self.t_m() {
                    self.enter_recovery();
                }
            }
            Phase::Block21 => {
                if rose {
                    self.rise += 1;
                    self.block = (self.block << 1) | din as u64;
                    self.block_bits += 1;
                    if self.block_bits == super::BLOCK_BITS {
                        self.process_block21();
                    }
                } else if quiet > self.t_m() {
                    self.enter_recovery();
                }
            }
            Phase::TypeOne => {
                if rose {
                    self.rise += 1;
                    if self.rise == self.k_off() {
                        self.drive = Drive {
                            enable: !self.absent,
                            level: false,
                        };
                    }
                } else if quiet > self.t_m() {
                    self.enter_recovery();
                }
            }
            Phase::Wait => {
                if rose {
                    self.rise += 1;
                    if self.rise == self.k_off() {
                        self.drive = Drive {
                            enable: !self.absent,
                            level: false,
                        };
                    }
                    if self.rise >= self.earliest
                        && (self.now >= self.ready_at || self.early_start > 0)
                        && !self.dead
                    {
                        self.build_frame();
                        self.drive.level = true; // the start bit
                        self.phase = Phase::Send;
                    }
                } else if quiet > self.t_m() {
                    self.enter_recovery();
                }
            }
            Phase::Send => {
                if rose {
                    self.rise += 1;
                    match self.queue.pop_front() {
                        Some(b) => self.drive.level = b,
                        None => {
                            if self.kind == FrameKind::Block22 {
                                self.drive.enable = false;
                                self.phase = Phase::Release;
                                self.block = 0;
                                self.block_bits = 0;
                                self.rise = 0;
                            } else {
                                self.enter_recovery();
                            }
                        }
                    }
                } else if quiet > self.t_m() {
                    self.enter_recovery();
                }
            }
            Phase::Release => {
                if rose {
                    self.rise += 1;
                    if self.rise >= self.cfg.block_gap {
                        self.block = (self.block << 1) | din as u64;
                        self.block_bits += 1;
                        if self.block_bits == super::BLOCK_BITS {
                            self.process_block22();
                            self.enter_recovery();
                            self.drive.enable = false;
                        }
                    }
                } else if quiet > self.t_m() {
                    self.enter_recovery();
                }
            }
            Phase::Recovery => {
                if fell
                    && self.kind == FrameKind::Pos21
                    && self.mode == Command::Pos21.code()
                    && self.now < self.recovery_until
                    && !self.dead
                {
                    // Continuous clock: the second falling edge after the CRC latches the next
                    // value; cont_low_bits low bits (the first already on the line), then the start bit.
                    self.latch();
                    self.build_frame();
                    let mut q: std::collections::VecDeque<bool> = std::collections::VecDeque::new();
                    for _ in 1..self.cfg.cont_low_bits {
                        q.push_back(false);
                    }
                    q.push_back(true);
                    q.extend(self.sent.iter().copied());
                    self.queue = q;
                    self.phase = Phase::Send;
                } else if fell {
                    self.violations += 1;
                } else if self.now >= self.recovery_until {
                    self.phase = Phase::Ready;
                    self.drive = Drive {
                        enable: !self.absent,
                        level: true,
                    };
                }
            }
        }
        self.now += 1;
        let d = Drive {
            enable: self.drive.enable && !self.absent,
            level: self.drive.level,
        };
        Drive {
            enable: self.en_line.step(d.enable),
            level: self.lvl_line.step(d.level),
        }
    }

    fn k_off(&self) -> u64 {
        if self.kind == FrameKind::Param21 {
            8 + super::BLOCK_BITS
        } else {
            8
        }
    }

    fn latch(&mut self) {
        self.latches += 1;
        self.latched = self.output_position(self.position);
        self.latched_position = self.latched;
        self.position = self.position.wrapping_add(self.advance_per_latch) & self.mask();
    }

    /// Recovery time I of the current command: type 2.2 commands follow word 3, type 2.1 ones are always long.
    fn t_m(&self) -> u64 {
        match Command::from_code(self.mode) {
            Some(c) if c.is_type22() && self.phase != Phase::Mode => {
                if self.short_tm == self.cfg.recovery_short {
                    self.cfg.t_m_clocks
                } else {
                    self.cfg.t_m_other_clocks
                }
            }
            _ => self.cfg.t_m21_clocks,
        }
    }

    /// Recovery time I: the line low until `t_m` after the master's last
    /// clock edge (seed 004, 2.3.2 and appendix A2, 4.2.1: "setting of the
    /// clock line to High ... and to wait for the time t_m before renewed
    /// data transfer is possible"). After a frame's last bit this is `t_m`
    /// from that edge; when a transfer is abandoned (type I error, a master
    /// that stops clocking), the silence that tells the encoder the clock has
    /// stopped is the recovery time itself, so the line is released as soon
    /// as it is detected and not `t_m` later (which held it low for about
    /// `2 t_m`, past the 30 µs the appendix tells the control to wait).
    fn enter_recovery(&mut self) {
        self.phase = Phase::Recovery;
        self.drive = Drive {
            enable: !self.absent,
            level: false,
        };
        self.recovery_until = self.last_edge + self.t_m();
        if self.now >= self.recovery_until {
            // Detected by the silence alone: ready at once, no one-cycle low pulse.
            self.phase = Phase::Ready;
            self.drive = Drive {
                enable: !self.absent,
                level: true,
            };
        }
    }

    fn decode_mode(&mut self) {
        self.decodes += 1;
        self.kind = frame_kind(self.mode);
        self.answer = Answer::Ok;
        let cmd = Command::from_code(self.mode);
        let supported = match cmd {
            None => false,
            Some(c) if c.is_type22() => self.cfg.endat22,
            Some(_) => true,
        };
        if !supported {
            self.answer = Answer::TypeI;
            self.phase = Phase::TypeOne;
            return;
        }
        self.earliest = self.k_off()
            + if self.early_start > 0 {
                self.early_start
            } else {
                3
            };
        if self.kind == FrameKind::Param21 {
            self.block = 0;
            self.block_bits = 0;
            self.phase = Phase::Block21;
        } else {
            self.phase = Phase::Wait;
        }
    }

    /// Appendix A2 and chapter 2.4 to 2.10 for the type 2.1 parameter commands.
    fn process_block21(&mut self) {
        let addr = (self.block >> 21) as u8;
        let data = (self.block >> 5) as u16;
        let crc = (self.block & 0x1F) as u8;
        self.phase = Phase::Wait;
        self.ready_at = self.now + self.cfg.t_cal_clocks;
        if crc != crc_norm(addr, data) {
            self.answer = Answer::TypeI; // frame disrupted: cause 2 of appendix A2
            self.phase = Phase::TypeOne;
            return;
        }
        let cmd = Command::from_code(self.mode).expect("decoded");
        let busy = self.busy();
        let (ok, ack_data) = match cmd {
            Command::Select21 => {
                if addr & 0xE1 != 0xA1 {
                    self.answer = Answer::TypeI;
                    self.phase = Phase::TypeOne;
                    return;
                }
                if busy
                    || matches!(addr, mrs::MFR22 | mrs::SECTION2 | mrs::OPERATING2)
                    || !self.mem.areas.contains_key(&addr)
                {
                    (false, data)
                } else {
                    self.selected = Some(addr);
                    (true, data)
                }
            }
            Command::Receive21 => {
                if busy {
                    self.last_mem = (addr, data, true);
                }
                (!busy && self.write(addr, data), data)
            }
            Command::Send21 => match (busy, self.read(addr)) {
                (false, Some(v)) => (true, v),
                _ => {
                    self.last_mem = (addr, 0, true); // as for 100100: the failed access is what I = 5 / 6 acknowledge
                    (false, 0)
                }
            },
            Command::Reset21 => {
                if busy {
                    (false, data)
                } else {
                    self.reset();
                    self.ready_at = self.now + self.cfg.reset_clocks;
                    (true, data)
                }
            }
            Command::TestCommand21 => {
                self.test_port = addr;
                (true, data)
            }
            Command::Communication22 => {
                let own = self.mem.areas[&mrs::OPERATING][4] as u8;
                (addr == 0 || addr == own, data)
            }
            _ => (true, data),
        };
        let (a, d) = if ok {
            (addr, ack_data)
        } else {
            (!addr, !ack_data)
        };
        self.answer = if ok { Answer::Ok } else { Answer::TypeII };
        self.queue.clear();
        self.pending_ack = Some((a, d));
    }

    fn reset(&mut self) {
        self.ad1 = None;
        self.ad2 = None;
        let op = &self.mem.areas[&mrs::OPERATING];
        self.datum_shift = (op[0] as u64) | ((op[1] as u64) << 16) | ((op[2] as u64) << 32);
        // Word 3 becomes active (3.4.4): bit 0 = 1 and bit 1 = 0 select the short recovery time I; any other
        // combination the factory default, the long one.
        let w3 = self.status()[3];
        self.short_tm = w3 & 0b11 == 0b01;
    }

    fn area_writable(&self, area: u8) -> bool {
        let prot = self.status()[2];
        match area {
            mrs::STATUS => true,
            mrs::OPERATING => prot & 2 == 0,
            a if mrs::OEM.contains(&a) => prot & 4 == 0,
            mrs::SECTION2 => prot & (1 << (6 + self.block_addr.min(3))) == 0,
            mrs::OPERATING2 => true,
            _ => false, // manufacturer parameters and compensation values (factory protected)
        }
    }

    fn word_ref(&mut self, addr: u8) -> Option<&mut u16> {
        let area = self.selected?;
        let a = addr as usize;
        if area == mrs::SECTION2 {
            return self
                .mem
                .section2
                .get_mut(self.block_addr as usize)?
                .get_mut(a);
        }
        if area == mrs::MFR_A && a < 4 {
            return None;
        }
        if area == mrs::OPERATING2 && !matches!(a, 0 | 1 | 11) {
            return None; // unassigned operating-parameter-2 address: type II (A2 cause 12)
        }
        self.mem.areas.get_mut(&area)?.get_mut(a)
    }

    fn read(&mut self, addr: u8) -> Option<u16> {
        let v = *self.word_ref(addr)?;
        self.last_mem = (addr, v, false);
        Some(v)
    }

    fn write(&mut self, addr: u8, data: u16) -> bool {
        let Some(area) = self.selected else {
            return false;
        };
        if !self.area_writable(area) {
            self.last_mem = (addr, data, true);
            return false;
        }
        let old = match self.word_ref(addr) {
            Some(w) => *w,
            None => {
                self.last_mem = (addr, data, true);
                return false;
            }
        };
        if area == mrs::STATUS && addr == 2 && (old & !data) != 0 {
            self.last_mem = (addr, data, true); // clearing a protection bit: A2 cause 10
            return false;
        }
        if area == mrs::STATUS && addr <= 1 && data != 0 {
            self.last_mem = (addr, data, true); // errors and warnings can only be cleared with 0000
            return false;
        }
        *self.word_ref(addr).expect("checked") = data;
        self.busy_until = self.now + self.cfg.t_ac_clocks;
        self.last_mem = (addr, data, false);
        true
    }

    /// The master's block after a type 2.2 frame (seed 2.4.2 to 2.8.1).
    fn process_block22(&mut self) {
        let addr = (self.block >> 21) as u8;
        let data = (self.block >> 5) as u16;
        let crc = (self.block & 0x1F) as u8;
        if crc != crc_norm(addr, data) {
            self.answer = Answer::TypeI;
            return;
        }
        let busy = self.busy();
        self.answer = Answer::Ok;
        match Command::from_code(self.mode) {
            Some(Command::Select22) => {
                if (addr & 0xE0) == 0x40 {
                    let code = addr & 0x1F;
                    let slot = if code < 16 {
                        &mut self.ad1
                    } else {
                        &mut self.ad2
                    };
                    *slot = if code & 0x0F == 0x0F {
                        None
                    } else {
                        Some(code)
                    };
                    self.last_mrs = (addr, data, false);
                } else if addr & 0xE1 == 0xA1 && self.mem.areas.contains_key(&addr) && !busy {
                    self.selected = Some(addr);
                    self.block_addr = data & 0xFF;
                    let ok = addr != mrs::SECTION2 || self.block_addr < self.cfg.section2_blocks;
                    self.last_mrs = (addr, data, !ok);
                    if !ok {
                        self.answer = Answer::TypeII;
                    }
                } else if addr == mrs::SECTION2 && !busy && self.block_addr_ok(data) {
                    self.selected = Some(addr);
                    self.block_addr = data & 0xFF;
                    self.last_mrs = (addr, data, false);
                } else {
                    self.last_mrs = (addr, data, true);
                    self.answer = if busy {
                        Answer::Ignored
                    } else {
                        Answer::TypeII
                    };
                }
            }
            Some(Command::Receive22) => {
                if busy {
                    self.answer = Answer::Ignored;
                } else if !self.write(addr, data) {
                    self.answer = Answer::TypeII;
                }
            }
            Some(Command::Send22) => {
                if busy {
                    self.answer = Answer::Ignored;
                } else if self.read(addr).is_none() {
                    self.last_mem = (addr, 0, true);
                    self.answer = Answer::TypeII;
                }
            }
            Some(Command::TestCommand22) => self.test_port22 = addr,
            Some(Command::ErrorReset22) => {
                let st = self.mem.areas.get_mut(&mrs::STATUS).expect("status");
                st[0] = 0;
                st[1] = 0;
            }
            _ => {}
        }
    }

    fn block_addr_ok(&self, data: u16) -> bool {
        (data & 0xFF) < self.cfg.section2_blocks
    }

    /// The bits after the start bit, as the encoder will send them, with any flips applied.
    fn build_frame(&mut self) {
        let st = self.status().to_vec();
        let f1 = st[0] != 0 || self.errors_f1;
        let f2 = match self.error2 {
            Some(e) => !e,
            None => !f1,
        };
        let mut bits: Vec<bool> = Vec::new();
        match self.kind {
            FrameKind::Pos21 | FrameKind::Pos22 | FrameKind::Block22 => {
                let n = self.cfg.pos_bits();
                let is22 = self.kind != FrameKind::Pos21;
                bits.push(f1);
                if is22 {
                    bits.push(f2);
                }
                for i in 0..n {
                    bits.push((self.latched >> i) & 1 == 1);
                }
                bits.extend(crc_wire(crc_pos(f1, is22.then_some(f2), self.latched, n)));
                if is22 {
                    if let Some(code) = self.ad2 {
                        let w = self.ad_word(code, &st);
                        push_ad(&mut bits, w);
                    }
                    if let Some(code) = self.ad1 {
                        let w = self.ad_word(code, &st);
                        push_ad(&mut bits, w);
                    }
                }
            }
            FrameKind::Test21 => {
                self.test_value = self.test_values(self.test_port);
                bits.push(f1);
                for i in 0..TEST_VALUE_BITS {
                    bits.push((self.test_value >> i) & 1 == 1);
                }
                bits.extend(crc_wire(crc_pos(
                    f1,
                    None,
                    self.test_value,
                    TEST_VALUE_BITS,
                )));
            }
            FrameKind::Param21 => {
                let (a, d) = self.pending_ack.take().unwrap_or((0, 0));
                let (a, d) = (a ^ self.ack_xor.0, d ^ self.ack_xor.1);
                for i in (0..8).rev() {
                    bits.push((a >> i) & 1 == 1);
                }
                for i in (0..16).rev() {
                    bits.push((d >> i) & 1 == 1);
                }
                bits.extend(crc_wire(crc_norm(a, d)));
            }
        }
        for &f in &self.flips {
            if let Some(b) = bits.get_mut(f as usize) {
                *b = !*b;
            }
        }
        self.flips.clear();
        self.ack_xor = (0, 0);
        self.frames.push_back((self.latched, bits.clone()));
        self.sent = bits.clone();
        self.queue = bits.into();
    }

    fn test_values(&self, port: u8) -> u64 {
        // Port 0: operating status error sources (2.9); other ports: a recognisable pattern.
        if port == 0 {
            self.status()[0] as u64
        } else {
            (0xA5_0000_0000u64 | (port as u64) << 24 | (self.latched & 0xFF_FFFF)) & ((1 << 40) - 1)
        }
    }

    /// The 24-bit additional datum with I code `code` (seed 2.3.5), type III and IV included.
    fn ad_word(&mut self, code: u8, st: &[u16]) -> u32 {
        let wrn = st[1] != 0;
        let rm = true;
        let busy = self.busy() || self.busy_forced;
        let ad1 = code < 16;
        let supported = self.cfg.ad_supported.contains(&code) || code == 0 || code == 16;
        let impermissible = matches!(code, 26 | 28 | 29 | 30);
        let (i, payload): (u8, u16) = if impermissible || !supported {
            (if ad1 { 15 } else { 31 }, 0)
        } else if self.ad_stale {
            (if ad1 { 0 } else { 16 }, 0)
        } else {
            let p = self.latched;
            let payload = match code {
                0 | 16 => 0,
                1 => {
                    self.diag_addr = self.diag_addr % 6 + 1;
                    ((self.diag_addr as u16) << 8) | 0x80
                }
                2 => {
                    self.pos2 = p;
                    self.pos2 as u16
                }
                3 => (self.pos2 >> 16) as u16,
                4 => (self.pos2 >> 32) as u16,
                5 => ((self.last_mem.0 as u16) << 8) | (self.last_mem.1 & 0xFF),
                6 => ((self.last_mem.0 as u16) << 8) | (self.last_mem.1 >> 8),
                7 => ((self.last_mrs.0 as u16) << 8) | (self.last_mrs.1 & 0xFF),
                8 => (self.test_port22 as u16) << 8,
                9 => {
                    self.test_value = self.test_values(self.test_port22);
                    self.test_value as u16
                }
                10 => (self.test_value >> 16) as u16,
                11 => (self.test_value >> 32) as u16,
                12 => 3131, // 313.1 K = 40 °C, 0.1 K per LSB (3.9.6)
                13 => 3031,
                14 => {
                    let a = self.sensor_addr;
                    self.sensor_addr = (self.sensor_addr + 1) % 3;
                    ((a as u16) << 12) | (1580 + 100 * a as u16)
                }
                17 => commutation(p, self.cfg.singleturn_bits) << 13,
                18 => 1200,
                19 => (commutation(p, self.cfg.singleturn_bits) << 13) | 1200,
                20 => 0x4000,
                21 => 0x4000 | 1200,
                22 => p as u16,
                23 => (p >> 16) as u16,
                24 => (p >> 32) as u16,
                25 => st[0],
                27 => (self.now / 64) as u16,
                _ => 0,
            };
            (code, payload)
        };
        let mut word = ((wrn as u32) << 23)
            | ((rm as u32) << 22)
            | ((busy as u32) << 21)
            | ((i as u32) << 16)
            | payload as u32;
        // Type II for type 2.2 accesses: the acknowledged address comes back inverted (A2 4.2.2).
        if (i == 5 || i == 6) && self.last_mem.2 || i == 7 && self.last_mrs.2 {
            word ^= 0xFF00;
        }
        word
    }
}

fn commutation(p: u64, st_bits: u32) -> u16 {
    // u v w of a 4-pole-pair motor: six sectors per electrical revolution.
    let per_rev = 1u64 << st_bits.min(40);
    let elec = (p % per_rev) * 4 * 6 / per_rev % 6;
    [0b100, 0b110, 0b010, 0b011, 0b001, 0b101][elec as usize]
}

fn push_ad(bits: &mut Vec<bool>, w: u32) {
    for i in (0..24).rev() {
        bits.push((w >> i) & 1 == 1);
    }
    bits.extend(crc_wire(crc_norm((w >> 16) as u8, w as u16)));
}
