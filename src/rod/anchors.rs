//! Point loads and strain jumps at interior actuator anchors.

use nalgebra::Vector3;

use super::ode::RodRhs;
use crate::error::{Error, Result};

impl RodRhs<'_> {
    /// Point loads on the body at an interior breakpoint `s` where strings
    /// are anchored. With `P` the total point force on the body,
    /// `n(s+) = n(s-) - P` and `m(s+) = m(s-) - sum r_i x P_i`, where a string
    /// ending at `s` contributes `P_i = -tau_i t_i(s-)` (it pulls toward the
    /// base), one starting at `s` contributes `+tau_i t_i(s+)`, and one passing
    /// `s` contributes `tau_i (t_i(s+) - t_i(s-))`: the strains jump at an
    /// anchor, so every string passing it has a kink there and presses on the
    /// body. `t(s+)` depends on the post-jump strains, so the jump is solved
    /// by Newton's method on the six strains (a 6x6 system; converges in a
    /// few iterations even where plain fixed-point iteration diverges).
    pub(crate) fn anchor_loads(&self, s: f64, y: &mut [f64]) -> Result<()> {
        let len = self.robot.body.length;
        let tol = 1e-12 * len;
        let v0 = Vector3::new(y[7], y[8], y[9]);
        let u0 = Vector3::new(y[10], y[11], y[12]);
        // (index, before-side weight, after-side weight): P_i = tau (a t+ - b t-)
        let mut terms: Vec<(usize, f64, f64)> = Vec::new();
        for (i, act) in self.robot.actuators.iter().enumerate() {
            if self.tensions[i] == 0.0 {
                continue;
            }
            let ends = (act.s_end - s).abs() <= tol;
            let starts = (act.s_start - s).abs() <= tol;
            let passes = act.s_start < s - tol && act.s_end > s + tol;
            let before = if ends || passes { 1.0 } else { 0.0 };
            let after = if starts || passes { 1.0 } else { 0.0 };
            if before != 0.0 || after != 0.0 {
                terms.push((i, before, after));
            }
        }
        if terms.is_empty() {
            return Ok(());
        }
        let tangent =
            |i: usize, v: &Vector3<f64>, u: &Vector3<f64>| -> (Vector3<f64>, Vector3<f64>) {
                let (pb, r) = self.pb(i, s, v, u);
                (pb / pb.norm(), r)
            };
        // explicit part (from s-)
        let mut f_minus = Vector3::zeros();
        let mut m_minus = Vector3::zeros();
        for &(i, b, _) in &terms {
            if b != 0.0 {
                let (t, r) = tangent(i, &v0, &u0);
                let p = t * (-b * self.tensions[i]);
                f_minus += p;
                m_minus += r.cross(&p);
            }
        }
        // residual of the jump for post-jump strains w = (v, u)
        let resid = |w: &nalgebra::Vector6<f64>| -> nalgebra::Vector6<f64> {
            let v = Vector3::new(w[0], w[1], w[2]);
            let u = Vector3::new(w[3], w[4], w[5]);
            let mut f = f_minus;
            let mut m = m_minus;
            for &(i, _, a) in &terms {
                if a != 0.0 {
                    let (t, r) = tangent(i, &v, &u);
                    let p = t * (a * self.tensions[i]);
                    f += p;
                    m += r.cross(&p);
                }
            }
            let dv = v - v0 + self.kse_inv.component_mul(&f);
            let du = (u - u0 + self.kbt_inv.component_mul(&m)) * len;
            nalgebra::Vector6::new(dv.x, dv.y, dv.z, du.x, du.y, du.z)
        };
        let mut w = nalgebra::Vector6::new(v0.x, v0.y, v0.z, u0.x, u0.y, u0.z);
        let mut r = resid(&w);
        let mut done = false;
        for _ in 0..50 {
            if r.amax() < 1e-14 {
                done = true;
                break;
            }
            let mut jac = nalgebra::Matrix6::zeros();
            for k in 0..6 {
                let scale = if k < 3 { 1.0 } else { 1.0 / len };
                let h = 1e-8 * w[k].abs().max(scale);
                let mut wp = w;
                wp[k] += h;
                jac.set_column(k, &((resid(&wp) - r) / h));
            }
            let dw = jac.lu().solve(&(-r)).ok_or_else(|| Error::Integration {
                s,
                reason: "singular anchor-load system".into(),
            })?;
            // backtrack if the full step does not reduce the residual
            let mut t = 1.0;
            loop {
                let wt = w + dw * t;
                let rt = resid(&wt);
                if rt.amax() < r.amax() || t < 1e-4 {
                    w = wt;
                    r = rt;
                    break;
                }
                t *= 0.5;
            }
        }
        if !done && r.amax() > 1e-12 {
            return Err(Error::Integration {
                s,
                reason: format!("anchor loads did not converge (residual {:.3e})", r.amax()),
            });
        }
        if w.iter().any(|x| !x.is_finite()) {
            return Err(Error::Integration {
                s,
                reason: "non-finite strains after anchor loads".into(),
            });
        }
        y[7..10].copy_from_slice(&[w[0], w[1], w[2]]);
        y[10..13].copy_from_slice(&[w[3], w[4], w[5]]);
        Ok(())
    }
}
