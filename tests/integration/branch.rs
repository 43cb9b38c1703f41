//! Branch following on multiple shooting (docs/stability.md, "Branch
//! following"): the branch of a heavy body whose single-shooting Jacobian
//! has lost every digit, and the folds of a buckled column pushed sideways
//! through snap-through.

use nalgebra::Vector3;
use tcarod::branch::{follow_branch, BranchOptions, EventKind, Parameter, Problem};
use tcarod::rod::{Body, Robot, Section};
use tcarod::shooting::{solve, SolveOptions};
use tcarod::solve::equilibrium::equilibrium;
use tcarod::solve::nleq::FLOOR_FACTOR;

use crate::common::heavy_column;

/// A soft round rod (L / r = 1000) hanging from its base at 45 degrees to
/// the vertical under the weight ratio `w = rho A |g| L^3 / EI`: it bends
/// toward the vertical within a bending length `sqrt(EI / T)` of the base
/// and hangs in tension below.
fn tilted_hanging_rod(w: f64) -> Robot {
    let mut b = Body::new(1.0, Section::Circle { diameter: 2e-3 }, 1e6, 0.5, 1000.0).unwrap();
    let (a, ix, _, _) = b.section.properties();
    let g = w * b.youngs_modulus * ix / (b.density * a);
    let s = std::f64::consts::FRAC_1_SQRT_2;
    b.gravity = Vector3::new(s * g, 0.0, s * g);
    Robot::new(b, vec![]).unwrap()
}

/// Gravity scaled from 0 to 1 on a rod of weight ratio 3000: single
/// shooting's Jacobian grows as `exp((2/3) sqrt(w)) = e^36 > 1 / eps`
/// (docs/solver.md) and has no digit left; on multiple shooting every point
/// of the branch is an equilibrium, the parameter covers the interval from
/// 0 to exactly 1, and the end agrees with the forward solve there.
#[test]
fn heavy_body_branch_on_multiple_shooting() {
    let r = tilted_hanging_rod(3000.0);
    let pb = Problem::new(&r, Parameter::GravityScale, &[]).unwrap();
    let opts = BranchOptions {
        start: 0.0,
        end: 1.0,
        ..Default::default()
    };
    let br = follow_branch(&pb, &opts, None).unwrap();
    println!(
        "heavy hanging rod: {} points, {} IVP-equivalents",
        br.points.len(),
        br.evaluations
    );
    let (first, last) = (&br.points[0], br.points.last().unwrap());
    assert_eq!(first.parameter, 0.0);
    assert_eq!(last.parameter, 1.0);
    assert!(br.points.len() >= 3);
    for w in br.points.windows(2) {
        assert!(w[1].parameter > w[0].parameter);
    }
    let tol = SolveOptions::default().tol;
    for p in &br.points {
        let (robot, ..) = pb.at(p.parameter).unwrap();
        let eq = equilibrium(&robot, &p.solution);
        // the residual at the corrector's tolerance, or stalled within
        // NLEQ's margin over its rounding floor (4 eps EA L^2 / EI ~ 4e-9
        // for L / r = 1000)
        let bound = FLOOR_FACTOR * tol.max(p.solution.floor);
        assert!(p.solution.residual <= bound, "at {}", p.parameter);
        // the base wrench balances the weight to the accuracy of the
        // 100-step grid: 1e-2 relative for a bending length of two steps,
        // as the heavy stress designs in `multiple_shooting.rs`
        assert!(
            eq.relative < 1e-2,
            "at {}: {:.1e}",
            p.parameter,
            eq.relative
        );
    }
    let direct = solve(&r, &[], &SolveOptions::default(), None).unwrap();
    let gap = (direct.tip_position() - last.solution.tip_position()).norm();
    println!("end vs forward solve: {gap:.1e} m");
    // the same discrete equations on the same grid and segments, each
    // solved to its rounding floor (a relative 1e-8 of the unknowns)
    assert!(gap <= 1e-8 * r.body.length, "{gap:.1e} m");
}

/// An upright 10 x 9 mm column under 1.15 times Greenhill's self-weight
/// load (buckled about its weak axis, `y`; below the strong axis's
/// `(10/9)^2 = 1.23` times, so the straight column has one unstable mode) and a lateral tip force along
/// `y` scaled from -1 to 1: the imperfect pitchfork's S-curve (Thompson &
/// Hunt, *A General Theory of Elastic Stability*, Wiley 1973, ch. 3). The
/// branch bent to `-y` holds against the force up to a fold, turns back on
/// the unstable branch to the mirror fold and comes up the branch bent to
/// `+y`. Checked independently of the branch: the folds are mirror images
/// (to 1e-6 of the force, the location's accuracy); every point's parameter
/// lies between them on the middle branch and outside on the outer ones;
/// a forward solve warm from the last point before the first fold stays
/// bent to `-y` just below it (0.1 % of the fold's force) and snaps to `+y`
/// just above it, where no equilibrium bent to `-y` is left.
#[test]
fn snap_through_folds_located() {
    // the column at 1.15 times its self-weight buckling load (Greenhill:
    // rho A g L^3 / EI = 7.837)
    let mut r = heavy_column();
    r.body.gravity *= 1.15 * 7.837;
    let b = &mut r.body;
    let (a, len) = (b.section.properties().0, b.length);
    // a tenth of the weight, sideways
    b.tip_force = Vector3::new(0.0, 0.1 * b.density * a * len * b.gravity.norm(), 0.0);
    let pb = Problem::new(&r, Parameter::TipLoadScale, &[]).unwrap();
    let opts = BranchOptions {
        start: -1.0,
        end: 1.0,
        ..Default::default()
    };
    let br = follow_branch(&pb, &opts, None).unwrap();
    let folds: Vec<f64> = br
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Fold)
        .map(|e| e.parameter)
        .collect();
    println!(
        "folds at {folds:?}, {} points, {} IVP-equivalents, events {:?}",
        br.points.len(),
        br.evaluations,
        br.events
            .iter()
            .map(|e| (e.kind, e.parameter))
            .collect::<Vec<_>>()
    );
    assert_eq!(folds.len(), 2);
    let fc = folds[0];
    assert!(fc > 0.0 && fc < 1.0, "{fc}");
    assert!((folds[1] + fc).abs() < 1e-6, "{folds:?}");
    assert_eq!(br.points.last().unwrap().parameter, 1.0);
    let after = |i: usize| br.events.iter().filter(|e| e.after_point < i).count();
    for (i, p) in br.points.iter().enumerate() {
        let inside = p.parameter.abs() <= fc * (1.0 + 1e-9);
        match after(i) {
            1 => assert!(inside && !p.stability.stable, "{}", p.parameter),
            _ => assert!(p.stability.stable, "{}", p.parameter),
        }
        assert!(inside || p.parameter < -fc || p.parameter > fc);
    }
    let before = &br.points[br.events[0].after_point];
    let near = |scale: f64| {
        let (robot, inputs, loads) = pb.at(scale * fc).unwrap();
        let o = SolveOptions::default();
        tcarod::solve::forward::solve(&robot, &inputs, &loads, &o, Some(&before.solution))
            .unwrap()
            .tip_position()
            .y
    };
    let (below, above) = (near(1.0 - 1e-3), near(1.0 + 1e-3));
    println!("tip y just below the fold {below:.5} m, just above {above:.5} m");
    assert!(below < 0.0 && above > 0.0);
}
