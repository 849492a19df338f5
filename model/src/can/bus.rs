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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
            return Err(ConfigError::invalid(
                format!("{field}.position_m"),
                format!("{}", self.position_m),
                "give a position from 0 to 10 000 m",
            ));
        }
        if !(0.0..=10_000.0).contains(&self.loop_delay_ns) {
            return Err(ConfigError::invalid(
                format!("{field}.loop_delay_ns"),
                format!("{}", self.loop_delay_ns),
                "give a loop delay from 0 to 10 000 ns",
            ));
        }
        Ok(())
    }
}

/// The wired-AND with its delay lines, kept as each node's level changes:
/// a node's level at an earlier cycle is its level now with every change
/// since undone, so that holding a level costs nothing (the benches'
/// fast-forward skips long stretches of it) and a read looks at the few
/// changes still on their way.
#[derive(Debug, Clone)]
pub struct Bus {
    delay: Vec<Vec<usize>>,
    /// Per node, the level it sent last.
    level: Vec<bool>,
    /// Per node, the cycles whose level differs from the cycle before's,
    /// oldest first, for as long as the change may still be on its way to
    /// a node.
    changes: Vec<VecDeque<usize>>,
    /// Cycles a change takes to reach every node: the longest delay, plus one.
    len: usize,
    /// The cycle the next `push` records.
    cycle: usize,
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
                        let ns = a.loop_delay_ns / 2.0
                            + (a.position_m - b.position_m).abs() * ns_per_m
                            + b.loop_delay_ns / 2.0;
                        ((ns * 1e3 / ps).round() as usize).max(1)
                    })
                    .collect()
            })
            .collect();
        let len = delay.iter().flatten().copied().max().unwrap_or(1) + 1;
        Bus {
            level: vec![true; places.len()],
            delay,
            len,
            cycle: 0,
            changes: vec![VecDeque::new(); places.len()],
        }
    }

    /// Delay from node `from`'s TXD to node `to`'s RXD, cycles.
    pub fn delay(&self, from: usize, to: usize) -> usize {
        self.delay[from][to]
    }

    /// The cycle the next `push` records.
    pub fn cycle(&self) -> u64 {
        self.cycle as u64
    }

    /// The level at node `j`'s RXD this cycle: every node's level of its
    /// delay to `j` ago (recessive before the first cycle).
    pub fn rx(&self, j: usize) -> bool {
        self.level
            .iter()
            .zip(&self.changes)
            .zip(&self.delay)
            .all(|((&level, changes), d)| {
                // A change made at cycle t reaches j at t + d: undo those still on
                // their way (mostly none: the last change has arrived).
                match changes.back() {
                    Some(&t) if t + d[j] > self.cycle => {
                        let on_the_way = changes
                            .iter()
                            .rev()
                            .take_while(|&&t| t + d[j] > self.cycle)
                            .count();
                        level ^ (on_the_way % 2 == 1)
                    }
                    _ => level,
                }
            })
    }

    /// [`Bus::rx`] and [`Bus::steady`] of node `j` in one pass over the
    /// changes on their way.
    pub fn rx_steady(&self, j: usize) -> (bool, u64) {
        let (mut rx, mut q) = (true, u64::MAX);
        for ((&level, changes), d) in self.level.iter().zip(&self.changes).zip(&self.delay) {
            let d = d[j];
            let mut sent = level;
            for &t in changes.iter().rev() {
                if t + d <= self.cycle {
                    break;
                }
                sent = !sent;
                q = q.min((t + d - self.cycle) as u64);
            }
            rx &= sent;
        }
        (rx, q)
    }

    /// For how many cycles from this one node `j`'s RXD keeps its level
    /// while every node keeps sending the level it sent last: until the
    /// first change of a node's level still on its way reaches `j` (one
    /// another node's dominant level masks is counted all the same), or
    /// for ever.
    pub fn steady(&self, j: usize) -> u64 {
        self.rx_steady(j).1
    }

    /// Moves `n` cycles on with every node sending the level it sent last
    /// (what `n` pushes of those levels would do).
    pub fn skip(&mut self, n: u64) {
        self.cycle += n as usize;
        self.forget();
    }

    /// Records this cycle's TXD levels and moves to the next cycle.
    pub fn push(&mut self, tx: &[bool]) {
        for ((level, &t), changes) in self.level.iter_mut().zip(tx).zip(&mut self.changes) {
            if *level != t {
                changes.push_back(self.cycle);
                *level = t;
            }
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
