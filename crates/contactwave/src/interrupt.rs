//! The process-wide interruption request (Ctrl-C or SIGTERM in the CLI, `KeyboardInterrupt`
//! in Python): once [`request`]ed, long loops (the solvers' time steps, the executor's
//! points, file writing between files) stop at their next check with
//! [`crate::Error::Interrupted`]. Files are written one whole file at
//! a time inside a [`Writing`] guard, so whoever ends the process on a signal can wait
//! until no file is half-written ([`writing`]).
//!
//! ```
//! use contactwave::interrupt;
//! interrupt::clear();
//! assert!(interrupt::check().is_ok());
//! interrupt::request();
//! assert_eq!(interrupt::check().unwrap_err().to_string(), "interrupted");
//! interrupt::clear();
//! ```

use crate::error::{Error, Result};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);
static WRITING: AtomicUsize = AtomicUsize::new(0);

/// Ask every running computation to stop at its next check.
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Withdraw the request (before a new computation: Python calls this at each entry).
pub fn clear() {
    REQUESTED.store(false, Ordering::SeqCst);
}

/// Whether an interruption was requested.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::Relaxed)
}

/// `Err(Error::Interrupted)` once an interruption was requested.
#[inline]
pub fn check() -> Result<()> {
    if requested() {
        Err(Error::Interrupted)
    } else {
        Ok(())
    }
}

/// Number of [`Writing`] guards alive: files being written now.
pub fn writing() -> usize {
    WRITING.load(Ordering::SeqCst)
}

/// Held while a file is written: see [`writing`].
#[derive(Debug)]
pub struct Writing(());

impl Writing {
    /// Start writing.
    pub fn start() -> Self {
        WRITING.fetch_add(1, Ordering::SeqCst);
        Writing(())
    }
}

impl Drop for Writing {
    fn drop(&mut self) {
        WRITING.fetch_sub(1, Ordering::SeqCst);
    }
}
