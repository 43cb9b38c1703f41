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
    /// `true` if value and derivatives are finite.
    fn is_finite(&self) -> bool;
}

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
}

/// `re + sum_k eps\[k\] e_k` with `e_j e_k = 0`: value and `N` directional derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual<const N: usize> {
    /// Value.
    pub re: f64,
    /// Derivative along each direction.
    pub eps: [f64; N],
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
        self.re.is_finite() && self.eps.iter().all(|e| e.is_finite())
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn add(mut self, o: Self) -> Self {
        self.re += o.re;
        for k in 0..N {
            self.eps[k] += o.eps[k];
        }
        self
    }
}
impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(mut self, o: Self) -> Self {
        self.re -= o.re;
        for k in 0..N {
            self.eps[k] -= o.eps[k];
        }
        self
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
        let re = self.re * inv;
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
    fn add(mut self, o: f64) -> Self {
        self.re += o;
        self
    }
}
impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(mut self, o: f64) -> Self {
        self.re -= o;
        self
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
        let inv = 1.0 / o;
        self.map(self.re * inv, inv)
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
