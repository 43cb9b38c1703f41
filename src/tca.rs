//! The TCA constitutive law (paper Section II, eqs 1-6).
//!
//! Units: lengths in m, forces in N, torques in N m, temperatures in C.
//! Sign convention (eq 2): `delta > 0` is extension, `F > 0` pulls the TCA
//! longer (tension). An extension (heterochiral) TCA lengthens when heated; a
//! contraction (homochiral) TCA uses the same law with the untwisting term's
//! sign reversed.
//!
//! Coil contact: a TCA is built with its coils touching (the `d0` relation
//! assumes it), so it cannot shorten below its coiled length: `delta >= 0`.
//! Under a load that would compress it further it stays at `delta = 0`.

use std::f64::consts::PI;

use crate::error::{positive, Error, Result};
use crate::material::Material;
use crate::roots::brent;

/// Absolute tolerance of the displacement solve, relative to the fibre
/// length `l`: the root of eqs (2), (5) is found to `1e-15 l`.
const DISPLACEMENT_XTOL_REL: f64 = 1e-15;

/// Which way a TCA moves when heated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Chirality {
    /// Twist and coil of opposite handedness: lengthens when heated.
    Extension,
    /// Twist and coil of the same handedness: shortens when heated.
    Contraction,
}

impl Chirality {
    /// `+1` for extension, `-1` for contraction: the sign of the untwisting term.
    pub fn sign(self) -> f64 {
        match self {
            Chirality::Extension => 1.0,
            Chirality::Contraction => -1.0,
        }
    }
}

/// A twisted-and-coiled actuator described by what a user measures.
#[derive(Debug, Clone, PartialEq)]
pub struct Tca {
    fibre_length: f64,
    coiled_length: f64,
    coil_diameter: f64,
    turns: f64,
    chirality: Chirality,
    material: Material,
    // derived (paper, below eq. 6)
    alpha0: f64,
    n_coils: f64,
    phi0: f64,
    d0: f64,
}

impl Tca {
    /// Build a TCA from the twisted-fibre length `l` \[m\], the coiled length
    /// `L` \[m\], the coil's outer diameter `D` \[m\], the inserted turns `N` \[-\],
    /// the chirality and the fibre material.
    ///
    /// Errors on non-finite or non-positive values, on `L >= l` (no pitch angle
    /// `asin(L/l)`), and on geometries whose derived fibre diameter
    /// `d0 = 2 D L / l` is not smaller than the coil diameter `D` (`L/l >= 1/2`).
    ///
    /// # Examples
    ///
    /// The paper's three-thread TCA of Fig. 5 (`l = 497 mm`, `L = 110 mm`,
    /// `D = 2 mm`, 300 turns):
    ///
    /// ```
    /// use tcarod::{Chirality, Material, Tca};
    ///
    /// let tca = Tca::new(0.497, 0.110, 2e-3, 300.0, Chirality::Extension, Material::silver_coated_nylon())?;
    /// assert!((tca.alpha0() - (0.110f64 / 0.497).asin()).abs() < 1e-15); // alpha0 = asin(L/l)
    /// assert!((tca.d0() - 2.0 * 2e-3 * 0.110 / 0.497).abs() < 1e-15); // d0 = 2 D L / l
    /// // L >= l has no pitch angle: an error naming the argument, not a panic
    /// assert!(Tca::new(0.110, 0.497, 2e-3, 300.0, Chirality::Extension, Material::silver_coated_nylon()).is_err());
    /// # Ok::<(), tcarod::Error>(())
    /// ```
    pub fn new(
        fibre_length: f64,
        coiled_length: f64,
        coil_diameter: f64,
        turns: f64,
        chirality: Chirality,
        material: Material,
    ) -> Result<Self> {
        let l = positive("fibre_length l [m]", fibre_length)?;
        let cl = positive("coiled_length L [m]", coiled_length)?;
        let dd = positive("coil_diameter D [m]", coil_diameter)?;
        let nn = positive("turns N [-]", turns)?;
        if cl >= l {
            return Err(Error::param(
                "coiled_length L [m]",
                cl,
                format!("0 < L < fibre_length l = {l} m (alpha0 = asin(L/l))"),
            ));
        }
        if 2.0 * cl >= l {
            return Err(Error::param(
                "coiled_length L [m]",
                cl,
                format!(
                    "L < l/2 = {} m so that the fibre diameter d0 = 2 D L / l is smaller than D",
                    0.5 * l
                ),
            ));
        }
        let alpha0 = (cl / l).asin();
        let t = Tca {
            fibre_length: l,
            coiled_length: cl,
            coil_diameter: dd,
            turns: nn,
            chirality,
            material,
            alpha0,
            n_coils: 2.0 * alpha0.cos() * l / (PI * dd),
            phi0: 2.0 * PI * nn,
            d0: 2.0 * dd * cl / l,
        };
        // Extreme inputs can pass every range check and still overflow or
        // underflow the law's powers (d^4, (l/n)^3); refuse them here rather
        // than return NaN from a solve later.
        let probe = t.at(t.material.t_max()).and_then(|a| {
            let f11 = a.f11(alpha0);
            let f12 = a.f12(alpha0);
            if [t.n_coils, t.d0, f11, f12, a.tau].iter().all(|x| x.is_finite()) && f11 > 0.0 && f12 > 0.0 {
                Ok(())
            } else {
                Err(Error::input(
                    "TCA geometry",
                    "derived quantities (n, d0, f11, f12, tau) are not finite positive numbers: sizes out of floating-point range",
                ))
            }
        });
        probe?;
        Ok(t)
    }

    /// A TCA specified, as in the paper's manipulators (Section V-B), by its
    /// coiled length `L` \[m\], pitch angle `alpha0` \[rad\], coil diameter `D` \[m\]
    /// and turns `N`: the fibre length follows as `l = L / sin(alpha0)`.
    pub fn from_pitch_angle(
        coiled_length: f64,
        alpha0: f64,
        coil_diameter: f64,
        turns: f64,
        chirality: Chirality,
        material: Material,
    ) -> Result<Self> {
        if !(alpha0.is_finite() && alpha0 > 0.0 && alpha0 < PI / 6.0) {
            return Err(Error::param(
                "alpha0 [rad]",
                alpha0,
                "0 < alpha0 < pi/6 (30 degrees)",
            ));
        }
        let cl = positive("coiled_length L [m]", coiled_length)?;
        Tca::new(
            cl / alpha0.sin(),
            cl,
            coil_diameter,
            turns,
            chirality,
            material,
        )
    }

    /// A warning text if the coil diameter looks like millimetres given as
    /// metres (above 0.1 m): a valid SI number, so not an error.
    pub fn units_warning(&self) -> Option<String> {
        let d = self.coil_diameter;
        (d > 0.1).then(|| {
            format!(
                "Tca: coil_diameter = {d} m: sizes are in metres (SI); did you give millimetres? \
                 (1.7 mm is 1.7e-3)"
            )
        })
    }

    /// Twisted-fibre length `l` \[m\].
    pub fn fibre_length(&self) -> f64 {
        self.fibre_length
    }
    /// Coiled length `L` \[m\].
    pub fn coiled_length(&self) -> f64 {
        self.coiled_length
    }
    /// Coil outer diameter `D` \[m\].
    pub fn coil_diameter(&self) -> f64 {
        self.coil_diameter
    }
    /// Inserted turns `N` \[-\].
    pub fn turns(&self) -> f64 {
        self.turns
    }
    /// Chirality.
    pub fn chirality(&self) -> Chirality {
        self.chirality
    }
    /// The fibre material.
    pub fn material(&self) -> &Material {
        &self.material
    }
    /// Initial pitch angle `alpha0 = asin(L/l)` \[rad\].
    pub fn alpha0(&self) -> f64 {
        self.alpha0
    }
    /// Number of coils `n = 2 cos(alpha0) l / (pi D)` \[-\].
    pub fn n_coils(&self) -> f64 {
        self.n_coils
    }
    /// Initial twist `phi0 = 2 pi N` \[rad\].
    pub fn phi0(&self) -> f64 {
        self.phi0
    }
    /// Fibre diameter at the reference temperature, `d0 = 2 D L / l` \[m\].
    pub fn d0(&self) -> f64 {
        self.d0
    }
    /// Largest elongation \[m\]: the fibre straight (`alpha = 90 deg`),
    /// `l (1 - sin alpha0)` (eq 5).
    pub fn max_displacement(&self) -> f64 {
        self.fibre_length * (1.0 - self.alpha0.sin())
    }

    /// Pitch angle \[rad\] at elongation `delta` \[m\], from eq (5):
    /// `delta = l (sin(alpha) - sin(alpha0))`.
    pub fn pitch_angle(&self, delta: f64) -> Result<f64> {
        let s = self.alpha0.sin() + delta / self.fibre_length;
        if !(delta.is_finite() && s > 0.0 && s < 1.0) {
            return Err(Error::param(
                "displacement [m]",
                delta,
                format!(
                    "-L < delta < l (1 - sin alpha0) = {:.6e} m (pitch angle between 0 and 90 deg)",
                    self.max_displacement()
                ),
            ));
        }
        Ok(s.asin())
    }

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
                "no temperature in [{lo}, {hi}] C gives displacement {displacement:.6e} m under force {force:.6e} N"
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

    /// A piece of this TCA: the fraction `fraction` (`0 < fraction <= 1`) of
    /// its length, as one segment of a TCA cut (or electrically divided) into
    /// segments in series. Fibre length `l`, coiled length `L` and turns `N`
    /// scale by `fraction`; the coil diameter, chirality and material stay, so
    /// the pitch angle `alpha0 = asin(L/l)`, the fibre diameter
    /// `d0 = 2 D L / l` and the twist density `N / l` are the same as the
    /// whole TCA's. The number of coils scales by `fraction`, so at one
    /// temperature and force a segment's elongation is `fraction` times the
    /// whole TCA's (eqs 2-5 are linear in `n` at fixed `l/n`).
    pub fn segment(&self, fraction: f64) -> Result<Tca> {
        if !(fraction.is_finite() && fraction > 0.0 && fraction <= 1.0) {
            return Err(Error::param("fraction [-]", fraction, "0 < fraction <= 1"));
        }
        Tca::new(
            self.fibre_length * fraction,
            self.coiled_length * fraction,
            self.coil_diameter,
            self.turns * fraction,
            self.chirality,
            self.material.clone(),
        )
    }

    /// Free stroke \[m\]: the elongation at `temperature` \[C\] with no load.
    pub fn free_stroke(&self, temperature: f64) -> Result<f64> {
        self.displacement(0.0, temperature)
    }

    /// Blocked force \[N\] at `temperature` \[C\]: the axial force that holds the
    /// TCA at its coiled length (`delta = 0`). Negative (compressive: the TCA
    /// pushes) for a heated extension TCA, positive for a contraction TCA.
    ///
    /// # Examples
    ///
    /// ```
    /// use tcarod::{Chirality, Material, Tca};
    ///
    /// let ext = Tca::new(0.497, 0.110, 2e-3, 300.0, Chirality::Extension, Material::silver_coated_nylon())?;
    /// let con = Tca::new(0.497, 0.110, 2e-3, 300.0, Chirality::Contraction, Material::silver_coated_nylon())?;
    /// let push = ext.blocked_force(100.0)?; // [N]
    /// assert!((push + 1.016).abs() < 1e-3, "{push}");
    /// assert!((con.blocked_force(100.0)? + push).abs() < 1e-12); // a contraction TCA pulls as hard
    /// assert!(ext.blocked_force(25.0)?.abs() < 1e-12); // no heating, no force
    /// # Ok::<(), tcarod::Error>(())
    /// ```
    pub fn blocked_force(&self, temperature: f64) -> Result<f64> {
        self.force(0.0, temperature)
    }
}

/// The TCA law frozen at one temperature.
#[derive(Debug, Clone, Copy)]
pub struct TcaAt<'a> {
    tca: &'a Tca,
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
    fn sign(&self) -> f64 {
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
                    "force {force:.6e} N straightens the fibre (delta would exceed l (1 - sin alpha0) = {:.6e} m)",
                    t.max_displacement()
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
}

impl TcaAt<'_> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn fig5_three_thread() -> Tca {
        Tca::new(
            0.497,
            0.110,
            2e-3,
            300.0,
            Chirality::Extension,
            Material::silver_coated_nylon(),
        )
        .unwrap()
    }

    #[test]
    fn contact_law_is_continuous_and_monotone() {
        let t = fig5_three_thread();
        let at = t.at(25.0).unwrap();
        let e = TcaAt::CONTACT_SMOOTHING;
        let f = |d: f64| at.tension(d).unwrap();
        // continuity at 0 and at -eps (relative 1e-9: rounding of the pieces)
        assert!((f(-1e-18) - f(0.0)).abs() < 1e-12);
        assert!(
            (f(-e * (1.0 - 1e-12)) - f(-e * (1.0 + 1e-12))).abs() < 1e-9 * f(-e).abs().max(1e-12)
        );
        // slope rises from the spring's to the contact stiffness
        let slope = |d: f64| (f(d + 1e-12) - f(d - 1e-12)) / 2e-12;
        assert!(slope(-2.0 * e) > 100.0 * slope(1e-6));
        assert!((slope(-3.0 * e) - at.contact_stiffness()).abs() < 1e-3 * at.contact_stiffness());
        // tension increases with elongation through the whole contact region
        let mut last = f64::NEG_INFINITY;
        for k in 0..50 {
            let d = -3.0 * e + 1e-8 * k as f64;
            assert!(f(d) > last, "not increasing at {d}");
            last = f(d);
        }
    }

    #[test]
    fn derived_quantities_follow_the_paper() {
        let t = fig5_three_thread();
        assert!((t.alpha0() - (0.110f64 / 0.497).asin()).abs() < 1e-15);
        assert!((t.n_coils() - 2.0 * t.alpha0().cos() * 0.497 / (PI * 2e-3)).abs() < 1e-12);
        assert!((t.d0() - 2.0 * 2e-3 * 0.110 / 0.497).abs() < 1e-15);
        assert!((t.phi0() - 600.0 * PI).abs() < 1e-12);
    }

    #[test]
    fn reference_temperature_gives_no_torque_and_hookean_response() {
        let t = fig5_three_thread();
        let s = t.at(25.0).unwrap();
        assert_eq!(s.tau, 0.0);
        // compression at T_ref: coils in contact
        assert_eq!(t.displacement(-0.1, 25.0).unwrap(), 0.0);
        // tension: delta = f11(alpha(delta)) F
        let f = 0.05;
        let d = t.displacement(f, 25.0).unwrap();
        let a = t.pitch_angle(d).unwrap();
        assert!((d - s.f11(a) * f).abs() < 1e-14);
    }

    #[test]
    fn force_and_displacement_are_inverse() {
        let t = fig5_three_thread();
        for temp in [25.0, 80.0, 160.0] {
            for f in [0.0, 0.02, 0.2] {
                let d = t.displacement(f, temp).unwrap();
                if d > 0.0 {
                    let f2 = t.force(d, temp).unwrap();
                    assert!((f2 - f).abs() < 1e-9, "{temp} {f} {f2}");
                }
            }
        }
    }

    #[test]
    fn temperature_inverts_displacement_at_the_ends_of_the_range() {
        // A state computed at t_min or t_max satisfies the law only to the
        // displacement solve's tolerance; the inverse must still find it.
        let t = fig5_three_thread();
        for temp in [25.0, 160.0] {
            for i in 0..=40 {
                let f = -0.3 + 0.02 * f64::from(i);
                let d = t.displacement(f, temp).unwrap();
                if d > 0.0 {
                    let back = t.temperature(f, d).unwrap();
                    // Brent's 1e-10 C, or the exact end
                    assert!((back - temp).abs() < 1e-7, "{temp} {f} {back}");
                }
            }
        }
    }

    #[test]
    fn segment_keeps_geometry_ratios_and_scales_elongation() {
        let t = fig5_three_thread();
        for frac in [0.25, 0.5, 1.0 / 3.0, 1.0] {
            let s = t.segment(frac).unwrap();
            // ratios of scaled lengths: equal to rounding (a few ulps)
            assert!((s.alpha0() - t.alpha0()).abs() < 1e-14, "{frac}");
            assert!((s.d0() - t.d0()).abs() < 1e-15 * t.d0().max(1.0), "{frac}");
            assert!(
                (s.turns() / s.fibre_length() - t.turns() / t.fibre_length()).abs() < 1e-9,
                "{frac}"
            );
            assert!((s.n_coils() - frac * t.n_coils()).abs() < 1e-12 * t.n_coils());
            assert_eq!(s.coil_diameter(), t.coil_diameter());
            assert_eq!(s.chirality(), t.chirality());
            // the law is linear in n at fixed l/n, d, alpha: a segment
            // stretches by `frac` of the whole under the same force and
            // temperature (to the displacement solve's 1e-15 l tolerance,
            // amplified by the conditioning of the root; 1e-9 relative is
            // far above that and far below any modelling difference)
            for (f, temp) in [(0.02, 25.0), (-0.05, 120.0), (0.0, 160.0)] {
                let dw = t.displacement(f, temp).unwrap();
                let ds = s.displacement(f, temp).unwrap();
                assert!(
                    (ds - frac * dw).abs() <= 1e-9 * dw.abs().max(1e-12),
                    "{frac} {f} {temp}: {ds} vs {}",
                    frac * dw
                );
                if dw > 0.0 {
                    let fw = t.force(dw, temp).unwrap();
                    let fs = s.force(frac * dw, temp).unwrap();
                    assert!((fw - fs).abs() < 1e-9 * fw.abs().max(1e-3));
                }
            }
        }
        for bad in [0.0, -0.5, 1.5, f64::NAN] {
            assert!(t.segment(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn invalid_geometry_rejected() {
        let m = Material::silver_coated_nylon();
        assert!(Tca::new(0.1, 0.11, 2e-3, 300.0, Chirality::Extension, m.clone()).is_err());
        assert!(Tca::new(0.5, 0.11, f64::NAN, 300.0, Chirality::Extension, m.clone()).is_err());
        assert!(Tca::new(0.5, 0.11, 2e-3, -1.0, Chirality::Extension, m).is_err());
    }
}
