//! A forward-mode dual number with `N` derivative directions, for the exact
//! tangents (variational equations) of the discrete RK4 map.
//!
//! Why hand-written rather than `num-dual`: the tangent twin of the ODE needs
//! only `+ - * /`, `sqrt` and constants, on a fixed, small number of
//! directions known at run time (6 + actuators); a 30-line `Copy` type with
//! a `[f64; N]` derivative part stays on the stack, monomorphises for a few
//! widths (4, 8, 16), and adds no dependency whose nalgebra version must
//! track ours (nalgebra 0.34).

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use super::ode::Eq25;

/// Scalar arithmetic shared by `f64` and [`Dual`]: what the generic twin of
/// the right-hand side needs.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + AddAssign
    + SubAssign
{
    /// A constant (zero derivative).
    fn cst(x: f64) -> Self;
    /// The value (real part).
    fn re(&self) -> f64;
    /// Square root.
    fn sqrt(self) -> Self;
    /// `true` if the value is finite (derivatives are checked once, at the
    /// end of a tangent pass).
    fn is_finite(&self) -> bool;
    /// `true` if the value and every derivative are zero (a slack string:
    /// no terms in eq 25).
    fn is_zero(&self) -> bool;
    /// Solve the eq-25 system `[[M11, M12], [M12^T, M22]] [v'; u'] = [e; f]`
    /// (symmetric blocks stored whole): in `f64` by block elimination; for a
    /// [`Dual`], the real part is factored ONCE in `f64` and every direction's
    /// derivative solved with that factorisation, `d x = M^-1 (d b - dM x)`.
    /// `None` if singular.
    fn solve_eq25(m: &Blocks<Self>, e: &V3<Self>, f: &V3<Self>) -> Option<(V3<Self>, V3<Self>)>;
}

/// A 3-vector of scalars.
pub type V3<T> = [T; 3];

/// The three 3x3 blocks `M11, M12, M22` of the eq-25 matrix.
pub type Blocks<T> = [[[T; 3]; 3]; 3];

impl Real for f64 {
    #[inline(always)]
    fn cst(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn re(&self) -> f64 {
        *self
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }
    #[inline(always)]
    fn is_zero(&self) -> bool {
        *self == 0.0
    }
    #[inline(always)]
    fn solve_eq25(m: &Blocks<f64>, e: &V3<f64>, f: &V3<f64>) -> Option<(V3<f64>, V3<f64>)> {
        Some(Eq25::factor(m)?.solve(e, f))
    }
}

/// `re + sum_k eps\[k\] e_k` with `e_j e_k = 0`: value and `N` directional derivatives.
///
/// Laid out derivatives first on a 64-byte boundary, so that the lanes of
/// a stored dual are one aligned vector load (AVX-512) rather than one
/// split across two cache lines.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct Dual<const N: usize> {
    /// Derivative along each direction.
    pub eps: [f64; N],
    /// Value.
    pub re: f64,
}

impl<const N: usize> Dual<N> {
    /// A value with derivatives.
    #[inline(always)]
    pub fn new(re: f64, eps: [f64; N]) -> Self {
        Dual { re, eps }
    }
    #[inline(always)]
    fn map(self, re: f64, d: f64) -> Self {
        // chain rule: f(x) with f'(x) = d
        let mut eps = self.eps;
        for e in &mut eps {
            *e *= d;
        }
        Dual { re, eps }
    }
}

impl<const N: usize> Real for Dual<N> {
    #[inline(always)]
    fn cst(x: f64) -> Self {
        Dual {
            re: x,
            eps: [0.0; N],
        }
    }
    #[inline(always)]
    fn re(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let r = self.re.sqrt();
        self.map(r, 0.5 / r)
    }
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.re.is_finite()
    }
    #[inline(always)]
    fn is_zero(&self) -> bool {
        self.re == 0.0 && self.eps.iter().all(|e| *e == 0.0)
    }
    #[inline(always)]
    fn solve_eq25(m: &Blocks<Self>, e: &V3<Self>, f: &V3<Self>) -> Option<(V3<Self>, V3<Self>)> {
        let fac = Eq25::factor(&m.map(|b| b.map(|r| r.map(|x| x.re))))?;
        let (v, u) = fac.solve(&e.map(|x| x.re), &f.map(|x| x.re));
        // each direction's right-hand side d b - dM x, all directions at once
        let (m11, m12, m22) = (&m[0], &m[1], &m[2]);
        let mut bv = [[0.0; N]; 3];
        let mut bu = [[0.0; N]; 3];
        for p in 0..3 {
            let (mut av, mut au) = (e[p].eps, f[p].eps);
            for q in 0..3 {
                let (a, b) = (&m11[p][q].eps, &m12[p][q].eps);
                let (c, d) = (&m12[q][p].eps, &m22[p][q].eps);
                for k in 0..N {
                    av[k] -= a[k] * v[q] + b[k] * u[q];
                    au[k] -= c[k] * v[q] + d[k] * u[q];
                }
            }
            bv[p] = av;
            bu[p] = au;
        }
        let (dv, du) = fac.solve_n(&bv, &bu);
        Some((
            v3(|p| Dual::new(v[p], dv[p])),
            v3(|p| Dual::new(u[p], du[p])),
        ))
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        // a fresh value, not `self` updated: updating would copy the
        // padding of the 64-byte-aligned layout through every sum
        let mut eps = [0.0; N];
        for ((e, a), b) in eps.iter_mut().zip(&self.eps).zip(&o.eps) {
            *e = a + b;
        }
        Dual {
            re: self.re + o.re,
            eps,
        }
    }
}
impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        // a fresh value, not `self` updated: updating would copy the
        // padding of the 64-byte-aligned layout through every sum
        let mut eps = [0.0; N];
        for ((e, a), b) in eps.iter_mut().zip(&self.eps).zip(&o.eps) {
            *e = a - b;
        }
        Dual {
            re: self.re - o.re,
            eps,
        }
    }
}
impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let mut eps = [0.0; N];
        for ((e, a), b) in eps.iter_mut().zip(&self.eps).zip(&o.eps) {
            *e = a * o.re + self.re * b;
        }
        Dual {
            re: self.re * o.re,
            eps,
        }
    }
}
impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.re;
        // the value as f64 divides (bit-for-bit the IVP's), the derivatives by `inv`
        let re = self.re / o.re;
        let mut eps = [0.0; N];
        for ((e, a), b) in eps.iter_mut().zip(&self.eps).zip(&o.eps) {
            *e = (a - re * b) * inv;
        }
        Dual { re, eps }
    }
}
impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(-self.re, -1.0)
    }
}
impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: f64) -> Self {
        Dual {
            re: self.re + o,
            eps: self.eps,
        }
    }
}
impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: f64) -> Self {
        Dual {
            re: self.re - o,
            eps: self.eps,
        }
    }
}
impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: f64) -> Self {
        self.map(self.re * o, o)
    }
}
impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: f64) -> Self {
        self.map(self.re / o, 1.0 / o)
    }
}
impl<const N: usize> AddAssign for Dual<N> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<const N: usize> SubAssign for Dual<N> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

/// `[f(0), f(1), f(2)]`: `std::array::from_fn` for 3-vectors, written out
/// so that it is always inlined (`from_fn` over a [`Dual`] need not be, and
/// an outlined call keeps the tangent pass's lanes from vectorising).
#[inline(always)]
pub(crate) fn v3<T>(f: impl Fn(usize) -> T) -> [T; 3] {
    [f(0), f(1), f(2)]
}

/// `a x b`.
#[inline(always)]
pub(crate) fn cross<T: Real>(a: &V3<T>, b: &V3<T>) -> V3<T> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a x b` for a constant `b`.
#[inline(always)]
pub(crate) fn cross_c<T: Real>(a: &V3<T>, b: &V3<f64>) -> V3<T> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a x b` for a constant `a`.
#[inline(always)]
pub(crate) fn c_cross<T: Real>(a: &V3<f64>, b: &V3<T>) -> V3<T> {
    [
        b[2] * a[1] - b[1] * a[2],
        b[0] * a[2] - b[2] * a[0],
        b[1] * a[0] - b[0] * a[1],
    ]
}

/// `a . b`.
#[inline(always)]
pub(crate) fn dot<T: Real>(a: &V3<T>, b: &V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Rotation matrix of a unit quaternion `[w, x, y, z]` (as `rod::rot`).
#[inline(always)]
pub(crate) fn rot_t<T: Real>(q: &[T; 4]) -> [[T; 3]; 3] {
    let (w, x, y, z) = (q[0], q[1], q[2], q[3]);
    let (xx, yy, zz) = (x * x, y * y, z * z);
    let (xy, xz, yz) = (x * y, x * z, y * z);
    let (wx, wy, wz) = (w * x, w * y, w * z);
    [
        [
            T::cst(1.0) - (yy + zz) * 2.0,
            (xy - wz) * 2.0,
            (xz + wy) * 2.0,
        ],
        [
            (xy + wz) * 2.0,
            T::cst(1.0) - (xx + zz) * 2.0,
            (yz - wx) * 2.0,
        ],
        [
            (xz - wy) * 2.0,
            (yz + wx) * 2.0,
            T::cst(1.0) - (xx + yy) * 2.0,
        ],
    ]
}

/// `R^T a` for a constant `a`.
#[inline(always)]
pub(crate) fn rt_mul<T: Real>(r: &[[T; 3]; 3], a: &V3<f64>) -> V3<T> {
    v3(|k| r[0][k] * a[0] + r[1][k] * a[1] + r[2][k] * a[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_of_a_rational_function_with_a_root() {
        // f(x, y) = sqrt(x^2 + y) / (x - 3 y) at (2, 5): analytic gradient
        let x = Dual::<2>::new(2.0, [1.0, 0.0]);
        let y = Dual::<2>::new(5.0, [0.0, 1.0]);
        let f = (x * x + y).sqrt() / (x - y * 3.0);
        let (g, d) = (3.0f64, 2.0 - 15.0);
        assert!((f.re - g / d).abs() < 1e-15);
        // df/dx = (x / g) / d - g / d^2, df/dy = (0.5 / g) / d + 3 g / d^2
        assert!((f.eps[0] - ((2.0 / g) / d - g / (d * d))).abs() < 1e-15);
        assert!((f.eps[1] - ((0.5 / g) / d + 3.0 * g / (d * d))).abs() < 1e-15);
    }
}
