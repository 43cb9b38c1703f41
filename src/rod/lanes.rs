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

use super::dual::{v3, Dual, V3};

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

/// `a x b` for lanes `a` and a value `b`.
#[inline(always)]
pub(crate) fn cross_lc<const N: usize>(a: &V3<Lanes<N>>, b: &V3<f64>) -> V3<Lanes<N>> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a x b` for a value `a` and lanes `b`.
#[inline(always)]
pub(crate) fn cross_cl<const N: usize>(a: &V3<f64>, b: &V3<Lanes<N>>) -> V3<Lanes<N>> {
    [
        b[2] * a[1] - b[1] * a[2],
        b[0] * a[2] - b[2] * a[0],
        b[1] * a[0] - b[0] * a[1],
    ]
}

/// `a . b` for a value `a` and lanes `b`.
#[inline(always)]
pub(crate) fn dot_cl<const N: usize>(a: &V3<f64>, b: &V3<Lanes<N>>) -> Lanes<N> {
    b[0] * a[0] + b[1] * a[1] + b[2] * a[2]
}

/// `m a` for lanes `m` (3x3) and a value `a`.
#[inline(always)]
pub(crate) fn mat_lc<const N: usize>(m: &[V3<Lanes<N>>; 3], a: &V3<f64>) -> V3<Lanes<N>> {
    v3(|k| m[k][0] * a[0] + m[k][1] * a[1] + m[k][2] * a[2])
}

/// `m^T a` for lanes `m` (3x3) and a value `a`.
#[inline(always)]
pub(crate) fn mat_t_lc<const N: usize>(m: &[V3<Lanes<N>>; 3], a: &V3<f64>) -> V3<Lanes<N>> {
    v3(|k| m[0][k] * a[0] + m[1][k] * a[1] + m[2][k] * a[2])
}

/// `m a` for a value `m` (3x3) and lanes `a`.
#[inline(always)]
pub(crate) fn mat_cl<const N: usize>(m: &[[f64; 3]; 3], a: &V3<Lanes<N>>) -> V3<Lanes<N>> {
    v3(|k| a[0] * m[k][0] + a[1] * m[k][1] + a[2] * m[k][2])
}

/// The lanes of `R(q)` (`rot_t` of `dual.rs`, differentiated) along `dq`:
/// with `R = I + 2 [[-(yy+zz), xy-wz, xz+wy], [xy+wz, -(xx+zz), yz-wx],
/// [xz-wy, yz+wx, -(xx+yy)]]`, `d(ab) = a db + b da`.
#[inline(always)]
pub(crate) fn rot_lanes<const N: usize>(q: &[f64; 4], dq: &[Lanes<N>; 4]) -> [V3<Lanes<N>>; 3] {
    let [w, x, y, z] = q.map(|c| 2.0 * c);
    let [dw, dx, dy, dz] = *dq;
    // twice the lanes of each product
    let (xx, yy, zz) = (dx * x, dy * y, dz * z);
    let (xy, xz, yz) = (dx * y + dy * x, dx * z + dz * x, dy * z + dz * y);
    let (wx, wy, wz) = (dw * x + dx * w, dw * y + dy * w, dw * z + dz * w);
    [
        [-(yy + zz) * 2.0, xy - wz, xz + wy],
        [xy + wz, -(xx + zz) * 2.0, yz - wx],
        [xz - wy, yz + wx, -(xx + yy) * 2.0],
    ]
}
