//! The full-grid finish of a coarse homotopy path from an intermediate
//! grid's root (see [`crate::solve::coarse_path::HOP_GRID_DIVISOR`]):
//! Newton on the full grid whose fresh Jacobians are taken on that
//! intermediate grid.
//!
//! A forward solve's full-grid Newton takes its fresh Jacobians on a tenth
//! of the steps ([`crate::solve::system::COARSE_JACOBIAN_MIN_STEPS`]),
//! within RK4's coarse-grid error of the exact one. A finish hops to the
//! intermediate grid exactly where that coarse grid does not resolve the
//! design at `lambda = 1` (its root's full-grid residual is out of the
//! finish's reach), so there the coarse Jacobians are the wrong ones: the
//! pre-solved finish (`presolve::presolved_shooting`: defect correction
//! with coarse Jacobians, then a full-grid Newton fallback) from the hop's
//! root takes several times the IVPs of this finish, which
//! starts from the hop's root with the hop's own Jacobian and takes fresh
//! ones on the hop's grid (until a failed line search, which moves them to
//! the full grid as `Shooting::refine` does): the hop grid's RK4 error is
//! a `(10/4)^4 ~ 39`th of the coarse grid's, so its Jacobian is near
//! enough the full grid's for chord steps to converge, at a fraction of a
//! full-grid tangent's cost. Richardson extrapolation of the coarse and
//! hop roots, `x_h + (x_h - x_c) / ((10/4)^4 - 1)`, as the start does not
//! shorten this finish: the hop's root is already within its chord steps'
//! reach.

use nalgebra::DMatrix;

use super::newton::{newton_from, NewtonResult, System};
use super::options::SolveOptions;
use super::residual::Loads;
use super::system::{settle, FinalIvp, Keep, Shooting, Work};
use crate::error::Result;
use crate::rod::Robot;

/// The full-grid shooting system `sys` with its fresh Jacobians taken on
/// `jac_grid` (the same residual on another grid) until `refine`.
struct GridJacobian<'a> {
    sys: Shooting<'a>,
    /// The Jacobians' grid (`None` once refined: the full grid's own policy).
    jac_grid: Option<Shooting<'a>>,
    /// IVPs of the Jacobians' grid so far (kept after it is dropped).
    jac_evaluations: usize,
}

impl System for GridJacobian<'_> {
    fn residual(&mut self, x: &[f64]) -> Result<Vec<f64>> {
        self.sys.residual(x)
    }
    /// The residual returned is the Jacobian grid's while it is used;
    /// Newton takes only the Jacobian (the full grid's residual at `x` is
    /// its last plain evaluation).
    fn residual_and_jacobian(&mut self, x: &[f64]) -> Result<(Vec<f64>, DMatrix<f64>)> {
        match self.jac_grid.as_mut() {
            Some(g) => {
                let out = g.residual_and_jacobian(x);
                self.jac_evaluations = g.evaluations();
                out
            }
            None => self.sys.residual_and_jacobian(x),
        }
    }
    fn floor(&self, x: &[f64], r: &[f64]) -> f64 {
        self.sys.floor(x, r)
    }
    fn evaluations(&self) -> usize {
        self.sys.evaluations() + self.jac_evaluations
    }
    fn limit_step(&self, x: &[f64], dx: &[f64], r: &[f64], jac: &DMatrix<f64>) -> Option<Vec<f64>> {
        // the slack tangents of the system whose Jacobian this is
        match &self.jac_grid {
            Some(g) => g.limit_step(x, dx, r, jac),
            None => self.sys.limit_step(x, dx, r, jac),
        }
    }
    fn refine(&mut self, x: &[f64]) -> bool {
        if self.jac_grid.take().is_some() {
            // to the full grid's own Jacobian (not its coarse one)
            self.sys.refine(x);
            return true;
        }
        self.sys.refine(x)
    }
}

/// Newton on the full grid `opts.steps` from `x0` (the root on
/// `jac_steps` RK4 steps, with its Jacobian `jac0` there), whose fresh
/// Jacobians are taken on `jac_steps` steps until a line search fails
/// (see the module docs); adds its work (both grids' IVPs) to `work`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn finish_on_grid(
    robot: &Robot,
    inputs: &[f64],
    loads: &Loads,
    opts: &SolveOptions,
    x0: &[f64],
    jac0: Option<&DMatrix<f64>>,
    jac_steps: usize,
    keep: Keep,
    work: &mut Work,
) -> Result<(NewtonResult, Option<FinalIvp>)> {
    let mut g = GridJacobian {
        sys: Shooting::new(robot, inputs, loads, opts.steps, keep),
        jac_grid: (jac_steps < opts.steps)
            .then(|| Shooting::new(robot, inputs, loads, jac_steps, false)),
        jac_evaluations: 0,
    };
    let nopts = work.newton_options(opts);
    let out = newton_from(&mut g, x0, &nopts, "forward shooting", jac0);
    work.evaluations += g.jac_evaluations;
    settle(&mut g.sys, out, work)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problems::{random_design, DEFAULT_SEED};
    use crate::solve::shooting::solve;
    use crate::solve::system::newton_shooting;

    /// Benchmark design 0 (converges by the direct run) on `steps`, from
    /// its converged unknowns: its root and Jacobian there, and the work.
    fn root_on(steps: usize) -> (crate::problems::Design, Vec<f64>, DMatrix<f64>) {
        let d = random_design(DEFAULT_SEED, 0);
        let opts = SolveOptions::default();
        let sol = solve(&d.robot, &d.inputs, &opts, None).expect("design 0 converges");
        let loads = Loads::of(&d.robot);
        let o = SolveOptions { steps, ..opts };
        let mut work = Work::start(&o);
        let (nr, _) = newton_shooting(
            &d.robot,
            &d.inputs,
            &loads,
            &o,
            &sol.unknowns,
            None,
            false,
            &mut work,
        )
        .expect("a root on the grid");
        let jac = nr.jacobian.expect("a Newton Jacobian");
        (d, nr.x, jac)
    }

    /// Without a coarser Jacobian grid the finish is `newton_shooting`:
    /// the same operations, so the same root bit for bit and the same IVPs.
    #[test]
    fn on_the_full_grid_it_is_newton_shooting() {
        let opts = SolveOptions::default();
        let (d, x0, jac) = root_on(opts.steps / 4);
        let loads = Loads::of(&d.robot);
        let (mut w1, mut w2) = (Work::start(&opts), Work::start(&opts));
        let (a, _) = newton_shooting(
            &d.robot,
            &d.inputs,
            &loads,
            &opts,
            &x0,
            Some(&jac),
            Keep::Nodes,
            &mut w1,
        )
        .unwrap();
        let (b, _) = finish_on_grid(
            &d.robot,
            &d.inputs,
            &loads,
            &opts,
            &x0,
            Some(&jac),
            opts.steps,
            Keep::Nodes,
            &mut w2,
        )
        .unwrap();
        assert_eq!(a.x, b.x);
        assert_eq!(w1.evaluations, w2.evaluations);
    }

    /// From the root on a quarter of the steps, with that grid's Jacobians,
    /// the finish reaches the full grid's root: the residual to `tol`, the
    /// unknowns (strains and `L omega`, of order one) within 1e-8 of
    /// `newton_shooting`'s (both converged to a scaled residual of 1e-10,
    /// with a Jacobian of order one), and its IVPs counted (at least one a
    /// Newton iteration, plus the first residual).
    #[test]
    fn from_a_quarter_grid_root_it_reaches_the_full_grids_root() {
        let opts = SolveOptions::default();
        let (d, x0, jac) = root_on(opts.steps / 4);
        let loads = Loads::of(&d.robot);
        let mut w1 = Work::start(&opts);
        let (a, _) = newton_shooting(
            &d.robot,
            &d.inputs,
            &loads,
            &opts,
            &x0,
            None,
            Keep::Nodes,
            &mut w1,
        )
        .unwrap();
        let mut w2 = Work::start(&opts);
        let (b, _) = finish_on_grid(
            &d.robot,
            &d.inputs,
            &loads,
            &opts,
            &x0,
            Some(&jac),
            opts.steps / 4,
            Keep::Nodes,
            &mut w2,
        )
        .unwrap();
        assert!(b.norm <= opts.tol.max(b.floor), "{} {}", b.norm, b.floor);
        let dx =
            a.x.iter()
                .zip(&b.x)
                .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
        assert!(dx <= 1e-8, "{dx:e}");
        assert!(w2.evaluations > b.iterations, "{} IVPs", w2.evaluations);
    }
}
