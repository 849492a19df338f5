//! The value changes of chosen scalars of a VCD, in picoseconds.
//!
//! tbgen's `capture` module opens the file, reads the header and finds the
//! signals (its errors name the command-line option to fix); the body, one
//! command per value change of every signal in the file, is read here.

use std::fs::File;
use std::io::BufReader;

use model::wire::Signal;

/// The parser `tbgen` reads a capture file with.
pub type Parser = vcd::Parser<BufReader<File>>;

/// One unit of a VCD timescale as a fraction of a picosecond: `(mul, div)`,
/// a timestamp `ts` being `ts × mul / div` ps. A femtosecond timescale (what
/// Icarus and Verilator write by default with `timescale 1fs`) has `div =
/// 1000`: its times are rounded to the nearest picosecond, the decoders'
/// resolution (a line edge is never closer than a few ns to the next).
pub fn timescale_ps(header: &vcd::Header) -> (u64, u64) {
    let Some((n, unit)) = header.timescale else {
        return (1, 1);
    };
    let n = n as u64;
    match unit {
        vcd::TimescaleUnit::S => (n * 1_000_000_000_000, 1),
        vcd::TimescaleUnit::MS => (n * 1_000_000_000, 1),
        vcd::TimescaleUnit::US => (n * 1_000_000, 1),
        vcd::TimescaleUnit::NS => (n * 1_000, 1),
        vcd::TimescaleUnit::PS => (n, 1),
        vcd::TimescaleUnit::FS => (n, 1000),
    }
}

/// The latest time a capture may reach, ps: 2^62 ps, about 53 days. The
/// decoders reckon times as signed 64-bit picoseconds with room for sums
/// (a time plus a period); a later time is refused here, not clamped there.
pub const MAX_PS: u64 = 1 << 62;

/// Why the body of a capture could not be read.
#[derive(Debug)]
pub enum ScanError {
    /// The parser's error (a malformed command, or the disk).
    Io(std::io::Error),
    /// A timestamp beyond [`MAX_PS`].
    TimestampOverflow(u64),
    /// A timestamp below the one before it (`#later`, then `#earlier`):
    /// a VCD's times never go back, so the file is damaged or two were
    /// joined, and no decoder can read its edges in order.
    TimeGoesBack {
        /// The timestamp before.
        later: u64,
        /// The smaller one after it.
        earlier: u64,
    },
}

/// Reads the rest of `parser`'s file (its header already read) and returns
/// one [`Signal`] per `(name, id)` of `signals`, built from every change
/// command in file order with [`Signal::push`]: a level is high unless the
/// value is 0 (x and z read high, like the idle line). `scale` is
/// [`timescale_ps`] of the header.
pub fn read_scalars(
    parser: Parser,
    signals: &[(&str, vcd::IdCode)],
    scale: (u64, u64),
) -> Result<Vec<Signal>, ScanError> {
    read_scalars_to_end(parser, signals, scale).map(|(s, _)| s)
}

/// [`read_scalars`], and the capture's last timestamp in ps: until then
/// every signal is known to hold its last level (`tbgen gen` ends its VCD
/// with the run's last cycle, after the last change).
pub fn read_scalars_to_end(
    parser: Parser,
    signals: &[(&str, vcd::IdCode)],
    scale: (u64, u64),
) -> Result<(Vec<Signal>, u64), ScanError> {
    let (mul, div) = scale;
    let mut out: Vec<Signal> = signals
        .iter()
        .map(|&(name, _)| Signal {
            name: name.to_string(),
            changes: Vec::new(),
        })
        .collect();
    let mut t = 0u64;
    let mut last_ts = 0u64;
    for cmd in parser {
        match cmd.map_err(ScanError::Io)? {
            vcd::Command::Timestamp(ts) => {
                if ts < last_ts {
                    return Err(ScanError::TimeGoesBack {
                        later: last_ts,
                        earlier: ts,
                    });
                }
                last_ts = ts;
                let ps = (ts as u128 * mul as u128 + div as u128 / 2) / div as u128;
                t = u64::try_from(ps)
                    .ok()
                    .filter(|&t| t <= MAX_PS)
                    .ok_or(ScanError::TimestampOverflow(ts))?;
            }
            vcd::Command::ChangeScalar(code, v) => {
                let level = v != vcd::Value::V0;
                for (sig, &(_, id)) in out.iter_mut().zip(signals) {
                    if id == code {
                        sig.push(t, level);
                    }
                }
            }
            _ => {}
        }
    }
    Ok((out, t))
}
