//! The verdict of heavy hanging and standing bodies (docs/stability.md,
//! "Growing tangents"): a rod hanging under its own weight, vertical or
//! tilted, is stable at every weight ratio (tension stiffens it); an upright
//! column is stable below Greenhill's self-weight load and unstable above
//! it; the verdict along a growing load is continuous; and the margin is the
//! tip stiffness measured independently, by the tip displacements under
//! small extra tip loads on the solver's own equilibria.

use nalgebra::{Matrix3, Matrix6, Vector3};
use tcarod::branch::{follow_branch, BranchOptions, EventKind, Parameter, Problem};
use tcarod::rod::{Body, Robot, Section};
use tcarod::shooting::{Solution, SolveOptions};
use tcarod::solve::{forward, residual::Loads};
use tcarod::stability::{stability, stability_with_bound, NEUTRAL};

/// Self-weight buckling of a clamped-free column (Greenhill): rho A g L^3 / EI.
const GREENHILL: f64 = 7.837;

/// A round rod of L / r = 1000 under its own weight of weight ratio
/// `w = rho A |g| L^3 / EI`, gravity along `dir` (+z: hanging from the base;
/// -z: upright), Poisson 0.5.
fn rod(w: f64, dir: Vector3<f64>) -> Robot {
    let mut b = Body::new(1.0, Section::Circle { diameter: 2e-3 }, 1e6, 0.5, 1000.0).unwrap();
    let (a, ix, _, _) = b.section.properties();
    let g = w * b.youngs_modulus * ix / (b.density * a);
    b.gravity = dir.normalize() * g;
    Robot::new(b, vec![]).unwrap()
}

/// 45 degrees from the vertical, in the x-z plane.
fn tilted() -> Vector3<f64> {
    Vector3::new(1.0, 0.0, 1.0)
}

/// RK4 steps that resolve the bending length `sqrt(EI / T) = L / sqrt(w)`
/// of the tension near the base: steps of at most half a bending length,
/// and at least the default 100.
fn steps(w: f64) -> usize {
    100.max((2.0 * w.sqrt()).ceil() as usize)
}

fn solve(robot: &Robot, loads: &Loads, steps: usize, warm: Option<&Solution>) -> Solution {
    let opts = SolveOptions {
        steps,
        ..Default::default()
    };
    forward::solve(robot, &[], loads, &opts, warm).unwrap()
}

/// Tension stiffens bending and gravity leaves the twist alone: a hanging
/// rod is stable at every weight ratio, vertical or tilted, and its margin
/// is the softest tip mode, near the twist `G J / E I = 2/3`. The margin
/// does not depend on the schedule of the march's re-orthonormalisations
/// (the default bound, or at every node): each replacement is exact to the
/// rounding of the columns, read through an orthonormal basis of their span.
#[test]
fn hanging_rods_are_stable_at_every_weight_ratio() {
    for w in [10.0, 300.0, 3000.0, 30000.0] {
        for (name, dir) in [("vertical", Vector3::z()), ("tilted", tilted())] {
            let r = rod(w, dir);
            let sol = solve(&r, &Loads::of(&r), steps(w), None);
            let st = stability(&r, &sol, &[]).unwrap();
            let (every, _) = stability_with_bound(&r, &sol, &[], 1.0).unwrap();
            println!(
                "hanging {name} w = {w}: margin {:.12}, every node {:.12}",
                st.margin, every.margin
            );
            assert!(st.stable && st.conjugate_point.is_none(), "{name} w = {w}");
            // a bending mode with the tension's stiffness, or the twist
            // (2/3 for the straight rod; the tilted rod's bend couples it)
            assert!(st.margin > 0.5 && st.margin < 0.7, "{name} w = {w}");
            assert!(every.stable, "{name} w = {w}");
            // below NEUTRAL, the resolution of the verdict
            assert!((st.margin - every.margin).abs() < NEUTRAL, "{name} w = {w}");
        }
    }
}

/// An upright straight column: stable below Greenhill's self-weight load
/// (0.9 times), unstable above it (1.2 times), with a conjugate point
/// inside the body.
#[test]
fn upright_column_is_stable_below_greenhill_only() {
    for (f, stable) in [(0.9, true), (1.2, false)] {
        let r = rod(f * GREENHILL, -Vector3::z());
        let sol = solve(&r, &Loads::of(&r), 100, None);
        let st = stability(&r, &sol, &[]).unwrap();
        println!("upright {f} x Greenhill: margin {:.6}", st.margin);
        assert_eq!(st.stable, stable, "{f} x Greenhill");
        assert_eq!(st.margin > 0.0, stable, "{f} x Greenhill");
        assert_eq!(st.conjugate_point.is_some(), !stable, "{f} x Greenhill");
    }
}

/// The tilted rod of weight ratio 3000 followed in gravity scale from 0 to
/// 1 (the branch of `branch.rs`): every point is stable, no event is
/// located, and the margin changes smoothly from point to point (the tip
/// stiffness of a body bending toward the vertical under a growing load;
/// a false conjugate point at `s_c` would drop it below `-(L - s_c)/L`).
#[test]
fn verdict_is_continuous_along_gravity_scale() {
    let r = rod(3000.0, tilted());
    let pb = Problem::new(&r, Parameter::GravityScale, &[]).unwrap();
    let opts = BranchOptions {
        start: 0.0,
        end: 1.0,
        ..Default::default()
    };
    let br = follow_branch(&pb, &opts, None).unwrap();
    for p in &br.points {
        println!(
            "gravity scale {:.4}: margin {:.9}",
            p.parameter, p.stability.margin
        );
        assert!(p.stability.stable, "at {}", p.parameter);
        // between the unloaded rod's twist 2/3 and its bending stiffness
        // in tension: the softest mode stays the twist
        assert!(p.stability.margin > 0.6, "at {}", p.parameter);
    }
    assert!(br.events.iter().all(|e| e.kind != EventKind::Bifurcation));
    assert!(br.events.is_empty(), "{:?}", br.events);
}

/// Tip compliance by central differences of the equilibrium under small
/// extra tip loads (dead, world frame, forces in `EI / L^2`, moments in
/// `EI / L`), each solved warm from `sol` on its grid: the inverse of the
/// tip stiffness (S2), `d (p / L, theta)(L) / d (n L^2 / EI, m L / EI)`.
fn tip_stiffness(r: &Robot, sol: &Solution, h: f64) -> Matrix6<f64> {
    let b = &r.body;
    let (ei, len) = (b.bending_stiffness(), b.length);
    let base = Loads::of(r);
    let mut c = Matrix6::zeros();
    for j in 0..6 {
        let pose = |sign: f64| {
            let mut l = base;
            if j < 3 {
                l.tip_force[j] += sign * h * ei / (len * len);
            } else {
                l.tip_moment[j - 3] += sign * h * ei / len;
            }
            let s = solve(r, &l, sol.steps, Some(sol));
            let dr: Matrix3<f64> = s.tip_rotation() * sol.tip_rotation().transpose();
            let th = Vector3::new(
                dr[(2, 1)] - dr[(1, 2)],
                dr[(0, 2)] - dr[(2, 0)],
                dr[(1, 0)] - dr[(0, 1)],
            ) * 0.5;
            (s.tip_position() / len, th)
        };
        let ((pp, tp), (pm, tm)) = (pose(1.0), pose(-1.0));
        let dp = (pp - pm) / (2.0 * h);
        let dt = (tp - tm) / (2.0 * h);
        for i in 0..3 {
            c[(i, j)] = dp[i];
            c[(3 + i, j)] = dt[i];
        }
    }
    c.try_inverse().unwrap()
}

/// The margin is the smallest eigenvalue of the symmetric tip stiffness, so
/// it can be measured without the verdict's tangents: by the tip's response
/// to small extra tip loads, on the multiple-shooting equilibria the solver
/// finds (independent of the plain tangent, which has no digit left at
/// `w = 3000`; on the light rod, w = 10, it is fine). Tolerance: central differences
/// with loads of 1e-3 carry a truncation error of ~1e-6 relative, and each
/// solve's residual (1e-10, the default tol, as strain errors) enters the
/// compliance divided by the load, 1e-7; the tip stiffness of these rods
/// is at most ~1e2 in the directions that matter, so 1e-4 on the margin.
#[test]
fn margin_is_the_measured_tip_stiffness() {
    for w in [10.0, 3000.0] {
        let r = rod(w, tilted());
        let sol = solve(&r, &Loads::of(&r), 100, None);
        let st = stability(&r, &sol, &[]).unwrap();
        let k = tip_stiffness(&r, &sol, 1e-3);
        let measured = ((k + k.transpose()) * 0.5).symmetric_eigenvalues().min();
        println!(
            "tilted w = {w}: margin {:.9}, measured {measured:.9}",
            st.margin
        );
        assert!(
            (st.margin - measured).abs() < 1e-4,
            "w = {w}: {} vs {measured}",
            st.margin
        );
    }
}
