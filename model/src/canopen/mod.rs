//! CANopen on the bit-level CAN model: the DS 406 encoder of the Leine &
//! Linde gateway (seed 003) and, in [`sar58k24`], the SAR58K24 CAN mode
//! (seed 001 §3.4).
//!
//! - [`cob`]: COB-IDs, NMT commands and states, boot-up forms;
//! - [`od`]: the object dictionary (also the source of `tbgen eds`);
//! - [`sdo`]: SDO server, client frames, abort codes;
//! - [`scaling`]: the note's scaling and preset formulas;
//! - [`encoder`]: the encoder at frame level; [`node`]: on a [`crate::can::Bus`].
//!
//! ```
//! use model::canopen::{encoder::{Encoder, EncoderConfig}, sdo};
//! use model::can::frame::Frame;
//!
//! // Seed 003 §8: boot-up on 0x80 + node, then the SDO write of 6200h = 10 ms.
//! let mut e = Encoder::new(&EncoderConfig { node_switch: 5, ..Default::default() }).unwrap();
//! assert_eq!(e.power_on(0), vec![Frame::data(0x85, &[])]);
//! let a = e.on_frame(&Frame::data(0x605, &[0x22, 0x00, 0x62, 0x00, 0x0A, 0, 0, 0]), 1_000);
//! assert_eq!(a, vec![Frame::data(0x585, &[0x60, 0x00, 0x62, 0x00, 0, 0, 0, 0])]);
//! assert_eq!(sdo::parse_response(&a[0].data, false), sdo::Response::Downloaded { index: 0x6200, sub: 0 });
//! ```

pub mod bench;
pub mod clauses;
pub mod cob;
pub mod descriptor;
pub mod encoder;
pub mod interpret;
pub mod master;
pub mod node;
pub mod od;
pub mod rules;
pub mod sar58k24;
pub mod scaling;
pub mod sdo;

pub use bench::BenchConfig;
pub use encoder::{Encoder, EncoderConfig, EncoderKind};
pub use node::{Device, DeviceNode, EncoderNode, NodeTiming};
