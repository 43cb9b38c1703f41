//! Temperature-dependent properties of a TCA's twisted fibre (paper Section II:
//! "we consider the relationships to be linear").
//!
//! All temperatures are in degrees Celsius (only differences enter the law, and
//! the paper, its sources and every oven in the field use C); moduli in Pa;
//! expansion coefficients in 1/C.

use crate::error::{finite, positive, Error, Result};

/// Linear-in-temperature material of a twisted polymer fibre.
///
/// * `E_T(T) = e_ref + e_slope (T - t_ref)` \[Pa\]
/// * `G_T(T) = g_ref + g_slope (T - t_ref)` \[Pa\]
/// * `rho(T) = rho_ref + rho_slope (T - t_ref)` \[1/C\], entering the fibre
///   diameter as `d = d0 (1 + rho(T) (T - t_ref))` (paper, below eq. 1).
///
/// Temperatures outside `\[t_min, t_max\]` are rejected, never extrapolated.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    name: String,
    /// `E_T`: \[Pa\] at `t_ref`, slope \[Pa/C\].
    youngs: Linear,
    /// `G_T`: \[Pa\] at `t_ref`, slope \[Pa/C\].
    shear: Linear,
    /// `rho`: \[1/C\] at `t_ref`, slope \[1/C^2\].
    expansion: Linear,
    /// Reference temperature and valid range \[C\].
    t_ref: f64,
    t_min: f64,
    t_max: f64,
}

/// A coefficient linear in temperature, `at_ref + slope (T - t_ref)`: each of
/// the material's three laws.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Linear {
    at_ref: f64,
    slope: f64,
}

impl Linear {
    /// The value at `dt = T - t_ref` \[C\].
    fn at(self, dt: f64) -> f64 {
        self.at_ref + self.slope * dt
    }
}

/// 0 C in kelvin \[K\]: absolute zero is `-ZERO_CELSIUS_IN_KELVIN` C.
pub const ZERO_CELSIUS_IN_KELVIN: f64 = 273.15;

/// Coefficients of the fibre-diameter fit `d/d0 = a T^2 + b T + c` (T in C) of
/// Sun & Zhao's `TCA_moduli_creeped.m` (the MATLAB code of their T-RO 2022
/// paper; see the sources in `docs/choices.md`).
const DIAMETER_FIT: (f64, f64, f64) = (3.542e-6, -6.705e-5, 1.00169);

/// Measured radial (transverse) coefficient of thermal expansion of oriented
/// nylon 6,6: `(T [C], alpha_r [1/K])`, an *instantaneous* coefficient
/// `(1/d) dd/dT`. Choy et al. 1984, as transcribed in `getMaterialProperties.m`
/// of `imcginty/TCPM-Optimal-Force-Tracking` (arrays `T2`, `alpha2`; see the
/// sources in `docs/choices.md`).
pub const NYLON66_RADIAL_CTE: [(f64, f64); 8] = [
    (-41.0, 10.84e-5),
    (1.0, 12.81e-5),
    (32.0, 15.50e-5),
    (64.0, 19.56e-5),
    (92.0, 24.90e-5),
    (116.0, 30.48e-5),
    (137.0, 36.35e-5),
    (160.0, 43.68e-5),
];

/// The measured radial CTE of oriented nylon 6,6 [1/K] at `t` \[C\]: linear
/// interpolation of [`NYLON66_RADIAL_CTE`]; an error outside its -41..160 C.
pub fn nylon66_radial_cte(t: f64) -> Result<f64> {
    let data = &NYLON66_RADIAL_CTE;
    let (lo, hi) = (data[0].0, data[data.len() - 1].0);
    if !(t.is_finite() && t >= lo && t <= hi) {
        return Err(Error::param(
            "temperature [C]",
            t,
            format!("{lo} <= T <= {hi} C (range of the measured CTE)"),
        ));
    }
    let k = data
        .iter()
        .rposition(|&(tk, _)| tk <= t)
        .unwrap_or(0)
        .min(data.len() - 2);
    let ((t0, a0), (t1, a1)) = (data[k], data[k + 1]);
    Ok(a0 + (a1 - a0) * (t - t0) / (t1 - t0))
}

impl Material {
    /// The shear-modulus slope \[Pa/C\] that keeps `G/E` constant, the default
    /// when only the Young's modulus slope is known: `dG/dT = dE/dT G_ref / E_ref`.
    pub fn proportional_shear_slope(e_ref: f64, e_slope: f64, g_ref: f64) -> f64 {
        e_slope * g_ref / e_ref
    }

    /// Build a material, validating every field.
    ///
    /// Errors if any value is non-finite, `t_min >= t_max`, `t_ref` lies outside
    /// `\[t_min, t_max\]`, or a modulus or the diameter ratio `1 + rho dT` is not
    /// positive somewhere in the valid range.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        name: impl Into<String>,
        e_ref: f64,
        e_slope: f64,
        g_ref: f64,
        g_slope: f64,
        rho_ref: f64,
        rho_slope: f64,
        t_ref: f64,
        t_min: f64,
        t_max: f64,
    ) -> Result<Self> {
        let law = |at_ref, slope| Linear { at_ref, slope };
        let laws = [
            law(e_ref, e_slope),
            law(g_ref, g_slope),
            law(rho_ref, rho_slope),
        ];
        Self::from_laws(name.into(), laws, [t_ref, t_min, t_max])
    }

    /// [`Material::new`] from the laws `[E_T, G_T, rho]` and `[t_ref, t_min, t_max]`.
    fn from_laws(name: String, laws: [Linear; 3], [t_ref, t_min, t_max]: [f64; 3]) -> Result<Self> {
        let [youngs, shear, expansion] = laws;
        positive("youngs_modulus [Pa]", youngs.at_ref)?;
        finite("youngs_modulus_slope [Pa/C]", youngs.slope)?;
        positive("shear_modulus [Pa]", shear.at_ref)?;
        finite("shear_modulus_slope [Pa/C]", shear.slope)?;
        finite("expansion [1/C]", expansion.at_ref)?;
        finite("expansion_slope [1/C^2]", expansion.slope)?;
        finite("t_ref [C]", t_ref)?;
        finite("t_min [C]", t_min)?;
        finite("t_max [C]", t_max)?;
        if t_min <= -ZERO_CELSIUS_IN_KELVIN {
            return Err(Error::param(
                "t_min [C]",
                t_min,
                "> -273.15 C (absolute zero)",
            ));
        }
        if t_max <= t_min {
            return Err(Error::param(
                "t_max [C]",
                t_max,
                format!("> t_min = {t_min} C"),
            ));
        }
        if t_ref < t_min || t_ref > t_max {
            return Err(Error::param(
                "t_ref [C]",
                t_ref,
                format!("{t_min} <= t_ref <= {t_max} C"),
            ));
        }
        let m = Material {
            name,
            youngs,
            shear,
            expansion,
            t_ref,
            t_min,
            t_max,
        };
        // Linear functions: positivity on the interval is positivity at its ends.
        for t in [t_min, t_max] {
            if m.youngs_modulus_unchecked(t) <= 0.0 {
                return Err(Error::param(
                    "youngs_modulus_slope [Pa/C]",
                    youngs.slope,
                    format!("a slope keeping E_T > 0 at {t} C"),
                ));
            }
            if m.shear_modulus_unchecked(t) <= 0.0 {
                return Err(Error::param(
                    "shear_modulus_slope [Pa/C]",
                    shear.slope,
                    format!("a slope keeping G_T > 0 at {t} C"),
                ));
            }
            if m.diameter_ratio_unchecked(t) <= 0.0 {
                return Err(Error::param(
                    "expansion [1/C]",
                    expansion.at_ref,
                    format!("a value keeping 1 + rho dT > 0 at {t} C"),
                ));
            }
        }
        Ok(m)
    }

    /// The silver-coated nylon 6,6 sewing thread of the paper (Shieldex
    /// 235/35 4-ply), with the defaults listed in `docs/choices.md` (the TCA
    /// law's material):
    ///
    /// * `E_T(25 C) = 1.198e9 Pa` and `G_T(25 C) = 2.218e8 Pa`: Sun & Zhao,
    ///   T-RO 2022 code (`rod_const_EG.m`).
    /// * `dE_T/dT = -1.3e6 Pa/C`: the same code (`TCA_moduli_creeped.m`,
    ///   filament modulus slope 1.1 MPa/C times a load factor of about 1.2).
    /// * `dG_T/dT = dE_T/dT * G_T/E_T` (constant `G/E`; an assumption, no
    ///   source gives the shear slope).
    /// * `rho(T)` linear, taken so that `d/d0 = 1 + rho(T) (T - 25)` reproduces
    ///   the diameter fit `d/d0 = 3.542e-6 T^2 - 6.705e-5 T + 1.00169` of
    ///   `TCA_moduli_creeped.m` exactly (normalised to 25 C): `rho(25 C) =
    ///   1.098e-4 1/C`, slope `3.534e-6 1/C^2`, `rho(160 C) = 5.87e-4 1/C`.
    ///   The paper calls `rho` linear in `T`; a linear `rho(T)` with a quadratic
    ///   `d(T)` is exactly that. (A constant `5.9e-4 1/C`, fitted to the
    ///   same quadratic, agrees at 160 C and overstates the expansion below
    ///   it; pass it with `rho_slope = 0` to compare.)
    /// * valid range 25-160 C: the range of the experiments and of the fits;
    ///   160 C is the annealing temperature. Reference (ambient) 25 C.
    pub fn silver_coated_nylon() -> Self {
        let (a, b, c) = DIAMETER_FIT;
        let t_ref = 25.0_f64;
        let q_ref = a * t_ref * t_ref + b * t_ref + c;
        // d(T)/d(t_ref) - 1 = (T - t_ref) (a (T + t_ref) + b) / q_ref
        //                   = (T - t_ref) (rho_ref + rho_slope (T - t_ref))
        let rho_slope = a / q_ref;
        let rho_ref = (2.0 * a * t_ref + b) / q_ref;
        let e_ref = 1.198e9;
        let e_slope = -1.3e6;
        let g_ref = 2.218e8;
        Material::new(
            "silver-coated nylon 6,6 (Shieldex 235/35)",
            e_ref,
            e_slope,
            g_ref,
            Material::proportional_shear_slope(e_ref, e_slope, g_ref),
            rho_ref,
            rho_slope,
            t_ref,
            25.0,
            160.0,
        )
        .expect("preset is valid")
    }

    /// The same thread with the *measured* radial CTE of oriented nylon 6,6
    /// (Choy et al. 1984, [`NYLON66_RADIAL_CTE`]) in place of the Sun & Zhao
    /// diameter fit; moduli as [`Material::silver_coated_nylon`].
    ///
    /// `rho(T)` stays linear (the paper's form). Its coefficients make the
    /// instantaneous coefficient `d'(T)/d(T)` of `d/d0 = 1 + rho(T) (T - 25)`
    /// fit the measured CTE at the data points inside 25-160 C (32 to 160 C),
    /// in least squares of the linearised equation `alpha d = d'` (linear in
    /// `rho_ref`, `rho_slope`): `rho(25 C) = 1.158e-4 1/C`, slope
    /// `1.160e-6 1/C^2`. The measured CTE is convex in `T` and a linear
    /// `rho(T)` gives a nearly linear `d'/d`: within 7.5 % of the data from
    /// 64 to 160 C, 15 % low at 32 C (tested).
    pub fn nylon66_measured_cte() -> Self {
        let t_ref = 25.0_f64;
        // normal equations of  rho_ref (1 - a x) + rho_slope (2 x - a x^2) = a,  x = T - t_ref
        let (mut m11, mut m12, mut m22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for &(t, a) in NYLON66_RADIAL_CTE
            .iter()
            .filter(|p| p.0 >= t_ref && p.0 <= 160.0)
        {
            let x = t - t_ref;
            let (u, v) = (1.0 - a * x, 2.0 * x - a * x * x);
            m11 += u * u;
            m12 += u * v;
            m22 += v * v;
            b1 += u * a;
            b2 += v * a;
        }
        let det = m11 * m22 - m12 * m12;
        let rho_ref = (b1 * m22 - b2 * m12) / det;
        let rho_slope = (m11 * b2 - m12 * b1) / det;
        let base = Material::silver_coated_nylon();
        let expansion = Linear {
            at_ref: rho_ref,
            slope: rho_slope,
        };
        Material::from_laws(
            "silver-coated nylon 6,6, measured radial CTE (Choy et al. 1984)".into(),
            [base.youngs, base.shear, expansion],
            [t_ref, 25.0, 160.0],
        )
        .expect("preset is valid")
    }

    /// This material with its expansion law scaled by `factor` [-]
    /// (`rho_ref` and `rho_slope` both times `factor`, so `d/d0 - 1` scales
    /// by `factor`); the name records the factor. For identification
    /// studies, never a default.
    pub fn with_expansion_scale(&self, factor: f64) -> Result<Self> {
        positive("factor [-]", factor)?;
        let expansion = Linear {
            at_ref: self.expansion.at_ref * factor,
            slope: self.expansion.slope * factor,
        };
        Material::from_laws(
            format!("{} (rho x {factor})", self.name),
            [self.youngs, self.shear, expansion],
            [self.t_ref, self.t_min, self.t_max],
        )
    }

    /// Instantaneous radial expansion coefficient `d'(T)/d(T)` [1/C] of the
    /// law `d/d0 = 1 + rho(T) (T - t_ref)`: what a dilatometer measures, so
    /// the quantity to compare with a measured CTE (`rho(T)` is the mean
    /// coefficient since `t_ref`, a different quantity).
    pub fn instantaneous_expansion(&self, t: f64) -> Result<f64> {
        self.check_temperature("temperature [C]", t)?;
        let dt = t - self.t_ref;
        let rho = self.expansion;
        Ok((rho.at_ref + 2.0 * rho.slope * dt) / self.diameter_ratio_unchecked(t))
    }

    /// Name of the material.
    pub fn name(&self) -> &str {
        &self.name
    }
    /// Reference (ambient) temperature \[C\] at which `d = d0`.
    pub fn t_ref(&self) -> f64 {
        self.t_ref
    }
    /// Lowest valid temperature \[C\].
    pub fn t_min(&self) -> f64 {
        self.t_min
    }
    /// Highest valid temperature \[C\].
    pub fn t_max(&self) -> f64 {
        self.t_max
    }
    /// `(e_ref, e_slope, g_ref, g_slope, rho_ref, rho_slope)` in Pa, Pa/C, Pa,
    /// Pa/C, 1/C, 1/C^2.
    pub fn coefficients(&self) -> (f64, f64, f64, f64, f64, f64) {
        let (e, g, rho) = (self.youngs, self.shear, self.expansion);
        (e.at_ref, e.slope, g.at_ref, g.slope, rho.at_ref, rho.slope)
    }

    /// Error unless `t` \[C\] is finite and within `\[t_min, t_max\]`.
    pub fn check_temperature(&self, name: &str, t: f64) -> Result<f64> {
        if t.is_finite() && t >= self.t_min && t <= self.t_max {
            Ok(t)
        } else {
            Err(Error::param(
                name,
                t,
                format!(
                    "{} <= T <= {} C (valid range of {})",
                    self.t_min, self.t_max, self.name
                ),
            ))
        }
    }

    fn youngs_modulus_unchecked(&self, t: f64) -> f64 {
        self.youngs.at(t - self.t_ref)
    }
    fn shear_modulus_unchecked(&self, t: f64) -> f64 {
        self.shear.at(t - self.t_ref)
    }
    fn diameter_ratio_unchecked(&self, t: f64) -> f64 {
        let dt = t - self.t_ref;
        1.0 + self.expansion.at(dt) * dt
    }

    /// Young's modulus `E_T(T)` \[Pa\] of the twisted fibre.
    pub fn youngs_modulus(&self, t: f64) -> Result<f64> {
        self.check_temperature("temperature [C]", t)?;
        Ok(self.youngs_modulus_unchecked(t))
    }
    /// Shear modulus `G_T(T)` \[Pa\] of the twisted fibre.
    pub fn shear_modulus(&self, t: f64) -> Result<f64> {
        self.check_temperature("temperature [C]", t)?;
        Ok(self.shear_modulus_unchecked(t))
    }
    /// Radial expansion coefficient `rho(T)` \[1/C\].
    pub fn expansion(&self, t: f64) -> Result<f64> {
        self.check_temperature("temperature [C]", t)?;
        Ok(self.expansion.at(t - self.t_ref))
    }
    /// Fibre diameter ratio `d/d0 = 1 + rho(T) (T - t_ref)` \[-\].
    pub fn diameter_ratio(&self, t: f64) -> Result<f64> {
        self.check_temperature("temperature [C]", t)?;
        Ok(self.diameter_ratio_unchecked(t))
    }

    /// `(E_T, G_T, d/d0)` at `t` (one range check).
    pub(crate) fn state(&self, t: f64) -> Result<(f64, f64, f64)> {
        self.check_temperature("temperature [C]", t)?;
        Ok((
            self.youngs_modulus_unchecked(t),
            self.shear_modulus_unchecked(t),
            self.diameter_ratio_unchecked(t),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn preset_reproduces_diameter_fit() {
        let m = Material::silver_coated_nylon();
        let (a, b, c) = DIAMETER_FIT;
        let q = |t: f64| a * t * t + b * t + c;
        for t in [25.0, 60.0, 100.0, 160.0] {
            // exact algebraic identity, so only rounding error (1e-15 relative)
            let want = q(t) / q(25.0);
            assert!((m.diameter_ratio(t).unwrap() - want).abs() < 1e-14, "{t}");
        }
        // the fit's own values at the ends of the range, d/d0 = 1.0816 at
        // 160 C and 1.0022 at 25 C (absolute, as the quadratic gives them):
        // their ratio
        assert!((m.diameter_ratio(160.0).unwrap() - 1.0816 / 1.0022).abs() < 1e-3);
    }

    #[test]
    fn measured_cte_preset_matches_choy_data() {
        let m = Material::nylon66_measured_cte();
        for &(t, a) in NYLON66_RADIAL_CTE.iter().filter(|p| p.0 >= 25.0) {
            let rel = m.instantaneous_expansion(t).unwrap() / a - 1.0;
            // a linear d'/d against convex data: 15 % at 32 C, 7.5 % above 60 C
            let tol = if t < 60.0 { 0.16 } else { 0.08 };
            assert!(rel.abs() < tol, "{t} C: {rel}");
        }
        let (.., r, rs) = m.coefficients();
        assert!(
            (r - 1.158e-4).abs() < 1e-7 && (rs - 1.160e-6).abs() < 1e-9,
            "{r} {rs}"
        );
    }

    #[test]
    fn instantaneous_expansion_is_log_derivative_of_diameter() {
        for m in [
            Material::silver_coated_nylon(),
            Material::nylon66_measured_cte(),
        ] {
            for t in [30.0, 95.0, 150.0] {
                let h = 1e-3;
                let ln_d = |t: f64| m.diameter_ratio(t).unwrap().ln();
                let fd = (ln_d(t + h) - ln_d(t - h)) / (2.0 * h);
                // central difference: truncation ~h^2 |(ln d)'''| < 1e-12, rounding ~1e-16/h
                assert!(
                    (m.instantaneous_expansion(t).unwrap() - fd).abs() < 1e-10,
                    "{t}"
                );
            }
        }
        // the default's d'/d over 95-135 C is 5.90e-4 .. 8.41e-4 1/C (d'/d0 there:
        // 6.0e-4 .. 8.9e-4), above the largest measured radial CTE of oriented nylon 6,6
        // (4.37e-4 at 160 C); values by hand from rho(25 C) = 1.098e-4, slope 3.534e-6
        let d = Material::silver_coated_nylon();
        assert!((d.instantaneous_expansion(95.0).unwrap() - 5.898e-4).abs() < 1e-7);
        assert!((d.instantaneous_expansion(135.0).unwrap() - 8.412e-4).abs() < 1e-7);
        assert!(d.instantaneous_expansion(80.0).unwrap() > NYLON66_RADIAL_CTE[7].1);
    }

    #[test]
    fn radial_cte_interpolates_and_scale_scales() {
        assert_eq!(nylon66_radial_cte(92.0).unwrap(), 24.90e-5);
        let mid = 0.5 * (24.90e-5 + 30.48e-5);
        assert!((nylon66_radial_cte(104.0).unwrap() - mid).abs() < 1e-15);
        assert_eq!(nylon66_radial_cte(160.0).unwrap(), 43.68e-5);
        assert!(nylon66_radial_cte(160.5).is_err() && nylon66_radial_cte(f64::NAN).is_err());
        let m = Material::nylon66_measured_cte();
        let h = m.with_expansion_scale(0.5).unwrap();
        let ratio =
            (h.diameter_ratio(120.0).unwrap() - 1.0) / (m.diameter_ratio(120.0).unwrap() - 1.0);
        assert!((ratio - 0.5).abs() < 1e-12);
        assert!(m.with_expansion_scale(0.0).is_err());
    }

    #[test]
    fn out_of_range_temperature_is_an_error() {
        let m = Material::silver_coated_nylon();
        assert!(m.youngs_modulus(24.9).is_err());
        assert!(m.youngs_modulus(160.1).is_err());
        assert!(m.youngs_modulus(f64::NAN).is_err());
        assert!((m.youngs_modulus(160.0).unwrap() - (1.198e9 - 1.3e6 * 135.0)).abs() < 1.0);
    }

    #[test]
    fn invalid_materials_are_rejected() {
        let ok = |e_slope: f64, t_max: f64| {
            Material::new("x", 1e9, e_slope, 1e8, 0.0, 1e-4, 0.0, 25.0, 25.0, t_max)
        };
        assert!(ok(-1e6, 160.0).is_ok());
        assert!(ok(-1e8, 160.0).is_err()); // E_T would go negative
        assert!(ok(0.0, 20.0).is_err()); // t_max < t_min
        assert!(Material::new("x", -1.0, 0.0, 1e8, 0.0, 0.0, 0.0, 25.0, 25.0, 50.0).is_err());
    }
}
