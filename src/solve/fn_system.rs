//! A Newton [`System`] from a closure.

use super::newton::System;
use crate::error::Result;

/// A [`System`] from a closure, with the forward-difference Jacobian; counts
/// its evaluations.
pub struct FnSystem<F: FnMut(&[f64]) -> Result<Vec<f64>>> {
    f: F,
    evaluations: usize,
}

impl<F: FnMut(&[f64]) -> Result<Vec<f64>>> FnSystem<F> {
    /// Wrap `f`.
    pub fn new(f: F) -> Self {
        FnSystem { f, evaluations: 0 }
    }
}

impl<F: FnMut(&[f64]) -> Result<Vec<f64>>> System for FnSystem<F> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        self.evaluations += 1;
        (self.f)(x)
    }
    fn evaluations(&self) -> usize {
        self.evaluations
    }
}
