//! [`ShootingSystem`]: the multiple-shooting system with its Jacobian
//! factorised as a staircase ([`crate::solve::abd`]), the system the damped
//! Newton method ([`crate::solve::nleq`]) solves.

use super::MultipleShooting;
use crate::error::Result;

/// [`MultipleShooting`] with its Jacobian factorised as a staircase
/// ([`crate::solve::abd`]), the system the damped Newton method solves.
pub struct ShootingSystem<'a> {
    /// The residual and its Jacobian blocks.
    pub ms: MultipleShooting<'a>,
    lu: crate::solve::abd::Staircase,
    singular: bool,
}

impl<'a> ShootingSystem<'a> {
    /// The system of `ms`.
    pub fn new(ms: MultipleShooting<'a>) -> Result<Self> {
        Ok(ShootingSystem {
            lu: ms.staircase()?,
            ms,
            singular: false,
        })
    }

    /// Whether a Jacobian is factorised (a first linearisation was made).
    pub fn is_factorised(&self) -> bool {
        self.lu.is_factorised()
    }

    /// The system of `ms` with the factorised Jacobian of `other`, a
    /// system of the same shape (the same problem on another grid), as its
    /// first factorisation: a chord Jacobian for Newton's first steps.
    pub fn with_factorisation(ms: MultipleShooting<'a>, other: ShootingSystem<'_>) -> Self {
        ShootingSystem {
            ms,
            lu: other.lu,
            singular: other.singular,
        }
    }
}

impl crate::solve::nleq::NonlinearSystem for ShootingSystem<'_> {
    fn dim(&self) -> usize {
        self.ms.dim()
    }
    fn residual(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
        crate::solve::cancel::check()?;
        self.ms.residual(x, f)
    }
    fn linearise(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
        crate::solve::cancel::check()?;
        self.ms.linearise(x, f)?;
        self.singular = self.ms.factorise(&mut self.lu);
        Ok(())
    }
    fn solve(&mut self, b: &[f64], dx: &mut [f64]) -> Result<bool> {
        if self.singular {
            return Ok(false);
        }
        dx.copy_from_slice(b);
        self.lu.solve(dx)?;
        Ok(dx.iter().all(|v| v.is_finite()))
    }
    fn floor(&self, x: &[f64], _f: &[f64]) -> f64 {
        self.ms.rounding_floor(x)
    }
    fn work(&self) -> f64 {
        self.ms.work
    }
    fn breakpoint(&self, x: &[f64], dx: &[f64]) -> Option<f64> {
        self.ms.breakpoint(x, dx)
    }
}
