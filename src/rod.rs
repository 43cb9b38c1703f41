//! The Cosserat rod with embedded string-like actuators (paper Section III,
//! eqs 7-31) and its initial value problem.
//!
//! Frames and signs:
//! * world frame: base at the origin, reference tangent `+z`; `R(s)` maps body
//!   to world; body strains `v = nu` (linear) and `u = omega` (angular);
//! * actuator `i` runs at body-frame offset `r_i(s)` between arc lengths
//!   `s_start` and `s_end`; its scalar force `tau_i` is a *tension* (positive
//!   pulls the anchors together); a heated extension TCA pushes, `tau_i < 0`;
//! * loads are given in the world frame: gravity `g` [m/s^2], distributed force
//!   [N/m] and moment [N m/m], tip force [N] and moment [N m].
//!
//! Rotation: `R` is carried as a unit quaternion `q` with `q' = q (0, u) / 2`
//! (eq 8), integrated by RK4 and renormalised after every step. `R(q)` is
//! orthogonal to rounding for any unit `q`, so the only drift is the
//! quaternion's norm, which renormalisation removes each step.
//!
//! String mechanics (Rucker & Webster, T-RO 2011): a string of constant tension
//! `tau` on the curve `p_a = p + R r` loads the body by `tau t_a'` per unit
//! length (eqs 14-15) and by point forces `-tau t_a` at its distal anchor and
//! `+tau t_a` at its proximal anchor. The distributed load depends on `v'` and
//! `u'`, which gives the linear system (25) with blocks (26)-(31).

use std::f64::consts::PI;
use std::fmt::Debug;
use std::sync::Arc;

use nalgebra::{Matrix3, Quaternion, Vector3};

use crate::error::{finite, non_negative, positive, Error, Result};
use crate::tca::Tca;

/// Cross-section of the body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Section {
    /// Solid circle of the given diameter [m].
    Circle {
        /// Diameter [m].
        diameter: f64,
    },
    /// Solid rectangle, `width` [m] along body `x`, `height` [m] along body `y`.
    Rectangle {
        /// Extent along body x [m].
        width: f64,
        /// Extent along body y [m].
        height: f64,
    },
    /// User-given properties.
    Custom {
        /// Area [m^2].
        area: f64,
        /// Second moment about body x [m^4] (bending with curvature `u_x`).
        ix: f64,
        /// Second moment about body y [m^4] (bending with curvature `u_y`).
        iy: f64,
        /// Torsion constant [m^4].
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
                let j = a * b.powi(3) * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b.powi(4) / (12.0 * a.powi(4))));
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

    /// Distance [m] from the centre line to the section's edge in the body-frame
    /// direction `(cos(theta), sin(theta))`.
    pub fn edge_distance(&self, theta: f64) -> f64 {
        match *self {
            Section::Circle { diameter } => 0.5 * diameter,
            Section::Rectangle { width, height } => {
                let (s, c) = theta.sin_cos();
                let tx = if c.abs() > 1e-12 { 0.5 * width / c.abs() } else { f64::INFINITY };
                let ty = if s.abs() > 1e-12 { 0.5 * height / s.abs() } else { f64::INFINITY };
                tx.min(ty)
            }
            Section::Custom { area, .. } => (area / PI).sqrt(),
        }
    }

    fn validate(&self) -> Result<()> {
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

/// The soft body: geometry, material, reference strains and external loads.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Length of the centre line [m].
    pub length: f64,
    /// Cross-section.
    pub section: Section,
    /// Young's modulus `E_B` [Pa].
    pub youngs_modulus: f64,
    /// Shear modulus `G_B` [Pa].
    pub shear_modulus: f64,
    /// Density `psi` [kg/m^3].
    pub density: f64,
    /// Shear correction factor `k` in `K_nu = diag(k G A, k G A, E A)`
    /// (1 in the paper).
    pub shear_coefficient: f64,
    /// Reference linear strain `nu*` [-] (`(0, 0, 1)` for an unstretched body).
    pub nu_star: Vector3<f64>,
    /// Reference angular strain `omega*` [1/m] (non-zero for a pre-curved body).
    pub omega_star: Vector3<f64>,
    /// Gravitational acceleration in the world frame [m/s^2].
    pub gravity: Vector3<f64>,
    /// Extra distributed force in the world frame [N/m].
    pub distributed_force: Vector3<f64>,
    /// Distributed moment in the world frame [N m/m].
    pub distributed_moment: Vector3<f64>,
    /// Tip force in the world frame [N].
    pub tip_force: Vector3<f64>,
    /// Tip moment in the world frame [N m].
    pub tip_moment: Vector3<f64>,
}

impl Body {
    /// A straight, unloaded, weightless body of isotropic material: `G_B = E_B / (2 (1 + poisson))`.
    pub fn new(length: f64, section: Section, youngs_modulus: f64, poisson: f64, density: f64) -> Result<Self> {
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
            return Err(Error::param("nu_star[2] [-]", self.nu_star.z, "> 0 (the body must not fold back)"));
        }
        Ok(())
    }

    /// `K_nu = diag(k G A, k G A, E A)` [N] and `K_omega = diag(E I_x, E I_y, G J)` [N m^2].
    pub fn stiffness(&self) -> (Matrix3<f64>, Matrix3<f64>) {
        let (a, ix, iy, j) = self.section.properties();
        let (e, g, k) = (self.youngs_modulus, self.shear_modulus, self.shear_coefficient);
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

/// Path of an actuator in the body frame, with exact derivatives in `s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Routing {
    /// Parallel to the centre line at a constant offset `(x, y)` [m].
    Straight {
        /// Body-frame x offset [m].
        x: f64,
        /// Body-frame y offset [m].
        y: f64,
    },
    /// Helix about the centre line: `r = radius (cos(rate s + phase), sin(rate s + phase), 0)`.
    Helix {
        /// Radius [m].
        radius: f64,
        /// Angular rate [rad/m] (positive: right-handed about +z).
        rate: f64,
        /// Angle at `s = 0` [rad].
        phase: f64,
    },
}

impl Routing {
    /// `(r, r', r'')` at arc length `s` [m].
    #[inline]
    pub fn eval(&self, s: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        match *self {
            Routing::Straight { x, y } => (Vector3::new(x, y, 0.0), Vector3::zeros(), Vector3::zeros()),
            Routing::Helix { radius, rate, phase } => {
                let (sn, cs) = (rate * s + phase).sin_cos();
                (
                    Vector3::new(radius * cs, radius * sn, 0.0),
                    Vector3::new(-radius * rate * sn, radius * rate * cs, 0.0),
                    Vector3::new(-radius * rate * rate * cs, -radius * rate * rate * sn, 0.0),
                )
            }
        }
    }

    fn validate(&self) -> Result<()> {
        match *self {
            Routing::Straight { x, y } => {
                finite("routing x [m]", x)?;
                finite("routing y [m]", y)?;
            }
            Routing::Helix { radius, rate, phase } => {
                non_negative("helix radius [m]", radius)?;
                finite("helix rate [rad/m]", rate)?;
                finite("helix phase [rad]", phase)?;
            }
        }
        Ok(())
    }
}

/// The force law of a string-like actuator: tension as a function of the
/// actuator's total elongation and of its actuation input.
///
/// The rod model (eqs 22-33) never looks inside: any law that returns a
/// tension works, which is the paper's point that the equations hold for any
/// string-like actuator.
pub trait ForceLaw: Send + Sync + Debug {
    /// Tension [N] (positive pulls the anchors together) at total elongation
    /// `elongation` [m] (current length minus reference length) and input
    /// `input` (unit in [`ForceLaw::input_name`]).
    fn tension(&self, elongation: f64, input: f64) -> Result<f64>;
    /// Name and unit of the input, e.g. `temperature [C]`.
    fn input_name(&self) -> &'static str;
    /// Valid input interval.
    fn input_bounds(&self) -> (f64, f64);
    /// The input at which the actuator is passive (reference state).
    fn reference_input(&self) -> f64;
    /// Error unless `input` is valid.
    fn check_input(&self, input: f64) -> Result<()> {
        let (lo, hi) = self.input_bounds();
        if input.is_finite() && input >= lo && input <= hi {
            Ok(())
        } else {
            Err(Error::param(self.input_name(), input, format!("{lo} <= input <= {hi}")))
        }
    }
    /// Short name of the law.
    fn kind(&self) -> &'static str;
    /// Inverse law: the elongation [m] at which the actuator carries
    /// `tension` [N] at `input`, where that is unique. Used only to build
    /// initial guesses (a warm start keeps the tension, a cold start begins at
    /// zero tension), so `None` is always safe.
    fn elongation(&self, _tension: f64, _input: f64) -> Option<f64> {
        None
    }
}

/// The TCA law (eq 13) at the input temperature [C]: tension from the TCA's
/// total elongation, with coil contact below zero elongation.
#[derive(Debug, Clone)]
pub struct TcaLaw(pub Tca);

impl ForceLaw for TcaLaw {
    fn tension(&self, elongation: f64, input: f64) -> Result<f64> {
        self.0.at(input)?.tension(elongation)
    }
    fn input_name(&self) -> &'static str {
        "temperature [C]"
    }
    fn input_bounds(&self) -> (f64, f64) {
        (self.0.material().t_min(), self.0.material().t_max())
    }
    fn reference_input(&self) -> f64 {
        self.0.material().t_ref()
    }
    fn kind(&self) -> &'static str {
        "tca"
    }
    fn elongation(&self, tension: f64, input: f64) -> Option<f64> {
        let at = self.0.at(input).ok()?;
        let f0 = at.force(0.0).ok()?;
        if tension >= f0 {
            at.displacement(tension).ok()
        } else {
            Some((tension - f0) / at.contact_stiffness())
        }
    }
}

/// A tendon pulled with a given tension [N] (the input), whatever its elongation.
#[derive(Debug, Clone, Copy)]
pub struct ConstantTension;

impl ForceLaw for ConstantTension {
    fn tension(&self, _elongation: f64, input: f64) -> Result<f64> {
        Ok(input)
    }
    fn input_name(&self) -> &'static str {
        "tension [N]"
    }
    fn input_bounds(&self) -> (f64, f64) {
        (0.0, f64::MAX)
    }
    fn reference_input(&self) -> f64 {
        0.0
    }
    fn kind(&self) -> &'static str {
        "tension"
    }
}

/// A linearly elastic tendon of stiffness `k` [N/m] under displacement
/// control: the input is the length [m] pulled in at the base, the tension is
/// `k (pull + elongation)` and zero when slack.
#[derive(Debug, Clone, Copy)]
pub struct LinearTendon {
    /// Axial stiffness of the tendon [N/m].
    pub stiffness: f64,
}

impl ForceLaw for LinearTendon {
    fn tension(&self, elongation: f64, input: f64) -> Result<f64> {
        Ok((self.stiffness * (input + elongation)).max(0.0))
    }
    fn input_name(&self) -> &'static str {
        "pull [m]"
    }
    fn input_bounds(&self) -> (f64, f64) {
        (f64::MIN, f64::MAX)
    }
    fn reference_input(&self) -> f64 {
        0.0
    }
    fn kind(&self) -> &'static str {
        "linear_tendon"
    }
    fn elongation(&self, tension: f64, input: f64) -> Option<f64> {
        Some(tension.max(0.0) / self.stiffness - input)
    }
}

/// A string-like actuator embedded in the body.
#[derive(Debug, Clone)]
pub struct Actuator {
    /// Path in the body frame.
    pub routing: Routing,
    /// Proximal anchor [m] (0: anchored to the base).
    pub s_start: f64,
    /// Distal anchor [m] (the body length: anchored at the tip).
    pub s_end: f64,
    /// The paper's length ratio `L_i` (eq 18). `None`: computed pointwise from
    /// the reference configuration, `|nu* + omega* x r + r'|`, which makes the
    /// reference configuration exactly unstrained for any routing and
    /// pre-curvature.
    pub length_ratio: Option<f64>,
    /// Force law.
    pub law: Arc<dyn ForceLaw>,
}

impl Actuator {
    /// An actuator from `s_start` to `s_end` [m].
    pub fn new(routing: Routing, s_start: f64, s_end: f64, law: Arc<dyn ForceLaw>) -> Self {
        Actuator {
            routing,
            s_start,
            s_end,
            length_ratio: None,
            law,
        }
    }
}

/// A body with its actuators.
#[derive(Debug, Clone)]
pub struct Robot {
    /// The soft body.
    pub body: Body,
    /// Embedded actuators.
    pub actuators: Vec<Actuator>,
}

/// Number of states besides the actuator elongations: p (3), q (4), v (3), u (3).
pub const BASE_STATES: usize = 13;

impl Robot {
    /// Validate and build.
    pub fn new(body: Body, actuators: Vec<Actuator>) -> Result<Self> {
        let r = Robot { body, actuators };
        r.validate()?;
        Ok(r)
    }

    /// Validate body and actuator layout.
    pub fn validate(&self) -> Result<()> {
        self.body.validate()?;
        let len = self.body.length;
        for (i, a) in self.actuators.iter().enumerate() {
            a.routing.validate()?;
            if !(a.s_start.is_finite() && a.s_start >= 0.0 && a.s_start < len) {
                return Err(Error::param(&format!("actuators[{i}].s_start [m]"), a.s_start, format!("0 <= s_start < body length {len} m")));
            }
            if !(a.s_end.is_finite() && a.s_end > a.s_start && a.s_end <= len * (1.0 + 1e-12)) {
                return Err(Error::param(
                    &format!("actuators[{i}].s_end [m]"),
                    a.s_end,
                    format!("s_start = {} < s_end <= body length {len} m", a.s_start),
                ));
            }
            if let Some(l) = a.length_ratio {
                positive(&format!("actuators[{i}].length_ratio [-]"), l)?;
            }
            // The actuator must not run through the centre line's singular
            // configuration: |nu* + omega* x r + r'| > 0 along it.
            for k in 0..=8 {
                let s = a.s_start + (a.s_end - a.s_start) * k as f64 / 8.0;
                let (r, rp, _) = a.routing.eval(s);
                let w = self.body.nu_star + self.body.omega_star.cross(&r) + rp;
                if w.norm() < 1e-9 {
                    return Err(Error::input(&format!("actuators[{i}]"), "its reference path has zero length rate"));
                }
            }
        }
        Ok(())
    }

    /// Number of ODE states: 13 + number of actuators.
    pub fn n_states(&self) -> usize {
        BASE_STATES + self.actuators.len()
    }

    /// Check one input per actuator.
    pub fn check_inputs(&self, inputs: &[f64]) -> Result<()> {
        if inputs.len() != self.actuators.len() {
            return Err(Error::input(
                "inputs",
                format!("expected {} values (one per actuator), got {}", self.actuators.len(), inputs.len()),
            ));
        }
        for (i, (a, &x)) in self.actuators.iter().zip(inputs).enumerate() {
            a.law.check_input(x).map_err(|e| e.renamed(|name| format!("inputs[{i}] ({name})")))?;
        }
        Ok(())
    }

    /// Reference (passive) inputs: ambient temperature for TCAs, zero tension/pull for tendons.
    pub fn reference_inputs(&self) -> Vec<f64> {
        self.actuators.iter().map(|a| a.law.reference_input()).collect()
    }

    /// Sorted unique breakpoints: 0, L and every actuator anchor.
    pub fn breakpoints(&self) -> Vec<f64> {
        let len = self.body.length;
        let mut b = Vec::with_capacity(2 + 2 * self.actuators.len());
        b.extend_from_slice(&[0.0, len]);
        for a in &self.actuators {
            b.push(a.s_start);
            b.push(a.s_end.min(len));
        }
        b.sort_by(|x, y| x.partial_cmp(y).unwrap());
        b.dedup_by(|x, y| (*x - *y).abs() <= 1e-12 * len);
        b
    }
}

/// Rotation matrix of a (unit) quaternion `[w, x, y, z]`.
#[inline]
pub fn rot(q: &Quaternion<f64>) -> Matrix3<f64> {
    let (w, x, y, z) = (q.w, q.i, q.j, q.k);
    Matrix3::new(
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}

/// A state of the rod at one arc length.
#[derive(Debug, Clone, PartialEq)]
pub struct RodState {
    /// Position [m], world frame.
    pub p: Vector3<f64>,
    /// Orientation (unit quaternion, body to world).
    pub q: Quaternion<f64>,
    /// Linear strain `nu` [-], body frame.
    pub v: Vector3<f64>,
    /// Angular strain `omega` [1/m], body frame.
    pub u: Vector3<f64>,
    /// Actuator elongations `delta_i(s)` [m].
    pub delta: Vec<f64>,
}

impl RodState {
    fn from_slice(y: &[f64]) -> Self {
        RodState {
            p: Vector3::new(y[0], y[1], y[2]),
            q: Quaternion::new(y[3], y[4], y[5], y[6]),
            v: Vector3::new(y[7], y[8], y[9]),
            u: Vector3::new(y[10], y[11], y[12]),
            delta: y[13..].to_vec(),
        }
    }
    /// Rotation matrix `R` (body to world).
    pub fn rotation(&self) -> Matrix3<f64> {
        rot(&self.q)
    }
}

/// Everything an IVP needs besides the state: robot, tensions, loads.
pub struct IvpSpec<'a> {
    /// The robot.
    pub robot: &'a Robot,
    /// Tension of each actuator [N] (constant along a string).
    pub tensions: &'a [f64],
    /// Tip force [N], world frame (overrides `body.tip_force`, so that
    /// Jacobians can perturb it).
    pub tip_force: Vector3<f64>,
    /// Tip moment [N m], world frame.
    pub tip_moment: Vector3<f64>,
    /// RK4 steps over the body length.
    pub steps: usize,
}

/// Output of one IVP.
#[derive(Debug, Clone)]
pub struct IvpResult {
    /// Tip state.
    pub tip: RodState,
    /// Elongation of each actuator at its distal anchor [m].
    pub elongation: Vec<f64>,
    /// Tip residual in body frame: `K_nu (v - nu*) - R^T F + sum tau t_b` [N]
    /// and `K_omega (u - omega*) - R^T M + sum r x tau t_b` [N m] (eqs 32-33).
    pub tip_force_residual: Vector3<f64>,
    /// See `tip_force_residual`.
    pub tip_moment_residual: Vector3<f64>,
    /// Recorded nodes `(s, state)`, if asked for.
    pub nodes: Vec<(f64, RodState)>,
}

/// Per-actuator constants of one IVP: a straight actuator's offset, its
/// cross-product matrix and reference length rate do not change along `s`.
struct ActConst {
    /// `(r, r^, L_i)` for a straight routing; `None` for a helix (evaluated per stage).
    straight: Option<(Vector3<f64>, Matrix3<f64>, f64)>,
}

struct Frozen<'a> {
    robot: &'a Robot,
    tensions: &'a [f64],
    /// Diagonals of `K_nu`, `K_omega` and their inverses.
    kse: Vector3<f64>,
    kbt: Vector3<f64>,
    kse_inv: Vector3<f64>,
    kbt_inv: Vector3<f64>,
    fe: Vector3<f64>,
    le: Vector3<f64>,
    has_le: bool,
    acts: Vec<ActConst>,
}

/// Inverse of a symmetric 3x3 matrix (upper triangle read) by cofactors, `None` if singular.
#[inline(always)]
fn inv_sym3a(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let (a, b, c) = (m[0][0], m[0][1], m[0][2]);
    let (d, e) = (m[1][1], m[1][2]);
    let f = m[2][2];
    let c00 = d * f - e * e;
    let c01 = c * e - b * f;
    let c02 = b * e - c * d;
    let det = a * c00 + b * c01 + c * c02;
    if !(det.is_finite() && det != 0.0) {
        return None;
    }
    let id = 1.0 / det;
    let c11 = (a * f - c * c) * id;
    let c12 = (b * c - a * e) * id;
    let c22 = (a * d - b * b) * id;
    let (c00, c01, c02) = (c00 * id, c01 * id, c02 * id);
    Some([[c00, c01, c02], [c01, c11, c12], [c02, c12, c22]])
}

impl<'a> Frozen<'a> {
    fn new(robot: &'a Robot, tensions: &'a [f64]) -> Self {
        let body = &robot.body;
        let (kse, kbt) = body.stiffness();
        let kse = kse.diagonal();
        let kbt = kbt.diagonal();
        let acts = robot
            .actuators
            .iter()
            .map(|a| ActConst {
                straight: match a.routing {
                    Routing::Straight { x, y } => {
                        let r = Vector3::new(x, y, 0.0);
                        let l = a.length_ratio.unwrap_or_else(|| (body.nu_star + body.omega_star.cross(&r)).norm());
                        Some((r, r.cross_matrix(), l))
                    }
                    Routing::Helix { .. } => None,
                },
            })
            .collect();
        Frozen {
            robot,
            tensions,
            kse,
            kbt,
            kse_inv: kse.map(|x| 1.0 / x),
            kbt_inv: kbt.map(|x| 1.0 / x),
            fe: body.distributed_load(),
            le: body.distributed_moment,
            has_le: body.distributed_moment != Vector3::zeros(),
            acts,
        }
    }

    /// Body-frame tangent rate of actuator `i`: `v + u x r + r'` (eq 19 without `R`).
    #[inline]
    fn pb(&self, i: usize, s: f64, v: &Vector3<f64>, u: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let (r, rp, _) = self.robot.actuators[i].routing.eval(s);
        (v + u.cross(&r) + rp, r)
    }

    /// Reference length rate of actuator `i` at `s` (the paper's `L_i`).
    #[inline]
    fn ref_rate(&self, i: usize, s: f64) -> f64 {
        let a = &self.robot.actuators[i];
        match a.length_ratio {
            Some(l) => l,
            None => {
                let (r, rp, _) = a.routing.eval(s);
                (self.robot.body.nu_star + self.robot.body.omega_star.cross(&r) + rp).norm()
            }
        }
    }

    /// `dy/ds` (eqs 22-25) with the actuators in `active` (indices).
    ///
    /// The 6x6 system (25) is symmetric, `[[M11, M12], [M12^T, M22]]` with
    /// `M11 = K_nu + sum A_i`, `M12 = -sum A_i r_i^`, `M22 = K_omega - sum r_i^ A_i r_i^`
    /// (`A_i` symmetric, `r^T = -r^`), and is solved by block elimination on
    /// its 3x3 blocks: `M11^-1`, then the Schur complement `S = M22 - M12^T M11^-1 M12`.
    #[inline]
    fn deriv(&self, s: f64, y: &[f64], active: &[usize], dy: &mut [f64]) -> Result<()> {
        let body = &self.robot.body;
        let q = Quaternion::new(y[3], y[4], y[5], y[6]);
        let r_mat = rot(&q);
        let v = Vector3::new(y[7], y[8], y[9]);
        let u = Vector3::new(y[10], y[11], y[12]);
        let nse = self.kse.component_mul(&(v - body.nu_star));
        let nbt = self.kbt.component_mul(&(u - body.omega_star));
        // eq (25) right-hand side: [e; f]
        let rhs_v = -u.cross(&nse) - r_mat.tr_mul(&self.fe);
        let mut rhs_u = -u.cross(&nbt) - v.cross(&nse);
        if self.has_le {
            rhs_u -= r_mat.tr_mul(&self.le);
        }
        for k in 0..self.robot.actuators.len() {
            dy[BASE_STATES + k] = 0.0;
        }
        let (vd, ud) = if active.is_empty() {
            (rhs_v.component_mul(&self.kse_inv), rhs_u.component_mul(&self.kbt_inv))
        } else {
            // Blocks in plain arrays (nalgebra's generic 3x3 arithmetic costs
            // several times the flops here). Symmetric blocks are stored whole.
            let mut m11 = [[0.0; 3]; 3];
            let mut m12 = [[0.0; 3]; 3];
            let mut m22 = [[0.0; 3]; 3];
            for k in 0..3 {
                m11[k][k] = self.kse[k];
                m22[k][k] = self.kbt[k];
            }
            let (mut e, mut f) = ([rhs_v.x, rhs_v.y, rhs_v.z], [rhs_u.x, rhs_u.y, rhs_u.z]);
            for &i in active {
                let (r, rp, rpp, lref) = match self.acts[i].straight {
                    Some((r, _, l)) => (r, Vector3::zeros(), Vector3::zeros(), l),
                    None => {
                        let (r, rp, rpp) = self.robot.actuators[i].routing.eval(s);
                        (r, rp, rpp, self.ref_rate(i, s))
                    }
                };
                let pb = v + u.cross(&r) + rp; // eq (19), body frame
                let nrm = pb.norm();
                if !(nrm > 1e-12) {
                    return Err(Error::Integration {
                        s,
                        reason: format!("actuator {i} has zero length rate"),
                    });
                }
                let tau = self.tensions[i];
                // A_i = -tau pb^2 / |pb|^3 = c (I - t t^T), c = tau / |pb| (eq 20:
                // tau t_a' = A_i R^T p_a''). With r^ x = r x x, w = t x r and
                // r^ r^ = r r^T - |r|^2 I:
                //   A_i r^ = c (r^ - t w^T),  r^ A_i r^ = c (r r^T - |r|^2 I + w w^T).
                let c = tau / nrm;
                let t = pb / nrm;
                let w = t.cross(&r);
                let ct = t * c;
                let g_i = u.cross(&(pb + rp)) + rpp; // omega^(nu + omega^ r + 2 r') + r''
                let ag = g_i * c - ct * t.dot(&g_i); // A_i g_i
                let rag = r.cross(&ag);
                let cr2 = c * r.norm_squared();
                let cw = w * c;
                // (26): M11 += c I - c t t^T (symmetric: upper triangle, mirrored below)
                m11[0][0] += c - ct.x * t.x;
                m11[0][1] -= ct.x * t.y;
                m11[0][2] -= ct.x * t.z;
                m11[1][1] += c - ct.y * t.y;
                m11[1][2] -= ct.y * t.z;
                m11[2][2] += c - ct.z * t.z;
                // (27): M12 += -c r^ + c t w^T; (28) is its transpose
                let cr = r * c;
                for p in 0..3 {
                    m12[p][0] += ct[p] * w.x;
                    m12[p][1] += ct[p] * w.y;
                    m12[p][2] += ct[p] * w.z;
                }
                m12[0][1] += cr.z;
                m12[0][2] -= cr.y;
                m12[1][0] -= cr.z;
                m12[1][2] += cr.x;
                m12[2][0] += cr.y;
                m12[2][1] -= cr.x;
                // (29): M22 += c |r|^2 I - c r r^T - c w w^T
                m22[0][0] += cr2 - cr.x * r.x - cw.x * w.x;
                m22[0][1] -= cr.x * r.y + cw.x * w.y;
                m22[0][2] -= cr.x * r.z + cw.x * w.z;
                m22[1][1] += cr2 - cr.y * r.y - cw.y * w.y;
                m22[1][2] -= cr.y * r.z + cw.y * w.z;
                m22[2][2] += cr2 - cr.z * r.z - cw.z * w.z;
                for p in 0..3 {
                    e[p] -= ag[p]; // (30)
                    f[p] -= rag[p]; // (31)
                }
                dy[BASE_STATES + i] = nrm - lref; // (24)
            }
            for (p, q) in [(1, 0), (2, 0), (2, 1)] {
                m11[p][q] = m11[q][p];
                m22[p][q] = m22[q][p];
            }
            let singular = || Error::Integration {
                s,
                reason: "singular stiffness system (25): actuator compression exceeds the body's stiffness".into(),
            };
            let m11_inv = inv_sym3a(&m11).ok_or_else(singular)?;
            // Y = M11^-1 M12, a = M11^-1 e
            let mut y12 = [[0.0; 3]; 3];
            let mut ae = [0.0; 3];
            for p in 0..3 {
                for q in 0..3 {
                    y12[p][q] = m11_inv[p][0] * m12[0][q] + m11_inv[p][1] * m12[1][q] + m11_inv[p][2] * m12[2][q];
                }
                ae[p] = m11_inv[p][0] * e[0] + m11_inv[p][1] * e[1] + m11_inv[p][2] * e[2];
            }
            // S = M22 - M12^T Y (symmetric), g = f - M12^T a
            let mut sc = [[0.0; 3]; 3];
            let mut g = [0.0; 3];
            for p in 0..3 {
                for q in p..3 {
                    sc[p][q] = m22[p][q] - (m12[0][p] * y12[0][q] + m12[1][p] * y12[1][q] + m12[2][p] * y12[2][q]);
                    sc[q][p] = sc[p][q];
                }
                g[p] = f[p] - (m12[0][p] * ae[0] + m12[1][p] * ae[1] + m12[2][p] * ae[2]);
            }
            let s_inv = inv_sym3a(&sc).ok_or_else(singular)?;
            let mut ud = Vector3::zeros();
            for p in 0..3 {
                ud[p] = s_inv[p][0] * g[0] + s_inv[p][1] * g[1] + s_inv[p][2] * g[2];
            }
            let mut vd = Vector3::zeros();
            for p in 0..3 {
                vd[p] = ae[p] - (y12[p][0] * ud[0] + y12[p][1] * ud[1] + y12[p][2] * ud[2]);
            }
            (vd, ud)
        };
        let pd = r_mat * v; // (22)
        dy[0] = pd.x;
        dy[1] = pd.y;
        dy[2] = pd.z;
        // (23) as q' = q (0, u) / 2
        let qd = q * Quaternion::new(0.0, u.x, u.y, u.z) * 0.5;
        dy[3] = qd.w;
        dy[4] = qd.i;
        dy[5] = qd.j;
        dy[6] = qd.k;
        dy[7] = vd.x;
        dy[8] = vd.y;
        dy[9] = vd.z;
        dy[10] = ud.x;
        dy[11] = ud.y;
        dy[12] = ud.z;
        if !dy.iter().fold(0.0, |acc, x| acc + x * 0.0).is_finite() {
            return Err(Error::Integration {
                s,
                reason: "non-finite derivative".into(),
            });
        }
        Ok(())
    }

    /// Point loads on the body at an interior breakpoint `s` where strings
    /// are anchored. With `P` the total point force on the body,
    /// `n(s+) = n(s-) - P` and `m(s+) = m(s-) - sum r_i x P_i`, where a string
    /// ending at `s` contributes `P_i = -tau_i t_i(s-)` (it pulls toward the
    /// base), one starting at `s` contributes `+tau_i t_i(s+)`, and one passing
    /// `s` contributes `tau_i (t_i(s+) - t_i(s-))`: the strains jump at an
    /// anchor, so every string passing it has a kink there and presses on the
    /// body. `t(s+)` depends on the post-jump strains, so the jump is solved
    /// by Newton's method on the six strains (a 6x6 system; converges in a
    /// few iterations even where plain fixed-point iteration diverges).
    fn anchor_loads(&self, s: f64, y: &mut [f64]) -> Result<()> {
        let len = self.robot.body.length;
        let tol = 1e-12 * len;
        let v0 = Vector3::new(y[7], y[8], y[9]);
        let u0 = Vector3::new(y[10], y[11], y[12]);
        // (index, before-side weight, after-side weight): P_i = tau (a t+ - b t-)
        let mut terms: Vec<(usize, f64, f64)> = Vec::new();
        for (i, act) in self.robot.actuators.iter().enumerate() {
            if self.tensions[i] == 0.0 {
                continue;
            }
            let ends = (act.s_end - s).abs() <= tol;
            let starts = (act.s_start - s).abs() <= tol;
            let passes = act.s_start < s - tol && act.s_end > s + tol;
            let before = if ends || passes { 1.0 } else { 0.0 };
            let after = if starts || passes { 1.0 } else { 0.0 };
            if before != 0.0 || after != 0.0 {
                terms.push((i, before, after));
            }
        }
        if terms.is_empty() {
            return Ok(());
        }
        let tangent = |i: usize, v: &Vector3<f64>, u: &Vector3<f64>| -> (Vector3<f64>, Vector3<f64>) {
            let (pb, r) = self.pb(i, s, v, u);
            (pb / pb.norm(), r)
        };
        // explicit part (from s-)
        let mut f_minus = Vector3::zeros();
        let mut m_minus = Vector3::zeros();
        for &(i, b, _) in &terms {
            if b != 0.0 {
                let (t, r) = tangent(i, &v0, &u0);
                let p = t * (-b * self.tensions[i]);
                f_minus += p;
                m_minus += r.cross(&p);
            }
        }
        // residual of the jump for post-jump strains w = (v, u)
        let resid = |w: &nalgebra::Vector6<f64>| -> nalgebra::Vector6<f64> {
            let v = Vector3::new(w[0], w[1], w[2]);
            let u = Vector3::new(w[3], w[4], w[5]);
            let mut f = f_minus;
            let mut m = m_minus;
            for &(i, _, a) in &terms {
                if a != 0.0 {
                    let (t, r) = tangent(i, &v, &u);
                    let p = t * (a * self.tensions[i]);
                    f += p;
                    m += r.cross(&p);
                }
            }
            let dv = v - v0 + self.kse_inv.component_mul(&f);
            let du = (u - u0 + self.kbt_inv.component_mul(&m)) * len;
            nalgebra::Vector6::new(dv.x, dv.y, dv.z, du.x, du.y, du.z)
        };
        let mut w = nalgebra::Vector6::new(v0.x, v0.y, v0.z, u0.x, u0.y, u0.z);
        let mut r = resid(&w);
        let mut done = false;
        for _ in 0..50 {
            if r.amax() < 1e-14 {
                done = true;
                break;
            }
            let mut jac = nalgebra::Matrix6::zeros();
            for k in 0..6 {
                let scale = if k < 3 { 1.0 } else { 1.0 / len };
                let h = 1e-8 * w[k].abs().max(scale);
                let mut wp = w;
                wp[k] += h;
                jac.set_column(k, &((resid(&wp) - r) / h));
            }
            let dw = jac.lu().solve(&(-r)).ok_or_else(|| Error::Integration {
                s,
                reason: "singular anchor-load system".into(),
            })?;
            // backtrack if the full step does not reduce the residual
            let mut t = 1.0;
            loop {
                let wt = w + dw * t;
                let rt = resid(&wt);
                if rt.amax() < r.amax() || t < 1e-4 {
                    w = wt;
                    r = rt;
                    break;
                }
                t *= 0.5;
            }
        }
        if !done && r.amax() > 1e-12 {
            return Err(Error::Integration {
                s,
                reason: format!("anchor loads did not converge (residual {:.3e})", r.amax()),
            });
        }
        if w.iter().any(|x| !x.is_finite()) {
            return Err(Error::Integration {
                s,
                reason: "non-finite strains after anchor loads".into(),
            });
        }
        y[7..10].copy_from_slice(&[w[0], w[1], w[2]]);
        y[10..13].copy_from_slice(&[w[3], w[4], w[5]]);
        Ok(())
    }

}

/// States held on the stack by [`integrate`] (13 + up to 19 actuators).
const STACK_STATES: usize = 32;

/// `out = y + h k`, elementwise.
#[inline(always)]
fn axpy(out: &mut [f64], y: &[f64], h: f64, k: &[f64]) {
    for ((o, a), b) in out.iter_mut().zip(y).zip(k) {
        *o = a + h * b;
    }
}

/// Integrate the rod from the base with unknown initial strains `v0`, `u0`
/// (eqs 22-25), by fixed-step RK4 on a grid that has a node at every actuator
/// anchor. Actuator elongations start at zero at their proximal anchors.
pub fn integrate(spec: &IvpSpec<'_>, v0: &Vector3<f64>, u0: &Vector3<f64>, record: bool) -> Result<IvpResult> {
    let robot = spec.robot;
    let body = &robot.body;
    let (kse, kbt) = body.stiffness();
    let fz = Frozen::new(robot, spec.tensions);
    let na = robot.actuators.len();
    let n = robot.n_states();
    let len = body.length;
    let steps = spec.steps.max(1);
    // state and RK4 stages on the stack for up to STACK_STATES states (no
    // allocation per IVP; cheap IVPs of coarse grids are dominated by it)
    let mut stack = [0.0f64; 6 * STACK_STATES];
    let mut heap: Vec<f64>;
    let all: &mut [f64] = if n <= STACK_STATES {
        &mut stack[..6 * n]
    } else {
        heap = vec![0.0; 6 * n];
        &mut heap
    };
    let (y, rest) = all.split_at_mut(n);
    let (k1, rest) = rest.split_at_mut(n);
    let (k2, rest) = rest.split_at_mut(n);
    let (k3, rest) = rest.split_at_mut(n);
    let (k4, yt) = rest.split_at_mut(n);
    y[3] = 1.0;
    y[7..10].copy_from_slice(v0.as_slice());
    y[10..13].copy_from_slice(u0.as_slice());
    let bps = robot.breakpoints();
    let tol = 1e-12 * len;
    let mut nodes = Vec::new();
    let mut elongation = vec![0.0; na];
    let mut active: Vec<usize> = Vec::with_capacity(na);
    for w in bps.windows(2) {
        let (a, b) = (w[0], w[1]);
        // anchors at `a`: record the elongation of strings ending here, then
        // apply all anchor and kink loads at `a` together
        if a > 0.0 {
            let mut any = false;
            for i in 0..na {
                let act = &robot.actuators[i];
                if (act.s_end - a).abs() <= tol {
                    elongation[i] = y[BASE_STATES + i];
                    any = true;
                }
                if (act.s_start - a).abs() <= tol {
                    any = true;
                }
            }
            if any {
                fz.anchor_loads(a, y)?;
            }
        }
        if record {
            nodes.push((a, RodState::from_slice(y)));
        }
        active.clear();
        for (i, act) in robot.actuators.iter().enumerate() {
            if act.s_start <= a + tol && act.s_end >= b - tol {
                active.push(i);
            }
        }
        let m = (((b - a) / len) * steps as f64).round().max(1.0) as usize;
        let h = (b - a) / m as f64;
        let (h2, h6) = (0.5 * h, h / 6.0);
        for k in 0..m {
            let s = a + k as f64 * h;
            fz.deriv(s, y, &active, k1)?;
            axpy(yt, y, h2, k1);
            fz.deriv(s + h2, yt, &active, k2)?;
            axpy(yt, y, h2, k2);
            fz.deriv(s + h2, yt, &active, k3)?;
            axpy(yt, y, h, k3);
            fz.deriv(s + h, yt, &active, k4)?;
            for ((((yj, a), b), c), d) in y.iter_mut().zip(k1.iter()).zip(k2.iter()).zip(k3.iter()).zip(k4.iter()) {
                *yj += h6 * (a + 2.0 * (b + c) + d);
            }
            let qn = (y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]).sqrt();
            for yq in &mut y[3..7] {
                *yq /= qn;
            }
            if record && k + 1 < m {
                nodes.push((s + h, RodState::from_slice(y)));
            }
        }
    }
    // tip: actuators anchored at the tip close the balance (32)-(33)
    let v = Vector3::new(y[7], y[8], y[9]);
    let u = Vector3::new(y[10], y[11], y[12]);
    let q = Quaternion::new(y[3], y[4], y[5], y[6]);
    let rt = rot(&q).transpose();
    let mut rf = kse * (v - body.nu_star) - rt * spec.tip_force;
    let mut rm = kbt * (u - body.omega_star) - rt * spec.tip_moment;
    for i in 0..na {
        let act = &robot.actuators[i];
        if (act.s_end - len).abs() <= tol {
            elongation[i] = y[BASE_STATES + i];
            let (pb, r) = fz.pb(i, len, &v, &u);
            let t = pb / pb.norm();
            let tau = spec.tensions[i];
            rf += t * tau;
            rm += r.cross(&t) * tau;
        }
    }
    let tip = RodState::from_slice(y);
    if record {
        nodes.push((len, tip.clone()));
    }
    Ok(IvpResult {
        tip,
        elongation,
        tip_force_residual: rf,
        tip_moment_residual: rm,
        nodes,
    })
}
