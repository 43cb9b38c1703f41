//! Checks of the inverse kinetostatics (paper Section IV, eqs 37-44) against
//! brute force: J and C by central differences of full BVP solves, the
//! blocked-tip temperature (eq 43) against a direct solve, the tip-position
//! inverse (eq 40), the grasp (eq 44), and the exact sensitivities.
use nalgebra::{DMatrix, Vector3};
use tcarod::experiments::{fig6_circle, fig6_square, square_manipulator, G0};
use tcarod::inverse::*;
use tcarod::shooting::{assemble, solve, solve_loaded, Loads, SolveOptions};

fn opts() -> SolveOptions {
    SolveOptions {
        tol: 1e-12,
        ..Default::default()
    }
}

/// Brute-force J and C: central differences of full BVP solves.
fn brute(
    robot: &tcarod::rod::Robot,
    inputs: &[f64],
    loads: &Loads,
    groups: &Groups,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let base = solve_loaded(robot, inputs, loads, &opts(), None).unwrap();
    let nz = groups.n_vars();
    let z0 = groups.vars(inputs);
    let pose = |s: &tcarod::shooting::Solution| {
        let th = rotation_vector(&(s.tip_rotation() * base.tip_rotation().transpose()));
        let p = s.tip_position();
        DMatrix::from_column_slice(6, 1, &[p.x, p.y, p.z, th.x, th.y, th.z])
    };
    let mut j = DMatrix::zeros(6, nz);
    for k in 0..nz {
        let h = 1e-2; // C; O(h^2) error ~1e-8 relative for this smooth response
        let mut zp = z0.clone();
        zp[k] += h;
        let sp = solve_loaded(robot, &groups.inputs(&zp), loads, &opts(), Some(&base)).unwrap();
        zp[k] -= 2.0 * h;
        let sm = solve_loaded(robot, &groups.inputs(&zp), loads, &opts(), Some(&base)).unwrap();
        j.set_column(k, &((pose(&sp) - pose(&sm)) / (2.0 * h)).column(0));
    }
    let (fc, mc) = load_scales(robot);
    let mut c = DMatrix::zeros(6, 6);
    for k in 0..6 {
        let h = 1e-3 * if k < 3 { fc } else { mc };
        let mut lp = *loads;
        let mut lm = *loads;
        if k < 3 {
            lp.tip_force[k] += h;
            lm.tip_force[k] -= h;
        } else {
            lp.tip_moment[k - 3] += h;
            lm.tip_moment[k - 3] -= h;
        }
        let sp = solve_loaded(robot, inputs, &lp, &opts(), Some(&base)).unwrap();
        let sm = solve_loaded(robot, inputs, &lm, &opts(), Some(&base)).unwrap();
        c.set_column(k, &((pose(&sp) - pose(&sm)) / (2.0 * h)).column(0));
    }
    (j, c)
}

#[test]
fn jacobian_and_compliance_match_brute_force() {
    let cases = [
        (fig6_square(true), vec![100.0, 100.0], Groups(vec![0, 0])),
        (fig6_square(false), vec![70.0, 130.0], Groups(vec![0, 1])),
        (fig6_circle(true), vec![120.0], Groups(vec![0])),
    ];
    for (robot, inputs, groups) in cases {
        let mut loads = Loads::of(&robot);
        loads.tip_force = Vector3::new(1e-3, -5e-4, 2e-3);
        let sol = solve_loaded(&robot, &inputs, &loads, &opts(), None).unwrap();
        let s = sensitivities(&robot, &sol, &loads, &groups, sol.steps, Scheme::Central).unwrap();
        let (jb, cb) = brute(&robot, &inputs, &loads, &groups);
        // central differences on both sides: agreement to ~1e-6 relative
        let ej = (&s.jacobian - &jb).norm() / jb.norm();
        let ec = (&s.compliance - &cb).norm() / cb.norm();
        assert!(ej < 1e-5, "J rel err {ej:e}\n{}\n{}", s.jacobian, jb);
        assert!(ec < 1e-5, "C rel err {ec:e}");
        // the paper's forward differences: ~sqrt(eps) relative error
        let f = sensitivities(&robot, &sol, &loads, &groups, sol.steps, Scheme::Forward).unwrap();
        let ejf = (&f.jacobian - &jb).norm() / jb.norm();
        assert!(ejf < 1e-3, "forward J rel err {ejf:e}");
        assert_eq!(
            f.evaluations,
            1 + 6 + robot.actuators.len() + groups.n_vars() + 6
        );
    }
}

#[test]
fn compliance_is_symmetric_and_matches_the_linear_cantilever() {
    // Loads here are conservative (elastic strings, gravity, dead tip loads),
    // so C is a Hessian inverse: symmetric at any equilibrium.
    for (robot, inputs) in [
        (fig6_square(true), vec![100.0, 100.0]),
        (fig6_circle(false), vec![140.0]),
    ] {
        let sol = solve(&robot, &inputs, &opts(), None).unwrap();
        let groups = Groups::identity(robot.actuators.len());
        let c = sensitivities(
            &robot,
            &sol,
            &Loads::of(&robot),
            &groups,
            sol.steps,
            Scheme::Central,
        )
        .unwrap()
        .compliance;
        let asym = (&c - c.transpose()).norm() / c.norm();
        assert!(asym < 1e-6, "asymmetry {asym:e}"); // central FD error ~1e-8
    }
    // Linear-elastic limit: a bare straight cantilever, no load. C is SPD and
    // its translational block is Timoshenko's: L^3/(3EI) + L/(k G A) in
    // bending, L/(EA) axially.
    let body = fig6_square(false).body.clone();
    let robot = tcarod::rod::Robot::new(body, vec![]).unwrap();
    let sol = solve(&robot, &[], &opts(), None).unwrap();
    let c = sensitivities(
        &robot,
        &sol,
        &Loads::of(&robot),
        &Groups(vec![]),
        sol.steps,
        Scheme::Central,
    )
    .unwrap()
    .compliance;
    let asym = (&c - c.transpose()).norm() / c.norm();
    assert!(asym < 1e-8, "asymmetry {asym:e}");
    let eig = c.clone().symmetric_eigen().eigenvalues;
    assert!(eig.iter().all(|&l| l > 0.0), "{eig}");
    let b = &robot.body;
    let (a, ix, iy, _) = b.section.properties();
    let l = b.length;
    let want_x = l.powi(3) / (3.0 * b.youngs_modulus * iy) + l / (b.shear_modulus * a);
    let want_y = l.powi(3) / (3.0 * b.youngs_modulus * ix) + l / (b.shear_modulus * a);
    let want_z = l / (b.youngs_modulus * a);
    // exact for the linearised rod; central FD relative error ~1e-9
    for (k, want) in [(0, want_x), (1, want_y), (2, want_z)] {
        assert!(
            (c[(k, k)] - want).abs() / want < 1e-7,
            "C[{k},{k}] = {} vs {want}",
            c[(k, k)]
        );
    }
    // rotation per tip moment: L / (E I)
    let want = l / (b.youngs_modulus * iy);
    assert!((c[(4, 4)] - want).abs() / want < 1e-7);
}

#[test]
fn incremental_blocked_temperature_matches_direct_solve() {
    let robot = square_manipulator(0.026, true);
    let groups = Groups(vec![0, 0]);
    let start = solve(&robot, &[55.0, 55.0], &opts(), None).unwrap();
    let block = Block::new(start.tip_position(), Vector3::new(-1.0, 0.0, 0.0)).unwrap();
    for force in [5e-3, 2e-2] {
        let inc = blocked_temperature(&robot, &groups, &block, &start, force, 10, &opts()).unwrap();
        let dir =
            blocked_variable_direct(&robot, &groups, &block, force, 80.0, &opts(), None).unwrap();
        // both converge the same equations to 1e-9 m tip gap and 1e-10 strain
        assert!(
            (inc.variables[0] - dir.variables[0]).abs() < 1e-5,
            "{} vs {}",
            inc.variables[0],
            dir.variables[0]
        );
        // and the force solve at that temperature returns the force, to 1e-6
        // of it (both solves converged to 1e-10 in scaled units)
        let f = blocked_force(&robot, &groups, &block, &dir.variables, &opts(), None).unwrap();
        assert!(
            (f.force - force).abs() < 1e-9 * force.max(1e-3) * 1e3,
            "{} vs {force}",
            f.force
        );
        assert!(inc.variables[0] > 55.0);
    }
}

#[test]
fn tip_position_inverse_reaches_reachable_and_reports_unreachable_targets() {
    let robot = fig6_square(false);
    let groups = Groups(vec![0, 1]);
    let truth = solve(&robot, &[90.0, 140.0], &opts(), None).unwrap();
    let res = tip_position_inverse(
        &robot,
        &groups,
        &truth.tip_position(),
        None,
        &[25.0, 25.0],
        &InverseOptions::default(),
    )
    .unwrap();
    assert!(res.reached, "{res:?}");
    // the inverse stops at its default tip tolerance, 1e-7 m
    assert!((res.solution.tip_position() - truth.tip_position()).norm() < 1e-7);
    // the tip cannot move toward +x: extension TCAs at +x only bend toward -x
    let far = Vector3::new(0.02, 0.0, 0.03);
    let res = tip_position_inverse(
        &robot,
        &groups,
        &far,
        None,
        &[60.0, 60.0],
        &InverseOptions::default(),
    )
    .unwrap();
    assert!(!res.reached);
    assert!(res.at_bound.iter().all(|&b| b), "{:?}", res.variables);
    // the closest configuration is the unheated body: clamped at the 25 C bound
    assert!(res.variables.iter().all(|&t| (t - 25.0).abs() < 1e-9));
}

#[test]
fn grasp_temperature_rises_with_mass() {
    let mut finger = square_manipulator(0.020, false);
    finger.body.gravity = Vector3::new(0.0, 0.0, G0);
    let groups = Groups(vec![0, 0]);
    let mut last = 25.0;
    for m in [1e-3, 2e-3, 3e-3] {
        let r = grasp(
            &finger,
            &groups,
            &Vector3::new(-1.0, 0.0, 0.0),
            m,
            1.1,
            2,
            G0,
            8,
            &opts(),
        )
        .unwrap();
        // eq 44: F = m g / (mu n), computed in closed form: rounding only
        assert!((r.force - m * G0 / 2.2).abs() < 1e-15);
        assert!(r.variables[0] > last);
        last = r.variables[0];
    }
}

#[test]
fn incremental_blocked_temperature_reaches_the_top_of_the_range() {
    // The blocked force at exactly 160 C (the material's top), fed back to the
    // incremental method, must give 160 C, not "outside [25, 160]" from a
    // rounding error above the bound.
    let robot = square_manipulator(0.026, true);
    let groups = Groups(vec![0, 0]);
    let start = solve(&robot, &[55.0, 55.0], &opts(), None).unwrap();
    let block = Block::new(start.tip_position(), Vector3::new(-1.0, 0.0, 0.0)).unwrap();
    let top = blocked_force(&robot, &groups, &block, &[160.0], &opts(), None).unwrap();
    let inc = blocked_temperature(&robot, &groups, &block, &start, top.force, 10, &opts()).unwrap();
    // gap tolerance 1e-9 L and dT/dF ~ 1.5e3 C/N: agreement far below 1e-6 C
    assert!(
        (inc.variables[0] - 160.0).abs() < 1e-6,
        "{}",
        inc.variables[0]
    );
    // a force beyond the range is still refused
    assert!(blocked_temperature(
        &robot,
        &groups,
        &block,
        &start,
        top.force * 1.01,
        10,
        &opts()
    )
    .is_err());
}

/// The exact J and C (one tangent IVP) against central differences of IVPs
/// (the paper's eqs 39-42) on TCA bodies with gravity, and against brute
/// force (differences of full solves) on the steel tendon robot, whose
/// residual is too stiff in shear for differenced IVPs (step eps^(1/3) puts
/// a 25 % error in its shear columns; see tests/integration/tangent.rs).
#[test]
fn exact_sensitivities_match_differences() {
    use tcarod::experiments::{steel_tendon_robot, STEEL_TENDON_TENSIONS};
    let opts = SolveOptions::default();
    let cases: Vec<(&str, tcarod::rod::Robot, Vec<f64>, Groups)> = vec![
        (
            "square",
            fig6_square(true),
            vec![100.0, 100.0],
            Groups(vec![0, 0]),
        ),
        (
            "square, legs apart",
            fig6_square(true),
            vec![90.0, 120.0],
            Groups::identity(2),
        ),
        ("circle", fig6_circle(true), vec![80.0], Groups::identity(1)),
    ];
    for (name, robot, inputs, groups) in cases {
        let s = solve(&robot, &inputs, &opts, None).unwrap();
        let l = Loads::of(&robot);
        let ex = sensitivities(&robot, &s, &l, &groups, opts.steps, Scheme::Exact).unwrap();
        let fd = sensitivities(&robot, &s, &l, &groups, opts.steps, Scheme::Central).unwrap();
        assert_eq!(ex.evaluations, 1);
        // central differences with step eps^(1/3): truncation and rounding
        // ~1e-10..1e-8 relative, amplified by B_u^-1; a wrong tangent term
        // is O(1) wrong
        for (what, a, b) in [
            ("J", &ex.jacobian, &fd.jacobian),
            ("C", &ex.compliance, &fd.compliance),
        ] {
            let err = (a - b).amax() / b.amax();
            assert!(
                err < 1e-5,
                "{name} {what}: relative error {err:e}\nexact {a:.5e}\nfd {b:.5e}"
            );
        }
    }
    let robot = steel_tendon_robot();
    // the benchmark tensions with the slack tendons at 0.5 N, so that brute
    // force can step both ways
    let inputs: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|t| t.max(0.5)).collect();
    let groups = Groups::identity(4);
    let l = Loads::of(&robot);
    let s = solve(&robot, &inputs, &opts, None).unwrap();
    let ex = sensitivities(&robot, &s, &l, &groups, opts.steps, Scheme::Exact).unwrap();
    let (bj, bc) = brute(&robot, &inputs, &l, &groups);
    // brute force: O(h^2) with h = 0.01 N and 1e-3 E I / L^2, and solves
    // converged to the rounding floor (~1e-9 strain): ~1e-6 relative
    for (what, a, b) in [("J", &ex.jacobian, &bj), ("C", &ex.compliance, &bc)] {
        let err = (a - b).amax() / b.amax();
        assert!(
            err < 1e-4,
            "steel {what}: relative error {err:e}\nexact {a:.5e}\nbrute {b:.5e}"
        );
    }
}

/// The Table I grasp: one bordered Newton solve of the blocked tip
/// (direct) and the paper's eq-43 increments converge the same equations.
#[test]
fn direct_grasp_agrees_with_the_incremental_method() {
    use tcarod::experiments::{table1_finger, table1_grasp, TABLE1_MASSES, TABLE1_NORMAL};
    use tcarod::stability::Policy;
    let finger = table1_finger();
    let len = finger.body.length;
    let groups = Groups(vec![0, 0]);
    let o = SolveOptions::default();
    let cases = [
        (TABLE1_MASSES[0], None),
        (TABLE1_MASSES[2], Some(vec![72.0, 72.0])),
    ];
    for (m, contact) in cases {
        let spec = Grasp {
            contact,
            ..table1_grasp(m, Policy::Off)
        };
        let (inc, p_inc) = spec
            .solve(&finger, &groups, GraspMethod::Incremental(8), &o)
            .unwrap();
        let (dir, p_dir) = spec
            .solve(&finger, &groups, GraspMethod::Direct, &o)
            .unwrap();
        assert_eq!(p_inc, p_dir);
        // The incremental method stops at a tip gap of 1e-9 L = 2e-11 m;
        // the finger's tip moves n^T J ~ 2e-5 m per C along the normal, so
        // the two temperatures agree to 1e-6 C.
        let dt = (inc.variables[0] - dir.variables[0]).abs();
        assert!(dt < 1e-6, "{} vs {}", inc.variables[0], dir.variables[0]);
        // the direct solve holds the tip on the block to its tolerance
        // (1e-10 of L) and presses with the eq-44 force exactly
        let gap = Vector3::from(TABLE1_NORMAL).dot(&(dir.solution.tip_position() - p_dir));
        assert!(gap.abs() < 1e-10 * len, "gap {gap:e} m");
        assert_eq!(dir.force, spec.force_per_finger().unwrap());
        assert!(dir.stability.is_none() && inc.stability.is_none());
        // IVP counts (deterministic, the free solve included): the direct
        // solve needs at most half the increments'
        assert!(
            2 * dir.evaluations <= inc.evaluations,
            "{} vs {} IVPs",
            dir.evaluations,
            inc.evaluations
        );
        // the direct solve's profile is the single IVP of its one segment
        // at its unknowns: the same, bit for bit, as assembling the
        // solution afresh there (the same arithmetic)
        let mut loads = Loads::of(&finger);
        loads.tip_force -= Vector3::from(TABLE1_NORMAL) * dir.force;
        let s = &dir.solution;
        let fresh = assemble(&finger, &s.inputs, &loads, &s.unknowns, o.steps, 0, 0).unwrap();
        assert_eq!(s.tip_position(), fresh.tip_position());
        assert_eq!(s.positions, fresh.positions);
        assert_eq!(s.tensions, fresh.tensions);
    }
}

/// The core's blocked solves carry the verdict of the tip held along the
/// block normal: the same as `stability()` called by hand, its tangent IVP
/// counted; `Off` skips it, `Continue` does not apply to a held tip.
#[test]
fn blocked_solves_carry_the_stability_verdict() {
    use tcarod::stability::{stability, Policy};
    let robot = square_manipulator(0.026, true);
    let groups = Groups(vec![0, 0]);
    let start = solve(&robot, &[55.0, 55.0], &opts(), None).unwrap();
    let block = Block::new(start.tip_position(), Vector3::new(-1.0, 0.0, 0.0)).unwrap();
    let off = block.with_stability(Policy::Off).unwrap();
    let f = blocked_force(&robot, &groups, &block, &[100.0], &opts(), None).unwrap();
    let f_off = blocked_force(&robot, &groups, &off, &[100.0], &opts(), None).unwrap();
    let st = f.stability.as_ref().expect("a verdict under Report");
    let by_hand = stability(&robot, &f.solution, &[block.normal]).unwrap();
    // the same computation on the same solution: bit-identical
    assert_eq!(st.margin, by_hand.margin);
    assert!(st.stable && st.margin > 0.0, "margin {}", st.margin);
    assert!(f_off.stability.is_none());
    assert_eq!(f.evaluations, f_off.evaluations + 1);
    // the other blocked solves attach it too
    let inc = blocked_temperature(&robot, &groups, &block, &start, f.force, 4, &opts()).unwrap();
    let dir = blocked_variable_from(&robot, &groups, &block, &start, f.force, &opts()).unwrap();
    let old = blocked_variable_direct(&robot, &groups, &block, f.force, 80.0, &opts(), None);
    for r in [inc, dir, old.unwrap()] {
        // each closes the tip gap to 1e-9 L: the temperature to far below 1e-5 C
        assert!((r.variables[0] - 100.0).abs() < 1e-5, "{}", r.variables[0]);
        assert!(r.stability.as_ref().is_some_and(|s| s.stable));
    }
    let require = block.with_stability(Policy::Require).unwrap();
    assert!(blocked_force(&robot, &groups, &require, &[100.0], &opts(), None).is_ok());
    assert!(block.with_stability(Policy::Continue).is_err());
}

/// A target off the curve the tip reaches with the two legs heated
/// together: the error stops at the distance to that curve within a few
/// Gauss-Newton steps, with the closest point in the result and its
/// message, not at the iteration limit.
#[test]
fn tip_position_inverse_stalls_at_the_closest_point_of_an_off_curve_target() {
    let robot = fig6_square(false);
    let groups = Groups(vec![0, 0]); // one temperature: the legs at y = +-d stay symmetric
    let on_curve = solve(&robot, &[100.0, 100.0], &opts(), None)
        .unwrap()
        .tip_position();
    let target = on_curve + Vector3::new(0.0, 2e-3, 0.0);
    let budget = InverseOptions {
        max_iter: 500,
        ..Default::default()
    };
    let res = tip_position_inverse(&robot, &groups, &target, None, &[25.0], &budget).unwrap();
    assert_eq!(res.status, InverseStatus::Stalled, "{res:?}");
    assert_eq!(res.status.code(), 3);
    assert!(res.iterations <= 10, "{} iterations", res.iterations);
    // the closest point is the target's projection on the curve: 2 mm off
    // it (y stays 0 by symmetry), the curve point to the default tol 1e-7 m
    let tip = res.solution.tip_position();
    assert!(tip.y.abs() < 1e-12);
    assert!((res.error - 2e-3).abs() < 1e-7, "{}", res.error);
    assert!((tip - on_curve).norm() < 1e-7);
    let message = res.message(budget.max_iter);
    assert!(message.starts_with("stalled"), "{message}");
    assert!(message.contains("closest tip point found") && message.contains(" m from the target"));
    assert!(!message.contains("max_iter"), "{message}");
}

/// One of two independently driven legs held at a fixed input: the
/// inverse over the other leg's temperature lands on a forward solve with
/// the held leg at its value, and the grasp of that finger holds.
#[test]
fn fixed_inputs_drive_one_leg_of_two() {
    let robot = fig6_square(false);
    let groups = Groups::with_fixed(&robot, None, &[(1, 25.0)]).unwrap();
    let truth = solve(&robot, &[110.0, 25.0], &opts(), None).unwrap();
    let res = tip_position_inverse(
        &robot,
        &groups,
        &truth.tip_position(),
        None,
        &[25.0],
        &InverseOptions::default(),
    )
    .unwrap();
    assert!(res.reached, "{res:?}");
    assert_eq!(res.variables.len(), 1);
    assert_eq!(res.solution.inputs[1], 25.0);
    let again = solve(&robot, &[res.variables[0], 25.0], &opts(), None).unwrap();
    // the inverse's tol 1e-7 m plus the two forward solves' agreement (1e-12 strain)
    assert!((again.tip_position() - truth.tip_position()).norm() < 1e-7 + 1e-10);
    // the grasp with that leg held, both methods: the blocked force at the
    // grasp temperature is the force eq 44 asks for
    let spec = Grasp {
        normal: Vector3::new(-1.0, 0.0, 0.0),
        mass: 2e-3,
        mu: 1.0,
        fingers: 2,
        gravity: G0,
        contact: None,
        stability: tcarod::stability::Policy::Off,
    };
    let force = spec.force_per_finger().unwrap();
    let mut temps = vec![];
    for method in [GraspMethod::Incremental(10), GraspMethod::Direct] {
        let (res, point) = spec.solve(&robot, &groups, method, &opts()).unwrap();
        let block = Block::new(point, spec.normal).unwrap();
        let f = blocked_force(&robot, &groups, &block, &res.variables, &opts(), None).unwrap();
        // both converged to Newton tol 1e-12 (scaled): 1e-6 of the force
        assert!(
            (f.force - force).abs() < 1e-6 * force,
            "{} vs {force}",
            f.force
        );
        assert_eq!(res.solution.inputs[1], 25.0);
        temps.push(res.variables[0]);
    }
    // as for the Table I finger: the two methods agree to 1e-5 C
    assert!((temps[0] - temps[1]).abs() < 1e-5, "{temps:?}");
}

/// A blocked tip on a heavy soft body, which single shooting's growth
/// defeats: a horizontal beam of the stress family sagging under its
/// weight (`q L^3 / EI` of a few hundred), its tip held by a support under
/// it, a tenth of the sag up from the free tip toward the base's height.
/// The blocked force is solved on several multiple-shooting segments; the
/// tip lies on the support to 1e-9 L and the solution is in global
/// equilibrium: the base wrench balances the weight and the contact force.
#[test]
fn blocked_tip_of_a_heavy_horizontal_body() {
    use tcarod::problems::{equilibrium, stress_design, weight_ratio, Orientation, STRESS_SEED};
    let d = (0..200)
        .map(|i| stress_design(STRESS_SEED, i))
        .find(|d| {
            let w = weight_ratio(&d.robot.body);
            Orientation::of(&d.robot.body) == Some(Orientation::Horizontal)
                && w > 100.0
                && w < 1000.0
        })
        .expect("a horizontal design of weight ratio 100-1000");
    let (robot, len) = (&d.robot, d.robot.body.length);
    let o = SolveOptions {
        steps: 400,
        ..opts()
    };
    let free = solve(robot, &d.inputs, &o, None).unwrap();
    let down = robot.body.gravity.normalize();
    let sag = down.dot(&(free.tip_position() - free.positions[0]));
    let point = free.tip_position() - down * (0.1 * sag);
    let block = Block::new(point, down).unwrap();
    let groups = Groups::identity(robot.actuators.len());
    let r = blocked_force(robot, &groups, &block, &d.inputs, &o, None)
        .unwrap_or_else(|e| panic!("{}: {e}", d.summary()));
    let segments = tcarod::solve::segments::segment_starts(robot, &r.solution.loads, o.steps);
    assert!(segments.len() > 1, "{} segments", segments.len());
    // the support pushes the tip up: a positive force, below the weight
    let weight = robot.body.distributed_load().norm() * len;
    assert!(
        r.force > 0.0 && r.force < weight,
        "{} of {weight} N",
        r.force
    );
    let gap = down.dot(&(r.solution.tip_position() - point));
    assert!(gap.abs() < 1e-9 * len, "gap {gap:e} m");
    // the equilibrium check's error is the grid's: RK4 on 400 steps, 4^4 =
    // 256 times below the 100-step error of such bodies (1e-5 to 1e-2,
    // tests/integration/multiple_shooting.rs) at most, well below 1e-6
    // for a weight ratio below 1000; a wrong contact force or a tip off
    // the support is an O(1) imbalance
    let eq = equilibrium(robot, &r.solution);
    assert!(eq.relative < 1e-6, "equilibrium {:e}", eq.relative);
}
