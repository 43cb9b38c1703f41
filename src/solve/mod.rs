//! Solvers: the forward problem by multiple shooting ([`forward`], on the
//! system of [`ms`], its staircase factorisation [`abd`]), the
//! error-oriented damped Newton method ([`nleq`]), pseudo-arclength
//! continuation ([`arclength`], in the homotopies of [`homotopy`]), the
//! public entry points ([`shooting`]) and cooperative cancellation
//! ([`cancel`]). `docs/solver.md` describes the algorithm.

pub mod abd;
pub mod arclength;
pub mod bordered;
pub mod cancel;
pub mod equilibrium;
pub mod forward;
pub mod guess;
pub mod homotopy;
pub mod law_coordinate;
pub mod ms;
pub mod nleq;
pub mod options;
pub mod residual;
pub mod segments;
pub mod shooting;
pub mod solution;
