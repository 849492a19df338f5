//! A generic CAN node for test benches: a model [`Controller`] with its own
//! oscillator (ppm offset), a script of frames to send at given times
//! (standard or extended, data or remote), and node-level faults: no ACK,
//! or a transmit level forced for a window of its own bits.
//!
//! Any number of emulators share a [`super::Bus`] with the core under test;
//! the CANopen device model builds on this node (`Emulator::load`,
//! [`Emulator::received`]).

use serde::{Deserialize, Serialize};

use super::bus::Place;
use super::controller::{Controller, ControllerConfig, In, TxBuffer};
use super::frame::{unpack, Frame};
use crate::{ConfigError, Result, Timebase};

/// A frame a node sends at a time (`frames = [{ at_us, id, ... }]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Scripted {
    /// Earliest time, µs after reset (sent when the buffer is free).
    pub at_us: f64,
    /// Identifier: 11 bits, or 29 with `ide`.
    pub id: u32,
    /// Extended frame.
    #[serde(default)]
    pub ide: bool,
    /// Remote frame.
    #[serde(default)]
    pub rtr: bool,
    /// DLC.
    #[serde(default)]
    pub dlc: u8,
    /// Data bytes (min(dlc, 8), none for a remote frame).
    #[serde(default)]
    pub data: Vec<u8>,
}

impl Scripted {
    /// `frame` at `at_us`.
    pub fn new(at_us: f64, frame: Frame) -> Scripted {
        Scripted {
            at_us,
            id: frame.id,
            ide: frame.ide,
            rtr: frame.rtr,
            dlc: frame.dlc,
            data: frame.data,
        }
    }

    /// The frame.
    pub fn frame(&self) -> Frame {
        Frame {
            id: self.id,
            ide: self.ide,
            rtr: self.rtr,
            dlc: self.dlc,
            data: self.data.clone(),
        }
    }
}

/// An emulated node (`[[can.nodes]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NodeSettings {
    /// Name in transcripts.
    pub name: String,
    /// Position along the cable, metres.
    #[serde(default)]
    pub position_m: f64,
    /// Transceiver loop delay, ns.
    #[serde(default = "default_loop")]
    pub loop_delay_ns: f64,
    /// Oscillator offset, ppm (positive: fast).
    #[serde(default)]
    pub ppm: f64,
    /// Acknowledges correct frames (false: never drives the ACK slot).
    #[serde(default = "yes")]
    pub ack: bool,
    /// Frames to send.
    #[serde(default)]
    pub frames: Vec<Scripted>,
}

fn yes() -> bool {
    true
}

fn default_loop() -> f64 {
    150.0
}

impl NodeSettings {
    /// Where the node sits.
    pub fn place(&self) -> Place {
        Place {
            position_m: self.position_m,
            loop_delay_ns: self.loop_delay_ns,
        }
    }

    /// Checks the fields; `field` names the table.
    pub fn validate(&self, field: &str) -> Result<()> {
        self.place().validate(field)?;
        if !(-50_000.0..=50_000.0).contains(&self.ppm) {
            return Err(ConfigError::invalid(
                format!("{field}.ppm"),
                format!("{}", self.ppm),
                "give an oscillator offset within ±50 000 ppm (±5 %)",
            ));
        }
        for (k, s) in self.frames.iter().enumerate() {
            s.frame().validate(&format!("{field}.frames[{k}]"))?;
            if !(0.0..1e8).contains(&s.at_us) {
                return Err(ConfigError::invalid(
                    format!("{field}.frames[{k}].at_us"),
                    format!("{}", s.at_us),
                    "give a time ≥ 0 µs",
                ));
            }
        }
        Ok(())
    }
}

/// The running node.
#[derive(Debug, Clone)]
pub struct Emulator {
    ctrl: Controller,
    script: Vec<(u64, Frame)>,
    next: usize,
    rate: f64,
    phase: f64,
    own_cycle: u64,
    tx: bool,
    sent: Vec<Frame>,
    received: Vec<Frame>,
    arb_lost: u64,
    errors: u64,
}

impl Emulator {
    /// A node in its reset state; `cfg` is its nominal controller configuration.
    pub fn new(s: &NodeSettings, cfg: ControllerConfig, tb: &Timebase) -> Result<Self> {
        let script = s
            .frames
            .iter()
            .map(|f| (tb.cycles_nearest_ns(f.at_us * 1e3), f.frame()))
            .collect();
        let mut ctrl = Controller::new(cfg)?;
        if !s.ack {
            ctrl.set_no_ack();
        }
        Ok(Emulator {
            ctrl,
            script,
            next: 0,
            rate: 1.0 + s.ppm * 1e-6,
            phase: 0.0,
            own_cycle: 0,
            tx: true,
            sent: Vec::new(),
            received: Vec::new(),
            arb_lost: 0,
            errors: 0,
        })
    }

    /// Queues a frame now (for device models built on the node); false while busy.
    pub fn load(&mut self, f: &Frame) -> bool {
        self.ctrl.load(TxBuffer {
            id: f.id,
            ide: f.ide,
            rtr: f.rtr,
            dlc: f.dlc,
            data: f.packed(),
        })
    }

    /// One reference cycle: the node's own clock runs `1 + ppm·1e-6` cycles
    /// per reference cycle (0, 1 or 2 steps); returns its TXD level.
    pub fn step(&mut self, rx: bool) -> bool {
        self.phase += self.rate;
        while self.phase >= 1.0 {
            self.phase -= 1.0;
            if let Some((at, f)) = self.script.get(self.next) {
                if self.own_cycle >= *at && !self.ctrl.out().o_tx_busy {
                    let f = TxBuffer {
                        id: f.id,
                        ide: f.ide,
                        rtr: f.rtr,
                        dlc: f.dlc,
                        data: f.packed(),
                    };
                    self.ctrl.load(f);
                    self.next += 1;
                }
            }
            let out = self.ctrl.step(&In {
                i_can_rx: rx,
                ..In::default()
            });
            self.own_cycle += 1;
            if out.o_tx_done {
                let t = self.ctrl.seen();
                self.sent.push(Frame {
                    id: t.id,
                    ide: t.ide,
                    rtr: t.rtr,
                    dlc: t.dlc,
                    data: unpack(t.data, super::frame::data_len(t.dlc, t.rtr)),
                });
            }
            if out.o_rx_valid {
                self.received.push(Frame {
                    id: out.o_rx_id,
                    ide: out.o_rx_ide,
                    rtr: out.o_rx_rtr,
                    dlc: out.o_rx_dlc,
                    data: unpack(
                        out.o_rx_data,
                        super::frame::data_len(out.o_rx_dlc, out.o_rx_rtr),
                    ),
                });
            }
            self.arb_lost += out.o_arb_lost as u64;
            self.errors += (out.o_err_bit
                || out.o_err_stuff
                || out.o_err_crc
                || out.o_err_form
                || out.o_err_ack) as u64;
            self.tx = out.o_can_tx;
        }
        self.tx
    }

    /// How many of the next f_sys cycles of the bench, with `rx` held,
    /// leave this node's transmit level and everything it records unchanged:
    /// its controller only counting ([`Controller::quiet`]) and no scripted
    /// frame due before then on its own clock (one already due waits for
    /// the controller's buffer, which frees only on a sample point). A node
    /// with a ppm offset runs `rate` own cycles per bench cycle; the count
    /// is rounded down and one cycle of phase kept in hand.
    pub fn quiet(&self, rx: bool) -> u64 {
        self.quiet_given(self.ctrl.quiet(rx))
    }

    /// [`Emulator::quiet`] with a level on its way through the controller's
    /// synchroniser counted as quiet up to where it leaves it
    /// ([`Controller::quiet_crossing`]).
    pub fn quiet_crossing(&self, rx: bool) -> u64 {
        self.quiet_given(self.ctrl.quiet_crossing(rx))
    }

    /// The bench cycles quiet when the controller is quiet for `ctrl` of its own.
    fn quiet_given(&self, ctrl: u64) -> u64 {
        if ctrl == 0 || self.tx != self.ctrl.out().o_can_tx {
            return 0;
        }
        let own = match self.script.get(self.next) {
            Some((at, _)) if *at <= self.own_cycle && self.ctrl.out().o_tx_busy => ctrl,
            Some((at, _)) => at.saturating_sub(self.own_cycle).min(ctrl),
            None => ctrl,
        };
        if self.rate == 1.0 || own == u64::MAX {
            own
        } else {
            ((own.saturating_sub(1)) as f64 / self.rate)
                .floor()
                .max(1.0) as u64
                - 1
        }
    }

    /// Advances `n` bench cycles, at most [`Emulator::quiet`]: the own clock's
    /// phase cycle by cycle (the same additions as stepping), the controller
    /// by the own cycles that makes.
    pub fn skip(&mut self, n: u64) {
        let own = self.own_cycles(n);
        self.ctrl.skip(own);
    }

    /// [`Emulator::skip`] with `rx` held, at most [`Emulator::quiet_crossing`]
    /// ([`Controller::skip_crossing`]).
    pub fn skip_crossing(&mut self, n: u64, rx: bool) {
        let own = self.own_cycles(n);
        self.ctrl.skip_crossing(own, rx);
    }

    /// Runs the own clock's phase `n` bench cycles on: the own cycles it makes.
    fn own_cycles(&mut self, n: u64) -> u64 {
        let own = if self.rate == 1.0 {
            n
        } else {
            let mut k = 0;
            for _ in 0..n {
                self.phase += self.rate;
                while self.phase >= 1.0 {
                    self.phase -= 1.0;
                    k += 1;
                }
            }
            k
        };
        self.own_cycle += own;
        own
    }

    /// Whether the node has nothing left to send.
    pub fn done(&self) -> bool {
        self.next == self.script.len() && !self.ctrl.out().o_tx_busy
    }

    /// The node's controller.
    pub fn controller(&self) -> &Controller {
        &self.ctrl
    }

    /// Frames the node sent successfully.
    pub fn sent(&self) -> &[Frame] {
        &self.sent
    }

    /// Frames the node received.
    pub fn received(&self) -> &[Frame] {
        &self.received
    }

    /// Arbitrations the node lost.
    pub fn arbitrations_lost(&self) -> u64 {
        self.arb_lost
    }

    /// Errors the node detected.
    pub fn errors(&self) -> u64 {
        self.errors
    }
}
