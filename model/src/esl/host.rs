//! The ESL host, cycle by cycle: the machine `hdl/rtl/esl_host.v` mirrors.
//! The request, turnaround, answer, gap, settle time and quiet wait are the
//! shared [`half_duplex::Link`]; this file holds ESL's requests, repeats,
//! busy retries, sequence counters and checks.

use super::frames::{self, DataId};
use crate::half_duplex::{self, End, Link, LinkConfig, Then};
use crate::uart::ReceiverConfig;
use crate::{ConfigError, Result};

pub use crate::half_duplex::{State, QUIET_BITS};

/// The host's configuration in cycles; each field is the Verilog parameter
/// of the same name in upper case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HostConfig {
    /// System clocks per bit (f_sys / 10 Mbps).
    pub clocks_per_bit: u64,
    /// Cycles from the end of the request to the answer's start bit before
    /// the host gives up (`o_err_timeout`); after a broadcast, the silence
    /// the host waits for.
    pub timeout_clocks: u64,
    /// Cycles from the end of one answer of an 8-times command to the next
    /// request (seed: "typical interval of 40 µs").
    pub repeat_gap_clocks: u64,
    /// Cycles before a memory read is repeated after a busy answer (seed: 200 µs).
    pub read_wait_clocks: u64,
    /// Cycles after an accepted EEPROM write, or before a write is repeated
    /// after a busy answer (seed: 6 ms).
    pub write_wait_clocks: u64,
    /// Cycles after a write to the page register (seed: 18 ms).
    pub page_wait_clocks: u64,
    /// Requests a memory access may take while the answer says busy.
    pub busy_tries: u64,
    /// Largest difference, in LSBs of RS, between channel 2's redundant
    /// single-turn and channel 1's position.
    pub rs_tolerance: u64,
    /// The address all encoders obey and none answers.
    pub broadcast_address: u64,
}

impl HostConfig {
    /// Checks the configuration; field names are those of `[esl.host]`.
    pub fn validate(&self) -> Result<()> {
        ReceiverConfig {
            clocks_per_bit: self.clocks_per_bit,
        }
        .validate()?;
        let c = self.clocks_per_bit;
        let checks = [
            (
                self.timeout_clocks < c,
                "host.timeout_us",
                "wait at least the encoder's 2 µs answer delay plus a bit",
            ),
            (
                self.repeat_gap_clocks < 2 * c,
                "host.repeat_gap_us",
                "give the seed's 40 µs or at least two bits",
            ),
            (
                self.read_wait_clocks < c,
                "host.read_wait_us",
                "give the seed's 200 µs",
            ),
            (
                self.write_wait_clocks < c,
                "host.write_wait_us",
                "give the seed's 6000 µs",
            ),
            (
                self.page_wait_clocks < c,
                "host.page_wait_us",
                "give the seed's 18000 µs",
            ),
            (
                !(1..=15).contains(&self.busy_tries),
                "host.busy_tries",
                "give 1 to 15 requests (2 read an EEPROM byte)",
            ),
            (
                self.rs_tolerance > 255,
                "host.rs_tolerance",
                "give 0 to 255 LSBs",
            ),
            (
                self.broadcast_address > 7,
                "host.broadcast_address",
                "give an address 0..7",
            ),
        ];
        for (bad, field, fix) in checks {
            if bad {
                return Err(ConfigError::invalid(field, "out of range", fix));
            }
        }
        for (v, field) in [
            (self.timeout_clocks, "host.timeout_us"),
            (self.repeat_gap_clocks, "host.repeat_gap_us"),
            (self.read_wait_clocks, "host.read_wait_us"),
        ] {
            if v >= 1 << 24 {
                return Err(ConfigError::invalid(
                    field,
                    "longer than 2^24 cycles",
                    "give a shorter time",
                ));
            }
        }
        for (v, field) in [
            (self.write_wait_clocks, "host.write_wait_us"),
            (self.page_wait_clocks, "host.page_wait_us"),
        ] {
            if v >= 1 << 24 {
                return Err(ConfigError::invalid(
                    field,
                    "longer than 2^24 cycles",
                    "give at most 200 ms at 80 MHz",
                ));
            }
        }
        Ok(())
    }
}

/// Requests of one 8-times command (Table 4: "minimum 8 times consecutively").
pub const REPEATS: u8 = 8;

/// The most fields an answer has (Data ID 1: 11 + 7).
pub const MAX_FIELDS: usize = 18;

/// Inputs at one rising edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct In {
    /// Host: start an operation (one-cycle pulse; ignored while busy).
    pub i_start: bool,
    /// Host: the Data ID code (Table 3).
    pub i_data_id: u8,
    /// Host: the encoder address 0..7.
    pub i_address: u8,
    /// Host: send to every encoder (the broadcast address), expect no answer.
    pub i_broadcast: bool,
    /// Host: memory address (E, F).
    pub i_mem_address: u8,
    /// Host: data to write (F).
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
            i_broadcast: false,
            i_mem_address: 0,
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
    /// CF1 of the answer.
    pub o_cf: u8,
    /// SF1 of the answer.
    pub o_sf: u8,
    /// SF2 of the answer.
    pub o_sf2: u8,
    /// ALM1.
    pub o_alm1: u8,
    /// ALM2.
    pub o_alm2: u8,
    /// Single-turn (ABS0..2).
    pub o_abs: u32,
    /// Multi-turn (ABM0..1).
    pub o_abm: u16,
    /// Redundant single-turn of channel 2 (9 bits; 16 for Data ID 6).
    pub o_rs: u16,
    /// SC1.
    pub o_sc1: u8,
    /// SC2 (7 bits).
    pub o_sc2: u8,
    /// ENID.
    pub o_enid: u8,
    /// Temperature.
    pub o_temp: u8,
    /// Memory address field (busy in bit 0).
    pub o_adf: u8,
    /// Memory data field.
    pub o_edf: u8,
    /// Channel 1's CRC did not match.
    pub o_err_crc1: bool,
    /// Channel 2's CRC did not match.
    pub o_err_crc2: bool,
    /// No answer began within the timeout.
    pub o_err_timeout: bool,
    /// A bad stop bit, or not the number of fields the request asks for.
    pub o_err_frame: bool,
    /// The answer's CF (or ADF address) is not the request's; or an answer to a broadcast.
    pub o_err_cf: bool,
    /// CA0 or CA1 set: the encoder saw a bad request.
    pub o_err_comm: bool,
    /// SC1 or SC2 is not the previous one plus one.
    pub o_err_seq: bool,
    /// Channel 2's redundant single-turn disagrees with channel 1's position.
    pub o_err_rs: bool,
    /// The memory was still busy after `BUSY_TRIES` requests.
    pub o_err_busy: bool,
}

impl Host {
    /// The input ports, in vector order (the Verilog port names).
    pub fn input_ports() -> Vec<crate::Port> {
        use crate::Port;
        vec![
            Port::new("i_start", 1),
            Port::new("i_data_id", 4),
            Port::new("i_address", 3),
            Port::new("i_broadcast", 1),
            Port::new("i_mem_address", 7),
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
            Port::new("o_sf2", 8),
            Port::new("o_alm1", 8),
            Port::new("o_alm2", 8),
            Port::new("o_abs", 24),
            Port::new("o_abm", 16),
            Port::new("o_rs", 16),
            Port::new("o_sc1", 8),
            Port::new("o_sc2", 7),
            Port::new("o_enid", 8),
            Port::new("o_temp", 8),
            Port::new("o_adf", 8),
            Port::new("o_edf", 8),
            Port::new("o_err_crc1", 1),
            Port::new("o_err_crc2", 1),
            Port::new("o_err_timeout", 1),
            Port::new("o_err_frame", 1),
            Port::new("o_err_cf", 1),
            Port::new("o_err_comm", 1),
            Port::new("o_err_seq", 1),
            Port::new("o_err_rs", 1),
            Port::new("o_err_busy", 1),
        ]
    }
}

impl crate::Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_start as u64;
        dst[1] = u64::from(self.i_data_id & 0xF);
        dst[2] = u64::from(self.i_address & 7);
        dst[3] = self.i_broadcast as u64;
        dst[4] = u64::from(self.i_mem_address & 0x7F);
        dst[5] = u64::from(self.i_wdata);
        dst[6] = self.i_rx as u64;
    }
}

impl crate::Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        let v = [
            self.o_tx as u64,
            self.o_tx_en as u64,
            self.o_busy as u64,
            self.o_done as u64,
            u64::from(self.o_cf),
            u64::from(self.o_sf),
            u64::from(self.o_sf2),
            u64::from(self.o_alm1),
            u64::from(self.o_alm2),
            u64::from(self.o_abs),
            u64::from(self.o_abm),
            u64::from(self.o_rs),
            u64::from(self.o_sc1),
            u64::from(self.o_sc2),
            u64::from(self.o_enid),
            u64::from(self.o_temp),
            u64::from(self.o_adf),
            u64::from(self.o_edf),
            self.o_err_crc1 as u64,
            self.o_err_crc2 as u64,
            self.o_err_timeout as u64,
            self.o_err_frame as u64,
            self.o_err_cf as u64,
            self.o_err_comm as u64,
            self.o_err_seq as u64,
            self.o_err_rs as u64,
            self.o_err_busy as u64,
        ];
        dst.copy_from_slice(&v);
    }
}

/// What the host remembers of one encoder's sequence counters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
struct Sequence {
    known: bool,
    sc1: u8,
    sc2: u8,
}

/// ESL's side of the host: the operation, the busy retries, the page
/// register and the sequence counters.
#[derive(Debug, Clone)]
pub struct Side {
    cfg: HostConfig,
    id: u8,
    address: u8,
    broadcast: bool,
    mem_address: u8,
    wdata: u8,
    /// The request's control field, for the answer's check.
    req_cf: u8,
    tries_left: u64,
    page: u8,
    seq: [Sequence; 8],
}

/// The host: the half-duplex skeleton (request, turnaround, answer, gap,
/// settle time, quiet wait) with ESL's [`Side`]. One `step` is one rising
/// edge of the system clock.
pub type Host = half_duplex::Host<Side, MAX_FIELDS>;

impl Host {
    /// A host in its reset state.
    pub fn new(cfg: HostConfig) -> Result<Self> {
        cfg.validate()?;
        half_duplex::Host::with(
            LinkConfig::new(
                cfg.clocks_per_bit,
                cfg.timeout_clocks,
                cfg.repeat_gap_clocks,
            ),
            Side {
                cfg,
                id: 0,
                address: 0,
                broadcast: false,
                mem_address: 0,
                wdata: 0,
                req_cf: 0,
                tries_left: 0,
                page: frames::DEFAULT_PAGE,
                seq: [Sequence::default(); 8],
            },
        )
    }

    /// The state after the last step.
    pub fn state(&self) -> State {
        self.link().state()
    }

    /// Fields received in the last answer.
    pub fn fields(&self) -> &[u8] {
        self.link().fields()
    }

    /// The request frame set last sent.
    pub fn request(&self) -> &[u8] {
        self.link().request()
    }

    /// The page register as the host last wrote it.
    pub fn page(&self) -> u8 {
        self.protocol().page
    }
}

impl half_duplex::Protocol<MAX_FIELDS> for Side {
    type In = In;
    type Out = Out;

    half_duplex::line_ports!();

    /// Latches the operation `input` asks for and clears the errors.
    fn start(&mut self, input: &In, next: &mut Out) -> (Vec<u8>, u8) {
        self.id = input.i_data_id & 0xF;
        self.broadcast = input.i_broadcast;
        self.address = if input.i_broadcast {
            self.cfg.broadcast_address as u8
        } else {
            input.i_address & 7
        };
        self.mem_address = input.i_mem_address & 0x7F;
        self.wdata = input.i_wdata;
        let set = frames::request(self.address, self.id, self.mem_address, self.wdata);
        self.req_cf = set[0];
        let repeats = if DataId::from_code(self.id).is_some_and(|d| d.is_repeated()) {
            REPEATS
        } else {
            1
        };
        self.tries_left = self.cfg.busy_tries;
        next.o_err_crc1 = false;
        next.o_err_crc2 = false;
        next.o_err_timeout = false;
        next.o_err_frame = false;
        next.o_err_cf = false;
        next.o_err_comm = false;
        next.o_err_seq = false;
        next.o_err_rs = false;
        next.o_err_busy = false;
        (set, repeats)
    }

    /// End of one request's answer (or of its timeout): check it, publish
    /// it, and say whether to retry, repeat, settle, wait for quiet or finish.
    fn finish(&mut self, link: &Link<MAX_FIELDS>, next: &mut Out, end: End) -> Then {
        let timeout = end == End::Timeout;
        let id = DataId::from_code(self.id);
        let bytes = link.fields();
        let flawed;
        let mut settle = 0;
        if self.broadcast {
            // Nobody may answer a broadcast.
            next.o_err_cf |= !timeout;
            flawed = !timeout;
        } else if timeout {
            next.o_err_timeout = true;
            flawed = true;
            self.seq[usize::from(self.address)].known = false;
        } else if let Some(id) = id {
            let d = frames::decode(id, bytes);
            let mut k = frames::check(
                id,
                self.req_cf,
                bytes,
                link.frame_err() || link.count() > MAX_FIELDS,
                self.cfg.rs_tolerance as u16,
            );
            if id.is_memory() && !k.any() {
                k.cf |= d.adf >> 1 != self.mem_address;
                if id == DataId::IdF && d.adf & 1 == 0 && d.edf != self.wdata {
                    k.cf = true;
                }
            }
            next.o_cf = d.cf;
            next.o_sf = d.sf;
            next.o_sf2 = d.sf2;
            next.o_alm1 = d.alm1;
            next.o_alm2 = d.alm2;
            next.o_abs = d.abs;
            next.o_abm = d.abm;
            next.o_rs = d.rs;
            next.o_sc1 = d.sc1;
            next.o_sc2 = d.sc2;
            next.o_enid = d.enid;
            next.o_temp = d.temp;
            next.o_adf = d.adf;
            next.o_edf = d.edf;
            next.o_err_crc1 |= k.crc1;
            next.o_err_crc2 |= k.crc2;
            next.o_err_frame |= k.frame;
            next.o_err_cf |= k.cf;
            next.o_err_comm |= k.comm;
            next.o_err_rs |= k.rs;
            let seq = &mut self.seq[usize::from(self.address)];
            let clean = !(k.crc1 || k.crc2 || k.frame || k.cf || k.comm);
            if id.is_safety() && clean {
                // A counter that is not the previous one plus one means a
                // lost, repeated or stale answer. After an answer that could
                // not be trusted the next good one is the new reference.
                next.o_err_seq |= seq.known
                    && (d.sc1 != seq.sc1.wrapping_add(1) || d.sc2 != (seq.sc2 + 1) & 0x7F);
                *seq = Sequence {
                    known: true,
                    sc1: d.sc1,
                    sc2: d.sc2,
                };
            } else if id.is_safety() {
                seq.known = false;
            }
            flawed = !clean || k.rs;
            if id.is_memory() && clean {
                let busy = d.adf & 1 == 1;
                self.tries_left -= 1;
                if busy && self.tries_left == 0 {
                    next.o_err_busy = true;
                } else if busy {
                    return Then::Retry(if self.id == DataId::IdF.code() {
                        self.cfg.write_wait_clocks
                    } else {
                        self.cfg.read_wait_clocks
                    });
                } else if id == DataId::IdF {
                    settle = if self.mem_address == frames::PAGE_REGISTER {
                        self.page = self.wdata & 0xF;
                        self.cfg.page_wait_clocks
                    } else if self.page == frames::REGISTER_PAGE {
                        0
                    } else {
                        self.cfg.write_wait_clocks
                    };
                }
            }
        } else {
            // A code Table 3 does not list: whatever comes back is not an answer to it.
            next.o_err_cf = true;
            flawed = true;
        }
        Then::Checked { flawed, settle }
    }
}
