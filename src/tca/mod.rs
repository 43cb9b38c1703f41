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
                format!(
                    "0 < L < fibre_length l = {} m (alpha0 = asin(L/l))",
                    crate::error::human(l)
                ),
            ));
        }
        if 2.0 * cl >= l {
            return Err(Error::param(
                "coiled_length L [m]",
                cl,
                format!(
                    "L < l/2 = {} m so that the fibre diameter d0 = 2 D L / l is smaller than D",
                    crate::error::human(0.5 * l)
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
    ///
    /// A fibre or coiled length above 10 m (the body-length threshold of
    /// [`crate::rod::Body::units_warning`]) warns the same way.
    pub fn units_warning(&self) -> Option<String> {
        use crate::error::{human, mm_hint, mm_question};
        let d = self.coil_diameter;
        if d > 0.1 {
            return Some(format!(
                "Tca: coil_diameter = {} m: sizes are in metres (SI){}",
                human(d),
                mm_question(d)
            ));
        }
        [
            ("fibre_length", self.fibre_length),
            ("coiled_length", self.coiled_length),
        ]
        .into_iter()
        .find(|(_, x)| *x > 10.0)
        .map(|(name, x)| {
            format!(
                "Tca: {name} = {} m: sizes are in metres (SI){}",
                human(x),
                mm_hint(x)
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
                    "-L < delta < l (1 - sin alpha0) = {} m (pitch angle between 0 and 90 deg)",
                    crate::error::human(self.max_displacement())
                ),
            ));
        }
        Ok(s.asin())
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

mod contact;
mod law;
#[cfg(test)]
mod tests;

pub use law::TcaAt;
