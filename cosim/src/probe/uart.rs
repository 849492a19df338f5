//! A host's pins on a half-duplex UART line, for the SAR58K24 and Modbus
//! probes: bit 1 its driver input D, bit 2 its driver enable DE, the other
//! bits (the SAR58K24's trigger and CLR) held at their idle levels unless a
//! pulse is asked for. Times are kept exact in ps as `f64` and each segment
//! is the difference of the rounded ends, so a character of any baud rate
//! does not drift.

use model::uart::Parity;

use super::Stimulus;

/// D.
const D: u32 = 2;
/// DE.
const DE: u32 = 4;

/// A host building its pins.
#[derive(Debug, Clone)]
pub struct Host {
    bit_ps: f64,
    parity: Parity,
    /// The other pins' idle levels.
    rest: u32,
    now: f64,
    line: Stimulus,
}

impl Host {
    /// A host at `baud` with `parity`, its other pins idle at `rest`.
    pub fn new(baud: f64, parity: Parity, rest: u32) -> Self {
        Host {
            bit_ps: 1e12 / baud,
            parity,
            rest,
            now: 0.0,
            line: Vec::new(),
        }
    }

    /// One bit time, ps.
    pub fn bit(&self) -> f64 {
        self.bit_ps
    }

    /// `levels` for `ps` (rounded at both ends).
    fn push(&mut self, levels: u32, ps: f64) -> &mut Self {
        let (a, b) = (self.now.round(), (self.now + ps).round());
        self.now += ps;
        if b > a {
            self.line.push((levels, (b - a) as u64));
        }
        self
    }

    /// The driver off (D high) for `ps`.
    pub fn idle(&mut self, ps: f64) -> &mut Self {
        self.push(self.rest | D, ps)
    }

    /// The driver on, D high, for `ps`.
    pub fn hold(&mut self, ps: f64) -> &mut Self {
        self.push(self.rest | D | DE, ps)
    }

    /// The driver on, D low (a line held low) for `ps`.
    pub fn low(&mut self, ps: f64) -> &mut Self {
        self.push(self.rest | DE, ps)
    }

    /// One character of `byte`, every bit `scale` bit times, the driver on.
    pub fn char(&mut self, byte: u8, scale: f64) -> &mut Self {
        for l in self.parity.levels(byte) {
            self.push(self.rest | DE | if l { D } else { 0 }, self.bit_ps * scale);
        }
        self
    }

    /// `bytes` back to back at the nominal rate, the driver on.
    pub fn chars(&mut self, bytes: &[u8]) -> &mut Self {
        for &b in bytes {
            self.char(b, 1.0);
        }
        self
    }

    /// A request: the driver on a bit before, `bytes` back to back, the
    /// driver off at the end of the last stop bit.
    pub fn request(&mut self, bytes: &[u8]) -> &mut Self {
        self.hold(self.bit_ps).chars(bytes)
    }

    /// A request of `bytes` with every bit `scale` bit times (a host off
    /// its baud rate), the driver off at the end of the last stop bit.
    pub fn skewed(&mut self, bytes: &[u8], scale: f64) -> &mut Self {
        self.hold(self.bit_ps);
        for &b in bytes {
            self.char(b, scale);
        }
        self
    }

    /// Pin `mask` low for `ps` (the driver off, D high).
    pub fn pulse(&mut self, mask: u32, ps: f64) -> &mut Self {
        self.push((self.rest | D) & !mask, ps)
    }

    /// The stimulus.
    pub fn line(&self) -> Stimulus {
        self.line.clone()
    }
}
