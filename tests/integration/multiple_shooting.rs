//! The multiple-shooting forward solve (`tcarod::solve::forward`) against
//! an independent single-shooting Newton solve and over seeded families of
//! designs: the same equilibria where both converge, every design below
//! self-weight buckling solved cold and along a warm sweep, heavy bodies
//! that single shooting's growth defeats.

use nalgebra::DVector;
use tcarod::experiments::{fig6_square, steel_tendon_robot, STEEL_TENDON_TENSIONS};
use tcarod::problems::{
    equilibrium, random_design, stress_design, Orientation, STRESS_SEED, TUNING_SEED,
};
use tcarod::shooting::{
    assemble, initial_guess, linear_guess, Loads, Shot, Solution, SolveOptions,
};
use tcarod::solve::forward;
use tcarod::solve::nleq::{self, NleqOptions, NonlinearSystem};

/// The shooting residual (eqs 32-33) with its exact Jacobian, dense LU:
/// single shooting, a formulation independent of the forward solver's.
struct SingleShooting<'a> {
    shot: Shot<'a>,
    lu: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
    work: f64,
}

impl NonlinearSystem for SingleShooting<'_> {
    fn dim(&self) -> usize {
        self.shot.robot.actuators.len() + 6
    }
    fn residual(&mut self, x: &[f64], f: &mut [f64]) -> tcarod::Result<()> {
        self.work += 1.0;
        f.copy_from_slice(&self.shot.residual(x, false)?.0);
        Ok(())
    }
    fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> tcarod::Result<()> {
        self.work += 1.0;
        let (r, j, _, _) = self.shot.jacobian(x, false)?;
        f.copy_from_slice(&r);
        self.lu = Some(j.lu());
        Ok(())
    }
    fn solve(&mut self, b: &[f64], dx: &mut [f64]) -> tcarod::Result<bool> {
        let sol = self
            .lu
            .as_ref()
            .and_then(|lu| lu.solve(&DVector::from_column_slice(b)));
        Ok(sol.is_some_and(|s| {
            dx.copy_from_slice(s.as_slice());
            true
        }))
    }
    fn work(&self) -> f64 {
        self.work
    }
}

/// Single shooting by the damped Newton method from the linear cold guess.
fn solve(
    robot: &tcarod::rod::Robot,
    inputs: &[f64],
    opts: &SolveOptions,
    _warm: Option<&Solution>,
) -> tcarod::Result<Solution> {
    let loads = Loads::of(robot);
    let mut x0 = initial_guess(robot, inputs, None);
    linear_guess(robot, inputs, &loads, &mut x0);
    let shot = Shot::new(robot, inputs, &loads, opts.steps);
    let mut sys = SingleShooting {
        shot,
        lu: None,
        work: 0.0,
    };
    let nopts = NleqOptions {
        tol: opts.tol,
        max_iterations: opts.max_iter,
        ..Default::default()
    };
    let x = nleq::solve(&mut sys, &x0, &nopts, "single shooting")?.x;
    assemble(robot, inputs, &loads, &x, opts.steps, 0, 0)
}

fn ms(
    robot: &tcarod::rod::Robot,
    inputs: &[f64],
    warm: Option<&Solution>,
) -> tcarod::Result<Solution> {
    forward::solve(
        robot,
        inputs,
        &Loads::of(robot),
        &SolveOptions::default(),
        warm,
    )
}

/// The paper's Fig. 6 robot at several temperatures and the steel tendon
/// robot: the tips of the two solvers agree within 1e-9 m, the bound the
/// fixtures are held to (both solve the same discrete equations to `tol =
/// 1e-10`, a strain error of that size moving a 40 mm tip by ~1e-12 m;
/// the steel robot's rounding floor, ~1e-9 in the scaled residual, moves
/// its 0.5 m tip by ~1e-11 m).
#[test]
fn agrees_with_single_shooting_on_the_papers_fixtures() {
    let opts = SolveOptions::default();
    let fig6 = fig6_square(true);
    for q in [[25.0, 25.0], [60.0, 25.0], [100.0, 100.0], [160.0, 40.0]] {
        let a = solve(&fig6, &q, &opts, None).unwrap();
        let b = ms(&fig6, &q, None).unwrap();
        let d = (a.tip_position() - b.tip_position()).norm();
        assert!(d < 1e-9, "Fig. 6 at {q:?}: tips {d:.2e} m apart");
        assert!(b.residual <= opts.tol);
    }
    let steel = steel_tendon_robot();
    let a = solve(&steel, &STEEL_TENDON_TENSIONS, &opts, None).unwrap();
    let b = ms(&steel, &STEEL_TENDON_TENSIONS, None).unwrap();
    let d = (a.tip_position() - b.tip_position()).norm();
    assert!(d < 1e-9, "steel tendon robot: tips {d:.2e} m apart");
    // the steel rod's residual floor (`EA L^2 / EI` large) is reported, and
    // the residual is within the tolerance or that floor
    assert!(b.floor > 0.0 && b.floor < 1e-6, "floor {:.1e}", b.floor);
    assert!(b.residual <= opts.tol.max(b.floor), "{:.1e}", b.residual);
}

/// The first 100 designs of the tuning seed: every one below self-weight
/// buckling converges cold; where single shooting converges too, the two
/// solutions are the same equilibrium (tips within 1e-9 of the length) in
/// all but the designs with several equilibria, each of which is then a
/// solution of its own: its global equilibrium check (base wrench against
/// the loads) holds as well as single shooting's does on the same grid
/// (within 10 times, or 1e-8 relative).
#[test]
fn solves_every_tuning_design_below_buckling_cold() {
    let opts = SolveOptions::default();
    let (mut same, mut other) = (0, 0);
    for i in 0..100 {
        let d = random_design(TUNING_SEED, i);
        let b = ms(&d.robot, &d.inputs, None);
        if d.past_buckling() {
            continue;
        }
        let b = b.unwrap_or_else(|e| panic!("design {i} ({}): {e}", d.summary()));
        assert!(
            b.residual <= opts.tol,
            "design {i}: residual {:.1e}",
            b.residual
        );
        let Ok(a) = solve(&d.robot, &d.inputs, &opts, None) else {
            continue;
        };
        let len = d.robot.body.length;
        if (a.tip_position() - b.tip_position()).norm() <= 1e-9 * len {
            same += 1;
        } else {
            other += 1;
            let (ea, eb) = (equilibrium(&d.robot, &a), equilibrium(&d.robot, &b));
            assert!(
                eb.relative <= (10.0 * ea.relative).max(1e-8),
                "design {i}: equilibrium {:.1e} against {:.1e}",
                eb.relative,
                ea.relative
            );
        }
    }
    // several equilibria are the exception among designs below buckling
    assert!(
        other * 20 <= same,
        "{same} the same, {other} other equilibria"
    );
}

/// Warm sweeps in ten equal steps from the reference inputs to the
/// design's, each solve warm from the last, for the first 800 tuning
/// designs below buckling whose cold solve converges: every step
/// converges, also where the warm path's branch turns back at a fold (the
/// body snaps through) and the solve takes the cold path from rest
/// instead.
#[test]
fn warm_sweeps_converge_at_every_step() {
    for i in 0..800 {
        let d = random_design(TUNING_SEED, i);
        if d.past_buckling() || ms(&d.robot, &d.inputs, None).is_err() {
            continue;
        }
        let reference = d.robot.reference_inputs();
        let mut last: Option<Solution> = None;
        for k in 0..=10 {
            let t = k as f64 / 10.0;
            let q: Vec<f64> = (reference.iter().zip(&d.inputs))
                .map(|(a, b)| a + t * (b - a))
                .collect();
            let sol = ms(&d.robot, &q, last.as_ref())
                .unwrap_or_else(|e| panic!("design {i} step {k}: {e}"));
            assert!(sol.residual <= 1e-10);
            last = Some(sol);
        }
    }
}

/// Stress design `d` (number `i`) solved cold at `inputs` converges, to
/// the global equilibrium of its grid: 1e-2 relative on 100 RK4 steps for
/// these bodies, whose bending length is a few steps.
fn solves_to_its_grid(d: &tcarod::problems::Design, inputs: &[f64], i: usize) {
    let sol = ms(&d.robot, inputs, None)
        .unwrap_or_else(|e| panic!("stress design {i} at {inputs:?} ({}): {e}", d.summary()));
    let eq = equilibrium(&d.robot, &sol);
    assert!(
        eq.relative < 1e-2,
        "stress design {i} at {inputs:?}: equilibrium {:.1e}",
        eq.relative
    );
}

/// Heavy soft bodies (weight ratio `q L^3 / EI` 20-3000) hanging or held
/// horizontally, where the tangent of single shooting grows past `1 /
/// eps`: the first 40 of the stress family converge cold, and each
/// solution satisfies the global equilibrium to the accuracy of its grid
/// (1e-2 relative on 100 RK4 steps for these bodies, whose bending length
/// is a few steps).
#[test]
fn solves_heavy_hanging_and_horizontal_bodies() {
    let mut solved = 0;
    for i in 0..40 {
        let d = stress_design(STRESS_SEED, i);
        if Orientation::of(&d.robot.body) == Some(Orientation::Upright) {
            continue;
        }
        solves_to_its_grid(&d, &d.inputs, i);
        solved += 1;
    }
    assert!(solved >= 20, "{solved}");
}

/// Every hanging body of the stress family's first 300 designs (weight
/// ratio 20-3000, tilted 1-5 degrees off vertical: in tension, stable, no
/// buckling) converges cold, to the global equilibrium of its grid (1e-2,
/// as above), and so does each at its reference inputs (the start of a
/// warm sweep). The cold homotopy's branch of a heavy body bends sharply
/// near the unloaded state: a long first step may meet it behind its
/// start, toward the reversed gravity that buckles the body, and is then
/// shortened.
#[test]
fn every_hanging_heavy_body_converges_cold() {
    let mut solved = 0;
    for i in (0..300).filter(|i| i % 3 == 0) {
        let d = stress_design(STRESS_SEED, i);
        assert_eq!(Orientation::of(&d.robot.body), Some(Orientation::Hanging));
        solves_to_its_grid(&d, &d.inputs, i);
        solves_to_its_grid(&d, &d.robot.reference_inputs(), i);
        solved += 1;
    }
    assert_eq!(solved, 100);
}

/// A budget of IVPs bounds the solve: a heavy design that needs
/// continuation stops with a budget error (the best residual and the work
/// spent in it) instead of running on, and a non-finite input is refused.
#[test]
fn budgets_bound_the_solve() {
    let d = (0..30)
        .map(|i| stress_design(STRESS_SEED, i))
        .find(|d| Orientation::of(&d.robot.body) == Some(Orientation::Hanging))
        .unwrap();
    let opts = SolveOptions {
        max_evaluations: 5,
        ..Default::default()
    };
    match forward::solve(&d.robot, &d.inputs, &Loads::of(&d.robot), &opts, None) {
        Err(tcarod::Error::NotConverged {
            stop,
            evaluations,
            residual,
            ..
        }) => {
            assert_eq!(stop, tcarod::error::StopReason::Budget);
            // one evaluation past the budget at most (a linearisation in flight)
            assert!(evaluations <= 5 + 4, "{evaluations}");
            assert!(!residual.is_nan());
        }
        other => panic!("expected a budget error, got {other:?}"),
    }
    // bad input is refused before any work, naming the argument
    let fig6 = fig6_square(true);
    let bad = forward::solve(&fig6, &[f64::NAN, 25.0], &Loads::of(&fig6), &opts, None);
    assert!(
        matches!(&bad, Err(tcarod::Error::InvalidParameter { name, .. }) if name.contains("temperature")),
        "{bad:?}"
    );
}

/// Accuracy control: with `equilibrium_tol`, the solve refines its grid
/// until the global equilibrium (base wrench against the loads, an
/// independent check of the discrete solution) holds to the tolerance. On
/// heavy hanging and horizontal bodies, whose 100-step equilibrium error is
/// 1e-5 to 1e-2, a tolerance of 1e-6 needs a finer grid, which the
/// solution reports; its tip agrees with a plain solve on that grid.
#[test]
fn refines_the_grid_to_an_equilibrium_tolerance() {
    let target = 1e-6;
    let mut refined = 0;
    for i in 0..12 {
        let d = stress_design(STRESS_SEED, i);
        if Orientation::of(&d.robot.body) == Some(Orientation::Upright) {
            continue;
        }
        let loads = Loads::of(&d.robot);
        let opts = SolveOptions {
            equilibrium_tol: Some(target),
            ..Default::default()
        };
        let sol = forward::solve(&d.robot, &d.inputs, &loads, &opts, None)
            .unwrap_or_else(|e| panic!("stress design {i} ({}): {e}", d.summary()));
        let eq = equilibrium(&d.robot, &sol).relative;
        assert!(eq <= target, "stress design {i}: equilibrium {eq:.1e}");
        if sol.steps > SolveOptions::default().steps {
            refined += 1;
            let plain = SolveOptions {
                steps: sol.steps,
                ..Default::default()
            };
            let again = forward::solve(&d.robot, &d.inputs, &loads, &plain, None).unwrap();
            // both solve the same discrete equations to tol = 1e-10
            let dist = (again.tip_position() - sol.tip_position()).norm();
            assert!(
                dist <= 1e-8 * d.robot.body.length,
                "design {i}: {dist:.1e} m"
            );
        }
    }
    assert!(refined >= 3, "{refined} designs needed a finer grid");
}
