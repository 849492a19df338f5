use cosim::ffi::*;
use std::ffi::{c_char, CStr};

fn last_error() -> String {
    // SAFETY: emu_last_error returns a valid NUL-terminated string.
    unsafe { CStr::from_ptr(emu_last_error()) }
        .to_string_lossy()
        .into_owned()
}

#[test]
fn a_missing_file_is_an_error_value_naming_the_path() {
    // SAFETY: both strings are NUL-terminated literals.
    let h = unsafe { emu_open(c"ssi".as_ptr(), c"/no/such/emu.toml".as_ptr(), 50_000_000) };
    assert_eq!(h, -1);
    assert!(
        last_error().contains("/no/such/emu.toml"),
        "{}",
        last_error()
    );
}

#[test]
fn create_writes_its_error_into_the_callers_buffer() {
    let mut buf = [0 as c_char; 256];
    // SAFETY: NUL-terminated literals, and a buffer of buf.len() bytes.
    let h = unsafe {
        emu_create(
            c"biss".as_ptr(),
            c"[[slaves]]\nbits = 0\n".as_ptr(),
            80_000_000,
            buf.as_mut_ptr(),
            buf.len(),
        )
    };
    assert_eq!(h, -1);
    // SAFETY: emu_create NUL-terminates within the buffer.
    let msg = unsafe { CStr::from_ptr(buf.as_ptr()) }
        .to_string_lossy()
        .into_owned();
    assert!(msg.contains("slaves[0].bits"), "{msg}");
}

#[test]
fn a_closed_or_unknown_handle_is_refused() {
    // SAFETY: NUL-terminated literals, and no error buffer.
    let h = unsafe {
        emu_create(
            c"ssi".as_ptr(),
            c"".as_ptr(),
            50_000_000,
            std::ptr::null_mut(),
            0,
        )
    };
    assert!(h > 0);
    assert_eq!(emu_close(h), 0);
    assert_eq!(emu_step(h, 1), -1);
    assert!(last_error().contains("not open"));
    assert_eq!(emu_step(0, 1), -1);
    assert_eq!(emu_count(-5), -1);
}
