//! The decode core of `tbgen decode sar` and of the co-simulation monitor
//! `sar58k24_monitor`: the line at a SAR58K24 asynchronous host and the
//! host's driver enable, turned into the events on it.
//!
//! Every character is read with its parity and stop bit
//! ([`crate::uart::line::chars`]); the host's commands (`BC AA Bx` read,
//! `BC AA Cx` zero) are the characters sent while it drives. The encoder's
//! characters go through the host's own frame finder (`Host`, `host.rs`): a
//! window of the last `L` characters (`L` = 5, 6, 7 for 16, 24, 32 bits) is
//! a frame when it starts `FF <tag>` (`81`, or `Bx` after a command to
//! encoder x when the bus answers echo the address, [`Options::answer_tag`])
//! and ends with the low byte of the sum; while synced (after a
//! frame or an idle gap of `gap_bits`) the `L`-th character must close a
//! frame, else it is flagged and the finder hunts byte by byte; a parity or
//! framing error breaks the frame; a gap with fewer than `L` characters
//! while synced is a truncated frame. Each event carries the characters
//! since the previous one, so the events together hold every character on
//! the line, and the flags have the host's names: `checksum`, `parity`,
//! `frame` (a low stop bit, a header that is not `FF <tag>`, a truncated
//! frame), `address` (`FF By` of another encoder).
//!
//! [`Decoder`] decodes a line piece by piece, cut at idle gaps (what a
//! monitor does, so that a long run keeps one piece in memory); [`decode`]
//! the whole line at once. Both give the same events.

use serde::Serialize;

use super::frames::{self, AnswerTag};
use crate::uart::line::{self, values, Char};
use crate::uart::Parity;
use crate::wire::Signal;

/// What the decoder needs besides the line.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Baud.
    pub baud: f64,
    /// Character format.
    pub parity: Parity,
    /// Resolution (10..32): the frame carries 2, 3 or 4 data bytes.
    pub bits: u32,
    /// Positions are sent in Gray code.
    pub gray: bool,
    /// Idle bit times that end a burst (`[sar.host] gap_bits`).
    pub gap_bits: f64,
    /// The second byte of a bus answer (the encoders' `answer_tag`, the
    /// host's `TAG_ADDRESS`): `Address` expects `Bx` of the last command,
    /// `Fixed81` expects `81` after a command as well (the manual's tables,
    /// [`AnswerTag`]). Frames before any command are `81` either way.
    pub answer_tag: AnswerTag,
}

/// One event on the line: a command, a frame, a flagged fault or a
/// boundary after characters that made no frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Burst {
    /// 0-based event number.
    pub index: usize,
    /// The first character's start bit, ps.
    pub start_ps: u64,
    /// `command` (the host drove it), `frame` (a position accepted), `fault`
    /// (the host flags it) or `noise` (characters that made no frame, ended
    /// by a gap without a flag).
    pub kind: &'static str,
    /// The characters since the previous event.
    pub bytes: Vec<u8>,
    /// A command: `read` or `zero`; `null` for bytes that are no command.
    pub command: Option<&'static str>,
    /// The encoder a command addresses.
    pub address: Option<u8>,
    /// The position of the frame (binary, after Gray decoding).
    pub position: Option<u32>,
    /// Its angle, `360° × a / 2^bits` cut to four decimals.
    pub angle_deg: Option<f64>,
    /// The host's flags: `checksum`, `parity`, `frame`, `address`.
    pub errors: Vec<&'static str>,
}

/// The host's frame finder over characters (`model::sar58k24::Host::step`).
struct Finder {
    options: Options,
    len: usize,
    window: Vec<u8>,
    count: usize,
    synced: bool,
    pending: Vec<Char>,
    last_end_ps: Option<u64>,
    tag: u8,
    out: Vec<Burst>,
}

impl Finder {
    fn emit(&mut self, kind: &'static str, errors: Vec<&'static str>, position: Option<u32>) {
        let start_ps = self.pending.first().map_or(0, |c| c.start_ps);
        let angle_deg = position.map(|v| crate::angle::angle_deg(v as u64, self.options.bits));
        let bytes = values(&self.pending);
        self.pending.clear();
        self.out.push(Burst {
            index: self.out.len(),
            start_ps,
            kind,
            bytes,
            command: None,
            address: None,
            position,
            angle_deg,
            errors,
        });
    }

    /// An idle gap of the host's `GAP_CLOCKS`: a frame boundary.
    fn gap(&mut self) {
        if self.count != 0 {
            if self.synced && self.count < self.len {
                self.emit("fault", vec!["frame"], None);
            }
            self.count = 0;
            self.synced = true;
        }
        if !self.pending.is_empty() {
            self.emit("noise", Vec::new(), None);
        }
    }

    fn char(&mut self, c: Char, bit_ps: u64) {
        let gap_ps = (self.options.gap_bits * bit_ps as f64) as u64;
        if self.last_end_ps.is_some_and(|e| c.start_ps >= e + gap_ps) {
            self.gap();
        }
        // Idle is counted from the receiver's stop-bit sample.
        self.last_end_ps =
            Some(c.start_ps + (self.options.parity.frame_bits() as u64 - 1) * bit_ps + bit_ps / 2);
        self.pending.push(c);
        if c.parity_error || c.framing_error {
            let errors = [(c.parity_error, "parity"), (c.framing_error, "frame")]
                .into_iter()
                .filter(|f| f.0)
                .map(|f| f.1)
                .collect();
            self.count = 0;
            self.synced = false;
            self.emit("fault", errors, None);
            return;
        }
        let l = self.len;
        self.window.remove(0);
        self.window.push(c.value);
        self.count = (self.count + 1).min(l + 1);
        let w = &self.window;
        let header_ok = w[0] == frames::SYNC && w[1] == self.tag;
        if self.count >= l && header_ok && frames::checksum(&w[..l - 1]) == w[l - 1] {
            let data = w[2..l - 1].iter().fold(0u64, |v, &x| (v << 8) | x as u64)
                & ((1u64 << self.options.bits) - 1);
            let v = if self.options.gray {
                crate::gray::from_gray(data)
            } else {
                data
            } as u32;
            self.count = 0;
            self.synced = true;
            self.emit("frame", Vec::new(), Some(v));
        } else if self.count == l && self.synced {
            self.synced = false;
            let error = if w[0] == frames::SYNC
                && w[1] & 0xF0 == 0xB0
                && self.tag & 0xF0 == 0xB0
                && w[1] != self.tag
            {
                "address"
            } else if !header_ok {
                "frame"
            } else {
                "checksum"
            };
            self.emit("fault", vec![error], None);
        }
    }
}

/// A decoder of one line, fed piece by piece (each piece cut where the line
/// has been idle for at least `gap_bits` after a character): the finder's
/// tag (the last command's address) carries over, the event numbers run on.
#[derive(Debug, Clone)]
pub struct Decoder {
    options: Options,
    tag: u8,
    next_index: usize,
    /// The finder as a piece cut between two characters left it
    /// ([`Decoder::feed_carrying`]), for the next piece.
    carried: Option<Carried>,
}

/// What a [`Finder`] holds from one character to the next.
#[derive(Debug, Clone)]
struct Carried {
    window: Vec<u8>,
    count: usize,
    synced: bool,
    pending: Vec<Char>,
    last_end_ps: Option<u64>,
}

impl Decoder {
    /// A decoder with `options`, the tag `81` (no command seen yet).
    pub fn new(options: Options) -> Self {
        Decoder {
            options,
            tag: frames::TAG_81,
            next_index: 0,
            carried: None,
        }
    }

    /// The bit time, ps.
    pub fn bit_ps(&self) -> u64 {
        (1e12 / self.options.baud).round() as u64
    }

    /// The events of the next piece of the line (`line` and the host's
    /// driver enable `tx_en`, both from the piece's start on; the piece ends
    /// with an idle gap, or the line's end).
    pub fn feed(&mut self, line_sig: &Signal, tx_en: &Signal) -> Vec<Burst> {
        self.feed_piece(line_sig, tx_en, false)
    }

    /// [`Decoder::feed`] for a piece cut between two of the encoder's
    /// characters (the line idle, no character under way and none of the
    /// host's before the next of the encoder's): the frame finder's state
    /// carries into the next piece, so the events are those of decoding the
    /// two pieces as one. A monitor asked for its events once per read then
    /// decodes one transaction each time, not everything since the last
    /// idle gap (reads may follow each other closer than that).
    pub fn feed_carrying(&mut self, line_sig: &Signal, tx_en: &Signal) -> Vec<Burst> {
        self.feed_piece(line_sig, tx_en, true)
    }

    /// The events of a piece; `carry`: keep the finder for the next piece
    /// instead of ending the piece with a gap.
    fn feed_piece(&mut self, line_sig: &Signal, tx_en: &Signal, carry: bool) -> Vec<Burst> {
        let options = self.options.clone();
        let bit_ps = self.bit_ps();
        let len = frames::frame_len(options.bits);
        let c = self.carried.take().unwrap_or(Carried {
            window: vec![0; len],
            count: 0,
            synced: true,
            pending: Vec::new(),
            last_end_ps: None,
        });
        let mut f = Finder {
            options: options.clone(),
            len,
            window: c.window,
            count: c.count,
            synced: c.synced,
            pending: c.pending,
            last_end_ps: c.last_end_ps,
            tag: self.tag,
            out: Vec::new(),
        };
        let chars = line::chars(line_sig, Some(tx_en), bit_ps, options.parity);
        let mut k = 0;
        while k < chars.len() {
            if chars[k].from_host {
                // The host is deaf while it drives: its command is one event. Its
                // characters end at an idle gap, as the encoder's do: two commands
                // with no answer between them (the host timed out on the first)
                // are two events, not one unreadable six-byte command.
                let gap_ps = (options.gap_bits * bit_ps as f64) as u64;
                let mut n = 1;
                while chars.get(k + n).is_some_and(|c| {
                    c.from_host
                        && c.start_ps < chars[k + n - 1].end_ps(bit_ps, options.parity) + gap_ps
                }) {
                    n += 1;
                }
                f.gap();
                let cmd = &chars[k..k + n];
                let bytes = values(cmd);
                let (command, address) = match frames::parse_command(&bytes) {
                    Some(frames::Command::Read(a)) => (Some("read"), Some(a)),
                    Some(frames::Command::Zero(a)) => (Some("zero"), Some(a)),
                    None => (None, None),
                };
                if let Some(a) = address {
                    // As the host: `TAG_ADDRESS ? {4'hB, i_address} : 8'h81`.
                    f.tag = frames::tag_byte(options.answer_tag, true, a);
                }
                f.out.push(Burst {
                    index: f.out.len(),
                    start_ps: cmd[0].start_ps,
                    kind: "command",
                    bytes,
                    command,
                    address,
                    position: None,
                    angle_deg: None,
                    errors: Vec::new(),
                });
                k += n;
            } else {
                f.char(chars[k], bit_ps);
                k += 1;
            }
        }
        if carry {
            self.carried = Some(Carried {
                window: std::mem::take(&mut f.window),
                count: f.count,
                synced: f.synced,
                pending: std::mem::take(&mut f.pending),
                last_end_ps: f.last_end_ps,
            });
        } else {
            f.gap();
        }
        self.tag = f.tag;
        let mut out = f.out;
        for b in &mut out {
            b.index += self.next_index;
        }
        self.next_index += out.len();
        out
    }
}

/// Decodes the whole line `line_sig` at the host, with the host's driver enable `tx_en`.
pub fn decode(line_sig: &Signal, tx_en: &Signal, options: &Options) -> Vec<Burst> {
    Decoder::new(options.clone()).feed(line_sig, tx_en)
}
