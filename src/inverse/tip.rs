//! The tip-position inverse (eqs 34-38): damped least squares on `J`.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

use super::{rotation_vector, sensitivities_exact, Groups};
use crate::error::{significant, Error, Result};
use crate::rod::Robot;
use crate::shooting::{solve_loaded, Loads, Solution, SolveOptions};

/// Outcome of [`tip_position_inverse`].
#[derive(Debug, Clone)]
pub struct InverseResult {
    /// Final forward solution (the closest reachable one if not `reached`).
    pub solution: Solution,
    /// Final actuation variables, and which of them rest on a bound at the end.
    pub variables: Vec<f64>,
    pub at_bound: Vec<bool>,
    /// Distance \[m\] from the target (and angle \[rad\] if orientation
    /// was asked), and whether it is within the tolerance.
    pub error: f64,
    pub reached: bool,
    /// Iterations (Jacobian evaluations) and IVPs integrated in total.
    pub iterations: usize,
    pub evaluations: usize,
    /// Why the iteration ended.
    pub status: InverseStatus,
}

/// Why [`tip_position_inverse`] ended (the codes are SciPy-style status
/// codes, [`InverseStatus::code`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InverseStatus {
    /// `0`: the tip is within `tol` of the target.
    Reached,
    /// `1`: no descent left with a variable on a bound: the closest point
    /// within the inputs' range.
    Unreachable,
    /// `2`: `max_iter` iterations used while the error still decreased.
    BudgetExhausted,
    /// `3`: the error stopped decreasing with no variable on a bound: the
    /// target lies off the set the tip reaches near the closest point (the
    /// error is orthogonal to every direction the actuators move the tip,
    /// `J^T e = 0`, e.g. off the bending plane of a planar robot), or a
    /// local minimum of the distance.
    Stalled,
}

impl InverseStatus {
    /// The SciPy-style status code: 0 reached, 1 unreachable, 2 out of budget, 3 stalled.
    pub fn code(self) -> i64 {
        match self {
            InverseStatus::Reached => 0,
            InverseStatus::Unreachable => 1,
            InverseStatus::BudgetExhausted => 2,
            InverseStatus::Stalled => 3,
        }
    }
}

impl InverseStatus {
    /// The status of an ended iteration from its outcome: the target
    /// `reached`, the iteration budget `exhausted` while the error still
    /// decreased, else unreachable if a variable rests on a bound
    /// (`at_bound`), stalled if none does.
    pub fn of(reached: bool, exhausted: bool, at_bound: &[bool]) -> Self {
        if reached {
            InverseStatus::Reached
        } else if exhausted {
            InverseStatus::BudgetExhausted
        } else if at_bound.iter().any(|b| *b) {
            InverseStatus::Unreachable
        } else {
            InverseStatus::Stalled
        }
    }

    /// The status in words, with the closest tip point `tip` \[m\] and the
    /// remaining distance `error` \[m\] when the target was not reached
    /// (`at_bound`: which variables rest on a bound; `max_iter`: the budget).
    pub fn message(
        self,
        tip: &Vector3<f64>,
        error: f64,
        at_bound: &[bool],
        max_iter: usize,
    ) -> String {
        let at = format!(
            "closest tip point found [{}, {}, {}] m, {} m from the target",
            significant(tip.x),
            significant(tip.y),
            significant(tip.z),
            significant(error)
        );
        let bound: Vec<usize> = (0..at_bound.len()).filter(|&k| at_bound[k]).collect();
        match self {
            InverseStatus::Reached => format!("target reached: error {error:.3e} m"),
            InverseStatus::Unreachable => format!(
                "target unreachable within the inputs' range: {at}, variables {bound:?} at their bounds"
            ),
            InverseStatus::BudgetExhausted => format!(
                "iteration budget exhausted (max_iter = {max_iter}) while the error still decreased: {at}; continue with start=result.variables or a larger max_iter"
            ),
            InverseStatus::Stalled => format!(
                "stalled: the error stopped decreasing with no variable at a bound (the target is off the set the tip reaches near this point, or a local minimum): {at}"
            ),
        }
    }
}

impl InverseResult {
    /// Why the iteration ended, in words ([`InverseStatus::message`]).
    pub fn message(&self, max_iter: usize) -> String {
        let tip = self.solution.tip_position();
        self.status
            .message(&tip, self.error, &self.at_bound, max_iter)
    }
}

/// Stall test of [`tip_position_inverse`]: over the last `STALL_WINDOW`
/// iterations the error fell by less than `STALL_DECREASE` of itself
/// (quadratically converging Gauss-Newton steps cut it by orders of
/// magnitude per iteration; creeping 1e-9 steps along a null direction do
/// not).
const STALL_WINDOW: usize = 5;
const STALL_DECREASE: f64 = 1e-6;

/// Stationarity test: the linearised step `J dz` can reduce the error by
/// less than this fraction of it (the error is orthogonal to the range of
/// `J` to this accuracy: the tip cannot move toward the target).
const STATIONARY: f64 = 1e-10;

/// Options of the inverse solvers.
#[derive(Debug, Clone, Copy)]
pub struct InverseOptions {
    /// Forward solver options.
    pub forward: SolveOptions,
    /// Position tolerance \[m\].
    pub tol: f64,
    /// Iteration limit.
    pub max_iter: usize,
    /// Damping `lambda` [m per unit variable] of the damped least squares.
    pub damping: f64,
}

impl Default for InverseOptions {
    fn default() -> Self {
        InverseOptions {
            forward: SolveOptions::default(),
            tol: 1e-7,
            max_iter: 50,
            damping: 1e-6,
        }
    }
}

/// Reach a target tip position `target` \[m\] (and orientation: rotation matrix
/// `target_rotation`, weighted by `orientation_weight` \[m/rad\]) by iterating
/// the local inverse `dz = J^+ dx` (damped least squares) with variables kept
/// within their bounds (ambient to the material's limit for TCAs).
///
/// An unreachable target ends at the closest configuration found with
/// `reached = false` and its [`InverseStatus`], not with an error: the
/// iteration stops as soon as the local inverse can no longer get closer
/// (a linearised decrease below `1e-10` of the error, or less than `1e-6`
/// of it over 5 iterations), e.g. within a few iterations for a target off
/// the bending plane of a planar robot. Actuators with fixed inputs in
/// `groups` keep them.
#[allow(clippy::too_many_arguments)]
pub fn tip_position_inverse(
    robot: &Robot,
    groups: &Groups,
    target: &Vector3<f64>,
    target_rotation: Option<(&Matrix3<f64>, f64)>,
    z_start: &[f64],
    opts: &InverseOptions,
) -> Result<InverseResult> {
    check_target(robot, groups, target, target_rotation, z_start)?;
    let nz = groups.n_vars();
    let bounds = groups.bounds(robot);
    let mut z: Vec<f64> = z_start
        .iter()
        .zip(&bounds)
        .map(|(v, (lo, hi))| v.clamp(*lo, *hi))
        .collect();
    let loads = Loads::of(robot);
    let mut sol = solve_loaded(robot, &groups.inputs(&z), &loads, &opts.forward, None)?;
    let mut evals = sol.evaluations;
    let rows = if target_rotation.is_some() { 6 } else { 3 };
    let err_vec = |s: &Solution| -> DVector<f64> {
        let dp = target - s.tip_position();
        let mut e = DVector::zeros(rows);
        e.rows_mut(0, 3).copy_from(&dp);
        if let Some((rt, w)) = target_rotation {
            let th = rotation_vector(&(rt * s.tip_rotation().transpose()));
            e.rows_mut(3, 3).copy_from(&(th * w));
        }
        e
    };
    let mut err = err_vec(&sol);
    let mut best = (err.norm(), sol.clone(), z.clone());
    let mut iterations = 0;
    let mut history = vec![err.norm()];
    let mut stopped = false; // no descent left (stationary, stalled or no step accepted)
    while err.norm() > opts.tol && iterations < opts.max_iter {
        iterations += 1;
        let sens = sensitivities_exact(robot, &sol, &loads, groups, opts.forward.steps)?;
        evals += sens.evaluations;
        let jr = weighted_rows(&sens.jacobian, rows, target_rotation.map(|(_, w)| w));
        let dz = bounded_step(&jr, &err, &z, &bounds, opts.damping);
        // predicted decrease of the linearised error |e| - |e - J dz|:
        // below STATIONARY |e|, no step of the local inverse gets closer
        let predicted = err.norm() - (&err - &jr * &dz).norm();
        if !(predicted > STATIONARY * err.norm()) {
            stopped = true;
            break;
        }
        // backtrack on the tip error, clamping to bounds
        let mut t = 1.0;
        let mut accepted = false;
        while t > 1e-4 {
            let zt: Vec<f64> = (0..nz)
                .map(|k| (z[k] + t * dz[k]).clamp(bounds[k].0, bounds[k].1))
                .collect();
            let inputs = groups.inputs(&zt);
            if let Ok(st) = solve_loaded(robot, &inputs, &loads, &opts.forward, Some(&sol)) {
                evals += st.evaluations;
                let et = err_vec(&st);
                if et.norm() < err.norm() {
                    (z, sol, err, accepted) = (zt, st, et, true);
                    break;
                }
            }
            t *= 0.5;
        }
        if err.norm() < best.0 {
            best = (err.norm(), sol.clone(), z.clone());
        }
        history.push(err.norm());
        let window = history.len() > STALL_WINDOW
            && history[history.len() - 1 - STALL_WINDOW] - err.norm() < STALL_DECREASE * err.norm();
        if !accepted || (window && err.norm() > opts.tol) {
            stopped = true; // no descent: closest reachable configuration
            break;
        }
    }
    let (e, s, zb) = best;
    let at_bound: Vec<bool> = zb
        .iter()
        .zip(&bounds)
        .map(|(v, (lo, hi))| *v <= *lo || *v >= *hi)
        .collect();
    let status = InverseStatus::of(e <= opts.tol, !stopped, &at_bound);
    Ok(InverseResult {
        solution: s,
        variables: zb,
        error: e,
        iterations,
        reached: e <= opts.tol,
        at_bound,
        evaluations: evals,
        status,
    })
}

/// A finite target and one start value per actuation variable.
fn check_target(
    robot: &Robot,
    groups: &Groups,
    target: &Vector3<f64>,
    target_rotation: Option<(&Matrix3<f64>, f64)>,
    z_start: &[f64],
) -> Result<()> {
    groups.validate(robot)?;
    if let Some((_, w)) = target_rotation {
        crate::error::positive("orientation_weight [m/rad]", w)?;
    }
    for (k, v) in target.iter().enumerate() {
        crate::error::finite(&format!("target[{k}] [m]"), *v)?;
    }
    let reach = 1e3 * robot.body.length; // far beyond any reachable tip; keeps the error finite
    if target.amax() > reach {
        let allowed = format!("coordinates within {reach} m (1000 body lengths)");
        return Err(Error::param("target [m]", target.amax(), allowed));
    }
    let nz = groups.n_vars();
    if z_start.len() != nz {
        return Err(Error::input(
            "start",
            format!("expected {nz} variables, got {}", z_start.len()),
        ));
    }
    Ok(())
}

/// Damped least-squares step `dz = (J^T J + lambda^2 I)^-1 J^T e` on the
/// free variables: a variable on a bound whose step would push past it is
/// frozen and the step recomputed without it.
fn bounded_step(
    jr: &DMatrix<f64>,
    err: &DVector<f64>,
    z: &[f64],
    bounds: &[(f64, f64)],
    damping: f64,
) -> DVector<f64> {
    let (rows, nz) = (jr.nrows(), jr.ncols());
    let mut free: Vec<bool> = vec![true; nz];
    let mut dz = DVector::zeros(nz);
    for _ in 0..=nz {
        let cols: Vec<usize> = (0..nz).filter(|&k| free[k]).collect();
        if cols.is_empty() {
            break;
        }
        let jf = DMatrix::from_fn(rows, cols.len(), |r, c| jr[(r, cols[c])]);
        let lam2 = damping * damping;
        let a = jf.transpose() * &jf + DMatrix::identity(cols.len(), cols.len()) * lam2;
        let step = a
            .lu()
            .solve(&(jf.transpose() * err))
            .unwrap_or_else(|| DVector::zeros(cols.len()));
        dz = DVector::zeros(nz);
        for (c, &k) in cols.iter().enumerate() {
            dz[k] = step[c];
        }
        let mut changed = false;
        for k in 0..nz {
            let (lo, hi) = bounds[k];
            if free[k] && ((z[k] <= lo && dz[k] < 0.0) || (z[k] >= hi && dz[k] > 0.0)) {
                free[k] = false;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    dz
}

/// The first `rows` rows of J, the rotation rows (3..6) weighted by `w` (the
/// weight of the orientation error, as in the tip error).
fn weighted_rows(jacobian: &DMatrix<f64>, rows: usize, w: Option<f64>) -> DMatrix<f64> {
    let mut jr = jacobian.rows(0, rows).into_owned();
    if let Some(w) = w {
        for c in 0..jr.ncols() {
            for r in 3..rows {
                jr[(r, c)] *= w;
            }
        }
    }
    jr
}
