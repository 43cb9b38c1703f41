//! Solvers: one Newton solver ([`newton()`](fn@newton)), the shooting boundary value
//! problem that uses it ([`shooting`]), homotopy continuation
//! ([`continuation`]) and cooperative cancellation ([`cancel`]).

pub mod cancel;
pub mod coarse_path;
pub mod continuation;
mod corrector;
pub mod equilibrium;
pub mod fn_system;
mod fold;
pub mod guess;
mod hop_finish;
pub mod limit;
pub mod newton;
pub mod options;
pub mod predict;
pub mod predict_warm;
pub mod presolve;
pub mod residual;
pub mod shooting;
pub mod solution;
pub mod system;
mod track;

pub use newton::{newton, FnSystem, NewtonOptions, NewtonResult, Status, System};
