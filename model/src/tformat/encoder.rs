//! A Tamagawa Smart Abs (TS5669 N127, seed 002) as the host sees it on the
//! line: request detection (7.1, 8.1), the answers of Table 2, EEPROM with
//! its busy status (Table 4), the resets sent ten times (9.), and every
//! answer Tables 5 and 6 prescribe for an abnormal request.

use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use serde::{Deserialize, Serialize};

use super::frames::{self, Alarms, DataId, Status};
use crate::line::Drive;

/// What the emulated encoder holds, as a scenario sets it (`[tformat.encoder]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderSettings {
    /// Single-turn position, 17 bits.
    pub single_turn: u32,
    /// Multi-turn count, 16 bits.
    pub multi_turn: u16,
    /// Error flags (ALMC).
    pub alarms: Alarms,
    /// Answer delay after the request's last delimiter, µs (seed: 3 µs typ.).
    pub answer_delay_us: f64,
    /// EEPROM write time, µs (seed: 18 ms max.).
    pub eeprom_write_us: f64,
    /// Shortest interval between the ten reset requests that still counts, µs (seed: 40 ms).
    pub reset_interval_us: f64,
    /// EEPROM contents at start, address 0 first (the rest 0, as shipped).
    pub eeprom: Vec<u8>,
    /// Faults: bits of answers inverted on the line, after the CRC is made.
    pub flips: Vec<AnswerFlip>,
    /// Fault: one answer cut short, the driver off after its first bits.
    pub truncate: Option<AnswerTruncation>,
    /// The answer's bit rate error in percent (positive = encoder fast).
    pub baud_error_percent: f64,
    /// Peak jitter of every edge inside a field against that field's start
    /// edge, ns (seed 002, 6.1: "permissible jitter ±100 ns").
    pub jitter_ns: f64,
    /// Seed of the jitter.
    pub seed: u64,
}

/// One bit of one answer inverted on the line (`[[tformat.encoder.flips]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AnswerFlip {
    /// Which answer (0 = the first the encoder sends).
    pub answer: usize,
    /// Which field of it (0 = CF).
    pub field: usize,
    /// Which of its 10 bits: 0 start, 1..8 data LSB first, 9 delimiter.
    pub bit: u8,
}

/// One answer cut short (`[tformat.encoder.truncate]`): a truncated frame set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AnswerTruncation {
    /// Which answer (0 = the first the encoder sends).
    pub answer: usize,
    /// How many of its bits go on the line before the driver turns off.
    pub bits: usize,
}

impl Default for EncoderSettings {
    fn default() -> Self {
        EncoderSettings {
            single_turn: 0x1_2345,
            multi_turn: 0x0102,
            alarms: Alarms::default(),
            answer_delay_us: 3.0,
            eeprom_write_us: 18_000.0,
            reset_interval_us: 40_000.0,
            eeprom: Vec::new(),
            flips: Vec::new(),
            truncate: None,
            baud_error_percent: 0.0,
            jitter_ns: 0.0,
            seed: 1,
        }
    }
}

/// The encoder's configuration in cycles.
#[derive(Debug, Clone, PartialEq)]
pub struct EncoderConfig {
    /// Clocks per bit of the line.
    pub clocks_per_bit: u64,
    /// Clocks per bit of the answers: `clocks_per_bit / (1 + baud error)`.
    pub answer_bit_clocks: f64,
    /// Peak jitter of the answers' edges in clocks.
    pub jitter_clocks: f64,
    /// Cycles from the end of the request's last delimiter to the answer's start bit.
    pub answer_delay: u64,
    /// Cycles the EEPROM stays busy after an accepted write.
    pub eeprom_write: u64,
    /// Shortest interval between counted reset requests, in cycles.
    pub reset_interval: u64,
    /// Initial state.
    pub settings: EncoderSettings,
}

/// Addresses 0..79 are open to the user (seed 002, 6.1.1).
pub const EEPROM_SIZE: usize = 80;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Rx {
    /// Waiting for a falling edge.
    Hunt,
    /// Sampling bit `n` (0 = start, 9 = delimiter) at `at`.
    Bit { n: u8, at: u64 },
}

/// What the receiver made of the request so far.
#[derive(Debug, Clone, Default)]
struct Request {
    fields: Vec<u8>,
    delimiter_error: bool,
}

/// The emulator. One [`Encoder::step`] is one system-clock cycle.
#[derive(Debug, Clone)]
pub struct Encoder {
    cfg: EncoderConfig,
    single_turn: u32,
    multi_turn: u16,
    alarms: Alarms,
    eeprom: [u8; EEPROM_SIZE],
    busy_until: u64,
    pending_write: Option<(u8, u8)>,
    reset_count: (Option<DataId>, u32, u64),
    pending_reset: Option<(DataId, u64)>,
    now: u64,
    last_level: bool,
    rx: Rx,
    shift: u8,
    request: Request,
    /// The answer being sent: its bits, the cycle each starts at (one more
    /// entry: the driver's end), and the next to send.
    tx_bits: Vec<bool>,
    tx_times: Vec<u64>,
    tx_index: usize,
    rng: Pcg64Mcg,
    answer_at: Option<(u64, Vec<u8>)>,
    driving: bool,
    level: bool,
    answered: Vec<(u64, Vec<u8>)>,
}

impl Encoder {
    /// An encoder at power-on.
    pub fn new(cfg: EncoderConfig) -> Self {
        let mut eeprom = [0u8; EEPROM_SIZE];
        for (i, b) in cfg.settings.eeprom.iter().take(EEPROM_SIZE).enumerate() {
            eeprom[i] = *b;
        }
        Encoder {
            single_turn: cfg.settings.single_turn & 0x1_FFFF,
            multi_turn: cfg.settings.multi_turn,
            alarms: cfg.settings.alarms,
            eeprom,
            busy_until: 0,
            pending_write: None,
            reset_count: (None, 0, 0),
            pending_reset: None,
            now: 0,
            last_level: true,
            rx: Rx::Hunt,
            shift: 0,
            request: Request::default(),
            tx_bits: Vec::new(),
            tx_times: Vec::new(),
            tx_index: 0,
            rng: Pcg64Mcg::seed_from_u64(cfg.settings.seed),
            answer_at: None,
            driving: false,
            level: true,
            answered: Vec::new(),
            cfg,
        }
    }

    /// The shaft turns: new single-turn and multi-turn values.
    pub fn set_position(&mut self, single_turn: u32, multi_turn: u16) {
        self.single_turn = single_turn & 0x1_FFFF;
        self.multi_turn = multi_turn;
    }

    /// Single-turn position now.
    pub fn single_turn(&self) -> u32 {
        self.single_turn
    }

    /// Multi-turn count now.
    pub fn multi_turn(&self) -> u16 {
        self.multi_turn
    }

    /// Error flags now.
    pub fn alarms(&self) -> Alarms {
        self.alarms
    }

    /// Sets the error flags (a testbench's status; the next answer reports them).
    pub fn set_alarms(&mut self, alarms: Alarms) {
        self.alarms = alarms;
    }

    /// Adds a bit flip to a later answer (a testbench's scheduled fault).
    pub fn add_flip(&mut self, flip: AnswerFlip) {
        self.cfg.settings.flips.push(flip);
    }

    /// One EEPROM byte.
    pub fn eeprom(&self, address: usize) -> u8 {
        self.eeprom[address]
    }

    /// Every answer sent so far: (cycle of its first start bit, fields).
    pub fn answered(&self) -> &[(u64, Vec<u8>)] {
        &self.answered
    }

    /// How many of the next steps with the line held at the level of the
    /// last step change nothing but the time (fast-forward): up to the next
    /// bit sample, the answer's start, next bit or end, or a pending EEPROM
    /// write or reset.
    pub fn quiet(&self) -> u64 {
        let until = |t: u64| t.saturating_sub(self.now);
        let write = self
            .pending_write
            .map_or(u64::MAX, |_| until(self.busy_until));
        let reset = self.pending_reset.map_or(u64::MAX, |(_, at)| until(at));
        let receive = match self.rx {
            _ if self.driving => u64::MAX,
            Rx::Hunt => u64::MAX,
            Rx::Bit { at, .. } => until(at),
        };
        let transmit = match (self.driving, &self.answer_at) {
            (true, _) => until(self.tx_times[self.tx_index]),
            (false, Some((at, _))) => until(*at),
            (false, None) => u64::MAX,
        };
        write.min(reset).min(receive).min(transmit)
    }

    /// The same as `n` steps with the last line level, for `n` up to [`Encoder::quiet`].
    pub fn skip(&mut self, n: u64) {
        self.now += n;
    }

    /// One cycle with the line level at the encoder's pins; returns what the
    /// encoder drives (it listens only while it does not drive).
    pub fn step(&mut self, line: bool) -> Drive {
        self.apply_pending();
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

    fn apply_pending(&mut self) {
        if let Some((address, data)) = self.pending_write {
            if self.now >= self.busy_until {
                self.eeprom[address as usize] = data;
                self.pending_write = None;
            }
        }
        if let Some((id, at)) = self.pending_reset {
            if self.now >= at {
                self.execute_reset(id);
                self.pending_reset = None;
            }
        }
    }

    /// Bit-level receiver: a start is the first 0 after idle; if the three
    /// bits after it are not the sink code, the search goes on from the next
    /// falling edge (7.1, 8.1).
    fn receive(&mut self, line: bool) {
        let c = self.cfg.clocks_per_bit;
        match self.rx {
            Rx::Hunt => {
                if self.last_level && !line {
                    self.rx = Rx::Bit {
                        n: 0,
                        at: self.now + c / 2,
                    };
                    self.shift = 0;
                }
            }
            Rx::Bit { n, at } => {
                if self.now < at {
                    return;
                }
                match n {
                    0 if line => self.rx = Rx::Hunt, // glitch
                    0 => self.rx = Rx::Bit { n: 1, at: at + c },
                    1..=8 => {
                        self.shift |= (line as u8) << (n - 1);
                        let first_field = self.request.fields.is_empty();
                        if n == 3 && first_field && self.shift & 0b111 != frames::SINK_CODE {
                            // Table 5/6 no. 1: not for us; keep searching.
                            self.rx = Rx::Hunt;
                            return;
                        }
                        self.rx = Rx::Bit {
                            n: n + 1,
                            at: at + c,
                        };
                    }
                    _ => {
                        self.request.fields.push(self.shift);
                        self.request.delimiter_error |= !line;
                        self.rx = Rx::Hunt;
                        self.field_received(at + c / 2);
                    }
                }
            }
        }
    }

    /// A whole field arrived; `end` is when its delimiter ends.
    fn field_received(&mut self, end: u64) {
        let cf = frames::parse_control_field(self.request.fields[0]);
        let id = DataId::from_code(cf.code);
        let expected = match id {
            Some(DataId::Id6) => 4,
            Some(DataId::IdD) => 3,
            _ => 1,
        };
        // A delimiter error or bad parity ends the request at once (we
        // cannot trust its Data ID to say how many fields follow).
        if self.request.fields.len() < expected && cf.parity_ok && !self.request.delimiter_error {
            return;
        }
        let request = std::mem::take(&mut self.request);
        let answer = self.answer(&request);
        self.answer_at = Some((end + self.cfg.answer_delay, answer));
    }

    /// The answer to a complete request (Tables 2, 4, 5, 6).
    fn answer(&mut self, request: &Request) -> Vec<u8> {
        let cf = frames::parse_control_field(request.fields[0]);
        let mut status = self.alarms.status();
        status.ca0 = !cf.parity_ok;
        status.ca1 = request.delimiter_error;
        let id = DataId::from_code(cf.code).filter(|_| cf.parity_ok && !request.delimiter_error);
        match id {
            Some(id @ (DataId::Id0 | DataId::Id1 | DataId::Id2 | DataId::Id3)) => {
                self.readout(id, status)
            }
            Some(id @ (DataId::Id7 | DataId::Id8 | DataId::IdC)) => {
                self.count_reset(id);
                self.readout(id, status)
            }
            Some(id @ (DataId::Id6 | DataId::IdD)) => {
                let address = request.fields.get(1).copied().unwrap_or(0xFF) & 0x7F;
                let crc_good = frames::crc_ok(&request.fields);
                if !crc_good || address as usize >= EEPROM_SIZE {
                    return self.readout(DataId::Id3, status); // Table 6 no. 2, 6
                }
                let busy = self.now < self.busy_until;
                let edf = if busy {
                    0x00
                } else if id == DataId::Id6 {
                    let data = request.fields[2];
                    self.pending_write = Some((address, data));
                    self.busy_until = self.now + self.cfg.eeprom_write;
                    data
                } else {
                    self.eeprom[address as usize]
                };
                frames::eeprom_answer(id, address, busy, edf)
            }
            // Table 5 no. 2-4, Table 6 no. 3-5: the Data ID 3 answer.
            None => self.readout(DataId::Id3, status),
        }
    }

    fn readout(&self, id: DataId, status: Status) -> Vec<u8> {
        frames::readout(
            id,
            status,
            self.single_turn,
            self.multi_turn,
            self.alarms.byte(),
        )
    }

    /// Ten requests of the same reset, each at least the reset interval after
    /// the one before, execute it; anything else starts the count again.
    fn count_reset(&mut self, id: DataId) {
        let (last_id, count, last_at) = self.reset_count;
        let counts = last_id == Some(id) && self.now >= last_at + self.cfg.reset_interval;
        let count = if counts { count + 1 } else { 1 };
        self.reset_count = (Some(id), count, self.now);
        if count == super::rules::RESET_REQUESTS {
            self.reset_count = (None, 0, 0);
            let delay = if id == DataId::Id8 {
                self.cfg.eeprom_write
            } else {
                0
            };
            self.pending_reset = Some((id, self.now + delay));
        }
    }

    fn execute_reset(&mut self, id: DataId) {
        let a = &mut self.alarms;
        // Latched errors (9.): over-speed, counter overflow, multi-turn error,
        // counting error, battery error.
        let clear_latched = |a: &mut Alarms| {
            a.over_speed = false;
            a.counter_overflow = false;
            a.multi_turn_error = false;
            a.counting_error = false;
            a.battery_error = false;
        };
        match id {
            DataId::Id7 => clear_latched(a),
            DataId::IdC => {
                clear_latched(a);
                self.multi_turn = 0;
            }
            DataId::Id8 => self.single_turn = 0,
            _ => {}
        }
    }

    /// Sends the pending answer when its time comes, back-to-back fields.
    fn transmit(&mut self) {
        if !self.driving {
            if let Some((at, _)) = &self.answer_at {
                if self.now >= *at {
                    let (_, fields) = self.answer_at.take().unwrap_or_default();
                    self.tx_bits = fields.iter().flat_map(|&b| frame_bits(b)).collect();
                    let n = self.answered.len();
                    for f in self.cfg.settings.flips.iter().filter(|f| f.answer == n) {
                        if let Some(b) = self.tx_bits.get_mut(f.field * 10 + f.bit as usize) {
                            *b = !*b;
                        }
                    }
                    if let Some(t) = self
                        .cfg
                        .settings
                        .truncate
                        .as_ref()
                        .filter(|t| t.answer == n)
                    {
                        self.tx_bits.truncate(t.bits);
                    }
                    self.tx_times = self.bit_times(self.now, self.tx_bits.len());
                    self.tx_index = 0;
                    self.driving = true;
                    self.answered.push((self.now, fields));
                }
            }
        }
        if !self.driving {
            return;
        }
        while self.tx_index < self.tx_bits.len() && self.now >= self.tx_times[self.tx_index] {
            self.level = self.tx_bits[self.tx_index];
            self.tx_index += 1;
        }
        if self.tx_index == self.tx_bits.len() && self.now >= self.tx_times[self.tx_index] {
            self.driving = false;
            self.level = true;
        }
    }

    /// The cycle each of `n` bits starts at, and the end: bit `i` starts at
    /// `start + i × answer_bit_clocks` moved by the jitter (not a field's
    /// start edge: the receiver's reference), from the first cycle at or
    /// after that time. At the nominal rate without jitter that is
    /// `start + i × clocks_per_bit`.
    fn bit_times(&mut self, start: u64, n: usize) -> Vec<u64> {
        let (bit, jitter) = (self.cfg.answer_bit_clocks, self.cfg.jitter_clocks);
        let mut times: Vec<u64> = Vec::with_capacity(n + 1);
        for i in 0..=n {
            let j = if jitter > 0.0 && i % 10 != 0 && i < n {
                self.rng.random_range(-jitter..=jitter)
            } else {
                0.0
            };
            let t = start + (i as f64 * bit + j).max(0.0).ceil() as u64;
            times.push(times.last().map_or(t, |&last| t.max(last + 1)));
        }
        times
    }
}

/// The ten bits of one field on the line: start 0, data LSB first, delimiter 1.
pub fn frame_bits(byte: u8) -> impl Iterator<Item = bool> {
    std::iter::once(false)
        .chain((0..8).map(move |i| (byte >> i) & 1 == 1))
        .chain(std::iter::once(true))
}
