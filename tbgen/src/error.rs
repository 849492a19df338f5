//! The one error type of `tbgen`. Every message names the file, the line or
//! field, and the fix; [`Error::exit_code`] is 2 for bad input, 1 otherwise.

use std::path::PathBuf;

/// What can go wrong in `tbgen`.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The scenario file is not valid TOML or has a misspelt or mistyped field.
    #[error("{file}:{line}:{column}: {message}")]
    ScenarioSyntax {
        /// The scenario file (or `builtin:<name>`).
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message (it names the field).
        message: String,
    },
    /// The scenario parses but asks for something the model cannot do.
    #[error("{file}:{line}: {source}")]
    ScenarioValue {
        /// The scenario file (or `builtin:<name>`).
        file: String,
        /// 1-based line of the field, or of the table it belongs in.
        line: usize,
        /// The model's error, which names the field and the fix.
        source: model::ConfigError,
    },
    /// A structural problem the parser cannot see (no protocol table, bad name).
    #[error("{file}: {message}")]
    Scenario {
        /// The scenario file (or `builtin:<name>`).
        file: String,
        /// What is wrong and how to fix it.
        message: String,
    },
    /// Neither a built-in scenario nor an existing file: the name, and a
    /// suggestion (` (did you mean ...?)`) or nothing.
    #[error(
        "no scenario `{0}`{1}: `tbgen list` shows the built-in ones; a file must end in .toml"
    )]
    UnknownScenario(String, String),
    /// A CRC name not in the catalogue.
    #[error("no CRC algorithm `{0}`; known: {1}")]
    UnknownCrc(String, String),
    /// A bit string with something other than 0 and 1.
    #[error(
        "bits `{0}`: give the bits as a string of 0 and 1 in wire order, e.g. 1000101011100011"
    )]
    BadBits(String),
    /// Bytes not given as pairs of hex digits.
    #[error("bytes `{0}`: give whole bytes in hex, e.g. --bytes 01 03 00 00 00 01 (or 0x01,0x03 or 010300)")]
    BadBytes(String),
    /// A waveform that cannot be decoded, or a bad decode option.
    #[error("{0}")]
    Decode(String),
    /// `tbgen fields`: an unknown protocol, or a configuration field the reference cannot document.
    #[error("{0}")]
    Fields(String),
    /// `tbgen probes`: a wrapper the probe testbench cannot be wired to, an
    /// export folder that is not one, or a probe that failed in a simulator.
    #[error("{0}")]
    Probes(String),
    /// Reading or writing a file failed.
    #[error("{path}: {}", io_cause(source))]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
}

impl Error {
    /// The process exit status for this error: 2 for bad input (a path the
    /// user gave that is missing, a folder, or not readable included), 1
    /// for the rest (a disk that is full, a device error).
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Io { source, .. } if !names_bad_input(source) => 1,
            _ => 2,
        }
    }

    /// Wraps an I/O error with the path it concerns.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.into(),
            source,
        }
    }
}

/// Result alias of `tbgen`.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// True when the operating system's error says the path itself is wrong.
fn names_bad_input(e: &std::io::Error) -> bool {
    use std::io::ErrorKind as K;
    matches!(
        e.kind(),
        K::NotFound
            | K::IsADirectory
            | K::NotADirectory
            | K::PermissionDenied
            | K::InvalidInput
            | K::InvalidData
    )
}

/// The operating system's error in words that say what to give instead.
fn io_cause(e: &std::io::Error) -> String {
    use std::io::ErrorKind as K;
    match e.kind() {
        K::NotFound => "no such file or folder".to_string(),
        K::IsADirectory => "is a folder; give a file".to_string(),
        K::NotADirectory => "a part of the path is a file, not a folder".to_string(),
        K::PermissionDenied => {
            "permission denied; give a path you can read (or write, for --out)".to_string()
        }
        _ => e.to_string(),
    }
}
