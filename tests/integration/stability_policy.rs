//! The stability policy of a solve (docs/stability.md, "The stability of
//! every solve"): `solve_checked` never hands back an unstable equilibrium
//! without saying so, the verdict costs at most one tangent IVP, and
//! `Continue` moves to a stable one at the same inputs (the post-buckled
//! elastica, checked against Euler's closed form with elliptic integrals).

use nalgebra::Vector3;
use tcarod::error::Error;
use tcarod::experiments::{
    fig6_square, soft_tendon_robot, soft_tendon_tension, steel_tendon_robot, table1_finger,
    STEEL_TENDON_TENSIONS,
};
use tcarod::problems::{
    equilibrium, overloaded_column, random_design, DEFAULT_SEED, EQUILIBRIUM_TOL,
};
use tcarod::rod::{Body, Robot, Section};
use tcarod::shooting::{assemble, solve_loaded, Loads, Solution, SolveOptions};
use tcarod::stability::{solve_checked, stability, Policy};

/// A slender round column (L/r = 100) under a dead compressive tip load of
/// `ratio` times the Euler load `pi^2 EI / (4 L^2)`; weightless, so the
/// elastica below is exact up to shear and extension (~2e-4 relative).
fn column(ratio: f64) -> Robot {
    let len = 0.5;
    let mut b = Body::new(len, Section::Circle { diameter: 10e-3 }, 1e6, 0.5, 1000.0).unwrap();
    b.gravity = Vector3::zeros();
    let (_, ix, _, _) = b.section.properties();
    let pc = std::f64::consts::PI.powi(2) * b.youngs_modulus * ix / (4.0 * len * len);
    b.tip_force = Vector3::new(0.0, 0.0, -ratio * pc);
    Robot::new(b, vec![]).unwrap()
}

/// Complete elliptic integral of the first kind K(k) by the AGM.
fn ellip_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    for _ in 0..30 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Lateral tip deflection / L of the clamped-free inextensible elastica under
/// a dead axial tip load `ratio` P_E (first mode): `lambda L = K(k)` with
/// `lambda = sqrt(P / EI)`, deflection `2 k / lambda`.
fn elastica_deflection(ratio: f64) -> f64 {
    let target = std::f64::consts::FRAC_PI_2 * ratio.sqrt();
    let (mut lo, mut hi) = (0.0, 0.999_999);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if ellip_k(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let k = 0.5 * (lo + hi);
    2.0 * k / ellip_k(k)
}

fn lateral(p: Vector3<f64>) -> f64 {
    (p.x * p.x + p.y * p.y).sqrt()
}

#[test]
fn report_carries_the_verdict_at_one_tangent_ivp() {
    let opts = SolveOptions::default();
    for (ratio, stable) in [(0.5, true), (1.5, false)] {
        let r = column(ratio);
        let loads = Loads::of(&r);
        let plain = solve_loaded(&r, &[], &loads, &opts, None).unwrap();
        let c = solve_checked(&r, &[], &loads, &opts, None, Policy::Report).unwrap();
        let st = c.stability.expect("Report always carries a verdict");
        assert_eq!(st.stable, stable, "ratio {ratio}: margin {}", st.margin);
        assert_eq!(st.stable, st.margin > 0.0);
        // the same equilibrium (the cold solve of the perfect column is
        // straight: on the axis to rounding)
        assert_eq!(c.solution.unknowns, plain.unknowns);
        assert!(lateral(c.solution.tip_position()) < 1e-9);
        // cost: exactly one integration (a tangent IVP) more than the solve
        assert_eq!(st.evaluations, 1);
        assert_eq!(c.solution.evaluations, plain.evaluations + 1);
        assert!(c.continued.is_none());
    }
}

/// Every recorded field of two solutions is the same, bit for bit.
fn assert_same_profile(a: &Solution, b: &Solution, what: &str) {
    assert_eq!(a.s, b.s, "{what}: s");
    assert_eq!(a.positions, b.positions, "{what}: positions");
    assert_eq!(a.rotations, b.rotations, "{what}: rotations");
    assert_eq!(a.nu, b.nu, "{what}: nu");
    assert_eq!(a.omega, b.omega, "{what}: omega");
    assert_eq!(a.internal_force, b.internal_force, "{what}: force");
    assert_eq!(a.internal_moment, b.internal_moment, "{what}: moment");
    assert_eq!(
        a.elongation_profile, b.elongation_profile,
        "{what}: delta(s)"
    );
    assert_eq!(a.actuator_paths, b.actuator_paths, "{what}: paths");
    assert_eq!(a.tensions, b.tensions, "{what}: tensions");
    assert_eq!(a.elongations, b.elongations, "{what}: elongations");
    assert_eq!(a.base_force, b.base_force, "{what}: base force");
    assert_eq!(a.base_moment, b.base_moment, "{what}: base moment");
    assert_eq!(a.residual, b.residual, "{what}: residual");
}

/// The four fixtures of the bit-for-bit tests: robot, inputs and the
/// inputs of the warm start. TCAs (Fig. 6, Table I), tendons through spacer
/// disks (steel) and a soft tendon rod.
fn fixtures() -> [(Robot, Vec<f64>, Vec<f64>); 4] {
    [
        (fig6_square(true), vec![100.0, 100.0], vec![98.0, 98.0]),
        (table1_finger(), vec![90.0; 2], vec![88.0; 2]),
        (
            steel_tendon_robot(),
            STEEL_TENDON_TENSIONS.to_vec(),
            vec![14.0, 0.0, 0.0, 0.0],
        ),
        (
            soft_tendon_robot(),
            vec![soft_tendon_tension(1.0)],
            vec![soft_tendon_tension(0.9)],
        ),
    ]
}

/// With a verdict, the solution is the one the solve without a verdict
/// hands back, bit for bit (the verdict is taken of it afterwards), and
/// its work counts the verdict's tangent integration too; rebuilding it
/// from its unknowns by a plain IVP (what a pickled solution does) gives
/// it back bit for bit. Cold and warm, on the four fixtures.
#[test]
fn report_hands_back_the_off_solution_bit_for_bit() {
    let opts = SolveOptions::default();
    for (robot, q, q_warm) in fixtures().iter() {
        assert_eq!(q.len(), robot.actuators.len());
        let loads = Loads::of(robot);
        let warm = solve_loaded(robot, q_warm, &loads, &opts, None).unwrap();
        for w in [None, Some(&warm)] {
            let checked = |p| solve_checked(robot, q, &loads, &opts, w, p).unwrap();
            let off = checked(Policy::Off).solution;
            let on = checked(Policy::Report);
            let what = format!("inputs {q:?}, warm {}", w.is_some());
            let verdict = on.stability.as_ref().expect("Report carries a verdict");
            let on = on.solution;
            assert_eq!(on.unknowns, off.unknowns, "{what}");
            assert_eq!(on.iterations, off.iterations, "{what}");
            assert_eq!(
                on.evaluations,
                off.evaluations + verdict.evaluations,
                "{what}"
            );
            assert_same_profile(&on, &off, &what);
            let again = assemble(robot, q, &loads, &on.unknowns, on.steps, 0, 0).unwrap();
            assert_same_profile(&again, &on, &format!("{what}, rebuilt"));
        }
    }
}

/// The verdict under `Report` is the one `stability` takes of the solution
/// by its own integration, bit for bit, from one tangent integration. All
/// eight runs of the four fixtures.
#[test]
fn report_takes_the_verdict_of_the_solution() {
    let opts = SolveOptions::default();
    let mut hits = 0;
    for (robot, q, q_warm) in fixtures().iter() {
        let loads = Loads::of(robot);
        let warm = solve_loaded(robot, q_warm, &loads, &opts, None).unwrap();
        for w in [None, Some(&warm)] {
            let what = format!("inputs {q:?}, warm {}", w.is_some());
            let checked = |p| solve_checked(robot, q, &loads, &opts, w, p).unwrap();
            let off = checked(Policy::Off);
            let on = checked(Policy::Report);
            let st = on.stability.expect("Report carries a verdict");
            let again = stability(robot, &off.solution, &[]).unwrap();
            assert_eq!(st.evaluations, 1, "{what}: one tangent integration");
            assert_eq!(
                (st.stable, st.margin),
                (again.stable, again.margin),
                "{what}"
            );
            assert_eq!(st.determinant, again.determinant, "{what}");
            assert_eq!(st.min_stiffness, again.min_stiffness, "{what}");
            assert_eq!(st.mode, again.mode, "{what}");
            hits += 1;
        }
    }
    assert_eq!(hits, 8);
}

/// The accuracy control under a verdict: the seeded benchmark design drawn
/// here (a 25 mm body with a tight helix, equilibrium check at 2.5e-5 on 100
/// steps, see `tests/integration/designs.rs`) is refined to a finer grid, and
/// the solution handed back with the verdict is the one `Off` refines to, with
/// the verdict of that refined solution (taken on its grid) for one tangent
/// IVP more.
#[test]
fn report_with_equilibrium_tol_gives_the_verdict_of_the_refined_solution() {
    let d = random_design(DEFAULT_SEED, 158);
    let loads = Loads::of(&d.robot);
    let o = SolveOptions {
        tol: 1e-10,
        equilibrium_tol: Some(EQUILIBRIUM_TOL),
        ..Default::default()
    };
    let checked = |p| solve_checked(&d.robot, &d.inputs, &loads, &o, None, p).unwrap();
    let off = checked(Policy::Off).solution;
    let on = checked(Policy::Report);
    assert!(
        off.steps > o.steps,
        "the design needs a refined grid: {} steps",
        off.steps
    );
    assert!(equilibrium(&d.robot, &off).relative <= EQUILIBRIUM_TOL);
    assert_eq!(on.solution.steps, off.steps);
    assert_eq!(on.solution.unknowns, off.unknowns);
    assert_eq!(on.solution.iterations, off.iterations);
    assert_same_profile(&on.solution, &off, "refined grid");
    let st = on.stability.expect("Report carries a verdict");
    let again = stability(&d.robot, &off, &[]).unwrap();
    assert_eq!(st.s, again.s, "the verdict is taken on the refined grid");
    assert_eq!((st.stable, st.margin), (again.stable, again.margin));
    // the verdict, on the refined grid only: one tangent IVP
    assert_eq!(on.solution.evaluations, off.evaluations + 1);
}

#[test]
fn off_skips_and_require_refuses() {
    let opts = SolveOptions::default();
    let r = column(1.5);
    let loads = Loads::of(&r);
    let plain = solve_loaded(&r, &[], &loads, &opts, None).unwrap();
    let off = solve_checked(&r, &[], &loads, &opts, None, Policy::Off).unwrap();
    assert!(off.stability.is_none());
    assert_eq!(off.solution.evaluations, plain.evaluations);
    match solve_checked(&r, &[], &loads, &opts, None, Policy::Require) {
        Err(Error::NoSolution { reason }) => {
            assert!(
                reason.contains("unstable") && reason.contains("margin"),
                "{reason}"
            )
        }
        other => panic!("expected NoSolution, got {other:?}"),
    }
    // a stable equilibrium passes `Require` unchanged
    let r = column(0.5);
    let c = solve_checked(&r, &[], &Loads::of(&r), &opts, None, Policy::Require).unwrap();
    assert!(c.stability.unwrap().stable);
}

#[test]
fn policy_names_parse_and_bad_ones_name_the_argument() {
    for (s, p) in [
        ("report", Policy::Report),
        ("require", Policy::Require),
        ("continue", Policy::Continue),
        ("off", Policy::Off),
    ] {
        assert_eq!(s.parse::<Policy>().unwrap(), p);
    }
    assert_eq!(Policy::default(), Policy::Report);
    let e = "stable".parse::<Policy>().unwrap_err().to_string();
    assert!(e.contains("stability") && e.contains("'continue'"), "{e}");
}

#[test]
fn continue_lands_on_the_post_buckled_elastica() {
    let opts = SolveOptions::default();
    for ratio in [1.2, 1.5, 2.0] {
        let r = column(ratio);
        let loads = Loads::of(&r);
        let c = solve_checked(&r, &[], &loads, &opts, None, Policy::Continue).unwrap();
        let st = c.stability.expect("verdict");
        assert!(st.stable, "ratio {ratio}: margin {}", st.margin);
        let cont = c.continued.expect("the straight column was unstable");
        // it started from the straight column (on the axis to rounding)
        assert!(!cont.from_stability.stable && lateral(cont.from.tip_position()) < 1e-9);
        // the route is recorded (loading with an imperfection, or a perturbed Newton start)
        assert!(!cont.route.to_string().is_empty() && cont.candidates >= 1);
        assert!(cont.evaluations > 0 && c.solution.evaluations > cont.evaluations);
        // the same problem: inputs and loads unchanged, an equilibrium to tol
        assert_eq!(c.solution.loads, loads);
        assert!(c.solution.residual <= opts.tol);
        let d = lateral(c.solution.tip_position()) / 0.5;
        let e = elastica_deflection(ratio);
        println!(
            "P/P_E = {ratio}: continued tip deflection {d:.5} L, elastica {e:.5} L ({})",
            cont.route
        );
        // 1e-3 L: shear and extension of an L/r = 100 column (~2e-4) and RK4
        assert!((d - e).abs() < 1e-3, "ratio {ratio}: {d} vs elastica {e}");
    }
}

/// An upright round silicone column (L 100 mm, d 12 mm, E 70 kPa, density
/// 1,070 kg/m^3) under `factor` times its self-weight buckling load.
fn greenhill_column(factor: f64) -> Robot {
    let b = Body::new(0.1, Section::Circle { diameter: 12e-3 }, 70e3, 0.5, 1070.0).unwrap();
    overloaded_column(b, factor)
}

#[test]
fn continue_bends_an_overloaded_round_column_over() {
    let opts = SolveOptions::default();
    let mut heights = vec![];
    for factor in [1.1, 2.0, 3.7, 5.0] {
        let r = greenhill_column(factor);
        let loads = Loads::of(&r);
        let c = solve_checked(&r, &[], &loads, &opts, None, Policy::Continue).unwrap();
        let st = c.stability.expect("verdict");
        // the bent column's turn about the vertical is a neutral mode: its
        // margin is zero up to rounding, which the verdict counts as stable
        assert!(st.stable, "{factor} x Greenhill: margin {}", st.margin);
        let cont = c.continued.expect("the straight column is unstable");
        assert!(!cont.from_stability.stable && lateral(cont.from.tip_position()) < 1e-9);
        assert!(c.solution.residual <= opts.tol && c.solution.loads == loads);
        let tip = c.solution.tip_position();
        // bent over: the tip a good fraction of the length off the axis
        assert!(lateral(tip) > 0.3 * r.body.length, "{factor}: tip {tip:?}");
        // a planar shape, in the vertical plane through the tip (the loads
        // have no moment about the vertical to turn it out of that plane)
        let n = Vector3::new(-tip.y, tip.x, 0.0) / lateral(tip);
        let off = c
            .solution
            .positions
            .iter()
            .map(|p| p.dot(&n).abs())
            .fold(0.0, f64::max);
        assert!(off < 1e-9 * r.body.length, "{factor}: {off} m out of plane");
        // the base wrench balances the weight up to RK4's error: at most
        // 1e-5 of the load scale on 100 steps, falling as h^4 (16-fold on
        // twice the steps; 10-fold asked)
        let eq = equilibrium(&r, &c.solution).relative;
        let fine = SolveOptions { steps: 200, ..opts };
        let c2 = solve_checked(&r, &[], &loads, &fine, None, Policy::Continue).unwrap();
        let eq2 = equilibrium(&r, &c2.solution).relative;
        assert!(
            eq < 1e-5 && eq2 < 0.1 * eq,
            "{factor}: global equilibrium {eq}, {eq2}"
        );
        println!(
            "{factor} x Greenhill: tip ({:.4}, {:.4}) m off the axis / height, {} IVPs ({})",
            lateral(tip),
            tip.z,
            c.solution.evaluations,
            cont.route
        );
        heights.push(tip.z);
    }
    // a heavier column droops further: its tip is lower
    assert!(heights.windows(2).all(|w| w[1] < w[0]), "{heights:?}");
}

/// Upright columns drawn from a seed (length 50-300 mm, modulus 10 kPa-1 MPa,
/// round or rectangular with aspect 0.5-1, 5-20 mm) at 1.05 to 6 times
/// their self-weight buckling load: `stability="continue"` lands every one
/// on a stable shape off the axis.
#[test]
fn continue_lands_every_overloaded_column_of_a_family() {
    use tcarod::problems::nonlinear::splitmix64;
    let mut state = 0x51ab_1e00_c011_u64;
    let mut u = || {
        state = splitmix64(state);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for i in 0..40 {
        let len = 0.05 + 0.25 * u();
        let modulus = 10f64.powf(4.0 + 2.0 * u());
        let d = 0.005 + 0.015 * u();
        let section = match u() < 0.5 {
            true => Section::Circle { diameter: d },
            false => Section::Rectangle {
                width: d,
                height: d * (0.5 + 0.5 * u()),
            },
        };
        let factor = 1.05 + 4.95 * u();
        let b = Body::new(len, section, modulus, 0.5, 1070.0).unwrap();
        let r = overloaded_column(b, factor);
        let loads = Loads::of(&r);
        let opts = SolveOptions::default();
        let c = solve_checked(&r, &[], &loads, &opts, None, Policy::Continue)
            .unwrap_or_else(|e| panic!("column {i} ({factor:.2} x Greenhill): {e}"));
        assert!(c.stability.is_some_and(|s| s.stable), "column {i}");
        assert!(
            c.continued.is_some() && c.solution.residual <= opts.tol,
            "column {i}"
        );
        let tip = c.solution.tip_position();
        assert!(
            lateral(tip) > 0.1 * len,
            "column {i} ({factor:.2} x): tip {tip:?}"
        );
    }
}
