//! The right-hand side of the rod's ODE, eqs 22-31, with the actuator
//! tensions frozen for one IVP.

use nalgebra::{Matrix3, Quaternion, Vector3};

use super::{rot, Robot, Routing, BASE_STATES};
use crate::error::{Error, Result};

/// Per-actuator constants of one IVP: a straight actuator's offset, its
/// cross-product matrix and reference length rate do not change along `s`.
pub(crate) struct ActuatorConstants {
    /// `(r, r^, L_i)` for a straight routing; `None` for a helix (evaluated per stage).
    pub(crate) straight: Option<(Vector3<f64>, Matrix3<f64>, f64)>,
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
    pub(crate) has_le: bool,
    pub(crate) acts: Vec<ActuatorConstants>,
}

/// Inverse of a symmetric 3x3 matrix (upper triangle read) by cofactors, `None` if singular.
#[inline(always)]
fn inv_sym3_upper(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let (a, b, c) = (m[0][0], m[0][1], m[0][2]);
    let (d, e) = (m[1][1], m[1][2]);
    let f = m[2][2];
    let c00 = d * f - e * e;
    let c01 = c * e - b * f;
    let c02 = b * e - c * d;
    let det = a * c00 + b * c01 + c * c02;
    if !(det.is_finite() && det != 0.0) {
        return None;
    }
    let id = 1.0 / det;
    let c11 = (a * f - c * c) * id;
    let c12 = (b * c - a * e) * id;
    let c22 = (a * d - b * b) * id;
    let (c00, c01, c02) = (c00 * id, c01 * id, c02 * id);
    Some([[c00, c01, c02], [c01, c11, c12], [c02, c12, c22]])
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
            .map(|a| ActuatorConstants {
                straight: match a.routing {
                    Routing::Straight { x, y } => {
                        let r = Vector3::new(x, y, 0.0);
                        let l = a
                            .length_ratio
                            .unwrap_or_else(|| (body.nu_star + body.omega_star.cross(&r)).norm());
                        Some((r, r.cross_matrix(), l))
                    }
                    Routing::Helix { .. } => None,
                },
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

    /// `dy/ds` (eqs 22-25) with the actuators in `active` (indices).
    ///
    /// The 6x6 system (25) is symmetric, `[[M11, M12], [M12^T, M22]]` with
    /// `M11 = K_nu + sum A_i`, `M12 = -sum A_i r_i^`, `M22 = K_omega - sum r_i^ A_i r_i^`
    /// (`A_i` symmetric, `r^T = -r^`), and is solved by block elimination on
    /// its 3x3 blocks: `M11^-1`, then the Schur complement `S = M22 - M12^T M11^-1 M12`.
    #[inline]
    pub(crate) fn deriv(&self, s: f64, y: &[f64], active: &[usize], dy: &mut [f64]) -> Result<()> {
        let body = &self.robot.body;
        let q = Quaternion::new(y[3], y[4], y[5], y[6]);
        let r_mat = rot(&q);
        let v = Vector3::new(y[7], y[8], y[9]);
        let u = Vector3::new(y[10], y[11], y[12]);
        let nse = self.kse.component_mul(&(v - body.nu_star));
        let nbt = self.kbt.component_mul(&(u - body.omega_star));
        // eq (25) right-hand side: [e; f]
        let rhs_v = -u.cross(&nse) - r_mat.tr_mul(&self.fe);
        let mut rhs_u = -u.cross(&nbt) - v.cross(&nse);
        if self.has_le {
            rhs_u -= r_mat.tr_mul(&self.le);
        }
        for k in 0..self.robot.actuators.len() {
            dy[BASE_STATES + k] = 0.0;
        }
        let (vd, ud) = if active.is_empty() {
            (
                rhs_v.component_mul(&self.kse_inv),
                rhs_u.component_mul(&self.kbt_inv),
            )
        } else {
            // Blocks in plain arrays (nalgebra's generic 3x3 arithmetic costs
            // several times the flops here). Symmetric blocks are stored whole.
            let mut m11 = [[0.0; 3]; 3];
            let mut m12 = [[0.0; 3]; 3];
            let mut m22 = [[0.0; 3]; 3];
            for k in 0..3 {
                m11[k][k] = self.kse[k];
                m22[k][k] = self.kbt[k];
            }
            let (mut e, mut f) = ([rhs_v.x, rhs_v.y, rhs_v.z], [rhs_u.x, rhs_u.y, rhs_u.z]);
            for &i in active {
                let (r, rp, rpp, lref) = match self.acts[i].straight {
                    Some((r, _, l)) => (r, Vector3::zeros(), Vector3::zeros(), l),
                    None => {
                        let (r, rp, rpp) = self.robot.actuators[i].routing.eval(s);
                        (r, rp, rpp, self.ref_rate(i, s))
                    }
                };
                let pb = v + u.cross(&r) + rp; // eq (19), body frame
                let nrm = pb.norm();
                if !(nrm > 1e-12) {
                    return Err(Error::Integration {
                        s,
                        reason: format!("actuator {i} has zero length rate"),
                    });
                }
                let tau = self.tensions[i];
                // A_i = -tau pb^2 / |pb|^3 = c (I - t t^T), c = tau / |pb| (eq 20:
                // tau t_a' = A_i R^T p_a''). With r^ x = r x x, w = t x r and
                // r^ r^ = r r^T - |r|^2 I:
                //   A_i r^ = c (r^ - t w^T),  r^ A_i r^ = c (r r^T - |r|^2 I + w w^T).
                let c = tau / nrm;
                let t = pb / nrm;
                let w = t.cross(&r);
                let ct = t * c;
                let g_i = u.cross(&(pb + rp)) + rpp; // omega^(nu + omega^ r + 2 r') + r''
                let ag = g_i * c - ct * t.dot(&g_i); // A_i g_i
                let rag = r.cross(&ag);
                let cr2 = c * r.norm_squared();
                let cw = w * c;
                // (26): M11 += c I - c t t^T (symmetric: upper triangle, mirrored below)
                m11[0][0] += c - ct.x * t.x;
                m11[0][1] -= ct.x * t.y;
                m11[0][2] -= ct.x * t.z;
                m11[1][1] += c - ct.y * t.y;
                m11[1][2] -= ct.y * t.z;
                m11[2][2] += c - ct.z * t.z;
                // (27): M12 += -c r^ + c t w^T; (28) is its transpose
                let cr = r * c;
                for p in 0..3 {
                    m12[p][0] += ct[p] * w.x;
                    m12[p][1] += ct[p] * w.y;
                    m12[p][2] += ct[p] * w.z;
                }
                m12[0][1] += cr.z;
                m12[0][2] -= cr.y;
                m12[1][0] -= cr.z;
                m12[1][2] += cr.x;
                m12[2][0] += cr.y;
                m12[2][1] -= cr.x;
                // (29): M22 += c |r|^2 I - c r r^T - c w w^T
                m22[0][0] += cr2 - cr.x * r.x - cw.x * w.x;
                m22[0][1] -= cr.x * r.y + cw.x * w.y;
                m22[0][2] -= cr.x * r.z + cw.x * w.z;
                m22[1][1] += cr2 - cr.y * r.y - cw.y * w.y;
                m22[1][2] -= cr.y * r.z + cw.y * w.z;
                m22[2][2] += cr2 - cr.z * r.z - cw.z * w.z;
                for p in 0..3 {
                    e[p] -= ag[p]; // (30)
                    f[p] -= rag[p]; // (31)
                }
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
            let m11_inv = inv_sym3_upper(&m11).ok_or_else(singular)?;
            // Y = M11^-1 M12, a = M11^-1 e
            let mut y12 = [[0.0; 3]; 3];
            let mut ae = [0.0; 3];
            for p in 0..3 {
                for q in 0..3 {
                    y12[p][q] = m11_inv[p][0] * m12[0][q]
                        + m11_inv[p][1] * m12[1][q]
                        + m11_inv[p][2] * m12[2][q];
                }
                ae[p] = m11_inv[p][0] * e[0] + m11_inv[p][1] * e[1] + m11_inv[p][2] * e[2];
            }
            // S = M22 - M12^T Y (symmetric), g = f - M12^T a
            let mut sc = [[0.0; 3]; 3];
            let mut g = [0.0; 3];
            for p in 0..3 {
                for q in p..3 {
                    sc[p][q] = m22[p][q]
                        - (m12[0][p] * y12[0][q] + m12[1][p] * y12[1][q] + m12[2][p] * y12[2][q]);
                    sc[q][p] = sc[p][q];
                }
                g[p] = f[p] - (m12[0][p] * ae[0] + m12[1][p] * ae[1] + m12[2][p] * ae[2]);
            }
            let s_inv = inv_sym3_upper(&sc).ok_or_else(singular)?;
            let mut ud = Vector3::zeros();
            for p in 0..3 {
                ud[p] = s_inv[p][0] * g[0] + s_inv[p][1] * g[1] + s_inv[p][2] * g[2];
            }
            let mut vd = Vector3::zeros();
            for p in 0..3 {
                vd[p] = ae[p] - (y12[p][0] * ud[0] + y12[p][1] * ud[1] + y12[p][2] * ud[2]);
            }
            (vd, ud)
        };
        let pd = r_mat * v; // (22)
        dy[0] = pd.x;
        dy[1] = pd.y;
        dy[2] = pd.z;
        // (23) as q' = q (0, u) / 2
        let qd = q * Quaternion::new(0.0, u.x, u.y, u.z) * 0.5;
        dy[3] = qd.w;
        dy[4] = qd.i;
        dy[5] = qd.j;
        dy[6] = qd.k;
        dy[7] = vd.x;
        dy[8] = vd.y;
        dy[9] = vd.z;
        dy[10] = ud.x;
        dy[11] = ud.y;
        dy[12] = ud.z;
        if !dy.iter().fold(0.0, |acc, x| acc + x * 0.0).is_finite() {
            return Err(Error::Integration {
                s,
                reason: "non-finite derivative".into(),
            });
        }
        Ok(())
    }
}
