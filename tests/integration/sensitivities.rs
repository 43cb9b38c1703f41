//! The paper's finite-difference J and C (eqs 39-42) on the 40 mm square
//! manipulator, upright: the forward scheme (the paper's) agrees with central
//! differences, heating moves the tip toward -x, and C is a symmetric compliance
//! with a positive diagonal. Brute force (differences of full solves) and the
//! exact tangents are checked in tests/integration/inverse.rs.
use tcarod::experiments::square_manipulator;
use tcarod::inverse::{sensitivities, Groups, Scheme};
use tcarod::shooting::{solve, Loads, SolveOptions};

#[test]
fn forward_and_central_schemes_agree() {
    let robot = square_manipulator(0.040, true);
    let sol = solve(&robot, &[80.0, 120.0], &SolveOptions::default(), None).unwrap();
    let loads = Loads::of(&robot);
    let groups = Groups::identity(2); // one variable per leg
    let run = |scheme| sensitivities(&robot, &sol, &loads, &groups, sol.steps, scheme).unwrap();
    let (f, c) = (run(Scheme::Forward), run(Scheme::Central));
    assert_eq!(f.jacobian.shape(), (6, 2));
    // forward differences: relative error ~sqrt(eps) x curvature ~1e-7; 1e-4 is generous
    let ej = (&f.jacobian - &c.jacobian).amax();
    let ec = (&f.compliance - &c.compliance).amax();
    assert!(ej < 1e-4 * c.jacobian.amax(), "J: {ej:e}");
    assert!(ec < 1e-4 * c.compliance.amax(), "C: {ec:e}");
}

#[test]
fn heating_moves_the_tip_toward_minus_x_and_c_is_a_compliance() {
    let robot = square_manipulator(0.040, true);
    let sol = solve(&robot, &[100.0, 100.0], &SolveOptions::default(), None).unwrap();
    let s = sensitivities(
        &robot,
        &sol,
        &Loads::of(&robot),
        &Groups(vec![0, 0]),
        sol.steps,
        Scheme::Central,
    )
    .unwrap();
    // TCA at +x: heating moves the tip toward -x
    assert!(s.jacobian[(0, 0)] < 0.0, "{}", s.jacobian);
    // conservative loads: C is symmetric (central differences, ~1e-8) and
    // positive on its diagonal
    let c = &s.compliance;
    assert!((c - c.transpose()).amax() < 1e-6 * c.amax());
    assert!((0..6).all(|k| c[(k, k)] > 0.0), "{c}");
}
