//! Coil contact: the TCA's law inside a body, below zero elongation (the
//! coils pressed together), and its exact slope for the shooting tangents.

use std::f64::consts::PI;

use super::TcaAt;
use crate::error::{Error, Result};

impl TcaAt<'_> {
    /// Stiffness \[N/m\] used for coil contact inside a body: the stacked coils
    /// as a solid ring column, `E_T pi (D - d) d / L`. Far stiffer than the
    /// coil spring (about 400x for the paper's manipulator TCAs), so a TCA
    /// shortens by micrometres at most once its coils touch.
    pub fn contact_stiffness(&self) -> f64 {
        let t = self.tca;
        self.e * PI * (t.coil_diameter - self.d).max(self.d) * self.d / t.coiled_length
    }

    /// Width \[m\] of the smoothed onset of coil contact inside a body (see
    /// [`Self::tension`]): 0.1 um, far below any elongation of interest
    /// (the paper's TCAs move by millimetres) and far above the finite-
    /// difference steps of the shooting Jacobian (~1e-9 m).
    pub const CONTACT_SMOOTHING: f64 = 1e-7;

    /// Tension \[N\] at any elongation `delta` \[m\], for use inside a body:
    /// eq (6) for `delta >= 0`; for `delta < 0` (coils pressed together) the
    /// slope rises from the coil spring's `k_s = dF/d delta (0+)` to the
    /// contact stiffness `k_c` ([`Self::contact_stiffness`]) linearly over
    /// [`Self::CONTACT_SMOOTHING`], and stays `k_c` beyond. The law is C1, so
    /// Newton's method converges through contact onset (a kink would stall it
    /// when a passive TCA is pressed).
    pub fn tension(&self, delta: f64) -> Result<f64> {
        if delta >= 0.0 {
            return self.force(delta);
        }
        if !delta.is_finite() {
            return Err(Error::param("displacement [m]", delta, "a finite number"));
        }
        let f0 = self.force(0.0)?;
        let h = 1e-9 * self.tca.coiled_length;
        let ks = (self.force(h)? - f0) / h;
        let kc = self.contact_stiffness().max(ks);
        let eps = Self::CONTACT_SMOOTHING;
        Ok(if delta >= -eps {
            f0 + ks * delta - (kc - ks) * delta * delta / (2.0 * eps)
        } else {
            f0 - ks * eps - (kc - ks) * eps / 2.0 + kc * (delta + eps)
        })
    }
    /// The elongation \[m\] below zero at which [`Self::tension`] equals
    /// `tension` \[N\] `< F(0)`: the exact inverse of the contact branch,
    /// smoothed onset included (the law increases there), by Brent's method
    /// on `[(tension - F(0)) / k_c - eps, 0]`, whose left end lies below
    /// `tension` on the law whichever of `k_s`, `k_c` is larger.
    pub fn contact_elongation(&self, tension: f64) -> Result<f64> {
        let f0 = self.force(0.0)?;
        if !(tension < f0) {
            return Err(Error::param(
                "tension [N]",
                tension,
                format!("< {f0} (the onset tension F(0))"),
            ));
        }
        let lo = (tension - f0) / self.contact_stiffness() - Self::CONTACT_SMOOTHING;
        let xtol = 4.0 * f64::EPSILON * lo.abs();
        crate::roots::brent(
            |d| self.tension(d).map_or(f64::NAN, |t| t - tension),
            lo,
            0.0,
            xtol,
        )
        .ok_or_else(|| Error::param("tension [N]", tension, "a tension the contact law reaches"))
    }
    /// `d tension / d T` [N/C] of [`Self::tension`] at fixed `delta` \[m\],
    /// exact (for the sensitivities to the temperature inputs):
    /// [`Self::force_temperature_slope`] for `delta >= 0`; below, the
    /// contact branch's `F(0)`, `k_s` and `k_c` differentiated as written.
    pub fn tension_temperature_slope(&self, delta: f64) -> Result<f64> {
        if delta >= 0.0 {
            return self.force_temperature_slope(delta);
        }
        if !delta.is_finite() {
            return Err(Error::param("displacement [m]", delta, "a finite number"));
        }
        let t = self.tca;
        let f0 = self.force(0.0)?;
        let h = 1e-9 * t.coiled_length;
        let ks = (self.force(h)? - f0) / h;
        let g0 = self.force_temperature_slope(0.0)?;
        let dks = (self.force_temperature_slope(h)? - g0) / h;
        // k_c = E pi max(D - d, d) d / L, or k_s where that is larger
        let (_, de, _, _, rho0, rho1) = t.material.coefficients();
        let dd = t.d0 * (rho0 + 2.0 * rho1 * (self.temperature - t.material.t_ref()));
        let (w, dw) = if t.coil_diameter - self.d >= self.d {
            (t.coil_diameter - self.d, -dd)
        } else {
            (self.d, dd)
        };
        let kc = self.contact_stiffness();
        let dkc = if kc >= ks {
            PI * (de * w * self.d + self.e * (dw * self.d + w * dd)) / t.coiled_length
        } else {
            dks
        };
        let eps = Self::CONTACT_SMOOTHING;
        Ok(if delta >= -eps {
            g0 + dks * delta - (dkc - dks) * delta * delta / (2.0 * eps)
        } else {
            g0 - dks * eps - (dkc - dks) * eps / 2.0 + dkc * (delta + eps)
        })
    }

    /// `d tension / d delta` [N/m] of [`Self::tension`], exact (for the
    /// shooting solver's tangents): eq (6) differentiated through the pitch
    /// angle `alpha(delta)` of eq (5) for `delta >= 0`, the contact branch's
    /// slope for `delta < 0`.
    pub fn tension_slope(&self, delta: f64) -> Result<f64> {
        let t = self.tca;
        if delta < 0.0 {
            let f0 = self.force(0.0)?;
            let h = 1e-9 * t.coiled_length;
            let ks = (self.force(h)? - f0) / h;
            let kc = self.contact_stiffness().max(ks);
            let eps = Self::CONTACT_SMOOTHING;
            return Ok(if delta >= -eps {
                ks - (kc - ks) * delta / eps
            } else {
                kc
            });
        }
        let a = t.pitch_angle(delta)?;
        let (s, c) = a.sin_cos();
        let da = 1.0 / (t.fibre_length * c); // d alpha / d delta, eq (5)
        let n = t.n_coils;
        let ln = t.fibre_length / n;
        let ka = 8.0 * n / (PI.powi(3) * self.d.powi(4)) * ln.powi(3);
        let kb = 8.0 * n / (PI * self.d * self.d) * ln;
        let f11 = self.f11(a);
        let df11 = ka
            * (-4.0 * c.powi(3) * s / self.g + 4.0 * (s * c.powi(3) - s.powi(3) * c) / self.e)
            + kb * (-c * s / self.g + s * c / self.e);
        let f12 = self.f12(a);
        let df12 = -2.0 * 8.0 * n / (PI * PI * self.d.powi(4)) * ln * ln * c * s / self.g;
        let num = delta - self.sign() * f12 * self.tau;
        let dnum = 1.0 - self.sign() * df12 * da * self.tau;
        Ok((dnum * f11 - num * df11 * da) / (f11 * f11))
    }
}
