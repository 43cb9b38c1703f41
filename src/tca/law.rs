//! The law at one temperature (eqs 1-5) and its inversions: force,
//! displacement and temperature of a TCA.

use std::f64::consts::PI;

use super::{Tca, DISPLACEMENT_XTOL_REL};
use crate::error::{Error, Result};
use crate::roots::brent;

impl Tca {
    /// The law's temperature-dependent quantities at `temperature` \[C\].
    pub fn at(&self, temperature: f64) -> Result<TcaAt<'_>> {
        let (e, g, ratio) = self.material.state(temperature)?;
        let d = self.d0 * ratio;
        // eq (1): tau = G_T J_T phi0 (1 - d0/d) / l, J_T = pi d^4 / 32
        let j = PI * d.powi(4) / 32.0;
        let tau = g * j * self.phi0 * (1.0 - self.d0 / d) / self.fibre_length;
        Ok(TcaAt {
            tca: self,
            temperature,
            e,
            g,
            d,
            tau,
        })
    }

    /// Elongation `delta` \[m\] under an axial force `force` \[N\] (tension > 0)
    /// at `temperature` \[C\], with coil contact (`delta >= 0`).
    ///
    /// # Examples
    ///
    /// ```
    /// use tcarod::{Chirality, Material, Tca};
    ///
    /// let tca = Tca::new(0.497, 0.110, 2e-3, 300.0, Chirality::Extension, Material::silver_coated_nylon())?;
    /// let weight = -0.010 * 9.81; // 10 g pressing on it: compressive [N]
    /// assert_eq!(tca.displacement(weight, 40.0)?, 0.0); // below the onset: coils still touch
    /// let d = tca.displacement(weight, 100.0)?; // [m]
    /// assert!((d - 11.23e-3).abs() < 0.01e-3, "{d}");
    /// assert!(tca.displacement(weight, 170.0).is_err()); // outside the material's 25-160 C
    /// # Ok::<(), tcarod::Error>(())
    /// ```
    pub fn displacement(&self, force: f64, temperature: f64) -> Result<f64> {
        self.at(temperature)?.displacement(force)
    }

    /// Axial force \[N\] (tension > 0) that holds the TCA at elongation
    /// `displacement` \[m\] at `temperature` \[C\]. At `delta = 0` this is the
    /// force at which the coils just touch (any more compression is carried
    /// by coil contact).
    ///
    /// # Examples
    ///
    /// The inverse of [`Self::displacement`] away from coil contact:
    ///
    /// ```
    /// use tcarod::{Chirality, Material, Tca};
    ///
    /// let tca = Tca::new(0.497, 0.110, 2e-3, 300.0, Chirality::Extension, Material::silver_coated_nylon())?;
    /// let d = tca.displacement(-0.0981, 100.0)?;
    /// assert!((tca.force(d, 100.0)? + 0.0981).abs() < 1e-9);
    /// # Ok::<(), tcarod::Error>(())
    /// ```
    pub fn force(&self, displacement: f64, temperature: f64) -> Result<f64> {
        self.at(temperature)?.force(displacement)
    }

    /// Temperature \[C\] at which a TCA under `force` \[N\] has elongation
    /// `displacement` \[m\] (`>= 0`). With `displacement = 0` this is the onset
    /// temperature at which the coils separate. Errors with
    /// [`Error::NoSolution`] if no temperature in the material's range does it.
    ///
    /// # Examples
    ///
    /// ```
    /// use tcarod::{Chirality, Material, Tca};
    ///
    /// let tca = Tca::new(0.497, 0.110, 2e-3, 300.0, Chirality::Extension, Material::silver_coated_nylon())?;
    /// let weight = -0.010 * 9.81; // [N]
    /// let onset = tca.temperature(weight, 0.0)?; // [C] at which the coils separate
    /// assert!((onset - 41.2).abs() < 0.05, "{onset}");
    /// let t = tca.temperature(weight, 5e-3)?; // [C] for 5 mm of stroke
    /// assert!((tca.displacement(weight, t)? - 5e-3).abs() < 1e-9);
    /// # Ok::<(), tcarod::Error>(())
    /// ```
    pub fn temperature(&self, force: f64, displacement: f64) -> Result<f64> {
        crate::error::finite("force [N]", force)?;
        if displacement < 0.0 || !displacement.is_finite() {
            return Err(Error::param(
                "displacement [m]",
                displacement,
                "delta >= 0 (coils cannot close further than touching)",
            ));
        }
        let alpha = self.pitch_angle(displacement)?;
        let m = &self.material;
        let resid = |t: f64| -> f64 {
            match self.at(t) {
                Ok(s) => displacement - s.f11(alpha) * force - s.sign() * s.f12(alpha) * s.tau,
                Err(_) => f64::NAN,
            }
        };
        let (lo, hi) = (m.t_min(), m.t_max());
        brent(resid, lo, hi, 1e-10)
            .or_else(|| self.range_end_attaining(force, displacement))
            .ok_or_else(|| Error::NoSolution {
                reason: format!(
                    "no temperature in [{}, {}] C gives displacement {} m under force {} N",
                    crate::error::human(lo),
                    crate::error::human(hi),
                    crate::error::human(displacement),
                    crate::error::human(force)
                ),
            })
    }

    /// The end of the temperature range \[C\] at which `force` \[N\] gives an
    /// elongation within the forward solve's tolerance of `displacement` \[m\]
    /// (`> 0`), if any. A state computed *at* an end of the range (e.g.
    /// `displacement(F, t_max)`) satisfies eqs (2), (5) only to that
    /// tolerance, so the residual at that end may have either sign and the
    /// bracket of [`Self::temperature`] can miss it.
    fn range_end_attaining(&self, force: f64, displacement: f64) -> Option<f64> {
        if displacement <= 0.0 {
            // coils closed: an onset, which needs a genuine sign change
            return None;
        }
        let tol = 4.0 * DISPLACEMENT_XTOL_REL * self.fibre_length;
        let m = &self.material;
        [m.t_min(), m.t_max()].into_iter().find(|&t| {
            self.displacement(force, t)
                .is_ok_and(|d| (d - displacement).abs() <= tol)
        })
    }
}

/// The TCA law frozen at one temperature.
#[derive(Debug, Clone, Copy)]
pub struct TcaAt<'a> {
    pub(super) tca: &'a Tca,
    /// Temperature \[C\].
    pub temperature: f64,
    /// `E_T(T)` \[Pa\].
    pub e: f64,
    /// `G_T(T)` \[Pa\].
    pub g: f64,
    /// Fibre diameter `d(T)` \[m\].
    pub d: f64,
    /// Untwisting torque `tau(T)` \[N m\], eq (1).
    pub tau: f64,
}

impl<'a> TcaAt<'a> {
    pub(super) fn sign(&self) -> f64 {
        self.tca.chirality.sign()
    }

    /// `f11(alpha)` \[m/N\], eq (3).
    pub fn f11(&self, alpha: f64) -> f64 {
        let t = self.tca;
        let n = t.n_coils;
        let ln = t.fibre_length / n;
        let (s, c) = alpha.sin_cos();
        let (s2, c2) = (s * s, c * c);
        8.0 * n / (PI.powi(3) * self.d.powi(4))
            * ln.powi(3)
            * (c2 * c2 / self.g + 2.0 * s2 * c2 / self.e)
            + 8.0 * n / (PI * self.d * self.d) * ln * (c2 / (2.0 * self.g) + s2 / (2.0 * self.e))
    }

    /// `f12(alpha)` \[1/N... m/(N m)\], eq (4).
    pub fn f12(&self, alpha: f64) -> f64 {
        let t = self.tca;
        let n = t.n_coils;
        let ln = t.fibre_length / n;
        let c = alpha.cos();
        8.0 * n / (PI * PI * self.d.powi(4)) * ln * ln * c * c / self.g
    }

    /// Elongation \[m\] under `force` \[N\], with coil contact. Solves
    /// `delta = f11(alpha(delta)) F + s f12(alpha(delta)) tau` (eqs 2, 5).
    pub fn displacement(&self, force: f64) -> Result<f64> {
        crate::error::finite("force [N]", force)?;
        let t = self.tca;
        let s = self.sign();
        let h = |delta: f64| -> f64 {
            let sa = t.alpha0.sin() + delta / t.fibre_length;
            if sa >= 1.0 {
                return f64::INFINITY;
            }
            let a = sa.asin();
            delta - self.f11(a) * force - s * self.f12(a) * self.tau
        };
        let h0 = h(0.0);
        if h0 >= 0.0 {
            // coils in contact: the law asks for delta <= 0
            return Ok(0.0);
        }
        let dmax = t.max_displacement() * (1.0 - 1e-12);
        if h(dmax) <= 0.0 {
            return Err(Error::NoSolution {
                reason: format!(
                    "force {} N straightens the fibre (delta would exceed l (1 - sin alpha0) = {} m)",
                    crate::error::human(force),
                    crate::error::human(t.max_displacement())
                ),
            });
        }
        brent(h, 0.0, dmax, DISPLACEMENT_XTOL_REL * t.fibre_length).ok_or_else(|| {
            Error::NoSolution {
                reason: "displacement equation has no root".into(),
            }
        })
    }

    /// Axial force \[N\] at elongation `delta >= 0` \[m\]: eq (6),
    /// `F = (delta - s f12 tau) / f11`.
    pub fn force(&self, delta: f64) -> Result<f64> {
        if delta < 0.0 || !delta.is_finite() {
            return Err(Error::param(
                "displacement [m]",
                delta,
                "delta >= 0 (coils cannot close further than touching)",
            ));
        }
        let a = self.tca.pitch_angle(delta)?;
        Ok((delta - self.sign() * self.f12(a) * self.tau) / self.f11(a))
    }

    /// `d force / d T` [N/C] at fixed elongation `delta >= 0` \[m\]: eq (6)
    /// differentiated, exactly, through the temperature laws of `E_T`, `G_T`
    /// and `d = d0 (1 + rho(T) (T - t_ref))` (eq 1 for `tau`, eqs 3-4 for
    /// `f11`, `f12`); the pitch angle depends on `delta` only (eq 5).
    pub fn force_temperature_slope(&self, delta: f64) -> Result<f64> {
        let f = self.force(delta)?;
        let t = self.tca;
        let a = t.pitch_angle(delta)?;
        let (s, c) = a.sin_cos();
        let (s2, c2) = (s * s, c * c);
        let (e, g, d) = (self.e, self.g, self.d);
        let (_, de, _, dg, rho0, rho1) = t.material.coefficients();
        let dt = self.temperature - t.material.t_ref();
        // d d/dT over d: d/d0 = 1 + rho0 dt + rho1 dt^2
        let dd = t.d0 * (rho0 + 2.0 * rho1 * dt) / d;
        let n = t.n_coils;
        let ln = t.fibre_length / n;
        // f11 = ka p + kb q with ka ~ d^-4, kb ~ d^-2 (eq 3)
        let ka = 8.0 * n / (PI.powi(3) * d.powi(4)) * ln.powi(3);
        let kb = 8.0 * n / (PI * d * d) * ln;
        let p = c2 * c2 / g + 2.0 * s2 * c2 / e;
        let q = c2 / (2.0 * g) + s2 / (2.0 * e);
        let dp = -c2 * c2 * dg / (g * g) - 2.0 * s2 * c2 * de / (e * e);
        let dq = -c2 * dg / (2.0 * g * g) - s2 * de / (2.0 * e * e);
        let df11 = ka * (dp - 4.0 * dd * p) + kb * (dq - 2.0 * dd * q);
        // f12 ~ d^-4 / G (eq 4); tau = G (pi d^4 / 32) phi0 (1 - d0/d) / l (eq 1)
        let f12 = self.f12(a);
        let df12 = -f12 * (4.0 * dd + dg / g);
        let dtau = self.tau * (dg / g + 4.0 * dd)
            + g * PI * d.powi(4) / 32.0 * t.phi0 * (t.d0 / d) * dd / t.fibre_length;
        let dnum = -self.sign() * (df12 * self.tau + f12 * dtau);
        Ok((dnum - f * df11) / self.f11(a))
    }
}
