//! EnDat 2.1 / 2.2: the bidirectional synchronous-serial interface of
//! HEIDENHAIN position encoders (seed `004_ccc82d0c5d00fde0.txt`, "EnDat 2.2",
//! D297403).
//!
//! The master ([`Master`], Verilog `endat_master`) clocks an encoder
//! ([`Encoder`], an emulator with its memory areas) over a cable: one clock
//! pair and one half-duplex data pair ([`crate::line::HalfDuplexLine`]).
//! [`Bench`] wires the three together with a host that issues mode commands.
//! [`budget`] computes the cycle-time budget of a configuration, phase by
//! phase, and [`diagram`] renders the model's own waveforms as ASCII.
//!
//! ```
//! use model::endat::{Bench, BenchConfig, Command};
//!
//! // One "Encoder send position values" (000111) at 1 MHz, 25-bit position.
//! let mut cfg = BenchConfig::example();
//! cfg.commands = vec![model::endat::HostCommand::new(Command::Pos21)];
//! cfg.positions = vec![104_462];
//! let run = model::testbench::run_to_end(Bench::new(&cfg).unwrap());
//! assert_eq!(run.transactions.last().unwrap().position, Some(104_462));
//! ```
//!
//! # What the seed fixes (section 2.3)
//! The master sends each mode bit with the falling clock edge; the encoder
//! takes it with the rising edge. The first falling edge latches the position
//! and switches the encoder's driver off (`t_ST`); the master drives the line
//! from the second falling edge, sends `M2 M1 M0 (M2) (M1) (M0)`, then
//! releases it and keeps clocking while it polls for the start bit. After
//! the start bit come F1, F2 (type 2.2 only, active low), the position LSB
//! first, a 5-bit CRC (appendix A4), and with type 2.2 commands the selected
//! additional data, each 24 bits and its own CRC. Data is taken at the
//! falling edge plus the propagation time `t_D`.
//!
//! # Cycle-level interpretation (the seed's figures are missing)
//! Falling edges are numbered `F1, F2, ...` from the latch edge; `R_k` is the
//! rising edge after `F_k`. Every choice below is documented with its reason
//! in `docs/timing/endat.md`; those where real encoders differ are named
//! configuration fields.
//!
//! * The first low phase lasts `T_ST_CLOCKS` (at least `LOW_CLOCKS`); the
//!   clock then runs with period `CLOCKS_PER_BIT`, high `HIGH_CLOCKS` and low
//!   `LOW_CLOCKS` cycles, until the transaction ends. An odd divider (4 MHz
//!   from 100 MHz, `f_sys / 25`: 13 high, 12 low) gives the high phase the
//!   extra cycle, because without compensation the encoder's bit leaves at a
//!   rising edge and is sampled after the next falling edge (the round trip
//!   is budgeted in the high phase; seed 2.1.1 `f_c = 1/(2 t_min)`); the
//!   phases stay within the seed's ±10 % on-off ratio error (2.3.2). The
//!   measuring clock splits the same way (`MEAS_HIGH_CLOCKS`,
//!   `MEAS_LOW_CLOCKS`); `docs/timing/endat.md` "Odd dividers".
//! * The master drives the line from `F2` and releases it at `F_off`:
//!   `F8` after the six mode bits, `F37` after mode bits plus its 29-bit
//!   parameter block (type 2.1 memory, reset, test and communication
//!   commands: 8-bit MRS/address, 16-bit parameter, CRC-5 `MakeCrcNorm`).
//! * The encoder switches its driver on, driving low, at `R_off` and sends
//!   the start bit at the first rising edge `R_k`, `k >= off + 3`, that is at
//!   least `t_cal` after `F1` (for `F_off = F8` this is the seed's 10.5
//!   periods). Every encoder bit changes at a rising edge.
//! * Sample `j` is the data-line level `D` cycles after `F_j`; it holds the
//!   bit the encoder launched at `R_{j-1}`. Without delay compensation
//!   `D = 2 + SAMPLE_DELAY` (two synchroniser flops); with it `D` is the mean
//!   of the power-on measurements (see below). Sample `off + 1` must be low
//!   (the encoder drives), samples from `off + 2` on are polled for the start
//!   bit, at most `TIMEOUT_CLOCKS` of them.
//! * The clock stops high after the rising edge that follows the falling edge
//!   of the last sample; the master releases its driver half a period later.
//! * Type 2.2 commands that carry a parameter (`001001`, `011011`, `100100`,
//!   `110110`, `101101`): after the encoder's last CRC bit (launched at
//!   `R_e`) the encoder releases the line at `R_{e+1}`; the master drives its
//!   29-bit block from `F_{e+1+BLOCK_GAP}`. `BLOCK_GAP` is a named
//!   configuration shared by master and encoder: it must cover the round
//!   trip so that the master has received the whole frame before it drives.
//! * Continuous clock (`000111` only): after a value's CRC the clock keeps
//!   running; the encoder latches the next value at the second falling edge
//!   after its CRC and sends at most 7 low bits before the next start bit.
//! * Delay measurement (seed 2.1.2): at `MEAS_CLOCKS_PER_BIT` (100 to 200
//!   kHz), `MEAS_COUNT` "Encoder send position values" transfers; a counter
//!   restarts at every rising clock edge from `R10` on and is stored when the
//!   start bit's rising edge reaches the synchroniser output. The mean
//!   becomes `D`; each measurement must lie within `DELAY_TOL` (1/8 of the
//!   target clock period) of the mean, or the round is repeated, up to
//!   `MEAS_RETRIES` rounds, then flagged (`o_err_meas`).
//!
//! ```text
//!  "Encoder send position values" 000111, POS_BITS = 3, no delay (D = 2)
//!
//!  clk   ‾‾\____/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\__/‾‾\_ ...
//!          F1 t_ST R1 F2   F3   F4   F5   F6   F7   F8   F9   F10  F11  F12
//!  oe    _________/‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾‾\_______________________________
//!  out            | M2 | M1 | M0 |/M2 |/M1 |/M0 |
//!  enc   ‾‾\______(driver off)______________________/ low (R8) ......./S F1 P0 P1 P2 CRC4..0
//!  sample                                              ^9 must be 0   ^12 start bit (earliest)
//!  after the last CRC bit: clock high, encoder holds the line low for t_m, then high
//! ```
//! `docs/timing/endat.md` has the same diagrams rendered from the model.

mod bench;
pub mod budget;
pub mod decode;
pub mod descriptor;
pub mod diagram;
mod encoder;
mod master;
pub mod rules;

pub use bench::{
    error_names, AckXor, Bench, BenchConfig, CableFaults, EncoderSettings, FaultSettings, Flip,
    HostCommand, HostSettings, MasterSettings, Transaction,
};
pub use encoder::{AdSource, Answer, Encoder, EncoderConfig, EncoderKind, Memory};
#[doc(hidden)]
pub use master::{catalogue_engine, lfsr_push_for_test, POSITION_BITS};
pub use master::{
    FrameChecker, FrameResult, In, LineJudge, Master, MasterConfig, Out, RxPhase, State,
    DELAY_COUNTER_MAX, SYNC_STAGES,
};

use crate::crc::{BitSerial, ENDAT_CRC5};
use schemars::JsonSchema;

/// The raw LFSR register after a frame and its correct CRC field: what the
/// RTL compares against (`ENDAT_CRC5.wire_residue()`).
pub const CRC_RESIDUE: u64 = 0x08;

/// Bits of the master's parameter block: 8-bit MRS/address, 16-bit
/// parameter, 5-bit CRC.
pub const BLOCK_BITS: u64 = 29;

/// Bits of one additional datum on the wire: 24 data bits and a 5-bit CRC.
pub const AD_WIRE_BITS: u64 = 29;

/// Bits of the test values ("Encoder send test values", `MakeCrcPos` with 40 clocks).
pub const TEST_VALUE_BITS: u32 = 40;

/// At most this many low bits between values with a continuous clock (seed 2.3.1.1).
pub const CONT_MAX_LOW_BITS: u64 = 7;

/// The 14 mode commands of seed section 2.3.2.1.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Command {
    /// Encoder send position values, type 2.1, `000111`.
    Pos21,
    /// Selection of memory area, type 2.1, `001110`.
    Select21,
    /// Encoder receive parameters, type 2.1, `011100`.
    Receive21,
    /// Encoder send parameters, type 2.1, `100011`.
    Send21,
    /// Encoder receive reset, type 2.1, `101010`.
    Reset21,
    /// Encoder send test values, type 2.1, `010101`.
    TestValues21,
    /// Encoder receive test command, type 2.1, `110001`.
    TestCommand21,
    /// Encoder send position values with additional data, type 2.2, `111000`.
    Pos22,
    /// Encoder send position values and selection of memory area / additional data / block address, `001001`.
    Select22,
    /// Encoder send position values and receive parameter, `011011`.
    Receive22,
    /// Encoder send position values and send parameter, `100100`.
    Send22,
    /// Encoder send position values and receive test command, `110110`.
    TestCommand22,
    /// Encoder send position values and receive error reset, `101101`.
    ErrorReset22,
    /// Encoder receive communication command, type 2.2, `010010`.
    Communication22,
}

/// How a frame is laid out, decided from the six mode bits alone (the
/// master's `frame_kind`; the RTL's `KIND_*` localparams have the same codes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameKind {
    /// Mode bits, start bit, F1, position LSB first, CRC (`000111` and every
    /// code that is not a mode command: the encoder answers those with an
    /// error of type I).
    Pos21 = 0,
    /// Mode bits, start bit, F1, F2, position, CRC, selected additional data.
    Pos22 = 1,
    /// As `Pos22`, then the master's parameter block after `BLOCK_GAP` clocks.
    Block22 = 2,
    /// Mode bits and the master's parameter block, then start bit, 24-bit
    /// acknowledgement MSB first, CRC.
    Param21 = 3,
    /// Mode bits, start bit, F1, 40 test-value bits LSB first, CRC.
    Test21 = 4,
}

impl Command {
    /// Every command, in the seed's table order.
    pub const ALL: [Command; 14] = [
        Command::Pos21,
        Command::Select21,
        Command::Receive21,
        Command::Send21,
        Command::Reset21,
        Command::TestValues21,
        Command::TestCommand21,
        Command::Pos22,
        Command::Select22,
        Command::Receive22,
        Command::Send22,
        Command::TestCommand22,
        Command::ErrorReset22,
        Command::Communication22,
    ];

    /// The six mode bits `M2 M1 M0 (M2) (M1) (M0)`, `M2` in bit 5.
    pub const fn code(self) -> u8 {
        match self {
            Command::Pos21 => 0b000111,
            Command::Select21 => 0b001110,
            Command::Receive21 => 0b011100,
            Command::Send21 => 0b100011,
            Command::Reset21 => 0b101010,
            Command::TestValues21 => 0b010101,
            Command::TestCommand21 => 0b110001,
            Command::Pos22 => 0b111000,
            Command::Select22 => 0b001001,
            Command::Receive22 => 0b011011,
            Command::Send22 => 0b100100,
            Command::TestCommand22 => 0b110110,
            Command::ErrorReset22 => 0b101101,
            Command::Communication22 => 0b010010,
        }
    }

    /// The command these six mode bits encode, if any.
    pub fn from_code(code: u8) -> Option<Command> {
        Command::ALL
            .iter()
            .copied()
            .find(|c| c.code() == code & 0x3F)
    }

    /// Whether the command is of type 2.2 (seed 2.3.2.1).
    pub fn is_type22(self) -> bool {
        matches!(
            self,
            Command::Pos22
                | Command::Select22
                | Command::Receive22
                | Command::Send22
                | Command::TestCommand22
                | Command::ErrorReset22
                | Command::Communication22
        )
    }

    /// The name used in scenario files and transcripts.
    pub fn name(self) -> &'static str {
        match self {
            Command::Pos21 => "pos21",
            Command::Select21 => "select21",
            Command::Receive21 => "receive21",
            Command::Send21 => "send21",
            Command::Reset21 => "reset21",
            Command::TestValues21 => "test_values21",
            Command::TestCommand21 => "test_command21",
            Command::Pos22 => "pos22",
            Command::Select22 => "select22",
            Command::Receive22 => "receive22",
            Command::Send22 => "send22",
            Command::TestCommand22 => "test_command22",
            Command::ErrorReset22 => "error_reset22",
            Command::Communication22 => "communication22",
        }
    }
}

/// The frame layout of six mode bits (any value, valid or not).
pub fn frame_kind(code: u8) -> FrameKind {
    match Command::from_code(code) {
        Some(Command::Pos22) => FrameKind::Pos22,
        Some(
            Command::Select22
            | Command::Receive22
            | Command::Send22
            | Command::TestCommand22
            | Command::ErrorReset22,
        ) => FrameKind::Block22,
        Some(
            Command::Select21
            | Command::Receive21
            | Command::Send21
            | Command::Reset21
            | Command::TestCommand21
            | Command::Communication22,
        ) => FrameKind::Param21,
        Some(Command::TestValues21) => FrameKind::Test21,
        Some(Command::Pos21) | None => FrameKind::Pos21,
    }
}

/// `MakeCrcNorm(param8, param16)` through the catalogue engine (seed A4).
pub fn crc_norm(param8: u8, param16: u16) -> u8 {
    let mut lfsr = BitSerial::new(&ENDAT_CRC5);
    for i in (0..8).rev() {
        lfsr.push((param8 >> i) & 1 == 1);
    }
    for i in (0..16).rev() {
        lfsr.push((param16 >> i) & 1 == 1);
    }
    lfsr.value() as u8
}

/// `MakeCrcPos`: CRC over the error bits then `bits` value bits LSB first
/// (seed A4). `f2` is `None` for type 2.1 frames.
pub fn crc_pos(f1: bool, f2: Option<bool>, value: u64, bits: u32) -> u8 {
    let mut lfsr = BitSerial::new(&ENDAT_CRC5);
    lfsr.push(f1);
    if let Some(f2) = f2 {
        lfsr.push(f2);
    }
    for i in 0..bits {
        lfsr.push((value >> i) & 1 == 1);
    }
    lfsr.value() as u8
}

/// The five CRC bits as they go on the wire, CRC bit 4 first.
pub fn crc_wire(crc: u8) -> [bool; 5] {
    [
        crc & 16 != 0,
        crc & 8 != 0,
        crc & 4 != 0,
        crc & 2 != 0,
        crc & 1 != 0,
    ]
}
