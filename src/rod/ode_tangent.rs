//! The right-hand side (eqs 22-31) with its tangents, for the tangent pass:
//! the value exactly as the `f64` IVP computes it, the derivative lanes by
//! the linearisation of (25) at its solution.
//!
//! Differentiating `M(y) x = b(y)` gives `M dx = db - dM x`. Formed
//! entry by entry (what [`RodRhs::deriv_generic`] does in [`Dual`]
//! arithmetic), `dM` costs 21 lane products per string and `dM x` 36 more.
//! With the blocks of [`RodRhs::deriv_generic`] and `z_i = v' + u' x r_i`,
//! the residual is
//!
//! `M x - b = [K_nu v' - e_0 + sum A_i (z_i + g_i); K_omega u' - f_0 + sum r_i x A_i (z_i + g_i)]`,
//!
//! and `A_i w = c (w - t (t . w))`: at fixed `x` its derivative costs a few
//! lane products per string. The value of `x` and the factorisation of `M`
//! come from `f64` ([`Eq25`]), bit-for-bit those of [`RodRhs::deriv`];
//! every direction's `dx` reuses the factorisation.

use super::dual::{c_cross, dot, v3, Dual, V3};
use super::ode::{singular, Eq25, Frame, RodRhs, StringAt};
use super::BASE_STATES;
use crate::error::Result;

impl RodRhs<'_> {
    /// `dy/ds` (eqs 22-31) with its tangents along the `N` directions of `y`
    /// and `tau`: the values bit-for-bit those of [`RodRhs::deriv`] (the
    /// tensions' values must be the IVP's), the tangents the exact
    /// derivatives of the same map (to rounding), as
    /// [`RodRhs::deriv_generic`] in [`Dual`] arithmetic gives them.
    #[inline(always)]
    pub(crate) fn deriv_tangent<const N: usize>(
        &self,
        s: f64,
        y: &[Dual<N>],
        tau: &[Dual<N>],
        active: &[usize],
        dy: &mut [Dual<N>],
    ) -> Result<()> {
        if active.is_empty() {
            // M is diagonal: the dual twin has no system to linearise
            return self.deriv_generic(s, y, tau, active, dy);
        }
        debug_assert!(tau.iter().zip(self.tensions).all(|(a, b)| a.re == *b));
        let fr = self.frame(y);
        // the value: (25) assembled, factored and solved in f64, as `deriv`
        let fr_re = Frame {
            rm: fr.rm.map(|row| row.map(|x| x.re)),
            v: fr.v.map(|x| x.re),
            u: fr.u.map(|x| x.re),
            e: fr.e.map(|x| x.re),
            f: fr.f.map(|x| x.re),
        };
        let (m, e, f) = self.assemble(s, &fr_re, self.tensions, active, |_, _| ())?;
        let fac = Eq25::factor(&m).ok_or_else(|| singular(s))?;
        let (vd, ud) = fac.solve(&e, &f);
        // the lanes: -d(M x - b) at fixed x, then dx = M^-1 (-d(M x - b))
        let (mut de, mut df) = (fr.e, fr.f);
        for d in dy[BASE_STATES..].iter_mut() {
            *d = Dual::new(0.0, [0.0; N]);
        }
        for &i in active {
            let StringAt { r, c, t, g, rate } = self.string_at(s, i, &fr.v, &fr.u, tau[i])?;
            let urx = [
                vd[0] + ud[1] * r[2] - ud[2] * r[1],
                vd[1] + ud[2] * r[0] - ud[0] * r[2],
                vd[2] + ud[0] * r[1] - ud[1] * r[0],
            ];
            let w: V3<Dual<N>> = v3(|k| g[k] + urx[k]); // z_i + g_i
            let tw = dot(&t, &w);
            let aw: V3<Dual<N>> = v3(|k| (w[k] - t[k] * tw) * c); // A_i (z_i + g_i)
            let raw = c_cross(&r, &aw);
            for k in 0..3 {
                de[k] -= aw[k];
                df[k] -= raw[k];
            }
            dy[BASE_STATES + i] = rate;
        }
        let (dvd, dud) = fac.solve_n(&de.map(|x| x.eps), &df.map(|x| x.eps));
        let vdd: V3<Dual<N>> = v3(|k| Dual::new(vd[k], dvd[k]));
        let udd: V3<Dual<N>> = v3(|k| Dual::new(ud[k], dud[k]));
        self.kinematics(s, y, &fr, &vdd, &udd, dy)
    }
}
