//! `encoder_emu`: the emulators of the `cosim` crate as a Python module, for
//! cocotb coroutines (and any Python). One class, [`Emulator`], over
//! [`cosim::Emulator`]: the same TOML tables, the same pins, the same
//! run-time controls and transcript as the HDL wrappers in `hdl/emu/`.
//!
//! ```python
//! import encoder_emu
//! emu = encoder_emu.Emulator("ssi", open("encoder.toml").read(), 50_000_000, "encoder.toml")
//! out = emu.step(pins)              # once per rising edge of the emulator clock
//! emu.set_position(0, 495); emu.last_value(0); emu.count(); emu.violations()
//! mon = encoder_emu.Monitor("ssi", open("encoder.toml").read(), 50_000_000, "encoder.toml")
//! mon.step(pins)                    # the master's pins, once per rising edge of the monitor clock
//! mon.count(); mon.last_value(0); mon.violations(); mon.transcript()
//! ```
//!
//! [`Monitor`] is the pin-level monitor and protocol checker of a protocol
//! (`cosim::monitor`): any `<proto>_monitor` the library opens, so a new
//! monitor needs no line here.

// PyO3 0.22's `#[pymethods]` expands each `PyResult` return into a
// conversion that clippy (1.85 on) calls useless (PyO3 issue #4828, fixed
// in 0.23); the lint is silenced for this crate until that upgrade.
#![allow(clippy::useless_conversion)]

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// An emulator of `kind` (an emulator's kind or alias in `tbgen protocols`:
/// `ssi`, `sar58k24`; `<kind>_monitor` for its monitor) made
/// from TOML text (`origin` names it in errors) on an emulator clock of
/// `f_emu_hz`. Errors (bad tables, a clock too slow) raise ValueError with
/// the file, the field and the fix.
#[pyclass(unsendable)]
struct Emulator {
    inner: Box<dyn cosim::Emulator>,
}

fn err(e: cosim::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

#[pymethods]
impl Emulator {
    #[new]
    #[pyo3(signature = (kind, toml, f_emu_hz, origin = "<toml>"))]
    fn new(kind: &str, toml: &str, f_emu_hz: u64, origin: &str) -> PyResult<Self> {
        Ok(Emulator {
            inner: cosim::open(kind, toml, origin, f_emu_hz).map_err(err)?,
        })
    }

    /// The protocol.
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.kind()
    }

    /// One rising edge of the emulator clock: the master's pins in (bit 0
    /// line clock or trigger, bit 1 master data/driver level, bit 2 driver
    /// enable, bit 3 CLR), the emulator's out (bit 0 data, bit 1 driver
    /// enable, bit 2 resolved half-duplex line level, bit 7 a violation waits).
    fn step(&mut self, pins: u32) -> u32 {
        self.inner.step(cosim::Pins(pins)).0
    }

    /// Device `device` latches `position` from its next transaction on.
    fn set_position(&mut self, device: usize, position: u64) -> PyResult<()> {
        self.inner.set_position(device, position).map_err(err)
    }

    /// One status bit of device `device` from its next transaction on.
    fn set_status(&mut self, device: usize, name: &str, value: bool) -> PyResult<()> {
        self.inner.set_status(device, name, value).map_err(err)
    }

    /// Faults (or CAN frames to send) as TOML tables.
    fn schedule_fault(&mut self, toml: &str) -> PyResult<()> {
        self.inner.schedule_fault(toml).map_err(err)
    }

    /// Transactions so far.
    fn count(&self) -> u64 {
        self.inner.count()
    }

    /// The value device `device` latched or sent in the last transaction (None: none yet).
    fn last_value(&self, device: usize) -> Option<u64> {
        self.inner.last_value(device)
    }

    /// A status of the last transaction.
    fn last_status(&self, device: usize, name: &str) -> PyResult<bool> {
        self.inner.last_status(device, name).map_err(err)
    }

    /// Every protocol violation of the master so far, one line each.
    fn violations(&mut self) -> Vec<String> {
        self.inner
            .violations()
            .iter()
            .map(|v| {
                format!(
                    "at {} ns (emulator cycle {}): {}: {}",
                    v.time_ns, v.cycle, v.rule, v.detail
                )
            })
            .collect()
    }

    /// The transcript (what the emulator sent and saw) as JSON text.
    fn transcript(&self) -> String {
        self.inner.transcript().to_string()
    }
}

/// The pin-level monitor and protocol checker of `protocol` (`ssi`, `biss`,
/// `endat`, and every other `<protocol>_monitor` of the library) from TOML
/// text (the emulator's file or a whole scenario will do) on a monitor clock
/// of `f_mon_hz`. It only listens: `step(pins)` with the master's pins (the
/// same bits as the HDL monitor's ports, `hdl/emu/<protocol>_monitor.v`:
/// SSI clock, data; BiSS-C MA, SLO; EnDat clock, data, data_oe, data_in)
/// returns True when a new violation was seen. Errors raise ValueError with
/// the file, the field and the fix.
#[pyclass(unsendable)]
struct Monitor {
    inner: Box<dyn cosim::Emulator>,
}

#[pymethods]
impl Monitor {
    #[new]
    #[pyo3(signature = (protocol, toml, f_mon_hz, origin = "<toml>"))]
    fn new(protocol: &str, toml: &str, f_mon_hz: u64, origin: &str) -> PyResult<Self> {
        let kind = format!("{}_monitor", protocol.trim_end_matches("_monitor"));
        Ok(Monitor {
            inner: cosim::open(&kind, toml, origin, f_mon_hz).map_err(err)?,
        })
    }

    /// The monitor's kind (`<protocol>_monitor`).
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.kind()
    }

    /// One rising edge of the monitor clock with the master's pins; True when a violation is new.
    fn step(&mut self, pins: u32) -> bool {
        self.inner.step(cosim::Pins(pins)).0 & cosim::check::VIOLATION_PENDING != 0
    }

    /// Transactions seen so far (the one in progress included).
    fn count(&self) -> u64 {
        self.inner.count()
    }

    /// The position of the last transaction seen (of slave `device` in a BiSS-C chain; None: none yet).
    fn last_value(&self, device: usize) -> Option<u64> {
        self.inner.last_value(device)
    }

    /// A status of the last transaction seen (SSI `error`; BiSS-C `error`, `warning`, `crc_ok`; EnDat `f1`,
    /// `f2`, `crc_ok`, `error`).
    fn last_status(&self, device: usize, name: &str) -> PyResult<bool> {
        self.inner.last_status(device, name).map_err(err)
    }

    /// Every violation of the seed's timing rules so far, one line each (time, rule with the seed's section, what).
    fn violations(&mut self) -> Vec<String> {
        self.inner
            .violations()
            .iter()
            .map(|v| {
                format!(
                    "at {} ns (monitor cycle {}): {}: {}",
                    v.time_ns, v.cycle, v.rule, v.detail
                )
            })
            .collect()
    }

    /// The transcript (every transaction as `tbgen decode` prints it, every violation) as JSON text.
    fn transcript(&self) -> String {
        self.inner.transcript().to_string()
    }
}

/// The module.
#[pymodule]
fn encoder_emu(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Emulator>()?;
    m.add_class::<Monitor>()?;
    Ok(())
}
