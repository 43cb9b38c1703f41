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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::{table1_finger, table1_grasp, TABLE1_MASSES};
    use crate::inverse::blocked::{direct_from, variable_scale};
    use crate::inverse::mixed::{coarse_steps, predictor, Extra};
    use crate::inverse::{Block, GraspMethod, Groups};
    use crate::shooting::{solve_loaded, Loads, SolveOptions};
    use crate::stability::Policy;

    /// The pre-solve's hand-over when a round does not cut the full grid's
    /// residual tenfold. A coarse grid's defect varies too little for that
    /// on the Table I finger (one RK4 step still contracts ~100x a round),
    /// so the stand-in "coarse" system here is the finger with half its
    /// body stiffness: its defect changes with the unknowns about as fast
    /// as the residual itself, the rounds stall (ratio ~0.5), and the
    /// full-grid Newton takes over from the best point. It still ends at
    /// the default path's grasp temperature, and the extra work is counted.
    #[test]
    fn a_round_without_tenfold_contraction_hands_over_to_the_full_grid() {
        let finger = table1_finger();
        let mut soft = finger.clone();
        soft.body.youngs_modulus *= 0.5;
        soft.body.shear_modulus *= 0.5;
        let groups = Groups(vec![0, 0]);
        let opts = SolveOptions::default();
        let spec = table1_grasp(TABLE1_MASSES[0], Policy::Off);
        let force = spec.force_per_finger().unwrap();
        let inputs = finger.reference_inputs();
        let start = solve_loaded(&finger, &inputs, &Loads::of(&finger), &opts, None).unwrap();
        let block = Block::new(start.tip_position(), spec.normal).unwrap();
        let extra = Extra::Variable {
            force,
            scale: variable_scale(&finger, &groups),
        };
        let steps = coarse_steps(opts.steps).unwrap();
        let mut full = Mixed::new(&finger, &groups, &block, extra.clone(), opts.steps);
        let mut coarse = Mixed::new(&soft, &groups, &block, extra, steps);
        let (x0, jac0) = predictor(&mut full, &start, groups.vars(&start.inputs)[0]).unwrap();
        let pre = presolve(&mut full, &mut coarse, &x0, jac0.clone(), &opts.newton());
        // handed over short of the tolerance (here the rounds reach max |r|
        // 0.53, 0.038, then 0.0084, not a tenth of 0.038: the hand-over is at
        // 0.038; the first round is always taken, here from a predictor at
        // 0.027)
        let handed = inf_norm(&full.residual(&pre.x).unwrap());
        assert!(
            handed > 1e3 * opts.tol,
            "the stand-in converged: {handed:e}"
        );
        assert!(pre.iterations > 0);

        // the full-grid Newton finishes from there: the same temperature as
        // the default path. Both hold the tip on the block to 1e-10 L, and
        // the tip moves ~2e-5 m per C along the normal
        // (tests/integration/inverse.rs), so the temperatures agree far
        // inside 1e-6 C.
        let nr = newton_from(
            &mut full,
            &pre.x,
            &opts.newton(),
            "test",
            Some(&pre.jacobian),
        );
        let t = full.problem(&nr.unwrap().x).unwrap().0[0];
        let (default, _) = spec
            .solve(&finger, &groups, GraspMethod::Direct, &opts)
            .unwrap();
        let dt = (t - default.variables[0]).abs();
        assert!(dt < 1e-6, "{t} vs {} C", default.variables[0]);
        // without a pre-solve at all the same answer, by the same Newton
        let bare = direct_from(&finger, &groups, &block, &start, force, &opts, None).unwrap();
        assert!((bare.variables[0] - default.variables[0]).abs() < 1e-6);
    }
}
