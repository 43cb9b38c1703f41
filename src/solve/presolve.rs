//! Coarse-grid pre-solve with defect correction, the direct Newton run of
//! a forward solve (cold or warm).
//!
//! A plain IVP costs in proportion to its RK4 steps, and the shooting
//! residual of a grid of a tenth of the steps differs from the full grid's
//! by RK4's truncation error only: a *defect* `d(x) = r_full(x) - r_coarse(x)`
//! that is small (Fig. 6, 10 against 100 steps: ~1e-6) and varies slowly
//! with `x`. So:
//!
//! 1. Newton on the coarse grid (its exact tangents, a tenth of the cost)
//!    to `0.1 tol`, from the cold guess or the warm one. Warm, the coarse
//!    system carries the warm solution's defect `-r_coarse(x_warm)` (its
//!    full residual is within `tol` of zero), and the warm Jacobian's
//!    actuator columns are rescaled to the force laws' slopes at the new
//!    inputs ([`rescale_tension_columns`]: the IVP depends on an elongation
//!    only through its tension).
//! 2. One full-grid IVP at that point: converged if `max |r_full| <=
//!    max(tol, floor)` (the same test, on the same grid, as Newton's);
//!    else the defect is updated to `r_full(x) - r_coarse(x)` and step 1
//!    repeated from `x` with the coarse Jacobian (a chord step or two). The
//!    full residual contracts by the defect's variation, about the coarse
//!    grid's error in the Jacobian (Fig. 6: 1.4e-6 to ~1e-10 per round).
//! 3. A failure anywhere (coarse Newton, a full residual that does not
//!    contract tenfold, [`MAX_ROUNDS`] used) falls back on full-grid
//!    Newton (`newton_shooting`) from the best point reached; its work is
//!    counted on top.
//!
//! Every IVP counts as one evaluation, coarse ones included
//! (`Solution.evaluations`); the designs bench's IVP-equivalents are CPU
//! times and so weigh them by their cost.

use nalgebra::DMatrix;

use super::newton::{newton_from, NewtonOptions, NewtonResult, Status, System};
use super::options::SolveOptions;
use super::residual::{tension_slope, Loads, Shot};
use super::system::{newton_shooting, FinalIvp, Shooting, Work, COARSE_JACOBIAN_MIN_STEPS};
use crate::error::{Error, Result};
use crate::rod::Robot;

/// Defect-correction rounds (full-grid IVPs) before falling back on
/// full-grid Newton.
pub const MAX_ROUNDS: usize = 4;

/// Largest full-grid residual of a pre-solve's point from which the
/// fallback's Newton starts (farther: from the guess, as without pre-solve).
const FALLBACK_NEAR: f64 = 1e-3;

/// Iteration limit of each coarse Newton run (a cold Fig. 6 solve takes 4;
/// a coarse run that needs more is cut short and the full-grid Newton
/// takes over).
const COARSE_MAX_ITER: usize = 20;

/// The warm start of a pre-solve: the neighbouring solution's unknowns,
/// inputs and Newton Jacobian.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Warm<'a> {
    pub unknowns: &'a [f64],
    pub inputs: &'a [f64],
    pub jacobian: Option<&'a DMatrix<f64>>,
}

/// The coarse shooting residual plus a constant defect `d`.
struct Corrected<'a> {
    sys: Shooting<'a>,
    defect: Vec<f64>,
}

impl System for Corrected<'_> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        let mut r = self.sys.residual(x)?;
        r.iter_mut().zip(&self.defect).for_each(|(a, d)| *a += d);
        Ok(r)
    }
    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let (mut r, j) = self.sys.residual_and_jacobian(x)?;
        r.iter_mut().zip(&self.defect).for_each(|(a, d)| *a += d);
        Ok((r, j))
    }
    fn floor(&self, x: &[f64], r: &[f64]) -> f64 {
        self.sys.floor(x, r)
    }
    fn evaluations(&self) -> usize {
        self.sys.evaluations
    }
    fn refine(&mut self) -> bool {
        self.sys.refine()
    }
    fn limit_step(&self, x: &[f64], dx: &[f64], r: &[f64], jac: &DMatrix<f64>) -> Option<Vec<f64>> {
        self.sys.limit_step(x, dx, r, jac) // the force laws do not depend on the grid
    }
}

/// `jac` (a Jacobian at `x_from`, inputs `from`) with each actuator column
/// rescaled to the tension slope at `x_to`, inputs `to`: column `6 + i` is
/// `(dr/dtau_i) (dtau_i/ddelta_i) L - e_(6+i)`, and `dr/dtau_i` is the
/// IVP's, which does not depend on the inputs. Columns of a slack actuator
/// (zero slope) are kept.
pub fn rescale_tension_columns(
    robot: &Robot,
    jac: &DMatrix<f64>,
    (x_from, from): (&[f64], &[f64]),
    (x_to, to): (&[f64], &[f64]),
) -> DMatrix<f64> {
    let len = robot.body.length;
    let mut j = jac.clone();
    for (i, a) in robot.actuators.iter().enumerate() {
        let c = 6 + i;
        let slope = |x: &[f64], u: &[f64]| {
            tension_slope(a.law.as_ref(), x[c] * len, u[i], len, false).map(|s| s.1)
        };
        let (Ok(s0), Ok(s1)) = (slope(x_from, from), slope(x_to, to)) else {
            continue;
        };
        if s0 == 0.0 || !(s1 / s0).is_finite() || c >= j.ncols() || c >= j.nrows() {
            continue;
        }
        j[(c, c)] += 1.0;
        j.column_mut(c).scale_mut(s1 / s0);
        j[(c, c)] -= 1.0;
    }
    j
}

/// The problem of one pre-solve (see the module docs).
struct PreSolve<'a> {
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: &'a Loads,
    opts: &'a SolveOptions,
    coarse: usize,
}

impl<'a> PreSolve<'a> {
    /// Coarse Newton on `r_coarse + defect` from `x0`; its result and the
    /// coarse IVPs used.
    fn coarse_run(
        &self,
        x0: &[f64],
        defect: Vec<f64>,
        jac0: Option<&DMatrix<f64>>,
        work: &Work,
    ) -> (Result<NewtonResult>, usize) {
        let mut sys = Corrected {
            sys: Shooting::new(self.robot, self.inputs, self.loads, self.coarse, false),
            defect,
        };
        let nopts = NewtonOptions {
            tol: 0.1 * self.opts.tol,
            max_iter: COARSE_MAX_ITER.min(self.opts.max_iter),
            ..work.newton_options(self.opts)
        };
        let out = newton_from(&mut sys, x0, &nopts, "coarse pre-solve", jac0);
        (out, sys.sys.evaluations)
    }
}

/// [`Status::Converged`] if `norm <= tol`, else at the floor.
fn converged_status(norm: f64, tol: f64) -> Status {
    if norm <= tol {
        Status::Converged
    } else {
        Status::ConvergedAtFloor
    }
}

/// The coarse system's initial defect and Jacobian: warm, the warm
/// solution's defect (its full residual is ~0: `-r_coarse(x_warm)`, one
/// coarse IVP) and its Jacobian at the new tension slopes; cold, zero and
/// none.
fn warm_start(
    robot: &Robot,
    loads: &Loads,
    coarse: usize,
    x0: &[f64],
    inputs: &[f64],
    warm: Option<Warm<'_>>,
    work: &mut Work,
) -> (Vec<f64>, Option<DMatrix<f64>>) {
    let mut defect = vec![0.0; x0.len()];
    let Some(w) = warm else {
        return (defect, None);
    };
    work.evaluations += 1;
    if let Ok((rw, _, _)) = Shot::new(robot, w.inputs, loads, coarse).residual(w.unknowns, false) {
        defect = rw.iter().map(|r| -r).collect();
    }
    let jac = w
        .jacobian
        .map(|j| rescale_tension_columns(robot, j, (w.unknowns, w.inputs), (x0, inputs)));
    (defect, jac)
}

/// The direct Newton run of a forward solve with the coarse-grid pre-solve
/// (see the module docs); the same contract as [`newton_shooting`], which it
/// falls back on (and which it is when `opts.steps` is below ten times
/// [`COARSE_JACOBIAN_MIN_STEPS`]).
#[allow(clippy::too_many_arguments)] // the shooting problem's parts, as newton_shooting's
pub(crate) fn presolved_shooting(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    warm: Option<Warm<'_>>,
    record: super::system::Keep,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    let jac0 = warm.and_then(|w| w.jacobian);
    let coarse = opts.steps / 10;
    if coarse < COARSE_JACOBIAN_MIN_STEPS || !opts.presolve {
        return newton_shooting(robot, inputs, loads, opts, x0, jac0, record, work);
    }
    let pre = PreSolve {
        robot,
        inputs,
        loads,
        opts,
        coarse,
    };
    let (mut defect, mut jac) = warm_start(robot, loads, coarse, x0, inputs, warm, work);
    let mut full = Shooting::new(robot, inputs, loads, opts.steps, record);
    let mut x = x0.to_vec();
    let mut iterations = 0;
    let mut last_norm = f64::INFINITY;
    for _ in 0..MAX_ROUNDS {
        let (out, evals) = pre.coarse_run(&x, defect.clone(), jac.as_ref(), work);
        work.evaluations += evals;
        let Some(nr) = unless_interrupted(out)? else {
            break;
        };
        iterations += nr.iterations;
        x = nr.x;
        jac = nr.jacobian.or(jac);
        let Some(r) = unless_interrupted(full.residual(&x))? else {
            break;
        };
        let norm = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let floor = full.floor(&x, &r);
        if norm <= opts.tol.max(floor) {
            work.evaluations += full.evaluations;
            work.iterations += iterations;
            let last = full.take_last(&x);
            let status = converged_status(norm, opts.tol);
            let nr = NewtonResult {
                x,
                residual: r,
                norm,
                floor,
                status,
                iterations,
                evaluations: work.evaluations,
                jacobian: jac,
            };
            return Ok((nr, last));
        }
        if !(norm <= 0.1 * last_norm) {
            break;
        }
        last_norm = norm;
        // the new defect: r_full(x) - r_coarse(x), r_coarse(x) = nr.residual - defect
        for ((d, rf), rc) in defect.iter_mut().zip(&r).zip(&nr.residual) {
            *d += rf - rc;
        }
    }
    // fall back on full-grid Newton: from the last point if it came near
    // (it is then as good a start as any), else from the guess
    work.evaluations += full.evaluations;
    work.iterations += iterations;
    if last_norm <= FALLBACK_NEAR {
        newton_shooting(robot, inputs, loads, opts, &x, jac.as_ref(), record, work)
    } else {
        newton_shooting(robot, inputs, loads, opts, x0, jac0, record, work)
    }
}

/// `Ok(Some(value))`, `Ok(None)` for an error the pre-solve falls back from,
/// or the error if it is an interrupt (which ends the solve).
fn unless_interrupted<T>(r: Result<T>) -> Result<Option<T>> {
    match r {
        Ok(v) => Ok(Some(v)),
        Err(e @ Error::Interrupted) => Err(e),
        Err(_) => Ok(None),
    }
}
