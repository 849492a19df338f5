//! SAR58K24 asynchronous serial (seed `001_dad17a172253ad83.txt`,
//! "Product communication", 3.1.1 to 3.3.4).
//!
//! [`frames`] holds the frame layer; the emulator, host and bench follow.

pub mod frames;

pub use frames::{checksum, data_bytes, decode, encode, FrameError, HEADER};
