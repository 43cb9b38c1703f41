//! Options of the forward shooting solve: grid, tolerance, iteration
//! limit, and the per-solve work budget (IVPs, wall time).

use std::time::Duration;

use crate::error::{Error, Result};

/// Options of the forward shooting solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveOptions {
    /// RK4 steps over the body length.
    pub steps: usize,
    /// Convergence tolerance on the max-norm of the dimensionless residual.
    pub tol: f64,
    /// Newton iteration limit (per Newton run: the direct solve and each
    /// continuation step's corrector, whose own limit is
    /// [`crate::solve::arclength::CORRECTOR_ITERATIONS`]).
    pub max_iter: usize,
    /// IVP budget of one solve, continuation included (a tangent IVP counts
    /// as one); exhausting it raises [`Error::NotConverged`] with
    /// [`crate::StopReason::Budget`].
    pub max_evaluations: usize,
    /// Wall-time limit of one solve (`None`: none); passing it raises
    /// [`Error::NotConverged`] with [`crate::StopReason::Budget`].
    pub time_limit: Option<Duration>,
    /// Solve first on a coarse grid of a tenth of the steps (at least
    /// [`crate::solve::forward::COARSE_MIN_STEPS`]), cold or warm, and start
    /// Newton on the full grid from its solution and Jacobian
    /// ([`crate::solve::forward`]); the default, `true`. Its IVPs cost a
    /// tenth each and are counted so in `Solution.evaluations`; the solution
    /// meets `tol` on the full grid either way. `false`: Newton on the full
    /// grid from the start.
    pub presolve: bool,
    /// Accuracy control (opt-in; `None`, the default: the grid is `steps`):
    /// the largest relative error of the global equilibrium check
    /// ([`crate::solve::equilibrium::equilibrium`]: base wrench against the
    /// external loads) a solution may have. Above it the solve is repeated on
    /// a finer grid until it holds (see
    /// [`crate::solve::equilibrium::refine_to_equilibrium`]); the solution's
    /// `steps` are those used. Applies to [`crate::shooting::solve`] and
    /// [`crate::stability::solve_checked`] (Python's `Robot.solve`); the
    /// solves inside the inverse, branches and continuation keep `steps`.
    pub equilibrium_tol: Option<f64>,
}

/// Default IVP budget of one solve ([`SolveOptions::max_evaluations`]):
/// about 4 times the most a converging design of the 1,000-design benchmark
/// (`benches/designs.rs`) uses (5,252 IVPs), so that it only stops runaway
/// solves.
pub const DEFAULT_MAX_EVALUATIONS: usize = 20_000;

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            steps: 100,
            tol: 1e-10,
            max_iter: 50,
            max_evaluations: DEFAULT_MAX_EVALUATIONS,
            time_limit: None,
            presolve: true,
            equilibrium_tol: None,
        }
    }
}

/// Smallest [`SolveOptions::equilibrium_tol`]: the check's own rounding is
/// about `1e-14` relative (tests/designs.rs: `1e-15`-`1e-13` on exact cases).
pub const MIN_EQUILIBRIUM_TOL: f64 = 1e-12;

impl SolveOptions {
    /// Validate.
    pub fn validate(&self) -> Result<()> {
        // the caps on the work of one solve (steps, max_iter,
        // max_evaluations, time_limit) are defined once, in crate::limits
        self.check_limits()?;
        if !(self.tol.is_finite() && self.tol > 0.0) {
            return Err(Error::param("tol", self.tol, "finite and > 0"));
        }
        if let Some(t) = self.equilibrium_tol {
            if !(MIN_EQUILIBRIUM_TOL..1.0).contains(&t) {
                return Err(Error::param(
                    "equilibrium_tol",
                    t,
                    "1e-12 <= equilibrium_tol < 1",
                ));
            }
        }
        Ok(())
    }
}
