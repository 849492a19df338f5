//! CANopen tools: the electronic data sheet of the emulated DS 406 encoder
//! (`tbgen eds`). Decode and timing follow with the protocol's registry line.

pub mod eds;
pub mod timing;
