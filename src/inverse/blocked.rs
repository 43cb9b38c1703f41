//! A blocked tip (mixed boundary conditions) and the paper's incremental
//! method (eq 43).

use nalgebra::Vector3;

use super::mixed::Extra;
use super::mixed_solve::{mixed_solve, Guess};
use super::predictor::{coarse_steps, predictor, Linearised};
use super::{exact_blocks, load_scales, ExactBlocks, Groups, Sensitivities};
use crate::error::{significant, Error, Result, StopReason};
use crate::rod::Robot;
use crate::shooting::{solve_loaded, Loads, Solution, SolveOptions};
use crate::stability::{stability, unstable_error, Policy, Stability};

/// A blocked tip: the tip's displacement along `normal` (unit, world) is held
/// at `point`; the environment pushes on the tip with force `-f normal`,
/// `f >= 0` (the tip presses along `+normal`).
#[derive(Debug, Clone, Copy)]
pub struct Block {
    /// A point of the blocking plane \[m\].
    pub point: Vector3<f64>,
    /// Unit normal: the direction the tip presses in.
    pub normal: Vector3<f64>,
    /// What the blocked solves do with the stability verdict of the
    /// equilibrium they find (tip held along `normal`): [`Policy::Report`]
    /// (the default) attaches it to the result, [`Policy::Require`] refuses
    /// an unstable one, [`Policy::Off`] skips it.
    pub stability: Policy,
}

impl Block {
    /// Validate and normalise; the verdict policy is [`Policy::Report`].
    pub fn new(point: Vector3<f64>, normal: Vector3<f64>) -> Result<Self> {
        for k in 0..3 {
            crate::error::finite(&format!("point[{k}] [m]"), point[k])?;
            crate::error::finite(&format!("normal[{k}]"), normal[k])?;
        }
        let n = normal.norm();
        if !(n > 0.0) {
            return Err(Error::input("normal", "must be a non-zero vector"));
        }
        Ok(Block {
            point,
            normal: normal / n,
            stability: Policy::Report,
        })
    }
    /// The same block under another stability policy; [`Policy::Continue`]
    /// (moving to a stable free-tip equilibrium) does not apply to a held tip.
    pub fn with_stability(self, policy: Policy) -> Result<Self> {
        if policy == Policy::Continue {
            return Err(Error::input(
                "stability",
                "'continue' is not available for a blocked tip: use 'report', 'require' or 'off'",
            ));
        }
        Ok(Block {
            stability: policy,
            ..self
        })
    }
    pub(crate) fn loads(&self, robot: &Robot, f: f64) -> Loads {
        let mut l = Loads::of(robot);
        l.tip_force -= self.normal * f;
        l
    }
    /// The block's verdict on `res` (see [`Block::stability`]); the
    /// verdict's tangent IVP is counted in `res.evaluations`.
    pub(super) fn check(&self, robot: &Robot, mut res: BlockedResult) -> Result<BlockedResult> {
        if self.stability == Policy::Off {
            return Ok(res);
        }
        let st = stability(robot, &res.solution, &[self.normal])?;
        res.evaluations += st.evaluations;
        if self.stability == Policy::Require && !st.stable {
            return Err(unstable_error(&res.solution, &st));
        }
        res.stability = Some(st);
        Ok(res)
    }
}

/// A blocked-tip solution.
#[derive(Debug, Clone)]
pub struct BlockedResult {
    /// The forward solution with the contact force applied at the tip.
    pub solution: Solution,
    /// Contact force magnitude \[N\] (the tip presses with it along the normal).
    pub force: f64,
    /// Actuation variables.
    pub variables: Vec<f64>,
    /// IVPs integrated (plain and tangent; the verdict's included).
    pub evaluations: usize,
    /// Iterations (increments for the incremental method, Newton iterations for the direct one).
    pub iterations: usize,
    /// Stability verdict of the equilibrium with the tip held along the
    /// block normal (`None` only under [`Policy::Off`]).
    pub stability: Option<Stability>,
}

/// Direct solve with the tip held (mixed boundary condition): at given
/// actuation variables `z`, the contact force `f` \[N\] is an extra unknown and
/// `normal . (p(L) - point) = 0` an extra residual, solved by the damped
/// Newton method on the multiple-shooting system bordered by that
/// condition (see `inverse::mixed`), from the forward solution at `z`
/// under the force of `warm` (zero without one), warm from its solution.
/// `f` may come out negative if the tip would pull away from the block
/// (the caller decides whether contact holds).
pub fn blocked_force(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    z: &[f64],
    opts: &SolveOptions,
    warm: Option<(&Solution, f64)>,
) -> Result<BlockedResult> {
    groups.validate(robot)?;
    let inputs = groups.inputs(z);
    robot.check_inputs(&inputs)?;
    let (fc, _) = load_scales(robot);
    let f0 = warm.map_or(0.0, |w| w.1);
    crate::error::finite("warm force [N]", f0)?;
    let start = solve_loaded(
        robot,
        &inputs,
        &block.loads(robot, f0),
        opts,
        warm.map(|w| w.0),
    )?;
    let extra = Extra::Force { inputs };
    let problem = (robot, groups, block);
    let guess = Guess::Solution(&start);
    let solver = "blocked-tip shooting";
    mixed_solve(problem, extra, guess, f0 / fc, opts, solver, (0, 0.0))
}

/// Direct solve for the single actuation variable at which the blocked tip
/// presses with `force` \[N\] (the variable an extra unknown, see
/// `inverse::mixed`), from the forward solution at `z_guess` under that
/// force (warm from `warm`). Independent check of [`blocked_temperature`].
pub fn blocked_variable_direct(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    force: f64,
    z_guess: f64,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<BlockedResult> {
    one_variable_and_force(robot, groups, force)?;
    crate::error::finite("z_guess", z_guess)?;
    let inputs = groups.inputs(&[z_guess]);
    robot.check_inputs(&inputs)?;
    let start = solve_loaded(robot, &inputs, &block.loads(robot, force), opts, warm)?;
    let scale = variable_scale(robot, groups);
    let extra = Extra::Variable { force, scale };
    let problem = (robot, groups, block);
    let solver = "blocked-tip temperature shooting";
    let guess = Guess::Solution(&start);
    mixed_solve(
        problem,
        extra,
        guess,
        z_guess / scale,
        opts,
        solver,
        (0, 0.0),
    )
}

/// Direct solve for the single actuation variable at which the blocked tip
/// presses with `force` \[N\], from `start` (a solution whose tip touches the
/// block with no force): the damped Newton method on the multiple-shooting
/// system under the contact force, with the variable as the extra unknown
/// and the tip's gap as the extra condition (see `inverse::mixed`), from
/// the eq-43 predictor of the whole force with the force law kept exact
/// (see `inverse::predictor`: one tangent IVP at `start` on a tenth of the
/// grid).
pub fn blocked_variable_from(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    start: &Solution,
    force: f64,
    opts: &SolveOptions,
) -> Result<BlockedResult> {
    one_variable_and_force(robot, groups, force)?;
    groups.check_fixed(&start.inputs, "start")?;
    let z0 = groups.vars(&start.inputs)[0];
    let scale = variable_scale(robot, groups);
    let extra = Extra::Variable { force, scale };
    let problem = (robot, groups, block);
    let linear = Linearised {
        robot,
        groups,
        block,
        force,
        scale,
    };
    // one tangent IVP on the predictor's grid, counted in IVPs of the
    // requested grid (`1 + (6 + N) / 8` directions)
    let coarse = coarse_steps(opts.steps);
    let cost = coarse as f64 / opts.steps as f64 * (1.0 + start.unknowns.len() as f64 / 8.0);
    let x = predictor(&linear, start, coarse, z0)?;
    let n = x.len() - 1;
    let guess = Guess::Base(x[..n].to_vec());
    mixed_solve(problem, extra, guess, x[n], opts, GRASP, (0, cost))
}

/// Newton's name for the direct grasp solve.
const GRASP: &str = "blocked-tip grasp shooting";

/// Scale of the single actuation variable: its range, within `[1, 1000]`.
pub(crate) fn variable_scale(robot: &Robot, groups: &Groups) -> f64 {
    let (lo, hi) = groups.bounds(robot)[0];
    (hi - lo).clamp(1.0, 1e3)
}

/// The paper's incremental method (eq 43 with `dx = 0`): starting from a
/// solution `start` whose tip touches the block with zero force, raise the
/// contact force to `force` \[N\] in `increments` steps, each
/// `dq = -(n^T J)^-1 n^T C dW`, followed by one forward solve and a
/// position correction `dq = (n^T J)^-1 n^T (point - p)` so that the tip stays
/// on the block. Needs exactly one actuation variable. A force that needs
/// an input outside the actuator's range is [`Error::NoSolution`]; a step that
/// overshoots a bound by linearisation error (a tenth of the step at most) is
/// clamped to it.
///
/// Where eq 43's linearisation fails within a step (a TCA whose coils touch
/// at ambient barely moves the tip until it is heated past contact, so that
/// `n^T J` is tiny at the start and grows a hundredfold within a few C), the
/// step is halved: when it leaves the input range, when its forward solve
/// fails, or when the tip then misses the block by more than half the
/// motion the step predicted (`|n^T J dq|`). After an accepted halved step the
/// increment doubles again, up to `force / increments`. Steps that
/// linearise well are the paper's, unchanged.
pub fn blocked_temperature(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    start: &Solution,
    force: f64,
    increments: usize,
    opts: &SolveOptions,
) -> Result<BlockedResult> {
    check_increments(robot, groups, force, increments)?;
    groups.check_fixed(&start.inputs, "start")?;
    let (lo, hi) = groups.bounds(robot)[0];
    let unit = groups.unit(robot, 0);
    let n = block.normal;
    let tight = 1e-9 * robot.body.length; // the tip on the block: gap below 1e-9 L
    let mut z = groups.vars(&start.inputs)[0];
    let mut sol = start.clone();
    let mut f = 0.0;
    let mut evals = 0;
    let mut pushed_out = false;
    let df = force / increments as f64;
    let mut h = df; // the current force increment (halved where eq 43 fails)
    let (mut halvings, mut corrections, mut taken) = (0, 0, 0);
    // J and C exactly, from one tangent IVP at each accepted solution (its
    // B blocks: the warm start)
    let mut linearised: Option<(ExactBlocks, Sensitivities)> = None;
    loop {
        let current = match linearised.take() {
            Some(current) => current,
            None => {
                let blocks = exact_blocks(robot, &sol, &block.loads(robot, f), groups, opts.steps)?;
                let sens = blocks.sensitivities()?;
                evals += sens.evaluations;
                (blocks, sens)
            }
        };
        let (blocks, sens) = (&current.0, &current.1);
        // the last increment lands on `force` exactly
        let remaining = force - f;
        let last = remaining.abs() <= h.abs();
        let step = if last { remaining } else { h };
        let gap = n.dot(&(block.point - sol.tip_position()));
        let Some(dz) = eq43_increment(sens, &n, step, gap) else {
            return Err(tip_cannot_move(taken, evals));
        };
        let may_halve = step != 0.0 && halvings < MAX_HALVINGS;
        // Near a bound (e.g. the blocked force at 160 C, fed back), a step may
        // overshoot the bound by its linearisation error, a small fraction of
        // the step: clamp it and let the next position correction decide.
        // Beyond that (more than a tenth of the step plus rounding, 1e-9 of
        // the range), or twice in a row in the corrections at the final
        // force, the force needs an input outside the range.
        let slack = 1e-9 * (hi - lo).clamp(1.0, 1e3);
        let zt = z + dz;
        let over = (lo - zt).max(zt - hi).max(0.0);
        let outside = over > slack;
        if over > 0.1 * dz.abs() + slack || (outside && step == 0.0 && pushed_out) {
            if may_halve {
                (h, halvings) = (0.5 * h, halvings + 1);
                linearised = Some(current);
                continue;
            }
            return Err(Error::NoSolution {
                reason: format!("the blocked force {} N needs an input outside [{lo}, {hi}] {unit} (the eq-43 increments reached {} {unit} at force {} N)", significant(force), significant(zt), significant(f + step)),
            });
        }
        let zc = zt.clamp(lo, hi);
        let dzc = zc - z;
        let ft = if last { force } else { f + step };
        let warm = predicted(robot, groups, &sol, blocks, dzc, -n * step, zc);
        let inputs = groups.inputs(&[zc]);
        let trial = solve_loaded(robot, &inputs, &block.loads(robot, ft), opts, Some(&warm));
        let st = match trial {
            Ok(st) => st,
            Err(_) if may_halve => {
                (h, halvings) = (0.5 * h, halvings + 1);
                linearised = Some(current);
                continue;
            }
            Err(e) => return Err(e),
        };
        evals += st.evaluations;
        let gap = n.dot(&(block.point - st.tip_position()));
        let moved: f64 = (0..3).map(|i| n[i] * sens.jacobian[(i, 0)]).sum::<f64>() * dzc;
        if may_halve && gap.abs() > 0.5 * moved.abs() + tight {
            (h, halvings) = (0.5 * h, halvings + 1);
            linearised = Some(current);
            continue;
        }
        pushed_out = outside && step == 0.0;
        (z, f, sol, taken) = (zc, ft, st, taken + 1);
        if step == 0.0 {
            corrections += 1;
        } else if h.abs() < df.abs() {
            h = (2.0 * h).clamp(-df.abs(), df.abs());
        }
        if last && gap.abs() < tight {
            let res = BlockedResult {
                solution: sol,
                force: f,
                variables: vec![z],
                evaluations: evals,
                iterations: taken,
                stability: None,
            };
            return block.check(robot, res);
        }
        if corrections >= 3 {
            break;
        }
    }
    Err(Error::NotConverged {
        solver: "blocked-tip increments",
        iterations: taken,
        evaluations: evals,
        stop: StopReason::IterationLimit,
        residual: n.dot(&(block.point - sol.tip_position())).abs() / robot.body.length,
        reason: "tip did not settle on the block".into(),
    })
}

/// Halvings of the eq-43 force increment allowed in one
/// [`blocked_temperature`] (`2^-60` of the increment: far below any force
/// resolution, so the limit ends only a force out of reach).
const MAX_HALVINGS: usize = 60;

/// The error of an eq-43 increment whose actuator cannot move the tip along
/// the block normal (`n^T J = 0`), after `iterations` increments.
fn tip_cannot_move(iterations: usize, evaluations: usize) -> Error {
    Error::NotConverged {
        solver: "blocked-tip increments",
        iterations,
        evaluations,
        residual: f64::INFINITY,
        stop: StopReason::SingularJacobian,
        reason: "the actuator cannot move the tip along the block normal (n^T J = 0)".into(),
    }
}

/// The arguments of [`blocked_temperature`]: one actuation variable, a
/// finite force, at least one increment.
fn check_increments(robot: &Robot, groups: &Groups, force: f64, increments: usize) -> Result<()> {
    one_variable_and_force(robot, groups, force)?;
    if increments == 0 {
        return Err(Error::param("increments", 0.0, ">= 1"));
    }
    Ok(())
}

/// Valid `groups` with exactly one actuation variable, which `what` (a
/// blocked-force temperature, or its peak) is solved for.
pub(super) fn one_variable(robot: &Robot, groups: &Groups, what: &str) -> Result<()> {
    groups.validate(robot)?;
    if groups.n_vars() != 1 {
        return Err(Error::input(
            "groups",
            format!(
                "a {what} needs exactly one actuation variable, got {} (share one with groups = [0, 0, ...], or hold the other actuators with fixed_inputs)",
                groups.n_vars()
            ),
        ));
    }
    Ok(())
}

/// Valid `groups` with exactly one actuation variable, and a finite force.
fn one_variable_and_force(robot: &Robot, groups: &Groups, force: f64) -> Result<()> {
    one_variable(robot, groups, "blocked-force temperature")?;
    crate::error::finite("force [N]", force)?;
    Ok(())
}

/// One eq-43 increment of the actuation variable for the tip wrench
/// increment `dW = -step n` (force only) and the gap `n . (point - p)` \[m\]:
/// `dz = (gap - n^T C dW) / (n^T J)`; `None` if `n^T J = 0`.
fn eq43_increment(sens: &Sensitivities, n: &Vector3<f64>, step: f64, gap: f64) -> Option<f64> {
    let nj: f64 = (0..3).map(|i| n[i] * sens.jacobian[(i, 0)]).sum();
    if nj.abs() < 1e-300 {
        return None;
    }
    let nc_dw: f64 = (0..3)
        .map(|i| {
            (0..3)
                .map(|j| n[i] * sens.compliance[(i, j)] * (-n[j] * step))
                .sum::<f64>()
        })
        .sum();
    Some((-nc_dw + gap) / nj)
}

/// The warm start of an eq-43 increment: `sol` moved to first order
/// along `dz` (variable) and `df` (tip force) by the exact blocks at `sol`
/// (`du = -B_u^-1 (B_q dz + B_W dW)`), with its tensions at the predicted
/// elongations.
fn predicted(
    robot: &Robot,
    groups: &Groups,
    sol: &Solution,
    blocks: &ExactBlocks,
    dz: f64,
    df: Vector3<f64>,
    z: f64,
) -> Solution {
    let mut warm = sol.clone();
    let dw = [df.x, df.y, df.z, 0.0, 0.0, 0.0];
    let Some(du) = blocks.predict(&[dz], &dw) else {
        return warm;
    };
    let len = robot.body.length;
    let inputs = groups.inputs(&[z]);
    let x: Vec<f64> = sol
        .unknowns
        .iter()
        .zip(du.iter())
        .map(|(a, b)| a + b)
        .collect();
    let tensions: Option<Vec<f64>> = robot
        .actuators
        .iter()
        .enumerate()
        .map(|(i, a)| a.law.tension(x[6 + i] * len, inputs[i]).ok())
        .collect();
    if let Some(t) = tensions.filter(|t| t.iter().all(|v| v.is_finite())) {
        if x.iter().all(|v| v.is_finite()) {
            warm.unknowns = x;
            warm.tensions = t;
        }
    }
    warm
}
