//! The steps of a Newton run ([`super::newton`]): the direction with its
//! descent check, the chord step with a kept Jacobian, Armijo backtracking,
//! and the slow-contraction count that refines the Jacobian.

use nalgebra::{DMatrix, DVector};

use super::{
    inf_norm, merit, Run, Step, System, SLOW_CONTRACTION, SLOW_STEPS_BEFORE_REFINE,
    WATCHDOG_COOLDOWN, WATCHDOG_MIN_STEP,
};
use crate::error::{Error, Result, StopReason};

impl<S: System> Run<'_, S> {
    /// The Newton direction for `jac` (steepest descent scaled to the
    /// Gauss-Newton length where it is not a descent direction), its slope
    /// `grad phi . dx`; `None`: singular or not descending with a kept Jacobian.
    pub(super) fn direction(&self, jac: &DMatrix<f64>) -> Result<Option<(DVector<f64>, f64)>> {
        let rv = DVector::from_column_slice(&self.r);
        let (m, n) = jac.shape();
        let dx = if m == n {
            jac.clone().lu().solve(&(-&rv))
        } else {
            jac.clone().svd(true, true).solve(&(-&rv), 1e-14).ok()
        };
        let grad = jac.tr_mul(&rv); // grad phi = J^T f
        let dx = match dx {
            Some(d) if d.iter().all(|v| v.is_finite()) => d,
            _ if !self.fresh => return Ok(None),
            _ => return Err(self.fail(StopReason::SingularJacobian, "singular Jacobian")),
        };
        let slope = grad.dot(&dx);
        if slope < 0.0 {
            return Ok(Some((dx, slope)));
        }
        if !self.fresh {
            return Ok(None);
        }
        // not a descent direction (inaccurate Jacobian): steepest descent,
        // scaled to the Gauss-Newton step length
        let g2 = grad.norm_squared();
        if !(g2 > 0.0) {
            return Err(self.fail(StopReason::SingularJacobian, "zero gradient of the merit"));
        }
        let jg = jac * &grad;
        let dx = -&grad * (g2 / jg.norm_squared().max(f64::MIN_POSITIVE));
        let slope = grad.dot(&dx);
        Ok(Some((dx, slope)))
    }

    /// Count a full step's contraction; refine the Jacobian after
    /// [`SLOW_STEPS_BEFORE_REFINE`] slow ones in a row.
    fn note_full_step(&mut self, before: f64, after: f64) {
        if after > SLOW_CONTRACTION * before {
            self.slow += 1;
            if self.slow >= SLOW_STEPS_BEFORE_REFINE && self.sys.refine(&self.x) {
                self.jacobian = None;
                self.slow = 0;
            }
        } else {
            self.slow = 0;
        }
    }

    /// A chord step with a kept Jacobian: full length only, and it must
    /// halve `max |f|`.
    pub(super) fn chord_step(&mut self, dx: &DVector<f64>, res: f64) -> Result<Step> {
        let xt: Vec<f64> = self.x.iter().zip(dx.iter()).map(|(a, b)| a + b).collect();
        match self.sys.residual(&xt) {
            Ok(rt) if inf_norm(&rt) <= 0.5 * res => {
                let after = inf_norm(&rt);
                // slow (linear) contraction, or the last iteration next:
                // a fresh Jacobian for the next step
                if after > 0.25 * res || self.iterations + 1 >= self.opts.max_iter {
                    self.jacobian = None;
                }
                self.x = xt;
                self.r = rt;
                self.note_full_step(res, after);
                Ok(Step::Moved)
            }
            Err(Error::Interrupted) => Err(Error::Interrupted),
            _ => {
                self.jacobian = None;
                Ok(Step::Redo)
            }
        }
    }

    /// Armijo backtracking (plain halving) along `dx` from the current point.
    /// `Ok(None)`: converged at the floor after a failed search.
    pub(super) fn line_search(
        &mut self,
        dx: &DVector<f64>,
        slope: f64,
        res: f64,
    ) -> Result<Option<Step>> {
        let phi0 = merit(&self.r);
        let mut t = 1.0;
        loop {
            let xt: Vec<f64> = self
                .x
                .iter()
                .zip(dx.iter())
                .map(|(a, b)| a + t * b)
                .collect();
            let trial = self.sys.residual(&xt);
            let bound = phi0 + 1e-4 * slope;
            if let Err(Error::Interrupted) = trial {
                return Err(Error::Interrupted);
            }
            match trial {
                Ok(rt) => {
                    let phi = merit(&rt);
                    if t == 1.0
                        && phi.is_finite()
                        && phi > bound
                        && self.watchdog(&xt, &rt, bound)?
                    {
                        self.history.push((res, false));
                        return Ok(Some(Step::Moved));
                    }
                    if phi.is_finite() && (phi <= phi0 + 1e-4 * t * slope) {
                        let after = inf_norm(&rt);
                        self.x = xt;
                        self.r = rt;
                        self.history.push((res, t < 1.0));
                        if t < 1.0 {
                            // a damped step: the Jacobian is recomputed at the new point
                            self.jacobian = None;
                            self.slow = 0;
                        } else {
                            self.note_full_step(res, after);
                        }
                        return Ok(Some(Step::Moved));
                    }
                }
                Err(Error::Interrupted) => return Err(Error::Interrupted),
                Err(_) => {}
            }
            // plain halving: the residual is only C1 where a TCA's coils
            // touch, and a quadratic model there shrinks the step too far
            t *= 0.5;
            if t < self.opts.min_step || self.over_budget() {
                if t < self.opts.min_step && self.sys.refine(&self.x) {
                    self.jacobian = None;
                    return Ok(Some(Step::Redo));
                }
                return Ok(None);
            }
        }
    }

    /// Watchdog step (Chamberlain, Powell, Lemarechal and Pedersen, Math.
    /// Prog. Study 16, 1982): the full Newton step to `x1` (residual `r1`)
    /// failed the Armijo test; take it anyway, take one more full Newton
    /// step from `x1` with a fresh Jacobian, and keep the pair if it meets
    /// the Armijo bound `bound` of the first step from the current point.
    /// `Ok(false)`: it did not (the caller backtracks from the current point
    /// as usual). Where a force law's slope jumps between `x` and `x1` (a
    /// tendon going taut or slack, TCA coils touching), the Jacobian at `x`
    /// misjudges the step, and backtracking creeps along the kink with steps
    /// of about `1e-6` of the Newton step, for tens of iterations; the
    /// Jacobian at `x1` has the slope of the side the root lies on.
    /// Off after a failed attempt for [`WATCHDOG_COOLDOWN`] iterations, on
    /// non-square systems, for the last iteration, and in a run that takes
    /// full steps only ([`WATCHDOG_MIN_STEP`]).
    fn watchdog(&mut self, x1: &[f64], r1: &[f64], bound: f64) -> Result<bool> {
        if self.cooldown > 0
            || self.opts.min_step > WATCHDOG_MIN_STEP
            || self.iterations + 1 >= self.opts.max_iter
            || x1.len() != r1.len()
            || self.over_budget()
        {
            return Ok(false);
        }
        let jac = match self.sys.residual_and_jacobian(x1) {
            Ok((_, j)) => j,
            Err(Error::Interrupted) => return Err(Error::Interrupted),
            Err(_) => return Ok(self.watchdog_failed()),
        };
        let rv = DVector::from_column_slice(r1);
        let d = match jac.lu().solve(&(-&rv)) {
            Some(d) if d.iter().all(|v| v.is_finite()) => d,
            _ => return Ok(self.watchdog_failed()),
        };
        let x2: Vec<f64> = x1.iter().zip(d.iter()).map(|(a, b)| a + b).collect();
        match self.sys.residual(&x2) {
            Ok(r2) if merit(&r2) <= bound => {
                self.x = x2;
                self.r = r2;
                self.iterations += 1;
                self.jacobian = None;
                self.slow = 0;
                Ok(true)
            }
            Err(Error::Interrupted) => Err(Error::Interrupted),
            _ => Ok(self.watchdog_failed()),
        }
    }

    fn watchdog_failed(&mut self) -> bool {
        self.cooldown = WATCHDOG_COOLDOWN;
        false
    }
}
