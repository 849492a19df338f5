//! GTKWave save files (`.gtkw`): the layout an engineer sees on
//! `make waves`: signals grouped by layer (line, core ports, decoded), full
//! vector names (`top.ssi_master.o_position[11:0]`), and a time range that
//! frames the first transaction.

use std::io::{self, Write};

/// GTKWave trace flags: `@28` binary, `@22` hex, `@24` decimal, group markers.
const FLAG_BINARY: &str = "@28";
const FLAG_HEX: &str = "@22";
const FLAG_GROUP_OPEN: &str = "@800200";
const FLAG_GROUP_CLOSE: &str = "@1000200";

/// Window size, and the widths of the hierarchy and signal-name panes; the
/// zoom is computed for what is left: the waveform pane.
const WINDOW_PX: f64 = 1400.0;
const SST_PX: f64 = 260.0;
const NAMES_PX: f64 = 300.0;

/// What to show.
pub struct Layout<'a> {
    /// The `.vcd` file name, relative to the `.gtkw` file.
    pub dumpfile: &'a str,
    /// `(group title, [full signal names])`, in display order.
    pub groups: &'a [(String, Vec<String>)],
    /// The time window to show at start, in ps: `(start, end)`.
    pub window_ps: (u64, u64),
    /// Scenario name, for the comment line.
    pub scenario: &'a str,
}

/// Writes the save file.
pub fn write(out: &mut impl Write, layout: &Layout) -> io::Result<()> {
    let (start, end) = layout.window_ps;
    let span = (end.saturating_sub(start)).max(1) as f64;
    // GTKWave's zoom z shows 2^-z time units per pixel (checked under Xvfb).
    let zoom = -(span / (WINDOW_PX - SST_PX - NAMES_PX)).log2();
    writeln!(out, "[*] tbgen layout for scenario {}", layout.scenario)?;
    writeln!(out, "[dumpfile] \"{}\"", layout.dumpfile)?;
    writeln!(out, "[timestart] {start}")?;
    writeln!(out, "[size] {} 800", WINDOW_PX as u32)?;
    writeln!(out, "[pos] -1 -1")?;
    writeln!(out, "*{zoom:.6} {start} -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1 -1")?;
    writeln!(out, "[sst_width] {}", SST_PX as u32)?;
    writeln!(out, "[signals_width] {}", NAMES_PX as u32)?;
    writeln!(out, "[sst_expanded] 1")?;
    writeln!(out, "[sst_vpaned_height] 200")?;
    for (title, names) in layout.groups {
        writeln!(out, "{FLAG_GROUP_OPEN}")?;
        writeln!(out, "-{title}")?;
        for name in names {
            let flag = if name.ends_with(']') { FLAG_HEX } else { FLAG_BINARY };
            writeln!(out, "{flag}")?;
            writeln!(out, "{name}")?;
        }
        writeln!(out, "{FLAG_GROUP_CLOSE}")?;
        writeln!(out, "-{title}")?;
    }
    writeln!(out, "[pattern_trace] 1")?;
    writeln!(out, "[pattern_trace] 0")?;
    Ok(())
}
