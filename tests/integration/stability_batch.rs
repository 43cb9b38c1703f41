//! Batch rows carry the stability verdict (docs/stability.md, "The stability
//! of every solve"): `solve_batch` with `stability` gives every converged row
//! `stable` and `margin`, the same verdict as a single solve's; without it the
//! rows say "not computed".

use nalgebra::Vector3;
use tcarod::batch::{solve_batch, BatchOptions};
use tcarod::experiments::fig6_square;
use tcarod::rod::{Body, Robot, Section};
use tcarod::shooting::{solve, solve_loaded, Loads, SolveOptions};
use tcarod::stability::stability;

/// A weightless slender round column (L/r = 100) without actuators, and its
/// Euler load `pi^2 EI / (4 L^2)` \[N\].
fn column() -> (Robot, f64) {
    let len = 0.5;
    let mut b = Body::new(len, Section::Circle { diameter: 10e-3 }, 1e6, 0.5, 1000.0).unwrap();
    b.gravity = Vector3::zeros();
    let (_, ix, _, _) = b.section.properties();
    let pc = std::f64::consts::PI.powi(2) * b.youngs_modulus * ix / (4.0 * len * len);
    (Robot::new(b, vec![]).unwrap(), pc)
}

#[test]
fn a_column_past_euler_reports_unstable_and_below_stable() {
    let (robot, pc) = column();
    let ratios = [0.5, 0.9, 1.5, 2.0];
    let wrenches: Vec<f64> = ratios
        .iter()
        .flat_map(|r| [0.0, 0.0, -r * pc, 0.0, 0.0, 0.0])
        .collect();
    // cold rows: the perfect column's solve stays straight, buckled or not
    let opts = BatchOptions {
        warm: false,
        threads: 1,
        ..Default::default()
    };
    let out = solve_batch(&robot, &[], Some(&wrenches), &opts).unwrap();
    for (k, r) in ratios.iter().enumerate() {
        assert!(out.converged[k], "row {k}");
        // on the axis to rounding: no lateral load breaks the symmetry
        let p = Vector3::from(out.tip_positions[k]);
        assert!(p.x.hypot(p.y) < 1e-9, "row {k}: straight");
        assert_eq!(
            out.stable[k],
            *r < 1.0,
            "ratio {r}: margin {}",
            out.margin[k]
        );
        assert_eq!(out.stable[k], out.margin[k] > 0.0);
        // the row's verdict is the single solve's (the same cold equilibrium)
        let w = &wrenches[6 * k..6 * k + 6];
        let loads = Loads {
            tip_force: Vector3::new(w[0], w[1], w[2]),
            tip_moment: Vector3::new(w[3], w[4], w[5]),
        };
        let sol = solve_loaded(&robot, &[], &loads, &opts.solve, None).unwrap();
        let st = stability(&robot, &sol, &[]).unwrap();
        assert_eq!(out.margin[k], st.margin, "row {k}");
        // the verdict's tangent IVP is counted with the row's integrations
        assert_eq!(out.evaluations[k] as usize, sol.evaluations + 1, "row {k}");
    }
}

#[test]
fn fig6_rows_are_stable_and_off_says_not_computed() {
    let robot = fig6_square(true);
    let inputs: Vec<f64> = [40.0, 80.0, 120.0, 160.0]
        .iter()
        .flat_map(|&t| [t, t])
        .collect();
    let on = solve_batch(&robot, &inputs, None, &BatchOptions::default()).unwrap();
    let off = solve_batch(
        &robot,
        &inputs,
        None,
        &BatchOptions {
            stability: false,
            ..Default::default()
        },
    )
    .unwrap();
    let opts = SolveOptions::default();
    for k in 0..4 {
        assert!(on.converged[k] && off.converged[k]);
        assert!(on.stable[k], "row {k}: margin {}", on.margin[k]);
        assert!(on.margin[k] > 0.0);
        // not computed: no flag, NaN margin, no extra integration, same pose
        assert!(!off.stable[k] && off.margin[k].is_nan());
        assert_eq!(on.evaluations[k], off.evaluations[k] + 1);
        assert_eq!(on.tip_positions[k], off.tip_positions[k]);
        // the same verdict as a cold single solve at these inputs: both
        // converged to 1e-10, so the margins (order 1) agree to ~1e-8; 1e-6
        // relative bounds it
        let sol = solve(&robot, &inputs[2 * k..2 * k + 2], &opts, None).unwrap();
        let st = stability(&robot, &sol, &[]).unwrap();
        assert!((on.margin[k] - st.margin).abs() < 1e-6 * st.margin.abs().max(1.0));
    }
}
