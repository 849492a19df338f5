//! A whole EnDat set-up: host, master, cable (clock pair and half-duplex data
//! pair) and encoder, stepped together.
//!
//! Each cycle `c`:
//! 1. the host decides the master's inputs; the master's data input is the
//!    level its receiver saw in cycle `c - 1`;
//! 2. the master steps and drives the clock, its data level and enable;
//! 3. the clock crosses the cable to the encoder; the data pair carries the
//!    master's driver one way and the encoder's (of cycle `c - 1`) the other;
//! 4. the encoder steps with the clock and data at its pins and drives its
//!    output, which passes its output delay (transceivers, the `0.2 µs` of
//!    the seed's `t_D`) before the pair.

use serde::{Deserialize, Serialize};

use super::encoder::{Answer, Encoder, EncoderConfig, EncoderKind};
use super::master::{self, In, Master, MasterConfig, Out};
use super::{Command, FrameKind};
use crate::line::{CableConfig, DelayLine, Drive, HalfDuplexLine};
use crate::ports::{Port, Ports};
use crate::testbench::{self, Setup, Testbench};
use crate::time::BitClock;
use crate::trace::{Layout, Sample};
use crate::{ConfigError, Result, Timebase};

/// The master's settings in a scenario's units (`[endat.master]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct MasterSettings {
    /// EnDat clock in kHz: 100 to 2000 without delay compensation, up to 8000 (16000) with it; f_sys divided by a whole number of at least 8, odd from 11 up (the high phase takes the extra cycle; each phase 45 to 55 % of the period).
    pub clock_khz: f64,
    /// Measure the propagation delay at power-on and compensate it.
    pub delay_comp: bool,
    /// Clock of the delay measurement in kHz (seed: 100 to 200 kHz).
    pub meas_clock_khz: f64,
    /// First low phase `t_ST` in µs; default: half a period below 2 MHz, 2 µs to 8 MHz, 1 µs at 16 MHz.
    pub t_st_us: Option<f64>,
    /// Extra delay of the fixed sample point in ns (without compensation).
    pub sample_delay_ns: f64,
    /// Measurements per round (power of two, at least 4).
    pub meas_count: u64,
    /// Measurement rounds before the failure is flagged.
    pub meas_retries: u64,
    /// Start-bit timeout in µs (at least the encoder's t_cal; the seed's maximum t_cal is 1 ms).
    pub timeout_us: f64,
    /// Recovery time I as the master allows for it: `short` (1.25 to 3.75 µs) or `long` (10 to 30 µs).
    pub recovery_short: bool,
    /// Recovery time II `t_R` in µs (seed: at least 0.5 µs).
    pub t_r_us: f64,
    /// Time between EnDat 2.1 cycles `t_b` in µs (seed: more than 1 ms).
    pub t_b_us: f64,
}

impl Default for MasterSettings {
    fn default() -> Self {
        MasterSettings {
            clock_khz: 1000.0,
            delay_comp: false,
            meas_clock_khz: 200.0,
            t_st_us: None,
            sample_delay_ns: 0.0,
            meas_count: 4,
            meas_retries: 3,
            timeout_us: 50.0,
            recovery_short: false,
            t_r_us: 0.5,
            t_b_us: 1010.0,
        }
    }
}

/// The encoder's settings in a scenario's units (`[endat.encoder]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct EncoderSettings {
    /// `singleturn`, `multiturn` or `linear`.
    pub kind: EncoderKind,
    /// Measuring-step bits (per revolution, or of the whole length).
    pub singleturn_bits: u32,
    /// Distinguishable-revolution bits (multiturn only).
    pub multiturn_bits: u32,
    /// Calculation time `t_cal` in µs.
    pub t_cal_us: f64,
    /// Time to acknowledge a reset in µs.
    pub reset_us: f64,
    /// Memory access time `t_ac` in µs (seed: up to 12 ms).
    pub t_ac_us: f64,
    /// Recovery time I `t_m` after type 2.2 frames, µs (1.25 to 3.75 with `recovery_short`, else 10 to 30);
    /// default 2 with `recovery_short`, else 15.
    pub t_m_us: Option<f64>,
    /// Recovery time I after type 2.1 frames, µs (10 to 30).
    pub t_m21_us: f64,
    /// Recovery time I of type 2.2 frames once word 3 selects the short setting (written, then a reset) on an
    /// encoder that powered on with the long one, µs (1.25 to 3.75).
    pub t_m_short_us: f64,
    /// Word 3 of the operating status selects the short recovery time (type 2.2 commands).
    pub recovery_short: bool,
    /// Clock edge to data output, both transceivers, ns.
    pub output_delay_ns: f64,
    /// Low bits between values with a continuous clock (1 to 7).
    pub cont_low_bits: u64,
    /// Type 2.2 command set supported.
    pub endat22: bool,
    /// Supported additional data as I codes (default: all defined ones).
    pub ad_supported: Option<Vec<u8>>,
    /// Blocks of the section 2 memory area.
    pub section2_blocks: u16,
    /// Maximum clock frequency, kHz (word 25).
    pub max_clock_khz: u16,
    /// Error word (operating status word 0) at power-on.
    pub errors: u16,
    /// Warning word (operating status word 1) at power-on.
    pub warnings: u16,
    /// Write-protection word (operating status word 2) at power-on, if not the factory value.
    pub write_protect: Option<u16>,
}

impl Default for EncoderSettings {
    fn default() -> Self {
        EncoderSettings {
            kind: EncoderKind::Multiturn,
            singleturn_bits: 13,
            multiturn_bits: 12,
            t_cal_us: 5.0,
            reset_us: 20.0,
            t_ac_us: 20.0,
            t_m_us: None,
            t_m21_us: 15.0,
            t_m_short_us: 2.0,
            recovery_short: false,
            output_delay_ns: 200.0,
            cont_low_bits: 3,
            endat22: true,
            ad_supported: None,
            section2_blocks: 2,
            max_clock_khz: 16000,
            errors: 0,
            warnings: 0,
            write_protect: None,
        }
    }
}

/// One request of the host (`[[endat.commands]]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HostCommand {
    /// The mode command.
    pub command: Command,
    /// Six raw mode bits instead of the command's (to provoke error handling type I), e.g. `0b000000`.
    pub raw_mode: Option<u8>,
    /// MRS code, address or port address.
    pub mrs: u8,
    /// Parameter.
    pub param: u16,
    /// Values with a continuous clock (`pos21` only).
    pub cont_values: u8,
    /// Repeat this request this many times.
    pub repeat: usize,
    /// Run the delay measurement instead of a command.
    pub measure: bool,
}

impl Default for HostCommand {
    fn default() -> Self {
        HostCommand {
            command: Command::Pos21,
            raw_mode: None,
            mrs: 0,
            param: 0,
            cont_values: 0,
            repeat: 1,
            measure: false,
        }
    }
}

impl HostCommand {
    /// One request of `command` with MRS and parameter 0.
    pub fn new(command: Command) -> Self {
        HostCommand {
            command,
            ..HostCommand::default()
        }
    }

    /// With MRS code / address and parameter.
    pub fn with(command: Command, mrs: u8, param: u16) -> Self {
        HostCommand {
            command,
            mrs,
            param,
            ..HostCommand::default()
        }
    }

    fn mode(&self) -> u8 {
        self.raw_mode.unwrap_or(self.command.code()) & 0x3F
    }
}

/// When the host asks (`[endat.host]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct HostSettings {
    /// The first request, µs after reset (after the power-on measurement, if any).
    pub first_start_us: f64,
    /// Idle time between the end of one request (o_busy low) and the next, µs.
    pub gap_us: f64,
}

impl Default for HostSettings {
    fn default() -> Self {
        HostSettings {
            first_start_us: 1.0,
            gap_us: 0.0,
        }
    }
}

/// A bit flip: frame bits (after the start bit, 0 = first) inverted by the encoder in request `request`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Flip {
    /// 0-based request number.
    pub request: usize,
    /// Bit indices after the start bit.
    pub bits: Vec<u64>,
}

/// A type 2.1 acknowledgement with other content and a correct CRC: in
/// request `request` (a `select21`, `receive21`, `send21` or `reset21`) the
/// encoder XORs `address` into the address (or MRS code) it sends back and
/// `data` into the data, then computes the CRC over what it sends. Bit flips
/// break the CRC; this fault reaches the master's content checks
/// (o_err_type2 for the right address with the data inverted, o_err_ack).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AckXor {
    /// 0-based request number.
    pub request: usize,
    /// XOR into the acknowledged address (MRS code).
    #[serde(default)]
    pub address: u8,
    /// XOR into the acknowledged data.
    #[serde(default)]
    pub data: u16,
}

/// Faults of the line and the encoder's electronics (`[endat.faults]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct CableFaults {
    /// The data line at the master's receiver stuck at this level from request `stuck_from` on.
    pub stuck_level: Option<bool>,
    /// First request with the stuck line.
    pub stuck_from: usize,
    /// Extra output delay (drift of t_D after the measurement) in ns from request `drift_from` on.
    pub drift_ns: Option<f64>,
    /// First request with the drift.
    pub drift_from: usize,
}

/// Encoder and line faults of a scenario (`[endat.faults]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct FaultSettings {
    /// Bit flips.
    pub flips: Vec<Flip>,
    /// Line faults.
    #[serde(flatten)]
    pub line: CableFaults,
    /// From this request on the encoder is dead: it holds the line low and never sends a start bit.
    pub dead_from: Option<usize>,
    /// From this request on the encoder is absent: nothing drives the line.
    pub absent_from: Option<usize>,
    /// In these requests the encoder cannot update its additional data (type IV).
    pub stale_ad: Vec<usize>,
    /// `errors_at = [word, request]`: the encoder's error word is set to
    /// `word` before request `request` (0-based).
    pub errors_at: Option<(u16, usize)>,
    /// Type 2.1 acknowledgements sent with other content and a correct CRC.
    pub ack_xor: Vec<AckXor>,
    /// In every frame (power-on measurement included) the encoder sends its start bit this many rising edges
    /// after `R_off` (1 or 2), ignoring `t_cal`: a conforming encoder waits `t_cal >= 10.5 / f_c` (seed 2.3.2),
    /// so its start bit comes at `R_off + 3` at the earliest, after the `R10` from which the master's delay
    /// counter runs (seed 2.1.2).
    pub early_start: Option<u64>,
}

/// Everything a scenario says about an EnDat set-up (`[endat]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct BenchConfig {
    /// System clock in MHz.
    pub f_sys_mhz: f64,
    /// Clocks between the encoder's last bit and the master's block of a type 2.2 command.
    pub block_gap_clocks: u64,
    /// The master.
    pub master: MasterSettings,
    /// The encoder.
    pub encoder: EncoderSettings,
    /// The cable; its delay per metre is one way (the seed's 0.01 µs/m of t_D is the round trip).
    pub cable: CableConfig,
    /// The host.
    pub host: HostSettings,
    /// Raw positions the encoder holds at successive requests (cycled).
    pub positions: Vec<u64>,
    /// Counts added per request (and per latch with a continuous clock).
    pub step: u64,
    /// The requests, in order.
    pub commands: Vec<HostCommand>,
    /// Faults.
    pub faults: FaultSettings,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            f_sys_mhz: 64.0,
            block_gap_clocks: 16,
            master: MasterSettings::default(),
            encoder: EncoderSettings::default(),
            cable: CableConfig::default(),
            host: HostSettings::default(),
            positions: vec![0],
            step: 0,
            commands: vec![HostCommand::new(Command::Pos21)],
            faults: FaultSettings::default(),
        }
    }
}

fn positive(field: &str, v: f64, fix: &str) -> Result<f64> {
    if (0.0..1e7).contains(&v) {
        Ok(v)
    } else {
        Err(ConfigError::invalid(field, format!("{v}"), fix))
    }
}

impl BenchConfig {
    /// A 25-bit multiturn encoder at 1 MHz through 10 m, no delay compensation.
    pub fn example() -> Self {
        BenchConfig {
            cable: CableConfig {
                length_m: 10.0,
                ..CableConfig::default()
            },
            ..BenchConfig::default()
        }
    }

    /// The master's configuration in cycles (the Verilog parameters).
    pub fn master_config(&self) -> Result<MasterConfig> {
        let tb = self.timebase()?;
        let m = &self.master;
        // The master's `pos_bits` is the encoder's: a bad width is blamed on
        // the encoder's fields, which the user wrote.
        super::encoder::check_position_bits(
            self.encoder.singleturn_bits,
            self.encoder.multiturn_bits,
        )?;
        if !(m.clock_khz >= 100.0 && m.clock_khz <= 16000.0) {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!("{} kHz", m.clock_khz),
                "give 100 to 2000 kHz (up to 8000, or 16000, with delay_comp = true)",
            ));
        }
        if m.clock_khz > 2000.0 && !m.delay_comp {
            return Err(ConfigError::invalid(
                "master.clock_khz",
                format!("{} kHz without delay compensation", m.clock_khz),
                "stay at or below 2000 kHz or set delay_comp = true (seed 2.1)",
            ));
        }
        if !(100.0..=200.0).contains(&m.meas_clock_khz) {
            return Err(ConfigError::invalid(
                "master.meas_clock_khz",
                format!("{} kHz", m.meas_clock_khz),
                "give 100 to 200 kHz (seed 2.1.2)",
            ));
        }
        if m.recovery_short && m.clock_khz <= 1000.0 {
            return Err(ConfigError::invalid(
                "master.recovery_short",
                format!("short recovery time at {} kHz", m.clock_khz),
                "use the short recovery time only above 1 MHz (seed 2.3.2 note 3 and 3.4.4)",
            ));
        }
        if m.t_b_us <= 1000.0 {
            return Err(ConfigError::invalid(
                "master.t_b_us",
                format!("{} µs", m.t_b_us),
                "give more than 1000 µs (seed 2.3.2: t_b > 1 ms)",
            ));
        }
        if m.t_r_us < 0.5 {
            return Err(ConfigError::invalid(
                "master.t_r_us",
                format!("{} µs", m.t_r_us),
                "give at least 0.5 µs (seed 2.3.2: t_R >= 500 ns)",
            ));
        }
        let clock = tb.divider(m.clock_khz * 1e3, "master.clock_khz", 8)?;
        let meas = tb.divider(m.meas_clock_khz * 1e3, "master.meas_clock_khz", 8)?;
        let cpb = clock.period;
        let t_st_us = match m.t_st_us {
            Some(v) => positive("master.t_st_us", v, "give t_ST in µs")?,
            None if m.clock_khz >= 16000.0 => 1.0,
            None if m.clock_khz >= 2000.0 => 2.0,
            None => 0.0,
        };
        let t_st = tb.cycles_at_least_ns(t_st_us * 1e3).max(clock.low);
        let t_m_max = if m.recovery_short { 3.75 } else { 30.0 };
        let t_r = positive("master.t_r_us", m.t_r_us, "give t_R in µs")?;
        let timeout_us = positive(
            "master.timeout_us",
            m.timeout_us,
            "give the start-bit timeout in µs",
        )?;
        let timeout_clocks = (timeout_us * m.clock_khz / 1e3).ceil() as u64;
        let cfg = MasterConfig {
            pos_bits: self.encoder.singleturn_bits + self.encoder.multiturn_bits,
            clocks_per_bit: cpb,
            high_clocks: clock.high,
            low_clocks: clock.low,
            meas_clocks_per_bit: meas.period,
            meas_high_clocks: meas.high,
            meas_low_clocks: meas.low,
            t_st_clocks: t_st,
            delay_comp: m.delay_comp,
            sample_delay: tb.cycles_nearest_ns(positive(
                "master.sample_delay_ns",
                m.sample_delay_ns,
                "give ns",
            )?),
            meas_count: m.meas_count,
            meas_retries: m.meas_retries,
            delay_tol: (cpb / 8).max(1),
            delay_max: MasterConfig::delay_limit(
                cpb,
                self.encoder.singleturn_bits + self.encoder.multiturn_bits,
                self.block_gap_clocks,
            ),
            timeout_clocks,
            t_m_clocks: tb.cycles_at_least_ns((t_m_max + t_r) * 1e3),
            t_b_clocks: tb
                .cycles_at_least_ns(positive("master.t_b_us", m.t_b_us, "give t_b in µs")? * 1e3),
            t_err_clocks: tb.cycles_at_least_ns((30.0 + t_r) * 1e3),
            block_gap: self.block_gap_clocks,
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// The encoder's configuration in cycles.
    pub fn encoder_config(&self) -> Result<EncoderConfig> {
        let tb = self.timebase()?;
        let e = &self.encoder;
        let ns = |field: &str, us: f64| -> Result<u64> {
            Ok(tb.cycles_at_least_ns(positive(field, us, "give a non-negative time")? * 1e3))
        };
        // Unwritten, t_m follows the recovery setting: a default the user never
        // wrote must not be what refuses `recovery_short = true`.
        let (t_m_range, t_m_default) = if e.recovery_short {
            ((1.25, 3.75), 2.0)
        } else {
            ((10.0, 30.0), 15.0)
        };
        let t_m_us = e.t_m_us.unwrap_or(t_m_default);
        if t_m_us < t_m_range.0 || t_m_us > t_m_range.1 {
            return Err(ConfigError::invalid(
                "encoder.t_m_us",
                format!(
                    "{t_m_us} µs with encoder.recovery_short = {}",
                    e.recovery_short
                ),
                format!(
                    "give {} to {} µs for this recovery setting, or leave t_m_us out (seed 2.3.2)",
                    t_m_range.0, t_m_range.1
                ),
            ));
        }
        if e.t_m21_us < 10.0 || e.t_m21_us > 30.0 {
            return Err(ConfigError::invalid(
                "encoder.t_m21_us",
                format!("{} µs", e.t_m21_us),
                "give 10 to 30 µs (seed 2.3.2)",
            ));
        }
        if !(1.25..=3.75).contains(&e.t_m_short_us) {
            return Err(ConfigError::invalid(
                "encoder.t_m_short_us",
                format!("{} µs", e.t_m_short_us),
                "give 1.25 to 3.75 µs (seed 2.3.2)",
            ));
        }
        if e.t_cal_us > 1000.0 {
            return Err(ConfigError::invalid(
                "encoder.t_cal_us",
                format!("{} µs", e.t_cal_us),
                "give at most 1000 µs (seed 2.3.2)",
            ));
        }
        let cfg = EncoderConfig {
            kind: e.kind,
            singleturn_bits: e.singleturn_bits,
            multiturn_bits: e.multiturn_bits,
            t_cal_clocks: ns("encoder.t_cal_us", e.t_cal_us)?,
            reset_clocks: ns("encoder.reset_us", e.reset_us)?,
            t_ac_clocks: ns("encoder.t_ac_us", e.t_ac_us)?,
            t_m_clocks: ns("encoder.t_m_us", t_m_us)?,
            t_m21_clocks: ns("encoder.t_m21_us", e.t_m21_us)?,
            t_m_other_clocks: if e.recovery_short {
                ns("encoder.t_m21_us", e.t_m21_us)?
            } else {
                ns("encoder.t_m_short_us", e.t_m_short_us)?
            },
            recovery_short: e.recovery_short,
            output_delay_clocks: tb.cycles_nearest_ns(positive(
                "encoder.output_delay_ns",
                e.output_delay_ns,
                "give ns",
            )?),
            block_gap: self.block_gap_clocks,
            cont_low_bits: e.cont_low_bits,
            endat22: e.endat22,
            ad_supported: e
                .ad_supported
                .clone()
                .unwrap_or_else(|| (1u8..=14).chain(17..=25).chain([27]).collect()),
            section2_blocks: e.section2_blocks,
            max_clock_khz: e.max_clock_khz,
            t_cal_us: e.t_cal_us.ceil() as u16,
        };
        cfg.validate()?;
        Ok(cfg)
    }

    /// The requests, each repeat expanded.
    pub fn requests(&self) -> Vec<HostCommand> {
        self.commands
            .iter()
            .flat_map(|c| std::iter::repeat_n(c.clone(), c.repeat))
            .collect()
    }

    /// The raw position at request `k`.
    pub fn position_at(&self, k: usize) -> u64 {
        let listed = if self.positions.is_empty() {
            0
        } else {
            self.positions[k % self.positions.len()]
        };
        listed.wrapping_add((k as u64).wrapping_mul(self.step))
    }

    /// Round-trip delay `D` the measurement should find: clock cable, the encoder's registered output and its
    /// output delay, data cable, the master's input register and synchroniser.
    pub fn expected_delay(&self) -> Result<u64> {
        let tb = self.timebase()?;
        let d = self.cable.delay_cycles(&tb);
        Ok(2 * d + self.encoder_config()?.output_delay_clocks + 2 + master::SYNC_STAGES)
    }

    /// Without delay compensation the master samples every bit at a fixed
    /// point: `D` cycles (its synchroniser and `sample_delay_ns`) after each
    /// falling clock edge, so a high phase plus `D` after the rising edge the
    /// encoder answers on. The answer reaches the receiver the round trip
    /// [`BenchConfig::expected_delay`] after that rising edge. `Some` when it
    /// comes later than the sample point: the first sample after the
    /// turnaround still sees the idle line and every read fails as
    /// `line_not_driven`. With delay compensation the reads sample after
    /// the measured round trip, but the delay measurement's own frames (at
    /// `meas_clock_khz`) are sampled at the fixed point, a high phase of the
    /// measurement clock plus `D`: `Some` when the round trip comes later
    /// than that, for then every measurement fails as
    /// `delay_measurement_inconsistent` and every read as `not_calibrated`.
    pub fn late_answer(&self) -> Result<Option<LateAnswer>> {
        let m = self.master_config()?;
        let round_trip = self.expected_delay()?;
        let high = if m.delay_comp {
            m.meas_high_clocks
        } else {
            m.high_clocks
        };
        let sample_point = high + m.fixed_delay();
        Ok((round_trip > sample_point).then(|| LateAnswer {
            round_trip,
            sample_point,
            period_ps: self.timebase().map_or(0, |tb| tb.period_ps()),
            sample_delay_cycles: round_trip - high - master::SYNC_STAGES,
            sample_delay_max: m.delay_max.saturating_sub(master::SYNC_STAGES),
            meas_clock_khz: m.delay_comp.then_some(self.master.meas_clock_khz),
            high_needed: round_trip - m.fixed_delay(),
        }))
    }

    fn check(&self) -> Result<()> {
        self.cable.validate("cable")?;
        let m = self.master_config()?;
        let e = self.encoder_config()?;
        // Counted before they are expanded: a huge `repeat` is refused, not allocated.
        let count = self
            .commands
            .iter()
            .fold(0usize, |n, c| n.saturating_add(c.repeat));
        if count == 0 {
            return Err(ConfigError::invalid(
                "commands",
                "no requests",
                "add at least one [[endat.commands]]",
            ));
        }
        if count > 100_000 {
            return Err(ConfigError::invalid(
                "commands",
                format!("{count} requests"),
                "ask for at most 100000",
            ));
        }
        let reqs = self.requests();
        let d = self.expected_delay()?;
        if m.delay_comp && d + m.delay_tol > m.delay_max {
            return Err(ConfigError::invalid(
                "block_gap_clocks",
                format!("the round trip of {d} cycles exceeds the {} the frame schedule allows at this clock", m.delay_max),
                "raise block_gap_clocks, shorten the cable or lower the clock",
            ));
        }
        if m.timeout_clocks * m.clocks_per_bit < e.t_cal_clocks && self.faults.dead_from.is_none() {
            // Allowed (it is the "start bit late" fault), but only on purpose: say so in the file.
        }
        let limit = if e.pos_bits() >= 64 {
            u64::MAX
        } else {
            (1u64 << e.pos_bits()) - 1
        };
        if let Some((i, p)) = self.positions.iter().enumerate().find(|(_, p)| **p > limit) {
            return Err(ConfigError::invalid(
                format!("positions[{i}]"),
                format!("{p} does not fit {} bits", e.pos_bits()),
                format!("give 0 to {limit}"),
            ));
        }
        // A fault in a request the run never reaches would pass unnoticed.
        let f = &self.faults;
        let scheduled = f
            .flips
            .iter()
            .enumerate()
            .map(|(j, x)| (format!("faults.flips[{j}].request"), x.request));
        let scheduled = scheduled
            .chain(
                f.line
                    .stuck_level
                    .map(|_| ("faults.stuck_from".to_string(), f.line.stuck_from)),
            )
            .chain(
                f.line
                    .drift_ns
                    .map(|_| ("faults.drift_from".to_string(), f.line.drift_from)),
            )
            .chain(f.dead_from.map(|r| ("faults.dead_from".to_string(), r)))
            .chain(f.absent_from.map(|r| ("faults.absent_from".to_string(), r)))
            .chain(
                f.stale_ad
                    .iter()
                    .enumerate()
                    .map(|(j, r)| (format!("faults.stale_ad[{j}]"), *r)),
            )
            .chain(
                f.errors_at
                    .map(|(_, r)| ("faults.errors_at".to_string(), r)),
            )
            .chain(
                f.ack_xor
                    .iter()
                    .enumerate()
                    .map(|(j, x)| (format!("faults.ack_xor[{j}].request"), x.request)),
            );
        for (field, request) in scheduled {
            if request >= reqs.len() {
                return Err(ConfigError::invalid(
                    field,
                    format!("request {request}, but the commands make {} requests (0 to {})", reqs.len(), reqs.len() - 1),
                    "give a request below that count (0-based, each `repeat` counted), or add commands",
                ));
            }
        }
        // An acknowledgement fault on a request that sends none would pass unnoticed.
        for (j, x) in f.ack_xor.iter().enumerate() {
            let c = &reqs[x.request];
            let param21 = matches!(
                c.command,
                Command::Select21 | Command::Receive21 | Command::Send21 | Command::Reset21
            );
            if !param21 || c.raw_mode.is_some() || c.measure {
                return Err(ConfigError::invalid(
                    format!("faults.ack_xor[{j}].request"),
                    format!("request {} is {}, which sends no type 2.1 acknowledgement", x.request, c.command.name()),
                    "give the number of a select21, receive21, send21 or reset21 request (0-based, each `repeat` counted)",
                ));
            }
            if x.address == 0 && x.data == 0 {
                return Err(ConfigError::invalid(
                    format!("faults.ack_xor[{j}]"),
                    "address and data 0 change nothing",
                    "give a nonzero address or data XOR",
                ));
            }
        }
        if let Some(k) = f.early_start.filter(|k| !(1..=2).contains(k)) {
            return Err(ConfigError::invalid(
                "faults.early_start",
                format!("{k} rising edges after R_off"),
                "give 1 or 2 (the start bit at R_off + 1 or R_off + 2; a conforming encoder's earliest is R_off + 3), or leave it out",
            ));
        }
        positive("host.first_start_us", self.host.first_start_us, "give µs")?;
        positive("host.gap_us", self.host.gap_us, "give µs")?;
        if let Some(v) = self.faults.line.drift_ns {
            positive("faults.drift_ns", v, "give the extra delay in ns")?;
        }
        Ok(())
    }

    fn parameters(&self) -> Result<Vec<(&'static str, u64)>> {
        let c = self.master_config()?;
        let mut p = vec![
            ("POS_BITS", c.pos_bits as u64),
            ("CLOCKS_PER_BIT", c.clocks_per_bit),
        ];
        p.extend(BitClock::parameters(
            c.high_clocks,
            c.low_clocks,
            ["HIGH_CLOCKS", "LOW_CLOCKS"],
        ));
        p.push(("MEAS_CLOCKS_PER_BIT", c.meas_clocks_per_bit));
        p.extend(BitClock::parameters(
            c.meas_high_clocks,
            c.meas_low_clocks,
            ["MEAS_HIGH_CLOCKS", "MEAS_LOW_CLOCKS"],
        ));
        p.extend([
            ("T_ST_CLOCKS", c.t_st_clocks),
            ("DELAY_COMP", c.delay_comp as u64),
            ("SAMPLE_DELAY", c.sample_delay),
            ("MEAS_COUNT", c.meas_count),
            ("MEAS_RETRIES", c.meas_retries),
            ("DELAY_TOL", c.delay_tol),
            ("DELAY_MAX", c.delay_max),
            ("TIMEOUT_CLOCKS", c.timeout_clocks),
            ("T_M_CLOCKS", c.t_m_clocks),
            ("T_B_CLOCKS", c.t_b_clocks),
            ("T_ERR_CLOCKS", c.t_err_clocks),
            ("BLOCK_GAP", c.block_gap),
        ]);
        Ok(p)
    }
}

impl Setup for BenchConfig {
    type Bench = Bench;
    const PROTOCOL: &'static crate::protocol::Protocol = &super::descriptor::PROTOCOL;

    /// The bench's own checks, and a set-up in which no read can succeed
    /// ([`BenchConfig::late_answer`]): refused for a scenario, as the
    /// `line_not_driven` on every read would be the set-up's, not a fault's
    /// (an absent encoder is `faults.absent_from`). The bench still runs
    /// such a set-up for a caller who builds it directly.
    fn validate(&self) -> Result<()> {
        self.check()?;
        match self.late_answer()? {
            Some(late) => Err(late.error()),
            None => Ok(()),
        }
    }

    fn timebase(&self) -> Result<Timebase> {
        Timebase::from_mhz(self.f_sys_mhz)
    }

    fn verilog_parameters(&self) -> Result<Vec<(&'static str, u64)>> {
        self.parameters()
    }

    fn bench(&self) -> Result<Bench> {
        Bench::new(self)
    }
}

/// One transaction of the transcript: a frame's results, a refused start, or a delay measurement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transaction {
    /// 0-based request number (measurements at power-on: none).
    pub request: Option<usize>,
    /// `command`, `continuous_value` or `delay_measurement`.
    pub kind: String,
    /// The command's name.
    pub command: String,
    /// The six mode bits sent.
    pub mode: String,
    /// Cycle of the host's start.
    pub start_cycle: u64,
    /// Cycle of `o_done` / `o_meas_done`.
    pub done_cycle: u64,
    /// MRS code / address sent.
    pub mrs: u8,
    /// Parameter sent.
    pub param: u16,
    /// The position the encoder latched (with its datum shift).
    pub encoder_position: Option<u64>,
    /// The encoder's frame after its start bit, as sent (flips included).
    pub sent_bits: String,
    /// How the encoder answered (`ok`, `type_i`, `type_ii`, `ignored`).
    pub encoder_answer: String,
    /// Decoded position or test value.
    pub position: Option<u64>,
    /// F1 and F2.
    pub f1: Option<bool>,
    /// F2 (type 2.2).
    pub f2: Option<bool>,
    /// Additional datum 1, hex.
    pub ad1: Option<String>,
    /// Additional datum 2, hex.
    pub ad2: Option<String>,
    /// Acknowledged address and data (type 2.1 parameter frames).
    pub ack: Option<(u8, u16)>,
    /// Measured delay in cycles (measurements).
    pub delay_cycles: Option<u64>,
    /// Everything the master flagged.
    pub errors: Vec<String>,
}

impl testbench::Transaction for Transaction {
    fn span(&self) -> (u64, u64) {
        (self.start_cycle, self.done_cycle)
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Host {
    WaitUntil(u64),
    WaitIdle,
    Finished(u64),
}

/// Cycles the bench runs on after the last request.
const TAIL_CYCLES: u64 = 32;

/// Host, master, cable and encoder.
pub struct Bench {
    cfg: BenchConfig,
    requests: Vec<HostCommand>,
    master: Master,
    encoder: Encoder,
    clk_line: DelayLine,
    pair: HalfDuplexLine,
    enc_drive: Drive,
    data_at_master: bool,
    host: Host,
    gap: u64,
    next: usize,
    current: Option<(usize, u64)>,
    stuck: Option<bool>,
    cycle: u64,
    last_in: In,
    last_out: Out,
    transactions: Vec<Transaction>,
    layout: Layout,
    tb: Timebase,
}

impl Bench {
    /// A bench at power-on.
    pub fn new(cfg: &BenchConfig) -> Result<Self> {
        cfg.check()?;
        let tb = cfg.timebase()?;
        let master = Master::new(cfg.master_config()?)?;
        let mut encoder = Encoder::new(cfg.encoder_config()?)?;
        encoder.set_errors(cfg.encoder.errors);
        encoder.set_warnings(cfg.encoder.warnings);
        encoder.early_start = cfg.faults.early_start.unwrap_or(0);
        if let Some(w) = cfg.encoder.write_protect {
            encoder
                .memory_mut()
                .areas
                .get_mut(&0xB9)
                .expect("status area")[2] = w;
        }
        let (clk_line, _) = cfg.cable.lines(&tb, true);
        let pair = HalfDuplexLine::new(cfg.cable.delay_cycles(&tb), true);
        let layout = Layout {
            inputs: master::input_ports(),
            outputs: master::output_ports(),
            line: vec![
                Port::new("endat_clk_master", 1),
                Port::new("endat_clk_encoder", 1),
                Port::new("endat_data_master", 1),
                Port::new("endat_data_encoder", 1),
                Port::new("master_oe", 1),
                Port::new("encoder_oe", 1),
            ],
            decoded: vec![
                Port::new("state", 3),
                Port::new("rx_phase", 4),
                Port::new("fall_idx", 16),
                Port::new("encoder_position", 48),
            ],
        };
        Ok(Bench {
            requests: cfg.requests(),
            master,
            encoder,
            clk_line,
            pair,
            enc_drive: Drive {
                enable: true,
                level: true,
            },
            data_at_master: true,
            host: Host::WaitUntil(tb.cycles_at_least_ns(cfg.host.first_start_us * 1e3)),
            gap: tb.cycles_at_least_ns(cfg.host.gap_us * 1e3),
            next: 0,
            current: None,
            stuck: None,
            cycle: 0,
            last_in: In::default(),
            last_out: Out {
                o_endat_clk: true,
                o_busy: cfg.master.delay_comp,
                ..Out::default()
            },
            transactions: Vec::new(),
            layout,
            tb,
            cfg: cfg.clone(),
        }
        .with_first_faults())
    }

    fn with_first_faults(mut self) -> Self {
        self.apply_faults(0);
        self
    }

    /// Runs to the end with nothing recorded.
    pub fn run_to_end(self) -> testbench::Run<Transaction> {
        testbench::run_to_end(self)
    }

    /// The encoder (for tests).
    pub fn encoder(&self) -> &Encoder {
        &self.encoder
    }

    /// The master (for tests).
    pub fn master(&self) -> &Master {
        &self.master
    }

    fn host_decides(&mut self) -> In {
        let mut input = In {
            i_endat_data_in: self.stuck.unwrap_or(self.data_at_master),
            ..In::default()
        };
        if let Host::WaitUntil(at) = self.host {
            if self.cycle >= at && !self.last_out.o_busy {
                let k = self.next;
                let req = self.requests[k].clone();
                self.encoder.set_position(self.cfg.position_at(k));
                self.encoder.advance_per_latch = self.cfg.step;
                if req.measure {
                    input.i_meas = true;
                } else {
                    input.i_start = true;
                    input.i_mode = req.mode();
                    input.i_mrs = req.mrs;
                    input.i_param = req.param;
                    input.i_cont_values = req.cont_values;
                }
                self.current = Some((k, self.cycle));
                self.next += 1;
                self.host = Host::WaitIdle;
            }
        }
        input.i_endat_data_in = self.stuck.unwrap_or(self.data_at_master);
        input
    }

    fn apply_faults(&mut self, k: usize) {
        let f = &self.cfg.faults;
        if let Some(level) = f.line.stuck_level {
            if k >= f.line.stuck_from {
                self.stuck = Some(level);
            }
        }
        if let Some(ns) = f.line.drift_ns {
            if k == f.line.drift_from {
                let extra = self.tb.cycles_nearest_ns(ns);
                let base = self.encoder.config().output_delay_clocks;
                self.encoder.set_output_delay(base + extra);
            }
        }
        self.encoder.dead = f.dead_from.is_some_and(|d| k >= d);
        self.encoder.absent = f.absent_from.is_some_and(|d| k >= d);
        self.encoder.ad_stale = f.stale_ad.contains(&k);
        if let Some((w, at)) = f.errors_at {
            if at == k {
                self.encoder.set_errors(w);
            }
        }
        self.encoder.flips = f
            .flips
            .iter()
            .filter(|x| x.request == k)
            .flat_map(|x| x.bits.iter().copied())
            .collect();
        self.encoder.ack_xor = f
            .ack_xor
            .iter()
            .filter(|x| x.request == k)
            .fold((0, 0), |(a, d), x| (a ^ x.address, d ^ x.data));
    }

    fn host_observes(&mut self, out: &Out) {
        if out.o_meas_done {
            let mut t = self.blank("delay_measurement", "pos21", 0b000111);
            t.delay_cycles = Some(out.o_delay as u64);
            if out.o_err_meas {
                t.errors.push("delay_measurement_inconsistent".into());
            }
            // Measurement frames are not reported one by one.
            self.encoder.frames.clear();
            self.transactions.push(t);
        }
        if out.o_done {
            let (k, start) = self.current.unwrap_or((0, 0));
            let req = self.requests.get(k).cloned().unwrap_or_default();
            let mode = req.mode();
            let cont = req.command == Command::Pos21 && req.cont_values > 1 && mode == 0b000111;
            let already = self
                .transactions
                .iter()
                .filter(|t| t.request == Some(k))
                .count();
            let mut t = self.blank(
                if cont && already > 0 {
                    "continuous_value"
                } else {
                    "command"
                },
                req.command.name(),
                mode,
            );
            t.request = Some(k);
            t.start_cycle = start;
            t.mrs = req.mrs;
            t.param = req.param;
            t.encoder_answer = answer_name(self.encoder.answer).into();
            let refused = out.o_err_idle || (out.o_err_meas && !out.o_meas_done);
            let aborted = out.o_err_timeout || out.o_err_absent;
            if !refused && !aborted {
                if let Some((pos, bits)) = self.encoder.frames.pop_front() {
                    t.encoder_position = Some(pos);
                    t.sent_bits = crate::bits::string(&bits);
                }
                if super::frame_kind(mode) == FrameKind::Param21 {
                    t.ack = Some((out.o_ack_addr, out.o_ack_data));
                } else {
                    t.position = Some(out.o_position);
                    t.f1 = Some(out.o_f1);
                    t.f2 = Some(out.o_f2);
                    if out.o_ad1_valid {
                        t.ad1 = Some(format!("{:06x}", out.o_ad1));
                    }
                    if out.o_ad2_valid {
                        t.ad2 = Some(format!("{:06x}", out.o_ad2));
                    }
                }
            } else {
                self.encoder.frames.clear();
            }
            t.errors = error_names(out);
            self.transactions.push(t);
        }
        if self.host == Host::WaitIdle && !out.o_busy {
            // A type 2.2 block is taken after o_done: its answer (type II, ignored) is known only now.
            if let Some((k, _)) = self.current {
                let mode = self.requests.get(k).map(|r| r.mode()).unwrap_or(0);
                if super::frame_kind(mode) == FrameKind::Block22 {
                    for t in self
                        .transactions
                        .iter_mut()
                        .rev()
                        .take_while(|t| t.request == Some(k))
                    {
                        t.encoder_answer = answer_name(self.encoder.answer).into();
                    }
                }
            }
            self.host = if self.next < self.requests.len() {
                // Faults appear while the line is idle before the request, as a real break would.
                self.apply_faults(self.next);
                Host::WaitUntil(self.cycle + self.gap)
            } else {
                Host::Finished(self.cycle + TAIL_CYCLES)
            };
        }
    }

    fn blank(&self, kind: &str, command: &str, mode: u8) -> Transaction {
        Transaction {
            request: None,
            kind: kind.into(),
            command: command.into(),
            mode: format!("{mode:06b}"),
            start_cycle: self.cycle,
            done_cycle: self.cycle,
            mrs: 0,
            param: 0,
            encoder_position: None,
            sent_bits: String::new(),
            encoder_answer: String::new(),
            position: None,
            f1: None,
            f2: None,
            ad1: None,
            ad2: None,
            ack: None,
            delay_cycles: None,
            errors: Vec::new(),
        }
    }
}

impl Bench {
    /// One sample: the master's `input` and `out`, the clock at the
    /// encoder, the pair and the decoded state as they stand now.
    fn fill(&self, input: &In, out: &Out, clk_at_encoder: bool, sample: &mut Sample) {
        input.write_values(&mut sample.inputs);
        out.write_values(&mut sample.outputs);
        sample.line[0] = out.o_endat_clk as u64;
        sample.line[1] = clk_at_encoder as u64;
        sample.line[2] = input.i_endat_data_in as u64;
        sample.line[3] = self.enc_drive.level as u64;
        sample.line[4] = out.o_endat_data_oe as u64;
        sample.line[5] = self.enc_drive.enable as u64;
        sample.decoded[0] = self.master.state() as u64;
        sample.decoded[1] = self.master.rx_phase() as u64;
        sample.decoded[2] = self.master.fall_idx();
        sample.decoded[3] = self.encoder.latched_position;
    }
}

fn answer_name(a: Answer) -> &'static str {
    match a {
        Answer::Ok => "ok",
        Answer::TypeI => "type_i",
        Answer::TypeII => "type_ii",
        Answer::Ignored => "ignored",
    }
}

/// The flags of one `o_done`, by name.
pub fn error_names(out: &Out) -> Vec<String> {
    let flags = [
        (out.o_err_crc, "crc"),
        (out.o_err_ad1_crc, "ad1_crc"),
        (out.o_err_ad2_crc, "ad2_crc"),
        (out.o_err_type2, "type_ii"),
        (out.o_err_type3, "type_iii"),
        (out.o_err_type4, "type_iv"),
        (out.o_err_ack, "acknowledgement_mismatch"),
        (out.o_err_timeout, "no_start_bit"),
        (out.o_err_absent, "line_not_driven"),
        (out.o_err_idle, "line_not_idle"),
        (out.o_err_delay, "delay_drift"),
        (out.o_err_meas && !out.o_meas_done, "not_calibrated"),
        (out.o_f1, "f1_error"),
        (!out.o_f2, "f2_error"),
    ];
    flags
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, n)| n.to_string())
        .collect()
}

impl Testbench for Bench {
    crate::compiled_here!();

    type Transaction = Transaction;

    fn layout(&self) -> &Layout {
        &self.layout
    }

    fn finished(&self) -> bool {
        matches!(self.host, Host::Finished(end) if self.cycle >= end)
    }

    fn cycle(&self) -> u64 {
        self.cycle
    }

    fn into_transactions(self) -> Vec<Transaction> {
        self.transactions
    }

    fn step(&mut self, sample: Option<&mut Sample>) {
        let input = self.host_decides();
        let out = self.master.step(&input);
        let clk_at_encoder = self.clk_line.step(out.o_endat_clk);
        let (at_master, at_encoder) = self.pair.step(
            Drive {
                enable: out.o_endat_data_oe,
                level: out.o_endat_data_out,
            },
            self.enc_drive,
        );
        self.enc_drive = self.encoder.step(clk_at_encoder, at_encoder.level);
        self.data_at_master = at_master.level;
        self.host_observes(&out);
        self.last_in = input;
        self.last_out = out;
        self.cycle += 1;
        let Some(sample) = sample else { return };
        self.fill(&input, &out, clk_at_encoder, sample);
    }

    /// Before the first cycle: the master in its reset state (`last_out`,
    /// clock high and driver off), the cable at rest carrying its clock,
    /// the pair high at both ends (the encoder's idle level).
    fn before_first_cycle(&self, sample: &mut Sample) -> bool {
        if self.cycle != 0 {
            return false;
        }
        let mut input = self.last_in;
        input.i_endat_data_in = self.data_at_master;
        self.fill(&input, &self.last_out, self.last_out.o_endat_clk, sample);
        true
    }

    fn quiet_cycles(&self) -> u64 {
        let host = match self.host {
            Host::WaitUntil(at) if self.cycle < at => at - self.cycle,
            Host::WaitUntil(_) | Host::WaitIdle if !self.last_out.o_busy => 0,
            Host::WaitUntil(_) | Host::WaitIdle => u64::MAX,
            Host::Finished(end) => end.saturating_sub(self.cycle),
        };
        let input = In {
            i_endat_data_in: self.stuck.unwrap_or(self.data_at_master),
            ..In::default()
        };
        // The cycle after a request shows its pulse falling.
        if host == 0 || input != self.last_in {
            return 0;
        }
        let master_drive = Drive {
            enable: self.last_out.o_endat_data_oe,
            level: self.last_out.o_endat_data_out,
        };
        host.min(self.master.quiet(&input))
            .min(self.clk_line.quiet(self.last_out.o_endat_clk))
            .min(self.pair.quiet(master_drive, self.enc_drive))
            .min(self.encoder.quiet(self.clk_line.output()))
    }

    fn skip(&mut self, n: u64) {
        let master_drive = Drive {
            enable: self.last_out.o_endat_data_oe,
            level: self.last_out.o_endat_data_out,
        };
        self.master.skip(n);
        self.clk_line.skip(n);
        self.pair.skip(n, master_drive, self.enc_drive);
        self.encoder.skip(n);
        self.cycle += n;
    }
}

/// An answer later than the fixed sample point ([`BenchConfig::late_answer`]),
/// in system clock cycles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LateAnswer {
    /// The round trip: the clock cable, the encoder's registered output and
    /// its output delay, the data cable, the master's input register and
    /// synchroniser.
    pub round_trip: u64,
    /// The sample point after the rising clock edge: the high phase, the
    /// synchroniser and `sample_delay_ns`.
    pub sample_point: u64,
    /// One cycle, ps.
    pub period_ps: u64,
    /// The least sample delay that reaches the round trip.
    pub sample_delay_cycles: u64,
    /// The greatest sample delay the frame schedule allows.
    pub sample_delay_max: u64,
    /// With delay compensation, the measurement clock whose frames are
    /// sampled late, kHz; `None` without (the reads are).
    pub meas_clock_khz: Option<f64>,
    /// The least high phase whose fixed sample point reaches the round trip.
    pub high_needed: u64,
}

impl LateAnswer {
    /// Cycles as ns.
    fn ns(&self, cycles: u64) -> f64 {
        cycles as f64 * self.period_ps as f64 / 1e3
    }

    /// What is wrong, in ns.
    pub fn problem(&self) -> String {
        let outcome = match self.meas_clock_khz {
            None => "without delay compensation every read fails as line_not_driven".to_string(),
            Some(khz) => format!("the delay measurement's frames at {khz} kHz are sampled there (the round trip is not known yet), so every measurement fails as delay_measurement_inconsistent and every read as not_calibrated"),
        };
        format!(
            "the round trip of {} cycles ({:.1} ns: cable both ways, the encoder's output delay, the master's input register and synchroniser) is longer than the fixed sample point, {} cycles ({:.1} ns) after the rising clock edge the encoder answers on: {outcome}",
            self.round_trip,
            self.ns(self.round_trip),
            self.sample_point,
            self.ns(self.sample_point)
        )
    }

    /// How to fix it: delay compensation (or, with it, a slower measurement
    /// clock), or a sample delay that reaches the round trip where the
    /// frame schedule allows one.
    pub fn fix(&self) -> String {
        let first = match self.meas_clock_khz {
            None => "set master.delay_comp = true (the master measures the round trip at power-on and samples after it; seed 2.1.2)".to_string(),
            Some(_) => {
                // The fastest measurement clock whose high phase is
                // `high_needed`: f_sys divided by twice that.
                let cycles = 2 * self.high_needed;
                let khz = 1e9 / (self.period_ps * cycles) as f64;
                if khz >= 100.0 {
                    format!("set master.meas_clock_khz = {khz} (f_sys / {cycles}) or slower (seed 2.1.2: \"reduced clock pulse frequency (100 kHz to 200 kHz)\")")
                } else {
                    "no measurement clock of the seed's 100 to 200 kHz (2.1.2) has a high phase that long".to_string()
                }
            }
        };
        // Without compensation a lower clock has a longer high phase; with
        // it, the measurement clock is the one that counts.
        let other = match self.meas_clock_khz {
            None => "shorten the cable or lower the clock",
            Some(_) => "shorten the cable",
        };
        if self.sample_delay_cycles <= self.sample_delay_max {
            format!(
                "{first}, or master.sample_delay_ns = {:.0} or more, or {other}",
                self.ns(self.sample_delay_cycles).ceil()
            )
        } else {
            format!("{first}, or {other} (a sample delay of {:.0} ns would reach the round trip; the frame schedule allows at most {:.0} ns)", self.ns(self.sample_delay_cycles).ceil(), self.ns(self.sample_delay_max))
        }
    }

    /// The refusal, on the cable's length.
    pub fn error(&self) -> ConfigError {
        ConfigError::invalid("cable.length_m", self.problem(), self.fix())
    }
}
