//! The right-hand side of the rod's ODE, eqs 22-31, with the actuator
//! tensions frozen for one IVP.

use nalgebra::Vector3;

use super::dual::{c_cross, cross, cross_c, dot, rot_t, rt_mul, v3, Blocks, Real, V3};
pub(crate) use super::eq25::Eq25;
use super::{Robot, Routing, BASE_STATES};
use crate::error::{Error, Result};

/// Per-actuator constants of one IVP: a straight actuator's offset and
/// reference length rate do not change along `s`.
pub(crate) struct ActuatorConstants {
    /// `(r, L_i)` for a straight routing; `None` for a helix (evaluated per stage).
    pub(crate) straight: Option<(Vector3<f64>, f64)>,
    /// `|r|^2` \[m^2\] of a straight routing (0 for a helix).
    pub(crate) rr: f64,
}

/// The eq-25 right-hand side of one IVP: the robot, its actuator tensions
/// (constant along each string) and constants derived from them.
pub(crate) struct RodRhs<'a> {
    pub(crate) robot: &'a Robot,
    pub(crate) tensions: &'a [f64],
    /// Diagonals of `K_nu`, `K_omega` and their inverses.
    pub(crate) kse: Vector3<f64>,
    pub(crate) kbt: Vector3<f64>,
    pub(crate) kse_inv: Vector3<f64>,
    pub(crate) kbt_inv: Vector3<f64>,
    pub(crate) fe: Vector3<f64>,
    pub(crate) le: Vector3<f64>,
    pub(crate) has_fe: bool,
    pub(crate) has_le: bool,
    pub(crate) acts: Vec<ActuatorConstants>,
}

impl<'a> RodRhs<'a> {
    pub(crate) fn new(robot: &'a Robot, tensions: &'a [f64]) -> Self {
        let body = &robot.body;
        let (kse, kbt) = body.stiffness();
        let kse = kse.diagonal();
        let kbt = kbt.diagonal();
        let acts = robot
            .actuators
            .iter()
            .map(|a| {
                let straight = match a.routing {
                    Routing::Straight { x, y } => {
                        let r = Vector3::new(x, y, 0.0);
                        let l = a
                            .length_ratio
                            .unwrap_or_else(|| (body.nu_star + body.omega_star.cross(&r)).norm());
                        Some((r, l))
                    }
                    Routing::Helix { .. } => None,
                };
                let rr = straight.map_or(0.0, |(r, _)| norm2(&r.into()));
                ActuatorConstants { straight, rr }
            })
            .collect();
        RodRhs {
            robot,
            tensions,
            kse,
            kbt,
            kse_inv: kse.map(|x| 1.0 / x),
            kbt_inv: kbt.map(|x| 1.0 / x),
            fe: body.distributed_load(),
            le: body.distributed_moment,
            has_fe: body.distributed_load() != Vector3::zeros(),
            has_le: body.distributed_moment != Vector3::zeros(),
            acts,
        }
    }

    /// Body-frame tangent rate of actuator `i`: `v + u x r + r'` (eq 19 without `R`).
    #[inline]
    pub(crate) fn pb(
        &self,
        i: usize,
        s: f64,
        v: &Vector3<f64>,
        u: &Vector3<f64>,
    ) -> (Vector3<f64>, Vector3<f64>) {
        let (r, rp, _) = self.robot.actuators[i].routing.eval(s);
        (v + u.cross(&r) + rp, r)
    }

    /// Reference length rate of actuator `i` at `s` (the paper's `L_i`).
    #[inline]
    pub(crate) fn ref_rate(&self, i: usize, s: f64) -> f64 {
        let a = &self.robot.actuators[i];
        match a.length_ratio {
            Some(l) => l,
            None => {
                let (r, rp, _) = a.routing.eval(s);
                (self.robot.body.nu_star + self.robot.body.omega_star.cross(&r) + rp).norm()
            }
        }
    }

    /// `(r, |r|^2, (r', r''), L_i)` of actuator `i` at `s`: the constants of
    /// a straight routing, with `None` for its vanishing `r'` and `r''`.
    #[inline(always)]
    pub(crate) fn routing_at(&self, i: usize, s: f64) -> (V3<f64>, f64, Option<Bend>, f64) {
        let a = &self.acts[i];
        match a.straight {
            Some((r, l)) => (r.into(), a.rr, None, l),
            None => {
                let (r, rp, rpp) = self.robot.actuators[i].routing.eval(s);
                let r: V3<f64> = r.into();
                let bend = Some((rp.into(), rpp.into()));
                (r, norm2(&r), bend, self.ref_rate(i, s))
            }
        }
    }

    /// `dy/ds` (eqs 22-31) with the IVP's tensions, in `f64`, WITHOUT the
    /// finiteness check of [`RodRhs::kinematics`]: the caller checks its
    /// state once per RK4 step instead (`all_finite`: a non-finite rate
    /// makes the stepped state non-finite).
    ///
    /// The elongation rates of the actuators not in `active` are NOT
    /// written: the caller keeps them zero in `dy` (the IVP zeroes its
    /// stages once per grid interval). Zeroing them here, a slice of
    /// run-time length, would compile to a `memset` call per stage, with
    /// spills of the registers the call clobbers around it.
    #[inline(always)]
    pub(crate) fn deriv(&self, s: f64, y: &[f64], active: &[usize], dy: &mut [f64]) -> Result<()> {
        self.deriv_with::<f64, false>(s, y, self.tensions, active, dy)
    }

    /// `dy/ds` (eqs 22-31) with tensions `tau` and the actuators in `active`
    /// (indices), in any [`Real`] arithmetic: `f64` for IVPs, [`super::dual::Dual`]
    /// for the reference tangents. The one implementation of the right-hand side
    /// (its plain twin in the paper's notation is `ode_reference.rs`; the
    /// tangent pass's linearisation, `ode_tangent.rs`, reuses its pieces).
    ///
    /// The 6x6 system (25) is symmetric, `[[M11, M12], [M12^T, M22]]` with
    /// `M11 = K_nu + sum A_i`, `M12 = -sum A_i r_i^`, `M22 = K_omega - sum r_i^ A_i r_i^`
    /// (`A_i` symmetric, `r^T = -r^`); it is assembled on the upper
    /// triangles ([`RodRhs::assemble`]) and solved by [`Real::solve_eq25`]
    /// (block elimination).
    #[inline(always)]
    pub(crate) fn deriv_generic<T: Real>(
        &self,
        s: f64,
        y: &[T],
        tau: &[T],
        active: &[usize],
        dy: &mut [T],
    ) -> Result<()> {
        for d in dy[BASE_STATES..].iter_mut() {
            *d = T::cst(0.0);
        }
        self.deriv_with::<T, true>(s, y, tau, active, dy)
    }

    /// [`RodRhs::deriv_generic`], with its finiteness check if `CHECK`,
    /// the inactive actuators' rates left as `dy` holds them.
    #[inline(always)]
    fn deriv_with<T: Real, const CHECK: bool>(
        &self,
        s: f64,
        y: &[T],
        tau: &[T],
        active: &[usize],
        dy: &mut [T],
    ) -> Result<()> {
        let fr = self.frame(y);
        let (vd, ud): (V3<T>, V3<T>) = if active.is_empty() {
            (
                v3(|k| fr.e[k] * self.kse_inv[k]),
                v3(|k| fr.f[k] * self.kbt_inv[k]),
            )
        } else {
            let (m, e, f) =
                self.assemble(s, &fr, tau, active, |i, st| dy[BASE_STATES + i] = st.rate)?;
            T::solve_eq25(&m, &e, &f).ok_or_else(|| singular(s))?
        };
        self.rates(y, &fr, &vd, &ud, dy);
        if CHECK {
            finite(s, dy)?;
        }
        Ok(())
    }

    /// The actuator-free part of (25) at the state `y`: `R`, the strains and
    /// `[e; f]` without the actuators' terms (30)-(31).
    #[inline(always)]
    pub(crate) fn frame<T: Real>(&self, y: &[T]) -> Frame<T> {
        let body = &self.robot.body;
        let (nu_star, omega_star): (V3<f64>, V3<f64>) =
            (body.nu_star.into(), body.omega_star.into());
        let (kse, kbt): (V3<f64>, V3<f64>) = (self.kse.into(), self.kbt.into());
        let rm = rot_t(&[y[3], y[4], y[5], y[6]]);
        let v = [y[7], y[8], y[9]];
        let u = [y[10], y[11], y[12]];
        let nse: V3<T> = v3(|k| (v[k] - nu_star[k]) * kse[k]);
        let nbt: V3<T> = v3(|k| (u[k] - omega_star[k]) * kbt[k]);
        let (ucn, rtfe) = (cross(&u, &nse), rt_mul(&rm, &self.fe.into()));
        let e: V3<T> = v3(|k| -ucn[k] - rtfe[k]);
        let (ucb, vcn) = (cross(&u, &nbt), cross(&v, &nse));
        let mut f: V3<T> = v3(|k| -ucb[k] - vcn[k]);
        if self.has_le {
            let rtle = rt_mul(&rm, &self.le.into());
            for k in 0..3 {
                f[k] -= rtle[k];
            }
        }
        Frame { rm, v, u, e, f }
    }

    /// Actuator `i`'s string at arc length `s` with strains `v`, `u` and
    /// tension `tau` (eqs 19-20): an error if its length rate vanishes.
    #[inline(always)]
    pub(crate) fn string_at<T: Real>(
        &self,
        s: f64,
        i: usize,
        v: &V3<T>,
        u: &V3<T>,
        tau: T,
    ) -> Result<StringAt<T>> {
        let (r, rr, bend, lref) = self.routing_at(i, s);
        let ucr = cross_c(u, &r);
        // eq (19), body frame; a straight routing's `r' = r'' = 0` is not
        // added (which changes no value but the sign of a zero)
        let mut pb: V3<T> = v3(|k| v[k] + ucr[k]);
        if let Some((rp, _)) = &bend {
            pb = v3(|k| pb[k] + rp[k]);
        }
        let nrm = dot(&pb, &pb).sqrt();
        if !(nrm.re() > 1e-12) {
            // a non-finite state reaches here first since the IVP checks
            // finiteness once per RK4 step, not per stage
            let reason = match nrm.re().is_finite() {
                true => format!("actuator {i} has zero length rate"),
                false => "non-finite derivative".into(),
            };
            return Err(Error::Integration { s, reason });
        }
        let (pbrp, g) = match &bend {
            // g_i = omega^(nu + omega^ r + 2 r') + r''
            Some((rp, rpp)) => {
                let pbrp: V3<T> = v3(|k| pb[k] + rp[k]);
                let upr = cross(u, &pbrp);
                (pbrp, v3(|k| upr[k] + rpp[k]))
            }
            None => (pb, cross(u, &pb)),
        };
        // one division, not four (on the critical path of every stage)
        let inv = T::cst(1.0) / nrm;
        Ok(StringAt {
            r,
            rr,
            c: tau * inv,
            t: v3(|k| pb[k] * inv),
            g,
            rate: nrm - lref, // (24)
            nrm,
            pbrp,
        })
    }

    /// The blocks `[M11, M12, M22]` of (25) (symmetric ones stored whole)
    /// and its right-hand side `[e; f]` for the actuators in `active`, from
    /// the actuator-free `frame`; `each(i, string)` gets each string (its
    /// elongation rate (24) among its fields), in the order of `active`.
    #[inline(always)]
    pub(crate) fn assemble<T: Real>(
        &self,
        s: f64,
        fr: &Frame<T>,
        tau: &[T],
        active: &[usize],
        mut each: impl FnMut(usize, &StringAt<T>),
    ) -> Result<(Blocks<T>, V3<T>, V3<T>)> {
        let zero = T::cst(0.0);
        let (kse, kbt): (V3<f64>, V3<f64>) = (self.kse.into(), self.kbt.into());
        let (mut e, mut f) = (fr.e, fr.f);
        let mut m = [[[zero; 3]; 3]; 3];
        for k in 0..3 {
            m[0][k][k] = T::cst(kse[k]);
            m[2][k][k] = T::cst(kbt[k]);
        }
        for &i in active {
            let st = self.string_at(s, i, &fr.v, &fr.u, tau[i])?;
            if tau[i].is_zero() {
                // A_i = 0: the slack string adds nothing to (25) (each
                // term below is a product with c = 0)
                each(i, &st);
                continue;
            }
            let StringAt { r, rr, c, t, g, .. } = st;
            let ct = add_string(&mut m, c, &t, &r, rr);
            let tg = dot(&t, &g);
            let ag: V3<T> = v3(|k| g[k] * c - ct[k] * tg); // A_i g_i
            let rag = c_cross(&r, &ag);
            for p in 0..3 {
                e[p] -= ag[p]; // (30)
                f[p] -= rag[p]; // (31)
            }
            each(i, &st);
        }
        for (p, q) in [(1, 0), (2, 0), (2, 1)] {
            m[0][p][q] = m[0][q][p];
            m[2][p][q] = m[2][q][p];
        }
        Ok((m, e, f))
    }

    /// The kinematics (22)-(23) into `dy` and the strain rates `vd`, `ud`
    /// (the solution of (25)); an error if any rate is not finite.
    #[inline(always)]
    pub(crate) fn kinematics<T: Real>(
        &self,
        s: f64,
        y: &[T],
        fr: &Frame<T>,
        vd: &V3<T>,
        ud: &V3<T>,
        dy: &mut [T],
    ) -> Result<()> {
        self.rates(y, fr, vd, ud, dy);
        finite(s, dy)
    }

    /// [`RodRhs::kinematics`] without the check.
    #[inline(always)]
    fn rates<T: Real>(&self, y: &[T], fr: &Frame<T>, vd: &V3<T>, ud: &V3<T>, dy: &mut [T]) {
        let (rm, v, u) = (&fr.rm, &fr.v, &fr.u);
        for k in 0..3 {
            dy[k] = rm[k][0] * v[0] + rm[k][1] * v[1] + rm[k][2] * v[2]; // (22)
        }
        // (23) as q' = q (0, u) / 2
        let (qw, qx, qy, qz) = (y[3], y[4], y[5], y[6]);
        dy[3] = -(qx * u[0] + qy * u[1] + qz * u[2]) * 0.5;
        dy[4] = (qw * u[0] + qy * u[2] - qz * u[1]) * 0.5;
        dy[5] = (qw * u[1] + qz * u[0] - qx * u[2]) * 0.5;
        dy[6] = (qw * u[2] + qx * u[1] - qy * u[0]) * 0.5;
        dy[7..10].copy_from_slice(vd);
        dy[10..13].copy_from_slice(ud);
    }
}

/// An error unless every rate in `dy` is finite.
#[inline(always)]
fn finite<T: Real>(s: f64, dy: &[T]) -> Result<()> {
    if !all_finite(dy) {
        return Err(Error::Integration {
            s,
            reason: "non-finite derivative".into(),
        });
    }
    Ok(())
}

/// `true` if every value in `x` is finite: `sum x * 0` is NaN exactly when
/// some entry is not finite, summed in four independent chains (no branch
/// per entry, no dependency chain as long as the state).
#[inline(always)]
pub(crate) fn all_finite<T: Real>(x: &[T]) -> bool {
    let mut acc = [0.0f64; 4];
    let chunks = x.chunks_exact(4);
    let rest = chunks.remainder();
    for c in chunks {
        for k in 0..4 {
            acc[k] += c[k].re() * 0.0;
        }
    }
    for (a, r) in acc.iter_mut().zip(rest) {
        *a += r.re() * 0.0;
    }
    (acc[0] + acc[1] + acc[2] + acc[3]).is_finite()
}

/// `r'` and `r''` of a curved routing (body frame).
pub(crate) type Bend = (V3<f64>, V3<f64>);

/// `|r|^2`, summed in the order `r0 r0 + r1 r1 + r2 r2`.
#[inline(always)]
fn norm2(r: &V3<f64>) -> f64 {
    r[0] * r[0] + r[1] * r[1] + r[2] * r[2]
}

/// The error of a singular system (25).
pub(crate) fn singular(s: f64) -> Error {
    Error::Integration {
        s,
        reason: "singular stiffness system (25): actuator compression exceeds the body's stiffness"
            .into(),
    }
}

/// Adds a string's terms to the eq-25 blocks `m` (upper triangles of `M11`
/// and `M22`, `M12` whole): `M11 += A`, `M12 += -A r^`, `M22 += -r^ A r^`
/// with `A = -tau pb^2 / |pb|^3 = c (I - t t^T)`, `c = tau / |pb|` (eq 20:
/// `tau t_a' = A R^T p_a''`); returns `c t`. With `r^ x = r x x`,
/// `w = t x r` and `r^ r^ = r r^T - |r|^2 I` (`rr = |r|^2`):
/// `A r^ = c (r^ - t w^T)`, `r^ A r^ = c (r r^T - |r|^2 I + w w^T)`. Also
/// the Jacobian of an anchor's string loads (`rod::anchors`).
#[inline(always)]
pub(crate) fn add_string<T: Real>(
    m: &mut Blocks<T>,
    c: T,
    t: &V3<T>,
    r: &V3<f64>,
    rr: f64,
) -> V3<T> {
    let w = cross_c(t, r);
    let ct: V3<T> = v3(|k| t[k] * c);
    let cr: V3<T> = v3(|k| c * r[k]);
    let cr2 = c * rr;
    let cw: V3<T> = v3(|k| w[k] * c);
    for p in 0..3 {
        for q in p..3 {
            m[0][p][q] -= ct[p] * t[q]; // (26): M11 += c I - c t t^T
            m[2][p][q] -= cr[p] * r[q] + cw[p] * w[q]; // (29): M22 += c |r|^2 I - c r r^T - c w w^T
        }
        m[0][p][p] += c;
        m[2][p][p] += cr2;
        for q in 0..3 {
            m[1][p][q] += ct[p] * w[q]; // (27): M12 += -c r^ + c t w^T; (28) is its transpose
        }
    }
    m[1][0][1] += cr[2];
    m[1][0][2] -= cr[1];
    m[1][1][0] -= cr[2];
    m[1][1][2] += cr[0];
    m[1][2][0] += cr[1];
    m[1][2][1] -= cr[0];
    ct
}

/// The actuator-free part of (25) at one state ([`RodRhs::frame`]).
#[derive(Clone, Copy)]
pub(crate) struct Frame<T> {
    /// `R` (body to world).
    pub(crate) rm: [[T; 3]; 3],
    /// Strains `nu`, `omega`.
    pub(crate) v: V3<T>,
    pub(crate) u: V3<T>,
    /// `[e; f]` of (25) without the actuators' terms (30)-(31).
    pub(crate) e: V3<T>,
    pub(crate) f: V3<T>,
}

/// One string at one state ([`RodRhs::string_at`]).
#[derive(Clone, Copy)]
pub(crate) struct StringAt<T> {
    /// Offset `r_i` \[m\], body frame.
    pub(crate) r: V3<f64>,
    /// `|r_i|^2` \[m^2\].
    pub(crate) rr: f64,
    /// `c = tau / |p_b|`, with `A_i = c (I - t t^T)`.
    pub(crate) c: T,
    /// Unit tangent `t = p_b / |p_b|` (body frame).
    pub(crate) t: V3<T>,
    /// `g_i = omega^(nu + omega^ r + 2 r') + r''`.
    pub(crate) g: V3<T>,
    /// Elongation rate `|p_b| - L_i` (24).
    pub(crate) rate: T,
    /// `|p_b|`.
    pub(crate) nrm: T,
    /// `p_b + r'`.
    pub(crate) pbrp: V3<T>,
}

#[cfg(test)]
#[path = "ode_reference.rs"]
mod reference;
