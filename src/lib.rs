//! # tcarod
//!
//! Kinetostatics of soft robots actuated by twisted-and-coiled actuators,
//! after Pawlowski, Sun, Xu, Liu and Zhao, "Modeling of Soft Robots Actuated
//! by Twisted-and-Coiled Actuators", IEEE/ASME T-Mech 24(1), 2019.
//!
//! Modules follow the paper:
//! * [`material`], [`tca`]: Section II, the TCA constitutive law (eqs 1-6);
//! * [`rod`]: Section III, the Cosserat rod with embedded string-like
//!   actuators (eqs 7-31) and its initial value problem;
//! * [`solve`]: one Newton solver (Armijo line search, rounding floor), the
//!   boundary value problem (eqs 32-33) by shooting with the exact Jacobian
//!   from the IVP's tangents ([`rod::integrate_tangent`]), homotopy
//!   continuation and cancellation; [`shooting`] re-exports its names;
//! * [`inverse`]: Section IV, Jacobian and compliance (eqs 34-43);
//! * [`experiments`]: Section V, the paper's test problems, shared by tests
//!   and benches.
//!
//! SI units throughout (m, N, Pa, kg), except temperatures, in degrees Celsius.

// `!(x > 0.0)` is deliberate throughout: unlike `x <= 0.0` it is also true for
// NaN, so one comparison rejects non-positive and non-finite values alike.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

// `tcarod::` paths inside the crate too, for benches/rows/mod.rs, which the
// bindings include (`tcarod bench`) and the criterion benches use.
extern crate self as tcarod;

pub mod batch;
pub mod branch;
pub mod error;
pub mod experiments;
pub mod inverse;
pub mod limits;
pub mod material;
pub mod problems;
pub mod rod;
pub mod roots;
pub mod shooting;
pub mod solve;
pub mod stability;
pub mod tca;
/// [`limits`] under the alias `validate` (hidden from the docs).
#[doc(hidden)]
pub use limits as validate;

#[cfg(feature = "python")]
mod python;

pub use error::{Error, Result, StopReason};
pub use material::Material;
/// The linear algebra crate of the public API (vectors, matrices).
pub use nalgebra;
pub use tca::{Chirality, Tca};
