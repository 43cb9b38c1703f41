//! Solvers: one Newton solver ([`newton()`](fn@newton)), the shooting boundary value
//! problem that uses it ([`shooting`]), homotopy continuation
//! ([`continuation`]) and cooperative cancellation ([`cancel`]).

pub mod cancel;
pub mod continuation;
pub mod newton;
pub mod shooting;

pub use newton::{newton, FnSystem, NewtonOptions, NewtonResult, Status, System};
