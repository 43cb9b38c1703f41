//! Tests of the augmented mixed-boundary system ([`super::Mixed`]): its exact
//! Jacobian against central differences of its residual.

use super::*;
use crate::experiments::square_manipulator;
use crate::shooting::{solve, SolveOptions};

/// The exact augmented Jacobian (full grid) against central differences
/// of the augmented residual, for both extra unknowns, away from a root.
#[test]
fn augmented_jacobian_matches_central_differences() {
    let robot = square_manipulator(0.026, true);
    let groups = Groups(vec![0, 0]);
    let start = solve(&robot, &[55.0, 55.0], &SolveOptions::default(), None).unwrap();
    let block = Block::new(start.tip_position(), Vector3::new(-1.0, 0.0, 0.0)).unwrap();
    let extras = [
        (
            Extra::Force {
                inputs: vec![90.0, 90.0],
            },
            0.4,
        ),
        (
            Extra::Variable {
                force: 0.02,
                scale: 135.0,
            },
            0.6,
        ),
    ];
    for (extra, e) in extras {
        let mut sys = Mixed::new(&robot, &groups, &block, extra, 100);
        assert!(sys.refine(&start.unknowns)); // the full grid's Jacobian
        let mut x = start.unknowns.clone();
        x.push(e);
        x[3] *= 1.1; // off the root: all terms of the tangent count
        let (r, jac) = sys.residual_and_jacobian(&x).unwrap();
        let r0 = sys.residual(&x).unwrap();
        // the tangent IVP's real part is the plain IVP (to rounding: the
        // generic and the f64 right-hand sides round differently)
        for (a, b) in r.iter().zip(&r0) {
            assert!((a - b).abs() < 1e-12 * b.abs().max(1.0), "{a} vs {b}");
        }
        // Checked here: the elongation columns, the extra column and the gap
        // row, which only the augmented system has. (The strain columns of
        // the tip balance are the forward solver's, checked in
        // tests/integration/tangent.rs; differenced, their stiff shear
        // entries carry truncation errors ~1e-5.)
        let n = x.len();
        for c in 0..n {
            // central step eps^(1/3) of the unknown's size; the stiff TCA
            // law makes the elongation columns the most nonlinear
            // (measured difference 3.3e-6 of the column, hence 1e-4); a
            // wrong tangent term is O(1) wrong
            let h = 6e-6 * x[c].abs().max(1e-2);
            let (mut xp, mut xm) = (x.clone(), x.clone());
            xp[c] += h;
            xm[c] -= h;
            let (rp, rm) = (sys.residual(&xp).unwrap(), sys.residual(&xm).unwrap());
            let col: Vec<f64> = rp
                .iter()
                .zip(&rm)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect();
            let rows: Vec<usize> = if c >= 6 {
                (0..n).collect()
            } else {
                vec![n - 1]
            };
            let size = rows.iter().fold(1e-3_f64, |m, &i| m.max(col[i].abs()));
            for i in rows {
                let err = (jac[(i, c)] - col[i]).abs() / size;
                assert!(
                    err < 1e-4,
                    "column {c} row {i}: {} vs {}",
                    jac[(i, c)],
                    col[i]
                );
            }
        }
    }
}
