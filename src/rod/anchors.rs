//! Point loads and strain jumps at interior actuator anchors.
//!
//! With `P` the total point force on the body at an interior breakpoint `s`
//! where strings are anchored, `n(s+) = n(s-) - P` and
//! `m(s+) = m(s-) - sum r_i x P_i`, where a string ending at `s` contributes
//! `P_i = -tau_i t_i(s-)` (it pulls toward the base), one starting at `s`
//! contributes `+tau_i t_i(s+)`, and one passing `s` contributes
//! `tau_i (t_i(s+) - t_i(s-))`: the strains jump at an anchor, so every
//! string passing it has a kink there and presses on the body. `t(s+)`
//! depends on the post-jump strains, so the jump is solved by Newton's
//! method on the six strains, with the exact Jacobian of the jump residual
//! (6-direction dual numbers); its tangents follow by the implicit function
//! theorem.

use nalgebra::{Matrix6, Vector6};

use super::dual::{c_cross, cross_c, dot, Dual, Real, V3};
use super::ode::RodRhs;
use crate::error::{Error, Result};

/// `(index, before-side weight, after-side weight)` of a string at an
/// anchor: `P_i = tau_i (a t_i(s+) - b t_i(s-))`.
type Term = (usize, f64, f64);

/// A 6-vector of dual numbers seeded with the unit directions at `w`.
fn seeded(w: &[f64; 6]) -> [Dual<6>; 6] {
    std::array::from_fn(|k| {
        let mut e = [0.0; 6];
        e[k] = 1.0;
        Dual::new(w[k], e)
    })
}

impl RodRhs<'_> {
    /// The strings anchored at or passing `s`; zero tensions left out unless `with_zero`.
    fn anchor_terms(&self, s: f64, with_zero: bool) -> Vec<Term> {
        let tol = 1e-12 * self.robot.body.length;
        let mut terms = Vec::new();
        for (i, act) in self.robot.actuators.iter().enumerate() {
            if !with_zero && self.tensions[i] == 0.0 {
                continue;
            }
            let ends = (act.s_end - s).abs() <= tol;
            let starts = (act.s_start - s).abs() <= tol;
            let passes = act.s_start < s - tol && act.s_end > s + tol;
            let b = if ends || passes { 1.0 } else { 0.0 };
            let a = if starts || passes { 1.0 } else { 0.0 };
            if b != 0.0 || a != 0.0 {
                terms.push((i, b, a));
            }
        }
        terms
    }

    /// Residual of the anchor jump at `s` for post-jump strains `w = (v, u)`,
    /// pre-jump strains `w0` and tensions `tau`: `v - v0 + K_nu^-1 P` and
    /// `(u - u0 + K_omega^-1 sum r_i x P_i) L` (dimensionless).
    fn anchor_residual<T: Real>(
        &self,
        s: f64,
        terms: &[Term],
        w: &[T; 6],
        w0: &[T; 6],
        tau: &[T],
    ) -> [T; 6] {
        let len = self.robot.body.length;
        let zero = T::cst(0.0);
        let (mut f, mut m) = ([zero; 3], [zero; 3]);
        let mut add = |i: usize, weight: f64, st: &[T; 6]| {
            let (r, rp, _) = self.robot.actuators[i].routing.eval(s);
            let (r, rp): (V3<f64>, V3<f64>) = (r.into(), rp.into());
            let (v, u) = ([st[0], st[1], st[2]], [st[3], st[4], st[5]]);
            let ucr = cross_c(&u, &r);
            let pb: V3<T> = std::array::from_fn(|k| v[k] + ucr[k] + rp[k]); // eq (19)
            let nrm = dot(&pb, &pb).sqrt();
            let p: V3<T> = std::array::from_fn(|k| pb[k] / nrm * tau[i] * weight);
            let rxp = c_cross(&r, &p);
            for k in 0..3 {
                f[k] += p[k];
                m[k] += rxp[k];
            }
        };
        for &(i, b, a) in terms {
            if b != 0.0 {
                add(i, -b, w0);
            }
            if a != 0.0 {
                add(i, a, w);
            }
        }
        std::array::from_fn(|k| {
            if k < 3 {
                w[k] - w0[k] + f[k] * self.kse_inv[k]
            } else {
                (w[k] - w0[k] + m[k - 3] * self.kbt_inv[k - 3]) * len
            }
        })
    }

    /// The post-jump strains at the anchor node `s`: Newton's method on
    /// [`RodRhs::anchor_residual`] with its exact Jacobian, backtracking
    /// when a full step does not reduce the residual (converges in a few
    /// iterations even where plain fixed-point iteration diverges).
    pub(crate) fn anchor_loads(&self, s: f64, y: &mut [f64]) -> Result<()> {
        let terms = self.anchor_terms(s, false);
        if terms.is_empty() {
            return Ok(());
        }
        let w0: [f64; 6] = std::array::from_fn(|k| y[7 + k]);
        let w0d: [Dual<6>; 6] = w0.map(Dual::cst);
        let taud: Vec<Dual<6>> = self.tensions.iter().map(|&t| Dual::cst(t)).collect();
        let amax = |r: &[f64; 6]| r.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut w = w0;
        let mut r = self.anchor_residual(s, &terms, &w, &w0, self.tensions);
        let mut done = false;
        for _ in 0..50 {
            if amax(&r) < 1e-14 {
                done = true;
                break;
            }
            let g = self.anchor_residual(s, &terms, &seeded(&w), &w0d, &taud);
            let jac = Matrix6::from_fn(|i, j| g[i].eps[j]);
            let rhs = -Vector6::from_column_slice(&r);
            let dw = jac.lu().solve(&rhs).ok_or_else(|| Error::Integration {
                s,
                reason: "singular anchor-load system".into(),
            })?;
            let mut t = 1.0;
            loop {
                let wt: [f64; 6] = std::array::from_fn(|k| w[k] + dw[k] * t);
                let rt = self.anchor_residual(s, &terms, &wt, &w0, self.tensions);
                if amax(&rt) < amax(&r) || t < 1e-4 {
                    w = wt;
                    r = rt;
                    break;
                }
                t *= 0.5;
            }
        }
        if !done && amax(&r) > 1e-12 {
            return Err(Error::Integration {
                s,
                reason: format!("anchor loads did not converge (residual {:.3e})", amax(&r)),
            });
        }
        if w.iter().any(|x| !x.is_finite()) {
            return Err(Error::Integration {
                s,
                reason: "non-finite strains after anchor loads".into(),
            });
        }
        y[7..13].copy_from_slice(&w);
        Ok(())
    }

    /// The anchor jump at `s` on a dual state: the real part by
    /// [`RodRhs::anchor_loads`], the tangents by the implicit function
    /// theorem, `dw = -G_w^-1 (G_w0 dw0 + G_tau dtau)`, with `G_w` exact
    /// (6-direction duals) and every string at `s` counted (zero tensions
    /// too, so that the derivative with respect to a tension is right).
    pub(crate) fn anchor_tangent<const N: usize>(
        &self,
        s: f64,
        y: &mut [Dual<N>],
        tau: &[Dual<N>],
    ) -> Result<()> {
        let terms = self.anchor_terms(s, true);
        let mut yr: Vec<f64> = y.iter().map(|d| d.re).collect();
        self.anchor_loads(s, &mut yr)?;
        if terms.is_empty() {
            return Ok(());
        }
        let ws: [f64; 6] = std::array::from_fn(|k| yr[7 + k]);
        let w06: [Dual<6>; 6] = std::array::from_fn(|k| Dual::cst(y[7 + k].re));
        let tau6: Vec<Dual<6>> = tau.iter().map(|t| Dual::cst(t.re)).collect();
        let g6 = self.anchor_residual(s, &terms, &seeded(&ws), &w06, &tau6);
        let lu = Matrix6::from_fn(|r, c| g6[r].eps[c]).lu();
        // G_w0 dw0 + G_tau dtau at fixed w
        let wn: [Dual<N>; 6] = ws.map(Dual::cst);
        let w0n: [Dual<N>; 6] = std::array::from_fn(|k| y[7 + k]);
        let gn = self.anchor_residual(s, &terms, &wn, &w0n, tau);
        let mut out: [Dual<N>; 6] = wn;
        for d in 0..N {
            let rhs = Vector6::from_fn(|r, _| -gn[r].eps[d]);
            let dw = lu.solve(&rhs).ok_or_else(|| Error::Integration {
                s,
                reason: "singular anchor-load system".into(),
            })?;
            for k in 0..6 {
                out[k].eps[d] = dw[k];
            }
        }
        y[7..13].copy_from_slice(&out);
        Ok(())
    }
}
