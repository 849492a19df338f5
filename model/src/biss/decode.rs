//! The frames of a BiSS-C line from MA and SLO at the master's end: the
//! decode core of `tbgen decode biss` (from a capture) and of the
//! co-simulation monitor `biss_monitor` (from the pins it samples).
//!
//! A frame is one burst of MA (edges no further apart than three half
//! periods, seed 001, BiSS-C): its first rising edge latches, the slave's
//! ack is SLO falling after the second, then the start bit, and per slave
//! CDS, data (MSB first), nE, nW and the inverted CRC, each cell read half
//! an MA period after the rising edge that sent it plus the round-trip
//! delay the ack showed.

use serde::Serialize;

use super::{control, data_crc, MAX_SLAVES};
use crate::angle::angle_deg;
use crate::wire::Signal;

/// One slave's part of a decoded frame: the fields of the `gen`
/// transcript's `slaves` entries that the line shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlaveSeen {
    /// Chain position.
    pub slave: u8,
    /// The decoded data.
    pub position: u64,
    /// `360° × position / 2^bits`, cut to 4 decimals.
    pub angle_deg: f64,
    /// nE was 0.
    pub error: bool,
    /// nW was 0.
    pub warning: bool,
    /// The CDS bit.
    pub cds: bool,
    /// The CRC matched.
    pub crc_ok: bool,
}

/// One decoded frame, with the field names of the model's transaction in the
/// `gen` transcript. Left out, because only the model knows them: cycle
/// numbers, what the slave was told to send. Times are in ps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrameSeen {
    /// 0-based, counting the frames visible on MA.
    pub index: usize,
    /// The first falling MA edge, ps.
    pub start_ps: u64,
    /// Second rising MA edge to the ack at the master's end, ps, when the ack
    /// came while MA was running.
    pub delay_ps: Option<u64>,
    /// The CDM bit: MA stopped low after the last clock.
    pub cdm: bool,
    /// Control-frame index of that bit, when a control frame was running.
    pub control_index: Option<u32>,
    /// Every bit read after the ack (start bit first).
    pub received_bits: String,
    /// Each slave's result, in chain order.
    pub slaves: Vec<SlaveSeen>,
    /// `no_ack`, `delay_beyond_compensation`, `no_start_bit`, per slave
    /// `crc_error_slave<i>`; `short_frame` (fewer than two rising MA edges,
    /// a capture cut short) is the decoder's own.
    pub errors: Vec<String>,
    /// A register access that ended with this frame.
    pub register: Option<RegisterSeen>,
    /// A command (`CTS = 0`) that ended with this frame.
    pub command: Option<CommandSeen>,
    /// Cells MA clocked after the start bit, and the cells the layout reads.
    #[serde(skip)]
    pub cells: Option<(u64, u64)>,
}

/// A command read off the CDM and CDS bits: the fields of the `gen`
/// transcript's `command`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CommandSeen {
    /// Slave-select bits IDS (0 = broadcast).
    pub ids: u8,
    /// The command.
    pub code: u8,
    /// Every selected slave acknowledged (IDA) and echoed EX.
    pub ok: bool,
    /// The CDM bits sent, `k = 0` to the frame that ended the command.
    pub cdm: String,
}

/// A register access read off the CDM and CDS bits: the fields of the `gen`
/// transcript's `register`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegisterSeen {
    /// Write or read.
    pub write: bool,
    /// Slave ID.
    pub id: u8,
    /// Address.
    pub addr: u8,
    /// Data written (0 on a read); left out when the access ended before
    /// the master sent it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wdata: Option<u8>,
    /// Data read, or the slave's echo of a write, as far as it came.
    pub rdata: u8,
    /// The access succeeded.
    pub ok: bool,
    /// `false` when the answer came with a wrong CRC-4.
    pub crc4_ok: bool,
    /// The CDM bits sent, `k = 0` to the frame that ended the access.
    pub cdm: String,
}

/// Per-slave layout the decoder expects.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// Data bits per slave.
    pub bits: Vec<u32>,
    /// CRC width per slave.
    pub crc_width: Vec<u32>,
    /// CRC polynomial per slave.
    pub crc_poly: Vec<u64>,
    /// The slaves' timeout, ps, when known: a frame ends when MA has not
    /// changed for it (the slave's meaning, as [`super::rules`] follows
    /// frames). Unknown (a capture without its configuration), a burst ends
    /// at a gap of more than three of its first half periods.
    pub timeout_ps: Option<u64>,
}

/// The decoder's state between frames: the frame count and the control
/// frames in progress (a register access or command spans many frames), so
/// a monitor can feed it one frame at a time.
#[derive(Debug, Clone, Default)]
pub struct Decoder {
    observer: control::Observer,
    next_index: usize,
}

impl Decoder {
    /// Decodes every frame of the MA and SLO lines at the master's end: the
    /// ack edge gives the round-trip delay, and each bit is read half an MA
    /// period after its rising edge plus that delay. Control frames are
    /// followed from the CDM (MA level after the last clock) and CDS bits by
    /// the master's rules ([`control::Observer`]).
    pub fn feed(&mut self, ma_line: &Signal, slo_line: &Signal, layout: &Layout) -> Vec<FrameSeen> {
        let edges = ma_line.edges();
        let mut frames = Vec::new();
        let mut i = 0;
        while i < edges.len() {
            if edges[i].1 {
                i += 1; // MA returning high after a CDM = 1 timeout
                continue;
            }
            // A burst: edges closer than the slaves' timeout, or, that
            // unknown, no further apart than 3 half periods.
            let mut j = i + 1;
            let mut half = None;
            while j < edges.len() {
                let gap = edges[j].0 - edges[j - 1].0;
                let ends = match layout.timeout_ps {
                    Some(t) => gap >= t,
                    None => gap > 3 * *half.get_or_insert(gap),
                };
                if ends {
                    break;
                }
                j += 1;
            }
            let burst = &edges[i..j];
            let next_start = edges[j..].iter().find(|e| !e.1).map_or(u64::MAX, |e| e.0);
            let mut f = read_frame(self.next_index, burst, next_start, slo_line, layout);
            self.next_index += 1;
            f.control_index = self.observer.index(f.cdm);
            let ok = f.errors.iter().all(|e| e.starts_with("crc_error"));
            let mut view = control::FrameView {
                ok,
                cdm: f.cdm,
                slaves: f.slaves.len(),
                ..Default::default()
            };
            for s in f.slaves.iter().filter(|s| (s.slave as usize) < MAX_SLAVES) {
                view.cds[s.slave as usize] = s.cds;
                view.crc_bad[s.slave as usize] = !s.crc_ok;
            }
            if let Some(o) = self.observer.take(&view) {
                let a = o.access;
                let cdm = crate::bits::string(&control::cdm_sequence(&a)[..=o.last_k as usize]);
                if a.command {
                    f.command = Some(CommandSeen {
                        ids: a.ids,
                        code: a.code,
                        ok: o.ok,
                        cdm,
                    });
                } else {
                    let wdata_seen = !a.write || o.last_k >= control::K_DATA_CRC - 1;
                    f.register = Some(RegisterSeen {
                        write: a.write,
                        id: a.id,
                        addr: a.addr,
                        wdata: wdata_seen.then_some(a.wdata),
                        rdata: o.rdata,
                        ok: o.ok,
                        crc4_ok: o.crc4_ok,
                        cdm,
                    });
                }
            }
            frames.push(f);
            i = j;
        }
        frames
    }
}

/// Cells MA clocks after the last CRC bit before it stops (the master's
/// stop bit and the first timeout clock, as biss_master does): not frame bits.
const TRAILING_CELLS: u64 = 2;

/// A layout that fits no frame (every frame clocked a different number of
/// cells after its start bit than the layout reads, and every CRC failed) is
/// the wrong `--bits` or `--crc-width`, not a line full of errors: say so,
/// and what would fit. `reread` decodes the line again with another layout:
/// the hint is the last slave's data width with which every frame's every
/// CRC passes (the MA clocks alone cannot tell it: a master compensating a
/// long line clocks a cell more per period of delay).
pub fn check_layout(
    frames: &[FrameSeen],
    layout: &Layout,
    reread: impl Fn(&Layout) -> Vec<FrameSeen>,
) -> Result<(), String> {
    let read: Vec<&FrameSeen> = frames.iter().filter(|f| f.cells.is_some()).collect();
    let misfit = |f: &&FrameSeen| {
        f.cells.is_some_and(|(clocked, need)| clocked != need) && f.slaves.iter().all(|s| !s.crc_ok)
    };
    if read.is_empty() || !read.iter().all(misfit) {
        return Ok(());
    }
    let (_, need) = read[0].cells.expect("filtered on cells");
    let list = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(",");
    let fits = |l: &Layout| {
        let again = reread(l);
        let read: Vec<&FrameSeen> = again.iter().filter(|f| f.cells.is_some()).collect();
        !read.is_empty()
            && read
                .iter()
                .all(|f| !f.slaves.is_empty() && f.slaves.iter().all(|s| s.crc_ok))
    };
    let hint = (1..=64u32)
        .map(|n| {
            let mut l = layout.clone();
            *l.bits.last_mut().expect("at least one slave") = n;
            l
        })
        .find(|l| l.bits != layout.bits && fits(l))
        .map(|l| format!("; with the same CRC widths, --bits {} would fit (every CRC passes)", list(&l.bits)))
        .unwrap_or_else(|| "; no data width of the last slave from 1 to 64 makes every CRC pass with these CRC widths: check --crc-width and the lines".to_string());
    Err(format!(
        "--bits {} with --crc-width {} read {need} bits after the start bit (per slave: CDS, data, nE, nW, CRC), and every frame's CRC fails{hint}",
        list(&layout.bits),
        list(&layout.crc_width),
    ))
}

/// One frame from its MA burst (falling edge first) and SLO; `next_start`
/// bounds the search for a late ack.
fn read_frame(
    index: usize,
    burst: &[(u64, bool)],
    next_start: u64,
    slo: &Signal,
    layout: &Layout,
) -> FrameSeen {
    let t0 = burst[0].0;
    let cdm = burst.last().is_some_and(|e| !e.1);
    let mut f = FrameSeen {
        index,
        start_ps: t0,
        delay_ps: None,
        cdm,
        control_index: None,
        received_bits: String::new(),
        slaves: Vec::new(),
        errors: Vec::new(),
        register: None,
        command: None,
        cells: None,
    };
    let rises: Vec<u64> = burst.iter().filter(|e| e.1).map(|e| e.0).collect();
    if rises.len() < 2 || burst.len() < 2 {
        f.errors.push("short_frame".into());
        return f;
    }
    // One MA period from rising edge to rising edge: with an odd divider the
    // high and low phases differ (the high one takes the extra cycle), so
    // twice the first low phase would be a cycle short and drift by a cycle
    // per bit.
    let period = rises[1] - rises[0];
    let r2 = rises[1];
    let last = burst[burst.len() - 1].0;
    // The ack is SLO falling after the second rising edge, while MA runs; a
    // later one is beyond the master's compensation, none at all no ack.
    match slo.next_level(r2, false) {
        Some(ack) if ack <= last => {
            let delay = ack - r2;
            f.delay_ps = Some(delay);
            read_sections(&mut f, r2 + delay, period, rises.len() as u64, slo, layout);
        }
        Some(ack) if ack < next_start => f.errors.push("delay_beyond_compensation".into()),
        _ => f.errors.push("no_ack".into()),
    }
    f
}

/// The start bit and every slave's section, cell `m` read at
/// `ack + m·period + period/2` (the middle of the cell that rising edge
/// `2 + m` sent), while MA clocked it (`m <= rises - 2`).
fn read_sections(
    f: &mut FrameSeen,
    ack: u64,
    period: u64,
    rises: u64,
    slo: &Signal,
    layout: &Layout,
) {
    let cell = |m: u64| slo.level_at(ack + m * period + period / 2);
    let Some(start) = (1..=rises.saturating_sub(2)).find(|&m| cell(m)) else {
        f.errors.push("no_start_bit".into());
        return;
    };
    let need: u64 = layout
        .bits
        .iter()
        .zip(&layout.crc_width)
        .map(|(n, w)| (1 + n + 2 + w) as u64)
        .sum();
    f.cells = Some((
        rises
            .saturating_sub(2 + TRAILING_CELLS)
            .saturating_sub(start),
        need,
    ));
    let mut m = start;
    let mut received = vec![true];
    for s in 0..layout.bits.len() {
        let (n, w) = (layout.bits[s] as usize, layout.crc_width[s] as usize);
        let section: Vec<bool> = (1..=(1 + n + 2 + w) as u64).map(|k| cell(m + k)).collect();
        m += section.len() as u64;
        received.extend(&section);
        let covered = &section[1..1 + n + 2];
        let alg = data_crc(w as u32, layout.crc_poly[s]);
        let crc_ok =
            alg.crc_from_wire_bits(&section[1 + n + 2..]) == Some(alg.checksum_bits(covered));
        let position = covered[..n].iter().fold(0u64, |a, &b| (a << 1) | b as u64);
        if !crc_ok {
            f.errors.push(format!("crc_error_slave{s}"));
        }
        f.slaves.push(SlaveSeen {
            slave: s as u8,
            position,
            angle_deg: angle_deg(position, n as u32),
            error: !covered[n],
            warning: !covered[n + 1],
            cds: section[0],
            crc_ok,
        });
    }
    f.received_bits = crate::bits::string(&received);
}
