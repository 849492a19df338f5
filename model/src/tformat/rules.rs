//! The T-format host's rules (seed 002, Tamagawa TS5669 N127), in the shape
//! of [`crate::rules`]: every rule the emulator and the monitor hold a host
//! to, decided once by [`Watch`], which both feed with the host's
//! transceiver pins (D, DE, R) and whose breaches both print.
//!
//! A request is the fields the host's driver sends while its enable DE is
//! on (start 0, 8 data LSB first, delimiter 1, 400 ns a bit at 2.5 Mbps);
//! the shared checks of character timing, back-to-back fields, release and
//! answer are [`crate::half_duplex::watch`]'s, this module adds the field
//! count of the Data ID and the spacing of a reset's ten requests:
//!
//! ```text
//!  DE   _/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_________________________/‾‾‾‾‾‾‾\___ ...
//!  D/R  ‾\_CF__/\_ADF_/\_EDF_/‾‾‾‾‾‾‾‾‾‾‾‾\_answer_/‾‾‾‾‾‾‾‾‾\_CF__/‾‾‾
//!         |<-- on the bit grid, +-100 ns -->|<=1.5 us|          |
//!         |<------------ reset requests 40 ms or more apart ---->|
//! ```

use std::sync::OnceLock;

use super::frames::{self, DataId};
use crate::half_duplex::watch::{self, Request};
use crate::rules::{self, Bound, Breach, Rule, Settable, Unit};
use crate::ConfigError;

/// A section of the seed, as a rule names it.
macro_rules! seed {
    ($s:literal) => {
        concat!("seed 002 TS5669 N127, ", $s)
    };
}

/// Every edge of a request on the bit grid.
pub static JITTER: Rule = Rule {
    protocol: "tformat",
    name: "jitter",
    section: seed!("6.1 and 6.3"),
    seed_words: "Transmission rate 2.5 Mbps, Permissible jitter:±100 ns",
    quantity: "request edge off the bit grid",
    bound: Bound::AtMost(100.0, Unit::Ns),
    measured: "every edge of a request field from the field's start edge (the first 0 after idle): its distance from the nearest whole bit; the delimiter high at its middle and a full bit long (the next start bit no sooner than 10 bits less the jitter); DE not released inside a field",
    reading: "the permissible jitter is held on every edge against the field's own start edge (a host's clock off the rate shows as a growing offset); a configuration may set less (`monitor.jitter_ns`)",
    settable: Some(Settable { lo: 0.0, hi: 100.0 }),
    label: OnceLock::new(),
};

/// A request's fields back to back.
pub static END_OF_FRAME: Rule = Rule {
    protocol: "tformat",
    name: "end of frame",
    section: seed!("7.2"),
    seed_words: "After the Starting frame is detected, if there is no Start bit after the Delimiter, End of Frame is judged.",
    quantity: "a request's fields back to back",
    bound: Bound::Form,
    measured: "the end of a delimiter (its field's start edge and 10 bits) to the next start bit while DE stays on",
    reading: "the project's reading: the encoder judges the end of the frame when no start bit follows a delimiter, so a request split by a pause is two; the next start bit is held within `monitor.max_gap_bits` (0.5 bit) and the jitter of the delimiter's end",
    settable: None,
    label: OnceLock::new(),
};

/// The fields a Data ID takes.
pub static FIELDS: Rule = Rule {
    protocol: "tformat",
    name: "request fields",
    section: seed!("6.2, 6.3 and 9"),
    seed_words: "\"User Data\" of 8 bits can be read out from the address designated. Regarding the transmission method for Readout request, refer to Paragraphs 6.2.3 and 6.3.5.",
    quantity: "the fields of the request's Data ID",
    bound: Bound::Form,
    measured: "the fields sent while DE was on, against the Data ID of the first (CF)",
    reading: "the frame figures of 6.2 are missing from the seed's text; the house reads a readout or reset request as CF alone, Data ID 6 as CF ADF EDF CRC and Data ID D as CF ADF CRC (`frames::request`)",
    settable: None,
    label: OnceLock::new(),
};

/// The host's driver off before the answer.
pub static RELEASE: Rule = Rule {
    protocol: "tformat",
    name: "release",
    section: seed!("7.1"),
    seed_words: "The Data frame is transmitted at 3 micro-seconds (typ.), after receiving the Delimiter signal of Request frame.",
    quantity: "DE on after the last delimiter",
    bound: Bound::AtMost(1.5, Unit::Us),
    measured: "the end of the request's last delimiter (its field's start edge and 10 bits) to the first sample with DE off",
    reading: "the project's reading: the host releases the line within half the typical answer delay, so that the encoder's answer never meets its driver; a configuration may set 0 to 3 us (`monitor.release_us`)",
    settable: Some(Settable { lo: 0.0, hi: 3.0 }),
    label: OnceLock::new(),
};

/// No request while the encoder answers.
pub static ANSWER: Rule = Rule {
    protocol: "tformat",
    name: "no request during the answer",
    section: seed!("10"),
    seed_words: "Never transmit any Request to Smart Abs while it transmits the data.",
    quantity: "the host's driver off while the encoder answers",
    bound: Bound::Form,
    measured: "DE switched on less than 11 bits after the start bit of the encoder's last character at the host, or on while the host's receiver hears a 0 against a 1 of its driver (both drivers on)",
    reading: "",
    settable: None,
    label: OnceLock::new(),
};

/// A reset's ten requests, 40 ms apart.
pub static RESET: Rule = Rule {
    protocol: "tformat",
    name: "reset interval",
    section: seed!("9"),
    seed_words: "Transmit 10 times in one sequence to Smart Abs with the interval of 40 ms or more",
    quantity: "interval between the requests of a reset",
    bound: Bound::AtLeast(40.0, Unit::Ms),
    measured: "start edge to start edge of successive requests of one reset Data ID (7, 8, C); ten of them before another Data ID",
    reading: "\"or more\": read inclusively; the bound is the encoder's `reset_interval_us` (the seed's 40 ms by default), a device property a bench may shorten to save time (`monitor.reset_interval_us` for the monitor)",
    settable: None,
    label: OnceLock::new(),
};

/// The T-format rules, in the order of the seed.
pub static RULES: &[&Rule] = &[&JITTER, &FIELDS, &RELEASE, &END_OF_FRAME, &RESET, &ANSWER];

/// The rules the shared half-duplex checks report under.
const SHARED: watch::Rules = watch::Rules {
    character: &JITTER,
    gap: &END_OF_FRAME,
    release: &RELEASE,
    answer: &ANSWER,
};

/// Requests of one reset sequence (seed 002 9: "10 times").
pub const RESET_REQUESTS: u32 = 10;

/// The bounds in force, ps.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// The shared checks'.
    pub line: watch::Limits,
    /// Least interval between a reset's requests ([`RESET`]).
    pub reset_interval_ps: u64,
}

impl Limits {
    /// The seed's bounds at `baud` bit/s for an encoder whose reset
    /// interval is `reset_interval_us`.
    pub fn seed(baud: f64, reset_interval_us: f64) -> Self {
        let (Bound::AtMost(jitter, j), Bound::AtMost(release, r)) = (JITTER.bound, RELEASE.bound)
        else {
            unreachable!("the jitter and the release are greatest times")
        };
        let bit_ps = 1e12 / baud;
        Limits {
            line: watch::Limits {
                bit_ps,
                tolerance: 0.0,
                jitter_ps: j.ps(jitter) as f64,
                max_gap_ps: 0.5 * bit_ps,
                release_ps: r.ps(release),
            },
            reset_interval_ps: Unit::Us.ps(reset_interval_us),
        }
    }

    /// The jitter set to `ns` (field `field`), within [`JITTER`]'s range.
    pub fn set_jitter(&mut self, field: &str, ns: f64) -> Result<(), ConfigError> {
        self.line.jitter_ps = Unit::Ns.ps(JITTER.setting(field, ns)?) as f64;
        Ok(())
    }

    /// The release set to `us` (field `field`), within [`RELEASE`]'s range.
    pub fn set_release(&mut self, field: &str, us: f64) -> Result<(), ConfigError> {
        self.line.set_release(&RELEASE, field, us)
    }

    /// The least lengths, for [`rules::resolution_notes`].
    pub fn least(&self) -> Vec<(&'static Rule, u64)> {
        vec![
            (&JITTER, self.line.jitter_ps as u64),
            (&RELEASE, self.line.release_ps),
            (&RESET, self.reset_interval_ps),
        ]
    }
}

/// The T-format checks of whole requests: the field count, a reset's spacing.
#[derive(Debug, Clone)]
pub struct Requests {
    reset_interval_ps: u64,
    /// A reset sequence in progress: Data ID, requests so far, start of the last.
    reset: Option<(u8, u32, u64)>,
}

/// The T-format watcher: the host's transceiver pins ([`watch::Host::sample`]).
pub type Watch = watch::Host<Requests>;

/// A watcher holding the host to `limits`.
pub fn watch(limits: Limits) -> Watch {
    let requests = Requests {
        reset_interval_ps: limits.reset_interval_ps,
        reset: None,
    };
    watch::Host::with(limits.line, SHARED, requests)
}

impl watch::Requests for Requests {
    fn request(&mut self, r: &Request, out: &mut Vec<Breach>) {
        let Some(&cf) = r.fields.first() else { return };
        let code = frames::parse_control_field(cf).code;
        let id = DataId::from_code(code);
        if let Some(id) = id.filter(|_| !r.damaged) {
            let want = frames::request(id, 0, 0).len();
            if r.fields.len() != want {
                out.push(FIELDS.breach(
                    r.end_ps,
                    format!(
                        "a request of {} field(s) for Data ID {code:X}, which takes {want}",
                        r.fields.len()
                    ),
                ));
            }
        }
        let reset = id.is_some_and(|d| d.is_reset());
        match self.reset {
            Some((rid, k, last)) if reset && rid == code => {
                let gap = r.start_ps - last;
                if rules::short(gap, self.reset_interval_ps, false) {
                    out.push(RESET.breach(r.start_ps, format!("request {} of reset Data ID {code:X} {:.6} ms after the one before; at least {:.6} ms", k + 1, gap as f64 / 1e9, self.reset_interval_ps as f64 / 1e9)));
                }
                self.reset = (k + 1 < RESET_REQUESTS).then_some((rid, k + 1, r.start_ps));
            }
            prev => {
                if let Some((rid, k, _)) = prev {
                    out.push(RESET.breach(r.start_ps, format!("reset Data ID {rid:X} sent {k} time(s), then Data ID {code:X}: a reset takes {RESET_REQUESTS} requests in one sequence")));
                }
                self.reset = reset.then_some((code, 1, r.start_ps));
            }
        }
    }
}
