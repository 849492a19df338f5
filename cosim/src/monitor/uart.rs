//! What the SAR58K24 and Modbus RTU monitors share: the host's side of a
//! half-duplex RS-485 pair carrying asynchronous characters, watched at the
//! host's transceiver (driver input D, its enable DE, receiver output R),
//! and the line recorded for the decoder (`model::uart::line`, shared with
//! `tbgen decode sar|modbus`). The rules of the host's characters are the
//! protocols' rule books' ([`model::sar58k24::rules`],
//! [`model::modbus::rules`], over [`model::uart::watch`]), which the
//! emulators feed too.

use model::wire::Signal;

/// The line as the decoder reads it: the wire at the host (D while DE is
/// on, else R) and DE, from the last cut on.
#[derive(Debug, Clone)]
pub struct Line {
    /// The wire.
    pub wire: Signal,
    /// The host's driver enable.
    pub de: Signal,
    /// Where the piece not yet decoded begins, ps.
    pub from: u64,
}

impl Line {
    /// An empty line, idle high, DE off.
    pub fn new() -> Self {
        let mut de = Signal::named("tx_en");
        de.push(0, false);
        Line {
            wire: Signal::named("line"),
            de,
            from: 0,
        }
    }

    /// One monitor cycle.
    pub fn step(&mut self, now: u64, tx: bool, de: bool, rx: bool) {
        self.wire.push(now, if de { tx } else { rx });
        self.de.push(now, de);
    }

    /// Forgets the line before `t_ps` (the next piece begins there).
    pub fn cut(&mut self, t_ps: u64) {
        self.wire.forget_before(t_ps);
        self.de.forget_before(t_ps);
        self.from = t_ps;
    }
}

impl Default for Line {
    fn default() -> Self {
        Line::new()
    }
}

/// The pins of a UART monitor: bit 0 R, bit 1 D, bit 2 DE.
pub fn pins(p: crate::Pins) -> (bool, bool, bool) {
    (p.0 & 1 != 0, p.0 & 2 != 0, p.0 & 4 != 0)
}
