//! Thread CPU time for the benchmarks, from
//! `clock_gettime(CLOCK_THREAD_CPUTIME_ID)` (declared here: no `libc`
//! dependency). Included by `#[path]` from each benchmark that needs it.

#[repr(C)]
struct Timespec {
    tv_sec: i64,
    tv_nsec: i64,
}

extern "C" {
    // POSIX, in the C library every Rust program on Linux links already
    fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
}

/// `CLOCK_THREAD_CPUTIME_ID` on Linux.
const CLOCK_THREAD_CPUTIME_ID: i32 = 3;

/// Thread CPU time [s] from `clock_gettime(CLOCK_THREAD_CPUTIME_ID)`, or
/// `None` where it fails. (`/proc/thread-self/schedstat` is no substitute:
/// it is updated at scheduler ticks, 4 ms apart here.)
pub fn thread_cpu() -> Option<f64> {
    if !cfg!(target_os = "linux") || !cfg!(target_pointer_width = "64") {
        return None;
    }
    let mut ts = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec (64-bit Linux layout).
    let rc = unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    (rc == 0).then_some(ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9)
}
