//! The BiSS-C control frame: register read and write, one bit per frame.
//!
//! The seed says nothing about it beyond the CDS bit; this layout follows the
//! public BiSS C protocol description (register access with `CTS = 1`), as
//! vendor manuals and MCU reference manuals restate it (see
//! `docs/timing/biss.md` for the sources and the choices made here).
//!
//! The master sends one control bit per frame, **CDM**, as the inverted MA
//! level during the BiSS timeout. Every slave answers with its **CDS** bit at
//! the head of its part of the next frame: the CDS of frame `k + 1` answers
//! the CDM of frame `k`. Index `k` counts frames from the master's start bit.
//!
//! ```text
//!  k     0  1   2..4     5..11    12..15   16 17 18  19..26      27..30    31  32
//!  CDM   S  CTS ID2..ID0 A6..A0   C3..C0   R  W  S   D7..D0 (wr) C3..C0(wr) P   0
//!  CDS   0  0   0        0        0        0  R  W   S           D7..D0    C3..C0 P
//!                                                    (k = 19)    (20..27)  (28..31) (32)
//! ```
//! * At least 14 frames with `CDM = 0` come before `S`; 14 zeros also cancel
//!   a control frame at any point (a read holds CDM at 0 for only 13 frames).
//! * `CTS = 1`: register access. `ID` is the slave's 3-bit ID (here its chain
//!   position unless configured), `A6..A0` the register address.
//! * The address CRC `C3..C0` is [`crate::crc::BISS_CTRL_CRC4`] over CTS, ID
//!   and ADR (11 bits, MSB first), sent inverted. The data CRC is the same
//!   algorithm over the 8 data bits.
//! * Read: `R W = 1 0`; the master sends 0 from `k = 19` to 31. Write:
//!   `R W = 0 1`, then the data and its CRC.
//! * The addressed slave echoes R and W (`k = 17, 18`) only if CTS = 1, the
//!   ID is its own and the address CRC is right; then its start bit (`k = 19`),
//!   the 8 data bits (the register on a read, the received data on a write)
//!   and their CRC. A write is carried out when the slave has received a
//!   data CRC that matches. Every other slave keeps CDS at 0.
//! * The master fails the access (`o_reg_err`) when R, W or S is not echoed,
//!   the returned CRC-4 is wrong, a write echo differs from the data sent, the
//!   stop bit is not 0, or a frame of the access fails.
//!
//! # Commands (`CTS = 0`)
//!
//! ```text
//!  k     0  1   2..9       10 11      12..15  16  17  18
//!  CDM   S  0   IDS7..IDS0 CMD1 CMD0  C3..C0  0   EX  0
//!  CDS   0  0   0          0          0       IDA 0   EX (echo)
//! ```
//! * `IDS` selects slaves by ID, one bit each (bit `i` = ID `i`); `IDS = 0`
//!   is a broadcast to every slave. `CMD` is the 2-bit command. The CRC-4
//!   covers CTS, IDS and CMD: 11 bits, as the address CRC of a register access.
//! * Every selected slave whose CRC-4 matched answers `IDA = 1` (`k = 16`);
//!   the master sends `EX = 1` only when every selected slave did (else the
//!   command fails there), and each selected slave echoes EX (`k = 18`) and
//!   carries the command out at the end of that frame's timeout.

/// Consecutive `CDM = 0` frames that precede a start bit and cancel a frame.
pub const SYNC_ZEROS: u32 = 14;
/// Index of the address CRC's first bit.
pub const K_ADDR_CRC: u32 = 12;
/// Index of R.
pub const K_R: u32 = 16;
/// Index of W.
pub const K_W: u32 = 17;
/// Index of the master's data start bit (and the slave's answering start).
pub const K_S2: u32 = 18;
/// Index of the first data bit the master sends (write).
pub const K_DATA: u32 = 19;
/// Index of the first data-CRC bit the master sends (write).
pub const K_DATA_CRC: u32 = 27;
/// Index of the stop bit.
pub const K_P: u32 = 31;
/// The last index of a control frame as the master sees it (the slave's stop bit arrives).
pub const K_LAST: u32 = 32;

/// Index of a command's IDA answer.
pub const K_IDA: u32 = 16;
/// Index of a command's execute bit EX.
pub const K_EX: u32 = 17;
/// The last index of a command (the EX echo arrives).
pub const K_CMD_LAST: u32 = 18;

/// One control-frame operation as the host asks for it: a register access,
/// or a command (`CTS = 0`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Access {
    /// A command (`CTS = 0`) instead of a register access.
    pub command: bool,
    /// Command: the slave-select bits IDS (0 = broadcast).
    pub ids: u8,
    /// Command: the 2-bit command CMD.
    pub code: u8,
    /// Write (`true`) or read.
    pub write: bool,
    /// Slave ID, 0 to 7.
    pub id: u8,
    /// Register address, 0 to 127.
    pub addr: u8,
    /// Data to write (ignored on a read).
    pub wdata: u8,
}

/// The 11 address-CRC bits (CTS = 1, ID, ADR), MSB first.
pub fn address_bits(id: u8, addr: u8) -> Vec<bool> {
    let mut bits = vec![true];
    bits.extend((0..3).rev().map(|i| (id >> i) & 1 == 1));
    bits.extend((0..7).rev().map(|i| (addr >> i) & 1 == 1));
    bits
}

/// The 11 CRC-covered bits of a command (CTS = 0, IDS, CMD), MSB first.
pub fn command_bits(ids: u8, code: u8) -> Vec<bool> {
    let mut bits = vec![false];
    bits.extend((0..8).rev().map(|i| (ids >> i) & 1 == 1));
    bits.extend((0..2).rev().map(|i| (code >> i) & 1 == 1));
    bits
}

/// Whether a command's IDS selects the slave with ID `id`.
pub fn selects(ids: u8, id: u8) -> bool {
    ids == 0 || (id < 8 && (ids >> id) & 1 == 1)
}

/// The 8 data bits, MSB first.
pub fn data_bits(data: u8) -> Vec<bool> {
    (0..8).rev().map(|i| (data >> i) & 1 == 1).collect()
}

/// The whole CDM sequence of one access, `k = 0..=K_LAST` (the frame that
/// brings the slave's stop bit carries a 0), for transcripts and tests; the
/// master builds it bit-serially.
pub fn cdm_sequence(a: &Access) -> Vec<bool> {
    let crc = &crate::crc::BISS_CTRL_CRC4;
    if a.command {
        let bits = command_bits(a.ids, a.code);
        let mut v = vec![true];
        v.extend(&bits);
        v.extend(crc.wire_bits(crc.checksum_bits(&bits)));
        v.extend([false, true, false]);
        return v;
    }
    let addr = address_bits(a.id, a.addr);
    let mut v = vec![true];
    v.extend(&addr);
    v.extend(crc.wire_bits(crc.checksum_bits(&addr)));
    v.push(!a.write);
    v.push(a.write);
    v.push(true);
    if a.write {
        let d = data_bits(a.wdata);
        v.extend(&d);
        v.extend(crc.wire_bits(crc.checksum_bits(&d)));
    } else {
        v.extend([false; 12]);
    }
    v.push(false);
    v.push(false);
    v
}

/// What one frame showed of the control frame, as a line observer sees it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FrameView {
    /// The frame completed (ack, start bit, every section, SLO released).
    pub ok: bool,
    /// Its CDM bit (the inverted MA level after the last clock).
    pub cdm: bool,
    /// CDS bit of each slave in chain order (`false` past the chain's end).
    pub cds: [bool; super::MAX_SLAVES],
    /// CRC error of each slave.
    pub crc_bad: [bool; super::MAX_SLAVES],
    /// Slaves in the frame (a command's broadcast selects them all).
    pub slaves: usize,
}

/// A register access as the line shows it: what [`Access`] the CDM bits
/// asked for and how the addressed slave answered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Observed {
    /// The access read off the CDM bits (`wdata` 0 on a read).
    pub access: Access,
    /// The data the slave sent back (read value or write echo), as far as it came.
    pub rdata: u8,
    /// The access succeeded by the master's rules.
    pub ok: bool,
    /// `false` when the answer's CRC-4 was wrong.
    pub crc4_ok: bool,
    /// The control index of the frame that ended it.
    pub last_k: u32,
}

/// Follows control frames off decoded frames, by the master's rules (the
/// sequencer of `Master` and `biss_master`): 14 completed frames with CDM = 0
/// arm it, a CDM = 1 then is `k = 0`, and the access ends at `k = 32` or at
/// the first missing echo, failed frame or CRC error of the addressed slave.
/// Used by `tbgen decode biss`, where only the line is known.
#[derive(Debug, Clone, Default)]
pub struct Observer {
    zeros: u32,
    k: Option<u32>,
    acc: Access,
    rdata: u8,
    crc_rx: Vec<bool>,
    crc_bad: bool,
}

impl Observer {
    /// The control index of a frame about to be read (`Some(k)` inside a
    /// control frame), given its CDM bit.
    pub fn index(&self, cdm: bool) -> Option<u32> {
        match self.k {
            Some(k) => Some(k),
            None => (cdm && self.zeros >= SYNC_ZEROS).then_some(0),
        }
    }

    /// Takes one frame; returns the access it ended, if any.
    pub fn take(&mut self, f: &FrameView) -> Option<Observed> {
        let started = self.index(f.cdm);
        self.zeros = match (f.ok, f.cdm) {
            (true, true) => 0,
            (true, false) => (self.zeros + 1).min(SYNC_ZEROS),
            (false, _) => self.zeros,
        };
        let k = started?;
        if k == 0 {
            *self = Observer {
                zeros: self.zeros,
                k: Some(0),
                ..Observer::default()
            };
        }
        let a = &mut self.acc;
        match k {
            1 => a.command = !f.cdm,
            2..=9 if a.command => a.ids = (a.ids << 1) | f.cdm as u8,
            10..=11 if a.command => a.code = (a.code << 1) | f.cdm as u8,
            2..=4 => a.id = (a.id << 1) | f.cdm as u8,
            5..=11 => a.addr = (a.addr << 1) | f.cdm as u8,
            K_W => a.write = f.cdm,
            19..=26 => a.wdata = (a.wdata << 1) | f.cdm as u8,
            _ => {}
        }
        if a.command {
            let selected: Vec<usize> = (0..f.slaves.min(super::MAX_SLAVES))
                .filter(|&i| selects(a.ids, i as u8))
                .collect();
            let all_cds = !selected.is_empty() && selected.iter().all(|&i| f.cds[i]);
            let crc_bad = selected.iter().any(|&i| f.crc_bad[i]);
            let end = match k {
                _ if !f.ok || crc_bad => Some(false),
                K_IDA if !all_cds => Some(false),
                K_CMD_LAST => Some(all_cds),
                _ => None,
            };
            return self.finish(k, end);
        }
        let slave = a.id as usize;
        let cds = slave < super::MAX_SLAVES && f.cds[slave];
        let crc_bad = slave < super::MAX_SLAVES && f.crc_bad[slave];
        let write = a.write;
        let mut end = None;
        if !f.ok || crc_bad {
            end = Some(false);
        } else {
            match k {
                K_W if cds == write => end = Some(false),
                K_S2 if cds != write => end = Some(false),
                K_DATA if !cds => end = Some(false),
                20..=27 => {
                    self.rdata = (self.rdata << 1) | cds as u8;
                    self.crc_rx.push(cds);
                }
                28..=31 => self.crc_rx.push(cds),
                K_LAST => {
                    let crc = &crate::crc::BISS_CTRL_CRC4;
                    self.crc_bad = crc.crc_from_wire_bits(&self.crc_rx[8..])
                        != Some(crc.checksum_bits(&self.crc_rx[..8]));
                    end = Some(!(self.crc_bad || cds || (write && self.rdata != a.wdata)));
                }
                _ => {}
            }
        }
        self.finish(k, end)
    }

    fn finish(&mut self, k: u32, end: Option<bool>) -> Option<Observed> {
        match end {
            Some(ok) => {
                self.k = None;
                Some(Observed {
                    access: self.acc,
                    rdata: self.rdata,
                    ok,
                    crc4_ok: !self.crc_bad,
                    last_k: k,
                })
            }
            None => {
                self.k = Some(k + 1);
                None
            }
        }
    }
}
