//! The global equilibrium check of a converged solution (derived in the
//! [`crate::problems`] module docs), and the accuracy control built on it
//! ([`SolveOptions::equilibrium_tol`]).

use nalgebra::Vector3;

use super::cancel;
use super::options::SolveOptions;
use super::shooting::solve_loaded;
use crate::error::{Error, Result, StopReason};
use crate::limits::MAX_STEPS;
use crate::rod::Robot;
use crate::shooting::Solution;

/// Result of [`equilibrium`]: base wrench against external loads.
#[derive(Debug, Clone, Copy)]
pub struct Equilibrium {
    /// Base force (body plus actuators anchored at the base) minus the
    /// external loads \[N\], world frame.
    pub force_error: Vector3<f64>,
    /// Base moment about the base origin minus the external loads' [N m].
    pub moment_error: Vector3<f64>,
    /// Force scale \[N\]: the largest of the external load, the tip force,
    /// the actuator tensions and the internal force along the body.
    pub force_scale: f64,
    /// Moment scale [N m]: the largest of the external moments, the force
    /// scale times the body length and the internal moment along the body.
    pub moment_scale: f64,
    /// `max(|force_error| / force_scale, |moment_error| / moment_scale)`.
    pub relative: f64,
    /// Relative difference between `Solution.base_force`/`base_moment` and
    /// the base wrench recomputed here (a consistency check of `Solution`).
    pub solution_mismatch: f64,
}

/// Relative tolerance of the global equilibrium check that the benchmark
/// (`benches/designs.rs`) reports against.
pub const EQUILIBRIUM_TOL: f64 = 1e-8;

/// Global equilibrium of a converged solution `sol` of `robot` (see the
/// module docs). The external loads are the body's distributed loads
/// (gravity, `distributed_force`, `distributed_moment`) and the tip loads the
/// solution is for (`sol.loads`). `int p ds` is integrated from the nodes'
/// positions and tangents `p' = R nu` by the end-corrected trapezoid rule
/// (error `O(h^4)`); on an interval ending at an anchor, where `nu` jumps and
/// only the post-jump tangent is recorded, by the cubic through the two
/// previous nodes, the tangent at the interval's start and the end position.
pub fn equilibrium(robot: &Robot, sol: &Solution) -> Equilibrium {
    let body = &robot.body;
    let len = body.length;
    let tol = 1e-12 * len;
    // base wrench: body cross-section plus actuators anchored at the base
    let r0 = sol.rotations[0];
    let p0 = sol.positions[0];
    let mut bf = sol.internal_force[0];
    let mut bm = sol.internal_moment[0] + p0.cross(&bf);
    let mut scale_f = bf.norm();
    for (i, a) in robot.actuators.iter().enumerate() {
        let tau = sol.tensions[i];
        scale_f = scale_f.max(tau.abs());
        if a.s_start <= tol {
            let (ri, rp, _) = a.routing.eval(0.0);
            let pb = sol.nu[0] + sol.omega[0].cross(&ri) + rp;
            let t = r0 * pb / pb.norm();
            bf += t * tau;
            bm += (p0 + r0 * ri).cross(&(t * tau));
        }
    }
    // external loads
    let fd = body.distributed_load();
    let ld = body.distributed_moment;
    let tip_p = sol.tip_position();
    let (tf, tm) = (sol.loads.tip_force, sol.loads.tip_moment);
    let pint = position_integral(robot, sol);
    let wf = fd * len + tf;
    let wm = pint.cross(&fd) + ld * len + tip_p.cross(&tf) + tm;
    scale_f = scale_f.max((fd * len).norm()).max(tf.norm());
    let mut scale_m = (ld * len)
        .norm()
        .max(tm.norm())
        .max(scale_f * len)
        .max((pint.cross(&fd)).norm());
    for (n, m) in sol.internal_force.iter().zip(&sol.internal_moment) {
        scale_f = scale_f.max(n.norm());
        scale_m = scale_m.max(m.norm());
    }
    scale_m = scale_m.max(scale_f * len);
    let ef = bf - wf;
    let em = bm - wm;
    let rel = |x: f64, s: f64| if s > 0.0 { x / s } else { x };
    let relative = rel(ef.norm(), scale_f).max(rel(em.norm(), scale_m));
    let solution_mismatch =
        rel((sol.base_force - bf).norm(), scale_f).max(rel((sol.base_moment - bm).norm(), scale_m));
    Equilibrium {
        force_error: ef,
        moment_error: em,
        force_scale: scale_f,
        moment_scale: scale_m,
        relative,
        solution_mismatch,
    }
}

/// `int_0^L p ds` [m^2] from the solution's nodes (see [`equilibrium`]).
pub fn position_integral(robot: &Robot, sol: &Solution) -> Vector3<f64> {
    let len = robot.body.length;
    let tol = 1e-9 * len;
    let bps = robot.breakpoints();
    let is_jump = |s: f64| s > tol && s < len - tol && bps.iter().any(|b| (b - s).abs() <= tol);
    let tangent = |k: usize| -> Vector3<f64> { sol.rotations[k] * sol.nu[k] };
    let (s, p) = (&sol.s, &sol.positions);
    let mut total = Vector3::zeros();
    for k in 0..s.len().saturating_sub(1) {
        let h = s[k + 1] - s[k];
        if h <= 0.0 {
            continue;
        }
        if !is_jump(s[k + 1]) {
            // end-corrected trapezoid: exact for cubics
            total += (p[k] + p[k + 1]) * (0.5 * h) + (tangent(k) - tangent(k + 1)) * (h * h / 12.0);
        } else if k >= 1 && !is_jump(s[k]) && ((s[k] - s[k - 1]) - h).abs() <= 1e-9 * h {
            // cubic c(t) = p_k + h p'_k t + a t^2 + b t^3 through p_{k-1}, p_{k+1}
            let a = (p[k + 1] + p[k - 1]) * 0.5 - p[k];
            let b = (p[k + 1] - p[k - 1]) * 0.5 - tangent(k) * h;
            total += (p[k] + tangent(k) * (0.5 * h) + a / 3.0 + b / 4.0) * h;
        } else {
            // quadratic c with c(0) = p_k, c'(0) = p'_k, c(h) = p_{k+1}:
            // int_0^h c = (2 p_k + p_{k+1}) h / 3 + p'_k h^2 / 6
            total += (p[k] * (2.0 / 3.0) + p[k + 1] / 3.0) * h + tangent(k) * (h * h / 6.0);
        }
    }
    total
}

/// Refinements [`refine_to_equilibrium`] tries before it gives up.
const REFINEMENTS: usize = 3;

/// Accuracy control ([`SolveOptions::equilibrium_tol`]): while the global
/// equilibrium error of `sol` exceeds the tolerance, solve again, warm
/// started from `sol`, on a finer grid. RK4's truncation error falls like
/// `h^4`, so the steps grow by `ceil((2 err / tol)^(1/4))` (at least 2);
/// the part from Newton's tolerance falls with it, which is divided by
/// `2 err / tol` too. The result's `steps` are those used; its `iterations` and
/// `evaluations` count every solve, and its `continuation_steps` are the
/// first solve's path (unless a re-solve needed one of its own).
/// [`Error::NotConverged`] if the tolerance is not met after three
/// refinements or within [`MAX_STEPS`]. Re-solves by single shooting
/// ([`solve_loaded`]); [`refine_with`] takes the solver.
pub fn refine_to_equilibrium(
    robot: &Robot,
    inputs: &[f64],
    opts: &SolveOptions,
    sol: Solution,
) -> Result<Solution> {
    let resolve =
        |o: &SolveOptions, w: &Solution| solve_loaded(robot, inputs, &w.loads, o, Some(w));
    refine_with(robot, opts, sol, resolve)
}

/// [`refine_to_equilibrium`] with the solver `resolve(opts, warm)`, which
/// solves the same problem again on `opts.steps`, warm from `warm`.
pub fn refine_with(
    robot: &Robot,
    opts: &SolveOptions,
    mut sol: Solution,
    resolve: impl Fn(&SolveOptions, &Solution) -> Result<Solution>,
) -> Result<Solution> {
    let Some(target) = opts.equilibrium_tol else {
        return Ok(sol);
    };
    let (mut iterations, mut evaluations) = (sol.iterations, sol.evaluations);
    // the path of the first solve (a warm re-solve from it needs none)
    let path = sol.continuation_steps.clone();
    let mut o = SolveOptions {
        equilibrium_tol: None,
        ..*opts
    };
    let mut err = equilibrium(robot, &sol).relative;
    for _ in 0..REFINEMENTS {
        if err <= target {
            break;
        }
        let ratio = err / target;
        // below the rounding floor Newton converges to the floor and says so
        o.tol = (o.tol / (2.0 * ratio)).max(f64::EPSILON);
        let factor = ((2.0 * ratio).powf(0.25).ceil() as usize).max(2);
        if o.steps.saturating_mul(factor) > MAX_STEPS {
            break;
        }
        o.steps *= factor;
        o.max_evaluations = opts.max_evaluations.saturating_sub(evaluations).max(1);
        cancel::check()?;
        let next = resolve(&o, &sol)?;
        (iterations, evaluations) = (iterations + next.iterations, evaluations + next.evaluations);
        sol = next;
        err = equilibrium(robot, &sol).relative;
    }
    if err > target {
        return Err(Error::NotConverged {
            solver: "equilibrium refinement",
            iterations,
            evaluations,
            residual: err,
            stop: StopReason::Other,
            reason: format!(
                "global equilibrium error {err:.2e} (relative) above equilibrium_tol {target:.1e} on {} RK4 steps",
                sol.steps
            ),
        });
    }
    (sol.iterations, sol.evaluations) = (iterations, evaluations);
    if sol.continuation_steps.is_empty() {
        sol.continuation_steps = path;
    }
    Ok(sol)
}
