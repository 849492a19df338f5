//! GTKWave save files (`.gtkw`): the layout an engineer sees on
//! `make waves`: signals grouped by layer (line, decoded, core ports: the
//! decoded group second so that it shows in an 800-pixel-high window), full
//! vector names (`top.ssi_master.o_position[11:0]`), state registers named
//! through translate filter files (`<core>.<signal>.filter`, made from the
//! model's enums), and a time range that frames the first transaction.
//!
//! Where the files are found: GTKWave 3.3 opens a save file's `[dumpfile]`
//! as given, relative to the current folder, unless the file also has a
//! `[savefile]` line; then it takes the path from the `[savefile]` to the
//! `[dumpfile]` and applies it to where the save file is now (`find_dumpfile`
//! in gtkwave's `savefile.c`). Both lines name bare file names, so the
//! committed files hold no path of this machine and `gtkwave out/x.gtkw`
//! works from any folder. Filter files (`^1 name`) are looked up next to
//! the save file the same way.

use std::io::{self, Write};

/// GTKWave trace flags: `@28` binary, `@22` hex, `@24` decimal, group markers.
const FLAG_BINARY: &str = "@28";
const FLAG_HEX: &str = "@22";
const FLAG_GROUP_OPEN: &str = "@800200";
const FLAG_GROUP_CLOSE: &str = "@1000200";

/// Window size, and the widths of the hierarchy and signal-name panes.
const WINDOW_PX: f64 = 1400.0;
const SST_PX: f64 = 260.0;
const NAMES_PX: f64 = 300.0;
/// The waveform pane's width that GTKWave 3.3 reports (`getWaveWidth`) for
/// that window and those panes, under Xvfb: the zoom is computed for it.
pub const WAVE_PX: f64 = 800.0;
/// GTKWave's pixels per zoom frame: at zoom `z` one frame of `2^-z` time
/// units spans this many pixels, so a pixel is `2^-z / 200` units
/// (`pixelsperframe` in GTKWave's zoom code). Checked by
/// `scripts/check_gtkw.sh`, which asks GTKWave for the time at the window's
/// right edge (`getWindowEndTime`) rather than working it out from the zoom.
const GTKWAVE_PIXELS_PER_FRAME: f64 = 200.0;

/// `@22` plus GTKWave's file-translated flag (`TR_FTRANSLATED`, 0x2000).
const FLAG_HEX_TRANSLATED: &str = "@2022";

/// A GTKWave translate filter file: one `value name` line per value, the
/// value in hex as the trace shows it.
pub fn filter_file(names: &[(u64, String)]) -> String {
    names.iter().map(|(v, n)| format!("{v:X} {n}\n")).collect()
}

/// The filter file's name for `signal` of `core` (`ssi_master.state.filter`).
pub fn filter_name(core: &str, signal: &str) -> String {
    format!("{core}.{signal}.filter")
}

/// What to show.
pub struct Layout<'a> {
    /// The `.vcd` file name, relative to the `.gtkw` file.
    pub dumpfile: &'a str,
    /// `(group title, [full signal names])`, in display order.
    pub groups: &'a [(String, Vec<String>)],
    /// The time window to show at start, in ps: `(start, end)`.
    pub window_ps: (u64, u64),
    /// The dump's last time, ps: GTKWave opens a window that would run past
    /// it at time 0 instead, so the window is moved to end there.
    pub dump_end_ps: u64,
    /// Scenario name, for the comment line and `[savefile]`.
    pub scenario: &'a str,
    /// Full signal names shown through a filter file, and the file's name.
    pub filters: &'a [(String, String)],
}

/// Writes the save file.
pub fn write(out: &mut impl Write, layout: &Layout) -> io::Result<()> {
    let (start, end) = layout.window_ps;
    let span = (end.saturating_sub(start)).max(1) as f64;
    // The zoom at which WAVE_PX pixels show `span` time units, rounded
    // down to the six decimals written, so that the window shows at least
    // `span`; and what it then shows.
    let zoom = (-(span * GTKWAVE_PIXELS_PER_FRAME / WAVE_PX).log2() * 1e6).floor() / 1e6;
    let shown = 2f64.powf(-zoom) * WAVE_PX / GTKWAVE_PIXELS_PER_FRAME;
    let start = if start as f64 + shown > layout.dump_end_ps as f64 {
        (layout.dump_end_ps as f64 - shown).floor().max(0.0) as u64
    } else {
        start
    };
    writeln!(out, "[*] tbgen layout for scenario {}", layout.scenario)?;
    writeln!(out, "[dumpfile] \"{}\"", layout.dumpfile)?;
    writeln!(out, "[savefile] \"{}.gtkw\"", layout.scenario)?;
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
            match layout.filters.iter().find(|(n, _)| n == name) {
                Some((_, file)) => {
                    writeln!(out, "{FLAG_HEX_TRANSLATED}")?;
                    writeln!(out, "^1 {file}")?;
                }
                None => writeln!(
                    out,
                    "{}",
                    if name.ends_with(']') {
                        FLAG_HEX
                    } else {
                        FLAG_BINARY
                    }
                )?,
            }
            writeln!(out, "{name}")?;
        }
        writeln!(out, "{FLAG_GROUP_CLOSE}")?;
        writeln!(out, "-{title}")?;
    }
    writeln!(out, "[pattern_trace] 1")?;
    writeln!(out, "[pattern_trace] 0")?;
    Ok(())
}
