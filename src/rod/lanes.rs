//! The tangent lanes: `N` directional derivatives of one scalar, stored
//! apart from its value (structure of arrays), for the tangent pass's
//! hand-linearised right-hand side (`ode_tangent.rs`).
//!
//! A [`super::dual::Dual`] carries its value beside the lanes, so every
//! product of two duals costs two lane products and a sum besides the
//! value's. Here the value is a plain `f64` computed by the IVP's own code,
//! and the lanes of a linear map are formed with the value's coefficients:
//! one lane product per term, eight lanes per AVX-512 instruction.

use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

use super::dual::{Dual, V3};

/// `N` tangent lanes of one scalar, on a 64-byte boundary (eight lanes are
/// one aligned AVX-512 load).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct Lanes<const N: usize>(pub(crate) [f64; N]);

impl<const N: usize> Lanes<N> {
    /// All lanes zero.
    pub(crate) const ZERO: Self = Lanes([0.0; N]);

    /// The lanes of a dual.
    #[inline(always)]
    pub(crate) fn of(d: &Dual<N>) -> Self {
        Lanes(d.eps)
    }
}

/// A lane-wise binary operation building a fresh value (updating `self`
/// would copy the padding of a 64-byte-aligned layout through every sum).
macro_rules! lanewise {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const N: usize> $tr for Lanes<N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: Self) -> Self {
                let mut r = [0.0; N];
                for ((x, a), b) in r.iter_mut().zip(&self.0).zip(&o.0) {
                    *x = a $op b;
                }
                Lanes(r)
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);

impl<const N: usize> Mul<f64> for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: f64) -> Self {
        let mut r = [0.0; N];
        for (x, a) in r.iter_mut().zip(&self.0) {
            *x = a * o;
        }
        Lanes(r)
    }
}
impl<const N: usize> Neg for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        let mut r = [0.0; N];
        for (x, a) in r.iter_mut().zip(&self.0) {
            *x = -a;
        }
        Lanes(r)
    }
}
impl<const N: usize> AddAssign for Lanes<N> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<const N: usize> SubAssign for Lanes<N> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

impl<const N: usize> Lanes<N> {
    /// `self * b + c` with one rounding per lane (`f64::mul_add`): one FMA
    /// instruction per vector where the pass is compiled with FMA
    /// (`tangent.rs`'s `dispatch`).
    #[inline(always)]
    pub(crate) fn fma(self, b: f64, c: Self) -> Self {
        let mut r = [0.0; N];
        for ((x, a), cc) in r.iter_mut().zip(&self.0).zip(&c.0) {
            *x = a.mul_add(b, *cc);
        }
        Lanes(r)
    }
}

/// `sum_m l_m c_m` for lanes `l_m` and values `c_m`: one product, then
/// fused multiply-adds in the order given.
#[inline(always)]
pub(crate) fn lin<const N: usize, const M: usize>(t: [(Lanes<N>, f64); M]) -> Lanes<N> {
    let mut acc = t[0].0 * t[0].1;
    for &(l, c) in &t[1..] {
        acc = l.fma(c, acc);
    }
    acc
}

/// `c - a x b` for a value `a` and lanes `b` and `c`.
#[inline(always)]
pub(crate) fn sub_cross_cl<const N: usize>(
    c: &V3<Lanes<N>>,
    a: &V3<f64>,
    b: &V3<Lanes<N>>,
) -> V3<Lanes<N>> {
    [
        b[1].fma(a[2], b[2].fma(-a[1], c[0])),
        b[2].fma(a[0], b[0].fma(-a[2], c[1])),
        b[0].fma(a[1], b[1].fma(-a[0], c[2])),
    ]
}

/// `a . b` for a value `a` and lanes `b`.
#[inline(always)]
pub(crate) fn dot_cl<const N: usize>(a: &V3<f64>, b: &V3<Lanes<N>>) -> Lanes<N> {
    lin([(b[0], a[0]), (b[1], a[1]), (b[2], a[2])])
}

/// `d(R(q) v) / dq` (3x4; `R` as `rot_t` of `dual.rs`, `v` fixed): with
/// `R = I + 2 Q(q)`, `Q` quadratic in `q = (w, x, y, z)`, each entry is
/// `2 sum_j dQ_kj/dq_m v_j`. The lanes of `R v` along `dq` are then one
/// 4-term combination per row, with no lanes of `R` formed.
#[inline(always)]
pub(crate) fn rot_coeffs(q: &[f64; 4], v: &V3<f64>) -> [[f64; 4]; 3] {
    let [w, x, y, z] = q.map(|c| 2.0 * c);
    let [a, b, c] = *v;
    [
        [
            y * c - z * b,
            y * b + z * c,
            x * b + w * c - 2.0 * y * a,
            x * c - w * b - 2.0 * z * a,
        ],
        [
            z * a - x * c,
            y * a - w * c - 2.0 * x * b,
            x * a + z * c,
            w * a + y * c - 2.0 * z * b,
        ],
        [
            x * b - y * a,
            z * a + w * b - 2.0 * x * c,
            z * b - w * a - 2.0 * y * c,
            x * a + y * b,
        ],
    ]
}

/// `d(R(q)^T a) / dq` (3x4): `Q^T` is `Q` with `w -> -w`, so [`rot_coeffs`]
/// at `(-w, x, y, z)` with its `d/dw` column negated.
#[inline(always)]
pub(crate) fn rot_t_coeffs(q: &[f64; 4], a: &V3<f64>) -> [[f64; 4]; 3] {
    let mut m = rot_coeffs(&[-q[0], q[1], q[2], q[3]], a);
    for row in &mut m {
        row[0] = -row[0];
    }
    m
}

/// `sum_m c_m dq_m` for the coefficient rows of [`rot_coeffs`].
#[inline(always)]
pub(crate) fn rot_apply<const N: usize>(c: &[[f64; 4]; 3], dq: &[Lanes<N>; 4]) -> V3<Lanes<N>> {
    // no closure: one compiled apart would lose the pass's target features
    let mut out = [Lanes::ZERO; 3];
    for k in 0..3 {
        out[k] = lin([
            (dq[0], c[k][0]),
            (dq[1], c[k][1]),
            (dq[2], c[k][2]),
            (dq[3], c[k][3]),
        ]);
    }
    out
}
