//! Cross-sections of the body: area, second moments, torsion constant.

use std::f64::consts::PI;

use crate::error::{positive, Error, Result};

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
    /// Solid circle of `diameter` \[m\] (> 0, with derived properties in double range).
    pub fn circle(diameter: f64) -> Result<Section> {
        let diameter = positive("diameter [m]", diameter)?;
        Section::Circle { diameter }.checked("diameter [m]")
    }

    /// Solid rectangle: `width` \[m\] along body x, `height` \[m\] along body y (both > 0).
    pub fn rectangle(width: f64, height: f64) -> Result<Section> {
        let width = positive("width [m]", width)?;
        let height = positive("height [m]", height)?;
        Section::Rectangle { width, height }.checked("width [m] / height [m]")
    }

    /// User-given area \[m^2\], second moments about body x and y \[m^4\] and
    /// torsion constant \[m^4\] (all > 0).
    pub fn custom(area: f64, ix: f64, iy: f64, j: f64) -> Result<Section> {
        let area = positive("area [m^2]", area)?;
        let ix = positive("ix [m^4]", ix)?;
        let iy = positive("iy [m^4]", iy)?;
        let j = positive("j [m^4]", j)?;
        Section::Custom { area, ix, iy, j }.checked("area [m^2]")
    }

    /// The section built by constructor `kind` (`"circle"`, `"rectangle"`,
    /// `"custom"`) from the values of [`Section::parameters`], in order.
    pub fn from_parameters(kind: &str, values: &[f64]) -> Result<Section> {
        match (kind, values) {
            ("circle", &[d]) => Section::circle(d),
            ("rectangle", &[w, h]) => Section::rectangle(w, h),
            ("custom", &[a, ix, iy, j]) => Section::custom(a, ix, iy, j),
            _ => Err(Error::input(
                "kind",
                format!("{kind:?} with {} values is not a section", values.len()),
            )),
        }
    }

    /// The constructor's name: `"circle"`, `"rectangle"` or `"custom"`.
    pub fn kind(&self) -> &'static str {
        match self {
            Section::Circle { .. } => "circle",
            Section::Rectangle { .. } => "rectangle",
            Section::Custom { .. } => "custom",
        }
    }

    /// The constructor's arguments by name, in order (SI units).
    pub fn parameters(&self) -> Vec<(&'static str, f64)> {
        match *self {
            Section::Circle { diameter } => vec![("diameter", diameter)],
            Section::Rectangle { width, height } => vec![("width", width), ("height", height)],
            Section::Custom { area, ix, iy, j } => {
                vec![("area", area), ("ix", ix), ("iy", iy), ("j", j)]
            }
        }
    }

    /// This section if its derived properties (area, second moments, edge
    /// distance) are finite and positive in double precision: a size so small
    /// or large that they under- or overflow is rejected, naming `name`.
    fn checked(self, name: &str) -> Result<Section> {
        let (a, ix, iy, j) = self.properties();
        for v in [a, ix, iy, j, self.edge_distance(0.0)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::input(
                    name,
                    format!(
                        "derived section property {v} (area, second moment or edge distance) \
                         is not finite and > 0 in double precision"
                    ),
                ));
            }
        }
        Ok(self)
    }

    /// Width and height \[m\] of the section's bounding box (custom sections:
    /// the edge distances along x and y, twice).
    pub fn extent(&self) -> (f64, f64) {
        let s = self;
        match *s {
            Section::Circle { diameter } => (diameter, diameter),
            Section::Rectangle { width, height } => (width, height),
            Section::Custom { .. } => (
                2.0 * s.edge_distance(0.0),
                2.0 * s.edge_distance(std::f64::consts::FRAC_PI_2),
            ),
        }
    }

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
