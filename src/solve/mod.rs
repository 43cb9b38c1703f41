//! Solvers: one Newton solver ([`newton()`](fn@newton)), the shooting boundary value
//! problem that uses it ([`shooting`]), homotopy continuation
//! ([`continuation`]) and cooperative cancellation ([`cancel`]).

pub mod abd;
pub mod arclength;
pub mod cancel;
pub mod coarse_path;
pub mod continuation;
mod corrector;
pub mod equilibrium;
pub mod fn_system;
mod fold;
pub mod forward;
pub mod guess;
pub mod homotopy;
mod hop_finish;
pub mod law_coordinate;
pub mod limit;
pub mod ms;
pub mod newton;
pub mod nleq;
pub mod options;
pub mod predict;
pub mod predict_warm;
pub mod presolve;
pub mod residual;
pub mod segments;
pub mod shooting;
pub mod solution;
pub mod system;
mod track;

pub use newton::{newton, FnSystem, NewtonOptions, NewtonResult, Status, System};
