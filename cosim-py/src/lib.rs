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
//! ```

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// An emulator of `kind` (`ssi`, `biss`, `endat`, `tformat`, `esl`, `sar58k24`, `modbus`, `can`) made
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
        Ok(Emulator { inner: cosim::open(kind, toml, origin, f_emu_hz).map_err(err)? })
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
            .map(|v| format!("at {} ns (emulator cycle {}): {}: {}", v.time_ns, v.cycle, v.rule, v.detail))
            .collect()
    }

    /// The transcript (what the emulator sent and saw) as JSON text.
    fn transcript(&self) -> String {
        self.inner.transcript().to_string()
    }
}

/// The module.
#[pymodule]
fn encoder_emu(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Emulator>()?;
    Ok(())
}
