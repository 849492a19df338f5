//! The EnDat master, cycle for cycle the same machine as `hdl/rtl/endat_master.v`.
//!
//! Written the way the RTL is: every register has a current value (`c`) and
//! a next value (`n`); one [`Master::step`] computes all next values from the
//! current ones and the inputs, then commits them, like one `posedge i_clk`.
//! Two cooperating parts share the registers: the transmitter (clock
//! generator, mode and parameter driver: [`State`]) and the receiver (the
//! sampler, `D` cycles behind every falling edge: [`RxPhase`]).

use super::{crc_norm, frame_kind, FrameKind, CONT_MAX_LOW_BITS, CRC_RESIDUE, TEST_VALUE_BITS};
use crate::crc::BitSerial;
use crate::crc::ENDAT_CRC5;
use crate::ports::{Port, Ports};
use crate::{ConfigError, Result};

/// The position's width the master reads (word 13 of the manufacturer
/// parameters; the core's `POS_BITS`).
pub const POSITION_BITS: std::ops::RangeInclusive<u32> = 1..=48;

/// Synchroniser depth on `i_endat_data_in` (fixed, as in the RTL).
pub const SYNC_STAGES: u64 = 2;

/// "No index yet" for the stop and block indices (16-bit all ones in the RTL).
const NONE: u64 = 0xFFFF;
/// Saturation of the 16-bit counters.
const SAT16: u64 = 0xFFFF;

/// The master's configuration, in cycles; each field is the Verilog
/// parameter of the same name in upper case.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MasterConfig {
    /// Position bits, word 13 of the manufacturer parameters, 1 to 48 (`POS_BITS`).
    pub pos_bits: u32,
    /// System clocks per EnDat clock period, at least 8 (`CLOCKS_PER_BIT`).
    pub clocks_per_bit: u64,
    /// System clocks of each clock-high phase (`HIGH_CLOCKS`); with
    /// `low_clocks` it makes up the period. An odd period gives the high
    /// phase the extra cycle ([`crate::time::BitClock`]): without delay
    /// compensation the encoder's bit leaves at a rising edge and is sampled
    /// after the next falling edge, so the cable's round trip is budgeted
    /// in the high phase (seed 2.1.1: with a duty cycle other than 1:1,
    /// `f_c = 1 / (2 t_min)`).
    pub high_clocks: u64,
    /// System clocks of each clock-low phase (`LOW_CLOCKS`).
    pub low_clocks: u64,
    /// System clocks per clock period of the delay measurement, 100 to 200 kHz (`MEAS_CLOCKS_PER_BIT`).
    pub meas_clocks_per_bit: u64,
    /// High phase of the measuring clock (`MEAS_HIGH_CLOCKS`), split as `high_clocks`.
    pub meas_high_clocks: u64,
    /// Low phase of the measuring clock (`MEAS_LOW_CLOCKS`).
    pub meas_low_clocks: u64,
    /// First low phase after the latching edge, `t_ST` (`T_ST_CLOCKS`).
    pub t_st_clocks: u64,
    /// Measure the propagation delay at power-on and sample at `F + D` (`DELAY_COMP`).
    pub delay_comp: bool,
    /// Without compensation (and during the measurement) samples are taken
    /// `2 + SAMPLE_DELAY` cycles after each falling edge (`SAMPLE_DELAY`).
    pub sample_delay: u64,
    /// Measurements per round, a power of two of at least 4 (`MEAS_COUNT`).
    pub meas_count: u64,
    /// Rounds before a failed measurement is flagged (`MEAS_RETRIES`).
    pub meas_retries: u64,
    /// Largest deviation of a measurement from the mean, and of a start
    /// bit's edge from its expected place: 1/8 of the data clock period (`DELAY_TOL`).
    pub delay_tol: u64,
    /// Largest usable measured delay for this clock and frame set (`DELAY_MAX`).
    pub delay_max: u64,
    /// Low samples polled for a start bit before giving up (`TIMEOUT_CLOCKS`).
    pub timeout_clocks: u64,
    /// Clock-high pause after a type 2.2 frame: `t_m` maximum plus `t_R` (`T_M_CLOCKS`).
    pub t_m_clocks: u64,
    /// Clock-high pause after a type 2.1 frame: `t_b` (`T_B_CLOCKS`).
    pub t_b_clocks: u64,
    /// Clock-high pause after a frame without start bit: 30 µs plus `t_R` (`T_ERR_CLOCKS`).
    pub t_err_clocks: u64,
    /// Clocks between the encoder's last bit and the master's parameter
    /// block of a type 2.2 command (`BLOCK_GAP`).
    pub block_gap: u64,
}

impl MasterConfig {
    /// The fixed sample delay used without compensation: synchroniser plus `SAMPLE_DELAY`.
    pub fn fixed_delay(&self) -> u64 {
        SYNC_STAGES + self.sample_delay
    }

    /// Shortest encoder frame after its start bit, in bits, over all frame kinds.
    pub fn shortest_frame(&self) -> u64 {
        let pos = self.pos_bits as u64;
        (1 + pos + 5).min(24 + 5)
    }

    /// The largest sample delay `D` the schedules allow: the stop index must
    /// be known before the clock passes it, and a type 2.2 parameter block
    /// may only start after the encoder's frame has arrived. At most
    /// [`DELAY_COUNTER_MAX`]: the core's delay counter has 16 bits, so a
    /// slow clock from a fast system clock (100 kHz from 257 MHz: 2570
    /// cycles a bit) cannot use a larger bound, and the core clamps its
    /// `DELAY_MAX` parameter to the same value.
    pub fn delay_limit(clocks_per_bit: u64, pos_bits: u32, block_gap: u64) -> u64 {
        let shortest = (1 + pos_bits as u64 + 5).min(24 + 5);
        let by_stop = (shortest + 1) * clocks_per_bit - 2;
        // The longer phase of an odd period (its high phase) keeps the bound safe.
        let by_gap = block_gap
            .saturating_mul(clocks_per_bit)
            .saturating_sub(clocks_per_bit - clocks_per_bit / 2);
        by_stop.min(by_gap).min(DELAY_COUNTER_MAX)
    }

    /// Checks the configuration; field names are those of a scenario's `[endat.master]` table.
    pub fn validate(&self) -> Result<()> {
        if !POSITION_BITS.contains(&self.pos_bits) {
            return Err(ConfigError::invalid(
                "master.pos_bits",
                format!("{} bits", self.pos_bits),
                format!(
                    "give {} to {} position bits (word 13 of the manufacturer parameters)",
                    POSITION_BITS.start(),
                    POSITION_BITS.end()
                ),
            ));
        }
        if self.clocks_per_bit < 8 {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!("the EnDat clock is f_sys / {}", self.clocks_per_bit),
                "make f_sys at least 8 times the EnDat clock (seed 2.1.2: f_e >= 8 f_c)",
            ));
        }
        if self.meas_clocks_per_bit < 8 {
            return Err(ConfigError::invalid(
                "master.meas_clock_khz",
                format!("f_sys / {}", self.meas_clocks_per_bit),
                "give a measuring clock of 100 to 200 kHz that divides f_sys",
            ));
        }
        for (field, period, high, low) in [
            (
                "master.clock_khz",
                self.clocks_per_bit,
                self.high_clocks,
                self.low_clocks,
            ),
            (
                "master.meas_clock_khz",
                self.meas_clocks_per_bit,
                self.meas_high_clocks,
                self.meas_low_clocks,
            ),
        ] {
            if high + low != period || high == 0 || low == 0 {
                return Err(ConfigError::invalid(
                    field,
                    format!("phases of {high} + {low} cycles for a period of {period}"),
                    "give high and low phases that make up the period",
                ));
            }
            // Seed 2.3.2, "on-off ratio error" up to ±10 % (read as the
            // stricter relative reading: each phase within 45 % to 55 % of
            // the period, so |high - low| <= period / 10).
            if 10 * high.abs_diff(low) > period {
                return Err(ConfigError::invalid(
                    field,
                    format!("a clock {high} cycles high and {low} low departs from 1:1 by more than 10 %"),
                    "give f_sys at least 10 times the clock (an odd divider of 11 or more) or an even divider (seed 2.3.2: on-off ratio error)",
                ));
            }
        }
        if self.t_st_clocks < self.low_clocks {
            return Err(ConfigError::invalid(
                "master.t_st_us",
                format!(
                    "{} cycles is shorter than half a clock period",
                    self.t_st_clocks
                ),
                "give t_ST of at least half the clock period",
            ));
        }
        if self.fixed_delay() >= self.low_clocks + self.meas_low_clocks {
            return Err(ConfigError::invalid(
                "master.sample_delay_ns",
                "the fixed sample point falls outside the measuring clock's bit",
                "lower sample_delay_ns",
            ));
        }
        if !self.meas_count.is_power_of_two() || self.meas_count < 4 || self.meas_count > 64 {
            return Err(ConfigError::invalid(
                "master.meas_count",
                format!("{}", self.meas_count),
                "give a power of two from 4 to 64 (the seed asks for at least three measurements)",
            ));
        }
        if self.meas_retries == 0 || self.meas_retries > 255 {
            return Err(ConfigError::invalid(
                "master.meas_retries",
                format!("{}", self.meas_retries),
                "give 1 to 255 rounds",
            ));
        }
        if self.timeout_clocks == 0 || self.timeout_clocks > 60_000 {
            return Err(ConfigError::invalid(
                "master.timeout_us",
                format!("{} clocks", self.timeout_clocks),
                "give a start-bit timeout of 1 to 60000 clock periods (at least t_cal)",
            ));
        }
        if self.block_gap < 2 || self.block_gap > 255 {
            return Err(ConfigError::invalid(
                "block_gap_clocks",
                format!("{}", self.block_gap),
                "give 2 to 255 clocks",
            ));
        }
        if self.delay_max < 1 {
            return Err(ConfigError::invalid(
                "block_gap_clocks",
                "no usable delay",
                "raise block_gap_clocks",
            ));
        }
        if !self.delay_comp && self.fixed_delay() > self.delay_max {
            return Err(ConfigError::invalid(
                "master.sample_delay_ns",
                "the fixed sample delay exceeds what the frame schedule allows",
                "lower sample_delay_ns or raise block_gap_clocks",
            ));
        }
        for (field, v) in [
            ("master.t_m_us", self.t_m_clocks),
            ("master.t_b_us", self.t_b_clocks),
            ("master.t_err_us", self.t_err_clocks),
        ] {
            if v == 0 || v >= 1 << 24 {
                return Err(ConfigError::invalid(
                    field,
                    format!("{v} cycles"),
                    "give a pause of 1 to 2^24 cycles",
                ));
            }
        }
        Ok(())
    }
}

/// The transmitter's states; the RTL's `localparam`s carry the same names and codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// Clock high, waiting for a start or a pending measurement.
    Idle = 0,
    /// The first low phase after the latching edge `F1` (`t_ST`).
    First = 1,
    /// Clock high half period; at its end the next falling edge, or the stop.
    High = 2,
    /// Clock low half period.
    Low = 3,
    /// Clock high for the recovery time (`t_m` + `t_R`, or `t_b`).
    Pause = 4,
}

/// What the receiver expects from its next sample; the RTL's `RX_*` codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RxPhase {
    /// Not sampling.
    Idle = 0,
    /// The first sample after the turnaround: must be low (the encoder drives).
    Turn = 1,
    /// Polling for the start bit.
    Poll = 2,
    /// Error bits F1 (and F2).
    FBit = 3,
    /// Position, test value or acknowledgement bits.
    Data = 4,
    /// The CRC of the head.
    Crc = 5,
    /// Additional datum 2.
    Ad2 = 6,
    /// Its CRC.
    Ad2Crc = 7,
    /// Additional datum 1.
    Ad1 = 8,
    /// Its CRC.
    Ad1Crc = 9,
}

/// Inputs sampled at one rising edge of the system clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct In {
    /// Host: start one transaction (one-cycle pulse; ignored while busy).
    pub i_start: bool,
    /// Host: the six mode bits `M2 M1 M0 (M2) (M1) (M0)`, `M2` in bit 5.
    pub i_mode: u8,
    /// Host: MRS code, address or port address (the 8-bit part of the block).
    pub i_mrs: u8,
    /// Host: parameter (the 16-bit part of the block).
    pub i_param: u16,
    /// Host: values to read with a continuous clock (`000111` only; 0 or 1: interrupted clock).
    pub i_cont_values: u8,
    /// Host: run the propagation-delay measurement again (one-cycle pulse while idle).
    pub i_meas: bool,
    /// Line: the data level at the master's receiver.
    pub i_endat_data_in: bool,
}

/// Registered outputs after one rising edge of the system clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Out {
    /// Line: the EnDat clock.
    pub o_endat_clk: bool,
    /// Line: the level the master drives while `o_endat_data_oe` is high (0 otherwise).
    pub o_endat_data_out: bool,
    /// Line: the master's RS-485 driver enable.
    pub o_endat_data_oe: bool,
    /// Host: a transaction, its recovery time or a measurement is under way.
    pub o_busy: bool,
    /// Host: one-cycle pulse when a frame's results are complete (one per value with a continuous clock), or a start was refused.
    pub o_done: bool,
    /// Host: position or test value of the last frame, LSB first on the wire, 48 bits.
    pub o_position: u64,
    /// Host: error bit F1 of the last frame (1 = error).
    pub o_f1: bool,
    /// Host: error bit F2 of the last type 2.2 frame (0 = error; 1 for type 2.1 frames).
    pub o_f2: bool,
    /// Pulse with `o_done`: the CRC of the position, test value or acknowledgement is wrong.
    pub o_err_crc: bool,
    /// Host: additional datum 1 of the last frame (WRN RM Busy I4..I0, byte 1, byte 2).
    pub o_ad1: u32,
    /// Host: the last frame carried additional datum 1.
    pub o_ad1_valid: bool,
    /// Pulse with `o_done`: additional datum 1 has a wrong CRC.
    pub o_err_ad1_crc: bool,
    /// Host: additional datum 2 of the last frame.
    pub o_ad2: u32,
    /// Host: the last frame carried additional datum 2.
    pub o_ad2_valid: bool,
    /// Pulse with `o_done`: additional datum 2 has a wrong CRC.
    pub o_err_ad2_crc: bool,
    /// Host: acknowledged address / MRS code of the last type 2.1 parameter frame.
    pub o_ack_addr: u8,
    /// Host: acknowledged (or read) parameter of the last type 2.1 parameter frame.
    pub o_ack_data: u16,
    /// Pulse with `o_done`: error handling type II (address or parameter returned inverted).
    pub o_err_type2: bool,
    /// Pulse with `o_done`: error handling type III (I = 15 or 31).
    pub o_err_type3: bool,
    /// Pulse with `o_done`: error handling type IV (NOP although other data are selected).
    pub o_err_type4: bool,
    /// Pulse with `o_done`: acknowledgement or additional-data content matches neither the request nor its inverse.
    pub o_err_ack: bool,
    /// Pulse with `o_done`: no start bit (error handling type I, dead encoder, start bit late) or more than 7 low bits between continuous values.
    pub o_err_timeout: bool,
    /// Pulse with `o_done`: the line was high when the encoder should drive it low (encoder absent, line stuck high).
    pub o_err_absent: bool,
    /// Pulse with `o_done`: a start was refused because the line was low (recovery time, line stuck low).
    pub o_err_idle: bool,
    /// Pulse with `o_done`: the start bit's edge is more than `DELAY_TOL` from where the measured delay puts it.
    pub o_err_delay: bool,
    /// Pulse: a delay measurement finished.
    pub o_meas_done: bool,
    /// Pulse with `o_meas_done` (or with `o_done` of a refused start): the measurements were inconsistent.
    pub o_err_meas: bool,
    /// Host: `o_delay` holds a valid measured delay.
    pub o_delay_valid: bool,
    /// Host: the sample delay `D` in use, in system clocks.
    pub o_delay: u16,
}

impl Ports for In {
    fn write_values(&self, dst: &mut [u64]) {
        dst[0] = self.i_start as u64;
        dst[1] = self.i_mode as u64;
        dst[2] = self.i_mrs as u64;
        dst[3] = self.i_param as u64;
        dst[4] = self.i_cont_values as u64;
        dst[5] = self.i_meas as u64;
        dst[6] = self.i_endat_data_in as u64;
    }
}

impl Ports for Out {
    fn write_values(&self, dst: &mut [u64]) {
        let v = [
            self.o_endat_clk as u64,
            self.o_endat_data_out as u64,
            self.o_endat_data_oe as u64,
            self.o_busy as u64,
            self.o_done as u64,
            self.o_position,
            self.o_f1 as u64,
            self.o_f2 as u64,
            self.o_err_crc as u64,
            self.o_ad1 as u64,
            self.o_ad1_valid as u64,
            self.o_err_ad1_crc as u64,
            self.o_ad2 as u64,
            self.o_ad2_valid as u64,
            self.o_err_ad2_crc as u64,
            self.o_ack_addr as u64,
            self.o_ack_data as u64,
            self.o_err_type2 as u64,
            self.o_err_type3 as u64,
            self.o_err_type4 as u64,
            self.o_err_ack as u64,
            self.o_err_timeout as u64,
            self.o_err_absent as u64,
            self.o_err_idle as u64,
            self.o_err_delay as u64,
            self.o_meas_done as u64,
            self.o_err_meas as u64,
            self.o_delay_valid as u64,
            self.o_delay as u64,
        ];
        dst[..v.len()].copy_from_slice(&v);
    }
}

/// The input ports, in vector order.
pub fn input_ports() -> Vec<Port> {
    vec![
        Port::new("i_start", 1),
        Port::new("i_mode", 6),
        Port::new("i_mrs", 8),
        Port::new("i_param", 16),
        Port::new("i_cont_values", 8),
        Port::new("i_meas", 1),
        Port::new("i_endat_data_in", 1).idle_high(),
    ]
}

/// The output ports, in vector order.
pub fn output_ports() -> Vec<Port> {
    vec![
        Port::new("o_endat_clk", 1),
        Port::new("o_endat_data_out", 1),
        Port::new("o_endat_data_oe", 1),
        Port::new("o_busy", 1),
        Port::new("o_done", 1),
        Port::new("o_position", 48),
        Port::new("o_f1", 1),
        Port::new("o_f2", 1),
        Port::new("o_err_crc", 1),
        Port::new("o_ad1", 24),
        Port::new("o_ad1_valid", 1),
        Port::new("o_err_ad1_crc", 1),
        Port::new("o_ad2", 24),
        Port::new("o_ad2_valid", 1),
        Port::new("o_err_ad2_crc", 1),
        Port::new("o_ack_addr", 8),
        Port::new("o_ack_data", 16),
        Port::new("o_err_type2", 1),
        Port::new("o_err_type3", 1),
        Port::new("o_err_type4", 1),
        Port::new("o_err_ack", 1),
        Port::new("o_err_timeout", 1),
        Port::new("o_err_absent", 1),
        Port::new("o_err_idle", 1),
        Port::new("o_err_delay", 1),
        Port::new("o_meas_done", 1),
        Port::new("o_err_meas", 1),
        Port::new("o_delay_valid", 1),
        Port::new("o_delay", 16),
    ]
}

/// Every register of the master (the RTL's `*_reg`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Regs {
    // transmitter
    state: State,
    cnt: u64,
    cpb: u64,
    fall_idx: u64,
    stop_idx: u64,
    blk_idx: u64,
    k_off: u64,
    kind: FrameKind,
    mode: u8,
    mrs: u8,
    param: u16,
    tx_bits: u64,
    meas_frame: bool,
    cont_left: u64,
    is21: bool,
    err_frame: bool,
    // receiver
    rx_on: bool,
    rx_cnt: u64,
    smp_idx: u64,
    phase: RxPhase,
    seg_cnt: u64,
    polls: u64,
    poll_limit: u64,
    lfsr: u64,
    f1: bool,
    f2: bool,
    rx_data: u64,
    ad_shift: u64,
    ad1_val: u64,
    ad2_val: u64,
    bad_head: bool,
    bad_ad1: bool,
    bad_ad2: bool,
    drift: bool,
    // line synchroniser and edge timing
    data_meta: bool,
    data_sync: bool,
    data_prev: bool,
    since_edge: u64,
    // delay measurement
    meas_on: bool,
    meas_cnt: u64,
    meas_got: bool,
    meas_cap: u64,
    meas_k: u64,
    meas_round: u64,
    meas_sum: u64,
    meas_min: u64,
    meas_max: u64,
    meas_bad: bool,
    meas_evt: bool,
    meas_evt_bad: bool,
    meas_eval1: bool,
    meas_eval2: bool,
    meas_mean: u64,
    delay: u64,
    delay_valid: bool,
    // additional-data selection as the master requested it
    ad1_on: bool,
    ad2_on: bool,
    ad1_sel: u8,
    ad2_sel: u8,
    // what the acknowledgements in additional datum 1 must echo (type 2.2, appendix A2 4.2.2)
    mem_addr: u8,
    mem_known: bool,
    mrs_sent: u8,
    mrs_known: bool,
    out: Out,
}

/// The EnDat master. One [`Master::step`] is one rising edge of the system clock.
#[derive(Debug, Clone)]
pub struct Master {
    cfg: MasterConfig,
    r: Regs,
}

/// The result of one frame as [`FrameChecker`] reports it (the fields the master publishes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FrameResult {
    /// Position / test value / acknowledgement bits.
    pub data: u64,
    /// F1.
    pub f1: bool,
    /// F2.
    pub f2: bool,
    /// CRC of the head wrong.
    pub bad_head: bool,
    /// Additional datum 1.
    pub ad1: u64,
    /// Its CRC wrong.
    pub bad_ad1: bool,
    /// Additional datum 2.
    pub ad2: u64,
    /// Its CRC wrong.
    pub bad_ad2: bool,
}

fn lfsr_push(reg: u64, bit: bool) -> u64 {
    // The catalogue engine, one bit (ENDAT_CRC5: x^5 + x^3 + x + 1).
    let fb = ((reg >> 4) & 1 == 1) ^ bit;
    let shifted = (reg << 1) & 0x1F;
    if fb {
        shifted ^ ENDAT_CRC5.poly
    } else {
        shifted
    }
}

impl Master {
    /// A master in its power-on state (with delay compensation it starts measuring at once).
    pub fn new(cfg: MasterConfig) -> Result<Self> {
        cfg.validate()?;
        debug_assert_eq!(ENDAT_CRC5.wire_residue(), CRC_RESIDUE);
        let out = Out {
            o_endat_clk: true,
            o_f2: true,
            o_busy: cfg.delay_comp,
            o_delay: cfg.fixed_delay() as u16,
            ..Out::default()
        };
        let r = Regs {
            state: State::Idle,
            cnt: 0,
            cpb: cfg.clocks_per_bit,
            fall_idx: 0,
            stop_idx: NONE,
            blk_idx: NONE,
            k_off: 8,
            kind: FrameKind::Pos21,
            mode: 0,
            mrs: 0,
            param: 0,
            tx_bits: 0,
            meas_frame: false,
            cont_left: 1,
            is21: true,
            err_frame: false,
            rx_on: false,
            rx_cnt: 0,
            smp_idx: 0,
            phase: RxPhase::Idle,
            seg_cnt: 0,
            polls: 0,
            poll_limit: 0,
            lfsr: 0x1F,
            f1: false,
            f2: true,
            rx_data: 0,
            ad_shift: 0,
            ad1_val: 0,
            ad2_val: 0,
            bad_head: false,
            bad_ad1: false,
            bad_ad2: false,
            drift: false,
            data_meta: true,
            data_sync: true,
            data_prev: true,
            since_edge: SAT16,
            meas_on: cfg.delay_comp,
            meas_cnt: SAT16,
            meas_got: false,
            meas_cap: 0,
            meas_k: 0,
            meas_round: 0,
            meas_sum: 0,
            meas_min: SAT16,
            meas_max: 0,
            meas_bad: false,
            meas_evt: false,
            meas_evt_bad: false,
            meas_eval1: false,
            meas_eval2: false,
            meas_mean: 0,
            delay: cfg.fixed_delay(),
            delay_valid: false,
            ad1_on: false,
            ad2_on: false,
            ad1_sel: 0,
            ad2_sel: 16,
            mem_addr: 0,
            mem_known: false,
            mrs_sent: 0,
            mrs_known: false,
            out,
        };
        Ok(Master { cfg, r })
    }

    /// The configuration.
    pub fn config(&self) -> &MasterConfig {
        &self.cfg
    }

    /// The transmitter state after the last step.
    pub fn state(&self) -> State {
        self.r.state
    }

    /// The receiver phase after the last step.
    pub fn rx_phase(&self) -> RxPhase {
        self.r.phase
    }

    /// Index of the last falling edge of the current transaction (`F1` = 1).
    pub fn fall_idx(&self) -> u64 {
        self.r.fall_idx
    }

    /// The last frame's raw received bits (position, test value or acknowledgement).
    pub fn rx_data(&self) -> u64 {
        self.r.rx_data
    }

    /// Whether a measurement frame is under way.
    pub fn measuring(&self) -> bool {
        self.r.meas_on || self.r.meas_frame && self.r.state != State::Idle
    }

    /// The last captured propagation delay (cycles from a rising clock edge to the start bit at the synchroniser's output).
    pub fn last_capture(&self) -> u64 {
        self.r.meas_cap
    }

    /// How many of the next steps with input `i` only run counters
    /// (fast-forward): idle without a request, or a clock phase or pause
    /// (`t_m`, `t_b`) counting down with the receiver off and the data line
    /// steady. 0 while a strobe is up or a measurement step is pending.
    pub fn quiet(&self, i: &In) -> u64 {
        let c = &self.r;
        let mut cleared = c.out;
        clear_strobes(&mut cleared);
        let d = i.i_endat_data_in;
        if cleared != c.out
            || i.i_start
            || i.i_meas
            || c.rx_on
            || c.meas_evt
            || c.meas_eval1
            || c.meas_eval2
            || c.data_meta != d
            || c.data_sync != d
            || c.data_prev != d
        {
            return 0;
        }
        match c.state {
            State::Idle if c.meas_on => 0,
            State::Idle => u64::MAX,
            State::First | State::High | State::Low | State::Pause => c.cnt,
        }
    }

    /// The same as `n` steps with the last input, for `n` up to [`Master::quiet`].
    pub fn skip(&mut self, n: u64) {
        let r = &mut self.r;
        if r.state != State::Idle {
            r.cnt -= n;
        }
        r.since_edge = (r.since_edge + n).min(SAT16);
        r.meas_cnt = (r.meas_cnt + n).min(SAT16);
    }

    /// One rising edge of the system clock.
    pub fn step(&mut self, i: &In) -> Out {
        let c = self.r;
        let mut n = c;
        clear_strobes(&mut n.out);

        // ---- line timing: edges of the synchronised data line -------------------------
        let edge_any = c.data_sync != c.data_prev;
        let edge_rise = c.data_sync && !c.data_prev;
        n.since_edge = if edge_any {
            1
        } else {
            (c.since_edge + 1).min(SAT16)
        };
        n.meas_cnt = (c.meas_cnt + 1).min(SAT16);
        if c.meas_frame && c.rx_on && c.phase == RxPhase::Poll && edge_rise && !c.meas_got {
            n.meas_cap = c.meas_cnt;
            n.meas_got = true;
        }

        // ---- receiver: one sample D cycles after every falling edge -----------------
        if c.rx_on {
            if c.rx_cnt == 0 {
                n.rx_cnt = c.cpb - 1;
                n.smp_idx = c.smp_idx + 1;
                self.rx_sample(&c, &mut n, c.data_sync);
            } else {
                n.rx_cnt = c.rx_cnt - 1;
            }
        }

        self.meas_stages(&c, &mut n);

        // ---- transmitter: clock, mode bits, parameter block ---------------------------
        let cfg = &self.cfg;
        let (high, low) = if c.meas_frame {
            (cfg.meas_high_clocks, cfg.meas_low_clocks)
        } else {
            (cfg.high_clocks, cfg.low_clocks)
        };
        match c.state {
            State::Idle => {
                n.out.o_endat_clk = true;
                if c.meas_on {
                    start_frame(cfg, &c, &mut n, true, 0b000111, 0, 0, 1);
                } else if i.i_meas {
                    n.meas_on = true;
                    n.meas_k = 0;
                    n.meas_round = 0;
                    n.meas_sum = 0;
                    n.meas_min = SAT16;
                    n.meas_max = 0;
                    n.meas_bad = false;
                    n.delay_valid = false;
                    n.out.o_delay_valid = false;
                } else if i.i_start {
                    if !c.data_sync {
                        n.out.o_done = true;
                        n.out.o_err_idle = true;
                    } else if cfg.delay_comp && !c.delay_valid {
                        n.out.o_done = true;
                        n.out.o_err_meas = true;
                    } else {
                        start_frame(
                            cfg,
                            &c,
                            &mut n,
                            false,
                            i.i_mode & 0x3F,
                            i.i_mrs,
                            i.i_param,
                            i.i_cont_values as u64,
                        );
                    }
                }
            }
            State::First => {
                if c.cnt == 0 {
                    n.state = State::High;
                    n.out.o_endat_clk = true;
                    n.cnt = high - 1;
                } else {
                    n.cnt = c.cnt - 1;
                }
            }
            State::High => {
                if c.cnt == 0 {
                    if c.fall_idx >= c.stop_idx {
                        n.state = State::Pause;
                        n.out.o_endat_data_oe = false;
                        n.out.o_endat_data_out = false;
                        let pause = if c.is21 {
                            cfg.t_b_clocks
                        } else if c.err_frame {
                            cfg.t_err_clocks
                        } else {
                            cfg.t_m_clocks
                        };
                        n.cnt = pause - 1;
                        remember_request(&c, &mut n);
                    } else {
                        let k = c.fall_idx + 1;
                        n.state = State::Low;
                        n.out.o_endat_clk = false;
                        n.fall_idx = k;
                        n.cnt = low - 1;
                        let in_block = c.kind == FrameKind::Block22
                            && k >= c.blk_idx
                            && k < c.blk_idx + super::BLOCK_BITS;
                        if (k >= 2 && k < c.k_off) || in_block {
                            n.out.o_endat_data_oe = true;
                            n.out.o_endat_data_out = (c.tx_bits >> 34) & 1 == 1;
                            n.tx_bits = (c.tx_bits << 1) & ((1u64 << 35) - 1);
                        } else {
                            n.out.o_endat_data_oe = false;
                            n.out.o_endat_data_out = false;
                        }
                        if k == c.k_off + 1 {
                            let d = if c.meas_frame || !(cfg.delay_comp && c.delay_valid) {
                                cfg.fixed_delay()
                            } else {
                                c.delay
                            };
                            n.rx_on = true;
                            n.rx_cnt = d - 1;
                            n.smp_idx = k;
                            n.phase = RxPhase::Turn;
                        }
                    }
                } else {
                    n.cnt = c.cnt - 1;
                }
            }
            State::Low => {
                if c.cnt == 0 {
                    n.state = State::High;
                    n.out.o_endat_clk = true;
                    n.cnt = high - 1;
                    if c.fall_idx >= 10 {
                        n.meas_cnt = 1;
                    }
                } else {
                    n.cnt = c.cnt - 1;
                }
            }
            State::Pause => {
                if c.cnt == 0 {
                    n.state = State::Idle;
                } else {
                    n.cnt = c.cnt - 1;
                }
            }
        }

        n.out.o_busy = n.state != State::Idle || n.meas_on;
        n.out.o_delay = n.delay as u16;
        n.out.o_delay_valid = n.delay_valid;
        n.data_prev = c.data_sync;
        n.data_sync = c.data_meta;
        n.data_meta = i.i_endat_data_in;
        self.r = n;
        n.out
    }

    /// One sample of the receiver.
    fn rx_sample(&self, c: &Regs, n: &mut Regs, bit: bool) {
        let cfg = &self.cfg;
        let (nf, len) = head_layout(c.kind, cfg.pos_bits);
        let is22 = matches!(c.kind, FrameKind::Pos22 | FrameKind::Block22);
        let lfsr = lfsr_push(c.lfsr, bit);
        match c.phase {
            RxPhase::Idle => {}
            RxPhase::Turn => {
                if bit {
                    self.abort(c, n, false);
                } else {
                    n.phase = RxPhase::Poll;
                    n.polls = 0;
                    n.poll_limit = cfg.timeout_clocks;
                }
            }
            RxPhase::Poll => {
                if bit {
                    let s = c.smp_idx;
                    n.phase = if nf == 0 {
                        RxPhase::Data
                    } else {
                        RxPhase::FBit
                    };
                    n.seg_cnt = 0;
                    n.lfsr = 0x1F;
                    n.rx_data = 0;
                    n.f1 = false;
                    n.f2 = true;
                    n.bad_head = false;
                    n.bad_ad1 = false;
                    n.bad_ad2 = false;
                    let ads = if is22 {
                        c.ad1_on as u64 + c.ad2_on as u64
                    } else {
                        0
                    };
                    let frame = nf + len + 5 + super::AD_WIRE_BITS * ads;
                    if c.kind == FrameKind::Block22 {
                        n.blk_idx = s + frame + cfg.block_gap;
                        n.stop_idx = n.blk_idx + super::BLOCK_BITS - 1;
                    } else if c.cont_left <= 1 {
                        n.stop_idx = s + frame;
                    }
                    // The edge came D after a rising clock edge, the sample
                    // is D after the falling edge that follows: a high phase apart.
                    let high = cfg.high_clocks;
                    n.drift = cfg.delay_comp
                        && !c.meas_frame
                        && c.delay_valid
                        && (c.since_edge > high + cfg.delay_tol
                            || c.since_edge + cfg.delay_tol < high);
                } else if c.polls == c.poll_limit {
                    self.abort(c, n, true);
                } else {
                    n.polls = c.polls + 1;
                }
            }
            RxPhase::FBit => {
                n.lfsr = lfsr;
                if c.seg_cnt == 0 {
                    n.f1 = bit;
                } else {
                    n.f2 = bit;
                }
                if c.seg_cnt + 1 == nf {
                    n.phase = RxPhase::Data;
                    n.seg_cnt = 0;
                } else {
                    n.seg_cnt = c.seg_cnt + 1;
                }
            }
            RxPhase::Data => {
                n.lfsr = lfsr;
                n.rx_data = if c.kind == FrameKind::Param21 {
                    ((c.rx_data << 1) | bit as u64) & 0xFF_FFFF
                } else {
                    c.rx_data | ((bit as u64) << c.seg_cnt)
                };
                if c.seg_cnt + 1 == len {
                    n.phase = RxPhase::Crc;
                    n.seg_cnt = 0;
                } else {
                    n.seg_cnt = c.seg_cnt + 1;
                }
            }
            RxPhase::Crc | RxPhase::Ad2Crc | RxPhase::Ad1Crc => {
                n.lfsr = lfsr;
                if c.seg_cnt == 4 {
                    let bad = lfsr != CRC_RESIDUE;
                    let next = match c.phase {
                        RxPhase::Crc => {
                            n.bad_head = bad;
                            if is22 && c.ad2_on {
                                RxPhase::Ad2
                            } else if is22 && c.ad1_on {
                                RxPhase::Ad1
                            } else {
                                RxPhase::Idle
                            }
                        }
                        RxPhase::Ad2Crc => {
                            n.bad_ad2 = bad;
                            n.ad2_val = c.ad_shift;
                            if c.ad1_on {
                                RxPhase::Ad1
                            } else {
                                RxPhase::Idle
                            }
                        }
                        _ => {
                            n.bad_ad1 = bad;
                            n.ad1_val = c.ad_shift;
                            RxPhase::Idle
                        }
                    };
                    n.seg_cnt = 0;
                    n.lfsr = 0x1F;
                    n.ad_shift = 0;
                    n.phase = next;
                    if next == RxPhase::Idle {
                        self.frame_done(c, n);
                    }
                } else {
                    n.seg_cnt = c.seg_cnt + 1;
                }
            }
            RxPhase::Ad2 | RxPhase::Ad1 => {
                n.lfsr = lfsr;
                n.ad_shift = ((c.ad_shift << 1) | bit as u64) & 0xFF_FFFF;
                if c.seg_cnt == 23 {
                    n.phase = if c.phase == RxPhase::Ad2 {
                        RxPhase::Ad2Crc
                    } else {
                        RxPhase::Ad1Crc
                    };
                    n.seg_cnt = 0;
                } else {
                    n.seg_cnt = c.seg_cnt + 1;
                }
            }
        }
    }

    /// A frame ended without its data (no encoder drive, or no start bit).
    fn abort(&self, c: &Regs, n: &mut Regs, timeout: bool) {
        n.phase = RxPhase::Idle;
        n.rx_on = false;
        n.stop_idx = c.fall_idx;
        n.err_frame = true;
        if c.meas_frame {
            n.meas_evt = true;
            n.meas_evt_bad = true;
        } else {
            n.out.o_done = true;
            n.out.o_err_timeout = timeout;
            n.out.o_err_absent = !timeout;
        }
    }

    /// The frame's last bit has been sampled: publish (uses the next values of this step).
    fn frame_done(&self, c: &Regs, n: &mut Regs) {
        if c.cont_left > 1 {
            n.cont_left = c.cont_left - 1;
            n.phase = RxPhase::Poll;
            n.polls = 0;
            n.poll_limit = CONT_MAX_LOW_BITS;
        } else {
            n.rx_on = false;
        }
        if c.meas_frame {
            n.meas_evt = true;
            n.meas_evt_bad = n.bad_head || !c.meas_got;
            return;
        }
        let is22 = matches!(c.kind, FrameKind::Pos22 | FrameKind::Block22);
        n.out.o_done = true;
        n.out.o_err_crc = n.bad_head;
        n.out.o_err_delay = n.drift;
        if c.kind == FrameKind::Param21 {
            let addr = ((n.rx_data >> 16) & 0xFF) as u8;
            let data = (n.rx_data & 0xFFFF) as u16;
            n.out.o_ack_addr = addr;
            n.out.o_ack_data = data;
            if !n.bad_head {
                let data_echoed = c.mode != super::Command::Send21.code();
                let inverted = addr == !c.mrs || (data_echoed && addr == c.mrs && data == !c.param);
                let matches = addr == c.mrs && (!data_echoed || data == c.param);
                n.out.o_err_type2 = inverted;
                n.out.o_err_ack = !inverted && !matches;
                if matches && c.mode == super::Command::Reset21.code() {
                    n.ad1_on = false;
                    n.ad2_on = false;
                    n.ad1_sel = 0;
                    n.ad2_sel = 16;
                }
            }
            return;
        }
        n.out.o_position = n.rx_data;
        n.out.o_f1 = n.f1;
        n.out.o_f2 = n.f2;
        let ad1 = is22 && c.ad1_on;
        let ad2 = is22 && c.ad2_on;
        n.out.o_ad1_valid = ad1;
        n.out.o_ad2_valid = ad2;
        n.out.o_err_ad1_crc = ad1 && n.bad_ad1;
        n.out.o_err_ad2_crc = ad2 && n.bad_ad2;
        if ad1 {
            n.out.o_ad1 = n.ad1_val as u32;
        }
        if ad2 {
            n.out.o_ad2 = n.ad2_val as u32;
        }
        let i1 = ((n.ad1_val >> 16) & 0x1F) as u8;
        let i2 = ((n.ad2_val >> 16) & 0x1F) as u8;
        let ok1 = ad1 && !n.bad_ad1;
        let ok2 = ad2 && !n.bad_ad2;
        let t3 = (ok1 && i1 == 15) || (ok2 && i2 == 31);
        let t4 = (ok1 && i1 == 0 && c.ad1_sel != 0) || (ok2 && i2 == 16 && c.ad2_sel != 16);
        let other = (ok1 && i1 != 15 && i1 != 0 && i1 != c.ad1_sel)
            || (ok2 && i2 != 31 && i2 != 16 && i2 != c.ad2_sel);
        // An acknowledgement (I = 5, 6, 7) echoes the address or MRS code the master sent; inverted it is error
        // handling type II (A2 4.2.2), anything else an access the encoder did not take (e.g. ignored while busy).
        let echoed = (n.ad1_val >> 8) as u8;
        let expected = match i1 {
            5 | 6 if c.mem_known => Some(c.mem_addr),
            7 if c.mrs_known => Some(c.mrs_sent),
            _ => None,
        };
        let t2 = ok1 && expected.is_some_and(|e| echoed == !e);
        let wrong_echo = ok1 && expected.is_some_and(|e| echoed != e && echoed != !e);
        n.out.o_err_type2 = t2;
        n.out.o_err_type3 = t3;
        n.out.o_err_type4 = t4;
        n.out.o_err_ack = other || wrong_echo;
    }

    /// Bookkeeping of the measurement, in three registered stages so that no
    /// long adder chain follows the frame's last sample (timing closure): the
    /// frame's capture is accumulated one cycle after the frame ends, the mean
    /// is formed in the next, and checked in the one after.
    fn meas_stages(&self, c: &Regs, n: &mut Regs) {
        let cfg = &self.cfg;
        if c.meas_evt {
            let bad = c.meas_evt_bad;
            let cap = c.meas_cap;
            n.meas_evt = false;
            n.meas_k = c.meas_k + 1;
            n.meas_sum = c.meas_sum + if bad { 0 } else { cap };
            n.meas_min = if bad { c.meas_min } else { c.meas_min.min(cap) };
            n.meas_max = if bad { c.meas_max } else { c.meas_max.max(cap) };
            n.meas_bad = c.meas_bad || bad;
            n.meas_eval1 = c.meas_k + 1 == cfg.meas_count;
        }
        if c.meas_eval1 {
            n.meas_eval1 = false;
            n.meas_eval2 = true;
            n.meas_mean = (c.meas_sum + cfg.meas_count / 2) >> cfg.meas_count.trailing_zeros();
        }
        if c.meas_eval2 {
            let mean = c.meas_mean;
            let ok = !c.meas_bad
                && c.meas_max <= mean + cfg.delay_tol
                && mean <= c.meas_min + cfg.delay_tol
                && mean <= cfg.delay_max
                && mean >= 1;
            n.meas_eval2 = false;
            n.meas_k = 0;
            n.meas_sum = 0;
            n.meas_min = SAT16;
            n.meas_max = 0;
            n.meas_bad = false;
            if ok {
                n.delay = mean;
                n.delay_valid = true;
                n.meas_on = false;
                n.out.o_meas_done = true;
            } else if c.meas_round + 1 < cfg.meas_retries {
                n.meas_round = c.meas_round + 1;
            } else {
                n.delay = cfg.fixed_delay();
                n.delay_valid = false;
                n.meas_on = false;
                n.out.o_meas_done = true;
                n.out.o_err_meas = true;
            }
        }
    }
}

/// The one-cycle outputs, low again in every cycle that does not raise them (results and F bits hold).
fn clear_strobes(out: &mut Out) {
    out.o_done = false;
    out.o_err_crc = false;
    out.o_err_ad1_crc = false;
    out.o_err_ad2_crc = false;
    out.o_err_type2 = false;
    out.o_err_type3 = false;
    out.o_err_type4 = false;
    out.o_err_ack = false;
    out.o_err_timeout = false;
    out.o_err_absent = false;
    out.o_err_idle = false;
    out.o_err_delay = false;
    out.o_meas_done = false;
    out.o_err_meas = false;
}

/// What the master remembers when a request ends, for judging the next answers: the additional data it has
/// selected (they decide the frame length) and the addresses the acknowledgements in additional datum 1 echo.
fn remember_request(c: &Regs, n: &mut Regs) {
    // The master's view of the encoder's additional-data selection (seed 2.4.2.2); a frame without a start bit
    // ends before the block, so the encoder's selection stays.
    if !c.err_frame && c.mode == super::Command::Select22.code() && (c.mrs & 0xE0) == 0x40 {
        if c.mrs & 0x10 == 0 {
            n.ad1_on = c.mrs != 0x4F;
            n.ad1_sel = c.mrs & 0x0F;
        } else {
            n.ad2_on = c.mrs != 0x5F;
            n.ad2_sel = 16 | (c.mrs & 0x0F);
        }
    }
    // The addresses the next acknowledgements in additional datum 1 refer to: I = 5 / 6 the
    // last memory access (2.1 or 2.2), I = 7 the last 2.2 MRS code (seed 2.3.5.1, A2 4.2.2).
    if !c.err_frame {
        use super::Command as C;
        if [C::Receive21, C::Send21, C::Receive22, C::Send22]
            .iter()
            .any(|x| x.code() == c.mode)
        {
            n.mem_addr = c.mrs;
            n.mem_known = true;
        }
        if c.mode == C::Select22.code() {
            n.mrs_sent = c.mrs;
            n.mrs_known = true;
        }
    }
}

/// F bits and data bits of a frame's head.
fn head_layout(kind: FrameKind, pos_bits: u32) -> (u64, u64) {
    match kind {
        FrameKind::Pos21 => (1, pos_bits as u64),
        FrameKind::Pos22 | FrameKind::Block22 => (2, pos_bits as u64),
        FrameKind::Param21 => (0, 24),
        FrameKind::Test21 => (1, TEST_VALUE_BITS as u64),
    }
}

/// Loads a transaction and produces the latching edge `F1`.
#[allow(clippy::too_many_arguments)]
fn start_frame(
    cfg: &MasterConfig,
    _c: &Regs,
    n: &mut Regs,
    meas: bool,
    code: u8,
    mrs: u8,
    param: u16,
    cont: u64,
) {
    let kind = frame_kind(code);
    n.state = State::First;
    n.out.o_endat_clk = false;
    n.fall_idx = 1;
    n.cpb = if meas {
        cfg.meas_clocks_per_bit
    } else {
        cfg.clocks_per_bit
    };
    n.cnt = if meas {
        cfg.meas_low_clocks
    } else {
        cfg.t_st_clocks
    } - 1;
    n.kind = kind;
    n.k_off = if kind == FrameKind::Param21 {
        8 + super::BLOCK_BITS
    } else {
        8
    };
    n.mode = code;
    n.mrs = mrs;
    n.param = param;
    n.tx_bits = ((code as u64) << 29)
        | ((mrs as u64) << 21)
        | ((param as u64) << 5)
        | crc_norm(mrs, param) as u64;
    n.stop_idx = NONE;
    n.blk_idx = NONE;
    n.meas_frame = meas;
    n.meas_got = false;
    n.cont_left = if !meas && code == 0b000111 && cont > 1 {
        cont
    } else {
        1
    };
    n.is21 = matches!(
        kind,
        FrameKind::Pos21 | FrameKind::Param21 | FrameKind::Test21
    );
    n.err_frame = false;
    n.drift = false;
}

/// Feeds a frame's bits (after the start bit) to the same receive logic the
/// master runs, without clocks: for the corruption campaign and for
/// `tbgen decode`. The layout is given by the mode bits, the position width
/// and which additional data are on.
#[derive(Debug, Clone)]
pub struct FrameChecker {
    master: Master,
}

impl FrameChecker {
    /// A checker for frames of `mode` with `pos_bits` position bits and the given additional data.
    pub fn new(mode: u8, pos_bits: u32, ad1: bool, ad2: bool) -> Self {
        let cfg = MasterConfig {
            pos_bits,
            clocks_per_bit: 8,
            high_clocks: 4,
            low_clocks: 4,
            meas_clocks_per_bit: 8,
            meas_high_clocks: 4,
            meas_low_clocks: 4,
            t_st_clocks: 4,
            delay_comp: false,
            sample_delay: 0,
            meas_count: 4,
            meas_retries: 1,
            delay_tol: 1,
            delay_max: 1000,
            timeout_clocks: 1,
            t_m_clocks: 1,
            t_b_clocks: 1,
            t_err_clocks: 1,
            block_gap: 2,
        };
        let mut master = Master::new(cfg).expect("fixed valid configuration");
        master.r.kind = frame_kind(mode);
        master.r.mode = mode;
        master.r.ad1_on = ad1;
        master.r.ad2_on = ad2;
        FrameChecker { master }
    }

    /// Bits after the start bit a frame of this layout has.
    pub fn frame_bits(&self) -> u64 {
        let (nf, len) = head_layout(self.master.r.kind, self.master.cfg.pos_bits);
        let is22 = matches!(self.master.r.kind, FrameKind::Pos22 | FrameKind::Block22);
        let ads = if is22 {
            self.master.r.ad1_on as u64 + self.master.r.ad2_on as u64
        } else {
            0
        };
        nf + len + 5 + super::AD_WIRE_BITS * ads
    }

    /// Runs the receiver over `bits` (the frame after its start bit).
    pub fn check(&self, bits: &[bool]) -> FrameResult {
        let m = &self.master;
        let mut c = m.r;
        c.phase = RxPhase::Poll;
        c.poll_limit = 0;
        c.rx_on = true;
        c.smp_idx = 0;
        let mut n = c;
        m.rx_sample(&c, &mut n, true);
        c = n;
        for &b in bits {
            let mut n = c;
            m.rx_sample(&c, &mut n, b);
            c = n;
        }
        FrameResult {
            data: c.rx_data,
            f1: c.f1,
            f2: c.f2,
            bad_head: c.bad_head,
            ad1: c.ad1_val,
            bad_ad1: c.bad_ad1,
            ad2: c.ad2_val,
            bad_ad2: c.bad_ad2,
        }
    }
}

/// The master's judgement of a whole line capture, request after request, without clocks: `tbgen decode endat`
/// hands it the mode bits and block it read at the master's pins and the frame after each start bit, and gets
/// back the outputs the master raises with `o_done`. Between requests it remembers what the master remembers
/// (the additional-data selection, the addresses acknowledgements echo), so its flags are the master's.
#[derive(Debug, Clone)]
pub struct LineJudge {
    checker: FrameChecker,
}

impl LineJudge {
    /// A judge for an encoder with `pos_bits` position bits, in the master's power-on state.
    pub fn new(pos_bits: u32) -> Self {
        LineJudge {
            checker: FrameChecker::new(0b000111, pos_bits, false, false),
        }
    }

    /// A request begins: its mode bits, and the MRS code / address and parameter of its block (0 if none).
    pub fn begin(&mut self, mode: u8, mrs: u8, param: u16) {
        let r = &mut self.checker.master.r;
        r.kind = frame_kind(mode);
        r.mode = mode & 0x3F;
        r.mrs = mrs;
        r.param = param;
        r.cont_left = 1;
        r.meas_frame = false;
        r.err_frame = false;
    }

    /// Bits after the start bit the current request's frame has.
    pub fn frame_bits(&self) -> u64 {
        self.checker.frame_bits()
    }

    /// The frame after its start bit (as many bits as [`LineJudge::frame_bits`]): the outputs at `o_done`.
    pub fn frame(&mut self, bits: &[bool]) -> Out {
        let m = &self.checker.master;
        let mut c = m.r;
        clear_strobes(&mut c.out);
        c.phase = RxPhase::Poll;
        c.poll_limit = 0;
        c.rx_on = true;
        c.smp_idx = 0;
        for &b in std::iter::once(&true).chain(bits) {
            let mut n = c;
            m.rx_sample(&c, &mut n, b);
            c = n;
        }
        self.checker.master.r = c;
        c.out
    }

    /// The frame ended without one: no start bit (`timeout`) or the line high at the turnaround.
    pub fn aborted(&mut self, timeout: bool) -> Out {
        let m = &self.checker.master;
        let mut c = m.r;
        clear_strobes(&mut c.out);
        let mut n = c;
        m.abort(&c, &mut n, timeout);
        self.checker.master.r = n;
        n.out
    }

    /// The request is over (the clock stopped): remember what the next answers are judged by.
    pub fn end(&mut self) {
        let c = self.checker.master.r;
        remember_request(&c, &mut self.checker.master.r);
    }
}

/// The largest delay, in cycles, the core's 16-bit delay counter holds
/// (`endat_master.v`: `meas_cnt_reg` saturates there).
pub const DELAY_COUNTER_MAX: u64 = 0xFFFF;

/// The master's own CRC step (`lfsr_push`), public for the test that it is
/// the catalogue engine's LFSR (`catalogue_engine`).
#[doc(hidden)]
pub fn lfsr_push_for_test(reg: u64, bit: bool) -> u64 {
    lfsr_push(reg, bit)
}

/// The catalogue's EnDat CRC engine, for that test.
#[doc(hidden)]
pub fn catalogue_engine() -> BitSerial {
    BitSerial::new(&ENDAT_CRC5)
}
