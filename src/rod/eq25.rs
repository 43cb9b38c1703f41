//! The block factorisation of the symmetric 6x6 eq-25 system, shared by
//! the IVP, the dual-number reference tangents and the tangent lanes.

use super::dual::{v3, Blocks, V3};

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

/// The block factorisation of the symmetric eq-25 matrix
/// `[[M11, M12], [M12^T, M22]]`: `M11^-1`, `Y = M11^-1 M12` and the inverse
/// of the Schur complement `S = M22 - M12^T Y`. Factored once per stage and
/// applied to the state's right-hand side and to every tangent direction's.
pub(crate) struct Eq25 {
    pub(crate) m11_inv: [[f64; 3]; 3],
    pub(crate) m12: [[f64; 3]; 3],
    pub(crate) y12: [[f64; 3]; 3],
    pub(crate) s_inv: [[f64; 3]; 3],
}

impl Eq25 {
    /// Factor the blocks `[M11, M12, M22]` (symmetric ones stored whole); `None` if singular.
    #[inline(always)]
    pub(crate) fn factor(m: &Blocks<f64>) -> Option<Self> {
        let (m11, m12, m22) = (&m[0], m[1], &m[2]);
        let m11_inv = inv_sym3_upper(m11)?;
        let mut y12 = [[0.0; 3]; 3];
        for p in 0..3 {
            for q in 0..3 {
                y12[p][q] = m11_inv[p][0] * m12[0][q]
                    + m11_inv[p][1] * m12[1][q]
                    + m11_inv[p][2] * m12[2][q];
            }
        }
        let mut sc = [[0.0; 3]; 3];
        for p in 0..3 {
            for q in p..3 {
                sc[p][q] = m22[p][q]
                    - (m12[0][p] * y12[0][q] + m12[1][p] * y12[1][q] + m12[2][p] * y12[2][q]);
            }
        }
        let s_inv = inv_sym3_upper(&sc)?;
        Some(Eq25 {
            m11_inv,
            m12,
            y12,
            s_inv,
        })
    }

    /// `[v'; u']` for the right-hand side `[e; f]`: `a = M11^-1 e`,
    /// `u' = S^-1 (f - M12^T a)`, `v' = a - Y u'`.
    #[inline(always)]
    pub(crate) fn solve(&self, e: &V3<f64>, f: &V3<f64>) -> (V3<f64>, V3<f64>) {
        let (mi, m12, y, si) = (&self.m11_inv, &self.m12, &self.y12, &self.s_inv);
        let a: V3<f64> = v3(|p| mi[p][0] * e[0] + mi[p][1] * e[1] + mi[p][2] * e[2]);
        let g: V3<f64> = v3(|p| f[p] - (m12[0][p] * a[0] + m12[1][p] * a[1] + m12[2][p] * a[2]));
        let ud: V3<f64> = v3(|p| si[p][0] * g[0] + si[p][1] * g[1] + si[p][2] * g[2]);
        let vd: V3<f64> = v3(|p| a[p] - (y[p][0] * ud[0] + y[p][1] * ud[1] + y[p][2] * ud[2]));
        (vd, ud)
    }

    /// [`Eq25::solve`] for `N` right-hand sides at once (`e[p][k]`: component `p`, direction `k`).
    #[inline(always)]
    pub(crate) fn solve_n<const N: usize>(
        &self,
        e: &[[f64; N]; 3],
        f: &[[f64; N]; 3],
    ) -> ([[f64; N]; 3], [[f64; N]; 3]) {
        let (mi, m12, y, si) = (&self.m11_inv, &self.m12, &self.y12, &self.s_inv);
        let mut a = [[0.0; N]; 3];
        let mut g = *f;
        let mut ud = [[0.0; N]; 3];
        for p in 0..3 {
            for k in 0..N {
                a[p][k] = mi[p][0] * e[0][k] + mi[p][1] * e[1][k] + mi[p][2] * e[2][k];
            }
        }
        for p in 0..3 {
            for k in 0..N {
                g[p][k] -= m12[0][p] * a[0][k] + m12[1][p] * a[1][k] + m12[2][p] * a[2][k];
            }
        }
        for p in 0..3 {
            for k in 0..N {
                ud[p][k] = si[p][0] * g[0][k] + si[p][1] * g[1][k] + si[p][2] * g[2][k];
            }
        }
        for p in 0..3 {
            for k in 0..N {
                a[p][k] -= y[p][0] * ud[0][k] + y[p][1] * ud[1][k] + y[p][2] * ud[2][k];
            }
        }
        (a, ud)
    }
}
