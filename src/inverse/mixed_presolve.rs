//! Coarse-grid pre-solve with defect correction for the mixed (blocked-tip)
//! system, as the forward solve's ([`crate::solve::presolve`]): Newton on
//! the augmented system on the Jacobian's coarse grid (a tenth of the RK4
//! steps), its residual shifted by the defect `d = r_full - r_coarse` of the
//! last full-grid IVP, then one full-grid IVP at its root, repeated while
//! that full-grid residual contracts tenfold (at most [`MAX_ROUNDS`]). The
//! full-grid Newton then starts from the best point with its full residual
//! already known, so a converged round costs no further IVP.
//!
//! Why: on the Table I grasp the full-grid chord steps from the predictor
//! contract only 8-56x each (the kept Jacobian is the predictor's, taken at
//! the free solution), so 7 full IVPs follow the predictor. The same chord
//! steps on the coarse grid cost a tenth each; the full grid's residual
//! differs from the coarse one by RK4's truncation error, a defect that
//! varies slowly with the unknowns.

use nalgebra::DMatrix;

use super::mixed::Mixed;
use crate::solve::newton::{newton_from, NewtonOptions, System};

/// Full-grid IVPs (defect updates) of a pre-solve.
pub(crate) const MAX_ROUNDS: usize = 3;

/// Iteration limit of each coarse Newton run.
const COARSE_MAX_ITER: usize = 20;

/// A coarse [`Mixed`] system with its residual shifted by a defect.
struct Defected<'s, 'a> {
    inner: &'s mut Mixed<'a>,
    defect: Vec<f64>,
}

impl Defected<'_, '_> {
    fn shift(&self, mut r: Vec<f64>) -> Vec<f64> {
        r.iter_mut().zip(&self.defect).for_each(|(a, d)| *a += d);
        r
    }
}

impl System for Defected<'_, '_> {
    fn residual(&mut self, x: &[f64]) -> crate::error::Result<Vec<f64>> {
        let r = self.inner.residual(x)?;
        Ok(self.shift(r))
    }
    fn residual_and_jacobian(
        &mut self,
        x: &[f64],
    ) -> crate::error::Result<(Vec<f64>, DMatrix<f64>)> {
        let (r, j) = self.inner.residual_and_jacobian(x)?;
        Ok((self.shift(r), j))
    }
    fn floor(&self, x: &[f64], r: &[f64]) -> f64 {
        self.inner.floor(x, r)
    }
    fn evaluations(&self) -> usize {
        self.inner.evaluations
    }
}

/// Where the full-grid Newton starts: the point, the Jacobian and the
/// coarse Newton iterations spent.
pub(crate) struct Presolved {
    pub x: Vec<f64>,
    pub jacobian: DMatrix<f64>,
    pub iterations: usize,
}

fn inf_norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The pre-solve (see the module docs) of `full` from `x0` with the
/// Jacobian `jac0` on `coarse`'s grid; `full`'s residual at the returned
/// point is primed ([`Mixed::prime`]) when one was taken there. Any failure
/// ends the rounds: the full-grid Newton takes over from the best point.
pub(crate) fn presolve(
    full: &mut Mixed<'_>,
    coarse: &mut Mixed<'_>,
    x0: &[f64],
    jac0: DMatrix<f64>,
    opts: &NewtonOptions,
) -> Presolved {
    let copts = NewtonOptions {
        tol: 0.1 * opts.tol,
        max_iter: COARSE_MAX_ITER,
        ..*opts
    };
    let mut best = Presolved {
        x: x0.to_vec(),
        jacobian: jac0,
        iterations: 0,
    };
    let (mut x, mut defect) = (x0.to_vec(), vec![0.0; x0.len()]);
    let mut primed: Option<Vec<f64>> = None;
    let mut last = f64::INFINITY;
    for _ in 0..MAX_ROUNDS {
        let mut sys = Defected {
            inner: coarse,
            defect: defect.clone(),
        };
        let Ok(nr) = newton_from(
            &mut sys,
            &x,
            &copts,
            "coarse blocked-tip shooting",
            Some(&best.jacobian),
        ) else {
            break;
        };
        best.iterations += nr.iterations;
        let jac = nr.jacobian.unwrap_or_else(|| best.jacobian.clone());
        let Ok(rf) = full.residual(&nr.x) else {
            break;
        };
        let norm = inf_norm(&rf);
        if !(norm < 0.1 * last) {
            break; // no tenfold contraction: the full grid takes over from the last best
        }
        last = norm;
        // the defect at the new point: r_full - r_coarse (without the old defect)
        for ((d, f), c) in defect.iter_mut().zip(&rf).zip(&nr.residual) {
            *d = f - (c - *d);
        }
        (x, best.x, best.jacobian) = (nr.x.clone(), nr.x, jac);
        primed = Some(rf);
        if norm
            <= opts
                .tol
                .max(full.floor(&x, primed.as_deref().unwrap_or(&[])))
        {
            break;
        }
    }
    if let Some(r) = primed {
        full.prime(&best.x, r);
    }
    best
}
