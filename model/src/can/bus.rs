//! The CAN bus: a wired-AND of every node's transmit level, each seen at
//! each node after that node pair's delay.
//!
//! ```text
//!  node i TXD ─(t_tx_i)─> bus at x_i ─(|x_i − x_j| · ns_per_m)─> bus at x_j ─(t_rx_j)─> node j RXD
//!  rx_j(t) = AND over i of tx_i(t − d_ij),  d_ij = t_tx_i + |x_i − x_j|·ns_per_m + t_rx_j  (≥ 1 cycle)
//! ```
//! A node's transceiver loop delay is split evenly between its driver
//! (`t_tx`) and its receiver (`t_rx`), so that a node hears itself after its
//! loop delay, as a transceiver datasheet states it.

use std::collections::VecDeque;

use serde::{Deserialize, Serialize};

use crate::{ConfigError, Result, Timebase};

/// Where a node sits and how slow its transceiver is.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Place {
    /// Position along the cable, metres from one end.
    pub position_m: f64,
    /// Transceiver loop delay (TXD to RXD), ns.
    pub loop_delay_ns: f64,
}

impl Place {
    /// Checks the fields; `field` names the scenario table.
    pub fn validate(&self, field: &str) -> Result<()> {
        if !(0.0..=10_000.0).contains(&self.position_m) {
            return Err(ConfigError::invalid(format!("{field}.position_m"), format!("{}", self.position_m), "give a position from 0 to 10 000 m"));
        }
        if !(0.0..=10_000.0).contains(&self.loop_delay_ns) {
            return Err(ConfigError::invalid(format!("{field}.loop_delay_ns"), format!("{}", self.loop_delay_ns), "give a loop delay from 0 to 10 000 ns"));
        }
        Ok(())
    }
}

/// The wired-AND with its delay lines.
#[derive(Debug, Clone)]
pub struct Bus {
    delay: Vec<Vec<usize>>,
    /// Per node, its TXD levels of the last `hist.len()` cycles, a ring
    /// indexed by cycle modulo its length (a power of two, so that `& mask`
    /// indexes it: the bus is read several times a cycle).
    hist: Vec<Vec<bool>>,
    mask: usize,
    /// Cycles a change takes to reach every node: the longest delay, plus one.
    len: usize,
    cycle: usize,
    /// Per node, the cycles whose level differs from the cycle before's,
    /// for as long as the change may still be on its way to a node.
    changes: Vec<VecDeque<usize>>,
}

impl Bus {
    /// A recessive bus for nodes at `places`, `ns_per_m` along the cable.
    pub fn new(places: &[Place], ns_per_m: f64, tb: &Timebase) -> Bus {
        let ps = tb.period_ps() as f64;
        let delay: Vec<Vec<usize>> = places
            .iter()
            .map(|a| {
                places
                    .iter()
                    .map(|b| {
                        let ns = a.loop_delay_ns / 2.0 + (a.position_m - b.position_m).abs() * ns_per_m + b.loop_delay_ns / 2.0;
                        ((ns * 1e3 / ps).round() as usize).max(1)
                    })
                    .collect()
            })
            .collect();
        let len = delay.iter().flatten().copied().max().unwrap_or(1) + 1;
        let ring = len.next_power_of_two();
        Bus { hist: vec![vec![true; ring]; places.len()], mask: ring - 1, delay, len, cycle: 0, changes: vec![VecDeque::new(); places.len()] }
    }

    /// Delay from node `from`'s TXD to node `to`'s RXD, cycles.
    pub fn delay(&self, from: usize, to: usize) -> usize {
        self.delay[from][to]
    }

    /// The level at node `j`'s RXD this cycle.
    pub fn rx(&self, j: usize) -> bool {
        (0..self.hist.len()).all(|i| self.hist[i][self.cycle.wrapping_sub(self.delay[i][j]) & self.mask])
    }

    /// Whether the delay lines hold nothing but recessive levels: then, as
    /// long as every node keeps sending recessive, every RXD reads
    /// recessive.
    pub fn recessive(&self) -> bool {
        (1..=self.len).all(|k| self.hist.iter().all(|h| h[self.cycle.wrapping_sub(k) & self.mask]))
    }

    /// For how many cycles from this one node `j`'s RXD keeps its level
    /// while every node keeps sending the level it sent last: until the
    /// first change of a node's level still on its way reaches `j` (one
    /// another node's dominant level masks is counted all the same), or
    /// for ever.
    pub fn steady(&self, j: usize) -> u64 {
        let mut q = u64::MAX;
        for (i, changes) in self.changes.iter().enumerate() {
            // A change pushed at cycle t reaches j at cycle t + d.
            let d = self.delay[i][j];
            for &t in changes.iter().rev() {
                if t + d <= self.cycle {
                    break;
                }
                q = q.min((t + d - self.cycle) as u64);
            }
        }
        q
    }

    /// Moves `n` cycles on with every node sending the level it sent last
    /// (what `n` pushes of those levels would do).
    pub fn skip(&mut self, n: u64) {
        let (mask, now) = (self.mask, self.cycle & self.mask);
        let last = self.cycle.wrapping_sub(1) & mask;
        // The cycles [now, now + n) of the ring, at most all of it: the
        // part up to the ring's end, then the part from its start.
        let fill = (n as usize).min(mask + 1);
        let (first, wrapped) = (fill.min(mask + 1 - now), fill.saturating_sub(mask + 1 - now));
        for h in &mut self.hist {
            let level = h[last];
            h[now..now + first].fill(level);
            h[..wrapped].fill(level);
        }
        self.cycle += n as usize;
        self.forget();
    }

    /// Records this cycle's TXD levels and moves to the next cycle.
    pub fn push(&mut self, tx: &[bool]) {
        let (now, last) = (self.cycle & self.mask, self.cycle.wrapping_sub(1) & self.mask);
        for ((h, &t), changes) in self.hist.iter_mut().zip(tx).zip(&mut self.changes) {
            if h[last] != t {
                changes.push_back(self.cycle);
            }
            h[now] = t;
        }
        self.cycle += 1;
        self.forget();
    }

    /// Drops the changes that have reached every node.
    fn forget(&mut self) {
        for changes in &mut self.changes {
            while changes.front().is_some_and(|&t| t + self.len <= self.cycle) {
                changes.pop_front();
            }
        }
    }
}
