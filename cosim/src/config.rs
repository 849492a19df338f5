//! Reading an emulator's TOML: the scenario's own tables, errors that name
//! the file, the field and the fix, and the emulator-clock check.

use model::{ConfigError, Timebase};

/// What can go wrong making or driving an emulator. Every message names
/// where the problem is and what to do.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A field of the configuration is out of range or inconsistent.
    #[error("{origin}{}: {error}", line.map_or(String::new(), |l| format!(":{l}")))]
    Config {
        /// The file (or text) the configuration came from.
        origin: String,
        /// The 1-based line the field is written on, once [`Error::placed`].
        line: Option<usize>,
        /// The model's verdict, naming the field and the fix.
        error: ConfigError,
    },
    /// The TOML itself is malformed or has a field of the wrong type.
    #[error("{origin}{}: {message}", line.map_or(String::new(), |l| format!(":{l}")))]
    Toml {
        /// The file (or text) the configuration came from.
        origin: String,
        /// The 1-based line of the field of the wrong type, once
        /// [`Error::placed`] (a malformed text: the parser's message says it).
        line: Option<usize>,
        /// The parser's message.
        message: String,
    },
    /// A call the emulator cannot honour (bad handle, unknown status name...).
    #[error("{0}")]
    Usage(String),
}

impl Error {
    /// A configuration error of `origin`.
    pub fn config(origin: &str, error: ConfigError) -> Self {
        Error::Config {
            origin: origin.to_string(),
            line: None,
            error,
        }
    }

    /// The error with the line of `text` its field is written on, the
    /// field being under the protocol table `table` (`ssi`: `encoder.bits`
    /// is `[ssi.encoder]`'s `bits`), as `tbgen` places a scenario's errors.
    /// A field of the wrong type is found from the path the parser's
    /// message ends with (``in `encoder.bits```). The text may also be an
    /// emulator's own configuration, its fields at the top level.
    pub fn placed(self, text: &str, table: &str) -> Self {
        let line_of = |field: &str| {
            let at = |path: &str| model::toml_place::find(text, path);
            at(&format!("{table}.{field}"))
                .or_else(|| at(field))
                .or_else(|| model::toml_place::locate(text, &format!("{table}.{field}")))
                .map(|o| model::toml_place::line_column(text, o).0)
        };
        match self {
            Error::Config {
                origin,
                line: None,
                error,
            } => {
                let line = line_of(error.field());
                Error::Config {
                    origin,
                    line,
                    error,
                }
            }
            Error::Toml {
                origin,
                line: None,
                message,
            } if !message.contains(" line ") => {
                let field = message
                    .rsplit_once(" in `")
                    .map(|(_, path)| path.trim_end_matches('`').to_string());
                let line = field.and_then(|f| line_of(&f));
                Error::Toml {
                    origin,
                    line,
                    message,
                }
            }
            other => other,
        }
    }

    /// A field error of `origin`.
    pub fn field(
        origin: &str,
        field: impl Into<String>,
        problem: impl Into<String>,
        fix: impl Into<String>,
    ) -> Self {
        Error::config(origin, ConfigError::invalid(field, problem, fix))
    }
}

/// Keys of a scenario's protocol table that describe the master or the host
/// side: an emulator reads a whole scenario file and leaves them alone.
pub const SCENARIO_ONLY: &[&str] = &[
    "master",
    "host",
    "f_sys_mhz",
    "reads",
    "name",
    "description",
    "monitor",
];

/// The emulator's own table: `[emulator]` in a device file, `[<proto>.emulator]`
/// in a scenario file.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EmulatorSettings {
    /// The fastest line clock the emulator must follow, kHz (default: the
    /// protocol's maximum); the emulator clock must be at least 4 times it.
    pub max_line_clock_khz: Option<f64>,
}

/// A configuration split into the device's tables and the emulator's own.
pub struct Tables {
    /// The protocol table with the scenario-only keys removed.
    pub device: toml::Table,
    /// `[emulator]`.
    pub emulator: EmulatorSettings,
}

/// Parses `text` and returns the protocol's tables: those under `[proto]`
/// when the text is a scenario file, else the top level.
pub fn tables(text: &str, origin: &str, proto: &str) -> Result<Tables, Error> {
    let root: toml::Table = text.parse().map_err(|e: toml::de::Error| Error::Toml {
        origin: origin.to_string(),
        line: None,
        message: one_line(&e.to_string()),
    })?;
    let mut device = match root.get(proto) {
        // In a scenario file the emulator's settings are the protocol's
        // (`[<proto>.emulator]`); a top-level `[emulator]` beside `[<proto>]`
        // would be silently ignored, so it is an error.
        Some(toml::Value::Table(_)) if root.contains_key("emulator") => {
            return Err(Error::field(
                origin,
                "emulator",
                format!(
                    "is a top-level table in a scenario file with [{proto}], where it is not read"
                ),
                format!("write it as [{proto}.emulator]"),
            ))
        }
        Some(toml::Value::Table(t)) => t.clone(),
        Some(_) => {
            return Err(Error::field(
                origin,
                proto,
                "is not a table",
                format!("write [{proto}] as a table header"),
            ))
        }
        None => {
            let mut t = root.clone();
            t.remove("name");
            t.remove("description");
            t
        }
    };
    for key in SCENARIO_ONLY {
        device.remove(*key);
    }
    let emulator = match device.remove("emulator") {
        Some(v) => v.try_into().map_err(|e: toml::de::Error| Error::Toml {
            origin: origin.to_string(),
            line: None,
            message: format!("{} in `emulator`", one_line(&e.to_string())),
        })?,
        None => EmulatorSettings {
            max_line_clock_khz: None,
        },
    };
    Ok(Tables { device, emulator })
}

/// Deserialises a table into `T`, naming `origin` in the error.
pub fn decode<T: serde::de::DeserializeOwned>(
    table: toml::Table,
    origin: &str,
) -> Result<T, Error> {
    toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| Error::Toml {
            origin: origin.to_string(),
            line: None,
            message: one_line(&e.to_string()),
        })
}

/// A sub-table (`monitor`, `master`, `checks`, `encoder`), empty when absent.
pub fn sub(table: &toml::Table, key: &str, origin: &str) -> Result<toml::Table, Error> {
    match table.get(key) {
        None => Ok(toml::Table::new()),
        Some(toml::Value::Table(t)) => Ok(t.clone()),
        Some(_) => Err(Error::field(
            origin,
            key,
            "is not a table",
            format!("write [{key}] as a table header"),
        )),
    }
}

/// Deserialises `table`'s sub-table `key` (empty when absent) into `T`; a
/// field of the wrong type is named from the protocol table on (`in
/// `encoder.bits``, not `in `bits``), so that [`Error::placed`] finds it.
pub fn decode_in<T: serde::de::DeserializeOwned>(
    table: &toml::Table,
    key: &str,
    origin: &str,
) -> Result<T, Error> {
    decode(sub(table, key, origin)?, origin).map_err(|e| match e {
        Error::Toml {
            origin,
            line,
            message,
        } => {
            let message = match message.rsplit_once(" in `") {
                Some((what, path)) => format!("{what} in `{key}.{path}"),
                None => format!("{message} in `{key}`"),
            };
            Error::Toml {
                origin,
                line,
                message,
            }
        }
        other => other,
    })
}

fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// Checks the emulator clock and returns its timebase: it must be a usable
/// clock (any whole number of hertz up to 1 GHz, as [`Timebase::new`]
/// accepts for the model's system clock) and at least 4 times the fastest line clock
/// (two samples per half period, as the cores need with `CLOCKS_PER_BIT >= 4`).
pub fn emulator_clock(
    f_emu_hz: u64,
    settings: &EmulatorSettings,
    default_max_khz: f64,
    proto: &str,
    origin: &str,
) -> Result<Timebase, Error> {
    let max_khz = settings.max_line_clock_khz.unwrap_or(default_max_khz);
    if !(max_khz > 0.0 && max_khz <= 1e6) {
        return Err(Error::field(
            origin,
            "emulator.max_line_clock_khz",
            format!("{max_khz} kHz"),
            "give the fastest line clock in kHz",
        ));
    }
    let minimum = (4.0 * max_khz * 1e3).ceil() as u64;
    if f_emu_hz < minimum {
        return Err(Error::Usage(format!(
            "{origin}: emulator clock f_emu = {f_emu_hz} Hz is too slow for {proto}: it must be at least 4 x the fastest line clock ({max_khz} kHz), i.e. at least {minimum} Hz; \
             give a faster emulator clock, or set emulator.max_line_clock_khz to the fastest clock your master uses"
        )));
    }
    // Any clock up to 1 GHz, as the model's system clock:
    // the emulator counts cycles, and times (checks, motion profiles) come
    // from the exact n x 10^12 / f_emu through the shared Timebase.
    Timebase::new(f_emu_hz).map_err(|e| {
        Error::Usage(format!(
            "{origin}: emulator clock f_emu = {f_emu_hz} Hz: {e}"
        ))
    })
}
