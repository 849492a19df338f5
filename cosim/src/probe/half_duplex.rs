//! Stimuli of a half-duplex request/answer host (ESL, T-format) as its
//! transceiver drives them: bit 1 the driver's input D, bit 2 its enable DE
//! (bit 0, the clock of the clocked protocols, unused). A request is
//! 10-bit characters (start 0, 8 data LSB first, stop 1) sent while DE is
//! on; between requests the driver is off with D high.
//!
//! A request is built as runs of one level ([`runs`]), which a probe may
//! bend at one edge ([`shift`]) or pause in ([`pause`]), then driven
//! ([`driven`]).

use super::Stimulus;

/// The driver's input D.
pub const D: u32 = 1 << 1;
/// The driver's enable DE.
pub const DE: u32 = 1 << 2;

/// The driver off for `ps` (D high).
pub fn idle(ps: u64) -> (u32, u64) {
    (D, ps)
}

/// The levels of `fields` as 10-bit characters, one a bit.
pub fn bits(fields: &[u8]) -> Vec<bool> {
    fields
        .iter()
        .flat_map(|&f| {
            std::iter::once(false)
                .chain((0..8).map(move |i| f >> i & 1 == 1))
                .chain(std::iter::once(true))
        })
        .collect()
}

/// `levels` at `bit_ps` a bit, as runs of one level: run `k` (k >= 1)
/// begins at the request's edge `k`.
pub fn runs(levels: &[bool], bit_ps: u64) -> Vec<(bool, u64)> {
    let mut out: Vec<(bool, u64)> = Vec::new();
    for &l in levels {
        match out.last_mut() {
            Some(r) if r.0 == l => r.1 += bit_ps,
            _ => out.push((l, bit_ps)),
        }
    }
    out
}

/// The request's edge `k` moved by `delta` ps (later when positive).
pub fn shift(mut r: Vec<(bool, u64)>, k: usize, delta: i64) -> Vec<(bool, u64)> {
    r[k - 1].1 = r[k - 1].1.saturating_add_signed(delta);
    r[k].1 = r[k].1.saturating_add_signed(-delta);
    r
}

/// The request's line held high (D high, DE on) for `ps` more after the
/// character `field` (0 the first).
pub fn pause(levels: &[bool], field: usize, bit_ps: u64, ps: u64) -> Vec<(bool, u64)> {
    let split = 10 * (field + 1);
    let mut r = runs(&levels[..split], bit_ps);
    if let Some(last) = r.last_mut() {
        last.1 += ps;
    }
    let rest = runs(&levels[split..], bit_ps);
    r.extend(rest);
    r
}

/// The runs driven with DE on, DE held `hold_ps` after the last stop bit.
pub fn driven(r: &[(bool, u64)], hold_ps: u64) -> Stimulus {
    let mut s: Stimulus = r
        .iter()
        .map(|&(l, ps)| (DE | (l as u32) << 1, ps))
        .collect();
    match s.last_mut() {
        Some(last) => last.1 += hold_ps,
        None => s.push((DE | D, hold_ps)),
    }
    s
}

/// The length of a stimulus, ps.
pub fn length(s: &Stimulus) -> u64 {
    s.iter().map(|x| x.1).sum()
}

/// Requests each starting `every` ps after the one before (its first
/// start edge), the first after `lead` of idle, and idle `tail` after the
/// last.
pub fn spaced(lead: u64, every: &[u64], requests: &[Stimulus], tail: u64) -> Stimulus {
    let mut s = vec![idle(lead)];
    for (i, r) in requests.iter().enumerate() {
        s.extend(r.iter().copied());
        let len = length(r);
        let gap = every.get(i).map_or(tail, |&e| e - len);
        s.push(idle(gap));
    }
    s
}
