//! The multiple-shooting system against single shooting and finite
//! differences.

use super::*;
use crate::problems::random_design;
use crate::rod::Grid;
use crate::solve::residual::Shot;

/// Segment starts every `every` nodes of the grid of `robot` on `steps`.
fn starts(robot: &Robot, steps: usize, every: usize) -> Vec<usize> {
    let tip = Grid::new(robot, steps).tip();
    (0..tip).step_by(every).collect()
}

/// Stretches chained end to start are the whole IVP bit for bit (the
/// same arithmetic on the same steps, anchor loads where the whole IVP
/// applies them).
#[test]
fn chained_stretches_are_the_whole_ivp_bit_for_bit() {
    let steps = 60;
    let mut checked = 0;
    for i in 0..12 {
        let d = random_design(crate::problems::DEFAULT_SEED, i);
        let robot = &d.robot;
        let loads = Loads::of(robot);
        let base = crate::solve::guess::initial_guess(robot, &d.inputs, None);
        let shot = Shot::new(robot, &d.inputs, &loads, steps);
        let Ok((_, whole, tau)) = shot.residual(&base, false) else {
            continue;
        };
        let spec = loads.ivp(robot, &tau, steps);
        let (v0, u0) = crate::solve::residual::base_strains(&base, robot.body.length);
        let mut y = vec![0.0; robot.n_states()];
        y[3] = 1.0;
        y[7..10].copy_from_slice(v0.as_slice());
        y[10..13].copy_from_slice(u0.as_slice());
        let mut bounds = starts(robot, steps, 17);
        bounds.push(Grid::new(robot, steps).tip());
        let mut elongation = vec![0.0; tau.len()];
        let mut last = None;
        for w in bounds.windows(2) {
            let st = Stretch {
                first: w[0],
                last: w[1],
            };
            let ivp = spec.integrate_stretch(st, &y).unwrap();
            for (e, v) in elongation.iter_mut().zip(&ivp.elongation) {
                *e += v;
            }
            y = crate::rod::FlatNodes::from_states(&[(0.0, ivp.tip.clone())]).y;
            last = Some(ivp);
        }
        let last = last.unwrap();
        assert_eq!(last.tip, whole.tip, "design {i}");
        assert_eq!(last.tip_force_residual, whole.tip_force_residual);
        assert_eq!(last.tip_moment_residual, whole.tip_moment_residual);
        assert_eq!(elongation, whole.elongation, "design {i}");
        checked += 1;
    }
    assert!(checked >= 8, "{checked}");
}

/// At unknowns chained from single shooting's, the continuity rows vanish
/// to the rounding of the scaling (`p / L`, `L omega`: a few eps) and the
/// tip rows are single shooting's residual to the rounding amplified by
/// the segments' growth (these light designs: well below 1e-9).
#[test]
fn chained_unknowns_have_single_shootings_residual() {
    let steps = 60;
    for i in 0..12 {
        let d = random_design(crate::problems::DEFAULT_SEED, i);
        let robot = &d.robot;
        let loads = Loads::of(robot);
        let na = robot.actuators.len();
        let base = crate::solve::guess::initial_guess(robot, &d.inputs, None);
        let single = Shot::new(robot, &d.inputs, &loads, steps).residual(&base, false);
        let Ok((r1, _, _)) = single else { continue };
        let st = starts(robot, steps, 17);
        let (mut ms, x) =
            MultipleShooting::chained(robot, &d.inputs, loads, steps, &st, &base).unwrap();
        let mut f = vec![f64::NAN; ms.dim()];
        ms.residual(&x, &mut f).unwrap();
        let rows = ms.rows();
        let mut at = 0;
        for (k, &r) in rows.iter().enumerate() {
            if k + 1 < rows.len() {
                let cont = &f[at..at + 12 + 2 * na];
                let worst = cont.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(worst <= 1e-14, "design {i} block {k}: {cont:?}");
            } else {
                for j in 0..6 {
                    let tol = 1e-9 * (1.0 + r1[j].abs());
                    assert!((f[at + j] - r1[j]).abs() <= tol, "design {i}: {f:?} {r1:?}");
                }
            }
            at += r;
        }
    }
}

/// The exact Jacobian blocks against central differences of the
/// residual, on designs with several segments (interior anchors, helices,
/// tendons and TCAs, gravity). Central differences with step `h = 1e-6`
/// on unknowns of order one err by `O(h^2 |f'''|)` plus rounding `eps |f| /
/// h`, about 1e-9 relative to the column; 1e-6 leaves room for the
/// residual's curvature on soft bodies.
#[test]
fn jacobian_blocks_match_central_differences() {
    let steps = 40;
    let mut checked = 0;
    for i in 0..10 {
        let d = random_design(crate::problems::DEFAULT_SEED, i);
        let robot = &d.robot;
        let loads = Loads::of(robot);
        let base = crate::solve::guess::initial_guess(robot, &d.inputs, None);
        let st = starts(robot, steps, 13);
        let Ok((mut ms, mut x)) =
            MultipleShooting::chained(robot, &d.inputs, loads, steps, &st, &base)
        else {
            continue;
        };
        // off the chained point: nonzero thetas and defects, and every
        // actuator elongation moved off its onset of tension (where the
        // cold guess puts it: a central difference there straddles the
        // force law's kink)
        for (j, v) in x.iter_mut().enumerate() {
            *v += 1e-3 * ((j * 7919 % 13) as f64 + 1.0) / 14.0;
        }
        let n = ms.dim();
        let mut f = vec![0.0; n];
        if ms.linearise(&x, &mut f).is_err() {
            continue;
        }
        let jac = ms.dense_jacobian();
        let h = 1e-6;
        let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
        for c in 0..n {
            let mut xp = x.clone();
            xp[c] += h;
            ms.residual(&xp, &mut fp).unwrap();
            xp[c] -= 2.0 * h;
            ms.residual(&xp, &mut fm).unwrap();
            let scale = 1.0 + jac.column(c).amax();
            for r in 0..n {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                let err = (fd - jac[(r, c)]).abs() / scale;
                assert!(
                    err < 1e-6,
                    "design {i} row {r} col {c}: {fd} vs {} (rows {:?} cols {:?})",
                    jac[(r, c)],
                    ms.rows(),
                    ms.cols()
                );
            }
        }
        checked += 1;
    }
    assert!(checked >= 5, "{checked} designs checked");
}
