//! The right-hand side (eqs 22-31) with its tangents, for the tangent pass:
//! the value by the `f64` IVP's own code, the derivative lanes
//! ([`Lanes`]) by the hand linearisation of each step.
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
//! every direction's `dx` reuses the factorisation. The frame and the
//! kinematics (22)-(23) are linear in the lanes at the value's
//! coefficients: `d(R v) = dR v + R dv` with `dR` linear in `dq`.

#[cfg(test)]
use super::dual::Dual;
use super::dual::{v3, V3};
use super::lanes::{dot_cl, lin, rot_apply, rot_coeffs, rot_t_coeffs, sub_cross_cl, Lanes};
use super::ode::{singular, Eq25, Frame, RodRhs, StringAt};
use super::BASE_STATES;
use crate::error::Result;

/// The lanes of one state: `dq`, `dnu`, `domega` (the others do not enter (22)-(31)).
struct StateLanes<const N: usize> {
    dq: [Lanes<N>; 4],
    dv: V3<Lanes<N>>,
    du: V3<Lanes<N>>,
}

impl RodRhs<'_> {
    /// `dy/ds` (eqs 22-31) into `dy`, bit-for-bit as [`RodRhs::deriv`] (the
    /// IVP's own code), and its tangents into `dyl` along the lanes `yl` of
    /// `y` and `taul` of the tensions: the exact derivatives of the same map
    /// (to rounding), as [`RodRhs::deriv_generic`] in [`Dual`] arithmetic
    /// gives them. `strings` is scratch. As in [`RodRhs::deriv`], the
    /// rates of the actuators not in `active` (and their lanes) are not
    /// written: the caller keeps them zero.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(crate) fn deriv_lanes<const N: usize>(
        &self,
        s: f64,
        (y, yl): (&[f64], &[Lanes<N>]),
        taul: &[Lanes<N>],
        active: &[usize],
        strings: &mut Vec<StringAt<f64>>,
        dy: &mut [f64],
        dyl: &mut [Lanes<N>],
    ) -> Result<()> {
        // the value: `deriv_generic` in f64, keeping the factorisation and strings
        let fr = self.frame(y);
        strings.clear();
        let (vd, ud, fac) = if active.is_empty() {
            let vd = v3(|k| fr.e[k] * self.kse_inv[k]);
            (vd, v3(|k| fr.f[k] * self.kbt_inv[k]), None)
        } else {
            let (m, e, f) = self.assemble(s, &fr, self.tensions, active, |i, st| {
                dy[BASE_STATES + i] = st.rate;
                strings.push(*st);
            })?;
            let fac = Eq25::factor(&m).ok_or_else(|| singular(s))?;
            let (vd, ud) = fac.solve(&e, &f);
            (vd, ud, Some(fac))
        };
        self.kinematics(s, y, &fr, &vd, &ud, dy)?;
        // the lanes
        let sl = StateLanes {
            dq: [yl[3], yl[4], yl[5], yl[6]],
            dv: [yl[7], yl[8], yl[9]],
            du: [yl[10], yl[11], yl[12]],
        };
        let q = [y[3], y[4], y[5], y[6]];
        let (mut de, mut df) = self.frame_lanes(&fr, &q, &sl);
        let (dvd, dud) = match fac {
            None => (
                v3(|k| de[k] * self.kse_inv[k]),
                v3(|k| df[k] * self.kbt_inv[k]),
            ),
            Some(fac) => {
                for (&i, st) in active.iter().zip(strings.iter()) {
                    let (daw, dnrm) = string_lanes(st, &fr.u, (&vd, &ud), &sl, taul[i]);
                    for k in 0..3 {
                        de[k] -= daw[k];
                    }
                    df = sub_cross_cl(&df, &st.r, &daw);
                    dyl[BASE_STATES + i] = dnrm; // (24)
                }
                fac.solve_lanes(&de, &df)
            }
        };
        kinematics_lanes(y, &fr, &sl, dyl);
        dyl[7..10].copy_from_slice(&dvd);
        dyl[10..13].copy_from_slice(&dud);
        Ok(())
    }

    /// The lanes of the actuator-free `[e; f]` of (25) ([`RodRhs::frame`]):
    /// `e = -u x n - R^T f_e`, `f = -u x m - v x n - R^T l_e` with
    /// `n = K_nu (v - nu*)`, `m = K_omega (u - omega*)`. Each component is
    /// a combination of four strain lanes with coefficients from the value
    /// (`-(du x n + u x K_nu dv)` and so on, cyclic `(i, j, k)`), and
    /// `R^T f_e` one of the four quaternion lanes.
    #[inline(always)]
    fn frame_lanes<const N: usize>(
        &self,
        fr: &Frame<f64>,
        q: &[f64; 4],
        sl: &StateLanes<N>,
    ) -> (V3<Lanes<N>>, V3<Lanes<N>>) {
        let body = &self.robot.body;
        let (v, u, kse, kbt) = (&fr.v, &fr.u, &self.kse, &self.kbt);
        let nse: V3<f64> = v3(|k| (v[k] - body.nu_star[k]) * kse[k]);
        let nbt: V3<f64> = v3(|k| (u[k] - body.omega_star[k]) * kbt[k]);
        let (du, dv) = (&sl.du, &sl.dv);
        let mut de = [Lanes::ZERO; 3];
        let mut df = [Lanes::ZERO; 3];
        for i in 0..3 {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            de[i] = lin([
                (du[j], -nse[k]),
                (du[k], nse[j]),
                (dv[j], u[k] * kse[j]),
                (dv[k], -u[j] * kse[k]),
            ]);
            df[i] = lin([
                (du[j], u[k] * kbt[j] - nbt[k]),
                (du[k], nbt[j] - u[j] * kbt[k]),
                (dv[j], v[k] * kse[j] - nse[k]),
                (dv[k], nse[j] - v[j] * kse[k]),
            ]);
        }
        if self.has_fe {
            let rtfe = rot_apply(&rot_t_coeffs(q, &self.fe.into()), &sl.dq);
            for k in 0..3 {
                de[k] -= rtfe[k];
            }
        }
        if self.has_le {
            let rtle = rot_apply(&rot_t_coeffs(q, &self.le.into()), &sl.dq);
            for k in 0..3 {
                df[k] -= rtle[k];
            }
        }
        (de, df)
    }

    /// `dy/ds` with its tangents along the `N` directions of `y` and `tau`
    /// in [`Dual`] form: [`RodRhs::deriv_lanes`] for the tests that compare
    /// it with [`RodRhs::deriv_generic`].
    #[cfg(test)]
    pub(crate) fn deriv_tangent<const N: usize>(
        &self,
        s: f64,
        y: &[Dual<N>],
        tau: &[Dual<N>],
        active: &[usize],
        dy: &mut [Dual<N>],
    ) -> Result<()> {
        debug_assert!(tau.iter().zip(self.tensions).all(|(a, b)| a.re == *b));
        let yr: Vec<f64> = y.iter().map(|d| d.re).collect();
        let yl: Vec<Lanes<N>> = y.iter().map(Lanes::of).collect();
        let taul: Vec<Lanes<N>> = tau.iter().map(Lanes::of).collect();
        let (mut out, mut outl) = (vec![0.0; y.len()], vec![Lanes::ZERO; y.len()]);
        let mut strings = Vec::new();
        self.deriv_lanes(
            s,
            (&yr, &yl),
            &taul,
            active,
            &mut strings,
            &mut out,
            &mut outl,
        )?;
        for (d, (re, l)) in dy.iter_mut().zip(out.iter().zip(&outl)) {
            *d = Dual::new(*re, l.0);
        }
        Ok(())
    }
}

/// One string's lanes at the solution `x = (v', u')` of (25): the lanes
/// of `A_i (z_i + g_i)` at fixed `x` and of `|p_b|` (eq 19, body frame):
/// `dp_b = dv + du x r`, `d|p_b| = t . dp_b`, `dc = (dtau - c d|p_b|) / |p_b|`,
/// `dt = (dp_b - t d|p_b|) / |p_b|`, `dg = du x (p_b + r') + u x dp_b`.
#[inline(always)]
fn string_lanes<const N: usize>(
    st: &StringAt<f64>,
    u: &V3<f64>,
    (vd, ud): (&V3<f64>, &V3<f64>),
    sl: &StateLanes<N>,
    dtau: Lanes<N>,
) -> (V3<Lanes<N>>, Lanes<N>) {
    let StringAt {
        r,
        c,
        t,
        g,
        nrm,
        pbrp,
        ..
    } = *st;
    // loops, not `v3` closures: a closure here may be compiled apart, without
    // the pass's target features. dp_b = dv + du x r:
    let (du, dv) = (&sl.du, &sl.dv);
    let dpb = [
        du[1].fma(r[2], du[2].fma(-r[1], dv[0])),
        du[2].fma(r[0], du[0].fma(-r[2], dv[1])),
        du[0].fma(r[1], du[1].fma(-r[0], dv[2])),
    ];
    let dnrm = dot_cl(&t, &dpb);
    let inv = 1.0 / nrm;
    let w = [
        g[0] + (vd[0] + ud[1] * r[2] - ud[2] * r[1]),
        g[1] + (vd[1] + ud[2] * r[0] - ud[0] * r[2]),
        g[2] + (vd[2] + ud[0] * r[1] - ud[1] * r[0]),
    ];
    let tw = t[0] * w[0] + t[1] * w[1] + t[2] * w[2];
    // w - t (t . w), the value A_i w / c
    let wt = [w[0] - t[0] * tw, w[1] - t[1] * tw, w[2] - t[2] * tw];
    if c == 0.0 {
        // a slack string: only its tension's lanes load the body,
        // A_i w = c (w - t (t . w)) with dc = dtau / |p_b|
        let dc = dtau * inv;
        return ([dc * wt[0], dc * wt[1], dc * wt[2]], dnrm);
    }
    let dc = dnrm.fma(-c, dtau) * inv;
    let mut dt = [Lanes::ZERO; 3];
    let mut dg = [Lanes::ZERO; 3];
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        dt[i] = dnrm.fma(-t[i], dpb[i]) * inv;
        // du x (p_b + r') + u x dp_b
        dg[i] = lin([
            (du[j], pbrp[k]),
            (du[k], -pbrp[j]),
            (dpb[k], u[j]),
            (dpb[j], -u[k]),
        ]);
    }
    // w = z_i + g_i at fixed x, its part along t removed: A_i w = c (w - t (t . w))
    let dtw = lin([
        (dt[0], w[0]),
        (dt[1], w[1]),
        (dt[2], w[2]),
        (dg[0], t[0]),
        (dg[1], t[1]),
        (dg[2], t[2]),
    ]);
    let mut daw = [Lanes::ZERO; 3];
    for k in 0..3 {
        let inner = dtw.fma(-t[k], dt[k].fma(-tw, dg[k]));
        daw[k] = inner.fma(c, dc * wt[k]);
    }
    (daw, dnrm)
}

/// The lanes of the kinematics (22)-(23) into `dyl[0..7]`:
/// `d(R v) = (dR/dq v) dq + R dv` and `dq' = (dq (0, u) + q (0, du)) / 2`.
#[inline(always)]
fn kinematics_lanes<const N: usize>(
    y: &[f64],
    fr: &Frame<f64>,
    sl: &StateLanes<N>,
    dyl: &mut [Lanes<N>],
) {
    let q = [y[3], y[4], y[5], y[6]];
    let cq = rot_coeffs(&q, &fr.v);
    let ([dw, dx, dy, dz], du, dv, rm) = (sl.dq, &sl.du, &sl.dv, &fr.rm);
    for k in 0..3 {
        // (22)
        dyl[k] = lin([
            (dw, cq[k][0]),
            (dx, cq[k][1]),
            (dy, cq[k][2]),
            (dz, cq[k][3]),
            (dv[0], rm[k][0]),
            (dv[1], rm[k][1]),
            (dv[2], rm[k][2]),
        ]);
    }
    let [hw, hx, hy, hz] = q.map(|c| 0.5 * c);
    let hu = fr.u.map(|c| 0.5 * c);
    // (23): q' = q (0, u) / 2, differentiated
    dyl[3] = lin([
        (dx, -hu[0]),
        (dy, -hu[1]),
        (dz, -hu[2]),
        (du[0], -hx),
        (du[1], -hy),
        (du[2], -hz),
    ]);
    dyl[4] = lin([
        (dw, hu[0]),
        (du[0], hw),
        (dy, hu[2]),
        (du[2], hy),
        (dz, -hu[1]),
        (du[1], -hz),
    ]);
    dyl[5] = lin([
        (dw, hu[1]),
        (du[1], hw),
        (dz, hu[0]),
        (du[0], hz),
        (dx, -hu[2]),
        (du[2], -hx),
    ]);
    dyl[6] = lin([
        (dw, hu[2]),
        (du[2], hw),
        (dx, hu[1]),
        (du[1], hx),
        (dy, -hu[0]),
        (du[0], -hy),
    ]);
}

impl Eq25 {
    /// [`Eq25::solve`] for the lanes of `[e; f]`, each product fused with its sum.
    #[inline(always)]
    fn solve_lanes<const N: usize>(
        &self,
        e: &V3<Lanes<N>>,
        f: &V3<Lanes<N>>,
    ) -> (V3<Lanes<N>>, V3<Lanes<N>>) {
        let (mi, m12, y, si) = (&self.m11_inv, &self.m12, &self.y12, &self.s_inv);
        let (mut a, mut g, mut ud) = ([Lanes::ZERO; 3], [Lanes::ZERO; 3], [Lanes::ZERO; 3]);
        for p in 0..3 {
            a[p] = lin([(e[0], mi[p][0]), (e[1], mi[p][1]), (e[2], mi[p][2])]);
        }
        for p in 0..3 {
            g[p] = a[2].fma(-m12[2][p], a[1].fma(-m12[1][p], a[0].fma(-m12[0][p], f[p])));
        }
        for p in 0..3 {
            ud[p] = lin([(g[0], si[p][0]), (g[1], si[p][1]), (g[2], si[p][2])]);
        }
        let mut vd = [Lanes::ZERO; 3];
        for p in 0..3 {
            vd[p] = ud[2].fma(-y[p][2], ud[1].fma(-y[p][1], ud[0].fma(-y[p][0], a[p])));
        }
        (vd, ud)
    }
}
