//! The ESL host's rules (seed 000, QS35 ESL Safety serial protocol), in the
//! shape of [`crate::rules`]: every rule the emulator and the monitor hold a
//! host to, decided once by [`Watch`], which both feed with the host's
//! transceiver pins (DI, DE, RO) and whose breaches both print.
//!
//! A request is the frames the host's driver sends while its enable DE is
//! on (start 0, 8 data LSB first, end bit 1, 100 ns a bit at 10 Mbps); the
//! shared checks of character timing, back-to-back frames, release and
//! answer are [`crate::half_duplex::watch`]'s, this module adds the frame
//! count of the Data ID and the spacing of requests per encoder address:
//!
//! ```text
//!  DE   _/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\____________________________/‾‾‾‾‾‾‾‾\___ ...
//!  DI/RO ‾\_RCF_/\_ADF_/\CRC_/‾‾‾‾‾‾‾‾\_answer_/‾‾‾‾‾‾‾‾‾‾‾‾\_RCF_/‾‾‾‾
//!         |<- bit grid, 3 % ->|<=1 us|                      |
//!                             |<- B, C, D: within the repeat window;
//!                                 EEPROM read > 200 us, write > 6 ms,
//!                                 after a page change 18 ms -->|
//! ```
//!
//! Spacing is measured between the ends of the requests' last frames (each
//! its frame's start edge and 10 bits), per encoder address (EAD0..2 of
//! RCF), for requests whose RCF parity holds.

use std::sync::OnceLock;

use super::frames::{self, DataId};
use super::REPEATS;
use crate::half_duplex::watch::{self, Request};
use crate::rules::{self, Bound, Breach, Rule, Settable, Unit};
use crate::ConfigError;

/// A section of the seed, as a rule names it.
macro_rules! seed {
    ($s:literal) => {
        concat!("seed 000 QS35 ESL, ", $s)
    };
}

/// Every edge of a request on the bit grid.
pub static BIT_RATE: Rule = Rule {
    protocol: "esl",
    name: "bit rate",
    section: seed!("Table 1 and Figure 1"),
    seed_words: "Communication Baud Rate 10 Mbps; Frame Length 10 bits/Frame; Start Bit: Indicating the start of Frame, always \"0\"; End Bit: Indicating end of Frame, always \"1\"",
    quantity: "request edge off the bit grid",
    bound: Bound::Form,
    measured: "every edge of a request frame from the frame's start edge (the first 0 after idle): its distance from the nearest whole bit, within `checks.bit_tolerance_percent` (3 %) of the time since the start edge; the end bit high at its middle and a full bit long; DE not released inside a frame",
    reading: "the seed states the rate but no tolerance: 3 % is what an RS-485 UART sampling mid-bit takes with room for the encoder's own error (`checks.bit_tolerance_percent`, `monitor.bit_tolerance_percent`, 0 to 20)",
    settable: None,
    label: OnceLock::new(),
};

/// A request's frames back to back.
pub static END_OF_FRAME_SET: Rule = Rule {
    protocol: "esl",
    name: "end of frame set",
    section: seed!("Figure 1"),
    seed_words: "After the Command Frame detected, if there is no Start Bit after the End Bit of the last frame read, and subsequent CRC frame detected, end of transmission frame set concluded.",
    quantity: "a request's frames back to back",
    bound: Bound::Form,
    measured: "the end of an end bit (its frame's start edge and 10 bits) to the next start bit while DE stays on",
    reading: "the project's reading: the encoder ends the frame set when no start bit follows an end bit, so a request split by a pause is two; the next start bit is held within `monitor.max_gap_bits` (0.5 bit) of the end bit's end",
    settable: None,
    label: OnceLock::new(),
};

/// The frames a Data ID takes.
pub static FRAMES: Rule = Rule {
    protocol: "esl",
    name: "request frames",
    section: seed!("Figures 1, 3 and 5"),
    seed_words: "RCF: Request Control Frame (Host Command) ... ADF: Memory Address Data Frame indicates the EEPROM memory location to write. ... EDF: Encoder Memory Data Frame where the data write into EEPROM.",
    quantity: "the frames of the request's Data ID",
    bound: Bound::Form,
    measured: "the frames sent while DE was on, against the Data ID of the first (RCF)",
    reading: "the house reads a request as RCF and CRC, Data ID E as RCF ADF CRC and Data ID F as RCF ADF EDF CRC (`frames::request`)",
    settable: None,
    label: OnceLock::new(),
};

/// The host's driver off before the answer.
pub static RELEASE: Rule = Rule {
    protocol: "esl",
    name: "release",
    section: seed!("Figure 2"),
    seed_words: "Upon the Host issuing a RCF request, after 2.0 μs (typical), the encoder shall respond with Encoder Data Frames set",
    quantity: "DE on after the last end bit",
    bound: Bound::AtMost(1.0, Unit::Us),
    measured: "the end of the request's last end bit (its frame's start edge and 10 bits) to the first sample with DE off",
    reading: "the project's reading: the host releases the line within half the typical answer delay, so that the answer never meets its driver; a configuration may set 0 to 2 us (`monitor.release_us`)",
    settable: Some(Settable { lo: 0.0, hi: 2.0 }),
    label: OnceLock::new(),
};

/// The host's driver off while an encoder answers.
pub static HALF_DUPLEX: Rule = Rule {
    protocol: "esl",
    name: "half duplex",
    section: seed!("Table 1"),
    seed_words: "Communication Type Half duplex",
    quantity: "the host's driver off while an encoder answers",
    bound: Bound::Form,
    measured: "DE switched on less than 11 bits after the start bit of an answer's last frame at the host, or on while the host's receiver hears a 0 against a 1 of its driver (both drivers on)",
    reading: "",
    settable: None,
    label: OnceLock::new(),
};

/// B, C, D eight times in a row.
pub static REPEAT: Rule = Rule {
    protocol: "esl",
    name: "repeat",
    section: seed!("Table 4"),
    seed_words: "Transmit request minimum 8 times consecutively at a typical interval of 40μs to encoder",
    quantity: "interval between the repeats of B, C, D",
    bound: Bound::AtMost(200.0, Unit::Us),
    measured: "end to end of successive requests of one Data ID (B, C, D) to one address; eight of them before another request to that address",
    reading: "\"consecutively\": the bound is the encoder's `repeat_window_us` (200 us, five typical intervals, by default), a device property",
    settable: None,
    label: OnceLock::new(),
};

/// EEPROM reads apart.
pub static READ: Rule = Rule {
    protocol: "esl",
    name: "EEPROM read",
    section: seed!("Figure 3"),
    seed_words: "User need to wait more than 200us between each memory read operation. The 200us is EEPROM read time.",
    quantity: "interval between EEPROM reads",
    bound: Bound::MoreThan(200.0, Unit::Us),
    measured: "end to end of successive Data ID E requests to one address, neither to the page register nor in the register page 8",
    reading: "the bound is the encoder's `eeprom_read_us` (the seed's 200 us by default), a device property",
    settable: None,
    label: OnceLock::new(),
};

/// EEPROM writes apart.
pub static WRITE: Rule = Rule {
    protocol: "esl",
    name: "EEPROM write",
    section: seed!("Figure 5"),
    seed_words: "User need to wait more than 6ms between each memory write operation. The 6ms is EEPROM writing time and busy will return high.",
    quantity: "interval between EEPROM writes",
    bound: Bound::MoreThan(6.0, Unit::Ms),
    measured: "end to end of successive Data ID F requests to one address, neither to the page register nor in the register page 8",
    reading: "the bound is the encoder's `eeprom_write_us` (the seed's 6 ms by default), a device property",
    settable: None,
    label: OnceLock::new(),
};

/// A page change before the next memory access.
pub static PAGE: Rule = Rule {
    protocol: "esl",
    name: "page change",
    section: seed!("Table 11 note 3"),
    seed_words: "Once the page value is changed, allow a 18ms delay.",
    quantity: "a memory access after a page-register write",
    bound: Bound::AtLeast(18.0, Unit::Ms),
    measured: "end to end of a Data ID F request to the page register (7Fh) and the next Data ID E or F request to that address",
    reading: "\"allow\": read inclusively; the bound is the encoder's `page_change_us` (the seed's 18 ms by default), a device property",
    settable: None,
    label: OnceLock::new(),
};

/// The ESL rules, in the order of the seed.
pub static RULES: &[&Rule] = &[
    &BIT_RATE,
    &HALF_DUPLEX,
    &END_OF_FRAME_SET,
    &FRAMES,
    &RELEASE,
    &READ,
    &WRITE,
    &REPEAT,
    &PAGE,
];

/// The rules the shared half-duplex checks report under.
const SHARED: watch::Rules = watch::Rules {
    character: &BIT_RATE,
    gap: &END_OF_FRAME_SET,
    release: &RELEASE,
    answer: &HALF_DUPLEX,
};

/// One encoder address's spacing bounds, ps (its device times).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Spacing {
    /// Longest interval between repeats ([`REPEAT`]).
    pub repeat_window: u64,
    /// EEPROM read time ([`READ`]).
    pub read: u64,
    /// EEPROM write time ([`WRITE`]).
    pub write: u64,
    /// Page change time ([`PAGE`]).
    pub page_change: u64,
}

impl Spacing {
    /// From an encoder's times in µs: repeat window, EEPROM read, EEPROM
    /// write, page change.
    pub fn of_us(repeat_window: f64, read: f64, write: f64, page_change: f64) -> Self {
        Spacing {
            repeat_window: Unit::Us.ps(repeat_window),
            read: Unit::Us.ps(read),
            write: Unit::Us.ps(write),
            page_change: Unit::Us.ps(page_change),
        }
    }

    /// An encoder's (`[[encoders]]`).
    pub fn of(e: &super::EncoderSettings) -> Self {
        Spacing::of_us(
            e.repeat_window_us,
            e.eeprom_read_us,
            e.eeprom_write_us,
            e.page_change_us,
        )
    }
}

impl Default for Spacing {
    /// The seed's encoder.
    fn default() -> Self {
        Spacing::of(&super::EncoderSettings::default())
    }
}

/// The bounds in force, ps.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// The shared checks'.
    pub line: watch::Limits,
    /// Spacing per encoder address (EAD 0 to 7).
    pub spacing: [Spacing; 8],
}

impl Limits {
    /// The seed's bounds at `baud` bit/s with `tolerance_percent` on the
    /// bit grid, every address at the seed's encoder times.
    pub fn seed(baud: f64, tolerance_percent: f64) -> Self {
        let Bound::AtMost(release, r) = RELEASE.bound else {
            unreachable!("the release is a greatest time")
        };
        let bit_ps = 1e12 / baud;
        Limits {
            line: watch::Limits {
                bit_ps,
                tolerance: tolerance_percent / 100.0,
                jitter_ps: 0.0,
                max_gap_ps: 0.5 * bit_ps,
                release_ps: r.ps(release),
            },
            spacing: [Spacing::default(); 8],
        }
    }

    /// The release set to `us` (field `field`), within [`RELEASE`]'s range.
    pub fn set_release(&mut self, field: &str, us: f64) -> Result<(), ConfigError> {
        self.line.set_release(&RELEASE, field, us)
    }

    /// The least lengths, for [`rules::resolution_notes`]: the drift the
    /// tolerance allows at a frame's end bit, and the release.
    pub fn least(&self) -> Vec<(&'static Rule, u64)> {
        vec![
            (
                &BIT_RATE,
                (self.line.tolerance * 10.0 * self.line.bit_ps) as u64,
            ),
            (&RELEASE, self.line.release_ps),
        ]
    }
}

/// One address's spacing as the watcher follows it.
#[derive(Debug, Clone, Default)]
struct Follow {
    page: u8,
    /// B/C/D in progress: Data ID, requests so far, end of the last.
    repeat: Option<(u8, u32, u64)>,
    last_read: Option<u64>,
    last_write: Option<u64>,
    page_write: Option<u64>,
}

/// The ESL checks of whole requests: the frame count, the spacing per address.
#[derive(Debug, Clone)]
pub struct Requests {
    spacing: [Spacing; 8],
    follow: [Follow; 8],
}

/// The ESL watcher: the host's transceiver pins ([`watch::Host::sample`]).
pub type Watch = watch::Host<Requests>;

/// A watcher holding the host to `limits`.
pub fn watch(limits: Limits) -> Watch {
    let follow = Follow {
        page: frames::DEFAULT_PAGE,
        ..Follow::default()
    };
    let requests = Requests {
        spacing: limits.spacing,
        follow: std::array::from_fn(|_| follow.clone()),
    };
    watch::Host::with(limits.line, SHARED, requests)
}

impl watch::Requests for Requests {
    fn request(&mut self, r: &Request, out: &mut Vec<Breach>) {
        let Some(&byte) = r.fields.first() else {
            return;
        };
        let cf = frames::parse_control_field(byte);
        let id = DataId::from_code(cf.code);
        if id.is_some() && !r.damaged {
            let want = frames::request(0, cf.code, 0, 0).len();
            if r.fields.len() != want {
                out.push(FRAMES.breach(
                    r.end_ps,
                    format!(
                        "a request of {} frame(s) for Data ID {:X}, which takes {want}",
                        r.fields.len(),
                        cf.code
                    ),
                ));
            }
        }
        if !cf.parity_ok {
            return;
        }
        let a = usize::from(cf.address & 7);
        let (lim, s) = (self.spacing[a], &mut self.follow[a]);
        let end = r.end_ps;
        let us = |ps: u64| ps as f64 / 1e6;
        match (s.repeat, id.filter(|d| d.is_repeated())) {
            (Some((rid, k, at)), Some(_)) if rid == cf.code => {
                if end - at > lim.repeat_window {
                    out.push(REPEAT.breach(end, format!("request {} of Data ID {:X} to address {} {:.3} us after the one before, beyond the encoder's repeat window of {:.3} us (the count starts again)", k + 1, cf.code, cf.address, us(end - at), us(lim.repeat_window))));
                    s.repeat = Some((rid, 1, end));
                } else {
                    s.repeat = (k + 1 < u32::from(REPEATS)).then_some((rid, k + 1, end));
                }
            }
            (prev, now_id) => {
                if let Some((rid, k, _)) = prev {
                    out.push(REPEAT.breach(end, format!("Data ID {rid:X} sent {k} time(s) to address {}, then Data ID {:X}: the command takes {REPEATS} in a row", cf.address, cf.code)));
                }
                s.repeat = now_id.map(|_| (cf.code, 1, end));
            }
        }
        let Some(id) = id.filter(|d| d.is_memory()) else {
            return;
        };
        let address = r.fields.get(1).map_or(0, |a| a >> 1);
        if let Some(c) = s
            .page_write
            .map(|t| end - t)
            .filter(|&c| rules::short(c, lim.page_change, false))
        {
            out.push(PAGE.breach(end, format!("a memory access {:.3} us after a write to the page register; the page change takes {:.3} us", us(c), us(lim.page_change))));
        }
        let eeprom = address != frames::PAGE_REGISTER && s.page != frames::REGISTER_PAGE;
        if id == DataId::IdE && eeprom {
            if let Some(c) = s
                .last_read
                .map(|t| end - t)
                .filter(|&c| rules::short(c, lim.read, true))
            {
                out.push(READ.breach(
                    end,
                    format!(
                        "an EEPROM read {:.3} us after the one before; more than {:.3} us (the read time)",
                        us(c),
                        us(lim.read)
                    ),
                ));
            }
            s.last_read = Some(end);
        }
        if id == DataId::IdF {
            if address == frames::PAGE_REGISTER {
                s.page_write = Some(end);
                s.page = r.fields.get(2).copied().unwrap_or(0) & 0xF;
            } else if eeprom {
                if let Some(c) = s
                    .last_write
                    .map(|t| end - t)
                    .filter(|&c| rules::short(c, lim.write, true))
                {
                    out.push(WRITE.breach(end, format!("an EEPROM write {:.3} us after the one before; more than {:.3} us (the write time)", us(c), us(lim.write))));
                }
                s.last_write = Some(end);
            }
        }
    }
}
