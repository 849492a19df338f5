//! Partial files removed when the user interrupts a run.
//!
//! `tbgen gen` writes its files under hidden temporary names and renames
//! them into place at the end (see `generate`); a drop guard removes them
//! when the run fails. A SIGINT (Ctrl-C) or SIGTERM runs no destructor, so
//! the paths being written are also listed here, and on either signal a
//! thread removes every listed file (and every folder the run created, if
//! it is still empty), then lets the signal end the process the default
//! way: the shell sees a death by that signal (status 130 for SIGINT, 143
//! for SIGTERM), as of any Unix tool interrupted.
//!
//! Creating, renaming and removing a listed file happen while the list is
//! locked, and the handler holds the lock until the process is gone, so no
//! file can be created or renamed into place behind its back.

use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, Once};

use signal_hook::consts::{SIGINT, SIGTERM};

/// What an interrupt removes: files, then folders if empty (deepest first).
#[derive(Default)]
pub struct Pending {
    files: Vec<PathBuf>,
    folders: Vec<PathBuf>,
}

static PENDING: Mutex<Pending> = Mutex::new(Pending {
    files: Vec::new(),
    folders: Vec::new(),
});

/// The list, locked (a panic elsewhere while it was held leaves it usable:
/// it holds only paths).
fn lock() -> MutexGuard<'static, Pending> {
    install();
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// Starts the thread that waits for SIGINT and SIGTERM, once.
fn install() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // Without the handler an interrupt leaves partial files, as before:
        // not a reason to refuse the run.
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
            return;
        };
        std::thread::spawn(move || {
            if let Some(signal) = signals.forever().next() {
                let pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
                for f in &pending.files {
                    let _ = std::fs::remove_file(f);
                }
                for d in &pending.folders {
                    let _ = std::fs::remove_dir(d);
                }
                // Dies of the signal with the list still locked; exits with
                // the shell's code for it should that fail.
                let _ = signal_hook::low_level::emulate_default_handler(signal);
                std::process::exit(128 + signal);
            }
        });
    });
}

impl Pending {
    /// Creates `path` (truncating it), listed for removal on an interrupt.
    pub fn create(&mut self, path: &Path) -> io::Result<File> {
        self.files.push(path.to_path_buf());
        File::create(path)
    }

    /// `path` is no longer removed on an interrupt (renamed into place, or
    /// removed already).
    pub fn forget(&mut self, path: &Path) {
        self.files.retain(|f| f != path);
    }
}

/// Runs `f` with the list locked: an interrupt waits until it is done.
pub fn locked<R>(f: impl FnOnce(&mut Pending) -> R) -> R {
    f(&mut lock())
}

/// `std::fs::create_dir_all`, each folder it creates listed for removal on
/// an interrupt if still empty then (a folder a finished scenario wrote
/// into is not).
pub fn create_dir_all(dir: &Path) -> io::Result<()> {
    let mut pending = lock();
    let mut missing = Vec::new();
    let mut d = Some(dir);
    while let Some(p) = d.filter(|p| !p.as_os_str().is_empty() && !p.exists()) {
        missing.push(p.to_path_buf());
        d = p.parent();
    }
    std::fs::create_dir_all(dir)?;
    // Deepest first, so that a chain of new empty folders goes whole.
    pending.folders.extend(missing);
    Ok(())
}
