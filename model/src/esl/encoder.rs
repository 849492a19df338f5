//! A QS35 encoder (seed 000) as the host sees it on the line: frame-set
//! detection, the answers of Table 12, the commands sent 8 times, memory
//! and registers with their busy timing (Tables 9 to 11), the CA0/CA1
//! answers to a bad request, a baud error of its own, and injectable faults.

use serde::{Deserialize, Serialize};

use super::frames::{self, Alarms, AnswerData, DataId, Status};
use crate::line::Drive;

/// What one emulated encoder holds, as a scenario sets it (`[[esl.encoders]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderSettings {
    /// Encoder address 0..7 (EAD0..2).
    pub address: u8,
    /// Single-turn position, 24 bits.
    pub single_turn: u32,
    /// Multi-turn count, 16 bits.
    pub multi_turn: u16,
    /// Error flags (ALM1 and ALM2).
    pub alarms: Alarms,
    /// Temperature in °C.
    pub temperature_c: i8,
    /// DD0 is set from this temperature on, °C.
    pub temperature_warning_c: i8,
    /// Multi-turn bytes in ENID (0 = single-turn encoder, 2 = QS35-M40M).
    pub enid_mt_bytes: u8,
    /// SC1 and SC2 of the first safety answer.
    pub sequence_start: u8,
    /// Answer delay after the request's last stop bit, µs (seed: 2.0 µs typ.).
    pub answer_delay_us: f64,
    /// EEPROM read time, µs (seed: 200 µs).
    pub eeprom_read_us: f64,
    /// EEPROM write time, µs (seed: 6 ms).
    pub eeprom_write_us: f64,
    /// Page change time, µs (seed: 18 ms).
    pub page_change_us: f64,
    /// Longest interval between two of the 8 repeated commands that still
    /// counts, µs (seed: "typical interval of 40 µs").
    pub repeat_window_us: f64,
    /// This encoder's bit rate error in percent (positive = fast).
    pub baud_error_percent: f64,
    /// Memory contents at power-on (all else 0, as shipped).
    pub memory: Vec<MemoryInit>,
    /// Faults: bits of answers inverted on the line, after the CRC is made.
    pub flips: Vec<AnswerFlip>,
    /// Faults: answers cut short after this many fields.
    pub truncations: Vec<Truncation>,
    /// Faults: a sequence counter that skips a value before an answer.
    pub sequence_jumps: Vec<SequenceJump>,
    /// Faults: answers sent with another encoder's address in CF1/CF2 (CRCs valid).
    pub foreign_address_answers: Vec<usize>,
    /// Fault: channel 2's redundant single-turn off by this many of its LSBs.
    pub rs_offset: i32,
}

/// Initial memory bytes (`[[esl.encoders.memory]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MemoryInit {
    /// ESL page 0..15.
    pub page: u8,
    /// First address 0x00..0x7E.
    pub address: u8,
    /// The bytes from there on.
    pub data: Vec<u8>,
}

/// One bit of one answer inverted on the line (`[[esl.encoders.flips]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AnswerFlip {
    /// Which answer (0 = the first this encoder sends).
    pub answer: usize,
    /// Which field of it (0 = CF1).
    pub field: usize,
    /// Which of its 10 bits: 0 start, 1..8 data LSB first, 9 stop.
    pub bit: u8,
}

/// An answer that stops after `fields` fields (`[[esl.encoders.truncations]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Truncation {
    /// Which answer.
    pub answer: usize,
    /// Fields sent.
    pub fields: usize,
}

/// A sequence counter that jumps by 2 before an answer (`[[esl.encoders.sequence_jumps]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SequenceJump {
    /// Which answer.
    pub answer: usize,
    /// 1: SC1, 2: SC2.
    pub channel: u8,
}

impl Default for EncoderSettings {
    fn default() -> Self {
        EncoderSettings {
            address: 0,
            single_turn: 0x12_3456,
            multi_turn: 0x0102,
            alarms: Alarms::default(),
            temperature_c: 35,
            temperature_warning_c: 100,
            enid_mt_bytes: 2,
            sequence_start: 0,
            answer_delay_us: 2.0,
            eeprom_read_us: 200.0,
            eeprom_write_us: 6_000.0,
            page_change_us: 18_000.0,
            repeat_window_us: 200.0,
            baud_error_percent: 0.0,
            memory: Vec::new(),
            flips: Vec::new(),
            truncations: Vec::new(),
            sequence_jumps: Vec::new(),
            foreign_address_answers: Vec::new(),
            rs_offset: 0,
        }
    }
}

/// The encoder's configuration in cycles.
#[derive(Debug, Clone, PartialEq)]
pub struct EncoderConfig {
    /// The encoder's own bit length in cycles (f_sys / baud / (1 + error)).
    pub bit_cycles: f64,
    /// Cycles from the end of the request's last stop bit to the answer's start bit.
    pub answer_delay: u64,
    /// Cycles of an EEPROM read.
    pub eeprom_read: u64,
    /// Cycles of an EEPROM write.
    pub eeprom_write: u64,
    /// Cycles of a page change.
    pub page_change: u64,
    /// Longest interval between counted repeats, cycles.
    pub repeat_window: u64,
    /// The address every encoder obeys and none answers (daisy-chain broadcast).
    pub broadcast_address: Option<u8>,
    /// Initial state.
    pub settings: EncoderSettings,
}

/// ESL pages 0..15, 128 addresses each (0x7F is the page register).
pub const PAGES: usize = 16;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Rx {
    /// Waiting for a falling edge after idle.
    Hunt,
    /// Sampling bit `n` (0 = start, 9 = stop) at cycle `at` of a field whose start edge was at `edge`.
    Bit { n: u8, at: u64, edge: u64 },
    /// After a stop bit: a falling edge continues the frame set, a high line for a bit and a half ends it.
    Gap { high: u64 },
}

/// The emulator. One [`Encoder::step`] is one system-clock cycle.
#[derive(Debug, Clone)]
pub struct Encoder {
    cfg: EncoderConfig,
    single_turn: u32,
    st_offset: u32,
    multi_turn: u16,
    alarms: Alarms,
    sc1: u8,
    sc2: u8,
    memory: Vec<u8>,
    page: u8,
    busy_until: u64,
    pending_write: Option<(usize, u8)>,
    prefetch: Option<(usize, u64)>,
    repeat: (Option<DataId>, u32, u64),
    now: u64,
    last_level: bool,
    rx: Rx,
    shift: u8,
    fields: Vec<u8>,
    stop_error: bool,
    for_me: bool,
    tx_bits: Vec<bool>,
    tx_index: usize,
    tx_start: u64,
    /// The cycle the next answer bit (`tx_index`) goes out:
    /// `tx_start + round(tx_index × bit_cycles)`, kept so that the float
    /// rounding runs once a bit, not every cycle (a libm call on x86-64).
    tx_next_at: u64,
    /// High cycles that end a frame set: ceil(1.5 × bit_cycles) (the same float once, not per cycle).
    gap_cycles: u64,
    answer_at: Option<(u64, Vec<u8>)>,
    driving: bool,
    level: bool,
    answered: Vec<(u64, Vec<u8>)>,
    executed: Vec<DataId>,
    temp_warning: Option<bool>,
    requests: u64,
    last_request: Option<Request>,
}

/// The last frame set an encoder received (for a co-simulation's checks of
/// the host: request spacing, character timing).
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// Cycle of the end of its last stop bit.
    pub end: u64,
    /// The fields as received (CF first).
    pub fields: Vec<u8>,
    /// Addressed to this encoder (or broadcast).
    pub for_me: bool,
    /// A stop bit was low.
    pub stop_error: bool,
    /// The page register when it arrived (EEPROM or register access).
    pub page: u8,
}

impl Encoder {
    /// An encoder at power-on.
    pub fn new(cfg: EncoderConfig) -> Self {
        let mut memory = vec![0u8; PAGES * 128];
        for m in &cfg.settings.memory {
            for (i, b) in m.data.iter().enumerate() {
                if let Some(slot) =
                    memory.get_mut(usize::from(m.page) * 128 + usize::from(m.address) + i)
                {
                    *slot = *b;
                }
            }
        }
        let s = &cfg.settings;
        Encoder {
            single_turn: s.single_turn & 0xFF_FFFF,
            st_offset: 0,
            multi_turn: s.multi_turn,
            alarms: s.alarms,
            sc1: s.sequence_start,
            sc2: s.sequence_start & 0x7F,
            memory,
            page: frames::DEFAULT_PAGE,
            busy_until: 0,
            pending_write: None,
            prefetch: None,
            repeat: (None, 0, 0),
            now: 0,
            last_level: true,
            rx: Rx::Hunt,
            shift: 0,
            fields: Vec::new(),
            stop_error: false,
            for_me: false,
            tx_bits: Vec::new(),
            tx_index: 0,
            tx_start: 0,
            tx_next_at: 0,
            gap_cycles: (1.5 * cfg.bit_cycles).ceil() as u64,
            answer_at: None,
            driving: false,
            level: true,
            answered: Vec::new(),
            executed: Vec::new(),
            temp_warning: None,
            requests: 0,
            last_request: None,
            cfg,
        }
    }

    /// This encoder's address.
    pub fn address(&self) -> u8 {
        self.cfg.settings.address
    }

    /// Single-turn position as reported (after a single-turn clear).
    pub fn single_turn(&self) -> u32 {
        self.single_turn.wrapping_sub(self.st_offset) & 0xFF_FFFF
    }

    /// Multi-turn count now.
    pub fn multi_turn(&self) -> u16 {
        self.multi_turn
    }

    /// Error flags now.
    pub fn alarms(&self) -> Alarms {
        self.alarms
    }

    /// One memory byte.
    pub fn memory(&self, page: u8, address: u8) -> u8 {
        self.memory[usize::from(page & 0xF) * 128 + usize::from(address & 0x7F)]
    }

    /// The page register.
    pub fn page(&self) -> u8 {
        self.page
    }

    /// Every answer sent so far: (cycle of its first start bit, fields as intended).
    pub fn answered(&self) -> &[(u64, Vec<u8>)] {
        &self.answered
    }

    /// Sets the shaft position a testbench wants reported from the next
    /// answer on (a single-turn clear's offset still applies).
    pub fn set_position(&mut self, single_turn: u32, multi_turn: u16) {
        self.single_turn = single_turn & 0xFF_FFFF;
        self.multi_turn = multi_turn;
    }

    /// Sets the error flags (ALM1/ALM2, and EA0/EA1 from them) from the next answer on.
    pub fn set_alarms(&mut self, alarms: Alarms) {
        self.alarms = alarms;
    }

    /// Forces DD0 (temperature warning) on or off, whatever the temperature.
    pub fn set_temp_warning(&mut self, on: bool) {
        self.temp_warning = Some(on);
    }

    /// Faults a testbench schedules at run time, in the scenario's own
    /// fields: appended to `flips`, `truncations`, `sequence_jumps`,
    /// `foreign_address_answers`; `rs_offset` replaced when given.
    pub fn add_faults(&mut self, faults: &EncoderSettings, rs_offset: Option<i32>) {
        let s = &mut self.cfg.settings;
        s.flips.extend(faults.flips.iter().cloned());
        s.truncations.extend(faults.truncations.iter().cloned());
        s.sequence_jumps
            .extend(faults.sequence_jumps.iter().cloned());
        s.foreign_address_answers
            .extend(faults.foreign_address_answers.iter().copied());
        if let Some(r) = rs_offset {
            s.rs_offset = r;
        }
    }

    /// Frame sets received so far (for this encoder or not).
    pub fn requests(&self) -> u64 {
        self.requests
    }

    /// The last frame set received.
    pub fn last_request(&self) -> Option<&Request> {
        self.last_request.as_ref()
    }

    /// The 8-times commands executed so far.
    pub fn executed(&self) -> &[DataId] {
        &self.executed
    }

    /// How many of the next steps with the line at `line` change nothing
    /// but the time (fast-forward): none on an edge; otherwise up to the
    /// next bit sample, the end of an inter-field gap, the answer's start or
    /// next bit, or a pending EEPROM write.
    pub fn quiet(&self, line: bool) -> u64 {
        if line != self.last_level {
            return 0;
        }
        let until = |t: u64| t.saturating_sub(self.now);
        let write = self
            .pending_write
            .map_or(u64::MAX, |_| until(self.busy_until));
        let receive = match self.rx {
            _ if self.driving => u64::MAX,
            Rx::Hunt => u64::MAX,
            Rx::Gap { .. } if !line => u64::MAX,
            Rx::Gap { high } => self.gap_cycles.saturating_sub(high + 1),
            Rx::Bit { at, .. } => until(at),
        };
        let transmit = if self.driving {
            until(self.tx_next_at)
        } else {
            self.answer_at
                .as_ref()
                .map_or(u64::MAX, |(at, _)| until(*at))
        };
        write.min(receive).min(transmit)
    }

    /// The same as `n` steps with the last line level, for `n` up to [`Encoder::quiet`].
    pub fn skip(&mut self, n: u64) {
        if let (false, true, Rx::Gap { high }) = (self.driving, self.last_level, self.rx) {
            self.rx = Rx::Gap { high: high + n };
        }
        self.now += n;
    }

    /// What the encoder drives after the last step.
    pub fn drive(&self) -> Drive {
        Drive {
            enable: self.driving,
            level: self.level,
        }
    }

    /// One cycle with the line level at the encoder's pins; returns what the
    /// encoder drives (it listens only while it does not drive).
    pub fn step(&mut self, line: bool) -> Drive {
        if let Some((index, data)) = self.pending_write {
            if self.now >= self.busy_until {
                self.memory[index] = data;
                self.pending_write = None;
            }
        }
        if !self.driving {
            self.receive(line);
        }
        self.transmit();
        self.last_level = line;
        self.now += 1;
        Drive {
            enable: self.driving,
            level: self.level,
        }
    }

    fn at_bit(&self, edge: u64, n: u8, frac: f64) -> u64 {
        edge + ((f64::from(n) + frac) * self.cfg.bit_cycles).round() as u64
    }

    /// Frame-set receiver: a set starts at the first 0 after idle; the three
    /// bits after the start bit must be this encoder's address (or the
    /// broadcast address), else the set is followed to its end but ignored.
    /// The set ends when no start bit follows a stop bit.
    fn receive(&mut self, line: bool) {
        let falling = self.last_level && !line;
        match self.rx {
            Rx::Hunt => {
                if falling {
                    self.fields.clear();
                    self.stop_error = false;
                    self.for_me = true;
                    self.begin_field();
                }
            }
            Rx::Gap { high } => {
                if falling {
                    self.begin_field();
                } else if line {
                    let high = high + 1;
                    if high as f64 >= 1.5 * self.cfg.bit_cycles {
                        self.rx = Rx::Hunt;
                        self.frame_set_received();
                    } else {
                        self.rx = Rx::Gap { high };
                    }
                }
            }
            Rx::Bit { n, at, edge } => {
                if self.now < at {
                    return;
                }
                match n {
                    0 if line => {
                        self.rx = if self.fields.is_empty() {
                            Rx::Hunt
                        } else {
                            Rx::Gap { high: 0 }
                        }
                    }
                    0 => {
                        self.rx = Rx::Bit {
                            n: 1,
                            at: self.at_bit(edge, 1, 0.5),
                            edge,
                        }
                    }
                    1..=8 => {
                        self.shift |= (line as u8) << (n - 1);
                        if n == 3 && self.fields.is_empty() {
                            let a = self.shift & 0b111;
                            self.for_me =
                                a == self.address() || Some(a) == self.cfg.broadcast_address;
                        }
                        self.rx = Rx::Bit {
                            n: n + 1,
                            at: self.at_bit(edge, n + 1, 0.5),
                            edge,
                        };
                    }
                    _ => {
                        self.fields.push(self.shift);
                        self.stop_error |= !line;
                        self.rx = Rx::Gap { high: 0 };
                    }
                }
            }
        }
    }

    fn begin_field(&mut self) {
        self.shift = 0;
        let edge = self.now;
        self.rx = Rx::Bit {
            n: 0,
            at: self.at_bit(edge, 0, 0.5),
            edge,
        };
    }

    /// The request is complete (its end was a bit and a half ago, minus the stop bit's second half).
    fn frame_set_received(&mut self) {
        let end = self.now - (self.cfg.bit_cycles).round() as u64;
        if !self.fields.is_empty() {
            self.requests += 1;
            self.last_request = Some(Request {
                end,
                fields: self.fields.clone(),
                for_me: self.for_me,
                stop_error: self.stop_error,
                page: self.page,
            });
        }
        if !self.for_me || self.fields.is_empty() {
            return;
        }
        let fields = std::mem::take(&mut self.fields);
        let cf = frames::parse_control_field(fields[0]);
        let broadcast =
            Some(cf.address) == self.cfg.broadcast_address && cf.address != self.address();
        let answer = if !cf.parity_ok || self.stop_error {
            let (ea0, ea1) = self.alarms.ea();
            let status = Status {
                ca0: !cf.parity_ok,
                ca1: self.stop_error,
                ea0,
                ea1,
                ready: true,
                ..Status::default()
            };
            Some(frames::comm_error_answer(fields[0], status))
        } else {
            self.execute(&fields, broadcast)
        };
        if let Some(answer) = answer.filter(|_| !broadcast) {
            self.answer_at = Some((end + self.cfg.answer_delay, answer));
        }
    }

    /// A well-framed request with good parity: check its length and CRC,
    /// then do what it asks (Table 4). `None`: not acknowledged.
    fn execute(&mut self, fields: &[u8], broadcast: bool) -> Option<Vec<u8>> {
        let cf = frames::parse_control_field(fields[0]);
        let id = DataId::from_code(cf.code)?;
        let expected = match id {
            DataId::IdE => 3,
            DataId::IdF => 4,
            _ => 2,
        };
        if fields.len() != expected
            || !frames::channel_crc_ok(fields, frames::CrcKind::Crc8, false)
            || (broadcast && id.is_memory())
        {
            return None;
        }
        let n = self.answered.len() + usize::from(self.answer_at.is_some());
        let mut d = self.answer_data(fields[0]);
        if id.is_repeated() {
            let (last, count, at) = self.repeat;
            let count = if last == Some(id) && self.now <= at + self.cfg.repeat_window {
                count + 1
            } else {
                1
            };
            self.repeat = (Some(id), count, self.now);
            if count == 8 {
                self.repeat = (None, 0, 0);
                self.executed.push(id);
                match id {
                    DataId::IdB => self.st_offset = self.single_turn,
                    DataId::IdC => self.alarms = self.alarms.after_clear(),
                    _ => self.multi_turn = 0,
                }
                d = self.answer_data(fields[0]);
            }
        } else {
            self.repeat = (None, 0, 0);
        }
        if id.is_safety() {
            for j in self
                .cfg
                .settings
                .sequence_jumps
                .iter()
                .filter(|j| j.answer == n)
            {
                if j.channel == 2 {
                    self.sc2 = self.sc2.wrapping_add(1) & 0x7F;
                } else {
                    self.sc1 = self.sc1.wrapping_add(1);
                }
            }
            d.sc1 = self.sc1;
            d.sc2 = self.sc2;
            self.sc1 = self.sc1.wrapping_add(1);
            self.sc2 = self.sc2.wrapping_add(1) & 0x7F;
        }
        d.rs = (i64::from(frames::redundant(d.abs, id)) + i64::from(self.cfg.settings.rs_offset))
            .rem_euclid(if id == DataId::Id6 { 1 << 16 } else { 1 << 9 }) as u16;
        if id.is_memory() {
            let address = fields[1] >> 1;
            let (busy, edf) = self.memory_access(id, address, fields.get(2).copied().unwrap_or(0));
            d.adf = frames::adf(address, busy);
            d.edf = edf;
        }
        if self.cfg.settings.foreign_address_answers.contains(&n) {
            d.cf ^= 0b001;
        }
        Some(frames::answer(id, &d))
    }

    fn answer_data(&self, cf: u8) -> AnswerData {
        let (ea0, ea1) = self.alarms.ea();
        let s = &self.cfg.settings;
        AnswerData {
            cf,
            status: Status {
                ea0,
                ea1,
                temp_warning: self
                    .temp_warning
                    .unwrap_or(s.temperature_c >= s.temperature_warning_c),
                ready: true,
                ..Status::default()
            },
            alm1: self.alarms.byte(),
            alm2: self.alarms.byte(),
            abs: self.single_turn(),
            abm: self.multi_turn,
            rs: 0,
            sc1: 0,
            sc2: 0,
            enid: frames::enid(true, s.enid_mt_bytes, frames::ST_BITS as u8),
            temp: s.temperature_c as u8,
            adf: 0,
            edf: 0,
        }
    }

    /// Table 10: (busy, EDF) for a read or write of `address` on the current page.
    fn memory_access(&mut self, id: DataId, address: u8, data: u8) -> (bool, u8) {
        let busy = self.now < self.busy_until;
        let index = usize::from(self.page & 0xF) * 128 + usize::from(address);
        let register = address == frames::PAGE_REGISTER || self.page == frames::REGISTER_PAGE;
        if id == DataId::IdF {
            if busy {
                return (true, 0x00);
            }
            if address == frames::PAGE_REGISTER {
                self.page = data & 0xF;
                self.busy_until = self.now + self.cfg.page_change;
            } else if register {
                self.memory[index] = data;
            } else {
                self.pending_write = Some((index, data));
                self.busy_until = self.now + self.cfg.eeprom_write;
            }
            self.prefetch = None;
            return (false, data);
        }
        if busy {
            return (true, 0x00);
        }
        if address == frames::PAGE_REGISTER {
            return (false, self.page);
        }
        if register {
            return (false, self.memory[index]);
        }
        // EEPROM: the first read fetches into a holding register (busy, 00);
        // a read of the same address 200 µs later returns it.
        match self.prefetch {
            Some((i, ready)) if i == index && self.now >= ready => {
                self.prefetch = None;
                (false, self.memory[index])
            }
            Some((i, _)) if i == index => (true, 0x00),
            _ => {
                self.prefetch = Some((index, self.now + self.cfg.eeprom_read));
                (true, 0x00)
            }
        }
    }

    /// Sends the pending answer when its time comes, fields back to back.
    fn transmit(&mut self) {
        if !self.driving {
            if let Some((at, _)) = &self.answer_at {
                if self.now >= *at {
                    let (_, fields) = self.answer_at.take().unwrap_or_default();
                    let n = self.answered.len();
                    let s = &self.cfg.settings;
                    let keep = s
                        .truncations
                        .iter()
                        .find(|t| t.answer == n)
                        .map_or(fields.len(), |t| t.fields.min(fields.len()));
                    self.tx_bits = fields[..keep].iter().flat_map(|&b| frame_bits(b)).collect();
                    for f in s.flips.iter().filter(|f| f.answer == n) {
                        if let Some(b) = self.tx_bits.get_mut(f.field * 10 + usize::from(f.bit)) {
                            *b = !*b;
                        }
                    }
                    self.tx_index = 0;
                    self.tx_start = self.now;
                    self.tx_next_at = self.now;
                    self.driving = true;
                    self.answered.push((self.now, fields));
                }
            }
        }
        if self.driving && self.now >= self.tx_next_at {
            if self.tx_index == self.tx_bits.len() {
                self.driving = false;
                self.level = true;
                return;
            }
            self.level = self.tx_bits[self.tx_index];
            self.tx_index += 1;
            self.tx_next_at =
                self.tx_start + (self.tx_index as f64 * self.cfg.bit_cycles).round() as u64;
        }
    }
}

/// The ten bits of one field on the line: start 0, data LSB first, stop 1.
pub fn frame_bits(byte: u8) -> impl Iterator<Item = bool> {
    std::iter::once(false)
        .chain((0..8).map(move |i| (byte >> i) & 1 == 1))
        .chain(std::iter::once(true))
}
