//! The model's unit tests, one file per module of `src/` (`endat_decode.rs`
//! tests `model::endat::decode`, `endat.rs` the whole of `model::endat`),
//! with the test-only references beside them: `seed_reference` (the seeds'
//! own CRC procedures, transliterated, kept apart from the catalogue engine
//! so that the two can disagree) and `phases` (the clock phases a bench
//! drives).
//!
//! They are an integration test rather than `#[cfg(test)]` modules inside
//! the library so that `make test`'s build compiles the model once: a
//! library with unit tests is compiled a second time, whole, for its test
//! harness. They reach the library through its public API; the
//! few internals they check directly are public and `#[doc(hidden)]`.

mod angle;
mod biss;
mod biss_campaign;
mod biss_decode;
mod bits;
mod can;
mod canopen;
mod canopen_interpret;
mod canopen_sar58k24;
mod crc;
mod endat;
mod endat_decode;
mod endat_master;
mod esl;
mod esl_frames;
mod gray;
mod half_duplex;
mod line;
mod modbus;
mod modbus_campaign;
mod modbus_frames;
mod modbus_timing;
mod phases;
mod sar58k24;
mod sar58k24_campaign;
mod sar58k24_decode;
mod sar58k24_frames;
mod sar58k24_timing;
#[allow(dead_code)]
mod seed_reference;
mod ssi;
mod ssi_decode;
mod tformat;
mod tformat_campaign;
mod tformat_frames;
mod time;
mod uart;
mod uart_line;
mod uart_tx;
mod wire;
