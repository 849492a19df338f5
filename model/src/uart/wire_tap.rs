//! A second receiver on the half-duplex line at the host that never goes
//! deaf: it records every character on the wire, in both directions, for the
//! transcript. The host's own receiver is blind while the host drives and
//! stops at its first framing error, so its `sent` / `received` are the
//! host's view; the tap's `wire_requests` / `wire_answers` are what a logic
//! analyser (or sigrok's `uart` decoder) sees at the host's pins. ESL and
//! T-format both keep the two views side by side.

use super::{In, Parity, Receiver, ReceiverConfig, State};
use crate::Result;

/// One host operation's `(wire_requests, wire_answers)`, as [`WireTap::step`] fills them.
pub type WireLog<'a> = (&'a mut Vec<Vec<u8>>, &'a mut Vec<Vec<u8>>);

/// The tap: a model receiver plus who drove when each character began.
#[derive(Debug, Clone)]
pub struct WireTap {
    rx: Receiver,
    /// The character being received began while the host drove.
    from_host: bool,
    /// The host's driver enable one cycle ago.
    tx_en_before: bool,
}

impl WireTap {
    /// A tap sampling at `clocks_per_bit`, the host's own rate.
    pub fn new(clocks_per_bit: u64) -> Result<Self> {
        WireTap::with_parity(clocks_per_bit, Parity::None)
    }

    /// A tap for characters with a parity bit (a character with a wrong
    /// parity bit is filed as received, like one with a low stop bit).
    pub fn with_parity(clocks_per_bit: u64, parity: Parity) -> Result<Self> {
        Ok(WireTap {
            rx: Receiver::with_parity(ReceiverConfig { clocks_per_bit }, parity)?,
            from_host: false,
            tx_en_before: false,
        })
    }

    /// How many of the next steps with `line` and `tx_en` record nothing
    /// and leave the receiver's state as it is (fast-forward).
    pub fn quiet(&self, line: bool, tx_en: bool) -> u64 {
        if tx_en != self.tx_en_before {
            return 0;
        }
        self.rx.quiet(&In { i_rx: line })
    }

    /// The same as `n` steps with the last inputs, for `n` up to [`WireTap::quiet`].
    pub fn skip(&mut self, n: u64) {
        self.rx.skip(n);
    }

    /// One system clock: `line` is the level at the host's receiver pin,
    /// `tx_en` the host's driver enable this cycle, `log` the current host
    /// operation's `(wire_requests, wire_answers)`: one list per request of
    /// the characters sent while the host drove, and one per request of
    /// what followed it. A rising `tx_en` opens a new pair of lists; a
    /// finished character, good or with a low stop bit, goes to the last list
    /// of its direction. With no `log` (no operation yet) the tap still
    /// follows the line.
    pub fn step(&mut self, line: bool, tx_en: bool, log: Option<WireLog>) {
        let was_busy = self.rx.state() != State::Idle;
        let rx = self.rx.step(&In { i_rx: line });
        if rx.o_busy && !was_busy {
            // The start bit reaches the tap two cycles after the pin: a
            // request's first start bit may begin while tx_en was still high
            // one cycle ago, hence both cycles.
            self.from_host = tx_en || self.tx_en_before;
        }
        let opens_request = tx_en && !self.tx_en_before;
        self.tx_en_before = tx_en;
        let Some((requests, answers)) = log else {
            return;
        };
        if opens_request {
            requests.push(Vec::new());
            answers.push(Vec::new());
        }
        if rx.o_valid || rx.o_frame_err || rx.o_parity_err {
            let to = if self.from_host { requests } else { answers };
            if let Some(set) = to.last_mut() {
                set.push(rx.o_data);
            }
        }
    }
}
