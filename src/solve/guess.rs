//! Initial guesses of the shooting unknowns: the reference configuration,
//! warm starts that keep tensions, and the linearised cold start.

use nalgebra::Vector3;

use super::residual::Loads;
use super::solution::Solution;
use crate::rod::Robot;

/// Scaled unknowns `[nu*, L omega*, 0...]` of the reference (straight or
/// pre-curved, unactuated) configuration: the paper's initial guess.
pub fn reference_guess(robot: &Robot) -> Vec<f64> {
    let b = &robot.body;
    let mut x = vec![0.0; 6 + robot.actuators.len()];
    x[0..3].copy_from_slice(b.nu_star.as_slice());
    for k in 0..3 {
        x[3 + k] = b.omega_star[k] * b.length;
    }
    x
}

/// Initial guess at `inputs`: the strains of `warm` (a nearby solution) or of
/// the reference configuration, and actuator elongations that keep the warm
/// solution's tensions (cold: zero tension, i.e. each actuator's free
/// elongation). Keeping tensions rather than elongations matters: a TCA is
/// far stiffer than a silicone body, so at a new temperature the old
/// elongation would imply a very different force, while the old force is
/// close to the new one.
pub fn initial_guess(robot: &Robot, inputs: &[f64], warm: Option<&Solution>) -> Vec<f64> {
    warm_guess(
        robot,
        inputs,
        warm.map(|w| (&w.unknowns[..], &w.tensions[..])),
    )
}

/// [`initial_guess`] from a neighbouring solution's `(unknowns, tensions)`.
pub fn warm_guess(robot: &Robot, inputs: &[f64], warm: Option<(&[f64], &[f64])>) -> Vec<f64> {
    let len = robot.body.length;
    let mut x = match warm {
        Some((unknowns, _)) => unknowns.to_vec(),
        None => reference_guess(robot),
    };
    for (i, a) in robot.actuators.iter().enumerate() {
        let tension = warm.map_or(0.0, |(_, t)| t[i]);
        if let Some(d) = a.law.elongation(tension, inputs[i]) {
            if d.is_finite() {
                x[6 + i] = d / len;
            }
        }
    }
    x
}

/// Cold start: replace the base strains of `x` by those of the problem
/// linearised about the straight reference configuration, where the base
/// section carries the dead loads' resultant (eq 9 integrated along the
/// straight centre line: `n(0) = F + L f`, `m(0) = M + L l + L e3 x F +
/// L^2/2 e3 x f`) minus the pull of the strings through it (tensions at the
/// guessed elongations): `nu(0) = nu* + K_nu^-1 (n(0) - sum tau t)`,
/// `omega(0) = omega* + K_omega^-1 (m(0) - sum r x tau t)`. Exact for a straight
/// weightless body bent by straight constant-tension tendons to the tip (then
/// Newton needs one iteration); where the body is soft and loaded this puts
/// Newton on the branch continuation from the reference would follow.
pub fn linear_guess(robot: &Robot, inputs: &[f64], loads: &Loads, x: &mut [f64]) {
    let b = &robot.body;
    if b.omega_star != Vector3::zeros() || b.nu_star != Vector3::z() {
        return; // a pre-curved body: keep its reference strains
    }
    let len = b.length;
    let f = b.distributed_load();
    let e3 = Vector3::z();
    let mut n0 = loads.tip_force + f * len;
    let mut m0 = loads.tip_moment
        + b.distributed_moment * len
        + e3.cross(&loads.tip_force) * len
        + e3.cross(&f) * (0.5 * len * len);
    let tol = 1e-12 * len;
    for (i, a) in robot.actuators.iter().enumerate() {
        if a.s_start > tol {
            continue;
        }
        let tau = match a.law.tension(x[6 + i] * len, inputs[i]) {
            Ok(t) if t.is_finite() => t,
            _ => continue,
        };
        let (r, rp, _) = a.routing.eval(0.0);
        let pb = e3 + rp;
        let t = pb / pb.norm();
        n0 -= t * tau;
        m0 -= r.cross(&t) * tau;
    }
    let (kse, kbt) = b.stiffness();
    let v = b.nu_star + n0.component_div(&kse.diagonal());
    let u = b.omega_star + m0.component_div(&kbt.diagonal());
    if v.z > 0.1 && v.iter().chain(u.iter()).all(|z| z.is_finite()) {
        x[0..3].copy_from_slice(v.as_slice());
        for k in 0..3 {
            x[3 + k] = u[k] * len;
        }
    }
}
