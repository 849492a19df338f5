//! The reads of an SSI line from its clock and data, as the master sees
//! them: the decode core of `tbgen decode ssi` (from a capture) and of the
//! co-simulation monitor `ssi_monitor` (from the pins it samples).
//!
//! A read is one burst of the clock: its first falling edge from the idle
//! high line stores the value in the encoder (the seed's `T_cs`, SAR58K24
//! manual, SSI section (4)), and each following low phase carries one bit,
//! MSB first, which the master samples in that low phase. The decoder reads
//! each bit at the end of its low phase (just before the rising edge): the
//! encoder changes its output on rising edges, so the bit is settled there
//! however long the cable. A read ends at a rising edge followed by more
//! than three half periods of high clock (the pause, `T_m`).

use serde::Serialize;

use crate::wire::Signal;

/// How the reads are laid out.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// Value bits per read; `None`: every sampled bit (less a copy or a wire-check bit).
    pub bits: Option<u32>,
    /// The value is Gray-coded.
    pub gray: bool,
    /// Each read carries the value twice.
    pub double_read: bool,
    /// Each read carries one more bit, which must be 0.
    pub wire_check: bool,
}

/// One read seen on the line.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ReadSeen {
    /// 0-based read number.
    pub index: usize,
    /// The first falling edge (the encoder stores its value), ps.
    pub start_ps: u64,
    /// The last rising edge, ps.
    pub end_ps: u64,
    /// The bits read, in order.
    pub received_bits: String,
    /// The value, binary.
    pub position: Option<u64>,
    /// `double_read_mismatch`, `wire_check_failed`.
    pub errors: Vec<String>,
}

/// The bits a Gray or binary word of `bits` carries, as a binary value.
fn value(bits: &str, gray: bool) -> u64 {
    let mut v = 0u64;
    let mut last = false;
    for c in bits.chars() {
        let b = c == '1';
        let bin = if gray { last ^ b } else { b };
        last = bin;
        v = (v << 1) | bin as u64;
    }
    v
}

/// The bursts of `clk` as `(first falling edge, last edge, bits read)`, ps.
pub fn bursts(clk: &Signal, data: &Signal) -> Vec<(u64, u64, String)> {
    let edges = clk.edges();
    // The clock's typical half period, the median gap between its edges: a
    // burst's own second gap is its half period, unless the capture opened
    // inside a read and the burst has no second low phase (then that gap
    // is the idle line, and every later read would join the burst).
    let mut gaps: Vec<u64> = edges.windows(2).map(|w| w[1].0 - w[0].0).collect();
    let typical = match gaps.len() {
        0 => u64::MAX,
        n => *gaps.select_nth_unstable((n - 1) / 2).1,
    };
    let mut reads = Vec::new();
    let mut i = 0;
    while i < edges.len() {
        if edges[i].1 {
            i += 1;
            continue;
        }
        // A burst: from this falling edge, edges no further apart than three
        // of its half periods (the first low phase, T_cs, may be longer: the
        // half period is taken from the second gap on).
        let mut j = i + 1;
        let mut half: Option<u64> = None;
        while j < edges.len() {
            let gap = edges[j].0 - edges[j - 1].0;
            if j > i + 1 && gap > 3 * *half.get_or_insert(gap.min(typical)) {
                break;
            }
            j += 1;
        }
        let burst = &edges[i..j];
        // Low phases after the first: (falling, rising) pairs from the second falling edge.
        let mut bits = String::new();
        for w in burst.windows(2).skip(1) {
            if !w[0].1 && w[1].1 {
                bits.push(if data.level_at(w[1].0.saturating_sub(1)) {
                    '1'
                } else {
                    '0'
                });
            }
        }
        let end_ps = burst.last().map_or(burst[0].0, |e| e.0);
        reads.push((burst[0].0, end_ps, bits));
        i = j;
    }
    reads
}

/// Every read of the line. Fails (with a message that says which read and
/// what `bits` would fit) when a read carries another number of bits than
/// `layout` reads.
pub fn decode(clk: &Signal, data: &Signal, layout: &Layout) -> Result<Vec<ReadSeen>, String> {
    bursts(clk, data)
        .into_iter()
        .enumerate()
        .map(|(index, (start_ps, end_ps, bits))| read(index, start_ps, end_ps, bits, layout))
        .collect()
}

/// One read from its bits.
pub fn read(
    index: usize,
    start_ps: u64,
    end_ps: u64,
    bits: String,
    layout: &Layout,
) -> Result<ReadSeen, String> {
    let copies = if layout.double_read { 2 } else { 1 };
    let extra = layout.wire_check as u32;
    let n = bits.len() as u32;
    let width = match layout.bits {
        Some(b) => {
            if b * copies + extra != n {
                let fits = n
                    .checked_sub(extra)
                    .filter(|m| m % copies == 0 && *m > 0)
                    .map(|m| m / copies);
                let hint = fits.map_or_else(
                    || "no --bits fits with these options".to_string(),
                    |b| format!("--bits {b} would fit"),
                );
                return Err(format!(
                    "read {index} at {start_ps} ps carries {n} bits, but --bits {b}{}{} reads {}: {hint}",
                    if layout.double_read { " with --double-read" } else { "" },
                    if layout.wire_check { " with --wire-check" } else { "" },
                    b * copies + extra
                ));
            }
            b
        }
        None => n.saturating_sub(extra) / copies,
    };
    let mut errors = Vec::new();
    let position = (width > 0 && width <= 64).then(|| value(&bits[..width as usize], layout.gray));
    if layout.double_read
        && n >= 2 * width
        && bits[..width as usize] != bits[width as usize..2 * width as usize]
    {
        errors.push("double_read_mismatch".to_string());
    }
    if layout.wire_check && bits.ends_with('1') {
        errors.push("wire_check_failed".to_string());
    }
    Ok(ReadSeen {
        index,
        start_ps,
        end_ps,
        received_bits: bits,
        position,
        errors,
    })
}
