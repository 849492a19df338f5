//! A line as a list of level changes: what the pin-level decoders read.
//!
//! `tbgen decode` builds these from a captured VCD, the co-simulation
//! monitors (`cosim::monitor`) from the pins they sample each monitor clock
//! cycle; both hand them to the same decode cores (`ssi::decode`,
//! `biss::decode`, `tformat::decode`, `esl::decode`), so a capture and a
//! live simulation are read alike. [`uart_bytes`] reads the 10-bit
//! characters of the RS-485 frame protocols (ESL, T-format) off a line.

/// One scalar's value changes, in time order: `(time_ps, level)`. X and Z
/// read as high, the level an idle RS-485 receiver with fail-safe biasing
/// reports.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Signal {
    /// Dotted path (or pin name) the signal was found under.
    pub name: String,
    /// Changes in time order; repeated values are kept out.
    pub changes: Vec<(u64, bool)>,
}

impl Signal {
    /// An empty signal named `name` (high until its first change).
    pub fn named(name: &str) -> Signal {
        Signal {
            name: name.to_string(),
            changes: Vec::new(),
        }
    }

    /// Appends a level at `t_ps` (not before the last change); a repeated
    /// level is left out, a second change at the same time replaces the first.
    pub fn push(&mut self, t_ps: u64, level: bool) {
        match self.changes.last_mut() {
            Some(last) if last.0 == t_ps => last.1 = level,
            Some(last) if last.1 == level => {}
            _ => self.changes.push((t_ps, level)),
        }
    }

    /// The level at `t_ps` (the last change at or before it; high before the
    /// first change).
    pub fn level_at(&self, t_ps: u64) -> bool {
        match self.changes.partition_point(|&(ct, _)| ct <= t_ps) {
            0 => true,
            i => self.changes[i - 1].1,
        }
    }

    /// The edges: changes that differ from the level before them, starting
    /// from an idle-high line.
    pub fn edges(&self) -> Vec<(u64, bool)> {
        let mut last = true;
        let mut edges = Vec::new();
        for &(t, v) in &self.changes {
            if v != last {
                edges.push((t, v));
                last = v;
            }
        }
        edges
    }

    /// The first time at or after `from_ps` at which the signal is `level`.
    pub fn next_level(&self, from_ps: u64, level: bool) -> Option<u64> {
        if self.level_at(from_ps) == level {
            return Some(from_ps);
        }
        let i = self.changes.partition_point(|&(ct, _)| ct <= from_ps);
        self.changes[i..]
            .iter()
            .find(|&&(_, v)| v == level)
            .map(|&(t, _)| t)
    }

    /// High whenever either signal is: what a receiver hears whose input is
    /// forced high while its own driver is on (`line.or(&tx_en)`).
    pub fn or(&self, other: &Signal) -> Signal {
        let mut times: Vec<u64> = self
            .changes
            .iter()
            .chain(&other.changes)
            .map(|c| c.0)
            .collect();
        times.sort_unstable();
        times.dedup();
        let mut changes: Vec<(u64, bool)> = Vec::with_capacity(times.len());
        for t in times {
            let level = self.level_at(t) || other.level_at(t);
            if changes.last().is_none_or(|&(_, last)| last != level) {
                changes.push((t, level));
            }
        }
        Signal {
            name: format!("{} | {}", self.name, other.name),
            changes,
        }
    }

    /// The part from `from_ps` on: the level at `from_ps` as its first
    /// change, then every later one (what a decoder of one transaction reads).
    pub fn tail(&self, from_ps: u64) -> Signal {
        let i = self.changes.partition_point(|&(ct, _)| ct <= from_ps);
        let mut changes = vec![(from_ps, self.level_at(from_ps))];
        changes.extend_from_slice(&self.changes[i..]);
        Signal {
            name: self.name.clone(),
            changes,
        }
    }

    /// Drops every change before `t_ps`, keeping the level at `t_ps`.
    pub fn forget_before(&mut self, t_ps: u64) {
        *self = self.tail(t_ps);
    }
}

/// One byte read off a UART-style line: start bit 0, 8 data bits LSB first,
/// stop bit 1 (the character of ESL and T-format).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UartByte {
    /// Falling edge of the start bit, ps.
    pub start_ps: u64,
    /// The data bits, LSB first on the wire.
    pub value: u8,
    /// The stop bit read low.
    pub framing_error: bool,
}

/// Reads every character of `line` at `bit_ps` picoseconds per bit, sampling
/// each bit in its middle from the start bit's falling edge. A start bit that
/// is high again at its middle is a glitch and is skipped. A character with a
/// low stop bit is kept and flagged; the reader then waits for the line to
/// go high before it looks for the next start bit.
pub fn uart_bytes(line: &Signal, bit_ps: u64) -> Vec<UartByte> {
    let mut bytes = Vec::new();
    let mut from = 0u64;
    while let Some(fall) = line.next_level(from, false) {
        // A line that is low from the start of the capture is not a start bit.
        let fall = if fall == 0 && line.changes.first().is_some_and(|&(t, v)| t == 0 && !v) {
            match line.next_level(0, true) {
                Some(t) => {
                    from = t;
                    continue;
                }
                None => break,
            }
        } else {
            fall
        };
        let mid = |k: u64| fall + k * bit_ps + bit_ps / 2;
        if line.level_at(mid(0)) {
            from = fall + 1;
            from = line.next_level(from, true).unwrap_or(from);
            continue;
        }
        let value = (0..8).fold(0u8, |acc, k| acc | ((line.level_at(mid(k + 1)) as u8) << k));
        let stop = line.level_at(mid(9));
        bytes.push(UartByte {
            start_ps: fall,
            value,
            framing_error: !stop,
        });
        from = if stop {
            mid(9)
        } else {
            line.next_level(mid(9), true).unwrap_or(u64::MAX)
        };
        if from == u64::MAX {
            break;
        }
    }
    bytes
}
