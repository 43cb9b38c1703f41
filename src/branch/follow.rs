//! Pseudo-arclength continuation: predictor, corrector, event location.

use nalgebra::{DMatrix, DVector};

use super::{Branch, BranchOptions, BranchPoint, Event, EventKind, Problem};
use crate::error::{Error, Result};
use crate::shooting::{Shot, Solution};
use crate::solve::newton::{newton, System};

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
    let (r, jx, _, _) = Shot::new(&robot, &inputs, &loads, steps).jacobian(&y[..m], false)?;
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

impl Corrector<'_, '_> {
    /// The pseudo-arclength condition `t . (y - y_p)`.
    fn arclength(&self, y: &[f64]) -> f64 {
        y.iter()
            .zip(self.yp)
            .zip(self.t.iter())
            .map(|((a, b), c)| (a - b) * c)
            .sum()
    }
}

impl System for Corrector<'_, '_> {
    fn residual(&mut self, y: &[f64]) -> Result<Vec<f64>> {
        let m = y.len() - 1;
        self.evaluations += 1;
        let mut r = self.pb.residual(&y[..m], y[m] * self.scale, self.steps)?;
        r.push(self.arclength(y));
        Ok(r)
    }
    fn residual_and_jacobian(&mut self, y: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        let m = y.len() - 1;
        let (mut r, j) = jacobian(self.pb, y, self.scale, self.steps, &mut self.evaluations)?;
        r.push(self.arclength(y));
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
    let mut tr = Tracer {
        pb,
        scale,
        opts: *opts,
        evals: 0,
    };
    let mut cur = tr.first(start)?;
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
        if distance(&next.y, &cur.y) > 3.0 * ds && ds > opts.min_step {
            ds *= 0.5;
            continue;
        }
        let event = tr.event(&cur, &next, ds, pts.len())?;
        let fold = event.as_ref().is_some_and(|e| e.kind == EventKind::Fold);
        events.extend(event);
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

/// Euclidean distance of two points of the path.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

impl Tracer<'_, '_> {
    /// The first point: `start` re-converged at `opts.start` (or a cold
    /// solve there), its tangent pointing toward `opts.end`.
    fn first(&mut self, start: Option<&Solution>) -> Result<Pt> {
        let o = self.opts;
        let sol0 = self.pb.solve(o.start, &o.solve, start)?;
        self.evals += sol0.evaluations;
        let m = sol0.unknowns.len();
        let mut y0 = sol0.unknowns;
        y0.push(o.start / self.scale);
        let mut e = DVector::zeros(m + 1);
        e[m] = (o.end - o.start).signum();
        self.point(y0, &e)
    }

    /// The event between consecutive points `a` and `b`, located: a fold
    /// (sign change of `d lambda / d sigma`), else a bifurcation (sign
    /// change of `det F_x`, or of the verdict).
    fn event(&mut self, a: &Pt, b: &Pt, ds: f64, idx: usize) -> Result<Option<Event>> {
        let fold = b.bp.dparameter * a.bp.dparameter < 0.0;
        let det_flip = b.bp.jacobian_det * a.bp.jacobian_det < 0.0;
        let stab_flip = b.bp.stability.stable != a.bp.stability.stable;
        if fold {
            Ok(Some(self.locate(a, b, ds, EventKind::Fold, idx)?))
        } else if det_flip || stab_flip {
            Ok(Some(self.locate(a, b, ds, EventKind::Bifurcation, idx)?))
        } else {
            Ok(None)
        }
    }
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
