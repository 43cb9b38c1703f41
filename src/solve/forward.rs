//! The forward solve by multiple shooting: segments placed before the
//! solve ([`super::segments`]), a first guess, the damped Newton method
//! ([`super::nleq`]) on the multiple-shooting system ([`super::ms`]), and
//! the solution assembled segment by segment.

use nalgebra::{Quaternion, UnitQuaternion};

use super::ms::{MultipleShooting, ShootingSystem};
use super::nleq::{self, NleqOptions};
use super::options::SolveOptions;
use super::residual::Loads;
use super::segments::segment_starts;
use super::solution::{assemble_flat, Solution};
use crate::error::Result;
use crate::rod::{FlatNodes, Robot, BASE_STATES};

/// A first guess of the multiple-shooting unknowns: the base unknowns
/// `base` (as single shooting's) integrated segment by segment where that
/// integration succeeds; a segment it cannot reach starts from the
/// straight reference configuration at its node. With `warm`, the states
/// of a neighbouring solution at the segments' nodes.
pub(crate) fn first_guess<'a>(
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: Loads,
    steps: usize,
    (starts, base): (&[usize], &[f64]),
    warm: Option<&Solution>,
) -> Result<(MultipleShooting<'a>, Vec<f64>)> {
    if let Some(w) = warm.filter(|w| w.steps == steps && w.s.len() > *starts.last().unwrap()) {
        return from_nodes(robot, inputs, loads, steps, starts, base, w);
    }
    match MultipleShooting::chained(robot, inputs, loads, steps, starts, base) {
        Ok(out) => Ok(out),
        Err(_) => {
            let straight = reference_nodes(robot, steps, base)?;
            from_nodes(robot, inputs, loads, steps, starts, base, &straight)
        }
    }
}

/// The unknowns whose blocks are the states of `sol` at the segments'
/// first nodes (a solution's recorded node `k` is grid node `k`; segments
/// never start at an anchor, where a recorded state is after its loads),
/// with the base block `base`.
fn from_nodes<'a>(
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: Loads,
    steps: usize,
    starts: &[usize],
    base: &[f64],
    sol: &Solution,
) -> Result<(MultipleShooting<'a>, Vec<f64>)> {
    let charts: Vec<Quaternion<f64>> = starts
        .iter()
        .map(|&k| *UnitQuaternion::from_matrix(&sol.rotations[k]).quaternion())
        .collect();
    let ms = MultipleShooting::new(robot, inputs, loads, steps, starts, charts)?;
    let (na, len) = (robot.actuators.len(), robot.body.length);
    let mut x = vec![0.0; ms.dim()];
    x[..6 + na].copy_from_slice(&base[..6 + na]);
    let mut o = 6 + na;
    for &k in &starts[1..] {
        for j in 0..3 {
            x[o + j] = sol.positions[k][j] / len;
            x[o + 6 + j] = sol.nu[k][j];
            x[o + 9 + j] = sol.omega[k][j] * len;
        }
        for i in 0..na {
            x[o + 12 + i] = sol.elongation_profile[(k, i)] / len;
            x[o + 12 + na + i] = base[6 + i];
        }
        o += 12 + 2 * na;
    }
    Ok((ms, x))
}

/// The straight reference configuration sampled at every grid node, as a
/// solution's nodes (for [`from_nodes`]): `p = s e_z`, identity rotations,
/// the reference strains, no elongation.
fn reference_nodes(robot: &Robot, steps: usize, base: &[f64]) -> Result<Solution> {
    let grid = crate::rod::Grid::new(robot, steps);
    let body = &robot.body;
    let na = robot.actuators.len();
    let mut nodes = FlatNodes::default();
    let mut y = vec![0.0; BASE_STATES + na];
    y[3] = 1.0;
    y[7..10].copy_from_slice(body.nu_star.as_slice());
    y[10..13].copy_from_slice(body.omega_star.as_slice());
    for k in 0..=grid.tip() {
        let s = grid.s(k);
        y[2] = s * body.nu_star[2];
        nodes.push(s, &y);
    }
    nodes.n = y.len();
    let ivp = crate::rod::IvpResult {
        tip: crate::rod::RodState::from_slice(&y),
        elongation: vec![0.0; na],
        tip_force_residual: Default::default(),
        tip_moment_residual: Default::default(),
        nodes: Vec::new(),
    };
    let loads = Loads::of(robot);
    let tau = vec![0.0; na];
    let r = vec![0.0; 6 + na];
    let counts = (steps, 0, 0);
    let inputs = vec![0.0; na];
    Ok(assemble_flat(
        robot,
        (&inputs, &loads, base),
        counts,
        r,
        (ivp, nodes),
        tau,
    ))
}

/// The Newton options of a forward solve.
pub fn newton_options(opts: &SolveOptions) -> NleqOptions {
    NleqOptions {
        tol: opts.tol,
        max_iterations: opts.max_iter,
        max_work: opts.max_evaluations as f64,
        deadline: opts.time_limit.map(|t| std::time::Instant::now() + t),
        ..Default::default()
    }
}

/// The [`Solution`] at the converged unknowns `x` of `ms`: each segment
/// integrated once more from its block, its nodes recorded.
pub(crate) fn assemble(
    ms: &MultipleShooting<'_>,
    x: &[f64],
    (iterations, evaluations): (usize, usize),
) -> Result<Solution> {
    let (robot, na) = (ms.robot(), ms.robot().actuators.len());
    let mut nodes = FlatNodes::default();
    let mut elongation = vec![0.0; na];
    let mut last = None;
    let mut tau0 = Vec::new();
    for k in 0..ms.segments() {
        let (y, tau) = ms.block(x, k)?;
        let spec = ms.loads().ivp(robot, &tau, ms.steps());
        let ivp = spec.integrate_stretch_recorded(ms.stretch(k), &y, &mut nodes)?;
        for i in (0..na).filter(|&i| ms.records(i) == k) {
            elongation[i] = ivp.elongation[i];
        }
        if k == 0 {
            tau0 = tau;
        }
        last = Some(ivp);
    }
    let mut ivp = last.expect("at least one segment");
    ivp.elongation = elongation;
    let mut f = vec![0.0; ms.dim()];
    let mut probe = ms.clone_unworked();
    probe.residual(x, &mut f)?;
    let r = ms.tip_rows(&f);
    let base = &x[..6 + na];
    Ok(assemble_flat(
        robot,
        (ms.inputs(), &ms.loads(), base),
        (ms.steps(), iterations, evaluations),
        r,
        (ivp, nodes),
        tau0,
    ))
}

/// Solve the forward problem of `robot` at `inputs` under `loads` by
/// multiple shooting (see the module docs).
pub fn solve(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Result<Solution> {
    let nopts = newton_options(opts);
    let mut base = super::guess::initial_guess(robot, inputs, warm);
    if warm.is_none() {
        super::guess::linear_guess(robot, inputs, loads, &mut base);
    }
    let starts = segment_starts(robot, loads, opts.steps);
    let (ms, x0) = first_guess(robot, inputs, *loads, opts.steps, (&starts, &base), warm)?;
    let mut sys = ShootingSystem::new(ms)?;
    // the direct solve is the continuation's first step, the whole path at
    // once: it hands over as a corrector does, when it needs damping below
    // the corrector's limit
    let dopts = NleqOptions {
        lambda_min: super::arclength::CORRECTOR_LAMBDA_MIN,
        ..nopts.clone()
    };
    let direct = nleq::solve(&mut sys, &x0, &dopts, "forward shooting");
    let (x, iterations, residual) = match direct {
        Ok(out) => (out.x, out.iterations, out.residual),
        Err(e) if !continues(&e) => return Err(e),
        Err(_) => {
            let spent = sys.ms.work;
            let (x, charts, path) = continued(robot, inputs, loads, opts, warm, spent)?;
            let mut ms = MultipleShooting::new(robot, inputs, *loads, opts.steps, &starts, charts)?;
            ms.work = spent + path.work;
            let mut sol = assemble(&ms, &x, (path.steps, ms.work.ceil() as usize))?;
            sol.residual = path.residual;
            return Ok(sol);
        }
    };
    let work = sys.ms.work.ceil() as usize;
    let mut sol = assemble(&sys.ms, &x, (iterations, work))?;
    sol.residual = residual;
    Ok(sol)
}

/// Whether a failed Newton solve hands over to continuation (not for
/// invalid input, an interrupt, or a spent budget).
fn continues(e: &crate::error::Error) -> bool {
    use crate::error::{Error, StopReason};
    !matches!(
        e,
        Error::InvalidParameter { .. }
            | Error::InvalidInput { .. }
            | Error::Interrupted
            | Error::NotConverged {
                stop: StopReason::Budget,
                ..
            }
    )
}

/// The solution at `inputs` under `loads` by pseudo-arclength continuation
/// from the unloaded body at rest (cold) or from `warm`'s inputs and loads;
/// its unknowns (on the segments of [`segment_starts`]), their rotation
/// charts and the path.
pub fn continued(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    warm: Option<&Solution>,
    spent: f64,
) -> Result<(Vec<f64>, Vec<Quaternion<f64>>, super::arclength::Path)> {
    use super::arclength::{follow, ArclengthOptions};
    use super::homotopy::{unloaded, Endpoint, LoadPath};
    let to = Endpoint::loaded(robot, inputs, *loads);
    // the target's segments: the path's loads are largest there
    let starts = segment_starts(robot, loads, opts.steps);
    let (ms, x0, from) = match warm {
        Some(w) => {
            let from = Endpoint::loaded(robot, &w.inputs, w.loads);
            let base = (&starts[..], &w.unknowns[..]);
            let (ms, x0) = first_guess(robot, &w.inputs, w.loads, opts.steps, base, Some(w))?;
            (ms.charts().to_vec(), x0, from)
        }
        None => {
            let free = unloaded(robot);
            let reference = robot.reference_inputs();
            let base = super::guess::initial_guess(robot, &reference, None);
            let none = Loads::of(&free);
            let (ms, x0) =
                MultipleShooting::chained(&free, &reference, none, opts.steps, &starts, &base)?;
            (ms.charts().to_vec(), x0, Endpoint::unloaded(robot))
        }
    };
    let mut path = LoadPath::new(robot, (from, to), opts.steps, starts, ms.clone());
    let aopts = ArclengthOptions {
        tol: opts.tol,
        max_work: (opts.max_evaluations as f64 - spent).max(1.0),
        deadline: opts.time_limit.map(|t| std::time::Instant::now() + t),
        ..Default::default()
    };
    let out = follow(&mut path, &x0, 0.0, 1.0, &aopts, false)?;
    let end = out.points.last().expect("a path ends at a point");
    Ok((end.x.clone(), ms, out))
}

#[doc(hidden)]
pub fn first_guess_pub<'a>(
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: Loads,
    steps: usize,
    base: &[f64],
) -> Result<(MultipleShooting<'a>, Vec<f64>)> {
    let starts = segment_starts(robot, &loads, steps);
    first_guess(robot, inputs, loads, steps, (&starts, base), None)
}
