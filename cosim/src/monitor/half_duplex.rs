//! What the T-format and ESL monitors share: the host's side of a
//! half-duplex RS-485 pair, watched at its transceiver (the driver's input
//! D, its enable DE, the receiver's output R): the line kept per exchange
//! (from one rise of DE to the next) for the protocol's decoder. The timing
//! rules are the protocol's rule book's ([`model::esl::rules`],
//! [`model::tformat::rules`], over [`model::half_duplex::watch`]), which
//! the monitor and the emulator both feed ([`emulator_step`]: the
//! emulators' side of it).

use model::half_duplex::watch;
use model::rules::Rule;
use model::wire::Signal;
use serde_json::Value;

use super::{limit, Base};
use crate::check::Checks;
use crate::config::Error;
use crate::pair::Pair;
use crate::{Pins, Result};

/// The host's transceiver pins of a monitor's input (bit 0 R, bit 1 D,
/// bit 2 DE), as `(tx, de, rx)`.
pub fn transceiver(pins: Pins) -> (bool, bool, bool) {
    (pins.0 & 2 != 0, pins.0 & 4 != 0, pins.0 & 1 != 0)
}

/// One step of a T-format or ESL emulator's host side at its `cycle` of
/// `f_hz`: the rule book's watcher sees the host as a monitor at the host's
/// pins does (its driver `host`, and the answer `out` the emulator put at
/// the host's end the step before), its breaches go to `checks`; then the
/// pair carries `host` and the device's `drive`. Both drivers on is the
/// watcher's rule, so the pair's own report of it is not kept. Returns the
/// level at the device's receiver.
#[allow(clippy::too_many_arguments)]
pub fn emulator_step<P: watch::Requests>(
    watch: &mut watch::Host<P>,
    pair: &mut Pair,
    checks: &mut Checks,
    cycle: u64,
    f_hz: u64,
    host: model::line::Drive,
    drive: model::line::Drive,
    out: Pins,
) -> bool {
    let answer = out.enable().then_some(out.data());
    for b in watch.sample_n(cycle, f_hz, host.level, host.enable, answer) {
        checks.breach(cycle, &b);
    }
    pair.step(host, drive, cycle, &mut Checks::default(), "")
}

/// The `[monitor]` settings of the shared checks into `line`: the release
/// (`release_us`, refused outside `release`'s range) and the longest pause
/// between a request's characters (`max_gap_bits`).
pub fn line_settings(
    line: &mut watch::Limits,
    release: &'static Rule,
    release_us: Option<f64>,
    gap_bits: Option<f64>,
    origin: &str,
) -> Result<()> {
    if let Some(us) = release_us {
        line.set_release(release, "monitor.release_us", us)
            .map_err(|e| Error::config(origin, e))?;
    }
    if let Some(bits) = gap_bits {
        line.set_gap_bits(limit(
            origin,
            "monitor.max_gap_bits",
            bits,
            "give the longest idle line between two characters of a request, in bits",
        )?);
    }
    Ok(())
}

/// The line since the exchange not yet decoded: the wire at the host (its
/// driver's level while DE is on, else the receiver's), DE, and what the
/// host's receiver hears (high while DE is on: it is deaf then). An exchange
/// runs from one rise of DE to the next; it is handed to the decoder a few
/// bits after the next rise (a character of the answer may straddle it),
/// and the line before it is then forgotten.
#[derive(Debug, Clone)]
pub struct Exchanges {
    /// The wire at the host.
    pub wire: Signal,
    /// The host's driver enable.
    pub de: Signal,
    /// What the host's receiver hears.
    pub heard: Signal,
    start: Option<u64>,
    next: Option<u64>,
    settle_ps: u64,
    de_now: bool,
}

/// An exchange to decode: DE's rise, its fall (`u64::MAX`: still on), the next rise (`u64::MAX`: none yet).
pub type Window = (u64, u64, u64);

impl Exchanges {
    /// An empty line; an exchange is decoded `settle_ps` after the next one began.
    pub fn new(settle_ps: u64) -> Self {
        Exchanges {
            wire: Signal::named("wire"),
            de: Signal::named("de"),
            heard: Signal::named("heard"),
            start: None,
            next: None,
            settle_ps,
            de_now: false,
        }
    }

    /// One cycle; `decode` gets each exchange as it becomes complete (with
    /// the line still holding it).
    pub fn step(
        &mut self,
        now: u64,
        tx: bool,
        de: bool,
        rx: bool,
        mut decode: impl FnMut(&Exchanges, Window),
    ) {
        if de && !self.de_now {
            if let Some(w) = self.window(false) {
                decode(self, w);
                self.advance();
            }
            if self.start.is_none() {
                self.start = Some(now);
            } else {
                self.next = Some(now);
            }
        }
        self.de_now = de;
        self.wire.push(now, if de { tx } else { rx });
        self.de.push(now, de);
        self.heard.push(now, de || rx);
        if self.next.is_some_and(|n| now >= n + self.settle_ps) {
            if let Some(w) = self.window(false) {
                decode(self, w);
                self.advance();
            }
        }
    }

    /// The exchange complete but not yet decoded (`open`: or else the one in
    /// progress, up to now).
    pub fn window(&self, open: bool) -> Option<Window> {
        let start = self.start?;
        if !open && self.next.is_none() {
            return None;
        }
        let next = self.next.unwrap_or(u64::MAX);
        let fall = self
            .de
            .next_level(start, false)
            .filter(|&f| f < next)
            .unwrap_or(u64::MAX);
        Some((start, fall, next))
    }

    /// Every exchange not yet decoded, the one in progress last.
    pub fn pending(&self) -> Vec<Window> {
        let mut list: Vec<Window> = self.window(true).into_iter().collect();
        if let Some(n) = self.next {
            list.push((
                n,
                self.de.next_level(n, false).unwrap_or(u64::MAX),
                u64::MAX,
            ));
        }
        list
    }

    /// After the complete exchange was decoded: forget the line before the next one.
    pub fn advance(&mut self) {
        if let Some(n) = self.next.take() {
            self.wire.forget_before(n);
            self.de.forget_before(n);
            self.heard.forget_before(n);
            self.start = Some(n);
        }
    }
}

/// A protocol's decoder, one exchange at a time (its transactions as JSON).
pub trait ExchangeDecoder: Clone {
    /// One exchange of `line`; the transaction it closed, if any.
    fn exchange(&mut self, line: &Exchanges, window: Window) -> Option<Value>;
    /// The transaction still open.
    fn finish(&mut self) -> Option<Value>;
}

/// The host's side of the pair as a monitor sees it: the line not yet
/// decoded and the decoder; what the T-format and ESL monitors share but
/// their rule books.
pub struct Side<D> {
    /// Clock, violations, decoded transactions.
    pub base: Base,
    line: Exchanges,
    decoder: D,
}

impl<D: ExchangeDecoder> Side<D> {
    /// A side at `base`'s clock for a line of `bit_ps` a bit; an exchange
    /// is decoded 12 bits after the next one began.
    pub fn new(base: Base, bit_ps: f64, decoder: D) -> Self {
        let settle = (12.0 * bit_ps).round() as u64;
        Side {
            base,
            line: Exchanges::new(settle),
            decoder,
        }
    }

    /// One monitor cycle (pins: bit 0 R, bit 1 D, bit 2 DE): the line
    /// kept, exchanges decoded as they complete. The monitor's cycle count
    /// is the caller's to advance ([`Base::step_out`]).
    pub fn step(&mut self, pins: Pins) {
        let now = self.base.now_ps();
        let (tx, de, rx) = transceiver(pins);
        let (decoder, done) = (&mut self.decoder, &mut self.base.done);
        self.line.step(now, tx, de, rx, |line, w| {
            done.extend(decoder.exchange(line, w))
        });
    }

    /// Records the breaches a rule book's watcher returned.
    pub fn breaches(&mut self, list: &[model::rules::Breach]) {
        for b in list {
            self.base.breach(b);
        }
    }

    /// The transactions not yet in `base.done` (the decoder's state is not changed).
    pub fn pending(&self) -> Vec<Value> {
        let mut d = self.decoder.clone();
        let mut out: Vec<Value> = self
            .line
            .pending()
            .into_iter()
            .filter_map(|w| d.exchange(&self.line, w))
            .collect();
        out.extend(d.finish());
        out
    }

    /// The last transaction (the one in progress included).
    pub fn last(&self) -> Option<Value> {
        self.pending()
            .pop()
            .or_else(|| self.base.done.last().cloned())
    }

    /// Transactions seen so far (the one in progress included).
    pub fn count(&self) -> u64 {
        (self.base.done.len() + self.pending().len()) as u64
    }

    /// The transcript.
    pub fn transcript(&self, protocol: &str) -> Value {
        self.base
            .transcript(protocol, &["rx", "tx", "tx_en"], self.pending())
    }
}
