//! The soft body: geometry, material, reference strains and dead loads.

use nalgebra::{Matrix3, Vector3};

use super::Section;
use crate::error::{finite, non_negative, positive, Error, Result};

/// Poisson's ratio \[-\] of a body given neither `poisson` nor
/// `shear_modulus`: 0.5, incompressible silicone (the paper's EcoFlex).
pub const DEFAULT_POISSON: f64 = 0.5;

/// How a body's shear modulus `G_B` is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shear {
    /// Isotropic material: `G_B = E_B / (2 (1 + poisson))`, `-1 < poisson <= 0.5`.
    Poisson(f64),
    /// `G_B` \[Pa\] directly (> 0).
    Modulus(f64),
}

impl Shear {
    /// The rule of the keyword constructor: `poisson` \[-\] or `shear_modulus`
    /// \[Pa\], not both; neither means [`DEFAULT_POISSON`].
    pub fn from_options(poisson: Option<f64>, shear_modulus: Option<f64>) -> Result<Shear> {
        match (poisson, shear_modulus) {
            (Some(_), Some(_)) => Err(Error::input(
                "poisson / shear_modulus",
                "give one of them, not both",
            )),
            (p, None) => Ok(Shear::Poisson(p.unwrap_or(DEFAULT_POISSON))),
            (None, Some(g)) => Ok(Shear::Modulus(g)),
        }
    }
}

/// The soft body: geometry, material, reference strains and external loads.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Length of the centre line \[m\].
    pub length: f64,
    /// Cross-section.
    pub section: Section,
    /// Young's modulus `E_B` \[Pa\].
    pub youngs_modulus: f64,
    /// Shear modulus `G_B` \[Pa\].
    pub shear_modulus: f64,
    /// Density `psi` \[kg/m^3\].
    pub density: f64,
    /// Shear correction factor `k` in `K_nu = diag(k G A, k G A, E A)`
    /// (1 in the paper).
    pub shear_coefficient: f64,
    /// Reference linear strain `nu*` \[-\] (`(0, 0, 1)` for an unstretched body).
    pub nu_star: Vector3<f64>,
    /// Reference angular strain `omega*` \[1/m\] (non-zero for a pre-curved body).
    pub omega_star: Vector3<f64>,
    /// Gravitational acceleration in the world frame \[m/s^2\].
    pub gravity: Vector3<f64>,
    /// Extra distributed force in the world frame \[N/m\].
    pub distributed_force: Vector3<f64>,
    /// Distributed moment in the world frame \[N m/m\].
    pub distributed_moment: Vector3<f64>,
    /// Tip force in the world frame \[N\].
    pub tip_force: Vector3<f64>,
    /// Tip moment in the world frame \[N m\].
    pub tip_moment: Vector3<f64>,
}

impl Body {
    /// A straight, unloaded, weightless body of isotropic material: `G_B = E_B / (2 (1 + poisson))`.
    pub fn new(
        length: f64,
        section: Section,
        youngs_modulus: f64,
        poisson: f64,
        density: f64,
    ) -> Result<Self> {
        Body::with_shear(
            length,
            section,
            youngs_modulus,
            Shear::Poisson(poisson),
            density,
        )
    }

    /// A straight, unloaded body of `length` \[m\], Young's modulus
    /// \[Pa\], shear modulus given by `shear` and `density` \[kg/m^3\].
    pub fn with_shear(
        length: f64,
        section: Section,
        youngs_modulus: f64,
        shear: Shear,
        density: f64,
    ) -> Result<Self> {
        positive("length [m]", length)?;
        let shear_modulus = match shear {
            Shear::Poisson(poisson) => {
                if !(poisson.is_finite() && poisson > -1.0 && poisson <= 0.5) {
                    return Err(Error::param("poisson [-]", poisson, "-1 < poisson <= 0.5"));
                }
                let e = positive("youngs_modulus E_B [Pa]", youngs_modulus)?;
                e / (2.0 * (1.0 + poisson))
            }
            Shear::Modulus(g) => g,
        };
        let b = Body {
            length,
            section,
            youngs_modulus,
            shear_modulus,
            density,
            shear_coefficient: 1.0,
            nu_star: Vector3::z(),
            omega_star: Vector3::zeros(),
            gravity: Vector3::zeros(),
            distributed_force: Vector3::zeros(),
            distributed_moment: Vector3::zeros(),
            tip_force: Vector3::zeros(),
            tip_moment: Vector3::zeros(),
        };
        b.validate()?;
        Ok(b)
    }

    /// Validate every field.
    pub fn validate(&self) -> Result<()> {
        positive("body length [m]", self.length)?;
        self.section.validate()?;
        positive("youngs_modulus E_B [Pa]", self.youngs_modulus)?;
        positive("shear_modulus G_B [Pa]", self.shear_modulus)?;
        non_negative("density [kg/m^3]", self.density)?;
        positive("shear_coefficient [-]", self.shear_coefficient)?;
        let vecs: [(&str, &Vector3<f64>); 7] = [
            ("nu_star [-]", &self.nu_star),
            ("omega_star [1/m]", &self.omega_star),
            ("gravity [m/s^2]", &self.gravity),
            ("distributed_force [N/m]", &self.distributed_force),
            ("distributed_moment [N m/m]", &self.distributed_moment),
            ("tip_force [N]", &self.tip_force),
            ("tip_moment [N m]", &self.tip_moment),
        ];
        for (name, v) in vecs {
            // (the name formatted only for the error: validated every solve)
            for (k, x) in v.iter().enumerate().filter(|(_, x)| !x.is_finite()) {
                finite(&format!("{name}[{k}]"), *x)?;
            }
        }
        if self.nu_star.z <= 0.0 {
            return Err(Error::param(
                "nu_star[2] [-]",
                self.nu_star.z,
                "> 0 (the body must not fold back)",
            ));
        }
        self.check_derived()
    }

    /// Error unless the derived quantities (stiffnesses, weight per length)
    /// are finite and the stiffnesses positive in double precision.
    fn check_derived(&self) -> Result<()> {
        let (kv, kw) = self.stiffness();
        for k in 0..3 {
            for (name, v) in [
                ("stiffness K_nu [N]", kv[(k, k)]),
                ("stiffness K_omega [N m^2]", kw[(k, k)]),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(Error::input(
                        name,
                        format!(
                            "is {v}: youngs_modulus / shear_modulus times the section \
                             properties leave double range"
                        ),
                    ));
                }
            }
        }
        for (k, x) in self.distributed_load().iter().enumerate() {
            if !x.is_finite() {
                return Err(Error::input(
                    &format!("distributed_load [N/m][{k}] (density x area x gravity)"),
                    format!("is {x}: the inputs leave double range"),
                ));
            }
        }
        Ok(())
    }

    /// A warning text if the sizes look like millimetres given as metres (length
    /// above 10 m, section size above 1 m): valid SI numbers, so not an error.
    pub fn units_warning(&self) -> Option<String> {
        let b = self;
        let (w, h) = b.section.extent();
        if b.length > 10.0 || w.max(h) > 1.0 {
            use crate::error::{human, mm_question};
            Some(format!(
                "Body: length = {} m, section {} m x {} m: sizes are in metres (SI){}",
                human(b.length),
                human(w),
                human(h),
                mm_question(if b.length > 10.0 { b.length } else { w.max(h) })
            ))
        } else {
            None
        }
    }

    /// `K_nu = diag(k G A, k G A, E A)` \[N\] and `K_omega = diag(E I_x, E I_y, G J)` \[N m^2\].
    pub fn stiffness(&self) -> (Matrix3<f64>, Matrix3<f64>) {
        let (a, ix, iy, j) = self.section.properties();
        let (e, g, k) = (
            self.youngs_modulus,
            self.shear_modulus,
            self.shear_coefficient,
        );
        (
            Matrix3::from_diagonal(&Vector3::new(k * g * a, k * g * a, e * a)),
            Matrix3::from_diagonal(&Vector3::new(e * ix, e * iy, g * j)),
        )
    }

    /// The smaller bending stiffness `E min(I_x, I_y)` \[N m^2\]: the scale
    /// of the bending moments, and the one buckling reads.
    pub fn bending_stiffness(&self) -> f64 {
        let (_, ix, iy, _) = self.section.properties();
        self.youngs_modulus * ix.min(iy)
    }

    /// The body's characteristic force \[N\] and moment \[N m\],
    /// `E I / L^2` and `E I / L` (with [`Body::bending_stiffness`]).
    pub fn load_scales(&self) -> (f64, f64) {
        let ei = self.bending_stiffness();
        (ei / (self.length * self.length), ei / self.length)
    }

    /// Total distributed force in the world frame [N/m]: `psi A g + f`.
    pub fn distributed_load(&self) -> Vector3<f64> {
        let (a, ..) = self.section.properties();
        self.density * a * self.gravity + self.distributed_force
    }
}
