//! Tests of the bordered blocked-tip system ([`super::Contact`]): its
//! border (the gap's row and the column of the extra unknown) against
//! central differences of its residual, on one segment and on several.

use super::*;
use crate::experiments::square_manipulator;
use crate::shooting::{solve, SolveOptions};
use crate::solve::nleq::NonlinearSystem;

/// The border of the bordered system at `z`: the gap's row `(grad_x g,
/// g_lambda)` and the column `G_lambda`, which only the blocked system
/// has (`G_x` is the forward solver's, checked in `solve::ms`), against
/// central differences of the residual.
fn check_border(sys: &mut Blocked<'_>, z: &[f64], what: &str) {
    let n = z.len();
    let mut f = vec![0.0; n];
    Contact { sys: &mut *sys }.linearise(z, &mut f).unwrap();
    let (row, row_lambda) = (sys.lin.row().0.to_vec(), sys.lin.row().1);
    let g_lambda = sys.g_lambda.clone();
    let mut contact = Contact { sys };
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    for c in 0..n {
        // central step 6e-7 of the unknown's size: the TCA law stiffens
        // toward its coil contact within ~1e-5 of a law coordinate, so a
        // longer step measures the law's curvature; rounding stays ~eps / h
        // ~ 1e-9 of the column. The variable's `G_lambda` is itself a
        // one-sided difference (~1e-8). A wrong term is O(1) wrong.
        let h = 6e-7 * z[c].abs().max(1e-2);
        let (mut zp, mut zm) = (z.to_vec(), z.to_vec());
        zp[c] += h;
        zm[c] -= h;
        contact.residual(&zp, &mut fp).unwrap();
        contact.residual(&zm, &mut fm).unwrap();
        let col: Vec<f64> = fp
            .iter()
            .zip(&fm)
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect();
        let exact: Vec<f64> = match c + 1 == n {
            true => g_lambda.iter().copied().chain([row_lambda]).collect(),
            false => vec![row[c]],
        };
        let rows: Vec<usize> = match c + 1 == n {
            true => (0..n).collect(),
            false => vec![n - 1],
        };
        let size = rows.iter().fold(1e-3_f64, |m, &i| m.max(col[i].abs()));
        for (k, &i) in rows.iter().enumerate() {
            let err = (exact[k] - col[i]).abs() / size;
            assert!(
                err < 1e-4,
                "{what}: column {c} row {i}: {} vs {}",
                exact[k],
                col[i]
            );
        }
    }
}

/// The border of both extra unknowns matches central differences, away
/// from a root, on one segment and on three.
#[test]
fn bordered_linearisation_matches_central_differences() {
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
    let steps = 100;
    for starts in [vec![0], vec![0, 30, 70]] {
        for (extra, lambda) in extras.clone() {
            let problem = (&robot, &groups, &block);
            let probe = Blocked::new(problem, extra.clone(), steps, vec![0], vec![]);
            let (inputs, loads, _) = probe.problem(lambda).unwrap();
            let base = (&starts[..], &start.unknowns[..]);
            let (ms, x) =
                crate::solve::forward::first_guess(&robot, &inputs, loads, steps, base, None)
                    .unwrap();
            let charts = ms.charts().to_vec();
            let mut sys = Blocked::new(problem, extra, steps, starts.clone(), charts);
            let mut z = x;
            z[3] *= 1.1; // off the root: every term of the tangent counts
            z.push(lambda);
            check_border(
                &mut sys,
                &z,
                &format!("{} segments, lambda {lambda}", starts.len()),
            );
        }
    }
}
