//! The encoder as a node on the bit-level bus: an [`Encoder`] behind a
//! generic CAN node ([`crate::can::Emulator`]) with its own transceiver
//! place, oscillator offset and bit timing from its bit-rate code.
//!
//! ```text
//!  can::Emulator (controller) ── o_rx_valid ──> Encoder::on_frame ──> queue (+ response_delay) ──> load when !o_tx_busy
//!                                 every cycle ──> Encoder::poll  ─────┘   (one frame at a time, in the order produced)
//! ```
//! A reset that changes the bit-rate code (5000h) rebuilds the controller
//! at the new bit rate; it integrates 11 recessive bits before sending its
//! boot-up, as after power-on.

use std::collections::VecDeque;

use super::encoder::{Encoder, EncoderConfig, BIT_RATES_KBPS};
use crate::can::emulator::NodeSettings;
use crate::can::frame::Frame;
use crate::can::{BitTiming, ControllerConfig, Emulator};
use crate::{ConfigError, Result, Timebase};

/// Bit timing rules shared by every node of a bench: quanta per bit,
/// sample point, SJW and synchroniser flops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeTiming {
    /// Quanta per bit wanted (another from 25 down to 8 is taken if this one does not divide f_sys).
    pub tq_per_bit: u32,
    /// Sample point, fraction of the bit.
    pub sample_point: f64,
    /// SJW, quanta.
    pub sjw: u32,
    /// Synchroniser flops.
    pub sync_stages: u32,
}

impl Default for NodeTiming {
    fn default() -> Self {
        NodeTiming {
            tq_per_bit: 16,
            sample_point: 0.875,
            sjw: 1,
            sync_stages: 2,
        }
    }
}

impl NodeTiming {
    /// The controller configuration for `kbps` at `tb`.
    pub fn controller(&self, tb: &Timebase, kbps: u32) -> Result<ControllerConfig> {
        let f = tb.f_sys_hz();
        let tries = std::iter::once(self.tq_per_bit).chain((8..=25).rev());
        for tq in tries {
            if let Ok(t) =
                BitTiming::for_rate(f, kbps as f64 * 1e3, tq, self.sample_point, self.sjw)
            {
                return Ok(ControllerConfig {
                    timing: t,
                    sync_stages: self.sync_stages,
                });
            }
        }
        Err(ConfigError::invalid("f_sys_mhz", format!("{} Hz has no bit timing of 8 to 25 quanta for {kbps} kbit/s", f), "choose f_sys a multiple of the bit rate × 8 .. 25 (40 MHz fits every rate but 800 kbit/s; 48 or 64 MHz fit all)"))
    }
}

/// A CANopen device at frame level, as a node drives it.
pub trait Device {
    /// Power-on: the frames it sends (its boot-up).
    fn power_on(&mut self, now_ns: u64) -> Vec<Frame>;
    /// The answers to a received frame.
    fn on_frame(&mut self, f: &Frame, now_ns: u64) -> Vec<Frame>;
    /// Frames due by `now_ns`.
    fn poll(&mut self, now_ns: u64) -> Vec<Frame>;
    /// The earliest time [`Device::poll`] has a frame to give (its timers:
    /// cyclic period, heartbeat, life guarding), `None` without a timer
    /// running. Until then a poll only records the time.
    fn next_due_ns(&self) -> Option<u64>;
    /// The bit rate in use, kbit/s.
    fn bit_rate_kbps(&self) -> u32;
    /// Time from a request to its answer, µs.
    fn response_delay_us(&self) -> f64;
}

impl Device for Encoder {
    fn power_on(&mut self, now_ns: u64) -> Vec<Frame> {
        Encoder::power_on(self, now_ns)
    }
    fn on_frame(&mut self, f: &Frame, now_ns: u64) -> Vec<Frame> {
        Encoder::on_frame(self, f, now_ns)
    }
    fn poll(&mut self, now_ns: u64) -> Vec<Frame> {
        Encoder::poll(self, now_ns)
    }
    fn next_due_ns(&self) -> Option<u64> {
        Encoder::next_due_ns(self)
    }
    fn bit_rate_kbps(&self) -> u32 {
        BIT_RATES_KBPS[self.bit_code() as usize]
    }
    fn response_delay_us(&self) -> f64 {
        self.config().response_delay_us
    }
}

/// The DS 406 encoder on the bus.
pub type EncoderNode = DeviceNode<Encoder>;

/// A device on the bus.
#[derive(Debug, Clone)]
pub struct DeviceNode<D> {
    enc: D,
    emu: Emulator,
    settings: NodeSettings,
    timing: NodeTiming,
    tb: Timebase,
    rate: u32,
    queue: VecDeque<(u64, Frame)>,
    seen: usize,
    cycle: u64,
    delay: u64,
    received: Vec<(u64, Frame)>,
}

impl EncoderNode {
    /// The encoder of `cfg` at power-on (its boot-up queued).
    pub fn new(
        cfg: &EncoderConfig,
        settings: &NodeSettings,
        timing: NodeTiming,
        tb: &Timebase,
    ) -> Result<EncoderNode> {
        DeviceNode::with(Encoder::new(cfg)?, settings, timing, tb)
    }
}

impl<D: Device> DeviceNode<D> {
    /// `dev` at power-on (its boot-up queued).
    pub fn with(
        mut enc: D,
        settings: &NodeSettings,
        timing: NodeTiming,
        tb: &Timebase,
    ) -> Result<DeviceNode<D>> {
        let boot = enc.power_on(0);
        let rate = enc.bit_rate_kbps();
        let emu = Emulator::new(
            &NodeSettings {
                frames: Vec::new(),
                ..settings.clone()
            },
            timing.controller(tb, rate)?,
            tb,
        )?;
        let delay = tb.cycles_nearest_ns(enc.response_delay_us() * 1e3);
        Ok(DeviceNode {
            enc,
            emu,
            settings: settings.clone(),
            timing,
            tb: *tb,
            rate,
            queue: boot.into_iter().map(|f| (0, f)).collect(),
            seen: 0,
            cycle: 0,
            delay,
            received: Vec::new(),
        })
    }

    fn now_ns(&self) -> u64 {
        self.tb.ps_at(self.cycle) / 1000
    }

    /// One reference cycle; returns the node's TXD level.
    pub fn step(&mut self, rx: bool) -> bool {
        let now = self.now_ns();
        let ready = self.cycle + self.delay;
        // Most cycles bring no frame and nothing due: no copy, no extend.
        if self.seen < self.emu.received().len() {
            let new: Vec<Frame> = self.emu.received()[self.seen..].to_vec();
            self.seen += new.len();
            for f in new {
                self.received.push((self.cycle, f.clone()));
                let out = self.enc.on_frame(&f, now);
                self.queue.extend(out.into_iter().map(|f| (ready, f)));
            }
        }
        let due = self.enc.poll(now);
        if !due.is_empty() {
            self.queue.extend(due.into_iter().map(|f| (self.cycle, f)));
        }
        if self.enc.bit_rate_kbps() != self.rate {
            // A reset applied a new bit rate (5000h): the controller restarts at the new rate.
            self.rate = self.enc.bit_rate_kbps();
            if let Ok(cc) = self.timing.controller(&self.tb, self.rate) {
                if let Ok(e) = Emulator::new(
                    &NodeSettings {
                        frames: Vec::new(),
                        ..self.settings.clone()
                    },
                    cc,
                    &self.tb,
                ) {
                    self.emu = e;
                    self.seen = 0;
                }
            }
        }
        if let Some((t, f)) = self.queue.front() {
            if *t <= self.cycle && !self.emu.controller().out().o_tx_busy && self.emu.load(f) {
                self.queue.pop_front();
            }
        }
        self.cycle += 1;
        self.emu.step(rx)
    }

    /// How many of the next cycles, with `rx` held, leave the node's
    /// transmit level and everything it records unchanged: no received
    /// frame unread, nothing queued to send before then (an answer waits
    /// out the response delay), no device timer due before then (the first
    /// cycle whose time reaches [`Device::next_due_ns`]) and its CAN node
    /// quiet ([`Emulator::quiet`]).
    pub fn quiet(&self, rx: bool) -> u64 {
        if self.emu.received().len() != self.seen || self.enc.bit_rate_kbps() != self.rate {
            return 0;
        }
        let mut q = self.emu.quiet(rx);
        if let Some((t, _)) = self.queue.front() {
            q = q.min(t.saturating_sub(self.cycle));
        }
        if let Some(due) = self.enc.next_due_ns() {
            q = q.min(self.cycles_before_ns(due));
        }
        q
    }

    /// Cycles from now before the first one whose time (in whole ns, as
    /// `step` reads it) reaches `due`.
    fn cycles_before_ns(&self, due: u64) -> u64 {
        let at_ns = |c: u64| self.tb.ps_at(c) / 1000;
        if at_ns(self.cycle) >= due {
            return 0;
        }
        let f = self.tb.f_sys_hz() as u128;
        let mut x =
            ((due as u128 * 1000 * f) / 1_000_000_000_000).max(self.cycle as u128 + 1) as u64;
        while x > self.cycle + 1 && at_ns(x - 1) >= due {
            x -= 1;
        }
        while at_ns(x) < due {
            x += 1;
        }
        x - self.cycle
    }

    /// Advances `n` cycles, at most [`DeviceNode::quiet`]: the device is
    /// polled once at the last of them (nothing is due, so the poll only
    /// records the time, as the `n` polls of stepping leave it), the CAN
    /// node is skipped.
    pub fn skip(&mut self, n: u64) {
        if n == 0 {
            return;
        }
        let now = self.tb.ps_at(self.cycle + n - 1) / 1000;
        let due = self.enc.poll(now);
        debug_assert!(due.is_empty(), "a skip passed a device timer");
        self.cycle += n;
        self.emu.skip(n);
    }

    /// The device.
    pub fn encoder(&self) -> &D {
        &self.enc
    }

    /// The encoder, to move its disk or raise an alarm (queue the frames it returns with [`EncoderNode::send`]).
    pub fn encoder_mut(&mut self) -> &mut D {
        &mut self.enc
    }

    /// Queues frames to send now.
    pub fn send(&mut self, frames: Vec<Frame>) {
        let c = self.cycle;
        self.queue.extend(frames.into_iter().map(|f| (c, f)));
    }

    /// Frames the node sent, in order.
    pub fn sent(&self) -> &[Frame] {
        self.emu.sent()
    }

    /// Frames the node received, with the reference cycle it handed each to the encoder.
    pub fn received(&self) -> &[(u64, Frame)] {
        &self.received
    }

    /// The node's CAN node (controller, counters).
    pub fn can(&self) -> &Emulator {
        &self.emu
    }

    /// The time now, ns.
    pub fn time_ns(&self) -> u64 {
        self.now_ns()
    }
}
