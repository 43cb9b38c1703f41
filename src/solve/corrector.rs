//! One homotopy corrector: a forward-shooting Newton run from a
//! predictor that records the predictor's residual `max |r(x0)|` and
//! refuses a predictor farther than a bound from the path (the step is
//! then shortened at the cost of that one IVP; see
//! [`crate::solve::continuation`]).
//!
//! Its Jacobian policy is the direct run's ([`newton_from`]): the last
//! converged point's Jacobian starts the corrector (chord steps), a chord
//! step must halve `max |r|`, and one that reduces it less than four times
//! gets a fresh Jacobian for the next step. Keeping a Jacobian longer
//! (handing a corrector's last Jacobian on to the next point, at no IVP)
//! does not pay, although tangents are a large share of the correctors'
//! IVPs: along a bending path a stale Jacobian costs more failed and
//! creeping steps than the tangents it saves, and on a body past buckling
//! its steps can carry the corrector onto another equilibrium branch. The
//! rule is a tuning choice, made by experiment on the tuning seed
//! ([`crate::problems::TUNING_SEED`]) of the design benchmark
//! (`benches/designs.rs`).

use nalgebra::DMatrix;

use super::newton::{newton_from, NewtonResult, System};
use super::options::SolveOptions;
use super::residual::Loads;
use super::system::{settle, FinalIvp, Keep, Shooting, Work};
use crate::error::{Error, Result, StopReason};
use crate::rod::Robot;

/// The shooting system of a corrector (delegates to [`Shooting`]), which
/// fails its first evaluation when the predictor's residual exceeds `reject`.
struct Corrector<'a> {
    sys: Shooting<'a>,
    /// `max |r|` at the predictor (`None` until evaluated).
    first: Option<f64>,
    reject: f64,
}

impl System for Corrector<'_> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        let r = self.sys.residual(x)?;
        if self.first.is_none() {
            let n = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            self.first = Some(n);
            if !(n <= self.reject) {
                return Err(Error::NotConverged {
                    solver: "forward shooting",
                    iterations: 0,
                    evaluations: self.sys.evaluations,
                    residual: n,
                    stop: StopReason::Other,
                    reason: "homotopy predictor outside the corrector's reach".into(),
                });
            }
        }
        Ok(r)
    }
    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        self.sys.residual_and_jacobian(x)
    }
    fn floor(&self, x: &[f64], r: &[f64]) -> f64 {
        self.sys.floor(x, r)
    }
    fn evaluations(&self) -> usize {
        self.sys.evaluations()
    }
    fn limit_step(&self, x: &[f64], dx: &[f64], r: &[f64], jac: &DMatrix<f64>) -> Option<Vec<f64>> {
        self.sys.limit_step(x, dx, r, jac)
    }
    fn refine(&mut self, x: &[f64]) -> bool {
        self.sys.refine(x)
    }
}

/// The outcome of one corrector run: the Newton result and the last IVP
/// (as [`crate::solve::system::newton_shooting`] returns them), and the
/// predictor's residual `max |r(x0)|` (`None` if its IVP failed).
pub(crate) type Corrected = (Result<(NewtonResult, Option<FinalIvp>)>, Option<f64>);

/// [`crate::solve::system::newton_shooting`] from the predictor `x0`, but
/// stopped after its first IVP if `max |r(x0)| > reject`. Adds its work
/// to `work`; errors carry the work totals.
#[allow(clippy::too_many_arguments)]
pub(crate) fn correct(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    jac0: Option<&DMatrix<f64>>,
    keep: impl Into<Keep>,
    reject: f64,
    work: &mut Work,
) -> Corrected {
    let mut c = Corrector {
        sys: Shooting::new(robot, inputs, loads, opts.steps, keep),
        first: None,
        reject,
    };
    let nopts = work.newton_options(opts);
    let out = newton_from(&mut c, x0, &nopts, "forward shooting", jac0);
    let out = settle(&mut c.sys, out, work);
    (out, c.first)
}
