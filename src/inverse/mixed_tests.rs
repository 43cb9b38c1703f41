//! Tests of the bordered blocked-tip system ([`super::Contact`]): its
//! linearisation against central differences of its residual, on one
//! segment and on several.

use super::*;
use crate::experiments::square_manipulator;
use crate::shooting::{solve, SolveOptions};
use crate::solve::nleq::NonlinearSystem;

/// The Jacobian of the bordered system `[G; g]`, column by column: `J e_c`
/// from the bordered solve's inverse is awkward, so the columns are
/// recovered as `J dz` for the solve's own `dz` (`J dz = b`), checked
/// against the central difference of the residual along `dz`.
fn check_directional(sys: &mut Blocked<'_>, z: &[f64], what: &str) {
    let n = z.len();
    let mut contact = Contact { sys };
    let mut f = vec![0.0; n];
    contact.linearise(z, &mut f).unwrap();
    // a right-hand side with every row of order one
    let b: Vec<f64> = (0..n).map(|i| 1.0 + (i % 7) as f64 * 0.1).collect();
    let mut dz = vec![0.0; n];
    assert!(contact.solve(&b, &mut dz).unwrap());
    // J dz by central differences along dz, step eps^(1/3) of |dz|_inf:
    // truncation ~h^2, rounding ~eps / h, both ~1e-10 of the row
    let size = dz.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let h = 6e-6 / size;
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    let zp: Vec<f64> = z.iter().zip(&dz).map(|(a, d)| a + h * d).collect();
    let zm: Vec<f64> = z.iter().zip(&dz).map(|(a, d)| a - h * d).collect();
    contact.residual(&zp, &mut fp).unwrap();
    contact.residual(&zm, &mut fm).unwrap();
    for i in 0..n {
        let jd = (fp[i] - fm[i]) / (2.0 * h);
        // the variable's G_lambda is a sqrt(eps) difference (its relative
        // error ~1e-8), the differenced rows' error ~1e-8 of the row: a
        // wrong tangent term is O(1) wrong
        assert!(
            (jd - b[i]).abs() < 1e-5 * b[i].abs(),
            "{what}: row {i}: J dz = {jd} vs {}",
            b[i]
        );
    }
}

/// The bordered linearisation of both extra unknowns solves the system's
/// own linearisation: `J dz = b` for the bordered solve's `dz`, away from a
/// root, on one segment and on three.
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
            check_directional(&mut sys, &z, &format!("{} segments", starts.len()));
        }
    }
}
