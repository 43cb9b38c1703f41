//! Cooperative cancellation of long solves, sweeps and batches.
//!
//! A cancel check is installed for the current thread by [`interruptible`];
//! the solvers poll it through [`check`] (every Newton iteration, every row
//! of a sweep or batch), which calls the check at most once per
//! [`POLL_INTERVAL`] of wall time, so a costly check (the Python bindings
//! reacquire the GIL to look for signals) stays cheap. When it returns
//! `true`, the work stops with [`Error::Interrupted`]. Batch worker threads
//! install a check on a shared flag that the calling thread sets.

use std::cell::RefCell;
use std::time::{Duration, Instant};

use crate::error::{Error, Result};

/// Minimum wall time between two calls of the installed check.
pub const POLL_INTERVAL: Duration = Duration::from_millis(20);

/// A cancel check: `true` means stop.
pub type CancelCheck<'a> = &'a (dyn Fn() -> bool + Sync);

struct Hook {
    check: *const (dyn Fn() -> bool + Sync),
    last: Instant,
    cancelled: bool,
}

thread_local! {
    static HOOK: RefCell<Vec<Hook>> = const { RefCell::new(Vec::new()) };
}

/// Run `f` with `check` installed as the current thread's cancel check
/// (nested calls stack; the innermost check is polled).
pub fn interruptible<T>(check: CancelCheck<'_>, f: impl FnOnce() -> T) -> T {
    // SAFETY: the pointer is removed from the stack before `check`'s
    // lifetime ends (the guard pops it on return and on unwinding).
    let ptr: *const (dyn Fn() -> bool + Sync + '_) = check;
    let ptr: *const (dyn Fn() -> bool + Sync + 'static) = unsafe { std::mem::transmute(ptr) };
    HOOK.with(|h| {
        h.borrow_mut().push(Hook {
            check: ptr,
            last: Instant::now(),
            cancelled: false,
        })
    });
    struct Pop;
    impl Drop for Pop {
        fn drop(&mut self) {
            HOOK.with(|h| {
                h.borrow_mut().pop();
            });
        }
    }
    let _pop = Pop;
    f()
}

/// `Err(Interrupted)` if the installed check (polled at most every
/// [`POLL_INTERVAL`]) asks to stop; `Ok` if none is installed.
pub fn check() -> Result<()> {
    let stop = HOOK.with(|h| {
        let mut h = h.borrow_mut();
        let Some(top) = h.last_mut() else {
            return false;
        };
        if top.cancelled {
            return true;
        }
        if top.last.elapsed() < POLL_INTERVAL {
            return false;
        }
        top.last = Instant::now();
        // SAFETY: see `interruptible`.
        let f = unsafe { &*top.check };
        top.cancelled = f();
        top.cancelled
    });
    if stop {
        Err(Error::Interrupted)
    } else {
        Ok(())
    }
}
