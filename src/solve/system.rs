//! The shooting residual as a Newton [`System`] (coarse-grid, then
//! full-grid exact Jacobians; the onset side of slack laws), the work and
//! budget carried through a solve, and one Newton run of a forward problem.

use std::time::Instant;

use nalgebra::DMatrix;

use super::newton::{newton_from, NewtonOptions, NewtonResult, System};
use super::options::SolveOptions;
use super::residual::{
    residual_scales, scaled_residual, taut_step, tensions, Loads, Shot, SlackTangent,
};
pub(crate) use super::solution::solution_from;
use crate::error::{Error, Result};
use crate::rod::{FlatNodes, IvpResult, Robot};
use crate::stability::{verdict_pass, Equilibrium, VerdictPass};

/// The residual, IVP and tensions \[N\] of one evaluation (at the point
/// Newton returns, they serve as the solution's profile), and the
/// stability verdict's tangent integration if it was taken there
/// ([`Keep::Verdict`]).
pub(crate) struct FinalIvp {
    /// Scaled residual.
    pub residual: Vec<f64>,
    /// The IVP (no node list).
    pub ivp: IvpResult,
    /// Its nodes, recorded flat: a plain IVP's if asked for ([`Keep`]), a
    /// stability verdict's pass's always.
    pub nodes: Option<FlatNodes>,
    /// Actuator tensions \[N\].
    pub tensions: Vec<f64>,
    /// The verdict's recorded tangent integration whose real part `ivp` is.
    pub verdict: Option<Box<VerdictPass>>,
}

/// What a [`Shooting`] records of its residual evaluations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Keep {
    /// Nothing but the tip (`false`).
    Tip,
    /// The nodes of every plain IVP (`true`): the last one is the
    /// solution's profile.
    Nodes,
    /// The tip only, except where the residual is predicted to pass
    /// Newton's test against the tolerance `tol` (see
    /// [`Shooting::predicts_convergence`]): there the residual comes from
    /// the stability verdict's recorded tangent integration
    /// ([`crate::stability`]), whose real part is the plain IVP's arithmetic
    /// bit for bit, so Newton's path is the same; if Newton stops there, the
    /// verdict and the solution's profile need no further IVP.
    Verdict {
        /// Newton's tolerance on `max |r|`.
        tol: f64,
        /// Whether the plain IVPs record their nodes too (for a solution
        /// refined by the accuracy control, which reads the recorded one).
        nodes: bool,
    },
}

impl Keep {
    /// This without the nodes of plain IVPs.
    pub(crate) fn tip_only(self) -> Keep {
        match self {
            Keep::Nodes => Keep::Tip,
            Keep::Verdict { tol, .. } => Keep::Verdict { tol, nodes: false },
            k => k,
        }
    }
}

impl From<bool> for Keep {
    fn from(nodes: bool) -> Self {
        if nodes {
            Keep::Nodes
        } else {
            Keep::Tip
        }
    }
}

/// The shooting residual of one forward problem as a Newton [`System`]:
/// plain IVPs for residuals, tangent IVPs for the exact Jacobian. Counts
/// every IVP (failed ones too) and keeps the last residual evaluation (at
/// the point Newton returns, it can serve as the solution's profile).
pub struct Shooting<'a> {
    shot: Shot<'a>,
    keep: Keep,
    /// IVPs integrated (plain and tangent).
    pub evaluations: usize,
    /// Tangent IVPs among them.
    pub tangent_evaluations: usize,
    /// RK4 steps of the Newton Jacobian: a tenth of `steps` (at least
    /// [`COARSE_JACOBIAN_MIN_STEPS`]) until [`System::refine`] switches to
    /// the exact Jacobian of the full grid (`None`).
    jacobian_steps: Option<usize>,
    /// The unknowns and the last residual evaluation.
    last: Option<(Vec<f64>, FinalIvp)>,
    /// `max |r|` of the last two residual evaluations (older first).
    norms: [f64; 2],
    /// The unknowns of the last two Jacobians (newest last) and whether
    /// each had an actuator at its onset of tension (see `refine`).
    onsets: Vec<(Vec<f64>, bool)>,
    /// Smallest `max |r|` of its residual evaluations.
    best_norm: f64,
    /// The full grid's Jacobian is taken ([`System::refine`]) only once
    /// `best_norm` is at or below this (see `Work::refine_within`).
    refine_within: f64,
    /// Take the slack side's derivative at an onset (see [`crate::solve::residual::tension_slope`]).
    slack_onset: bool,
    /// The unknowns of the last Jacobian and its slack actuators' taut pieces.
    slack_tangents: (Vec<f64>, Vec<SlackTangent>),
}

/// Fewest RK4 steps of the coarse-grid Newton Jacobian (below ten times
/// this, the Jacobian is taken on the full grid).
pub const COARSE_JACOBIAN_MIN_STEPS: usize = 10;

impl<'a> Shooting<'a> {
    /// The system of `robot` at `inputs` under `loads` on `steps` RK4 steps;
    /// `keep`: what its residual evaluations record ([`Keep`], or a bool:
    /// the nodes or not).
    pub fn new(
        robot: &'a Robot,
        inputs: &'a [f64],
        loads: &'a Loads,
        steps: usize,
        keep: impl Into<Keep>,
    ) -> Self {
        let coarse = steps / 10;
        let jacobian_steps = if coarse >= COARSE_JACOBIAN_MIN_STEPS {
            Some(coarse)
        } else {
            None
        };
        Shooting {
            shot: Shot::new(robot, inputs, loads, steps),
            keep: keep.into(),
            evaluations: 0,
            tangent_evaluations: 0,
            jacobian_steps,
            last: None,
            norms: [f64::INFINITY; 2],
            best_norm: f64::INFINITY,
            refine_within: f64::INFINITY,
            onsets: Vec::with_capacity(2),
            slack_onset: false,
            slack_tangents: (Vec::new(), Vec::new()),
        }
    }
    /// The last residual evaluation if it was at `x`.
    pub(crate) fn take_last(&mut self, x: &[f64]) -> Option<FinalIvp> {
        match self.last.take() {
            Some((xl, last)) if xl == x => Some(last),
            _ => None,
        }
    }

    /// Whether the residual at `x` is predicted to pass Newton's test
    /// `max |r| <= max(tol, floor)`: the linear contraction of the last two
    /// evaluations, `|r_k| ~ |r_(k-1)|^2 / |r_(k-2)|`. Newton's and the
    /// chord iteration's convergence is at least linear near a root, so
    /// this errs late rather than early (on the four fixtures of
    /// `tests/stability_policy.rs`, cold and warm, it predicts the last
    /// evaluation in seven runs out of eight and never a point that fails;
    /// the eighth converges in one quadratic step from its first residual,
    /// with no rate to go on). A wrong prediction costs a tangent IVP for
    /// a plain one; a missed one, the verdict's own integration.
    pub fn predicts_convergence(&self, x: &[f64], tol: f64) -> bool {
        let [older, newer] = self.norms;
        let predicted = newer * (newer / older);
        older.is_finite() && older > 0.0 && predicted <= tol.max(self.floor(x, &[]))
    }

    /// Set the `max |r|` history that [`Shooting::predicts_convergence`]
    /// extrapolates from (older first) in place of this system's own last
    /// two evaluations: the coarse-grid pre-solve's full-grid rounds
    /// ([`crate::solve::presolve`]) have their own estimates.
    pub(crate) fn set_history(&mut self, older: f64, newer: f64) {
        self.norms = [older, newer];
    }

    /// Predict that the next evaluation converges (a history whose
    /// extrapolation [`Shooting::predicts_convergence`] is zero): for a run
    /// that knows its next full-grid IVP is normally its last.
    pub(crate) fn expect_convergence(&mut self) {
        self.set_history(1.0, 0.0);
    }

    /// Change what the next residual evaluations record.
    pub(crate) fn set_keep(&mut self, keep: Keep) {
        self.keep = keep;
    }

    /// The residual at `x` from a plain IVP.
    fn plain(&self, x: &[f64]) -> Result<FinalIvp> {
        let record = matches!(self.keep, Keep::Nodes | Keep::Verdict { nodes: true, .. });
        let (residual, ivp, tensions, nodes) = match record {
            true => {
                let (r, ivp, tau, nodes) = self.shot.residual_flat(x)?;
                (r, ivp, tau, Some(nodes))
            }
            false => {
                let (r, ivp, tau) = self.shot.residual(x, false)?;
                (r, ivp, tau, None)
            }
        };
        Ok(FinalIvp {
            residual,
            ivp,
            nodes,
            tensions,
            verdict: None,
        })
    }

    /// The residual at `x` from the stability verdict's recorded tangent
    /// integration ([`crate::stability`]), whose real part is the plain IVP:
    /// the tensions and the residual's arithmetic are [`Shot::residual`]'s.
    fn with_verdict(&self, x: &[f64]) -> Result<FinalIvp> {
        let robot = self.shot.robot;
        let len = robot.body.length;
        let na = robot.actuators.len();
        let delta: Vec<f64> = x[6..6 + na].iter().map(|d| d * len).collect();
        let tau = tensions(robot, self.shot.inputs, &delta)?;
        let eq = Equilibrium {
            along: None,
            unknowns: x,
            inputs: self.shot.inputs,
            loads: *self.shot.loads,
            steps: self.shot.steps,
        };
        let (pass, ivp) = verdict_pass(robot, &eq, &tau)?;
        let r = scaled_residual(robot, &ivp, &delta);
        Ok(FinalIvp {
            residual: r,
            ivp,
            nodes: Some(pass.ivp_nodes()),
            tensions: tau,
            verdict: Some(Box::new(pass)),
        })
    }
}

impl System for Shooting<'_> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        self.evaluations += 1;
        let last = match self.keep {
            Keep::Verdict { tol, .. } if self.predicts_convergence(x, tol) => {
                self.tangent_evaluations += 1;
                match self.with_verdict(x) {
                    Ok(last) => last,
                    Err(Error::Interrupted) => return Err(Error::Interrupted),
                    // (the verdict's pass failed where the plain IVP may
                    // not: the plain one, counted too)
                    Err(_) => {
                        self.evaluations += 1;
                        self.plain(x)?
                    }
                }
            }
            _ => self.plain(x)?,
        };
        let r = last.residual.clone();
        let norm = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        self.norms = [self.norms[1], norm];
        self.best_norm = self.best_norm.min(norm);
        self.last = Some((x.to_vec(), last));
        Ok(r)
    }
    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        self.evaluations += 1;
        self.tangent_evaluations += 1;
        // the tangents of a grid of a tenth of the steps: a tenth of the cost,
        // and a Jacobian within RK4's coarse-grid error (~1e-4) of the exact
        // one, which Newton's convergence test on the full grid absorbs in a
        // chord step or two; the full-grid Jacobian after a failed line search
        let steps = self.jacobian_steps.unwrap_or(self.shot.steps);
        let out = self
            .shot
            .with_steps(steps)
            .jacobian_side(x, false, self.slack_onset, true);
        let (((r, j, _, _), onset), slack) = match out {
            // the coarse grid does not resolve the design (RK4 is unstable
            // where a step exceeds ~2.8 of the shortest length of the rod's
            // ODE, e.g. the bending length `sqrt(EI / tau)` of a soft body
            // pulled by a strong tendon: at a 2.3 mm bending length and a
            // 7.3 mm coarse step the tangent IVP overflows):
            // the full grid's exact Jacobian from now on
            Err(Error::Integration { .. }) if self.jacobian_steps.take().is_some() => {
                self.evaluations += 1;
                self.tangent_evaluations += 1;
                self.shot.jacobian_side(x, false, self.slack_onset, true)?
            }
            out => out?,
        };
        if self.onsets.len() == 2 {
            self.onsets.remove(0);
        }
        self.onsets.push((x.to_vec(), onset));
        self.slack_tangents = (x.to_vec(), slack);
        Ok((r, j))
    }
    fn limit_step(&self, x: &[f64], dx: &[f64], r: &[f64], jac: &DMatrix<f64>) -> Option<Vec<f64>> {
        let (robot, inputs) = (self.shot.robot, self.shot.inputs);
        let (at, slack) = &self.slack_tangents;
        let taut = (at.as_slice() == x).then(|| taut_step(robot.body.length, slack, x, dx, r, jac));
        match taut
            .flatten()
            .or_else(|| super::limit::piece_step(robot, inputs, x, dx, r, jac))
        {
            Some(d) => super::limit::limited_step(robot, inputs, x, &d)
                .or_else(|| Some(x.iter().zip(&d).map(|(a, b)| a + b).collect())),
            None => super::limit::limited_step(robot, inputs, x, dx),
        }
    }
    /// First the full grid's Jacobian; then, if an actuator was at its
    /// onset of tension, the slack side's derivative there (see
    /// [`crate::solve::residual::tension_slope`]). The onset is that of
    /// the Jacobian at `x`, if one of the last two was taken there, else
    /// of the last one: a watchdog's Jacobian at its trial point must not
    /// hide the current point's onset (a cold guess with a tendon exactly
    /// at its onset would otherwise keep the taut side's derivative, on
    /// which the line search fails, and reach the slack side's only after
    /// more failed line searches).
    fn refine(&mut self, x: &[f64]) -> bool {
        if self.jacobian_steps.is_some() && self.best_norm <= self.refine_within {
            self.jacobian_steps = None;
            return true;
        }
        let at_onset = match self.onsets.iter().rev().find(|(p, _)| p == x) {
            Some((_, onset)) => *onset,
            None => self.onsets.last().is_some_and(|(_, onset)| *onset),
        };
        if at_onset && !self.slack_onset {
            self.slack_onset = true;
            return true;
        }
        false
    }
    /// `4 eps max(fs (k_nu |nu| + |F| + sum |tau|), ms (k_omega |omega| L + |M| + sum |r_i| |tau_i|))`:
    /// the rounding of the largest terms of the tip balance (32)-(33),
    /// `K (strain - strain*)` with strains of order one, in the scaled
    /// residual. (For a steel rod `EA L^2 / EI` makes this ~1e-9.)
    fn floor(&self, x: &[f64], _r: &[f64]) -> f64 {
        let robot = self.shot.robot;
        let (kse, kbt) = robot.body.stiffness();
        let (fs, ms) = residual_scales(robot);
        let len = robot.body.length;
        let tau: &[f64] = match &self.last {
            Some((_, last)) => &last.tensions,
            None => &[],
        };
        let vmax = x[0].abs().max(x[1].abs()).max(x[2].abs());
        let umax = x[3].abs().max(x[4].abs()).max(x[5].abs()) / len;
        let st: f64 = tau.iter().map(|t| t.abs()).sum();
        let srt: f64 = robot
            .actuators
            .iter()
            .zip(tau)
            .map(|(a, t)| a.routing.eval(len).0.norm() * t.abs())
            .sum();
        let f = fs * (kse.max() * vmax + self.shot.loads.tip_force.amax() + st);
        let m = ms * (kbt.max() * umax * len + self.shot.loads.tip_moment.amax() + srt);
        4.0 * f64::EPSILON * f.max(m)
    }
    fn evaluations(&self) -> usize {
        self.evaluations
    }
}

/// Work counters carried through a solve and its fallbacks, and the solve's
/// budget.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Work {
    pub iterations: usize,
    pub evaluations: usize,
    /// IVP budget of the whole solve (0: none).
    pub max_evaluations: usize,
    /// Deadline of the whole solve.
    pub deadline: Option<Instant>,
    /// Stall window of the next Newton runs (see
    /// [`NewtonOptions::stall_window`]).
    pub stall_window: usize,
    /// The next Newton runs take the full grid's Jacobian after a failed
    /// line search only once their `max |r|` has come to this.
    pub refine_within: f64,
    /// The next pre-solve is a cold solve's direct run: if its first coarse
    /// Newton run fails, the run fails with it (no full-grid Newton from
    /// the guess; see [`crate::solve::presolve`]).
    pub cold_direct: bool,
}

impl Work {
    /// Counters at zero and the budget of `opts` from now.
    pub fn start(opts: &SolveOptions) -> Self {
        Work {
            max_evaluations: opts.max_evaluations,
            deadline: opts.time_limit.map(|t| Instant::now() + t),
            stall_window: STALL_WINDOW,
            refine_within: f64::INFINITY,
            ..Default::default()
        }
    }
    fn add(&mut self, sys: &Shooting<'_>, iterations: usize) {
        self.iterations += iterations;
        self.evaluations += sys.evaluations;
    }
    /// Whether the budget is spent.
    pub fn exhausted(&self) -> bool {
        (self.max_evaluations > 0 && self.evaluations >= self.max_evaluations)
            || self.deadline.is_some_and(|d| Instant::now() >= d)
    }
    /// The Newton options of one run within the remaining budget.
    pub(crate) fn newton_options(&self, opts: &SolveOptions) -> NewtonOptions {
        let max_evaluations = if self.max_evaluations == 0 {
            usize::MAX
        } else {
            self.max_evaluations.saturating_sub(self.evaluations)
        };
        NewtonOptions {
            max_evaluations,
            deadline: self.deadline,
            stall_window: self.stall_window,
            ..opts.newton()
        }
    }
}

/// Stall window of a forward solve's direct Newton run (see
/// [`NewtonOptions::stall_window`]; 0: off): 3. A direct run whose damped
/// steps creep (no halving of `max |f|` over 3 of them) hands over to
/// continuation, whose correctors are cheap
/// ([`crate::solve::continuation::HOMOTOPY_STALL_WINDOW`]); without a
/// window a creeping run can take tens of iterations at `t ~ 1e-5`, each
/// an IVP per halving of its line search. A longer window sends fewer
/// solves to continuation but lets more runs creep. A tuning constant,
/// chosen by experiment on the tuning seed
/// ([`crate::problems::TUNING_SEED`]) of the design benchmark
/// (`benches/designs.rs`), with the homotopy's window.
pub const STALL_WINDOW: usize = 3;

/// Newton shooting from `x0`; returns the Newton result and the IVP at its
/// solution (if it was the last one integrated). Adds the work to `work`
/// (also on failure).
#[allow(clippy::too_many_arguments)] // the shooting problem's parts, passed through to `Shooting::new`
pub(crate) fn newton_shooting(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    jac0: Option<&DMatrix<f64>>,
    keep: impl Into<Keep>,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    let mut sys = Shooting::new(robot, inputs, loads, opts.steps, keep);
    sys.refine_within = work.refine_within;
    let nopts = work.newton_options(opts);
    let out = newton_from(&mut sys, x0, &nopts, "forward shooting", jac0);
    settle(&mut sys, out, work)
}

/// Newton's outcome `out` on `sys`: adds its IVPs and iterations to `work`
/// and returns the result with the IVP at the solution, or the error with
/// the solve's work totals (also after earlier attempts).
pub(crate) fn settle(
    sys: &mut Shooting<'_>,
    out: Result<NewtonResult>,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    match out {
        Ok(nr) => {
            work.add(sys, nr.iterations);
            let last = sys.take_last(&nr.x);
            Ok((nr, last))
        }
        Err(Error::NotConverged {
            solver,
            iterations,
            evaluations: _,
            residual,
            stop,
            reason,
        }) => {
            work.add(sys, iterations);
            Err(Error::NotConverged {
                solver,
                iterations: work.iterations,
                evaluations: work.evaluations,
                residual,
                stop,
                reason,
            })
        }
        Err(e) => {
            work.add(sys, 0);
            Err(e)
        }
    }
}
