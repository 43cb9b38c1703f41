//! Step limiting through the actuators' force laws (the shooting analogue
//! of SPICE's junction-voltage limiting, Nagel 1975): a Newton step that
//! carries an actuator's elongation across a sharp stiffening of its law
//! (a TCA's coil contact: the slope rises ~400x within 0.1 um) overshoots,
//! because the Jacobian has the soft side's slope. The limited step keeps
//! the Newton step in the body's unknowns and replaces each actuator's
//! elongation step `d -> d + dd` by the elongation that gives the tension
//! the linear model predicted, `tau(d) + k dd` (`k` the law's slope at
//! `d`), where that tension lies between `tau(d)` and `tau(d + dd)` (the
//! law is stiffer along the step than the model: an overshoot). For one
//! monotone law alone the limited step is Newton's step in the tension.
//! Along a softer law (a tendon going slack, a TCA's coils parting) the
//! step is instead recomputed with the law linearised on the piece it
//! lands on (`piece_step`), and then limited as above.

use nalgebra::{DMatrix, DVector};

use crate::rod::{ForceLaw, Robot};

/// Bisection steps of the scalar inversion (the bracket shrinks to
/// `2^-60` of the step, below rounding of the elongation).
const INVERSION_STEPS: usize = 60;

/// The elongation in `[a, b]` (`tau(a) <= target <= tau(b)` or the
/// reverse) where `law` gives `target` at `input`: bisection (the law is
/// monotone but only C1, where regula falsi stalls on one side).
fn invert(law: &dyn ForceLaw, input: f64, target: f64, mut a: f64, mut b: f64) -> Option<f64> {
    let ta = law.tension(a, input).ok()?;
    let up = law.tension(b, input).ok()? >= ta;
    for _ in 0..INVERSION_STEPS {
        let m = 0.5 * (a + b);
        let tm = law.tension(m, input).ok()?;
        if (tm < target) == up {
            a = m;
        } else {
            b = m;
        }
    }
    Some(0.5 * (a + b))
}

/// The limited step `x + dx` of the shooting unknowns (see the module
/// docs; elongations are `x[6 + i] L`), or `None` where no actuator's
/// step overshoots.
pub(crate) fn limited_step(
    robot: &Robot,
    inputs: &[f64],
    x: &[f64],
    dx: &[f64],
) -> Option<Vec<f64>> {
    let len = robot.body.length;
    let mut out: Vec<f64> = x.iter().zip(dx).map(|(a, b)| a + b).collect();
    let mut changed = false;
    for (i, (a, &input)) in robot.actuators.iter().zip(inputs).enumerate() {
        let law = a.law.as_ref();
        let (d, dd) = (x[6 + i] * len, dx[6 + i] * len);
        let Ok((t0, k, _)) = law.tension_derivatives(d, input) else {
            continue;
        };
        let Ok(t1) = law.tension(d + dd, input) else {
            continue;
        };
        let target = t0 + k * dd;
        // an overshoot: the target lies strictly between tau(d) and tau(d + dd)
        let (lo, hi) = (t0.min(t1), t0.max(t1));
        if !(k > 0.0 && target > lo && target < hi && (t1 - target).abs() > 0.5 * (t1 - t0).abs()) {
            continue;
        }
        if let Some(e) = invert(law, input, target, d, d + dd) {
            out[6 + i] = e / len;
            changed = true;
        }
    }
    changed.then_some(out)
}

/// The Newton step `dx` (Jacobian `jac` at `x`, residual `r`) recomputed
/// where an actuator's step lands on a softer piece of its law than the
/// one `jac` linearised (a tendon going slack, a TCA's coils parting):
/// there the law at the end of the step is at most half as stiff as at
/// `x` and, along the step, changes the tension by less than half of the
/// linear model's `k dd`, so the model step would not even halve that
/// actuator's tension error (a chord iteration with the stiff slope
/// creeps: a tendon at its onset stepping into slack makes each line
/// search accept only `t ~ 1e-4`). Each such law is
/// linearised on the landing piece instead, `tau ~ tau(d + dd) + k1 (d' -
/// d - dd)` (`k1` the law's slope at `d + dd`), as a piecewise-linear
/// solver does when a step crosses into another region (Katzenelson,
/// Bell Syst. Tech. J. 44, 1965): the Jacobian's tension part of column
/// `6 + i`, `g k L` with `g = dr / d tau_i` (the column plus the unit
/// elongation term), is rescaled to `k1`, and the residual moves by
/// `g (tau(d + dd) - k1 dd - tau(d))`. `None`: no law softens along the
/// step (or the system is singular).
pub(crate) fn piece_step(
    robot: &Robot,
    inputs: &[f64],
    x: &[f64],
    dx: &[f64],
    r: &[f64],
    jac: &DMatrix<f64>,
) -> Option<Vec<f64>> {
    let len = robot.body.length;
    if jac.nrows() != jac.ncols() || jac.ncols() != x.len() {
        return None;
    }
    let mut jm = jac.clone();
    let mut rm = DVector::from_column_slice(r);
    let mut changed = false;
    for (i, (a, &input)) in robot.actuators.iter().zip(inputs).enumerate() {
        let law = a.law.as_ref();
        let (j, d, dd) = (6 + i, x[6 + i] * len, dx[6 + i] * len);
        let Ok((t0, k, _)) = law.tension_derivatives(d, input) else {
            continue;
        };
        let Ok((t1, k1, _)) = law.tension_derivatives(d + dd, input) else {
            continue;
        };
        // the secant over the step and the landing slope, against the model's
        if !(k > 0.0 && dd != 0.0 && (t1 - t0) / (k * dd) < 0.5 && k1 < 0.5 * k) {
            continue;
        }
        let mut g = jm.column(j).clone_owned();
        g[j] += 1.0;
        g /= k * len;
        relinearise(&mut jm, &mut rm, j, &g, k1 * len, t1 - k1 * dd - t0);
        changed = true;
    }
    if !changed {
        return None;
    }
    let step = jm.lu().solve(&(-rm))?;
    step.iter()
        .all(|v| v.is_finite())
        .then(|| step.iter().copied().collect())
}

/// One actuator's law re-linearised on another piece, in a Newton system
/// `jm dx = -rm`: column `j` (the actuator's elongation) becomes
/// `g slope - e_j` (`g = dr / d tau`, `slope` the piece's `d tau / d x_j`)
/// and the residual moves by `g shift` (the piece's tension at `x` minus
/// the Jacobian's). Shared by [`piece_step`] and
/// [`crate::solve::residual::taut_step`].
pub(crate) fn relinearise(
    jm: &mut DMatrix<f64>,
    rm: &mut DVector<f64>,
    j: usize,
    g: &DVector<f64>,
    slope: f64,
    shift: f64,
) {
    *rm += g * shift;
    let mut col = g * slope;
    col[j] -= 1.0;
    jm.set_column(j, &col);
}

#[cfg(test)]
mod tests {
    use super::limited_step;
    use crate::experiments::fig6_square;

    /// A step from the coil spring into coil contact is cut to the
    /// elongation where the law gives the linear model's tension; a step
    /// within the coil spring's smooth range is left alone.
    #[test]
    fn a_step_into_coil_contact_is_limited_to_the_predicted_tension() {
        let robot = fig6_square(true);
        let len = robot.body.length;
        let na = robot.actuators.len();
        let inputs: Vec<f64> = robot
            .actuators
            .iter()
            .map(|a| a.law.reference_input())
            .collect();
        let law = robot.actuators[0].law.as_ref();
        let (d, dd) = (1e-6, -2e-6); // from 1 um stretched to 1 um pressed
        let mut x = vec![0.0; 6 + na];
        let mut dx = vec![0.0; 6 + na];
        x[6] = d / len;
        dx[6] = dd / len;
        dx[0] = 1e-3; // a body unknown's step is kept as it is
        let out = limited_step(&robot, &inputs, &x, &dx).expect("the step overshoots");
        let (t0, k, _) = law.tension_derivatives(d, inputs[0]).unwrap();
        let target = t0 + k * dd;
        let reached = law.tension(out[6] * len, inputs[0]).unwrap();
        // bisection to 2^-60 of the 2 um bracket: the tension is exact to
        // rounding times the contact stiffness' scale
        assert!(
            (reached - target).abs() <= 1e-9 * target.abs().max(1.0),
            "{reached} vs {target}"
        );
        assert!(
            out[6] * len > d + dd && out[6] * len < d,
            "limited within the step"
        );
        assert_eq!(out[0], 1e-3);
        // within the coil spring's range (no contact) the law is not stiffer
        // along the step than the model: no limiting
        x[6] = 1e-3 / len;
        dx[6] = 1e-4 / len;
        assert!(limited_step(&robot, &inputs, &x, &dx).is_none());
    }
}
