//! What the bad-input sweeps share (`tests/bad_values.rs`,
//! `tests/bad_captures.rs`, `cosim/tests/unit/bad_values.rs`): the awkward
//! numbers, the numeric fields of a TOML document, a deterministic random
//! source, and a panic caught with its message instead of printed. Each
//! test crate includes this file (`#[path]`); not every crate uses every
//! item.
#![allow(dead_code)]

use std::cell::RefCell;
use std::panic::{catch_unwind, AssertUnwindSafe};

use toml::Value;

/// Integers a field may be set to: zero, negative, one, just past 16, 31 and
/// 32 bits, past f64's exact integers, and the extremes.
pub const INTEGERS: &[i64] = &[
    0,
    -1,
    1,
    65_536,
    2_147_483_648,
    4_294_967_296,
    1 << 53,
    i64::MAX,
    i64::MIN,
];

/// Floats a field may be set to (also where an integer belongs).
pub const FLOATS: &[f64] = &[
    0.0,
    -1.0,
    1e-300,
    4_294_967_296.0,
    1e300,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
];

/// xorshift64*: the same sequence every run, so a failure repeats.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A number below `n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One step of a path into a TOML document.
#[derive(Clone, Debug)]
pub enum Key {
    Field(String),
    Index(usize),
}

/// Every numeric leaf under `value` with its path (below `path`), and
/// whether it is an integer.
pub fn numeric_leaves(value: &Value, path: &mut Vec<Key>, out: &mut Vec<(Vec<Key>, bool)>) {
    match value {
        Value::Integer(_) => out.push((path.clone(), true)),
        Value::Float(_) => out.push((path.clone(), false)),
        Value::Table(t) => {
            for (k, v) in t {
                path.push(Key::Field(k.clone()));
                numeric_leaves(v, path, out);
                path.pop();
            }
        }
        Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                path.push(Key::Index(i));
                numeric_leaves(v, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

/// The value at `path`.
pub fn leaf_mut<'a>(value: &'a mut Value, path: &[Key]) -> &'a mut Value {
    path.iter().fold(value, |v, k| match k {
        Key::Field(f) => &mut v[f.as_str()],
        Key::Index(i) => &mut v[*i],
    })
}

/// `ssi.master.clock_khz`, `can.nodes[0].position`.
pub fn dotted(path: &[Key]) -> String {
    let mut s = String::new();
    for k in path {
        match k {
            Key::Field(f) if s.is_empty() => s.push_str(f),
            Key::Field(f) => s.push_str(&format!(".{f}")),
            Key::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// `value` for a message: floats in exponent form (1e300, not 301 digits).
pub fn shown(value: &Value) -> String {
    match value {
        Value::Float(v) => format!("{v:e}"),
        v => v.to_string(),
    }
}

/// Every value a field at `path` is tried with: the integers where it holds
/// an integer, and the floats everywhere.
pub fn awkward_values(integer: bool) -> impl Iterator<Item = Value> {
    INTEGERS
        .iter()
        .filter(move |_| integer)
        .map(|&v| Value::Integer(v))
        .chain(FLOATS.iter().map(|&v| Value::Float(v)))
}

thread_local! {
    static CATCHING: RefCell<bool> = const { RefCell::new(false) };
    static LAST_PANIC: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Installs a panic hook that keeps the message and place of a panic inside
/// [`caught`] for the report instead of printing it; any other panic (the
/// test's own) goes to the hook there was.
pub fn quiet_panics() {
    let before = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if CATCHING.with(|c| *c.borrow()) {
            let place = info
                .location()
                .map(|l| format!("{}:{}", l.file(), l.line()))
                .unwrap_or_default();
            let payload = info.payload();
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            LAST_PANIC.with(|p| *p.borrow_mut() = format!("panicked at {place}: {what}"));
        } else {
            before(info);
        }
    }));
}

/// Runs `f`; a panic in it comes back as its message and place (with
/// [`quiet_panics`] installed).
pub fn caught<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    CATCHING.with(|c| *c.borrow_mut() = true);
    let outcome = catch_unwind(AssertUnwindSafe(f));
    CATCHING.with(|c| *c.borrow_mut() = false);
    outcome.map_err(|_| LAST_PANIC.with(|p| p.borrow().clone()))
}
