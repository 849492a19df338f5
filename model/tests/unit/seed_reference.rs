//! Test-only reference implementations transliterated from the seeds, kept
//! apart from the catalogue engine so that the two can disagree.
//!
//! * [`make_crc_norm`] and [`make_crc_pos`]: line-by-line Rust ports of the
//!   C functions `MakeCrcNorm` and `MakeCrcPos` of seed 004 (HEIDENHAIN
//!   EnDat 2.2), appendix A4, 4.4.2 "Software CRC generation". Variable
//!   names, array sizes and loop bounds are the C code's; C's `unsigned int`
//!   and `unsigned long` are `u32` (the functions read 8, 16 and 32 bits of
//!   them).
//! * [`modbus_crc_seed_steps`]: the CRC procedure of seed 001 (SAR58K24
//!   manual, Modbus RTU, "The steps to calculate CRC code are", steps ① to
//!   ⑧), with step ②'s "OR" read as XOR.

/// Port of `MakeCrcNorm(param8, param16)` (seed 004, 4.4.2).
#[allow(clippy::needless_range_loop)]
pub fn make_crc_norm(param8: u32, param16: u32) -> u32 {
    let mut param8 = param8;
    let mut param16 = param16;
    let mut ff = [0u32; 5]; // State of the 5 flip-flops
    let mut code = [0u32; 24]; // Data-bit array
    let mut ex: u32; // Auxiliary variable
    let mut crc: u32 = 0; // Determined CRC code

    for i in 0..5 {
        // set all flip-flops to 1
        ff[i] = 1;
    }
    for i in 0..8 {
        // read 8 bit parameter into code array
        code[i] = if param8 & 0x0080 != 0 { 1 } else { 0 };
        param8 <<= 1;
    }

    for i in 8..24 {
        // read 16 bit parameter into code array
        code[i] = if param16 & 0x8000 != 0 { 1 } else { 0 };
        param16 <<= 1;
    }

    for i in 0..24 {
        // calculate CRC, analog to
        ex = ff[4] ^ code[i];
        ff[4] = ff[3];
        ff[3] = ff[2] ^ ex;
        ff[2] = ff[1];
        ff[1] = ff[0] ^ ex;
        ff[0] = ex;
    }

    for i in (0..=4).rev() {
        // save CRC in variable
        ff[i] = if ff[i] != 0 { 0 } else { 1 }; // invert bits
        crc <<= 1;
        crc |= ff[i];
    }

    crc
}

/// Port of `MakeCrcPos(clocks, error1, error2, endat22, highpos, lowpos)`
/// (seed 004, 4.4.2). `clocks` must be at most 64 (the C `code[66]` array).
#[allow(clippy::needless_range_loop)]
pub fn make_crc_pos(
    clocks: u32,
    error1: u32,
    error2: u32,
    endat22: u32,
    highpos: u32,
    lowpos: u32,
) -> u32 {
    let mut highpos = highpos;
    let mut lowpos = lowpos;
    let mut ff = [0u32; 5]; // State of the 5 flip-flops
    let mut code = [0u32; 66]; // Data-bit array (C leaves it uninitialised; code[0] is unused with EnDat 2.1)
    let mut ex: u32; // Auxiliary variable
    let mut crc: u32 = 0; // Determined CRC code

    for i in 0..5 {
        // set all flip-flops to 1
        ff[i] = 1;
    }

    if endat22 != 0 {
        // load alarm bits into code array
        code[0] = error1;
        code[1] = error2;
    } else {
        code[1] = error1;
    }

    for i in 2..34 {
        // load lowpos bits into code array
        code[i] = if lowpos & 0x0000_0001 != 0 { 1 } else { 0 };
        lowpos >>= 1;
    }

    for i in 34..66 {
        // load highpos bits into code array
        code[i] = if highpos & 0x0000_0001 != 0 { 1 } else { 0 };
        highpos >>= 1;
    }

    let first = if endat22 != 0 { 0 } else { 1 };
    for i in first..=(clocks as usize + 1) {
        // Calculate the CRC analog to the described generator hardware
        ex = ff[4] ^ code[i];
        ff[4] = ff[3];
        ff[3] = ff[2] ^ ex;
        ff[2] = ff[1];
        ff[1] = ff[0] ^ ex;
        ff[0] = ex;
    }

    for i in (0..=4).rev() {
        // save CRC in variable
        ff[i] = if ff[i] != 0 { 0 } else { 1 }; // invert bits
        crc <<= 1;
        crc |= ff[i];
    }

    crc
}

/// The Modbus CRC exactly as seed 001 describes it, step by step. Returns
/// the register of step ⑦ (low byte goes first on the wire, step ⑧).
pub fn modbus_crc_seed_steps(data: &[u8]) -> u16 {
    // ① preset the 16-bit CRC register to FFFF
    let mut crc: u16 = 0xFFFF;
    for &byte in data {
        // ② combine the 8 data bits with the low byte of the register
        //    (the seed says "OR"; only XOR reproduces its example frames)
        crc ^= u16::from(byte);
        // ⑤ eight shifts per byte
        for _ in 0..8 {
            // ③ shift right by one, fill the top with 0, look at the bit shifted out
            let out = crc & 1;
            crc >>= 1;
            // ④ if it was 1, XOR with A001
            if out == 1 {
                crc ^= 0xA001;
            }
        }
        // ⑥ next byte
    }
    // ⑦ the register is the CRC code
    crc
}
