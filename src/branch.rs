//! Branch following (issue 16): pseudo-arclength continuation of the
//! shooting equilibria in one scalar parameter, through limit points, with
//! folds, bifurcations and the stability of each point; and a sweep that
//! stays on stable equilibria and reports where the physical robot jumps.
//!
//! The path is `y(sigma) = (x, lambda / scale)` with `x` the scaled shooting
//! unknowns of [`crate::shooting`]; each step predicts along the unit tangent
//! `t` (the null vector of `[F_x, F_lambda]`, oriented by `t_prev . t > 0`)
//! and corrects on the hyperplane `t . (y - y_pred) = 0`. A fold (limit point)
//! is a sign change of `d lambda / d sigma`; a bifurcation is a sign change
//! of `det F_x` not explained by a fold, or a change of the stability verdict
//! without a fold (a symmetric double root leaves `det F_x` positive).
//! Events are located by regula falsi on the arclength.

use nalgebra::{DMatrix, DVector, Vector3};

use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{
    assemble, initial_guess, reference_guess, shoot, shoot_jacobian, solve_loaded, Loads, Solution,
    SolveOptions,
};
use crate::solve::newton::{newton, System};
use crate::stability::{stability, Stability};

/// The continuation parameter.
#[derive(Debug, Clone, PartialEq)]
pub enum Parameter {
    /// The inputs of the listed actuators, all set to the parameter
    /// (temperature \[C\], tension \[N\] or pull \[m\]).
    Inputs(Vec<usize>),
    /// Scale [-] of the body's tip force and moment.
    TipLoadScale,
    /// Scale [-] of the body's gravity vector.
    GravityScale,
}

/// The problem at one parameter value: robot, inputs, tip loads.
pub struct Problem<'a> {
    robot: &'a Robot,
    parameter: Parameter,
    inputs: Vec<f64>,
}

impl<'a> Problem<'a> {
    /// `inputs`: the actuator inputs (those named by `Parameter::Inputs` are
    /// overridden by the parameter).
    pub fn new(robot: &'a Robot, parameter: Parameter, inputs: &[f64]) -> Result<Self> {
        robot.validate()?;
        if inputs.len() != robot.actuators.len() {
            return Err(Error::input(
                "inputs",
                format!(
                    "expected {} values, got {}",
                    robot.actuators.len(),
                    inputs.len()
                ),
            ));
        }
        if let Parameter::Inputs(idx) = &parameter {
            if idx.is_empty() {
                return Err(Error::input("parameter", "names no actuator"));
            }
            for &i in idx {
                if i >= robot.actuators.len() {
                    return Err(Error::param(
                        "parameter actuator index",
                        i as f64,
                        format!("0 <= index < {}", robot.actuators.len()),
                    ));
                }
            }
        }
        Ok(Problem {
            robot,
            parameter,
            inputs: inputs.to_vec(),
        })
    }

    /// Robot, inputs and loads at parameter value `lambda`.
    pub fn at(&self, lambda: f64) -> Result<(Robot, Vec<f64>, Loads)> {
        crate::error::finite("parameter", lambda)?;
        let mut robot = self.robot.clone();
        let mut inputs = self.inputs.clone();
        let mut loads = Loads::of(self.robot);
        match &self.parameter {
            Parameter::Inputs(idx) => {
                for &i in idx {
                    inputs[i] = lambda;
                }
            }
            Parameter::TipLoadScale => {
                loads.tip_force *= lambda;
                loads.tip_moment *= lambda;
            }
            Parameter::GravityScale => robot.body.gravity *= lambda,
        }
        robot.check_inputs(&inputs)?;
        Ok((robot, inputs, loads))
    }

    /// Scaled shooting residual at `(x, lambda)`.
    fn residual(&self, x: &[f64], lambda: f64, steps: usize) -> Result<Vec<f64>> {
        let (robot, inputs, loads) = self.at(lambda)?;
        shoot(&robot, &inputs, &loads, x, steps, false).map(|t| t.0)
    }

    /// Equilibrium with its profile at `lambda` from unknowns `x`.
    pub fn assemble(&self, x: &[f64], lambda: f64, steps: usize) -> Result<Solution> {
        let (robot, inputs, loads) = self.at(lambda)?;
        assemble(&robot, &inputs, &loads, x, steps, 0, 0)
    }

    /// Stability verdict of `sol` at `lambda` (free tip).
    pub fn stability(&self, sol: &Solution, lambda: f64) -> Result<Stability> {
        let (robot, ..) = self.at(lambda)?;
        stability(&robot, sol, &[])
    }

    /// Newton solve at fixed `lambda` from `warm` (or cold).
    pub fn solve(
        &self,
        lambda: f64,
        opts: &SolveOptions,
        warm: Option<&Solution>,
    ) -> Result<Solution> {
        let (robot, inputs, loads) = self.at(lambda)?;
        solve_loaded(&robot, &inputs, &loads, opts, warm)
    }
}

/// Options of [`follow_branch`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchOptions {
    /// Parameter value to start from.
    pub start: f64,
    /// Parameter value to reach (the path stops once it leaves the interval
    /// between `start` and `end`).
    pub end: f64,
    /// Initial arclength step, in units of `|end - start|` (the path norm
    /// is that of `(x, lambda / |end - start|)`).
    pub step: f64,
    /// Largest arclength step (same units).
    pub max_step: f64,
    /// Smallest arclength step before giving up.
    pub min_step: f64,
    /// Largest number of points.
    pub max_points: usize,
    /// Stop at the first point that is not stable or lies past a fold (sweep mode).
    pub stop_when_unstable: bool,
    /// Shooting options (grid, tolerance, iterations of each corrector).
    pub solve: SolveOptions,
}

impl Default for BranchOptions {
    fn default() -> Self {
        BranchOptions {
            start: 0.0,
            end: 1.0,
            step: 0.02,
            max_step: 0.1,
            min_step: 1e-6,
            max_points: 500,
            stop_when_unstable: false,
            solve: SolveOptions::default(),
        }
    }
}

impl BranchOptions {
    /// Validate.
    pub fn validate(&self) -> Result<()> {
        crate::error::finite("start", self.start)?;
        crate::error::finite("end", self.end)?;
        if self.start == self.end {
            return Err(Error::param("end", self.end, "!= start"));
        }
        if !(self.min_step > 0.0
            && self.min_step <= self.step
            && self.step <= self.max_step
            && self.max_step.is_finite())
        {
            return Err(Error::param(
                "step",
                self.step,
                "0 < min_step <= step <= max_step < inf",
            ));
        }
        if self.max_points < 2 || self.max_points > 1_000_000 {
            return Err(Error::param(
                "max_points",
                self.max_points as f64,
                "2 <= max_points <= 1e6",
            ));
        }
        self.solve.validate()
    }
}

/// One point of a branch.
#[derive(Debug, Clone)]
pub struct BranchPoint {
    /// Parameter value.
    pub parameter: f64,
    /// The equilibrium (profile included).
    pub solution: Solution,
    /// Its stability.
    pub stability: Stability,
    /// `d lambda / d sigma` (scaled) of the path tangent.
    pub dparameter: f64,
    /// `det F_x`, the determinant of the (scaled) shooting Jacobian at fixed
    /// parameter (exact, from the tangent IVP).
    pub jacobian_det: f64,
}

/// Kind of a located event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EventKind {
    /// Limit point (snap-through when stability is lost there).
    Fold,
    /// Branch point (or a stability change without a fold).
    Bifurcation,
}

/// A located fold or bifurcation.
#[derive(Debug, Clone)]
pub struct Event {
    /// Fold or bifurcation.
    pub kind: EventKind,
    /// Parameter value at the event.
    pub parameter: f64,
    /// Tip position \[m\] at the event.
    pub tip_position: Vector3<f64>,
    /// Index of the branch point just before the event.
    pub after_point: usize,
}

/// A followed branch.
#[derive(Debug, Clone)]
pub struct Branch {
    /// Points in path order.
    pub points: Vec<BranchPoint>,
    /// Located folds and bifurcations, in path order.
    pub events: Vec<Event>,
    /// IVPs integrated.
    pub evaluations: usize,
}

/// Jacobian `[F_x, F_lambda~]` (`m x (m+1)`, scaled lambda) and the
/// residual: `F_x` exact from one tangent IVP, `F_lambda` by a forward
/// difference (one IVP).
fn jacobian(
    pb: &Problem<'_>,
    y: &[f64],
    scale: f64,
    steps: usize,
    evals: &mut usize,
) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let m = y.len() - 1;
    let (robot, inputs, loads) = pb.at(y[m] * scale)?;
    let (r, jx, _, _) = shoot_jacobian(&robot, &inputs, &loads, &y[..m], steps, false)?;
    let mut j = DMatrix::zeros(m, m + 1);
    j.columns_mut(0, m).copy_from(&jx);
    let h = f64::EPSILON.sqrt() * y[m].abs().max(1.0);
    let mut lp = y[m] + h;
    let rp = match pb.residual(&y[..m], lp * scale, steps) {
        Ok(rp) => rp,
        Err(_) => {
            // at the end of an input range: step the other way
            lp = y[m] - h;
            pb.residual(&y[..m], lp * scale, steps)?
        }
    };
    *evals += 2;
    for i in 0..m {
        j[(i, m)] = (rp[i] - r[i]) / (lp - y[m]);
    }
    Ok((r, j))
}

/// Unit tangent: null vector of `j` with `t . prev > 0`.
fn tangent(j: &DMatrix<f64>, prev: &DVector<f64>) -> Option<DVector<f64>> {
    let m = j.nrows();
    let mut a = DMatrix::zeros(m + 1, m + 1);
    a.view_mut((0, 0), (m, m + 1)).copy_from(j);
    a.row_mut(m).copy_from(&prev.transpose());
    let mut b = DVector::zeros(m + 1);
    b[m] = 1.0;
    let t = a.lu().solve(&b)?;
    let n = t.norm();
    (n.is_finite() && n > 0.0).then(|| t / n)
}

/// A converged point: unknowns, Jacobian, tangent and the equilibrium data.
struct Pt {
    y: Vec<f64>,
    t: DVector<f64>,
    bp: BranchPoint,
}

struct Tracer<'a, 'b> {
    pb: &'b Problem<'a>,
    scale: f64,
    opts: BranchOptions,
    evals: usize,
}

impl Tracer<'_, '_> {
    /// Complete a point at `y` (converged): Jacobian, tangent (oriented by
    /// `prev`), profile, stability.
    fn point(&mut self, y: Vec<f64>, prev: &DVector<f64>) -> Result<Pt> {
        let m = y.len() - 1;
        let steps = self.opts.solve.steps;
        let lambda = y[m] * self.scale;
        let (r, j) = jacobian(self.pb, &y, self.scale, steps, &mut self.evals)?;
        let evaluations = self.evals;
        let t = tangent(&j, prev).ok_or_else(|| Error::NotConverged {
            solver: "branch following",
            iterations: 0,
            evaluations,
            stop: crate::error::StopReason::SingularJacobian,
            residual: r.iter().fold(0.0, |a: f64, b| a.max(b.abs())),
            reason: "singular augmented Jacobian (tangent undefined)".into(),
        })?;
        let jacobian_det = j.columns(0, m).into_owned().determinant();
        let solution = self.pb.assemble(&y[..m], lambda, steps)?;
        self.evals += 1;
        let stability = self.pb.stability(&solution, lambda)?;
        self.evals += stability.evaluations;
        let dparameter = t[m];
        Ok(Pt {
            y,
            t,
            bp: BranchPoint {
                parameter: lambda,
                solution,
                stability,
                dparameter,
                jacobian_det,
            },
        })
    }

    /// Corrector from `from` along its tangent by arclength `ds`: Newton on
    /// `[F(y); t . (y - y_pred)] = 0` with the exact `F_x`.
    fn step(&mut self, from: &Pt, ds: f64) -> Result<Pt> {
        crate::solve::cancel::check()?;
        let yp: Vec<f64> = from
            .y
            .iter()
            .zip(from.t.iter())
            .map(|(a, b)| a + ds * b)
            .collect();
        let mut sys = Corrector {
            pb: self.pb,
            scale: self.scale,
            steps: self.opts.solve.steps,
            t: &from.t,
            yp: &yp,
            evaluations: 0,
        };
        let res = newton(&mut sys, &yp, &self.opts.solve.newton(), "branch following");
        self.evals += sys.evaluations;
        let nr = res?;
        self.point(nr.x, &from.t)
    }
}

/// The pseudo-arclength corrector as a Newton system.
struct Corrector<'a, 'b> {
    pb: &'b Problem<'a>,
    scale: f64,
    steps: usize,
    t: &'b DVector<f64>,
    yp: &'b [f64],
    evaluations: usize,
}

impl System for Corrector<'_, '_> {
    fn residual(&mut self, y: &[f64]) -> Result<Vec<f64>> {
        let m = y.len() - 1;
        self.evaluations += 1;
        let mut r = self.pb.residual(&y[..m], y[m] * self.scale, self.steps)?;
        r.push(
            y.iter()
                .zip(self.yp)
                .zip(self.t.iter())
                .map(|((a, b), c)| (a - b) * c)
                .sum(),
        );
        Ok(r)
    }
    fn residual_and_jacobian(&mut self, y: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let m = y.len() - 1;
        let (mut r, j) = jacobian(self.pb, y, self.scale, self.steps, &mut self.evaluations)?;
        r.push(
            y.iter()
                .zip(self.yp)
                .zip(self.t.iter())
                .map(|((a, b), c)| (a - b) * c)
                .sum(),
        );
        let mut a = DMatrix::zeros(m + 1, m + 1);
        a.view_mut((0, 0), (m, m + 1)).copy_from(&j);
        a.row_mut(m).copy_from(&self.t.transpose());
        Ok((r, a))
    }
    fn evaluations(&self) -> usize {
        self.evaluations
    }
}

/// Follow the branch through `start` (a converged equilibrium at
/// `opts.start`, or a cold solve there) toward `opts.end`.
pub fn follow_branch(
    pb: &Problem<'_>,
    opts: &BranchOptions,
    start: Option<&Solution>,
) -> Result<Branch> {
    opts.validate()?;
    let scale = (opts.end - opts.start).abs();
    let dir = (opts.end - opts.start).signum();
    let mut tr = Tracer {
        pb,
        scale,
        opts: *opts,
        evals: 0,
    };
    let sol0 = match start {
        Some(s) => pb.solve(opts.start, &opts.solve, Some(s))?,
        None => pb.solve(opts.start, &opts.solve, None)?,
    };
    tr.evals += sol0.evaluations;
    let m = sol0.unknowns.len();
    let mut y0 = sol0.unknowns.clone();
    y0.push(opts.start / scale);
    let mut e = DVector::zeros(m + 1);
    e[m] = dir;
    let mut cur = tr.point(y0, &e)?;
    let (lo, hi) = (opts.start.min(opts.end), opts.start.max(opts.end));
    let mut pts = vec![];
    let mut events = vec![];
    let mut ds = opts.step;
    while pts.len() + 1 < opts.max_points {
        let next = match tr.step(&cur, ds) {
            Ok(p) => p,
            Err(Error::Interrupted) => return Err(Error::Interrupted),
            Err(Error::InvalidParameter { .. } | Error::InvalidInput { .. }) => break,
            Err(e) => {
                ds *= 0.5;
                if ds < opts.min_step {
                    if pts.is_empty() {
                        return Err(e);
                    }
                    break;
                }
                continue;
            }
        };
        // a jump to another branch shows as a large change of the unknowns
        let dy: f64 = next
            .y
            .iter()
            .zip(&cur.y)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt();
        if dy > 3.0 * ds && ds > opts.min_step {
            ds *= 0.5;
            continue;
        }
        let fold = next.bp.dparameter * cur.bp.dparameter < 0.0;
        let det_flip = next.bp.jacobian_det * cur.bp.jacobian_det < 0.0;
        let stab_flip = next.bp.stability.stable != cur.bp.stability.stable;
        let idx = pts.len();
        if fold {
            events.push(tr.locate(&cur, &next, ds, EventKind::Fold, idx)?);
        } else if det_flip || stab_flip {
            events.push(tr.locate(&cur, &next, ds, EventKind::Bifurcation, idx)?);
        }
        let lam = next.bp.parameter;
        let unstable = !next.bp.stability.stable;
        pts.push(std::mem::replace(&mut cur, next));
        if lam < lo - 1e-12 * scale
            || lam > hi + 1e-12 * scale
            || (opts.stop_when_unstable && (unstable || fold))
        {
            break;
        }
        ds = (ds * 1.5).min(opts.max_step);
    }
    pts.push(cur);
    Ok(Branch {
        points: pts.into_iter().map(|p| p.bp).collect(),
        events,
        evaluations: tr.evals,
    })
}

impl Tracer<'_, '_> {
    /// Locate an event between `a` and `b` (arclength `ds` apart) by regula
    /// falsi on the event's test function along the arclength from `a`.
    fn locate(&mut self, a: &Pt, b: &Pt, ds: f64, kind: EventKind, idx: usize) -> Result<Event> {
        // a bifurcation where the verdict changes is located on the margin,
        // otherwise on det F_x
        let on_margin = a.bp.stability.margin * b.bp.stability.margin < 0.0;
        let test = |p: &Pt| -> f64 {
            match kind {
                EventKind::Fold => p.bp.dparameter,
                EventKind::Bifurcation if on_margin => p.bp.stability.margin,
                EventKind::Bifurcation => p.bp.jacobian_det,
            }
        };
        let (mut s0, mut f0) = (0.0, test(a));
        let (mut s1, mut f1) = (ds, test(b));
        let mut best = (s1, b.bp.parameter, b.bp.solution.tip_position());
        // Illinois variant: halve the stale end's value so both ends move
        let mut side = 0i32;
        for _ in 0..16 {
            // (a NaN product also stops the search)
            if f0 * f1 >= 0.0 || (f0 * f1).is_nan() {
                break;
            }
            let sm = s0 - f0 * (s1 - s0) / (f1 - f0);
            let p = match self.step(a, sm) {
                Ok(p) => p,
                Err(_) => break,
            };
            let fm = test(&p);
            best = (sm, p.bp.parameter, p.bp.solution.tip_position());
            if fm == 0.0 {
                break;
            }
            if fm * f0 > 0.0 {
                s0 = sm;
                f0 = fm;
                if side == -1 {
                    f1 *= 0.5;
                }
                side = -1;
            } else {
                s1 = sm;
                f1 = fm;
                if side == 1 {
                    f0 *= 0.5;
                }
                side = 1;
            }
            if (s1 - s0).abs() < 1e-7 * ds {
                break;
            }
        }
        let _ = best.0;
        Ok(Event {
            kind,
            parameter: best.1,
            tip_position: best.2,
            after_point: idx,
        })
    }
}

/// A jump of the physical robot in a stable sweep.
#[derive(Debug, Clone)]
pub struct Jump {
    /// Parameter at which the stable branch ends (fold or stability loss).
    pub parameter: f64,
    /// The last stable equilibrium before the jump.
    pub before: Solution,
    /// The stable equilibrium the robot lands on, just past the jump.
    pub after: Solution,
}

/// Result of [`sweep_stable`].
#[derive(Debug, Clone)]
pub struct StableSweep {
    /// Stable points in parameter order.
    pub points: Vec<BranchPoint>,
    /// Jumps, in order.
    pub jumps: Vec<Jump>,
    /// IVPs integrated.
    pub evaluations: usize,
}

/// Sweep the parameter from `opts.start` to `opts.end` staying on stable
/// equilibria: follow the branch until it loses stability (fold or
/// bifurcation) or turns back in the parameter (a fold), then land on a stable equilibrium just beyond (the nearest
/// one, by tip position, among those reached from a few perturbed starts)
/// and go on. Equilibria that are unstable from the start are refused.
pub fn sweep_stable(
    pb: &Problem<'_>,
    opts: &BranchOptions,
    start: Option<&Solution>,
) -> Result<StableSweep> {
    opts.validate()?;
    let mut o = *opts;
    o.stop_when_unstable = true;
    let mut points: Vec<BranchPoint> = vec![];
    let mut jumps = vec![];
    let mut evals = 0;
    let mut from: Option<Solution> = start.cloned();
    let dir = (opts.end - opts.start).signum();
    for _ in 0..20 {
        let br = follow_branch(pb, &o, from.as_ref())?;
        evals += br.evaluations;
        let n0 = points.len();
        // the sweep ends early at a loss of stability or at a fold (the
        // parameter cannot run back)
        let folded = br.events.iter().any(|e| e.kind == EventKind::Fold);
        let ended_early = folded || br.points.last().is_some_and(|p| !p.stability.stable);
        let within = |l: f64| (l - opts.end) * dir <= 0.0;
        for p in br.points.into_iter() {
            let ahead = points.last().map_or(true, |q: &BranchPoint| {
                (p.parameter - q.parameter) * dir > 0.0
            });
            if p.stability.stable && within(p.parameter) && ahead {
                points.push(p);
            }
        }
        if points.len() == n0 {
            return Err(Error::input(
                "start",
                "the equilibrium at the start of the sweep is not stable",
            ));
        }
        if !ended_early {
            break;
        }
        let before = points.last().expect("non-empty").solution.clone();
        let lam_c = br
            .events
            .last()
            .map_or(points.last().expect("non-empty").parameter, |e| e.parameter);
        if !within(lam_c) {
            break;
        }
        let past = lam_c + dir * 3e-3 * (opts.end - opts.start).abs();
        let after = land(pb, past, &before, &opts.solve, &mut evals)?;
        jumps.push(Jump {
            parameter: lam_c,
            before,
            after: after.clone(),
        });
        o.start = past;
        from = Some(after);
        if !within(past) {
            break;
        }
    }
    Ok(StableSweep {
        points,
        jumps,
        evaluations: evals,
    })
}

/// A stable equilibrium at `lambda` near `before`: by imperfection homotopy
/// (a tip wrench `eps (EI/L^2, EI/L) mode` along the softest mode of the
/// continued equilibrium, either sign, `eps` from 0.5 down to 0 in seven
/// warm-started solves), and by Newton from the cold
/// guess, from `before`, and from `before` with its scaled base curvature
/// `L omega(0)` pushed by +-0.03, 0.1, 0.3, 1 and 3 about each bending axis (the
/// tensions kept); among the stable results, the one whose tip is nearest
/// `before`'s.
fn land(
    pb: &Problem<'_>,
    lambda: f64,
    before: &Solution,
    opts: &SolveOptions,
    evals: &mut usize,
) -> Result<Solution> {
    let (robot, inputs, loads) = pb.at(lambda)?;
    let tip = before.tip_position();
    let mut found: Vec<Solution> = vec![];
    let mut consider = |s: Solution, evals: &mut usize| {
        *evals += s.evaluations;
        if let Ok(st) = stability(&robot, &s, &[]) {
            *evals += st.evaluations;
            if st.stable {
                found.push(s);
            }
        }
    };
    // imperfection homotopy along the softest mode of the continued
    // (unstable) equilibrium: a tip wrench eps (EI/L^2, EI/L) mode large
    // enough that the near-unstable solutions do not exist, removed again
    // in warm-started steps
    let len = robot.body.length;
    let (_, ix, iy, _) = robot.body.section.properties();
    let ei = robot.body.youngs_modulus * ix.min(iy);
    let mode = solve_loaded(&robot, &inputs, &loads, opts, Some(before))
        .ok()
        .and_then(|s| stability(&robot, &s, &[]).ok())
        .map(|st| st.mode);
    if let Some(mode) = mode {
        for sgn in [1.0, -1.0] {
            let mut w: Option<Solution> = Some(before.clone());
            for eps in [0.5, 0.25, 0.1, 0.04, 0.015, 0.005, 0.0] {
                let mut l = loads;
                l.tip_force +=
                    Vector3::new(mode[0], mode[1], mode[2]) * (sgn * eps * ei / (len * len));
                l.tip_moment += Vector3::new(mode[3], mode[4], mode[5]) * (sgn * eps * ei / len);
                w = solve_loaded(&robot, &inputs, &l, opts, w.as_ref()).ok();
                if w.is_none() {
                    break;
                }
            }
            if let Some(s) = w {
                consider(s, evals);
            }
        }
    }
    let mut guesses = vec![
        reference_guess(&robot),
        initial_guess(&robot, &inputs, Some(before)),
    ];
    for amp in [0.03, 0.1, 0.3, 1.0, 3.0] {
        for k in [3usize, 4] {
            for sgn in [-1.0, 1.0] {
                let mut g = before.unknowns.clone();
                g[k] += sgn * amp;
                guesses.push(g);
            }
        }
    }
    for g in guesses {
        let mut w = before.clone();
        w.unknowns = g;
        w.newton_jacobian = None;
        if let Ok(s) = solve_loaded(&robot, &inputs, &loads, opts, Some(&w)) {
            consider(s, evals);
        }
    }
    crate::solve::cancel::check()?;
    found
        .into_iter()
        .min_by(|a, b| {
            (a.tip_position() - tip)
                .norm()
                .total_cmp(&(b.tip_position() - tip).norm())
        })
        .ok_or_else(|| Error::NoSolution {
            reason: format!("no stable equilibrium found just past the jump at parameter {lambda}"),
        })
}
