//! sigrok's `can` decoder on the scenarios with errors and overload frames.
//!
//! The plain check (`Protocol::sigrok` in `mod.rs`) compares sigrok's
//! values in order, which works only while every frame on the line is a
//! frame. With errors, sigrok's decoder (libsigrokdecode `can`, 0.5/0.7)
//! does not report them: its `is_valid_crc` always answers true, it has no
//! stuff-error check, and `decode_error_frame` / `decode_overload_frame`
//! are empty. It reads an error or overload flag as the start of a frame
//! of its own, decodes whatever follows as that frame's fields, and is
//! back in step only after its own idea of that frame's end-of-frame, when
//! the line next goes dominant. So here each sigrok frame is located by
//! its start-of-frame sample (`--protocol-decoder-samplenum`) and matched
//! to the transaction that starts there:
//!
//! * a complete frame of the transcript (its fields all on the line; an
//!   error at or after the ACK delimiter, or none) that sigrok starts at
//!   the same SOF must carry the same identifier (and extension), DLC,
//!   data, CRC sequence and ACK slot, whatever the error was;
//! * a frame cut by an error (`complete = false`): its SOF must be found;
//!   the transcript holds no fields of it, so none are compared;
//! * a complete frame sigrok has no SOF for must fall inside a frame
//!   sigrok was decoding at that time (it was reading a flag as a frame);
//! * a sigrok frame at no transaction's SOF must start after the first
//!   error or overload of the scenario (a flag read as a frame).
//!
//! sigrok re-synchronises on every recessive-to-dominant edge, without the
//! SJW limit, so on a bus longer than the timing allows or with a clock
//! beyond the tolerance it can read a late bit (an ACK from a far node) that
//! the core, held to SJW, reads as recessive: there (`within_limits` false)
//! the ACK slot is not compared, and sigrok frames that match no
//! transaction are allowed anywhere (the core lost them, sigrok did not).
//!
//! What sigrok cannot report, and so is not compared: the error type and
//! where it was detected, error and overload flags and delimiters, the
//! fields of a frame cut by an error, and any frame it missed while it was
//! out of step.

use serde_json::Value;

use crate::registry::SigrokCheck;

/// The `-A` option: the field annotations, with the start and end of frame.
pub const ANNOTATIONS: &str = "can=sof:eof:id:ext-id:dlc:data:crc-sequence:ack-slot";

/// One frame as sigrok printed it: its first sample, its last, its values.
#[derive(Debug, Default)]
struct Frame {
    start: u64,
    end: u64,
    values: Vec<u128>,
    /// The first sample of each value.
    starts: Vec<u64>,
}

/// What the comparison found.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Counts {
    /// Complete frames compared field by field.
    pub frames: usize,
    /// Values compared.
    pub values: usize,
    /// Frames cut by an error whose SOF sigrok found.
    pub cut: usize,
    /// Complete frames sigrok missed while out of step.
    pub missed: usize,
    /// sigrok frames that are flags read as frames.
    pub flags: usize,
}

/// Frames of sigrok-cli's output (`ss-es can-1: text` lines).
fn frames(lines: &[String]) -> Result<Vec<Frame>, String> {
    let mut out: Vec<Frame> = Vec::new();
    for line in lines {
        let Some((span, text)) = line.split_once(' ') else { continue };
        let Some(text) = text.strip_prefix("can-1: ") else { continue };
        let (ss, es) = span.split_once('-').ok_or_else(|| format!("sigrok line `{line}`: no sample span"))?;
        let (ss, es): (u64, u64) = (ss.parse().map_err(|_| format!("sigrok line `{line}`"))?, es.parse().map_err(|_| format!("sigrok line `{line}`"))?);
        if text == "Start of frame" {
            out.push(Frame { start: ss, end: es, values: Vec::new(), starts: Vec::new() });
        } else if let Some(f) = out.last_mut() {
            f.end = es;
            if text == "End of frame" {
                continue;
            }
            f.values.push(SigrokCheck::value(text).ok_or_else(|| format!("sigrok printed `{text}`, not a value"))?);
            f.starts.push(ss);
        }
    }
    Ok(out)
}

/// The values sigrok prints for a complete transaction, as the plain check
/// builds them (a remote frame with DLC > 0: up to its DLC, since sigrok
/// reads DLC × 8 data bits into it).
fn expected(tr: &Value) -> Option<(Vec<u128>, bool)> {
    let mut v = Vec::new();
    let id = tr["id"].as_u64()? as u128;
    if tr["ide"].as_bool()? {
        v.push(id >> 18);
        v.push(id & 0x3FFFF);
    } else {
        v.push(id);
    }
    let dlc = tr["dlc"].as_u64()?;
    v.push(dlc as u128);
    if tr["rtr"].as_bool()? && dlc > 0 {
        return Some((v, true));
    }
    for b in tr["data"].as_array()? {
        v.push(b.as_u64()? as u128);
    }
    v.push(tr["crc"].as_u64()? as u128);
    v.push(tr["ack"].as_bool()? as u128);
    Some((v, false))
}

/// Compares sigrok's output `lines` (run with [`ANNOTATIONS`] and
/// `--protocol-decoder-samplenum`, one sample per f_sys cycle) with the
/// transcript's `transactions`; `bit` is the bit time in cycles and
/// `sample` the sample point's offset in cycles.
pub fn check(lines: &[String], transactions: &[Value], bit: u64, sample: u64, within_limits: bool) -> Result<Counts, String> {
    let frames = frames(lines)?;
    let mut used = vec![false; frames.len()];
    let mut c = Counts::default();
    // sigrok's start of frame is one bit before its SOF sample point; the
    // transcript's, the core's sample point of SOF after the synchroniser.
    let at = |sof: u64| frames.iter().position(|f| (f.start + sample).abs_diff(sof) <= bit / 4);
    let mut first_fault = u64::MAX;
    let mut prev_cycle = 0;
    for (i, tr) in transactions.iter().enumerate() {
        let sof = tr["sof_cycle"].as_u64().ok_or_else(|| format!("transaction {i}: no sof_cycle"))?;
        let complete = tr["complete"].as_bool().ok_or_else(|| format!("transaction {i}: no complete"))?;
        let cycle = tr["cycle"].as_u64().unwrap_or(u64::MAX);
        if tr["outcome"].as_str().is_some_and(|o| o.starts_with("err_")) {
            first_fault = first_fault.min(cycle.saturating_sub(2 * bit));
        }
        if tr["overloads"].as_u64().unwrap_or(0) > 0 {
            // A transaction counts the overload frames before it, after the previous one's end.
            first_fault = first_fault.min(prev_cycle);
        }
        prev_cycle = cycle;
        match (at(sof), complete) {
            (Some(k), true) => {
                used[k] = true;
                let (mut want, cut) = expected(tr).ok_or_else(|| format!("transaction {i}: fields missing"))?;
                let got = &frames[k].values;
                // The ACK slot is compared when the frame reached it: no
                // error before it (a form error at the CRC delimiter puts
                // an error flag in the slot), and edges within SJW.
                let reached = frames[k].starts.get(want.len() - 1).is_some_and(|&ss| cycle + bit / 2 >= ss + sample);
                if !cut && (!within_limits || !reached) {
                    want.pop();
                }
                let n = if cut || want.len() < got.len() { want.len() } else { got.len() };
                if got.len() < n || got.len() < want.len() || got[..n] != want[..] {
                    return Err(format!("transaction {i} (SOF at cycle {sof}): sigrok read {got:x?}, the transcript says {want:x?}"));
                }
                c.frames += 1;
                c.values += want.len();
            }
            (Some(k), false) => {
                used[k] = true;
                c.cut += 1;
            }
            (None, true) => {
                if !frames.iter().any(|f| f.start < sof && sof <= f.end + bit) {
                    return Err(format!("transaction {i}: a complete frame from cycle {sof} that sigrok neither found nor was inside another frame for"));
                }
                c.missed += 1;
            }
            (None, false) => {
                // A frame cut early while sigrok decoded a flag: nothing on the line to compare.
                c.missed += 1;
            }
        }
    }
    for (k, f) in frames.iter().enumerate().filter(|(k, _)| !used[*k]) {
        // Beyond the limits sigrok, re-synchronising on every edge, reads
        // frames the core (held to SJW) cannot follow.
        if f.start < first_fault && within_limits {
            return Err(format!("sigrok frame {k} at sample {} matches no transaction and comes before any error or overload flag", f.start));
        }
        c.flags += 1;
    }
    Ok(c)
}
