//! Cross-sections of the body: area, second moments, torsion constant.

use std::f64::consts::PI;

use crate::error::{positive, Result};

/// Cross-section of the body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Section {
    /// Solid circle of the given diameter \[m\].
    Circle {
        /// Diameter \[m\].
        diameter: f64,
    },
    /// Solid rectangle, `width` \[m\] along body `x`, `height` \[m\] along body `y`.
    Rectangle {
        /// Extent along body x \[m\].
        width: f64,
        /// Extent along body y \[m\].
        height: f64,
    },
    /// User-given properties.
    Custom {
        /// Area \[m^2\].
        area: f64,
        /// Second moment about body x \[m^4\] (bending with curvature `u_x`).
        ix: f64,
        /// Second moment about body y \[m^4\] (bending with curvature `u_y`).
        iy: f64,
        /// Torsion constant \[m^4\].
        j: f64,
    },
}

impl Section {
    /// `(A, I_x, I_y, J)` in m^2 and m^4. For a rectangle `J` is Saint-Venant's
    /// torsion constant `a b^3 (1/3 - 0.21 (b/a) (1 - b^4 / (12 a^4)))`
    /// (`a >= b`), not the polar moment, which overstates a square's torsional
    /// stiffness by 18%.
    pub fn properties(&self) -> (f64, f64, f64, f64) {
        match *self {
            Section::Circle { diameter } => {
                let a = PI * diameter * diameter / 4.0;
                let i = PI * diameter.powi(4) / 64.0;
                (a, i, i, 2.0 * i)
            }
            Section::Rectangle { width, height } => {
                let (a, b) = if width >= height {
                    (width, height)
                } else {
                    (height, width)
                };
                let j = a
                    * b.powi(3)
                    * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b.powi(4) / (12.0 * a.powi(4))));
                (
                    width * height,
                    width * height.powi(3) / 12.0,
                    height * width.powi(3) / 12.0,
                    j,
                )
            }
            Section::Custom { area, ix, iy, j } => (area, ix, iy, j),
        }
    }

    /// Distance \[m\] from the centre line to the section's edge in the body-frame
    /// direction `(cos(theta), sin(theta))`.
    pub fn edge_distance(&self, theta: f64) -> f64 {
        match *self {
            Section::Circle { diameter } => 0.5 * diameter,
            Section::Rectangle { width, height } => {
                let (s, c) = theta.sin_cos();
                let tx = if c.abs() > 1e-12 {
                    0.5 * width / c.abs()
                } else {
                    f64::INFINITY
                };
                let ty = if s.abs() > 1e-12 {
                    0.5 * height / s.abs()
                } else {
                    f64::INFINITY
                };
                tx.min(ty)
            }
            Section::Custom { area, .. } => (area / PI).sqrt(),
        }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        match *self {
            Section::Circle { diameter } => {
                positive("section diameter [m]", diameter)?;
            }
            Section::Rectangle { width, height } => {
                positive("section width [m]", width)?;
                positive("section height [m]", height)?;
            }
            Section::Custom { area, ix, iy, j } => {
                positive("section area [m^2]", area)?;
                positive("section ix [m^4]", ix)?;
                positive("section iy [m^4]", iy)?;
                positive("section j [m^4]", j)?;
            }
        }
        Ok(())
    }
}
