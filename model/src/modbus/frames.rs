//! Modbus RTU frames as the SAR58K24 manual uses them (seed 001, 3.1.7):
//! function 03 from register 0x0000, the address query `FF A0 40 38`, the
//! exception answers of the Modbus specification, and the address change
//! this project chose (function 06, see [`ADDRESS_REGISTER`]). CRC-16 from
//! the catalogue (`modbus-crc16`), low byte first on the wire.

use crate::crc::MODBUS_CRC16;

/// Read holding registers.
pub const READ_HOLDING: u8 = 0x03;
/// Write single register (the address change; see [`ADDRESS_REGISTER`]).
pub const WRITE_SINGLE: u8 = 0x06;
/// The manual's address-query function (`FF A0 40 38`).
pub const QUERY_FUNCTION: u8 = 0xA0;
/// The address the query is sent to (any device: one device on the line).
pub const QUERY_ADDRESS: u8 = 0xFF;
/// Broadcast address: no device answers.
pub const BROADCAST: u8 = 0x00;
/// The register the position is read from ("start address 0x00 0x00").
pub const POSITION_REGISTER: u16 = 0x0000;

/// The register that holds the device address. "Change the device
/// address" has a heading and no content in the manual; this project
/// writes the new address (1..247) to holding register 0x0010 with
/// function 06, answered by the standard echo ("send a return data match
/// to indicate that the setting is successful", 3.1.7 (3)); the new
/// address holds from the next request on. A named field of the device
/// (`address_register`) so another firmware's register can be set.
pub const ADDRESS_REGISTER: u16 = 0x0010;

/// Exception codes of the Modbus application protocol.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Exception {
    /// 01: the function code is not supported.
    IllegalFunction = 1,
    /// 02: the register range is not there.
    IllegalDataAddress = 2,
    /// 03: a value in the request is not allowed (register count, address value).
    IllegalDataValue = 3,
}

/// The CRC of `bytes` as it goes on the wire: low byte, high byte.
pub fn crc_bytes(bytes: &[u8]) -> [u8; 2] {
    let crc = MODBUS_CRC16.checksum_bytes(bytes) as u16;
    crc.to_le_bytes()
}

/// `bytes` with their CRC appended.
pub fn with_crc(bytes: &[u8]) -> Vec<u8> {
    let mut v = bytes.to_vec();
    v.extend_from_slice(&crc_bytes(bytes));
    v
}

/// Whether a whole frame (CRC included) checks: the CRC over everything is 0.
pub fn crc_ok(frame: &[u8]) -> bool {
    frame.len() >= 3 && MODBUS_CRC16.checksum_bytes(frame) == 0
}

/// `addr 03 00 00 00 count CRC`: read `count` registers from 0x0000.
pub fn read_request(address: u8, count: u16) -> Vec<u8> {
    let [ch, cl] = count.to_be_bytes();
    let [sh, sl] = POSITION_REGISTER.to_be_bytes();
    with_crc(&[address, READ_HOLDING, sh, sl, ch, cl])
}

/// The answer: `addr 03 <2·count> <data high first> CRC`.
pub fn read_answer(address: u8, count: u16, value: u32) -> Vec<u8> {
    let data = if count == 1 {
        (value as u16).to_be_bytes().to_vec()
    } else {
        value.to_be_bytes().to_vec()
    };
    let mut v = vec![address, READ_HOLDING, data.len() as u8];
    v.extend(data);
    with_crc(&v)
}

/// `addr (function | 0x80) code CRC`.
pub fn exception_answer(address: u8, function: u8, code: Exception) -> Vec<u8> {
    with_crc(&[address, function | 0x80, code as u8])
}

/// The address query `FF A0 40 38`.
pub fn address_query() -> Vec<u8> {
    with_crc(&[QUERY_ADDRESS, QUERY_FUNCTION])
}

/// Its answer `FF A0 <address> CRC`.
pub fn address_answer(address: u8) -> Vec<u8> {
    with_crc(&[QUERY_ADDRESS, QUERY_FUNCTION, address])
}

/// `addr 06 <register> <value> CRC`: write one register (the address change).
pub fn write_request(address: u8, register: u16, value: u16) -> Vec<u8> {
    let [rh, rl] = register.to_be_bytes();
    let [vh, vl] = value.to_be_bytes();
    with_crc(&[address, WRITE_SINGLE, rh, rl, vh, vl])
}

/// Seconds of one character (start, 8 data, parity if any, stop).
pub fn char_seconds(baud: f64, frame_bits: usize) -> f64 {
    frame_bits as f64 / baud
}

/// t3.5, the silent interval between frames: 3.5 characters, fixed at
/// 1750 µs above 19200 baud (Modbus over serial line, 2.5.1.1; the
/// manual says only "at least 3.5 bytes of time interval").
pub fn t35_seconds(baud: f64, frame_bits: usize) -> f64 {
    if baud > 19_200.0 {
        1750e-6
    } else {
        3.5 * char_seconds(baud, frame_bits)
    }
}

/// t1.5, the longest silence inside a frame: 1.5 characters, fixed at 750 µs above 19200 baud.
pub fn t15_seconds(baud: f64, frame_bits: usize) -> f64 {
    if baud > 19_200.0 {
        750e-6
    } else {
        1.5 * char_seconds(baud, frame_bits)
    }
}
