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
use super::lanes::{cross_cl, cross_lc, dot_cl, mat_cl, mat_lc, mat_t_lc, rot_lanes, Lanes};
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
    /// gives them. `strings` is scratch.
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
        for d in dy[BASE_STATES..].iter_mut() {
            *d = 0.0;
        }
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
        let drm = rot_lanes(&[y[3], y[4], y[5], y[6]], &sl.dq);
        let (mut de, mut df) = self.frame_lanes(&fr, &drm, &sl);
        for d in dyl[BASE_STATES..].iter_mut() {
            *d = Lanes::ZERO;
        }
        let (dvd, dud) = match fac {
            None => (
                v3(|k| de[k] * self.kse_inv[k]),
                v3(|k| df[k] * self.kbt_inv[k]),
            ),
            Some(fac) => {
                for (&i, st) in active.iter().zip(strings.iter()) {
                    let (daw, dnrm) = string_lanes(st, &fr.u, (&vd, &ud), &sl, taul[i]);
                    let rdaw = cross_cl(&st.r, &daw);
                    for k in 0..3 {
                        de[k] -= daw[k];
                        df[k] -= rdaw[k];
                    }
                    dyl[BASE_STATES + i] = dnrm; // (24)
                }
                let (a, b) = fac.solve_n(&de.map(|x| x.0), &df.map(|x| x.0));
                (a.map(Lanes), b.map(Lanes))
            }
        };
        kinematics_lanes(y, &fr, &drm, &sl, dyl);
        dyl[7..10].copy_from_slice(&dvd);
        dyl[10..13].copy_from_slice(&dud);
        Ok(())
    }

    /// The lanes of the actuator-free `[e; f]` of (25) ([`RodRhs::frame`]):
    /// `e = -u x n - R^T f_e`, `f = -u x m - v x n - R^T l_e` with
    /// `n = K_nu (v - nu*)`, `m = K_omega (u - omega*)`.
    #[inline(always)]
    fn frame_lanes<const N: usize>(
        &self,
        fr: &Frame<f64>,
        drm: &[V3<Lanes<N>>; 3],
        sl: &StateLanes<N>,
    ) -> (V3<Lanes<N>>, V3<Lanes<N>>) {
        let body = &self.robot.body;
        let (v, u) = (&fr.v, &fr.u);
        let nse: V3<f64> = v3(|k| (v[k] - body.nu_star[k]) * self.kse[k]);
        let nbt: V3<f64> = v3(|k| (u[k] - body.omega_star[k]) * self.kbt[k]);
        let dnse: V3<Lanes<N>> = v3(|k| sl.dv[k] * self.kse[k]);
        let dnbt: V3<Lanes<N>> = v3(|k| sl.du[k] * self.kbt[k]);
        let (a, b) = (cross_lc(&sl.du, &nse), cross_cl(u, &dnse));
        let mut de: V3<Lanes<N>> = v3(|k| -(a[k] + b[k]));
        let (a, b) = (cross_lc(&sl.du, &nbt), cross_cl(u, &dnbt));
        let (c, d) = (cross_lc(&sl.dv, &nse), cross_cl(v, &dnse));
        let mut df: V3<Lanes<N>> = v3(|k| -(a[k] + b[k]) - (c[k] + d[k]));
        if self.has_fe {
            let rtfe = mat_t_lc(drm, &self.fe.into());
            for k in 0..3 {
                de[k] -= rtfe[k];
            }
        }
        if self.has_le {
            let rtle = mat_t_lc(drm, &self.le.into());
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
    // loops, not `v3` closures: a closure here was compiled apart, without
    // the pass's target features
    let dur = cross_lc(&sl.du, &r);
    let mut dpb = [Lanes::ZERO; 3];
    for k in 0..3 {
        dpb[k] = sl.dv[k] + dur[k];
    }
    let dnrm = dot_cl(&t, &dpb);
    let inv = 1.0 / nrm;
    let w = [
        g[0] + (vd[0] + ud[1] * r[2] - ud[2] * r[1]),
        g[1] + (vd[1] + ud[2] * r[0] - ud[0] * r[2]),
        g[2] + (vd[2] + ud[0] * r[1] - ud[1] * r[0]),
    ];
    let tw = t[0] * w[0] + t[1] * w[1] + t[2] * w[2];
    if c == 0.0 {
        // a slack string: only its tension's lanes load the body,
        // A_i w = c (w - t (t . w)) with dc = dtau / |p_b|
        let dc = dtau * inv;
        let mut daw = [Lanes::ZERO; 3];
        for k in 0..3 {
            daw[k] = dc * (w[k] - t[k] * tw);
        }
        return (daw, dnrm);
    }
    let dc = (dtau - dnrm * c) * inv;
    let mut dt = [Lanes::ZERO; 3];
    for k in 0..3 {
        dt[k] = (dpb[k] - dnrm * t[k]) * inv;
    }
    let (a, b) = (cross_lc(&sl.du, &pbrp), cross_cl(u, &dpb));
    let mut dg = [Lanes::ZERO; 3];
    for k in 0..3 {
        dg[k] = a[k] + b[k];
    }
    // w = z_i + g_i at fixed x, its part along t removed: A_i w = c (w - t (t . w))
    let dtw = dot_cl(&w, &dt) + dot_cl(&t, &dg);
    let mut daw = [Lanes::ZERO; 3];
    for k in 0..3 {
        daw[k] = (dg[k] - dt[k] * tw - dtw * t[k]) * c + dc * (w[k] - t[k] * tw);
    }
    (daw, dnrm)
}

/// The lanes of the kinematics (22)-(23) into `dyl[0..7]`:
/// `d(R v) = dR v + R dv` and `dq' = (dq (0, u) + q (0, du)) / 2`.
#[inline(always)]
fn kinematics_lanes<const N: usize>(
    y: &[f64],
    fr: &Frame<f64>,
    drm: &[V3<Lanes<N>>; 3],
    sl: &StateLanes<N>,
    dyl: &mut [Lanes<N>],
) {
    let (a, b) = (mat_lc(drm, &fr.v), mat_cl(&fr.rm, &sl.dv));
    for k in 0..3 {
        dyl[k] = a[k] + b[k]; // (22)
    }
    let [hw, hx, hy, hz] = [y[3], y[4], y[5], y[6]].map(|c| 0.5 * c);
    let hu = fr.u.map(|c| 0.5 * c);
    let ([dw, dx, dy, dz], du) = (sl.dq, &sl.du);
    // (23): q' = q (0, u) / 2, differentiated
    dyl[3] = -(dx * hu[0] + dy * hu[1] + dz * hu[2] + du[0] * hx + du[1] * hy + du[2] * hz);
    dyl[4] = dw * hu[0] + du[0] * hw + dy * hu[2] + du[2] * hy - dz * hu[1] - du[1] * hz;
    dyl[5] = dw * hu[1] + du[1] * hw + dz * hu[0] + du[0] * hz - dx * hu[2] - du[2] * hx;
    dyl[6] = dw * hu[2] + du[2] * hw + dx * hu[1] + du[1] * hx - dy * hu[0] - du[0] * hy;
}
