//! Encoder emulators for any testbench: the model's encoders, slaves and
//! cables behind one small interface ([`Emulator`]) and one C ABI
//! ([`ffi`]), for Verilator (DPI-C), Icarus (VPI, `hdl/emu/vpi/emu_vpi.c`)
//! and, later, cocotb.
//!
//! An emulator is made from the TOML tables a scenario file uses for its
//! device, cable and faults, and runs on the testbench's own emulator clock
//! `f_emu`: one [`Emulator::step`] per rising edge of that clock, with the
//! master's line pins in and the emulator's line pins out, after the cable.
//!
//! ```
//! use cosim::{open, Pins};
//!
//! // The seed's SSI example (SAR58K24 manual): 12 bits, 495, 10 m of cable.
//! let toml = "[encoder]\nbits = 12\n[cable]\nlength_m = 10\n";
//! let mut emu = open("ssi", toml, "example.toml", 50_000_000).unwrap();
//! emu.set_position(0, 495).unwrap();
//! // Clock it as a 250 kHz reader would: 100 cycles per half period, the
//! // first falling edge at cycle 100 stores, each later low phase ends with a sample.
//! let mut bits = String::new();
//! for cycle in 0..2700 {
//!     let clk = cycle < 100 || (cycle / 100) % 2 == 0;
//!     let out = emu.step(Pins::line(clk));
//!     if cycle > 200 && cycle % 200 == 199 {
//!         bits.push(if out.data() { '1' } else { '0' });
//!     }
//! }
//! assert_eq!(&bits[..12], "000111101111"); // 495, MSB first
//! assert_eq!(emu.last_value(0), Some(495));
//! ```

pub mod biss;
pub mod can;
pub mod canopen;
pub mod check;
pub mod config;
pub mod endat;
pub mod esl;
pub mod ffi;
pub mod half_duplex;
pub mod modbus;
pub mod monitor;
pub mod motion;
pub mod pair;
pub mod probe;
pub mod registry;
pub mod sar58k24;
pub mod ssi;
pub mod tformat;

pub use config::Error;

/// Result alias of the crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// The line pins between master and emulator, one bit each, as the C ABI
/// passes them (`emu_step(handle, pins)`).
///
/// In: bit 0 is the line clock the master drives (SSI clock, BiSS MA,
/// EnDat clock); bit 1 the master's data line and bit 2 its driver enable
/// (half-duplex protocols). Out: bit 0 the data the emulator drives towards
/// the master (after the cable), bit 1 its driver enable, bit 7 set when a
/// protocol violation of the master waits to be shown
/// ([`Emulator::take_violation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Pins(pub u32);

impl Pins {
    /// A line clock (or single line) level alone.
    pub fn line(level: bool) -> Pins {
        Pins(level as u32)
    }

    /// Bit 0: the clock in, or the data out.
    pub fn data(self) -> bool {
        self.0 & 1 != 0
    }

    /// Bit 1 of an output: the emulator's driver enable.
    pub fn enable(self) -> bool {
        self.0 & 2 != 0
    }
}

/// One emulated device (or chain) and its cable, stepped on the emulator clock.
pub trait Emulator: Send {
    /// The protocol name (`ssi`, `biss`).
    fn kind(&self) -> &'static str;

    /// One rising edge of the emulator clock: the master's pins now in,
    /// the emulator's pins at the master's end of the cable out.
    fn step(&mut self, pins: Pins) -> Pins;

    /// The position device `device` (chain position, 0 for a single
    /// encoder) stores at its next latch; from now on the testbench owns
    /// the position (the configuration's `positions` list no longer applies).
    fn set_position(&mut self, device: usize, position: u64) -> Result<()>;

    /// Sets one status the device reports (`error`, `warning`, ...), from its
    /// next transaction on, independently of every other status.
    fn set_status(&mut self, device: usize, name: &str, value: bool) -> Result<()>;

    /// Moves device `device` along a motion profile (a `[motion]` table in
    /// TOML text, see [`motion`]) from now on, instead of set positions.
    fn set_motion(&mut self, device: usize, toml: &str) -> Result<()> {
        let _ = (device, toml);
        Err(Error::Usage(format!(
            "the {} emulator takes no motion profile",
            self.kind()
        )))
    }

    /// Schedules faults given as the scenario's fault tables in TOML text.
    fn schedule_fault(&mut self, toml: &str) -> Result<()>;

    /// Transactions begun (latches) so far.
    fn count(&self) -> u64;

    /// The position device `device` latched in the last transaction.
    fn last_value(&self, device: usize) -> Option<u64>;

    /// A status device `device` reported in the last transaction.
    fn last_status(&self, device: usize, name: &str) -> Result<bool>;

    /// Everything the emulator sent, one entry per transaction, and every
    /// protocol violation of the master it saw.
    fn transcript(&self) -> serde_json::Value;

    /// The protocol checks of the master (see [`check`]).
    fn checks(&mut self) -> &mut check::Checks;

    /// The master's protocol violations seen so far.
    fn violations(&mut self) -> &[check::Violation] {
        self.checks().all()
    }

    /// The next violation the testbench has not been shown, as one line.
    fn take_violation(&mut self) -> Option<String> {
        self.checks().take()
    }
}

/// Makes an emulator of protocol `kind` from TOML text (`origin` names the
/// text in errors, normally its file, and a field's error its line),
/// clocked at `f_emu_hz`. The kinds are the descriptors' (`tbgen
/// protocols`): an emulator's kind or alias, or either followed by
/// `_monitor` for its monitor ([`registry`]).
pub fn open(kind: &str, toml: &str, origin: &str, f_emu_hz: u64) -> Result<Box<dyn Emulator>> {
    let (k, monitor) = registry::find(kind)
        .ok_or_else(|| Error::Usage(format!("no emulator `{kind}`; {}", registry::choices())))?;
    let make = if monitor { k.monitor } else { k.emulator };
    // The protocol's table, which each kind reads its fields from.
    make(toml, origin, f_emu_hz).map_err(|e| e.placed(toml, k.protocol.stem))
}
