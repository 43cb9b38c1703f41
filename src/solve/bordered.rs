//! The multiple-shooting Jacobian `A = G_x` bordered by one column `g` and
//! one row `(r, r_l)`,
//!
//! `[[A, g], [r^T, r_l]] (dx, dl) = (b, c)`,
//!
//! the linear system of a continuation step (`g = G_lambda`, `r` the
//! tangent) and of a blocked tip (`r` the gradient of the tip's gap). It is
//! solved by block elimination with `A`'s staircase LU
//! ([`super::abd::Staircase`]) and one step of iterative refinement on the
//! whole bordered system, which makes it accurate also where `A` is nearly
//! singular, at a fold (Govaerts & Pryce, "Block elimination with one
//! refinement solves bordered linear systems accurately", BIT 30, 1990;
//! Govaerts, *Numerical Methods for Bifurcations of Dynamical Equilibria*,
//! SIAM 2000, sec. 3.3).

use super::abd::Staircase;
use super::ms::MultipleShooting;
use crate::error::Result;

/// `A`'s factorisation with its border (see the module docs).
#[derive(Debug, Clone, Default)]
pub struct Bordered {
    lu: Option<Staircase>,
    singular: bool,
    g: Vec<f64>,
    a_inv_g: Vec<f64>,
    row: (Vec<f64>, f64),
}

impl Bordered {
    /// Factorise the Jacobian of `ms`'s last linearisation as `A`, in the
    /// storage of the last factorisation where its shape is the same.
    pub fn factorise(&mut self, ms: &MultipleShooting<'_>) -> Result<()> {
        let lu = match self.lu.take() {
            Some(lu) if lu.shape().rows == ms.rows() && lu.shape().cols == ms.cols() => lu,
            _ => ms.staircase()?,
        };
        self.singular = ms.factorise(self.lu.insert(lu));
        Ok(())
    }

    /// `det A` from the staircase factors ([`Staircase::determinant`]);
    /// `None` before a factorisation, or where `A` is singular.
    pub fn determinant(&self) -> Option<f64> {
        match self.singular {
            true => None,
            false => self.lu.as_ref().and_then(Staircase::determinant),
        }
    }

    /// Border the factorised `A` with the column `g` and the row `row`.
    pub fn border(&mut self, g: Vec<f64>, row: (&[f64], f64)) -> Result<()> {
        self.set_row(row);
        self.a_inv_g = g.clone();
        self.g = g;
        if !self.singular {
            let mut v = std::mem::take(&mut self.a_inv_g);
            self.solve_a(&mut v)?;
            self.a_inv_g = v;
        }
        Ok(())
    }

    /// Replace the border's row.
    pub fn set_row(&mut self, row: (&[f64], f64)) {
        self.row = (row.0.to_vec(), row.1);
    }

    /// The border's row `(r, r_l)`.
    pub fn row(&self) -> (&[f64], f64) {
        (&self.row.0, self.row.1)
    }

    /// `(dx, dl)` for the right-hand side `(b, c)`: block elimination and
    /// one step of iterative refinement; `Ok(false)` if `A` is singular or
    /// the solution is not finite.
    pub fn solve(&self, b: &[f64], c: f64, dx: &mut [f64], dl: &mut f64) -> Result<bool> {
        if self.singular {
            return Ok(false);
        }
        let d0 = self.eliminate(b, c, dx)?;
        // the residual of the bordered system at (dx, d0)
        let n = dx.len();
        let mut ax = vec![0.0; n];
        if let Some(lu) = &self.lu {
            lu.mul(dx, &mut ax)?;
        }
        let rb: Vec<f64> = (0..n).map(|i| b[i] - ax[i] - self.g[i] * d0).collect();
        let rc = c - self.dot(dx) - self.row.1 * d0;
        let mut cx = vec![0.0; n];
        let d1 = self.eliminate(&rb, rc, &mut cx)?;
        for (d, c) in dx.iter_mut().zip(&cx) {
            *d += c;
        }
        *dl = d0 + d1;
        Ok(dx.iter().all(|v| v.is_finite()) && dl.is_finite())
    }

    /// `r . u`.
    fn dot(&self, u: &[f64]) -> f64 {
        u.iter().zip(&self.row.0).map(|(p, q)| p * q).sum()
    }

    /// Solve `A dx = b` in place with the factorisation.
    fn solve_a(&self, b: &mut [f64]) -> Result<()> {
        match &self.lu {
            Some(lu) => lu.solve(b),
            None => Ok(()),
        }
    }

    /// One block elimination of the bordered system for `(b, c)`.
    fn eliminate(&self, b: &[f64], c: f64, dx: &mut [f64]) -> Result<f64> {
        dx.copy_from_slice(b);
        self.solve_a(dx)?;
        let dl = (c - self.dot(dx)) / (self.row.1 - self.dot(&self.a_inv_g));
        for (d, v) in dx.iter_mut().zip(&self.a_inv_g) {
            *d -= dl * v;
        }
        Ok(dl)
    }
}
