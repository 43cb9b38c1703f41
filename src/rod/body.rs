//! The soft body: geometry, material, reference strains and dead loads.

use nalgebra::{Matrix3, Vector3};

use super::Section;
use crate::error::{finite, non_negative, positive, Error, Result};

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
        if !(poisson.is_finite() && poisson > -1.0 && poisson <= 0.5) {
            return Err(Error::param("poisson [-]", poisson, "-1 < poisson <= 0.5"));
        }
        let e = positive("youngs_modulus E_B [Pa]", youngs_modulus)?;
        let b = Body {
            length,
            section,
            youngs_modulus: e,
            shear_modulus: e / (2.0 * (1.0 + poisson)),
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
            for (k, x) in v.iter().enumerate() {
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
        Ok(())
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

    /// Total distributed force in the world frame [N/m]: `psi A g + f`.
    pub fn distributed_load(&self) -> Vector3<f64> {
        let (a, ..) = self.section.properties();
        self.density * a * self.gravity + self.distributed_force
    }
}
