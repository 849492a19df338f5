//! The C ABI: one handle table, plain integers and C strings, errors as
//! values. The signatures are DPI-C compatible (`int` = `int32_t`,
//! `longint` = `int64_t`, `string` = `const char *`), so Verilator's
//! `import "DPI-C"` calls them directly; Icarus reaches them through the
//! VPI module `hdl/emu/vpi/emu_vpi.c`.
//!
//! Every function returns a negative value (or a null pointer) on failure
//! and leaves the message in [`emu_last_error`]; none unwinds a panic into C
//! (each body runs under `catch_unwind`, and a caught panic becomes an
//! error message). Simulators call from one thread; the table is behind a
//! mutex all the same.
//!
//! The functions that take C strings or buffers are `unsafe`: Rust cannot
//! check the pointers a simulator passes, so each states its contract under
//! "Safety", and every `unsafe { text(..) }` in them rests on it.

use std::ffi::{c_char, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Mutex;

use crate::{open, Emulator, Error, Pins};

static TABLE: Mutex<Vec<Option<Box<dyn Emulator>>>> = Mutex::new(Vec::new());
static LAST_ERROR: Mutex<Option<CString>> = Mutex::new(None);
static TEXT: Mutex<Option<CString>> = Mutex::new(None);

fn set_error(message: String) {
    let c = CString::new(message.replace('\0', " ")).unwrap_or_default();
    *LAST_ERROR.lock().unwrap_or_else(|e| e.into_inner()) = Some(c);
}

/// Runs `f`, turning an error or a panic into `fail` and a message.
fn guard<T>(fail: T, f: impl FnOnce() -> Result<T, Error>) -> T {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(v)) => v,
        Ok(Err(e)) => {
            set_error(e.to_string());
            fail
        }
        Err(p) => {
            let what = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            set_error(format!(
                "internal error in the emulator library (please report): {what}"
            ));
            fail
        }
    }
}

/// A C string argument as trimmed text; null or non-UTF-8 is a usage error.
///
/// # Safety
/// `p` is null or points to a NUL-terminated string that stays valid for
/// the call (DPI-C and VPI both pass such strings).
unsafe fn text(p: *const c_char, what: &str) -> Result<String, Error> {
    if p.is_null() {
        return Err(Error::Usage(format!("{what} is a null pointer")));
    }
    // SAFETY: not null, and NUL-terminated by the caller's contract.
    let s = unsafe { CStr::from_ptr(p) };
    // A wide Verilog reg carries leading spaces (or NULs) before its characters.
    s.to_str()
        .map(|t| {
            t.trim_matches(|c: char| c == '\0' || c.is_whitespace())
                .to_string()
        })
        .map_err(|_| Error::Usage(format!("{what} is not UTF-8")))
}

fn with<T>(handle: i32, f: impl FnOnce(&mut dyn Emulator) -> Result<T, Error>) -> Result<T, Error> {
    let mut table = TABLE.lock().unwrap_or_else(|e| e.into_inner());
    match usize::try_from(handle)
        .ok()
        .and_then(|h| h.checked_sub(1))
        .and_then(|i| table.get_mut(i))
        .and_then(|e| e.as_mut())
    {
        Some(emu) => f(emu.as_mut()),
        None => Err(Error::Usage(format!(
            "emulator handle {handle} is not open"
        ))),
    }
}

fn register(emu: Box<dyn Emulator>) -> i32 {
    let mut table = TABLE.lock().unwrap_or_else(|e| e.into_inner());
    table.push(Some(emu));
    table.len() as i32
}

fn frequency(f_emu_hz: i64) -> Result<u64, Error> {
    u64::try_from(f_emu_hz)
        .ok()
        .filter(|&f| f > 0)
        .ok_or_else(|| {
            Error::Usage(format!(
                "emulator clock {f_emu_hz} Hz: give a positive frequency in Hz"
            ))
        })
}

/// Opens an emulator of `kind` (`"ssi"`, `"biss"`) from the TOML file at
/// `path`, clocked at `f_emu_hz`. Returns a handle (1, 2, ...) or -1.
/// # Safety
/// Each string argument is null or NUL-terminated and valid for the call.
#[no_mangle]
pub unsafe extern "C" fn emu_open(kind: *const c_char, path: *const c_char, f_emu_hz: i64) -> i32 {
    guard(-1, || {
        let kind = unsafe { text(kind, "kind") }?;
        let path = unsafe { text(path, "path") }?;
        if path.is_empty() {
            return Err(Error::Usage(format!("no configuration file for the {kind} emulator: set the wrapper's CONFIG parameter or its plusarg to a TOML file")));
        }
        let toml = std::fs::read_to_string(&path).map_err(|e| {
            Error::Usage(format!(
                "{path}: cannot read the emulator configuration: {e}; check the path"
            ))
        })?;
        Ok(register(open(&kind, &toml, &path, frequency(f_emu_hz)?)?))
    })
}

/// Creates an emulator from TOML text. On failure returns -1 and, when
/// `err_buf` is not null, writes the message there (NUL-terminated,
/// truncated to `err_len` bytes).
/// # Safety
/// Each string argument is null or NUL-terminated and valid for the call; `err_buf` is null or points to at least `err_len` writable bytes.
#[no_mangle]
pub unsafe extern "C" fn emu_create(
    kind: *const c_char,
    toml: *const c_char,
    f_emu_hz: i64,
    err_buf: *mut c_char,
    err_len: usize,
) -> i32 {
    let h = guard(-1, || {
        let kind = unsafe { text(kind, "kind") }?;
        let toml = unsafe { text(toml, "toml") }?;
        Ok(register(open(
            &kind,
            &toml,
            "<toml>",
            frequency(f_emu_hz)?,
        )?))
    });
    if h < 0 {
        let msg = LAST_ERROR
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()
            .unwrap_or_default();
        // SAFETY: the caller gives a buffer of at least err_len bytes, or null.
        unsafe { copy_out(msg.as_bytes(), err_buf, err_len) };
    }
    h
}

/// Copies `bytes` into the caller's buffer, truncated to `len - 1` bytes and
/// NUL-terminated; nothing when `buf` is null or `len` is 0. Returns the
/// length of the whole text.
///
/// # Safety
/// `buf` is null or points to at least `len` writable bytes.
unsafe fn copy_out(bytes: &[u8], buf: *mut c_char, len: usize) -> i32 {
    if !buf.is_null() && len > 0 {
        let n = bytes.len().min(len - 1);
        // SAFETY: n + 1 <= len bytes, writable by the caller's contract.
        unsafe {
            std::ptr::copy_nonoverlapping(bytes.as_ptr() as *const c_char, buf, n);
            *buf.add(n) = 0;
        }
    }
    i32::try_from(bytes.len()).unwrap_or(i32::MAX)
}

/// One rising edge of the emulator clock: `pins` in (bit 0 line clock, bit
/// 1 master data, bit 2 master driver enable), the emulator's pins out (bit
/// 0 data, bit 1 driver enable), or -1 for a bad handle.
#[no_mangle]
pub extern "C" fn emu_step(handle: i32, pins: i32) -> i32 {
    guard(-1, || {
        with(handle, |e| Ok(e.step(Pins(pins as u32)).0 as i32))
    })
}

/// Device `device`'s position from its next latch on (the testbench owns it from now).
#[no_mangle]
pub extern "C" fn emu_set_position(handle: i32, device: i32, position: i64) -> i32 {
    guard(-1, || {
        with(handle, |e| {
            e.set_position(device.max(0) as usize, position as u64)
                .map(|_| 0)
        })
    })
}

/// Sets one status (`"error"`, `"warning"`, ...) of device `device` to `value` (0 or 1).
/// # Safety
/// Each string argument is null or NUL-terminated and valid for the call.
#[no_mangle]
pub unsafe extern "C" fn emu_set_status(
    handle: i32,
    device: i32,
    name: *const c_char,
    value: i32,
) -> i32 {
    guard(-1, || {
        let name = unsafe { text(name, "status name") }?;
        with(handle, |e| {
            e.set_status(device.max(0) as usize, &name, value != 0)
                .map(|_| 0)
        })
    })
}

/// Moves device `device` along a motion profile (a `[motion]` table in TOML text) from now on.
/// # Safety
/// Each string argument is null or NUL-terminated and valid for the call.
#[no_mangle]
pub unsafe extern "C" fn emu_set_motion(handle: i32, device: i32, toml: *const c_char) -> i32 {
    guard(-1, || {
        let toml = unsafe { text(toml, "motion") }?;
        with(handle, |e| {
            e.set_motion(device.max(0) as usize, &toml).map(|_| 0)
        })
    })
}

/// Schedules faults given as the scenario's fault tables in TOML text.
/// # Safety
/// Each string argument is null or NUL-terminated and valid for the call.
#[no_mangle]
pub unsafe extern "C" fn emu_schedule_fault(handle: i32, toml: *const c_char) -> i32 {
    guard(-1, || {
        let toml = unsafe { text(toml, "fault") }?;
        with(handle, |e| e.schedule_fault(&toml).map(|_| 0))
    })
}

/// Transactions (latches) so far, or -1.
#[no_mangle]
pub extern "C" fn emu_count(handle: i32) -> i64 {
    guard(-1, || with(handle, |e| Ok(e.count() as i64)))
}

/// The position device `device` latched in the last transaction, or -1
/// when there is none (a 64-bit position of all ones reads as -1 too:
/// check [`emu_count`]).
#[no_mangle]
pub extern "C" fn emu_last_value(handle: i32, device: i32) -> i64 {
    guard(-1, || {
        with(handle, |e| {
            Ok(e.last_value(device.max(0) as usize)
                .map_or(-1, |v| v as i64))
        })
    })
}

/// A status (0 or 1) device `device` reported in the last transaction, or -1.
/// # Safety
/// Each string argument is null or NUL-terminated and valid for the call.
#[no_mangle]
pub unsafe extern "C" fn emu_last_status(handle: i32, device: i32, name: *const c_char) -> i32 {
    guard(-1, || {
        let name = unsafe { text(name, "status name") }?;
        with(handle, |e| {
            e.last_status(device.max(0) as usize, &name)
                .map(|b| b as i32)
        })
    })
}

/// Protocol violations of the master seen so far, or -1.
#[no_mangle]
pub extern "C" fn emu_violations(handle: i32) -> i64 {
    guard(-1, || with(handle, |e| Ok(e.violations().len() as i64)))
}

/// The next violation not yet shown, as one line ("" when none); the
/// pointer stays valid until the next call of this function. `emu_step`
/// sets bit 7 of its result while one waits.
#[no_mangle]
pub extern "C" fn emu_take_violation(handle: i32) -> *const c_char {
    guard(std::ptr::null(), || {
        let line = with(handle, |e| Ok(e.take_violation().unwrap_or_default()))?;
        let c = CString::new(line).map_err(|e| Error::Usage(e.to_string()))?;
        let mut slot = TEXT.lock().unwrap_or_else(|e| e.into_inner());
        *slot = Some(c);
        Ok(slot.as_ref().map_or(std::ptr::null(), |c| c.as_ptr()))
    })
}

/// Writes the transcript (JSON) to `path`. Returns 0 or -1.
/// # Safety
/// Each string argument is null or NUL-terminated and valid for the call.
#[no_mangle]
pub unsafe extern "C" fn emu_write_transcript(handle: i32, path: *const c_char) -> i32 {
    guard(-1, || {
        let path = unsafe { text(path, "path") }?;
        let json = with(handle, |e| Ok(e.transcript()))?;
        let body = serde_json::to_string_pretty(&json).map_err(|e| Error::Usage(e.to_string()))?;
        std::fs::write(&path, body + "\n")
            .map_err(|e| Error::Usage(format!("{path}: cannot write the transcript: {e}")))?;
        Ok(0)
    })
}

/// The transcript as JSON text; the pointer stays valid until the next call
/// of this function. Null on failure.
#[no_mangle]
pub extern "C" fn emu_transcript(handle: i32) -> *const c_char {
    guard(std::ptr::null(), || {
        let json = with(handle, |e| Ok(e.transcript()))?;
        let c = CString::new(json.to_string()).map_err(|e| Error::Usage(e.to_string()))?;
        let mut slot = TEXT.lock().unwrap_or_else(|e| e.into_inner());
        *slot = Some(c);
        Ok(slot.as_ref().map_or(std::ptr::null(), |c| c.as_ptr()))
    })
}

/// Closes an emulator. Returns 0 or -1.
#[no_mangle]
pub extern "C" fn emu_close(handle: i32) -> i32 {
    guard(-1, || {
        let mut table = TABLE.lock().unwrap_or_else(|e| e.into_inner());
        match usize::try_from(handle)
            .ok()
            .and_then(|h| h.checked_sub(1))
            .and_then(|i| table.get_mut(i))
        {
            Some(slot @ Some(_)) => {
                *slot = None;
                Ok(0)
            }
            _ => Err(Error::Usage(format!(
                "emulator handle {handle} is not open"
            ))),
        }
    })
}

// The *_copy functions and emu_plusarg hand back text by copying it into
// the caller's buffer, and their result through `result`, not as a return
// value: VHDL (VHDL-2008) has no function with an `out` parameter, so they
// are foreign procedures there, whose `out` arguments GHDL passes by
// address (a string(1 to N) as a pointer to its N characters, an integer
// as a pointer to it).

/// Writes `value` through `result` when it is not null.
///
/// # Safety
/// `result` is null or points to a writable `i32`.
unsafe fn put(result: *mut i32, value: i32) {
    if !result.is_null() {
        // SAFETY: not null, writable by the caller's contract.
        unsafe { *result = value };
    }
}

/// The message of the last failure copied into `buf` (see [`copy_out`]);
/// `*result` its length (0 when none).
/// # Safety
/// `buf` is null or points to at least `len` writable bytes; `result` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn emu_last_error_copy(buf: *mut c_char, len: i32, result: *mut i32) {
    let slot = LAST_ERROR.lock().unwrap_or_else(|e| e.into_inner());
    let bytes = slot.as_ref().map_or(&b""[..], |c| c.as_bytes());
    // SAFETY: the caller's contract.
    unsafe { put(result, copy_out(bytes, buf, len.max(0) as usize)) }
}

/// The next violation not yet shown (as [`emu_take_violation`]) copied into
/// `buf`; `*result` its length, 0 when none waits, or -1.
/// # Safety
/// `buf` is null or points to at least `len` writable bytes; `result` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn emu_take_violation_copy(
    handle: i32,
    buf: *mut c_char,
    len: i32,
    result: *mut i32,
) {
    let n = guard(-1, || {
        let line = with(handle, |e| Ok(e.take_violation().unwrap_or_default()))?;
        // SAFETY: the caller's contract.
        Ok(unsafe { copy_out(line.as_bytes(), buf, len.max(0) as usize) })
    });
    // SAFETY: the caller's contract.
    unsafe { put(result, n) }
}

/// The value of the simulator's command-line argument `+<name>=<value>`
/// (the last one given) copied into `buf`; `*result` its length, or -1
/// when there is none. For simulators whose language has no
/// `$value$plusargs` (VHDL in GHDL, which hands `+` arguments through to
/// the simulation's process).
/// # Safety
/// `name` is null or NUL-terminated; `buf` is null or points to at least `len` writable bytes; `result` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn emu_plusarg(
    name: *const c_char,
    buf: *mut c_char,
    len: i32,
    result: *mut i32,
) {
    let n = guard(-1, || {
        let name = unsafe { text(name, "plusarg name") }?;
        let prefix = format!("+{name}=");
        let value = std::env::args_os()
            .filter_map(|a| a.into_string().ok())
            .filter_map(|a| a.strip_prefix(&prefix).map(str::to_string))
            .next_back();
        // SAFETY: the caller's contract.
        Ok(value.map_or(-1, |v| unsafe {
            copy_out(v.as_bytes(), buf, len.max(0) as usize)
        }))
    });
    // SAFETY: the caller's contract.
    unsafe { put(result, n) }
}

/// Transcripts to write when the process exits: (handle, path).
static AT_EXIT: Mutex<Vec<(i32, String)>> = Mutex::new(Vec::new());

extern "C" {
    /// The C library's exit hook (C99 7.20.4.2).
    fn atexit(hook: extern "C" fn()) -> i32;
}

extern "C" fn write_transcripts_at_exit() {
    let list = std::mem::take(&mut *AT_EXIT.lock().unwrap_or_else(|e| e.into_inner()));
    for (handle, path) in list {
        let Ok(c) = CString::new(path.clone()) else {
            continue;
        };
        // SAFETY: a NUL-terminated string valid for the call.
        if unsafe { emu_write_transcript(handle, c.as_ptr()) } < 0 {
            let msg = LAST_ERROR
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .clone()
                .unwrap_or_default();
            eprintln!("ERROR: emulator {handle}: {}", msg.to_string_lossy());
        }
    }
}

/// Writes the transcript of `handle` to `path` when the process exits, for
/// simulators whose language has no end-of-simulation hook (VHDL: GHDL
/// exits after `std.env.finish` or the last event). Returns 0 or -1.
/// # Safety
/// `path` is null or NUL-terminated and valid for the call.
#[no_mangle]
pub unsafe extern "C" fn emu_transcript_at_exit(handle: i32, path: *const c_char) -> i32 {
    guard(-1, || {
        let path = unsafe { text(path, "path") }?;
        with(handle, |_| Ok(()))?;
        let mut list = AT_EXIT.lock().unwrap_or_else(|e| e.into_inner());
        if list.is_empty() {
            static HOOKED: std::sync::Once = std::sync::Once::new();
            let mut hooked = 0;
            // SAFETY: registers a function that takes no arguments and never unwinds.
            HOOKED.call_once(|| hooked = unsafe { atexit(write_transcripts_at_exit) });
            if hooked != 0 {
                return Err(Error::Usage(
                    "the C library refused an exit hook: write the transcript with emu_write_transcript".into(),
                ));
            }
        }
        list.push((handle, path));
        Ok(0)
    })
}

/// The message of the last failure ("" when none). Valid until the next failure.
#[no_mangle]
pub extern "C" fn emu_last_error() -> *const c_char {
    let slot = LAST_ERROR.lock().unwrap_or_else(|e| e.into_inner());
    match slot.as_ref() {
        Some(c) => c.as_ptr(),
        None => c"".as_ptr(),
    }
}
