//! The transactions of an EnDat line read at the master's pins (clock and
//! data), in the shape of the `gen` transcript: the decode core of `tbgen
//! decode endat` (from a capture) and of the co-simulation monitor
//! `endat_monitor` (from the pins it samples).
//!
//! The clock tells the transactions apart (a burst of falling edges, ended
//! by the clock staying high for more than a period) and the master's own
//! bits: the mode bits at `R2..R7`, the parameter block of a type 2.1
//! command at `R8..R36` and that of a type 2.2 command on the burst's last 29
//! rising edges (the master drives at falling edges; the level at the next
//! rising edge is the bit). The encoder's bits arrive later by the round
//! trip, which the capture shows: the encoder drives the line low at
//! `R_off` (`R8`, `R37`), so the first low level after `R_off` gives a first
//! round trip. Each bit is then read as a master reads it: at the rising edge
//! that launched it plus the frame's round trip (the mean over the frame's
//! data edges of each edge's time after its launching rising edge) plus half
//! a period, so that jitter on the cable moves no sample out of its cell
//! (`FrameTiming`). Whether the master saw the
//! start bit at all follows from the burst's length: the master stops the
//! clock right after the frame's last bit, so a burst too short for the
//! frame means it gave up polling (`no_start_bit`).
//!
//! The frames are judged by `model::endat::LineJudge`, the master's own
//! receive and check logic, fed request by request: CRCs, F1/F2, the
//! acknowledgements, error types II to IV and the additional-data selection
//! it tracks are the master's. What a line capture cannot show is left out:
//! a start the master refused (`line_not_idle`, `not_calibrated`: no clock
//! at all), the mode bits under a data line stuck at the master's receiver
//! (the capture shows the stuck level), `delay_drift` (it compares the start bit with the delay the
//! master measured, which is inside the master), the verdict of a delay
//! measurement, and the MRS code and parameter of commands that send no
//! block.

use serde::Serialize;

use super::{error_names, frame_kind, Command, FrameKind, LineJudge, Out, BLOCK_BITS};
use crate::wire::Signal;

/// What the decoder needs to know that the line does not say.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Position bits of the encoder (word 13 of its manufacturer parameters).
    pub pos_bits: u32,
    /// Clock of the master's delay measurement in kHz, if it measures: 000111 bursts at this clock (±3 %) are
    /// measurement frames, and a run of them is one `delay_measurement`.
    pub meas_khz: Option<f64>,
}

/// One transaction, with the field names and meanings of the `gen` transcript.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// `command`, `continuous_value` or `delay_measurement`.
    pub kind: String,
    /// The command's name, if the mode bits are a mode command.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub command: Option<String>,
    /// The six mode bits on the line.
    pub mode: String,
    /// MRS code / address of the master's block (commands with a block).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mrs: Option<u8>,
    /// Parameter of the master's block.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub param: Option<u16>,
    /// The latching falling edge `F1`, ps.
    pub start_ps: u64,
    /// Position or test value.
    pub position: Option<u64>,
    /// F1.
    pub f1: Option<bool>,
    /// F2.
    pub f2: Option<bool>,
    /// Additional datum 1, hex.
    pub ad1: Option<String>,
    /// Additional datum 2, hex.
    pub ad2: Option<String>,
    /// Acknowledged address and data (type 2.1 parameter frames).
    pub ack: Option<(u8, u16)>,
    /// What the master flags (the `gen` names), `block_crc` for a master block with a wrong CRC and `framing`
    /// for a clock burst too short for the mode bits or the turnaround; absent for a delay measurement.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub errors: Option<Vec<String>>,
}

/// The clock edges of one burst: `falls[k]` is `F_(k+1)`, `rises[k]` is `R_(k+1)`.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Burst {
    /// The falling edges, ps.
    pub falls: Vec<u64>,
    /// The rising edges, ps.
    pub rises: Vec<u64>,
}

impl Burst {
    /// Clock period, ps (the clock is periodic from `F2`).
    pub fn period(&self) -> Option<u64> {
        match (self.falls.get(1), self.falls.get(2), self.rises.first()) {
            (Some(f2), Some(f3), _) => Some(f3 - f2),
            (Some(f2), None, Some(r1)) => Some((f2 - r1).saturating_mul(2)),
            _ => None,
        }
    }

    /// Whether a falling edge at `t_ps` continues the burst (else it starts the
    /// next one): until `F2` every one does; from then on the clock high for
    /// more than twice the high phase `R1..F2` ends the burst.
    pub fn continues_at(&self, t_ps: u64) -> bool {
        let high_for = t_ps.saturating_sub(self.rises.last().copied().unwrap_or(t_ps));
        match (self.falls.get(1), self.rises.first()) {
            (Some(f2), Some(r1)) => high_for <= (f2 - r1).saturating_mul(2),
            _ => self.falls.len() < 2,
        }
    }

    /// The six mode bits (the line at `R2..R7`), if the burst is that long.
    pub fn mode(&self, data: &Signal) -> Option<u8> {
        self.bits_at_rises(data, 2, 7)
            .map(|bits| bits.iter().fold(0u8, |a, &x| (a << 1) | x as u8))
    }

    /// A frame of the master's delay measurement: `000111` at `opts.meas_khz` (±3 %).
    pub fn is_measurement(&self, data: &Signal, opts: &Options) -> bool {
        let khz = self.period().map_or(0.0, |p| 1e9 / p as f64);
        self.mode(data) == Some(Command::Pos21.code())
            && opts.meas_khz.is_some_and(|m| (khz - m).abs() <= 0.03 * m)
    }

    /// The level of `line` at each rising edge `R_from..=R_to` (1-based).
    pub fn bits_at_rises(&self, line: &Signal, from: usize, to: usize) -> Option<Vec<bool>> {
        (from..=to)
            .map(|k| self.rises.get(k - 1).map(|&t| line.level_at(t)))
            .collect()
    }
}

/// Splits the clock into bursts: a falling edge after the clock was high for more than a period starts one.
pub fn bursts(clk: &Signal) -> Vec<Burst> {
    let mut out: Vec<Burst> = Vec::new();
    let mut cur: Option<Burst> = None;
    for (t, level) in clk.edges() {
        if let Some(b) = cur.as_mut() {
            if level {
                b.rises.push(t);
                continue;
            }
            if b.continues_at(t) {
                b.falls.push(t);
                continue;
            }
            out.extend(cur.take());
        }
        if !level {
            cur = Some(Burst {
                falls: vec![t],
                rises: Vec::new(),
            });
        }
    }
    out.extend(cur);
    out
}

/// The master's receive and check logic between bursts: what a decoder of a
/// line carries from one transaction to the next (the additional-data
/// selection the master tracks, a run of measurement frames).
#[derive(Debug, Clone)]
pub struct Decoder {
    judge: LineJudge,
    last_was_measurement: bool,
}

impl Decoder {
    /// A decoder in the master's power-on state; fails when `opts.pos_bits` is not 1 to 48.
    pub fn new(opts: &Options) -> Result<Decoder, String> {
        let range = super::master::POSITION_BITS;
        if !range.contains(&opts.pos_bits) {
            return Err(format!(
                "decode endat: --pos-bits {} is not {} to {}",
                opts.pos_bits,
                range.start(),
                range.end()
            ));
        }
        Ok(Decoder {
            judge: LineJudge::new(opts.pos_bits),
            last_was_measurement: false,
        })
    }

    /// The transactions of one burst (none for a measurement frame that continues a run).
    pub fn burst(&mut self, b: &Burst, data: &Signal, opts: &Options) -> Vec<Transaction> {
        let mut out = Vec::new();
        let Some(period) = b.period() else {
            out.push(framing(b)); // fewer than 3 falling edges
            self.last_was_measurement = false;
            return out;
        };
        let Some(mode) = b.mode(data) else {
            out.push(framing(b)); // the clock stopped within the mode bits
            self.last_was_measurement = false;
            return out;
        };
        if b.is_measurement(data, opts) {
            if !self.last_was_measurement {
                out.push(Transaction {
                    kind: "delay_measurement".into(),
                    ..blank(b, mode)
                });
            }
            self.last_was_measurement = true;
            return out;
        }
        self.last_was_measurement = false;
        decode_burst(b, period, mode, data, &mut self.judge, &mut out);
        out
    }
}

/// Every transaction of a line (`clk` and `data` at the master).
pub fn decode(clk: &Signal, data: &Signal, opts: &Options) -> Result<Vec<Transaction>, String> {
    let mut decoder = Decoder::new(opts)?;
    Ok(bursts(clk)
        .iter()
        .flat_map(|b| decoder.burst(b, data, opts))
        .collect())
}

fn blank(b: &Burst, mode: u8) -> Transaction {
    Transaction {
        kind: "command".into(),
        command: Command::from_code(mode).map(|c| c.name().to_string()),
        mode: format!("{mode:06b}"),
        mrs: None,
        param: None,
        start_ps: b.falls[0],
        position: None,
        f1: None,
        f2: None,
        ad1: None,
        ad2: None,
        ack: None,
        errors: None,
    }
}

/// A burst too short to be a transaction.
fn framing(b: &Burst) -> Transaction {
    Transaction {
        kind: "command".into(),
        command: None,
        mode: String::new(),
        errors: Some(vec!["framing".into()]),
        ..blank(b, 0)
    }
}

/// MRS code / address, parameter and whether the block's CRC is right, from 29 bits.
fn block(bits: &[bool]) -> (u8, u16, bool) {
    let word = bits.iter().fold(0u64, |a, &x| (a << 1) | x as u64);
    let (mrs, param, crc) = ((word >> 21) as u8, (word >> 5) as u16, (word & 0x1F) as u8);
    (mrs, param, crc == super::crc_norm(mrs, param))
}

fn decode_burst(
    b: &Burst,
    period: u64,
    mode: u8,
    data: &Signal,
    judge: &mut LineJudge,
    out: &mut Vec<Transaction>,
) {
    let kind = frame_kind(mode);
    let k_off = if kind == FrameKind::Param21 {
        8 + BLOCK_BITS as usize
    } else {
        8
    };
    let n = b.falls.len();
    let mut t = blank(b, mode);
    let mut extra = Vec::new();
    let blk = match kind {
        FrameKind::Param21 => b.bits_at_rises(data, 8, 36),
        FrameKind::Block22 if n >= BLOCK_BITS as usize => {
            b.bits_at_rises(data, n + 1 - BLOCK_BITS as usize, n)
        }
        _ => None,
    };
    let (mrs, param) = match blk.map(|bits| block(&bits)) {
        Some((mrs, param, crc_ok)) => {
            if !crc_ok {
                extra.push("block_crc".to_string());
            }
            (Some(mrs), Some(param))
        }
        None => (None, None),
    };
    judge.begin(mode, mrs.unwrap_or(0), param.unwrap_or(0));
    // A type 2.1 block precedes the answer, so it is on the line even if no answer comes; a type 2.2 block follows
    // the frame and is only sent after one.
    let before = kind == FrameKind::Param21;
    if before {
        (t.mrs, t.param) = (mrs, param);
    }
    let extra_if_aborted = if before { extra.clone() } else { Vec::new() };
    let Some(&r_off) = b.rises.get(k_off - 1) else {
        t.errors = Some(vec!["framing".into()]);
        out.push(t);
        return;
    };
    let last_rise = *b.rises.last().unwrap_or(&r_off);
    // The encoder drives low from R_off: its arrival is the round trip; none before the clock stops: not driven.
    let low = data
        .next_level(r_off, false)
        .filter(|&tl| tl <= last_rise.saturating_add(period));
    let Some(t_low) = low else {
        finish(&mut t, judge.aborted(false), kind, extra_if_aborted);
        out.push(t);
        judge.end();
        return;
    };
    let round_trip = t_low - r_off;
    let mut from = t_low;
    let mut first = true;
    loop {
        // The start bit: launched at R_j, seen by the master at sample j + 1; the frame must fit the burst.
        let frame_bits = judge.frame_bits();
        let start = data.next_level(from, true).map(|ts| {
            (
                ts,
                FrameTiming::of(b, data, ts, round_trip, period, frame_bits),
            )
        });
        let seen = start.filter(|(_, ft)| n >= ft.j.saturating_add(1 + frame_bits as usize));
        let Some((_, ft)) = seen else {
            if first {
                finish(&mut t, judge.aborted(true), kind, extra_if_aborted);
                out.push(t);
            }
            break;
        };
        // Bit i after the start bit leaves at R_(j+1+i) and is read in the middle of its cell.
        let bits: Vec<bool> = (0..frame_bits as usize)
            .map(|i| data.level_at(ft.arrival(b, ft.j + i, period).saturating_add(period / 2)))
            .collect();
        let o = judge.frame(&bits);
        let mut v = t.clone();
        if !first {
            v.kind = "continuous_value".into();
        }
        v.mrs = mrs;
        v.param = param;
        finish(&mut v, o, kind, extra.clone());
        out.push(v);
        first = false;
        // Continuous clock (000111 only): further values while the clock runs on.
        if mode != Command::Pos21.code() {
            break;
        }
        let end = ft.arrival(b, ft.j + frame_bits as usize, period);
        match data.next_level(end, false) {
            // Only forward: each value starts after the last one's start.
            Some(tl) if tl <= last_rise && tl > from => from = tl,
            _ => break,
        }
    }
    judge.end();
}

/// Where the master reads one frame: the rising edge that launched its start bit and the round trip of its bits.
///
/// The master samples each bit a fixed delay after the rising edge that launched it (its measured delay, or a
/// fixed one), not from the start bit's own edge: with jitter on the cable each edge of the answer arrives a
/// little early or late, and a bit read a set time after the start bit's edge drifts with that edge's jitter
/// (with ±25 ns on each line at 8 MHz by more than half a cell). So the decoder reads like a master: the round
/// trip is the mean, over the frame's data edges, of each edge's time minus the rising edge that launched it,
/// and bit `i` is read at its launching edge plus that round trip plus half a period. An answer reads right
/// as long as each of its edges stays less than half a period from that mean (the mean of many edges moves
/// little with one late or early edge); an unjittered answer reads exactly (all its edges are one round trip
/// after their rising edges, and the samples fall where the old reading from the start bit put them).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct FrameTiming {
    /// The start bit leaves at `R_j` (1-based, so `b.rises[j - 1]`).
    j: usize,
    /// Mean arrival of the frame's edges after their launching rising edge, ps (negative only under jitter
    /// larger than the cable's delay).
    round_trip: i64,
}

impl FrameTiming {
    /// The timing of the frame whose start bit rises at `ts`, `frame_bits` bits after it; `rt0` is a first
    /// estimate of the round trip (the first low after `R_off`), only used for its whole periods.
    fn of(
        b: &Burst,
        data: &Signal,
        ts: u64,
        rt0: u64,
        period: u64,
        frame_bits: u64,
    ) -> FrameTiming {
        let p = ps(period.max(1));
        let r1 = ps(b.rises.first().copied().unwrap_or(0));
        // The frame's edges: the start bit's and those between its bits, not the one after its last bit (what
        // follows the frame need not be launched by the clock), nor any after the clock stopped.
        let last = b
            .rises
            .last()
            .copied()
            .unwrap_or(0)
            .saturating_add(rt0)
            .saturating_add(period / 2);
        let until = ts
            .saturating_add(frame_bits.saturating_mul(period))
            .saturating_add(period / 2)
            .min(last.max(ts));
        let lo = data.changes.partition_point(|&(t, _)| t < ts);
        let hi = data.changes.partition_point(|&(t, _)| t <= until);
        let mut edges: Vec<i64> = (lo..hi)
            .filter(|&i| data.changes[i].1 != (i == 0 || data.changes[i - 1].1))
            .map(|i| ps(data.changes[i].0))
            .collect();
        if edges.is_empty() {
            edges.push(ps(ts));
        }
        // The round trip modulo the period: the circular mean of the edges' phases after R1, which needs no
        // first guess (a guess from one jittered edge can be off by more than half a period from another).
        let (sin, cos) = edges.iter().fold((0.0f64, 0.0f64), |(s, c), &t| {
            let angle = (t - r1).rem_euclid(p) as f64 / p as f64 * std::f64::consts::TAU;
            (s + angle.sin(), c + angle.cos())
        });
        let phase =
            sin.atan2(cos).rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU * p as f64;
        let guess = phase + ((rt0 as f64 - phase) / p as f64).round() * p as f64;
        // Each edge against its launching rising edge (the one nearest the edge less the guess), then the mean.
        let sum: i128 = edges.iter().map(|&t| launch(b, t, guess).1 as i128).sum();
        let round_trip = (sum as f64 / edges.len() as f64).round() as i64;
        FrameTiming {
            j: launch(b, ps(ts), round_trip as f64).0 + 1,
            round_trip,
        }
    }

    /// When the bit launched at rising edge `b.rises[k]` (0-based; extrapolated past the burst) reaches the master.
    fn arrival(&self, b: &Burst, k: usize, period: u64) -> u64 {
        let rise = match (b.rises.get(k), b.rises.last()) {
            (Some(&r), _) => r,
            (None, Some(&last)) => {
                last.saturating_add(((k + 1 - b.rises.len()) as u64).saturating_mul(period))
            }
            (None, None) => 0,
        };
        ps(rise).saturating_add(self.round_trip).max(0) as u64
    }
}

/// A time in ps as a signed number (captures end long before 2^62 ps, about 53 days).
fn ps(t: u64) -> i64 {
    t.min(1 << 62) as i64
}

/// The rising edge (0-based index into `b.rises`) that launched an edge arriving at `t` after about `round_trip`
/// ps, and the edge's time after it.
fn launch(b: &Burst, t: i64, round_trip: f64) -> (usize, i64) {
    let k = b
        .rises
        .partition_point(|&r| (ps(r) as f64) < t as f64 - round_trip);
    [k.checked_sub(1), (k < b.rises.len()).then_some(k)]
        .into_iter()
        .flatten()
        .map(|k| (k, t - ps(b.rises[k])))
        .min_by(|x, y| {
            (x.1 as f64 - round_trip)
                .abs()
                .total_cmp(&(y.1 as f64 - round_trip).abs())
        })
        .unwrap_or((0, t))
}

/// The fields `gen` fills from the master's outputs at `o_done`.
fn finish(t: &mut Transaction, o: Out, kind: FrameKind, extra: Vec<String>) {
    let aborted = o.o_err_timeout || o.o_err_absent;
    if !aborted {
        if kind == FrameKind::Param21 {
            t.ack = Some((o.o_ack_addr, o.o_ack_data));
        } else {
            t.position = Some(o.o_position);
            t.f1 = Some(o.o_f1);
            t.f2 = Some(o.o_f2);
            t.ad1 = o.o_ad1_valid.then(|| format!("{:06x}", o.o_ad1));
            t.ad2 = o.o_ad2_valid.then(|| format!("{:06x}", o.o_ad2));
        }
    }
    let mut errors = error_names(&o);
    errors.extend(extra);
    t.errors = Some(errors);
}
