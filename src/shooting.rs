//! The shooting boundary value problem (eqs 32-33): the public names of
//! [`crate::solve::shooting`] at the crate root, `tcarod::shooting`, the
//! path the tests, benches and examples use.

pub use crate::solve::shooting::*;
