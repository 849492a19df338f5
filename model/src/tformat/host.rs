//! The T-format host, cycle by cycle: the machine `hdl/rtl/tformat_host.v`
//! mirrors. The request, turnaround, answer, gap and quiet wait are the
//! shared [`half_duplex::Link`] (with an answer limit and a quiet limit);
//! this file holds T-format's requests, repeats and checks.

use super::frames::{self, DataId};
use crate::half_duplex::{self, End, Link, LinkConfig, Then};
use crate::uart::{self, ReceiverConfig};
use crate::{ConfigError, Result};

pub use crate::half_duplex::QUIET_BITS;

/// The host's configuration in cycles; each field is the Verilog parameter
/// of the same name in upper case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HostConfig {
    /// System clocks per bit (f_sys / 2.5 Mbps).
    pub clocks_per_bit: u64,
    /// Cycles from the end of the request to the answer's start bit before
    /// the host gives up (`o_err_timeout`).
    pub timeout_clocks: u64,
    /// Cycles from one reset request to the next of the ten (seed: ≥ 40 ms).
    pub repeat_gap_clocks: u64,
}

impl HostConfig {
    /// Checks the configuration; field names are those of `[tformat.host]`.
    pub fn validate(&self) -> Result<()> {
        ReceiverConfig {
            clocks_per_bit: self.clocks_per_bit,
        }
        .validate()?;
        if self.timeout_clocks < self.clocks_per_bit {
            return Err(ConfigError::invalid(
                "host.timeout_us",
                "shorter than one bit",
                "wait at least the encoder's 3 µs answer delay plus a bit",
            ));
        }
        if self.repeat_gap_clocks < 20 * self.clocks_per_bit {
            return Err(ConfigError::invalid(
                "host.repeat_gap_us",
                "shorter than a request and its answer",
                "give the seed's 40 000 µs or at least 20 bits",
            ));
        }
        Ok(())
    }
}

/// The host's states; the RTL's `localparam`s will carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// Waiting for `i_start`.
    Idle = 0,
    /// Driving the request.
    Send = 1,
    /// Driver off, waiting for the answer's start bit.
    Wait = 2,
    /// Receiving the answer's fields.
    Recv = 3,
    /// Between two of the ten reset requests.
    Gap = 4,
    /// After a flawed answer: waiting for the line to fall quiet, so that
    /// the next request cannot land on the rest of an answer whose framing
    /// was lost ("never transmit any Request while it transmits the data").
    Quiet = 5,
}

/// The encoder baud errors (percent, positive = encoder fast) between which
/// the host reads every answer without error, when every edge inside a
/// field may move by up to `jitter_cycles` against the field's start edge:
/// the receiver's window ([`uart::tolerance`]), and on the slow side the
/// end-of-set rule: one field's start edge to the next's, `10·T`, must not
/// exceed `HALF + 10·C` (the stop sample at `HALF + 9·C`, then one bit of
/// idle line ends the answer).
pub fn tolerance(clocks_per_bit: u64, jitter_cycles: f64) -> (f64, f64) {
    let (low, high) = uart::tolerance(clocks_per_bit, jitter_cycles);
    (low.max(always_flagged(clocks_per_bit).0), high)
}

/// The encoder baud errors beyond which every answer is flagged, whatever
/// the jitter inside the fields and wherever the edges fall in a clock
/// cycle: slow, the host ends the answer after its first field (`10·T >
/// HALF + 10·C`); fast, the stop sample lands in the next start bit
/// (`10·T ≤ HALF + 9·C`), a framing error.
pub fn always_flagged(clocks_per_bit: u64) -> (f64, f64) {
    let (c, half) = (clocks_per_bit as f64, (clocks_per_bit / 2) as f64);
    (
        (10.0 * c / (half + 10.0 * c) - 1.0) * 100.0,
        (10.0 * c / (half + 9.0 * c) - 1.0) * 100.0,
    )
}

/// Bit times from an answer's first start bit after which the host stops
/// receiving and flags a framing error: the longest answer (11 fields) and
/// one field more. A line held low, or a second driver that keeps sending,
/// cannot keep the host in `Recv`.
pub const ANSWER_LIMIT_BITS: u64 = 10 * (MAX_FIELDS as u64 + 1);

/// Bit times after which `Quiet` gives up waiting for an idle line and ends
/// the operation (its errors are already flagged): by then any answer that
/// was in flight has ended; what still holds the line is a fault, and the
/// user logic must not hang on it.
pub const QUIET_LIMIT_BITS: u64 = ANSWER_LIMIT_BITS;

/// Inputs at one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct In {
    /// Host: start an operation (one-cycle pulse; ignored while busy).
    pub i_start: bool,
    /// Host: the Data ID code (0, 1, 2, 3, 6, 7, 8, C, D).
    pub i_data_id: u8,
    /// Host: EEPROM address (6, D).
    pub i_address: u8,
    /// Host: EEPROM data to write (6).
    pub i_wdata: u8,
    /// Line: the RS-485 receiver output.
    pub i_rx: bool,
}

impl Default for In {
    fn default() -> Self {
        In {
            i_start: false,
            i_data_id: 0,
            i_address: 0,
            i_wdata: 0,
            i_rx: true,
        }
    }
}

/// Registered outputs after one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Out {
    /// Line: the level driven.
    pub o_tx: bool,
    /// Line: RS-485 driver enable.
    pub o_tx_en: bool,
    /// Host: an operation is under way.
    pub o_busy: bool,
    /// Host: one-cycle pulse at the end of an operation, results valid.
    pub o_done: bool,
    /// The answer's control field.
    pub o_cf: u8,
    /// The answer's status field.
    pub o_sf: u8,
    /// Single-turn data (ABS, 17 bits).
    pub o_abs: u32,
    /// Multi-turn data (ABM, 16 bits).
    pub o_abm: u16,
    /// Encoder ID.
    pub o_enid: u8,
    /// ALMC.
    pub o_almc: u8,
    /// EEPROM address field of the answer (bit 7: busy).
    pub o_adf: u8,
    /// EEPROM data field of the answer.
    pub o_edf: u8,
    /// The answer's CRC did not match.
    pub o_err_crc: bool,
    /// No answer began within the timeout.
    pub o_err_timeout: bool,
    /// A framing error, or not the number of fields the request asks for.
    pub o_err_frame: bool,
    /// The answer's control field is not the request's (an abnormal request
    /// answered with Data ID 3 data, or an answer to someone else).
    pub o_err_cf: bool,
    /// ca0 or ca1 set: the encoder saw a parity or delimiter error.
    pub o_err_comm: bool,
}

/// The most fields an answer has (Data ID 3).
pub const MAX_FIELDS: usize = 11;

impl Host {
    /// The input ports, in vector order (the Verilog port names).
    pub fn input_ports() -> Vec<crate::Port> {
        use crate::Port;
        vec![
            Port::new("i_start", 1),
            Port::new("i_data_id", 4),
            Port::new("i_address", 7),
            Port::new("i_wdata", 8),
            Port::new("i_rx", 1).idle_high(),
        ]
    }

    /// The output ports, in vector order (the Verilog port names).
    pub fn output_ports() -> Vec<crate::Port> {
        use crate::Port;
        vec![
            Port::new("o_tx", 1),
            Port::new("o_tx_en", 1),
            Port::new("o_busy", 1),
            Port::new("o_done", 1),
            Port::new("o_cf", 8),
            Port::new("o_sf", 8),
            Port::new("o_abs", 17),
            Port::new("o_abm", 16),
            Port::new("o_enid", 8),
            Port::new("o_almc", 8),
            Port::new("o_adf", 8),
            Port::new("o_edf", 8),
            Port::new("o_err_crc", 1),
            Port::new("o_err_timeout", 1),
            Port::new("o_err_frame", 1),
            Port::new("o_err_cf", 1),
            Port::new("o_err_comm", 1),
        ]
    }
}

impl crate::Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_start as u64;
        dst[1] = (self.i_data_id & 0xF) as u64;
        dst[2] = (self.i_address & 0x7F) as u64;
        dst[3] = self.i_wdata as u64;
        dst[4] = self.i_rx as u64;
    }
}

impl crate::Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        let v = [
            self.o_tx as u64,
            self.o_tx_en as u64,
            self.o_busy as u64,
            self.o_done as u64,
            self.o_cf as u64,
            self.o_sf as u64,
            self.o_abs as u64,
            self.o_abm as u64,
            self.o_enid as u64,
            self.o_almc as u64,
            self.o_adf as u64,
            self.o_edf as u64,
            self.o_err_crc as u64,
            self.o_err_timeout as u64,
            self.o_err_frame as u64,
            self.o_err_cf as u64,
            self.o_err_comm as u64,
        ];
        dst.copy_from_slice(&v);
    }
}

/// T-format's side of the host: the request's Data ID and control field,
/// and the answer's CRC.
#[derive(Debug, Clone)]
pub struct Side {
    id: u8,
    /// The request's control field, for the answer's check.
    req_cf: u8,
    /// The XOR of the answer's fields so far (all of them, also those past
    /// `MAX_FIELDS`).
    crc: u8,
}

/// The host: the half-duplex skeleton (request, turnaround, answer with its
/// limit, gap, quiet wait with its limit) with T-format's [`Side`]. One
/// `step` is one rising edge of the system clock.
pub type Host = half_duplex::Host<Side, MAX_FIELDS>;

impl Host {
    /// A host in its reset state.
    pub fn new(cfg: HostConfig) -> Result<Self> {
        cfg.validate()?;
        half_duplex::Host::with(
            LinkConfig {
                answer_limit_bits: Some(ANSWER_LIMIT_BITS),
                quiet_limit_bits: Some(QUIET_LIMIT_BITS),
                ..LinkConfig::new(
                    cfg.clocks_per_bit,
                    cfg.timeout_clocks,
                    cfg.repeat_gap_clocks,
                )
            },
            Side {
                id: 0,
                req_cf: 0,
                crc: 0,
            },
        )
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        match self.link().state() {
            half_duplex::State::Idle => State::Idle,
            half_duplex::State::Send => State::Send,
            half_duplex::State::Wait => State::Wait,
            half_duplex::State::Recv => State::Recv,
            half_duplex::State::Gap => State::Gap,
            // The T-format host holds no operation after an accepted
            // answer: its `finish` never settles.
            half_duplex::State::Quiet | half_duplex::State::Settle => State::Quiet,
        }
    }

    /// Fields received in the current answer: the first `MAX_FIELDS` of them.
    pub fn fields(&self) -> &[u8] {
        self.link().fields()
    }
}

impl half_duplex::Protocol<MAX_FIELDS> for Side {
    type In = In;
    type Out = Out;

    half_duplex::line_ports!();

    fn field(&mut self, byte: u8) {
        self.crc ^= byte;
    }

    /// Latches the operation `input` asks for and clears the errors.
    fn start(&mut self, input: &In, next: &mut Out) -> (Vec<u8>, u8) {
        self.id = input.i_data_id & 0xF;
        let id = DataId::from_code(self.id);
        let mut bytes = frames::request(id.unwrap_or(DataId::Id0), input.i_address, input.i_wdata);
        // An undefined code is sent as asked: the encoder answers it with
        // Data ID 3 data (Table 5 no. 2).
        bytes[0] = frames::control_field_for_code(self.id);
        self.req_cf = bytes[0];
        let repeats = if id.is_some_and(|d| d.is_reset()) {
            10
        } else {
            1
        };
        next.o_err_crc = false;
        next.o_err_timeout = false;
        next.o_err_frame = false;
        next.o_err_cf = false;
        next.o_err_comm = false;
        (bytes, repeats)
    }

    /// End of one request's answer: check it, publish it, repeat or finish.
    fn finish(&mut self, link: &Link<MAX_FIELDS>, next: &mut Out, end: End) -> Then {
        let timeout = end == End::Timeout;
        let request_cf = self.req_cf;
        let expected = DataId::from_code(self.id).map_or(11, |d| d.answer_fields());
        let f = *link.registers();
        let cf = f[0];
        if !timeout {
            next.o_cf = cf;
            match DataId::from_code((cf >> 3) & 0xF) {
                Some(DataId::Id6 | DataId::IdD) => {
                    next.o_adf = f[1];
                    next.o_edf = f[2];
                }
                received => {
                    next.o_sf = f[1];
                    match received {
                        Some(DataId::Id1) => next.o_abm = u16::from_le_bytes([f[2], f[3]]),
                        Some(DataId::Id2) => next.o_enid = f[2],
                        Some(DataId::Id3) => {
                            next.o_abs = u32::from_le_bytes([f[2], f[3], f[4] & 0x01, 0]);
                            next.o_enid = f[5];
                            next.o_abm = u16::from_le_bytes([f[6], f[7]]);
                            next.o_almc = f[9];
                        }
                        _ => next.o_abs = u32::from_le_bytes([f[2], f[3], f[4] & 0x01, 0]),
                    }
                }
            }
        }
        let sf_comm = !timeout
            && !DataId::from_code((cf >> 3) & 0xF).is_some_and(|d| d.is_eeprom())
            && f[1] & 0xC0 != 0;
        let crc_bad = !timeout && self.crc != 0;
        let frame_bad =
            !timeout && (end == End::Overlong || link.frame_err() || link.count() != expected);
        let cf_bad = !timeout && cf != request_cf;
        next.o_err_timeout |= timeout;
        next.o_err_crc |= crc_bad;
        next.o_err_frame |= frame_bad;
        next.o_err_cf |= cf_bad;
        next.o_err_comm |= sf_comm;
        // The next answer's XOR starts from 0 (every answer ends here).
        self.crc = 0;
        // The gap runs from the end of this answer; the seed asks for 40 ms
        // between requests, which this more than keeps.
        Then::Checked {
            flawed: timeout || crc_bad || frame_bad || cf_bad,
            settle: 0,
        }
    }
}
