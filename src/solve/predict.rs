//! First-order predictor of a warm start in the actuation inputs.
//!
//! A warm solution `x_w` at inputs `p_w` solves `r(x_w; p_w) = 0`. At new
//! inputs `p` the tension-keeping guess `x_g` ([`super::guess::warm_guess`])
//! gives every actuator the tension it had, so the IVP from `x_g` is the
//! warm solution's own and `r(x_g; p)` is known without integrating: zero
//! but for the elongation rows, `r_(6+i) = -(x_g - x_w)_(6+i)` (eq 32-33's
//! tip balance holds; the guessed elongation moved). One Newton step with
//! the warm solution's Jacobian (actuator columns rescaled to the force
//! laws' slopes at `p`, [`rescale_tension_columns`]) is then the
//! first-order predictor `x_w + (dx/dp) dp` of the solution branch, with
//! the force laws' own nonlinearity in the input taken exactly by `x_g`
//! and the step limited through the laws as Newton's are
//! ([`super::limit`]). It costs one small LU and no IVP.

use nalgebra::{DMatrix, DVector};

use super::guess::warm_guess;
use super::presolve::rescale_tension_columns;
use super::solution::Solution;
use crate::rod::Robot;

/// Largest predicted step (max norm of the scaled unknowns: strains and
/// `L omega`, of order one) that is taken; beyond it the linearisation is
/// not trusted (a near-singular Jacobian, e.g. at a fold) and the
/// tension-keeping guess is returned.
pub const MAX_PREDICTED_STEP: f64 = 0.5;

/// The warm guess at `inputs` from the neighbouring solution `warm`: its
/// first-order prediction if `warm` carries a Newton Jacobian, else the
/// tension-keeping guess.
pub fn predicted_guess(robot: &Robot, inputs: &[f64], warm: &Solution) -> Vec<f64> {
    predict(
        robot,
        inputs,
        (&warm.unknowns, &warm.tensions, &warm.inputs),
        warm.newton_jacobian.as_ref(),
    )
}

/// Move the base strains of `x` by the linear model of
/// [`super::guess::linear_guess`] for the tension changes that keeping
/// tensions could not avoid (an input that is itself a tension, a law with
/// no elongation for the old tension): each string anchored at the base
/// pulls it with `tau t`, so the base section's force and moment change by
/// `-t dtau` and `-r x t dtau` (body frame, `t` the string's unit tangent
/// at the guess), `d nu(0) = K_nu^-1 (-t dtau)`, `d omega(0) = K_omega^-1
/// (-r x t dtau)`. Exact for straight strings to the tip of a weightless
/// body (eq 9: the body's internal moment is then the strings' own at
/// every section); the shape's change under other loads is left to Newton.
fn shift_base_strains(robot: &Robot, inputs: &[f64], tau_w: &[f64], x: &mut [f64]) {
    let b = &robot.body;
    let len = b.length;
    let (kse, kbt) = b.stiffness();
    let (v, u) = (
        nalgebra::Vector3::new(x[0], x[1], x[2]),
        nalgebra::Vector3::new(x[3], x[4], x[5]) / len,
    );
    let (mut dn, mut dm) = (nalgebra::Vector3::zeros(), nalgebra::Vector3::zeros());
    for (i, a) in robot.actuators.iter().enumerate() {
        if a.s_start > 1e-12 * len {
            continue;
        }
        let Ok(tau) = a.law.tension(x[6 + i] * len, inputs[i]) else {
            continue;
        };
        let dtau = tau - tau_w[i];
        let (r, rp, _) = a.routing.eval(0.0);
        let pb = v + u.cross(&r) + rp;
        let t = pb / pb.norm();
        dn -= t * dtau;
        dm -= r.cross(&t) * dtau;
    }
    let dv = dn.component_div(&kse.diagonal());
    let du = dm.component_div(&kbt.diagonal());
    if dv.iter().chain(du.iter()).all(|z| z.is_finite()) {
        for k in 0..3 {
            x[k] += dv[k];
            x[3 + k] += du[k] * len;
        }
    }
}

/// [`predicted_guess`] from a neighbour's `(unknowns, tensions, inputs)`
/// and Newton Jacobian.
pub fn predict(
    robot: &Robot,
    inputs: &[f64],
    (x_w, tau_w, p_w): (&[f64], &[f64], &[f64]),
    jac: Option<&DMatrix<f64>>,
) -> Vec<f64> {
    let mut x_g = warm_guess(robot, inputs, Some((x_w, tau_w)));
    shift_base_strains(robot, inputs, tau_w, &mut x_g);
    let n = x_g.len();
    let Some(jac) = jac.filter(|j| j.nrows() == n && j.ncols() == n && p_w.len() == inputs.len())
    else {
        return x_g;
    };
    // the residual at the tension-keeping guess: the elongation rows only
    let mut r = vec![0.0; n];
    for c in 6..n {
        r[c] = -(x_g[c] - x_w[c]);
    }
    if r.iter().all(|v| *v == 0.0) {
        return x_g;
    }
    let j = rescale_tension_columns(robot, jac, (x_w, p_w), (&x_g, inputs));
    let Some(dx) = j.clone().lu().solve(&(-DVector::from_column_slice(&r))) else {
        return x_g;
    };
    let step = dx.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(step <= MAX_PREDICTED_STEP) {
        return x_g;
    }
    let dx: Vec<f64> = dx.iter().copied().collect();
    let limited = match super::limit::piece_step(robot, inputs, &x_g, &dx, &r, &j) {
        Some(d) => super::limit::limited_step(robot, inputs, &x_g, &d)
            .or_else(|| Some(x_g.iter().zip(&d).map(|(a, b)| a + b).collect())),
        None => super::limit::limited_step(robot, inputs, &x_g, &dx),
    };
    let x = limited.unwrap_or_else(|| x_g.iter().zip(&dx).map(|(a, b)| a + b).collect());
    if x.iter().all(|v| v.is_finite()) {
        x
    } else {
        x_g
    }
}
