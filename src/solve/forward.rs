//! The forward solve by multiple shooting (`docs/solver.md`): segments
//! placed before the solve ([`super::segments`]); the damped Newton method
//! ([`super::nleq`]) on the multiple-shooting system ([`super::ms`]) from a
//! first guess (the actuators' unknowns their law coordinates,
//! [`super::law_coordinate`]); where Newton fails (its damping factor below
//! [`super::nleq::DEFAULT_LAMBDA_MIN`], or no convergence within its
//! iterations), pseudo-arclength continuation in the inputs and loads
//! ([`super::homotopy`]) from the unloaded body at rest, or from a warm
//! start's inputs and loads; the solution assembled segment by segment. A
//! solve, cold or warm, runs first on a coarse grid ([`COARSENING`]), whose
//! solution and Jacobian start Newton on the requested grid.

use std::time::Instant;

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use super::ms::{MultipleShooting, ShootingSystem};
use super::nleq::{self, NleqOptions};
use super::options::SolveOptions;
use super::residual::Loads;
use super::segments::segment_starts;
use super::solution::{assemble_flat, Solution};
use crate::error::Result;
use crate::rod::{Grid, Robot, RodState};

/// A first guess of the multiple-shooting unknowns: the base unknowns
/// `base` (as single shooting's) integrated segment by segment where that
/// integration succeeds; else each segment starts from the straight
/// reference configuration at its node (`p = s nu*_z e_z`, the identity
/// rotation, the reference strains, no elongation). With `warm`, the
/// states of a neighbouring solution at the segments' nodes: on its own
/// grid, the recorded node nearest in arc length that is not an anchor (a
/// recorded state there is after the anchor's loads; segments never start
/// at one).
pub(crate) fn first_guess<'a>(
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: Loads,
    steps: usize,
    (starts, base): (&[usize], &[f64]),
    warm: Option<&Solution>,
) -> Result<(MultipleShooting<'a>, Vec<f64>)> {
    let na = robot.actuators.len();
    // (a solution of another robot, whose nodes are not this robot's grid
    // at its steps, gives no states)
    let own_grid =
        |w: &Solution| Some(Grid::new(robot, w.steps)).filter(|g| g.tip() + 1 == w.s.len());
    if let Some((w, own)) = warm.and_then(|w| own_grid(w).map(|g| (w, g))) {
        let grid = Grid::new(robot, steps);
        let nearest = |s: f64| {
            let inner = (1..own.tip()).filter(|&j| !own.is_breakpoint(j));
            inner.min_by(|&a, &b| (own.s(a) - s).abs().total_cmp(&(own.s(b) - s).abs()))
        };
        let state = |k: usize| node_state(w, nearest(grid.s(k)).unwrap_or(0));
        return with_blocks(robot, inputs, loads, steps, (starts, base), state);
    }
    match MultipleShooting::chained(robot, inputs, loads, steps, starts, base) {
        Ok(out) => Ok(out),
        Err(_) => {
            let (body, grid) = (&robot.body, Grid::new(robot, steps));
            let state = |k: usize| RodState {
                p: Vector3::z() * (grid.s(k) * body.nu_star[2]),
                q: Quaternion::identity(),
                v: body.nu_star,
                u: body.omega_star,
                delta: vec![0.0; na],
            };
            with_blocks(robot, inputs, loads, steps, (starts, base), state)
        }
    }
}

/// The rod state of the solution `w` at its node `j`.
pub(crate) fn node_state(w: &Solution, j: usize) -> RodState {
    RodState {
        p: w.positions[j],
        q: *UnitQuaternion::from_matrix(&w.rotations[j]).quaternion(),
        v: w.nu[j],
        u: w.omega[j],
        delta: w.elongation_profile.row(j).iter().copied().collect(),
    }
}

/// The unknowns with the base block `base` and each later block at the
/// rod state `state(node)` of its segment's first node.
fn with_blocks<'a>(
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: Loads,
    steps: usize,
    (starts, base): (&[usize], &[f64]),
    state: impl Fn(usize) -> RodState,
) -> Result<(MultipleShooting<'a>, Vec<f64>)> {
    let charts = vec![Quaternion::identity(); starts.len()];
    let mut ms = MultipleShooting::new(robot, inputs, loads, steps, starts, charts)?;
    let mut x = vec![0.0; ms.dim()];
    let sigma = ms.set_base(&mut x, base)?;
    for (k, &node) in starts.iter().enumerate().skip(1) {
        ms.set_block(&mut x, k, &state(node), &sigma);
    }
    Ok((ms, x))
}

/// The solution of `robot` at `inputs` under `loads` on `steps` RK4 steps
/// whose base unknowns are `base` and whose later segments
/// ([`segment_starts`]) start at the rod states `states`, one per segment
/// after the first: each segment integrated once from its state, as the
/// solve's last evaluation did (a pickled solution of several segments
/// carries these states). An error if `states` does not match the
/// segments.
pub fn from_segment_states(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    steps: usize,
    base: &[f64],
    states: &[RodState],
) -> Result<Solution> {
    let starts = segment_starts(robot, loads, steps);
    if states.len() + 1 != starts.len() {
        let why = format!(
            "{} segment states for {} segments",
            states.len(),
            starts.len()
        );
        return Err(crate::error::Error::input("segment states", why));
    }
    let state = |node: usize| {
        let k = starts.iter().position(|&n| n == node).unwrap_or(1);
        states[k - 1].clone()
    };
    let (mut ms, x) = with_blocks(robot, inputs, *loads, steps, (&starts, base), state)?;
    assemble(&mut ms, &x, (0, 0))
}

/// The Newton options of a forward solve.
pub(crate) fn newton_options(opts: &SolveOptions) -> NleqOptions {
    NleqOptions {
        tol: opts.tol,
        max_iterations: opts.max_iter,
        max_work: opts.max_evaluations as f64,
        deadline: opts.time_limit.map(|t| std::time::Instant::now() + t),
        ..Default::default()
    }
}

/// The [`Solution`] at the converged unknowns `x` of `ms`: the nodes of
/// the residual evaluation at `x` if it was recorded (Newton's last), else
/// each segment integrated once more from its block; with one segment, by
/// the single-shooting IVP from the base unknowns
/// ([`super::solution::assemble`]), which is what rebuilds a pickled
/// solution, so that the rebuilt one is the same bit for bit.
pub(crate) fn assemble(
    ms: &mut MultipleShooting<'_>,
    x: &[f64],
    (iterations, evaluations): (usize, usize),
) -> Result<Solution> {
    let rec = match ms.recorded(x) {
        Some(rec) => rec,
        None if ms.segments() == 1 => {
            let (robot, steps) = (ms.robot(), ms.steps());
            let (inputs, loads, base) = (ms.inputs(), ms.loads(), ms.base(x)?);
            let at = (iterations, evaluations);
            return super::solution::assemble(robot, inputs, &loads, &base, steps, at.0, at.1);
        }
        None => {
            let was = std::mem::replace(&mut ms.work, 0.0);
            ms.record(true);
            let mut f = vec![0.0; x.len()];
            let out = ms.residual(x, &mut f);
            ms.record(false);
            ms.work = was;
            out?;
            ms.recorded(x).expect("the evaluation just recorded")
        }
    };
    let robot = ms.robot();
    let len = robot.body.length;
    let base = ms.base(x)?;
    let delta: Vec<f64> = base[6..].iter().map(|d| d * len).collect();
    let r = super::residual::scaled_residual(robot, &rec.ivp, &delta);
    Ok(assemble_flat(
        robot,
        (ms.inputs(), &ms.loads(), &base),
        (ms.steps(), iterations, evaluations),
        r,
        (rec.ivp, rec.nodes),
        rec.tau0,
    ))
}

/// Share of the RK4 steps of the grid that a solve's first guess is
/// solved on ([`SolveOptions::presolve`]): the coarse grid's IVPs cost a
/// tenth of the fine grid's, its solution differs from the fine one by
/// RK4's error on ten times the step (`~1e4` times the fine grid's), and
/// its Jacobian serves as the fine grid's chord Jacobian, whose steps then
/// contract by about that relative difference each.
pub const COARSENING: usize = 10;

/// Fewest RK4 steps of the presolve's coarse grid: a body bent by up to a
/// full turn (`kappa L <= 2 pi`) has `h kappa <= 0.63` on ten steps, where
/// RK4's local error `(h kappa)^5 / 120` is below `1e-3`; on fewer steps
/// a buckled or curled shape is no guess for the fine grid's (a column
/// just past buckling, solved on 20 steps, has a coarse grid of 2).
pub const COARSE_MIN_STEPS: usize = 10;

/// The unknowns of a converged solve with their system.
struct Solved<'a> {
    sys: ShootingSystem<'a>,
    x: Vec<f64>,
    iterations: usize,
    residual: f64,
    /// The continuation parameter at each accepted point of the path
    /// taken (empty without continuation).
    path: Vec<f64>,
    /// Whether Newton stopped at the rounding floor above `tol`.
    at_floor: bool,
}

/// Solve the forward problem of `robot` at `inputs` under `loads` by
/// multiple shooting (see the module docs); with `opts.equilibrium_tol`,
/// on grids refined until the global equilibrium holds to it
/// ([`super::equilibrium::refine_with`]).
pub fn solve(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<Solution> {
    super::shooting::validate(robot, inputs, loads, opts, warm)?;
    let sol = solve_on_grid(robot, inputs, loads, opts, warm)?;
    let resolve = |o: &SolveOptions, w: &Solution| solve_on_grid(robot, inputs, loads, o, Some(w));
    super::equilibrium::refine_with(robot, opts, sol, resolve)
}

/// [`solve`] on the grid of `opts.steps`: from the solution on the
/// coarse grid of the presolve where that grid carries the segments
/// ([`presolved`]); where that fails, or without a coarse grid, damped
/// Newton and continuation on the grid itself ([`solve_on`]).
fn solve_on_grid(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<Solution> {
    super::cancel::check()?;
    let starts = segment_starts(robot, loads, opts.steps);
    let deadline = opts.time_limit.map(|t| Instant::now() + t);
    let (mut spent, mut best) = (0.0, f64::INFINITY);
    let coarse = match opts.presolve {
        true => coarse_grid(robot, loads, opts.steps, &starts),
        false => None,
    };
    if let Some((csteps, cstarts)) = coarse {
        let grids = (&starts[..], &cstarts[..]);
        match presolved(robot, inputs, loads, opts, csteps, grids, warm) {
            Ok(done) => return finish(done),
            Err((e, _)) if !continues(&e) => return Err(e),
            Err((e, work)) => (spent, best) = (work, e.best_residual()),
        }
    }
    let rest = remaining(opts, deadline, (spent, best))?;
    let mut done = solve_on(robot, inputs, loads, &rest, (&starts, true), warm)?;
    done.sys.ms.work += spent;
    finish(done)
}

/// `opts` with what is left of its budget after `spent` IVPs and of its
/// time until `deadline`; a budget error if nothing is left, with the best
/// full-grid residual `best` of the work spent (infinite if none was
/// evaluated).
fn remaining(
    opts: &SolveOptions,
    deadline: Option<Instant>,
    (spent, best): (f64, f64),
) -> Result<SolveOptions> {
    let now = Instant::now();
    let left = opts.max_evaluations.saturating_sub(spent.ceil() as usize);
    if left == 0 || deadline.is_some_and(|d| now >= d) {
        let reason = match best.is_finite() {
            true => "the IVP budget or the time limit was spent",
            false => "the IVP budget or the time limit was spent before a full-grid residual",
        };
        return Err(crate::error::Error::NotConverged {
            solver: "forward shooting",
            iterations: 0,
            evaluations: spent.ceil() as usize,
            residual: best,
            stop: crate::error::StopReason::Budget,
            reason: reason.into(),
        });
    }
    Ok(SolveOptions {
        max_evaluations: left,
        time_limit: deadline.map(|d| d.saturating_duration_since(now)),
        ..*opts
    })
}

/// The solution of a converged solve.
fn finish(mut done: Solved<'_>) -> Result<Solution> {
    let work = done.sys.ms.work.ceil() as usize;
    let mut sol = assemble(&mut done.sys.ms, &done.x, (done.iterations, work))?;
    sol.residual = done.residual;
    sol.continuation_steps = done.path;
    sol.floor = nleq::NonlinearSystem::floor(&done.sys, &done.x, &[]);
    if done.at_floor {
        sol.status = nleq::Status::ConvergedAtFloor;
    }
    Ok(sol)
}

/// The solve from the solution on the coarse grid ([`COARSENING`]), cold
/// or warm from `warm`: the same segments (at the coarse nodes nearest the
/// fine ones), its unknowns as the first guess and its last Jacobian as the
/// first factorisation on the fine grid. On failure, the error and the work
/// spent (in IVPs of the fine grid).
fn presolved<'a>(
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: &Loads,
    opts: &SolveOptions,
    csteps: usize,
    (starts, cstarts): (&[usize], &[usize]),
    warm: Option<&Solution>,
) -> std::result::Result<Solved<'a>, (crate::error::Error, f64)> {
    let started = Instant::now();
    // a coarse IVP costs `scale` of a fine one: the budget and the work
    // reported are in fine IVPs
    let scale = csteps as f64 / opts.steps as f64;
    let coarse = SolveOptions {
        steps: csteps,
        max_evaluations: (opts.max_evaluations as f64 / scale) as usize,
        ..*opts
    };
    let c = solve_on(robot, inputs, loads, &coarse, (cstarts, false), warm);
    let c = c.map_err(|e| match e {
        crate::error::Error::NotConverged {
            solver,
            iterations,
            evaluations,
            residual,
            stop,
            reason,
        } => {
            let work = evaluations as f64 * scale;
            let e = crate::error::Error::NotConverged {
                solver,
                iterations,
                evaluations: work.ceil() as usize,
                residual,
                stop,
                reason,
            };
            (e, work)
        }
        e => (e, 0.0),
    })?;
    let spent = c.sys.ms.work * scale;
    let charts = c.sys.ms.charts().to_vec();
    let ms = MultipleShooting::new(robot, inputs, *loads, opts.steps, starts, charts)
        .map_err(|e| (e, spent))?;
    let mut sys = ShootingSystem::with_factorisation(ms, c.sys);
    sys.ms.work = spent;
    sys.ms.record(true);
    let mut f0 = vec![0.0; c.x.len()];
    let rest = remaining(
        opts,
        opts.time_limit.map(|t| started + t),
        (spent, f64::INFINITY),
    );
    let nopts = NleqOptions {
        lambda_min: super::arclength::CORRECTOR_LAMBDA_MIN,
        ..newton_options(&rest.map_err(|e| (e, spent))?)
    };
    let factorised = sys.is_factorised();
    let out = match factorised {
        true => nleq::NonlinearSystem::residual(&mut sys, &c.x, &mut f0).and_then(|_| {
            nleq::Nleq::default().solve_linearised(&mut sys, &c.x, &f0, &nopts, "forward shooting")
        }),
        false => nleq::solve(&mut sys, &c.x, &nopts, "forward shooting"),
    };
    match out {
        Ok(out) => Ok(Solved {
            iterations: c.iterations + out.iterations,
            x: out.x,
            residual: out.residual,
            at_floor: out.status == nleq::Status::ConvergedAtFloor,
            sys,
            path: c.path,
        }),
        Err(e) => Err((e, sys.ms.work)),
    }
}

/// The segments' first nodes on the coarse grid of the presolve: the
/// nodes nearest `starts` on the grid of `steps`; `None` where the coarse
/// grid cannot carry them (two segments on one node, or one at an anchor).
fn coarse_grid(
    robot: &Robot,
    loads: &Loads,
    steps: usize,
    starts: &[usize],
) -> Option<(usize, Vec<usize>)> {
    // at most one bending length `1 / lambda` per step, where RK4's local
    // error `(h lambda)^5 / 120` stays below 1 %: a coarser grid's solution
    // is no guess for the fine grid's (and past `h lambda = 2.79` RK4
    // amplifies the decaying modes)
    let len = robot.body.length;
    let resolved = (len * super::segments::largest_rate(robot, loads)).ceil() as usize;
    let coarse = (steps / COARSENING).max(resolved).max(COARSE_MIN_STEPS);
    if 2 * coarse > steps {
        return None;
    }
    let (fine, rough) = (
        crate::rod::Grid::new(robot, steps),
        crate::rod::Grid::new(robot, coarse),
    );
    let cstarts: Vec<usize> = starts
        .iter()
        .map(|&k| nearest_node(&rough, fine.s(k)))
        .collect();
    let usable = coarse >= 2
        && cstarts.windows(2).all(|w| w[0] < w[1])
        && cstarts
            .iter()
            .skip(1)
            .all(|&k| k < rough.tip() && !rough.is_breakpoint(k));
    usable.then_some((coarse, cstarts))
}

/// The node of `grid` nearest the arc length `s` \[m\].
fn nearest_node(grid: &crate::rod::Grid, s: f64) -> usize {
    let mut best = 0;
    for k in 0..=grid.tip() {
        if (grid.s(k) - s).abs() < (grid.s(best) - s).abs() {
            best = k;
        }
    }
    best
}

/// The solve on the grid of `opts.steps` with segments at `starts`:
/// damped Newton from the first guess; where it fails, continuation. With
/// `record` (the requested grid, not the presolve's coarse one), Newton's
/// evaluations record their nodes for the solution's assembly.
fn solve_on<'a>(
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: &Loads,
    opts: &SolveOptions,
    (starts, record): (&[usize], bool),
    warm: Option<&Solution>,
) -> Result<Solved<'a>> {
    let started = Instant::now();
    let nopts = newton_options(opts);
    let mut base = super::guess::initial_guess(robot, inputs, warm);
    if warm.is_none() {
        super::guess::linear_guess(robot, inputs, loads, &mut base);
    }
    let (ms, x0) = first_guess(robot, inputs, *loads, opts.steps, (starts, &base), warm)?;
    let mut sys = ShootingSystem::new(ms)?;
    sys.ms.record(record);
    match nleq::solve(&mut sys, &x0, &nopts, "forward shooting") {
        Ok(out) => Ok(Solved {
            sys,
            x: out.x,
            iterations: out.iterations,
            residual: out.residual,
            path: Vec::new(),
            at_floor: out.status == nleq::Status::ConvergedAtFloor,
        }),
        Err(e) if !continues(&e) => Err(e),
        Err(e) => {
            let (spent, best) = (sys.ms.work, e.best_residual());
            let deadline = opts.time_limit.map(|t| started + t);
            let rest = remaining(opts, deadline, (spent, best))?;
            let (x, charts, path) = match continued(robot, inputs, loads, &rest, starts, warm) {
                // The warm path does not reach the target (its branch turns
                // back at a fold and leaves the inputs' range: the body snaps
                // through to another branch; or its steps fall below
                // `min_step`): the cold path from rest, which does not pass
                // that fold, reaches an equilibrium at the target.
                Err(e) if warm.is_some() && continues(&e) => {
                    let failed = e.evaluations() as f64;
                    let best = best.min(e.best_residual());
                    let rest = remaining(opts, deadline, (spent + failed, best))?;
                    let (x, charts, mut path) =
                        continued(robot, inputs, loads, &rest, starts, None)?;
                    path.work += failed;
                    (x, charts, path)
                }
                out => out?,
            };
            let grid = (opts.steps, starts, opts.tol);
            let mut done = path_end(robot, inputs, *loads, grid, (x, charts, path))?;
            done.sys.ms.work += spent;
            Ok(done)
        }
    }
}

/// The end of a continuation `path` at the unknowns `x` with rotation
/// charts `charts`, on `steps` RK4 steps with segments at `starts`: a
/// solve of `robot` at `inputs` under `loads` whose work is the path's,
/// converged to `tol` or at its floor.
fn path_end<'a>(
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: Loads,
    (steps, starts, tol): (usize, &[usize], f64),
    (x, charts, path): (Vec<f64>, Vec<Quaternion<f64>>, super::arclength::Path),
) -> Result<Solved<'a>> {
    let ms = MultipleShooting::new(robot, inputs, loads, steps, starts, charts)?;
    let mut sys = ShootingSystem::new(ms)?;
    sys.ms.work = path.work;
    Ok(Solved {
        sys,
        x,
        iterations: path.steps,
        residual: path.residual,
        path: path.points[1..].iter().map(|p| p.lambda).collect(),
        at_floor: path.residual > tol,
    })
}

/// Whether a failed Newton solve hands over to continuation (not for
/// invalid input, an interrupt, or a spent budget).
pub(crate) fn continues(e: &crate::error::Error) -> bool {
    !(super::shooting::is_input_error(e) || super::shooting::is_budget_error(e))
}

/// The solution at `inputs` under `loads` by pseudo-arclength continuation
/// from the unloaded body at rest (cold) or from `warm`'s inputs and loads;
/// its unknowns (on the segments of [`segment_starts`]), their rotation
/// charts and the path.
fn continued(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    starts: &[usize],
    warm: Option<&Solution>,
) -> Result<(Vec<f64>, Vec<Quaternion<f64>>, super::arclength::Path)> {
    use super::arclength::{follow, ArclengthOptions, Predictor};
    use super::homotopy::{unloaded, Endpoint, LoadPath};
    let to = Endpoint::loaded(robot, inputs, *loads);
    // (the target's segments: the path's loads are largest there)
    let (ms, x0, from) = match warm {
        Some(w) => {
            let from = Endpoint::loaded(robot, &w.inputs, w.loads);
            let base = (starts, &w.unknowns[..]);
            let (ms, x0) = first_guess(robot, &w.inputs, w.loads, opts.steps, base, Some(w))?;
            (ms.charts().to_vec(), x0, from)
        }
        None => {
            let free = unloaded(robot);
            let reference = robot.reference_inputs();
            let base = super::guess::initial_guess(robot, &reference, None);
            let none = Loads::of(&free);
            let (ms, x0) =
                MultipleShooting::chained(&free, &reference, none, opts.steps, starts, &base)?;
            (ms.charts().to_vec(), x0, Endpoint::unloaded(robot))
        }
    };
    let mut path = LoadPath::new(robot, (from, to), opts.steps, starts.to_vec(), ms.clone());
    // (only the path's end is wanted: the Hermite predictor's longer steps)
    let aopts = ArclengthOptions {
        tol: opts.tol,
        predictor: Predictor::Hermite,
        corrector_iterations: opts.max_iter.min(super::arclength::CORRECTOR_ITERATIONS),
        max_work: opts.max_evaluations as f64,
        deadline: opts.time_limit.map(|t| std::time::Instant::now() + t),
        ..Default::default()
    };
    let out = follow(&mut path, &x0, 0.0, 1.0, &aopts, true)?;
    let end = out.points.last().expect("a path ends at a point");
    Ok((end.x.clone(), ms, out))
}

/// The equilibrium of `robot` at `inputs` under `loads` that a loading
/// history with an imperfection ends on: pseudo-arclength continuation
/// ([`super::homotopy`]) from the unloaded body at rest to the loads with
/// the tip wrench `imperfection` added, then the forward solve ([`solve`])
/// of the loads alone, warm from there. The imperfection selects one branch
/// of a bifurcation on the way (a column loaded past its buckling load
/// bends toward it instead of staying on the straight, unstable, branch;
/// Thompson & Hunt, *A General Theory of Elastic Stability*, Wiley 1973,
/// ch. 3). Taking it away is a warm solve like any other: Newton from the
/// imperfect shape, which lies on the selected branch's neighbourhood, and
/// where Newton fails the continuation from the imperfect loads to the
/// loads alone. The path runs on the coarse grid of the presolve where
/// there is one; the solution's `evaluations` count all of it.
pub fn solve_imperfect(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    imperfection: &Loads,
    opts: &SolveOptions,
) -> Result<Solution> {
    super::shooting::validate(robot, inputs, loads, opts, None)?;
    let starts = segment_starts(robot, loads, opts.steps);
    let (steps, starts) =
        coarse_grid(robot, loads, opts.steps, &starts).unwrap_or((opts.steps, starts));
    // a coarse IVP costs `scale` of a fine one: the budget is in fine IVPs
    let scale = steps as f64 / opts.steps as f64;
    let coarse = SolveOptions {
        steps,
        max_evaluations: (opts.max_evaluations as f64 / scale) as usize,
        ..*opts
    };
    let deadline = opts.time_limit.map(|t| Instant::now() + t);
    let mut imperfect = *loads;
    imperfect.tip_force += imperfection.tip_force;
    imperfect.tip_moment += imperfection.tip_moment;
    let path = continued(robot, inputs, &imperfect, &coarse, &starts, None)?;
    let spent = path.2.work * scale;
    let grid = (steps, &starts[..], opts.tol);
    let loaded = finish(path_end(robot, inputs, imperfect, grid, path)?)?;
    let rest = remaining(opts, deadline, (spent, f64::INFINITY))?;
    let mut sol = solve(robot, inputs, loads, &rest, Some(&loaded))?;
    sol.evaluations += spent.ceil() as usize;
    Ok(sol)
}
