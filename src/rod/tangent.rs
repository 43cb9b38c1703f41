//! Tangents (forward sensitivities) of the IVP: the variational equations
//! integrated with the state on the same RK4 grid.
//!
//! The right-hand side (eqs 22-31), the RK4 stages, the quaternion
//! renormalisation, the anchor jumps and the tip balance (32)-(33) are run in
//! [`Dual`] arithmetic, so the tangents are the exact derivatives of the
//! *discrete* map (to rounding): `d y(s_k) / d seed` at every grid node.
//! Directions are seeded on the initial strains `nu(0)`, `omega(0)` and on
//! the actuator tensions; the force laws' derivatives are applied by the
//! caller (the shooting residual, J and C). All directions share one
//! evaluation of the real part (the eq-25 block factorisation included).
//!
//! The generic right-hand side here is the plain twin of the hand-tuned
//! `f64` fast path in `ode.rs`; `f64` instances of both agree to rounding
//! (tested).

use nalgebra::{DMatrix, Matrix6, Vector3, Vector6};

use super::dual::{Dual, Real};
use super::ode::RodRhs;
use super::{IvpResult, IvpSpec, RodState, BASE_STATES};
use crate::error::{Error, Result};

type V3<T> = [T; 3];

#[inline(always)]
fn cross<T: Real>(a: &V3<T>, b: &V3<T>) -> V3<T> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a x b` for a constant `b`.
#[inline(always)]
fn cross_c<T: Real>(a: &V3<T>, b: &Vector3<f64>) -> V3<T> {
    [
        a[1] * b.z - a[2] * b.y,
        a[2] * b.x - a[0] * b.z,
        a[0] * b.y - a[1] * b.x,
    ]
}

/// `a x b` for a constant `a`.
#[inline(always)]
fn c_cross<T: Real>(a: &Vector3<f64>, b: &V3<T>) -> V3<T> {
    [
        b[2] * a.y - b[1] * a.z,
        b[0] * a.z - b[2] * a.x,
        b[1] * a.x - b[0] * a.y,
    ]
}

#[inline(always)]
fn dot<T: Real>(a: &V3<T>, b: &V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Rotation matrix of a unit quaternion `[w, x, y, z]` (as `rod::rot`).
#[inline(always)]
fn rot_t<T: Real>(q: &[T; 4]) -> [[T; 3]; 3] {
    let (w, x, y, z) = (q[0], q[1], q[2], q[3]);
    let one = T::cst(1.0);
    [
        [
            one - (y * y + z * z) * 2.0,
            (x * y - w * z) * 2.0,
            (x * z + w * y) * 2.0,
        ],
        [
            (x * y + w * z) * 2.0,
            one - (x * x + z * z) * 2.0,
            (y * z - w * x) * 2.0,
        ],
        [
            (x * z - w * y) * 2.0,
            (y * z + w * x) * 2.0,
            one - (x * x + y * y) * 2.0,
        ],
    ]
}

/// `R^T a` for a constant `a`.
#[inline(always)]
fn rt_mul<T: Real>(r: &[[T; 3]; 3], a: &Vector3<f64>) -> V3<T> {
    std::array::from_fn(|k| r[0][k] * a.x + r[1][k] * a.y + r[2][k] * a.z)
}

/// Inverse of a symmetric 3x3 matrix (upper triangle read), `None` if singular.
#[inline(always)]
fn inv_sym3<T: Real>(m: &[[T; 3]; 3]) -> Option<[[T; 3]; 3]> {
    let (a, b, c) = (m[0][0], m[0][1], m[0][2]);
    let (d, e) = (m[1][1], m[1][2]);
    let f = m[2][2];
    let c00 = d * f - e * e;
    let c01 = c * e - b * f;
    let c02 = b * e - c * d;
    let det = a * c00 + b * c01 + c * c02;
    if !(det.re().is_finite() && det.re() != 0.0) {
        return None;
    }
    let c11 = (a * f - c * c) / det;
    let c12 = (b * c - a * e) / det;
    let c22 = (a * d - b * b) / det;
    let (c00, c01, c02) = (c00 / det, c01 / det, c02 / det);
    Some([[c00, c01, c02], [c01, c11, c12], [c02, c12, c22]])
}

impl RodRhs<'_> {
    /// `(r, r', r'', L_i)` of actuator `i` at `s` (constants of the routing).
    #[inline(always)]
    fn routing_at(&self, i: usize, s: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>, f64) {
        match self.acts[i].straight {
            Some((r, _, l)) => (r, Vector3::zeros(), Vector3::zeros(), l),
            None => {
                let (r, rp, rpp) = self.robot.actuators[i].routing.eval(s);
                (r, rp, rpp, self.ref_rate(i, s))
            }
        }
    }

    /// `dy/ds` (eqs 22-31) in any [`Real`] arithmetic, with tensions `tau`:
    /// the plain twin of [`RodRhs::deriv`].
    pub(crate) fn deriv_generic<T: Real>(
        &self,
        s: f64,
        y: &[T],
        tau: &[T],
        active: &[usize],
        dy: &mut [T],
    ) -> Result<()> {
        let body = &self.robot.body;
        let zero = T::cst(0.0);
        let rm = rot_t(&[y[3], y[4], y[5], y[6]]);
        let v = [y[7], y[8], y[9]];
        let u = [y[10], y[11], y[12]];
        let nse: V3<T> = std::array::from_fn(|k| (v[k] - body.nu_star[k]) * self.kse[k]);
        let nbt: V3<T> = std::array::from_fn(|k| (u[k] - body.omega_star[k]) * self.kbt[k]);
        // eq (25) right-hand side: [e; f]
        let (ucn, rtfe) = (cross(&u, &nse), rt_mul(&rm, &self.fe));
        let mut e: V3<T> = std::array::from_fn(|k| -ucn[k] - rtfe[k]);
        let (ucb, vcn) = (cross(&u, &nbt), cross(&v, &nse));
        let mut f: V3<T> = std::array::from_fn(|k| -ucb[k] - vcn[k]);
        if self.has_le {
            let rtle = rt_mul(&rm, &self.le);
            for k in 0..3 {
                f[k] -= rtle[k];
            }
        }
        for d in dy[BASE_STATES..].iter_mut() {
            *d = zero;
        }
        let (vd, ud): (V3<T>, V3<T>) = if active.is_empty() {
            (
                std::array::from_fn(|k| e[k] * self.kse_inv[k]),
                std::array::from_fn(|k| f[k] * self.kbt_inv[k]),
            )
        } else {
            let mut m11 = [[zero; 3]; 3];
            let mut m12 = [[zero; 3]; 3];
            let mut m22 = [[zero; 3]; 3];
            for k in 0..3 {
                m11[k][k] = T::cst(self.kse[k]);
                m22[k][k] = T::cst(self.kbt[k]);
            }
            for &i in active {
                let (r, rp, rpp, lref) = self.routing_at(i, s);
                let ucr = cross_c(&u, &r);
                let pb: V3<T> = std::array::from_fn(|k| v[k] + ucr[k] + rp[k]); // eq (19), body frame
                let nrm = dot(&pb, &pb).sqrt();
                if !(nrm.re() > 1e-12) {
                    return Err(Error::Integration {
                        s,
                        reason: format!("actuator {i} has zero length rate"),
                    });
                }
                // A_i = c (I - t t^T), c = tau / |pb| (eq 20)
                let c = tau[i] / nrm;
                let t: V3<T> = std::array::from_fn(|k| pb[k] / nrm);
                let w = cross_c(&t, &r);
                let ct: V3<T> = std::array::from_fn(|k| t[k] * c);
                let pbrp: V3<T> = std::array::from_fn(|k| pb[k] + rp[k]);
                let upr = cross(&u, &pbrp);
                let g: V3<T> = std::array::from_fn(|k| upr[k] + rpp[k]);
                let tg = dot(&t, &g);
                let ag: V3<T> = std::array::from_fn(|k| g[k] * c - ct[k] * tg); // A_i g_i
                let rag = c_cross(&r, &ag);
                let cr: V3<T> = std::array::from_fn(|k| c * r[k]);
                let cr2 = c * r.norm_squared();
                let cw: V3<T> = std::array::from_fn(|k| w[k] * c);
                for p in 0..3 {
                    for q in p..3 {
                        // (26): M11 += c I - c t t^T; (29): M22 += c |r|^2 I - c r r^T - c w w^T
                        m11[p][q] -= ct[p] * t[q];
                        m22[p][q] -= cr[p] * r[q] + cw[p] * w[q];
                    }
                    m11[p][p] += c;
                    m22[p][p] += cr2;
                    // (27): M12 += -c r^ + c t w^T
                    for q in 0..3 {
                        m12[p][q] += ct[p] * w[q];
                    }
                    e[p] -= ag[p]; // (30)
                    f[p] -= rag[p]; // (31)
                }
                m12[0][1] += cr[2];
                m12[0][2] -= cr[1];
                m12[1][0] -= cr[2];
                m12[1][2] += cr[0];
                m12[2][0] += cr[1];
                m12[2][1] -= cr[0];
                dy[BASE_STATES + i] = nrm - lref; // (24)
            }
            for (p, q) in [(1, 0), (2, 0), (2, 1)] {
                m11[p][q] = m11[q][p];
                m22[p][q] = m22[q][p];
            }
            let singular = || {
                Error::Integration {
                s,
                reason: "singular stiffness system (25): actuator compression exceeds the body's stiffness".into(),
            }
            };
            let m11_inv = inv_sym3(&m11).ok_or_else(singular)?;
            // Y = M11^-1 M12, a = M11^-1 e; S = M22 - M12^T Y, g = f - M12^T a
            let y12: [[T; 3]; 3] = std::array::from_fn(|p| {
                std::array::from_fn(|q| {
                    m11_inv[p][0] * m12[0][q]
                        + m11_inv[p][1] * m12[1][q]
                        + m11_inv[p][2] * m12[2][q]
                })
            });
            let ae: V3<T> = std::array::from_fn(|p| {
                m11_inv[p][0] * e[0] + m11_inv[p][1] * e[1] + m11_inv[p][2] * e[2]
            });
            let mut sc = [[zero; 3]; 3];
            for p in 0..3 {
                for q in p..3 {
                    sc[p][q] = m22[p][q]
                        - (m12[0][p] * y12[0][q] + m12[1][p] * y12[1][q] + m12[2][p] * y12[2][q]);
                    sc[q][p] = sc[p][q];
                }
            }
            let g: V3<T> = std::array::from_fn(|p| {
                f[p] - (m12[0][p] * ae[0] + m12[1][p] * ae[1] + m12[2][p] * ae[2])
            });
            let s_inv = inv_sym3(&sc).ok_or_else(singular)?;
            let ud: V3<T> = std::array::from_fn(|p| {
                s_inv[p][0] * g[0] + s_inv[p][1] * g[1] + s_inv[p][2] * g[2]
            });
            let vd: V3<T> = std::array::from_fn(|p| {
                ae[p] - (y12[p][0] * ud[0] + y12[p][1] * ud[1] + y12[p][2] * ud[2])
            });
            (vd, ud)
        };
        for k in 0..3 {
            dy[k] = rm[k][0] * v[0] + rm[k][1] * v[1] + rm[k][2] * v[2]; // (22)
        }
        // (23) as q' = q (0, u) / 2
        let (w, x, yq, z) = (y[3], y[4], y[5], y[6]);
        dy[3] = -(x * u[0] + yq * u[1] + z * u[2]) * 0.5;
        dy[4] = (w * u[0] + yq * u[2] - z * u[1]) * 0.5;
        dy[5] = (w * u[1] + z * u[0] - x * u[2]) * 0.5;
        dy[6] = (w * u[2] + x * u[1] - yq * u[0]) * 0.5;
        dy[7..10].copy_from_slice(&vd);
        dy[10..13].copy_from_slice(&ud);
        if !dy.iter().all(|d| d.is_finite()) {
            return Err(Error::Integration {
                s,
                reason: "non-finite derivative".into(),
            });
        }
        Ok(())
    }

    /// Residual of the anchor jump at `s` (see `anchor_loads`) for post-jump
    /// strains `w = (v, u)`, pre-jump strains `w0` and tensions `tau`, with
    /// every string anchored at or passing `s` (zero tensions included, so
    /// that the derivative with respect to a tension is right).
    fn anchor_residual<T: Real>(
        &self,
        s: f64,
        terms: &[(usize, f64, f64)],
        w: &[T; 6],
        w0: &[T; 6],
        tau: &[T],
    ) -> [T; 6] {
        let len = self.robot.body.length;
        let zero = T::cst(0.0);
        let (mut f, mut m) = ([zero; 3], [zero; 3]);
        let mut add = |i: usize, weight: f64, st: &[T; 6]| {
            let (r, rp, _) = self.robot.actuators[i].routing.eval(s);
            let (v, u) = ([st[0], st[1], st[2]], [st[3], st[4], st[5]]);
            let ucr = cross_c(&u, &r);
            let pb: V3<T> = std::array::from_fn(|k| v[k] + ucr[k] + rp[k]);
            let nrm = dot(&pb, &pb).sqrt();
            let p: V3<T> = std::array::from_fn(|k| pb[k] / nrm * tau[i] * weight);
            let rp_ = c_cross(&r, &p);
            for k in 0..3 {
                f[k] += p[k];
                m[k] += rp_[k];
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

    /// The anchor jump at `s` on a dual state: the real part by the `f64`
    /// Newton solve of `anchor_loads`, the tangents by the implicit function
    /// theorem, `dw = -G_w^-1 (G_w0 dw0 + G_tau dtau)`, with `G_w` exact
    /// (6-direction duals).
    fn anchor_tangent<const N: usize>(
        &self,
        s: f64,
        y: &mut [Dual<N>],
        tau: &[Dual<N>],
    ) -> Result<()> {
        let tol = 1e-12 * self.robot.body.length;
        let mut terms: Vec<(usize, f64, f64)> = Vec::new();
        for (i, act) in self.robot.actuators.iter().enumerate() {
            let ends = (act.s_end - s).abs() <= tol;
            let starts = (act.s_start - s).abs() <= tol;
            let passes = act.s_start < s - tol && act.s_end > s + tol;
            let (b, a) = (
                if ends || passes { 1.0 } else { 0.0 },
                if starts || passes { 1.0 } else { 0.0 },
            );
            if b != 0.0 || a != 0.0 {
                terms.push((i, b, a));
            }
        }
        let mut yr: Vec<f64> = y.iter().map(|d| d.re).collect();
        self.anchor_loads(s, &mut yr)?;
        if terms.is_empty() {
            return Ok(());
        }
        let ws: [f64; 6] = std::array::from_fn(|k| yr[7 + k]);
        // G_w by 6 dual directions
        let w6: [Dual<6>; 6] = std::array::from_fn(|k| {
            let mut e = [0.0; 6];
            e[k] = 1.0;
            Dual::new(ws[k], e)
        });
        let w06: [Dual<6>; 6] = std::array::from_fn(|k| Dual::cst(y[7 + k].re));
        let tau6: Vec<Dual<6>> = tau.iter().map(|t| Dual::cst(t.re)).collect();
        let g6 = self.anchor_residual(s, &terms, &w6, &w06, &tau6);
        let gw = Matrix6::from_fn(|r, c| g6[r].eps[c]);
        let lu = gw.lu();
        // G_w0 dw0 + G_tau dtau at fixed w
        let wn: [Dual<N>; 6] = std::array::from_fn(|k| Dual::cst(ws[k]));
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

/// Seed directions of a tangent IVP: each column is one direction, giving
/// the derivative of the initial strains and of the tensions along it.
#[derive(Debug, Clone)]
pub struct TangentSeeds {
    /// `d nu(0)` \[-\], `3 x k`.
    pub nu0: DMatrix<f64>,
    /// `d omega(0)` \[1/m\], `3 x k`.
    pub omega0: DMatrix<f64>,
    /// `d tau` \[N\], `n_actuators x k`.
    pub tensions: DMatrix<f64>,
}

impl TangentSeeds {
    /// `k` zero directions for a robot with `na` actuators.
    pub fn zeros(na: usize, k: usize) -> Self {
        TangentSeeds {
            nu0: DMatrix::zeros(3, k),
            omega0: DMatrix::zeros(3, k),
            tensions: DMatrix::zeros(na, k),
        }
    }
    /// Number of directions.
    pub fn directions(&self) -> usize {
        self.nu0.ncols()
    }
}

/// One recorded grid node of a tangent IVP.
#[derive(Debug, Clone)]
pub struct TangentNode {
    /// Arc length \[m\].
    pub s: f64,
    /// State `y(s)` (`p, q, nu, omega, delta`; see [`crate::rod::BASE_STATES`]).
    pub state: Vec<f64>,
    /// `d y(s) / d seed`, `n_states x k` (after the jump at an anchor node).
    pub tangent: DMatrix<f64>,
}

/// A tangent IVP: the IVP (its real part) and its derivatives along the seeds.
#[derive(Debug, Clone)]
pub struct TangentIvp {
    /// The IVP itself (nodes recorded if asked for).
    pub ivp: IvpResult,
    /// `d y(L) / d seed`, `n_states x k`.
    pub tip: DMatrix<f64>,
    /// `d delta_i(s_end) / d seed` (distal elongations), `n_actuators x k`.
    pub elongation: DMatrix<f64>,
    /// `d r_F / d seed` (tip force balance (32), body frame) \[N\], `3 x k`.
    pub tip_force_residual: DMatrix<f64>,
    /// `d r_M / d seed` (tip moment balance (33)) \[N m\], `3 x k`.
    pub tip_moment_residual: DMatrix<f64>,
    /// Every grid node with its tangents, if `record` (anchor nodes after their jump).
    pub nodes: Vec<TangentNode>,
}

/// Largest number of directions integrated in one pass (more are split into passes).
const MAX_PASS: usize = 16;

/// Integrate the IVP (eqs 22-31, as [`crate::rod::integrate`]) together with
/// its tangents along `seeds`, on the same RK4 grid, through the anchor
/// jumps and the tip balance. The tangents are the exact derivatives of the
/// discrete map. With `record`, every grid node's state and tangent matrix
/// are returned (for stability analyses).
pub fn integrate_tangent(
    spec: &IvpSpec<'_>,
    v0: &Vector3<f64>,
    u0: &Vector3<f64>,
    seeds: &TangentSeeds,
    record: bool,
) -> Result<TangentIvp> {
    let k = seeds.directions();
    let na = spec.robot.actuators.len();
    if seeds.nu0.nrows() != 3
        || seeds.omega0.nrows() != 3
        || seeds.tensions.nrows() != na
        || seeds.omega0.ncols() != k
        || seeds.tensions.ncols() != k
    {
        return Err(Error::input(
            "seeds",
            format!("expected 3, 3 and {na} rows and equal column counts"),
        ));
    }
    let mut out: Option<TangentIvp> = None;
    let mut c0 = 0;
    loop {
        let w = (k - c0).min(MAX_PASS);
        let part = match w {
            0..=4 => pass::<4>(spec, v0, u0, seeds, c0, w, record)?,
            5..=8 => pass::<8>(spec, v0, u0, seeds, c0, w, record)?,
            9..=12 => pass::<12>(spec, v0, u0, seeds, c0, w, record)?,
            _ => pass::<MAX_PASS>(spec, v0, u0, seeds, c0, w, record)?,
        };
        out = Some(match out {
            None => part,
            Some(mut o) => {
                let cat = |a: &DMatrix<f64>, b: &DMatrix<f64>| {
                    let mut m = a.clone().resize_horizontally(a.ncols() + b.ncols(), 0.0);
                    m.columns_mut(a.ncols(), b.ncols()).copy_from(b);
                    m
                };
                o.tip = cat(&o.tip, &part.tip);
                o.elongation = cat(&o.elongation, &part.elongation);
                o.tip_force_residual = cat(&o.tip_force_residual, &part.tip_force_residual);
                o.tip_moment_residual = cat(&o.tip_moment_residual, &part.tip_moment_residual);
                for (a, b) in o.nodes.iter_mut().zip(&part.nodes) {
                    a.tangent = cat(&a.tangent, &b.tangent);
                }
                o
            }
        });
        c0 += w;
        if c0 >= k {
            break;
        }
    }
    Ok(out.expect("at least one pass"))
}

/// One pass of [`integrate_tangent`] over directions `c0 .. c0 + w` (`w <= N`).
fn pass<const N: usize>(
    spec: &IvpSpec<'_>,
    v0: &Vector3<f64>,
    u0: &Vector3<f64>,
    seeds: &TangentSeeds,
    c0: usize,
    w: usize,
    record: bool,
) -> Result<TangentIvp> {
    type D<const N: usize> = Dual<N>;
    let robot = spec.robot;
    let body = &robot.body;
    let fz = RodRhs::new(robot, spec.tensions);
    let na = robot.actuators.len();
    let n = robot.n_states();
    let len = body.length;
    let steps = spec.steps.max(1);
    let seed = |m: &DMatrix<f64>, row: usize| -> [f64; N] {
        std::array::from_fn(|d| if d < w { m[(row, c0 + d)] } else { 0.0 })
    };
    let tau: Vec<D<N>> = (0..na)
        .map(|i| Dual::new(spec.tensions[i], seed(&seeds.tensions, i)))
        .collect();
    let zero = D::<N>::cst(0.0);
    let mut y = vec![zero; n];
    y[3] = D::cst(1.0);
    for k in 0..3 {
        y[7 + k] = Dual::new(v0[k], seed(&seeds.nu0, k));
        y[10 + k] = Dual::new(u0[k], seed(&seeds.omega0, k));
    }
    let (mut k1, mut k2, mut k3, mut k4, mut yt) = (
        vec![zero; n],
        vec![zero; n],
        vec![zero; n],
        vec![zero; n],
        vec![zero; n],
    );
    let to_node = |s: f64, y: &[D<N>]| TangentNode {
        s,
        state: y.iter().map(|d| d.re).collect(),
        tangent: DMatrix::from_fn(n, w, |r, c| y[r].eps[c]),
    };
    let bps = robot.breakpoints();
    let tol = 1e-12 * len;
    let mut nodes = Vec::new();
    let mut elongation = vec![zero; na];
    let mut active: Vec<usize> = Vec::with_capacity(na);
    for win in bps.windows(2) {
        let (a, b) = (win[0], win[1]);
        if a > 0.0 {
            let mut any = false;
            for (i, act) in robot.actuators.iter().enumerate() {
                if (act.s_end - a).abs() <= tol {
                    elongation[i] = y[BASE_STATES + i];
                    any = true;
                }
                any |= (act.s_start - a).abs() <= tol;
            }
            if any {
                fz.anchor_tangent(a, &mut y, &tau)?;
            }
        }
        if record {
            nodes.push(to_node(a, &y));
        }
        active.clear();
        for (i, act) in robot.actuators.iter().enumerate() {
            if act.s_start <= a + tol && act.s_end >= b - tol {
                active.push(i);
            }
        }
        let m = (((b - a) / len) * steps as f64).round().max(1.0) as usize;
        let h = (b - a) / m as f64;
        let (h2, h6) = (0.5 * h, h / 6.0);
        for kk in 0..m {
            let s = a + kk as f64 * h;
            fz.deriv_generic(s, &y, &tau, &active, &mut k1)?;
            for j in 0..n {
                yt[j] = y[j] + k1[j] * h2;
            }
            fz.deriv_generic(s + h2, &yt, &tau, &active, &mut k2)?;
            for j in 0..n {
                yt[j] = y[j] + k2[j] * h2;
            }
            fz.deriv_generic(s + h2, &yt, &tau, &active, &mut k3)?;
            for j in 0..n {
                yt[j] = y[j] + k3[j] * h;
            }
            fz.deriv_generic(s + h, &yt, &tau, &active, &mut k4)?;
            for j in 0..n {
                y[j] += (k1[j] + (k2[j] + k3[j]) * 2.0 + k4[j]) * h6;
            }
            let qn = (y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]).sqrt();
            for yq in &mut y[3..7] {
                *yq = *yq / qn;
            }
            if record && kk + 1 < m {
                nodes.push(to_node(s + h, &y));
            }
        }
    }
    // tip balance (32)-(33), body frame
    let rm = rot_t(&[y[3], y[4], y[5], y[6]]);
    let v = [y[7], y[8], y[9]];
    let u = [y[10], y[11], y[12]];
    let rtf = rt_mul(&rm, &spec.tip_force);
    let rtm = rt_mul(&rm, &spec.tip_moment);
    let mut rf: V3<D<N>> = std::array::from_fn(|k| (v[k] - body.nu_star[k]) * fz.kse[k] - rtf[k]);
    let mut rmm: V3<D<N>> =
        std::array::from_fn(|k| (u[k] - body.omega_star[k]) * fz.kbt[k] - rtm[k]);
    for (i, act) in robot.actuators.iter().enumerate() {
        if (act.s_end - len).abs() <= tol {
            elongation[i] = y[BASE_STATES + i];
            let (r, rp, _) = act.routing.eval(len);
            let ucr = cross_c(&u, &r);
            let pb: V3<D<N>> = std::array::from_fn(|k| v[k] + ucr[k] + rp[k]);
            let nrm = dot(&pb, &pb).sqrt();
            let p: V3<D<N>> = std::array::from_fn(|k| pb[k] / nrm * tau[i]);
            let rxp = c_cross(&r, &p);
            for k in 0..3 {
                rf[k] += p[k];
                rmm[k] += rxp[k];
            }
        }
    }
    let yr: Vec<f64> = y.iter().map(|d| d.re).collect();
    let tip = RodState::from_slice(&yr);
    if record {
        nodes.push(to_node(len, &y));
    }
    let tan = |v: &[D<N>]| DMatrix::from_fn(v.len(), w, |r, c| v[r].eps[c]);
    let ivp_nodes = if record {
        nodes
            .iter()
            .map(|nd| (nd.s, RodState::from_slice(&nd.state)))
            .collect()
    } else {
        Vec::new()
    };
    Ok(TangentIvp {
        ivp: IvpResult {
            tip,
            elongation: elongation.iter().map(|d| d.re).collect(),
            tip_force_residual: Vector3::new(rf[0].re, rf[1].re, rf[2].re),
            tip_moment_residual: Vector3::new(rmm[0].re, rmm[1].re, rmm[2].re),
            nodes: ivp_nodes,
        },
        tip: tan(&y),
        elongation: tan(&elongation),
        tip_force_residual: tan(&rf),
        tip_moment_residual: tan(&rmm),
        nodes,
    })
}
