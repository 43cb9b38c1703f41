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

use nalgebra::Vector3;

use super::dual::{c_cross, cross_c, dot, Dual, Real, V3};
use super::eq25::Eq25;
use super::ode::{add_string, RodRhs};
use crate::error::{Error, Result};

/// A string at an anchor, its routing evaluated there once (not per
/// residual evaluation): `P_i = tau_i (a t_i(s+) - b t_i(s-))`.
#[derive(Clone, Copy, Default)]
struct Anchored {
    /// Actuator index.
    i: usize,
    /// Before-side weight `b`.
    b: f64,
    /// After-side weight `a`.
    a: f64,
    /// Routing `r` \[m\] and `r'` at the anchor.
    r: V3<f64>,
    rp: V3<f64>,
    /// Tension \[N\] (value only).
    tau: f64,
    /// The before side's `(P, r x P)`, constant while the post-jump strains
    /// are iterated (zero if `b == 0`).
    pre: (V3<f64>, V3<f64>),
}

/// Strings kept on the stack at one anchor (more spill to the heap).
const INLINE: usize = 8;

/// Tolerance on the max-norm of the jump residual (dimensionless: strain
/// mismatches, the curvatures times `L`; see `RodRhs::jump_residual`).
const JUMP_TOL: f64 = 1e-14;
/// A residual accepted when the full Newton step no longer reduces it
/// (the rounding floor of large strains lies between the two).
const JUMP_FLOOR: f64 = 1e-12;

/// `(P, r x P)` of one side of string `t` with strains `st = (v, u)`:
/// `P = tau weight p / |p|`, `p = v + u x r + r'` (eq 19).
#[inline(always)]
fn side<T: Real>(t: &Anchored, weight: f64, st: &[T; 6], tau: T) -> (V3<T>, V3<T>) {
    let (v, u) = ([st[0], st[1], st[2]], [st[3], st[4], st[5]]);
    let ucr = cross_c(&u, &t.r);
    let pb: V3<T> = std::array::from_fn(|k| v[k] + ucr[k] + t.rp[k]);
    let nrm = dot(&pb, &pb).sqrt();
    let p: V3<T> = std::array::from_fn(|k| pb[k] / nrm * tau * weight);
    let rxp = c_cross(&t.r, &p);
    (p, rxp)
}

/// A factored jump Newton matrix `D (K + G)` ([`RodRhs::jump_matrix`]):
/// `K + G` by blocks, and `D^-1` as a vector.
struct JumpMatrix {
    eq25: Eq25,
    /// `D^-1 = diag(K_nu, K_omega / L)`.
    d: [f64; 6],
}

impl JumpMatrix {
    /// `dw` with `D (K + G) dw = -r`.
    fn newton_step(&self, r: &[f64; 6]) -> [f64; 6] {
        let e: V3<f64> = std::array::from_fn(|k| -r[k] * self.d[k]);
        let f: V3<f64> = std::array::from_fn(|k| -r[k + 3] * self.d[k + 3]);
        let (dv, du) = self.eq25.solve(&e, &f);
        [dv[0], dv[1], dv[2], du[0], du[1], du[2]]
    }
}

/// Largest absolute entry.
fn amax(r: &[f64; 6]) -> f64 {
    r.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The singular-system error at `s`.
fn singular(s: f64) -> Error {
    Error::Integration {
        s,
        reason: "singular anchor-load system".into(),
    }
}

impl RodRhs<'_> {
    /// Calls `f` with the strings anchored at or passing `s`, their
    /// tensions `tau(i)`; zero tensions left out unless `with_zero`.
    fn with_terms<R>(
        &self,
        s: f64,
        with_zero: bool,
        tau: impl Fn(usize) -> f64,
        f: impl FnOnce(&mut [Anchored]) -> R,
    ) -> R {
        let tol = 1e-12 * self.robot.body.length;
        let mut buf = [Anchored::default(); INLINE];
        let mut heap = Vec::new();
        let mut n = 0;
        for (i, act) in self.robot.actuators.iter().enumerate() {
            if !with_zero && self.tensions[i] == 0.0 {
                continue;
            }
            let ends = (act.s_end - s).abs() <= tol;
            let starts = (act.s_start - s).abs() <= tol;
            let passes = act.s_start < s - tol && act.s_end > s + tol;
            let b = if ends || passes { 1.0 } else { 0.0 };
            let a = if starts || passes { 1.0 } else { 0.0 };
            if b == 0.0 && a == 0.0 {
                continue;
            }
            let (r, rp, _) = act.routing.eval(s);
            let (r, rp) = (r.into(), rp.into());
            let (tau, pre) = (tau(i), ([0.0; 3], [0.0; 3]));
            let t = Anchored {
                i,
                b,
                a,
                r,
                rp,
                tau,
                pre,
            };
            if n < INLINE {
                buf[n] = t;
            } else {
                if n == INLINE {
                    heap.extend_from_slice(&buf);
                }
                heap.push(t);
            }
            n += 1;
        }
        if n <= INLINE {
            f(&mut buf[..n])
        } else {
            f(&mut heap)
        }
    }

    /// `v - v0 + K_nu^-1 f` and `(u - u0 + K_omega^-1 m) L` (dimensionless).
    #[inline(always)]
    fn jump_residual<T, U>(&self, w: &[T; 6], w0: &[U; 6], f: &V3<T>, m: &V3<T>) -> [T; 6]
    where
        T: Real + std::ops::Sub<U, Output = T>,
        U: Real,
    {
        let len = self.robot.body.length;
        std::array::from_fn(|k| {
            if k < 3 {
                w[k] - w0[k] + f[k] * self.kse_inv[k]
            } else {
                (w[k] - w0[k] + m[k - 3] * self.kbt_inv[k - 3]) * len
            }
        })
    }

    /// Residual of the anchor jump for post-jump strains `w = (v, u)`,
    /// pre-jump strains `w0` and tensions `tau` (all sides evaluated; the
    /// tangent pass's derivatives with respect to `w0` and `tau`).
    fn anchor_residual<T: Real>(
        &self,
        terms: &[Anchored],
        w: &[T; 6],
        w0: &[T; 6],
        tau: &[T],
    ) -> [T; 6] {
        let zero = T::cst(0.0);
        let (mut f, mut m) = ([zero; 3], [zero; 3]);
        for t in terms {
            for (weight, st) in [(-t.b, w0), (t.a, w)] {
                if weight != 0.0 {
                    let (p, rxp) = side(t, weight, st, tau[t.i]);
                    for k in 0..3 {
                        f[k] += p[k];
                        m[k] += rxp[k];
                    }
                }
            }
        }
        self.jump_residual(w, w0, &f, &m)
    }

    /// [`RodRhs::anchor_residual`] at fixed `w0` and tensions, the before
    /// sides taken from `Anchored::pre` (same operations in the same order,
    /// so the same value bit for bit).
    fn after_residual<T: Real>(&self, terms: &[Anchored], w: &[T; 6], w0: &[f64; 6]) -> [T; 6] {
        let zero = T::cst(0.0);
        let (mut f, mut m) = ([zero; 3], [zero; 3]);
        for t in terms {
            if t.b != 0.0 {
                for k in 0..3 {
                    f[k] = f[k] + t.pre.0[k];
                    m[k] = m[k] + t.pre.1[k];
                }
            }
            if t.a != 0.0 {
                let (p, rxp) = side(t, t.a, w, T::cst(t.tau));
                for k in 0..3 {
                    f[k] += p[k];
                    m[k] += rxp[k];
                }
            }
        }
        self.jump_residual(w, w0, &f, &m)
    }

    /// The Newton matrix of the jump residual at post-jump strains `w`,
    /// factored: `G_w = D (K + G)` with `D = diag(K_nu^-1, L K_omega^-1)`,
    /// `K = diag(K_nu, K_omega)` and `G` the derivative of the after
    /// sides' `(F, r x F)` with respect to `w`, which has the eq-25
    /// blocks of each string (`ode::add_string`, with `c = tau a / |p|`):
    /// `K + G` is symmetric and factored as eq 25 is (`Eq25`). (The
    /// before sides do not depend on `w`.) `None` if singular.
    fn jump_matrix(&self, terms: &[Anchored], w: &[f64; 6]) -> Option<JumpMatrix> {
        let (v, u) = ([w[0], w[1], w[2]], [w[3], w[4], w[5]]);
        let diag = |k: &Vector3<f64>| {
            std::array::from_fn(|p| std::array::from_fn(|q| k[p] * f64::from(p == q)))
        };
        let mut m = [diag(&self.kse), [[0.0; 3]; 3], diag(&self.kbt)];
        for t in terms.iter().filter(|t| t.a != 0.0) {
            let ucr = cross_c(&u, &t.r);
            let pb: V3<f64> = std::array::from_fn(|k| v[k] + ucr[k] + t.rp[k]);
            let nrm = dot(&pb, &pb).sqrt();
            let tt: V3<f64> = pb.map(|x| x / nrm);
            add_string(&mut m, t.tau * t.a / nrm, &tt, &t.r, dot(&t.r, &t.r));
        }
        let d: [f64; 6] = std::array::from_fn(|k| match k < 3 {
            true => self.kse[k],
            false => self.kbt[k - 3] / self.robot.body.length,
        });
        Some(JumpMatrix {
            eq25: Eq25::factor(&m)?,
            d,
        })
    }

    /// Fills every string's before side at `w0`.
    fn prepare(terms: &mut [Anchored], w0: &[f64; 6]) {
        for t in terms.iter_mut() {
            if t.b != 0.0 {
                t.pre = side(t, -t.b, w0, t.tau);
            }
        }
    }

    /// The post-jump strains for pre-jump strains `w0`: Newton's method on
    /// the jump residual with its exact Jacobian, backtracking when a full
    /// step does not reduce the residual (converges in a few iterations
    /// even where plain fixed-point iteration diverges). Stops at
    /// [`JUMP_TOL`], or at the rounding floor: a residual at most
    /// [`JUMP_FLOOR`] that a full step no longer reduces. Returns the
    /// strains and the Newton iterations taken.
    fn jump(&self, s: f64, terms: &mut [Anchored], w0: &[f64; 6]) -> Result<([f64; 6], usize)> {
        Self::prepare(terms, w0);
        let terms = &*terms;
        let mut w = *w0;
        let mut r = self.after_residual(terms, &w, w0);
        let mut done = false;
        let mut iterations = 0;
        'newton: for _ in 0..50 {
            if amax(&r) < JUMP_TOL {
                done = true;
                break;
            }
            iterations += 1;
            let dw = self
                .jump_matrix(terms, &w)
                .ok_or_else(|| singular(s))?
                .newton_step(&r);
            let mut t = 1.0;
            loop {
                let wt: [f64; 6] = std::array::from_fn(|k| w[k] + dw[k] * t);
                let rt = self.after_residual(terms, &wt, w0);
                if amax(&rt) < amax(&r) || t < 1e-4 {
                    w = wt;
                    r = rt;
                    break;
                }
                if t == 1.0 && amax(&r) <= JUMP_FLOOR {
                    // at the rounding floor: no step can do better
                    done = true;
                    break 'newton;
                }
                t *= 0.5;
            }
        }
        if !done && amax(&r) > JUMP_FLOOR {
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
        Ok((w, iterations))
    }

    /// The post-jump strains at the anchor node `s` (by `RodRhs::jump`),
    /// written into `y`.
    pub(crate) fn anchor_loads(&self, s: f64, y: &mut [f64]) -> Result<()> {
        let w0: [f64; 6] = std::array::from_fn(|k| y[7 + k]);
        let w = self.post_jump(s, &w0)?;
        y[7..13].copy_from_slice(&w);
        Ok(())
    }

    /// The post-jump strains at `s` for pre-jump strains `w0` (`w0` itself
    /// where no string with a tension is anchored or kinked).
    fn post_jump(&self, s: f64, w0: &[f64; 6]) -> Result<[f64; 6]> {
        let tensions = self.tensions;
        self.with_terms(
            s,
            false,
            |i| tensions[i],
            |terms| {
                if terms.is_empty() {
                    return Ok(*w0);
                }
                Ok(self.jump(s, terms, w0)?.0)
            },
        )
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
        let w0: [f64; 6] = std::array::from_fn(|k| y[7 + k].re);
        let ws = self.post_jump(s, &w0)?;
        let out = self.with_terms(
            s,
            true,
            |i| tau[i].re,
            |terms| {
                if terms.is_empty() {
                    return Ok(None);
                }
                let jac = self.jump_matrix(terms, &ws).ok_or_else(|| singular(s))?;
                // G_w0 dw0 + G_tau dtau at fixed w
                let wn: [Dual<N>; 6] = ws.map(Dual::cst);
                let w0n: [Dual<N>; 6] = std::array::from_fn(|k| y[7 + k]);
                let gn = self.anchor_residual(terms, &wn, &w0n, tau);
                let mut out: [Dual<N>; 6] = wn;
                for d in 0..N {
                    let dw = jac.newton_step(&gn.map(|g| g.eps[d]));
                    for k in 0..6 {
                        out[k].eps[d] = dw[k];
                    }
                }
                Ok(Some(out))
            },
        )?;
        if let Some(out) = out {
            y[7..13].copy_from_slice(&out);
        }
        Ok(())
    }
}

#[cfg(test)]
#[path = "anchors_tests.rs"]
mod tests;
