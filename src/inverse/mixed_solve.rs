//! The blocked-tip solve: the damped Newton method NLEQ-ERR
//! ([`crate::solve::nleq`]) on the bordered multiple-shooting system
//! ([`super::mixed`]) from a forward solution; where it fails,
//! pseudo-arclength continuation ([`crate::solve::arclength`]) of the
//! free-tip equilibrium in the extra unknown toward the bordered system's
//! linear prediction of the contact, and Newton again from there.

use nalgebra::Quaternion;

use super::blocked::{Block, BlockedResult};
use super::mixed::{Blocked, Contact, Extra};
use super::Groups;
use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{Solution, SolveOptions, Status};
use crate::solve::arclength::{follow, ArclengthOptions, ParametrisedSystem, Predictor};
use crate::solve::forward::{assemble, continues, first_guess, newton_options};
use crate::solve::ms::MultipleShooting;
use crate::solve::nleq::{self, NonlinearSystem};
use crate::solve::segments::segment_starts;

/// The first guess of a blocked solve: a forward solution (its states at
/// the segments' nodes, [`first_guess`]), or base unknowns (`nu(0)`,
/// `L omega(0)`, `d / L`, integrated segment by segment).
pub(crate) enum Guess<'s> {
    Solution(&'s Solution),
    Base(Vec<f64>),
}

/// The robot, the actuation map and the block of a blocked solve.
pub(crate) type Problem<'a> = (&'a Robot, &'a Groups, &'a Block);

/// A converged blocked solve: the unknowns `(x, lambda)`, the system's
/// segments and charts, and whether Newton stopped at the rounding floor.
struct Converged {
    z: Vec<f64>,
    starts: Vec<usize>,
    charts: Vec<Quaternion<f64>>,
    at_floor: bool,
}

/// The blocked tip of `problem` with the extra unknown `extra`, from the
/// guess `start` at the scaled extra unknown `lambda0` (a forward solution,
/// its tip off the block, or a predictor's base unknowns), with `spent`
/// iterations and IVPs before it: segments placed for the loads at `lambda0`, Newton on
/// the bordered system ([`solve_on`]), then, if the loads at the root need
/// other segments (a contact force raises the axial tension: the growth
/// bound of [`segment_starts`]), Newton once more on those from the root,
/// whose force is the same to the tolerance, so that the segments placed
/// for it are final. The solution is assembled at the root and carries the
/// block's verdict; a guessed solution's IVPs are counted.
pub(crate) fn mixed_solve(
    problem: Problem<'_>,
    extra: Extra,
    start: Guess<'_>,
    lambda0: f64,
    opts: &SolveOptions,
    solver: &'static str,
    mut spent: (usize, f64),
) -> Result<BlockedResult> {
    let (robot, groups, block) = problem;
    if let Guess::Solution(s) = &start {
        (spent.0, spent.1) = (spent.0 + s.iterations, spent.1 + s.evaluations as f64);
    }
    let mut done = solve_on(problem, &extra, &start, lambda0, opts, solver, &mut spent)?;
    let n = done.z.len() - 1;
    let probe = Blocked::new(problem, extra.clone(), opts.steps, vec![0], vec![]);
    let (inputs, loads, _) = probe.problem(done.z[n])?;
    let starts = segment_starts(robot, &loads, opts.steps);
    if starts != done.starts {
        let mut ms = MultipleShooting::new(
            robot,
            &inputs,
            loads,
            opts.steps,
            &done.starts,
            done.charts.clone(),
        )?;
        let at_root = assemble(&mut ms, &done.z[..n], (0, 0))?;
        spent.1 += 1.0;
        let guess = Guess::Solution(&at_root);
        done = solve_on(problem, &extra, &guess, done.z[n], opts, solver, &mut spent)?;
    }
    let n = done.z.len() - 1;
    let (inputs, loads, force) = probe.problem(done.z[n])?;
    let mut ms =
        MultipleShooting::new(robot, &inputs, loads, opts.steps, &done.starts, done.charts)?;
    // the solution's profile: one more IVP, counted
    let evaluations = (spent.1 + 1.0).ceil() as usize;
    let mut sol = assemble(&mut ms, &done.z[..n], (spent.0, evaluations))?;
    sol.floor = ms.rounding_floor(&done.z[..n]);
    sol.status = match done.at_floor {
        true => Status::ConvergedAtFloor,
        false => Status::Converged,
    };
    let res = BlockedResult {
        solution: sol,
        force,
        variables: groups.vars(&inputs),
        evaluations,
        iterations: spent.0,
        stability: None,
    };
    block.check(robot, res)
}

/// Newton on the bordered system on the segments of the loads at
/// `lambda0`, from `start`'s states; where it fails, [`continued`].
/// `spent`: iterations and IVPs so far, incremented.
fn solve_on(
    problem: Problem<'_>,
    extra: &Extra,
    start: &Guess<'_>,
    lambda0: f64,
    opts: &SolveOptions,
    solver: &'static str,
    spent: &mut (usize, f64),
) -> Result<Converged> {
    let robot = problem.0;
    let probe = Blocked::new(problem, extra.clone(), opts.steps, vec![0], vec![]);
    let (inputs, loads, _) = probe.problem(lambda0)?;
    let starts = segment_starts(robot, &loads, opts.steps);
    let (base, warm) = match start {
        Guess::Solution(s) => (&s.unknowns[..], Some(*s)),
        Guess::Base(b) => (&b[..], None),
    };
    let (ms, x0) = first_guess(robot, &inputs, loads, opts.steps, (&starts, base), warm)?;
    if warm.is_none() && starts.len() > 1 {
        spent.1 += 1.0; // the chained integration of the base unknowns
    }
    let charts = ms.charts().to_vec();
    drop(ms);
    let mut sys = Blocked::new(problem, extra.clone(), opts.steps, starts, charts);
    let mut z0 = x0;
    z0.push(lambda0);
    let nopts = newton_options(opts);
    let out = nleq::solve(&mut Contact { sys: &mut sys }, &z0, &nopts, solver);
    let out = match out {
        Ok(out) => Ok(out),
        Err(e) if !continues(&e) => {
            spent.1 += sys.work();
            return Err(e);
        }
        Err(e) => continued(&mut sys, z0, opts, solver, e).map(|(out, steps)| {
            spent.0 += steps;
            out
        }),
    };
    spent.1 += sys.work();
    let out = out.map_err(|e| with_work(e, spent.1))?;
    spent.0 += out.iterations;
    Ok(Converged {
        z: out.x,
        starts: sys.starts().to_vec(),
        charts: sys.charts().to_vec(),
        at_floor: out.status == nleq::Status::ConvergedAtFloor,
    })
}

/// `e` with `evaluations` IVPs (all of the blocked solve's work).
fn with_work(e: Error, evaluations: f64) -> Error {
    match e {
        Error::NotConverged {
            solver,
            iterations,
            residual,
            stop,
            reason,
            ..
        } => Error::NotConverged {
            solver,
            iterations,
            evaluations: evaluations.ceil() as usize,
            residual,
            stop,
            reason,
        },
        e => e,
    }
}

/// The fallback of a failed Newton run from `z0 = (x0, lambda0)` (`failed`
/// its error): rounds of pseudo-arclength continuation of the free-tip
/// equilibrium `G(x, lambda) = 0` from the last point to the `lambda` that
/// the bordered system predicts for the contact there (its first Newton
/// step; for the variable, within its range), each followed by Newton on
/// the bordered system from the path's end. Each round starts on the
/// equilibrium branch, so its prediction is Newton's from a point of `G =
/// 0`, where only the contact condition is off; at most `opts.max_iter`
/// rounds. The converged solve and the continuation steps taken.
fn continued(
    sys: &mut Blocked<'_>,
    z0: Vec<f64>,
    opts: &SolveOptions,
    solver: &'static str,
    failed: Error,
) -> Result<(nleq::NleqResult, usize)> {
    let n = z0.len() - 1;
    let (lo, hi) = sys.domain();
    let (mut x, mut lambda) = (z0[..n].to_vec(), z0[n]);
    let (mut steps, mut last) = (0, failed);
    let work0 = sys.work();
    for _ in 0..opts.max_iter.max(1) {
        let left = opts.max_evaluations as f64 - (sys.work() - work0);
        if left <= 0.0 {
            break;
        }
        // the contact's linear prediction from (x, lambda)
        let mut z: Vec<f64> = x.iter().copied().chain([lambda]).collect();
        let (mut f, mut dz) = (vec![0.0; n + 1], vec![0.0; n + 1]);
        let mut contact = Contact { sys: &mut *sys };
        let predicted = contact
            .linearise(&z, &mut f)
            .and_then(|_| contact.solve(&f, &mut dz));
        match predicted {
            Ok(true) => {}
            Ok(false) => break,
            Err(e) if !continues(&e) => return Err(e),
            Err(e) => {
                last = e;
                break;
            }
        }
        let target = (lambda - dz[n]).clamp(lo, hi);
        if !target.is_finite() || target == lambda {
            break;
        }
        let aopts = ArclengthOptions {
            tol: opts.tol,
            predictor: Predictor::Hermite,
            corrector_iterations: opts
                .max_iter
                .min(crate::solve::arclength::CORRECTOR_ITERATIONS),
            max_work: left,
            deadline: opts.time_limit.map(|t| std::time::Instant::now() + t),
            // the path's span in lambda is one unit of the arclength norm,
            // as the homotopies' `[0, 1]`
            lambda_weight: 1.0 / (target - lambda).abs().max(f64::MIN_POSITIVE),
            ..Default::default()
        };
        let path = match follow(sys, &x, lambda, target, &aopts, false) {
            Ok(path) => path,
            Err(e) => {
                last = e;
                break;
            }
        };
        steps += path.steps;
        let end = path.points.last().expect("a path ends at a point");
        (x, lambda) = (end.x.clone(), end.lambda);
        z.copy_from_slice(&x.iter().copied().chain([lambda]).collect::<Vec<_>>());
        let nopts = nleq::NleqOptions {
            max_work: (opts.max_evaluations as f64 - (sys.work() - work0)).max(f64::MIN_POSITIVE),
            ..newton_options(opts)
        };
        match nleq::solve(&mut Contact { sys: &mut *sys }, &z, &nopts, solver) {
            Ok(out) => return Ok((out, steps)),
            Err(e) if !continues(&e) => return Err(e),
            Err(e) => last = e,
        }
    }
    Err(last)
}
