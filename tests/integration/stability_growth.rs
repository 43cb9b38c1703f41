//! The stability verdict of heavy rods, whose tangent columns grow apart
//! by many orders of magnitude along the body (docs/stability.md,
//! "Computation"): Greenhill's upright column, the hanging rod that tension
//! stabilises, and the invariance of the verdict to the re-orthonormalisation
//! of the columns.

use nalgebra::Vector3;
use tcarod::experiments::{
    fig6_circle, fig6_square, soft_tendon_robot, soft_tendon_tension, steel_tendon_robot,
    table1_finger, STEEL_TENDON_TENSIONS,
};
use tcarod::rod::{Body, Robot, Section};
use tcarod::shooting::{solve, Solution, SolveOptions};
use tcarod::stability::{stability, stability_with_bound, Stability, GROWTH_BOUND};

/// Self-weight buckling of an upright column (Greenhill): rho A g L^3 / EI.
const GREENHILL: f64 = 7.837;

/// A straight round rod, L / r = 1000 (extension under its weight at most
/// w r^2 / 4 L^2 = 7.5e-4 at w = 3000), under its own weight with weight
/// ratio `w = rho A |g| L^3 / EI`, gravity along `sign` z (+1: hanging from
/// the base, -1: upright), Poisson 0.5.
fn heavy_rod(w: f64, sign: f64) -> Robot {
    let mut b = Body::new(1.0, Section::Circle { diameter: 2e-3 }, 1e6, 0.5, 1000.0).unwrap();
    let (a, ix, _, _) = b.section.properties();
    let g = w * b.youngs_modulus * ix / (b.density * a);
    b.gravity = Vector3::new(0.0, 0.0, sign * g);
    Robot::new(b, vec![]).unwrap()
}

/// The straight equilibrium of [`heavy_rod`] (the cold solve of the perfect
/// rod: nothing breaks the symmetry) and its verdict.
fn straight(w: f64, sign: f64) -> (Robot, Solution, Stability) {
    let r = heavy_rod(w, sign);
    let sol = solve(&r, &[], &SolveOptions::default(), None).unwrap();
    let tip = sol.tip_position();
    assert!(
        tip.x.abs() < 1e-9 && tip.y.abs() < 1e-9,
        "w = {w}: tip {tip}"
    );
    let st = stability(&r, &sol, &[]).unwrap();
    (r, sol, st)
}

/// Torsional tip stiffness of the straight rod, G J / L in units of EI / L:
/// `G J / E I = 1 / (1 + nu)` for a round section (J = 2 I).
const TWIST: f64 = 2.0 / 3.0;

#[test]
fn hanging_heavy_rod_is_stable() {
    for w in [10.0, 100.0, 1000.0, 3000.0] {
        let (r, sol, st) = straight(w, 1.0);
        let (_, count) = stability_with_bound(&r, &sol, &[], GROWTH_BOUND).unwrap();
        println!(
            "hanging w = {w}: stable {}, margin {:.15}, {count} re-orthonormalisations",
            st.stable, st.margin
        );
        // tension stiffens bending and gravity does not load the twist of
        // the straight rod: the softest tip mode is the twist, at G J / L
        assert!(st.stable && st.conjugate_point.is_none(), "w = {w}");
        assert!((st.margin - TWIST).abs() < 1e-9, "w = {w}: {}", st.margin);
        assert!(st.mode[5].abs() > 1.0 - 1e-9, "w = {w}: mode {:?}", st.mode);
        // the tangent columns of the heavy rods grow apart past the bound
        // (bending in tension: modes like exp(+-int sqrt(n / EI) ds),
        // exp(+-2/3 sqrt(w)) over this body), so the march replaces them
        if w >= 100.0 {
            assert!(count > 0, "w = {w}");
        }
    }
}

#[test]
fn upright_heavy_rod_buckles_above_greenhill() {
    let (_, _, below) = straight(5.0, -1.0);
    println!("upright w = 5: margin {:.6}", below.margin);
    assert!(below.stable && below.margin > 0.0);
    // the lateral mode is the soft one, below the twist
    assert!(below.margin < TWIST);
    for w in [10.0, 300.0] {
        let (_, _, st) = straight(w, -1.0);
        println!(
            "upright w = {w}: margin {:.6}, conjugate point {:?}",
            st.margin, st.conjugate_point
        );
        assert!(w > GREENHILL && !st.stable && st.margin < 0.0, "w = {w}");
        assert!(st.conjugate_point.is_some());
    }
}

/// A fixture: name, robot, inputs, blocked tip directions.
type Case = (&'static str, Robot, Vec<f64>, Vec<Vector3<f64>>);

/// Every fixture's verdict with the columns re-orthonormalised at every node
/// equals the plain one (which the default bound leaves untouched there).
#[test]
fn verdict_invariant_to_reorthonormalisation() {
    let mut cases: Vec<Case> = vec![];
    for t in [25.0, 100.0, 160.0] {
        let sq = fig6_square(true);
        let n = sq.actuators.len();
        cases.push(("fig6 square", sq, vec![t; n], vec![]));
        let ci = fig6_circle(true);
        let n = ci.actuators.len();
        cases.push(("fig6 circle", ci, vec![t; n], vec![]));
    }
    cases.push((
        "fig6 square, blocked x",
        fig6_square(true),
        vec![100.0; 2],
        vec![Vector3::x()],
    ));
    let finger = table1_finger();
    let n = finger.actuators.len();
    cases.push(("table1 finger", finger, vec![90.0; n], vec![]));
    cases.push((
        "steel tendon",
        steel_tendon_robot(),
        STEEL_TENDON_TENSIONS.to_vec(),
        vec![],
    ));
    cases.push((
        "soft tendon",
        soft_tendon_robot(),
        vec![soft_tendon_tension(2.0)],
        vec![],
    ));
    for (name, r, q, blocked) in cases {
        let sol = solve(&r, &q, &SolveOptions::default(), None).unwrap();
        let a = stability(&r, &sol, &blocked).unwrap();
        let (plain, untouched) = stability_with_bound(&r, &sol, &blocked, f64::INFINITY).unwrap();
        let (b, count) = stability_with_bound(&r, &sol, &blocked, 1.0).unwrap();
        let (_, used) = stability_with_bound(&r, &sol, &blocked, GROWTH_BOUND).unwrap();
        println!(
            "{name} {q:?}: margin {:.15e}, every node {:.15e} ({count}), diff {:.1e}, default re-orthonormalisations {used}",
            a.margin, b.margin, (a.margin - b.margin).abs()
        );
        assert_eq!((used, untouched), (0, 0));
        assert_eq!(a.margin.to_bits(), plain.margin.to_bits());
        // (the base node's columns are orthonormal already)
        assert!(count + 1 >= sol.s.len());
        assert_eq!(a.stable, b.stable);
        assert_eq!(a.conjugate_point, b.conjugate_point);
        // each of the ~100 replacements is exact up to the rounding of the
        // columns (a few eps relative), which the tip stiffness amplifies by
        // the condition of H(L) (1e2 to 1e3 on these robots): ~1e-11, well
        // inside 1e-9
        assert!(
            (a.margin - b.margin).abs() < 1e-9 * (1.0 + a.margin.abs()),
            "{name}"
        );
        for (x, y) in a.determinant.iter().zip(&b.determinant) {
            assert!(
                (x - y).abs() <= 1e-9 * x.abs().max(1.0),
                "{name}: det {x} vs {y}"
            );
        }
    }
}

/// The tip stiffness with actuator springs (S3) of a heavy hanging rod: two
/// linear tendons at opposite offsets, pulled alike (the rod stays
/// straight), so the actuator directions are integrated and carried through
/// the re-orthonormalisations with the base strains.
#[test]
fn hanging_heavy_rod_with_tendon_springs() {
    use std::sync::Arc;
    use tcarod::rod::{Actuator, LinearTendon, Routing};
    for w in [100.0, 1000.0] {
        let body = heavy_rod(w, 1.0).body;
        let tendon = |x: f64| {
            Actuator::new(
                Routing::Straight { x, y: 0.0 },
                0.0,
                1.0,
                Arc::new(LinearTendon { stiffness: 10.0 }),
            )
        };
        let r = Robot::new(body, vec![tendon(0.5e-3), tendon(-0.5e-3)]).unwrap();
        let sol = solve(&r, &[1e-3, 1e-3], &SolveOptions::default(), None).unwrap();
        let tip = sol.tip_position();
        assert!(
            tip.x.abs() < 1e-9 && tip.y.abs() < 1e-9,
            "w = {w}: tip {tip}"
        );
        let a = stability(&r, &sol, &[]).unwrap();
        let (_, used) = stability_with_bound(&r, &sol, &[], GROWTH_BOUND).unwrap();
        let (b, count) = stability_with_bound(&r, &sol, &[], 1.0).unwrap();
        println!(
            "hanging w = {w} with tendons: margin {:.15} ({used} re-orthonormalisations), every node {:.15} ({count})",
            a.margin, b.margin
        );
        assert!(used > 0);
        assert!(a.stable && b.stable && a.margin > 0.0);
        // two schedules of re-orthonormalisation, one verdict: each
        // replacement is exact up to the rounding of the columns
        assert!((a.margin - b.margin).abs() < 1e-9 * (1.0 + a.margin.abs()));
    }
}

/// The verdict of a recorded solution is taken along its own states
/// (docs/stability.md, "Computation"): on a heavy body's multiple-shooting
/// solution, whose base unknowns the IVP no longer carries to its tip to
/// the solution's accuracy, it converges with the grid like the solution
/// itself. Horizontal designs of the stress family (weight ratio 20-3,000):
/// halving RK4's step moves their tips by less than 1e-5 L (O(h^4)), and
/// the margin is a smooth function of the equilibrium, so the two grids'
/// margins agree to 1e-3; a pass that left the equilibrium scatters by up
/// to 0.1 between grids.
#[test]
fn verdict_of_a_multiple_shooting_solution_converges_with_the_grid() {
    use tcarod::problems::held_out::{stress_design, STRESS_SEED};
    use tcarod::solve::{forward, residual::Loads};
    for i in (2..24).step_by(3) {
        let d = stress_design(STRESS_SEED, i);
        let loads = Loads::of(&d.robot);
        let [coarse, fine] = [100, 200].map(|steps| {
            let opts = SolveOptions {
                steps,
                ..Default::default()
            };
            let sol = forward::solve(&d.robot, &d.inputs, &loads, &opts, None)
                .unwrap_or_else(|e| panic!("stress design {i}, {steps} steps: {e}"));
            stability(&d.robot, &sol, &[]).unwrap()
        });
        assert_eq!(coarse.stable, fine.stable, "stress design {i}");
        let tol = 1e-3 * fine.margin.abs().max(1.0);
        assert!(
            (coarse.margin - fine.margin).abs() < tol,
            "stress design {i}: margin {} on 100 steps, {} on 200",
            coarse.margin,
            fine.margin
        );
    }
}

/// On a solution of one IVP the pass along the recorded states is that
/// IVP: the verdict is the one from the unknowns, bit for bit.
#[test]
fn verdict_along_the_recorded_states_of_one_ivp_is_the_plain_one() {
    use tcarod::stability::{stability_at, Equilibrium};
    let finger = table1_finger();
    let n = finger.actuators.len();
    let cases = [
        (fig6_square(true), vec![100.0; 2]),
        (finger, vec![90.0; n]),
        (steel_tendon_robot(), STEEL_TENDON_TENSIONS.to_vec()),
    ];
    for (robot, inputs) in cases {
        let sol = solve(&robot, &inputs, &SolveOptions::default(), None).unwrap();
        let along = stability(&robot, &sol, &[]).unwrap();
        let eq = Equilibrium {
            along: None,
            ..Equilibrium::from(&sol)
        };
        let plain = stability_at(&robot, &eq, &[]).unwrap();
        assert_eq!((along.stable, along.margin), (plain.stable, plain.margin));
        assert_eq!(along.determinant, plain.determinant);
    }
}
