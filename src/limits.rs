//! Caps on the work of one call (issue 12): far above any robot of the
//! paper, far below what could exhaust memory or run unbounded. The core
//! checks them ([`crate::batch::BatchOptions::validate`], ...); the Python
//! bindings read integer arguments against them.

/// Largest number of RK4 steps over the body accepted per solve.
pub const MAX_STEPS: usize = 100_000;
/// Largest Newton (or inverse) iteration budget accepted per call.
pub const MAX_ITER: usize = 100_000;
/// Largest number of eq-43 increments of `blocked_temperature`.
pub const MAX_INCREMENTS: usize = 10_000;
/// Largest number of rows of one batch call (`solve_batch`, `sweep`).
pub const MAX_BATCH_ROWS: usize = 10_000_000;
/// Largest chunk size of a batch call.
pub const MAX_CHUNK: usize = 10_000_000;
/// Largest worker-thread count of a batch call.
pub const MAX_THREADS: usize = 1024;
