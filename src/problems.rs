//! Test problems shared by the tests and the benches: a seeded
//! generator of random, physically valid designs, a classifier for bodies past
//! self-weight buckling, and a global equilibrium check of a converged
//! solution.
//!
//! # Random designs
//! [`random_design`]`(seed, index)` draws design `index` from its own stream
//! (SplitMix64 seeded by `seed` mixed with `index`), so the set is the same on
//! every machine and a subset of the first `n` designs is a prefix of any
//! larger set. Each design is a soft body (10 kPa-10 MPa, 10-300 mm long,
//! circle or rectangle, never pre-curved) with 1-4 actuators mixing TCAs
//! ([`Tca`] of the default material, extension or contraction), constant-tension
//! tendons and linear tendons, on straight or helical routings, anchored at the
//! base/tip or inside the body; gravity (9.81 m/s^2) in any direction in 80 %
//! of the designs; tip forces and moments in half of them. Tendon inputs are
//! set for tip rotations up to ~3 rad, so large deflections are common.
//!
//! Bodies too floppy to be a robot, `psi A |g| L^3 / (E I) > 50` (a noodle that
//! sags to the floor under its own weight whatever its orientation), are
//! rejected and redrawn; about one upright design in ten is then past
//! self-weight buckling (7.837).
//!
//! # Seeds and the stress family
//! [`TUNING_SEED`] (the tests' set, the one a solver may be tuned on),
//! [`HELD_OUT_SEEDS`] (for reporting only, never used by a test or while
//! tuning) and [`STRESS_SEED`] name the sets; [`stress_design`] draws heavy
//! soft bodies (weight ratio 20-3000) hanging, upright or horizontal. See
//! [`held_out`].
//!
//! # Global equilibrium
//! The robot (body plus actuators) is held by the base only. The base takes
//! the body's cross-section wrench `n(0)`, `m(0)` and the pull `tau_i t_i(0)`
//! of every actuator anchored to the base (`s_start = 0`). Every other force
//! between an actuator and the body is internal to the robot: a string whose
//! both anchors are on the body pulls each anchor toward the other and presses
//! on the body along its curved path by `tau t_a'` per unit length (eqs
//! 14-15), and these sum to zero force and moment, as for any string in
//! equilibrium under its end and contact forces. So
//!
//! ```text
//! n(0) + sum_{s_start = 0} tau_i t_i(0)                  = int (psi A g + f) ds + F_tip
//! m(0) + sum_{s_start = 0} (p(0) + R(0) r_i(0)) x tau_i t_i(0)
//!                      = int p x (psi A g + f) ds + int l ds + p(L) x F_tip + M_tip
//! ```
//!
//! (moments about the base origin, `p(0) = 0`). The left side is
//! `Solution.base_force` / `base_moment`; [`equilibrium`] recomputes it
//! from the body's base wrench and the actuators' base anchor loads. Checked
//! numerically in the unit tests: one tendon, no gravity, no tip load gives a
//! zero base wrench while `n(0) = -tau t(0)` (base anchor) or `n(0) = 0`
//! (both anchors inside the body).

use std::f64::consts::PI;
use std::sync::Arc;

use nalgebra::Vector3;

use crate::material::Material;
use crate::rod::{Actuator, Body, ConstantTension, LinearTendon, Robot, Routing, Section, TcaLaw};
use crate::tca::{Chirality, Tca};

/// Seed of the benchmark set (`benches/designs.rs`,
/// `tests/integration/designs.rs`).
pub const DEFAULT_SEED: u64 = 0x7ca5_0d10_2026_0010;

pub mod held_out;
pub mod nonlinear;
pub mod paths;
pub use held_out::{
    stress_design, stress_designs, weight_ratio, Orientation, HELD_OUT_SEEDS, STRESS_MODULUS,
    STRESS_SEED, STRESS_WEIGHT_RATIO, TUNING_SEED,
};

/// Critical `psi A g L^3 / (E I)` of an upright clamped-free column buckling
/// under its own weight (Greenhill: `(7.837 E I / (psi A g))^(1/3)`).
pub const SELF_WEIGHT_BUCKLING: f64 = 7.837;

/// Largest `psi A |g| L^3 / (E I)` the generator accepts (see the module docs).
pub const MAX_WEIGHT_RATIO: f64 = 50.0;

/// Standard gravity [m/s^2] of the random designs (the paper's `G0`).
pub const GRAVITY: f64 = crate::experiments::G0;

/// SplitMix64 (Steele, Lea and Flood 2014): a 64-bit generator with a
/// one-word state, written out so that the designs do not depend on an
/// external crate's version.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }
    /// Next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in `[0, 1)` (53 random bits).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in `[a, b)`.
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.uniform()
    }
    /// Log-uniform in `[a, b)`, `0 < a < b`.
    pub fn log_range(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.uniform()).exp()
    }
    /// Uniform integer in `0..n`.
    pub fn below(&mut self, n: usize) -> usize {
        ((self.uniform() * n as f64) as usize).min(n - 1)
    }
    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.uniform() < p
    }
    /// Uniform direction on the unit sphere.
    pub fn unit_vector(&mut self) -> Vector3<f64> {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, 2.0 * PI);
        let rho = (1.0 - z * z).sqrt();
        Vector3::new(rho * phi.cos(), rho * phi.sin(), z)
    }
}

/// Kind of a random design's actuator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ActuatorKind {
    /// A TCA (input: temperature \[C\]).
    Tca,
    /// A tendon at a given tension (input: tension \[N\]).
    ConstantTension,
    /// A linear tendon under displacement control (input: pull \[m\]).
    LinearTendon,
}

/// One random design: the robot (tip loads in its body) and the inputs to
/// solve at.
#[derive(Debug, Clone)]
pub struct Design {
    /// Index in its set.
    pub index: usize,
    /// The robot; `body.tip_force` / `tip_moment` hold the tip loads.
    pub robot: Robot,
    /// One input per actuator (temperature \[C\], tension \[N\] or pull \[m\]).
    pub inputs: Vec<f64>,
    /// Kind of each actuator.
    pub kinds: Vec<ActuatorKind>,
}

impl Design {
    /// [`column_ratio`] of the body.
    pub fn column_ratio(&self) -> f64 {
        column_ratio(&self.robot.body)
    }
    /// [`past_self_weight_buckling`] of the body.
    pub fn past_buckling(&self) -> bool {
        past_self_weight_buckling(&self.robot.body)
    }
    /// One-line summary (sizes in mm, modulus in kPa).
    pub fn summary(&self) -> String {
        let b = &self.robot.body;
        let sec = match b.section {
            Section::Circle { diameter } => format!("circle {:.1} mm", diameter * 1e3),
            Section::Rectangle { width, height } => {
                format!("rect {:.1}x{:.1} mm", width * 1e3, height * 1e3)
            }
            Section::Custom { .. } => "custom".into(),
        };
        let acts: Vec<String> = self
            .robot
            .actuators
            .iter()
            .zip(&self.kinds)
            .zip(&self.inputs)
            .map(|((a, k), x)| {
                let route = a.routing.kind();
                format!(
                    "{k:?} {route} [{:.0},{:.0}] mm @ {x:.4e}",
                    a.s_start * 1e3,
                    a.s_end * 1e3
                )
            })
            .collect();
        format!(
            "#{} L {:.1} mm, {sec}, E {:.3} kPa, g ({:.2},{:.2},{:.2}), tip F ({:.2e},{:.2e},{:.2e}) N, column ratio {:.2}; {}",
            self.index,
            b.length * 1e3,
            b.youngs_modulus * 1e-3,
            b.gravity.x,
            b.gravity.y,
            b.gravity.z,
            b.tip_force.x,
            b.tip_force.y,
            b.tip_force.z,
            self.column_ratio(),
            acts.join("; ")
        )
    }
}

/// `psi A g_a L^3 / (E I_min)` of the body in its reference (straight,
/// base tangent `+z`) configuration, where `g_a = max(0, -g_z)` is the
/// component of gravity pointing from the tip toward the base, the part that
/// compresses an upright column.
///
/// Inclined gravity: only this axial component is counted. The transverse
/// component bends the column from the start (an imperfect column: no
/// bifurcation, but past the critical axial load the leaning shape is no
/// longer the only equilibrium, and a cold solve from the straight guess may
/// land on any of them); a hanging body (`g_z > 0`) is in tension and has
/// ratio 0.
pub fn column_ratio(body: &Body) -> f64 {
    let (a, ..) = body.section.properties();
    let g_axial = (-body.gravity.z).max(0.0);
    body.density * a * g_axial * body.length.powi(3) / body.bending_stiffness()
}

/// Whether the body, upright, is past self-weight buckling:
/// [`column_ratio`] `>` [`SELF_WEIGHT_BUCKLING`].
pub fn past_self_weight_buckling(body: &Body) -> bool {
    column_ratio(body) > SELF_WEIGHT_BUCKLING
}

/// An upright column of `body` (clamped at the base, free at the tip, no
/// actuators) under `factor` times its self-weight buckling load: gravity
/// along `-z` scaled so that [`column_ratio`] is `factor`
/// [`SELF_WEIGHT_BUCKLING`]. `body.density` must be positive.
pub fn overloaded_column(mut body: Body, factor: f64) -> Robot {
    let (a, ..) = body.section.properties();
    let g = factor * SELF_WEIGHT_BUCKLING * body.bending_stiffness()
        / (body.density * a * body.length.powi(3));
    body.gravity = Vector3::new(0.0, 0.0, -g);
    Robot::new(body, vec![]).expect("a body without actuators is a valid robot")
}

/// `psi A |g| L^3 / (E I_min)` whatever the direction of gravity.
fn weight_ratio_of(density: f64, section: &Section, length: f64, e: f64) -> f64 {
    let (a, ix, iy, _) = section.properties();
    density * a * GRAVITY * length.powi(3) / (e * ix.min(iy))
}

/// Design `index` of the set `seed`: see the module docs. Deterministic.
pub fn random_design(seed: u64, index: usize) -> Design {
    // one stream per design: mix the index into the seed through SplitMix64
    let mut mix = SplitMix64::new(seed ^ (index as u64).wrapping_mul(0xd1b5_4a32_d192_ed03));
    let mut rng = SplitMix64::new(mix.next_u64());
    loop {
        if let Some(d) = try_design(&mut rng, index) {
            return d;
        }
    }
}

/// The first `n` designs of the set `seed`.
pub fn random_designs(seed: u64, n: usize) -> Vec<Design> {
    (0..n).map(|i| random_design(seed, i)).collect()
}

/// One attempt; `None` when the draw is rejected (too floppy, or an actuator
/// that does not fit).
fn try_design(rng: &mut SplitMix64, index: usize) -> Option<Design> {
    let (body, draw) = draw_body(rng)?;
    with_actuators(rng, index, body, &draw)
}

/// The design `index` of a drawn body: 1-4 actuators drawn on it (one draw
/// for every family of designs); `None` when an actuator does not fit.
fn with_actuators(
    rng: &mut SplitMix64,
    index: usize,
    body: Body,
    draw: &BodyDraw,
) -> Option<Design> {
    let n_act = 1 + rng.below(4);
    let mut actuators = Vec::with_capacity(n_act);
    let mut inputs = Vec::with_capacity(n_act);
    let mut kinds = Vec::with_capacity(n_act);
    for _ in 0..n_act {
        let (act, input, kind) = draw_actuator(rng, draw, n_act)?;
        actuators.push(act);
        inputs.push(input);
        kinds.push(kind);
    }
    let robot = Robot::new(body, actuators).ok()?;
    robot.check_inputs(&inputs).ok()?;
    Some(Design {
        index,
        robot,
        inputs,
        kinds,
    })
}

/// Sizes of a drawn body that its actuators' draws need.
#[derive(Debug, Clone, Copy)]
struct BodyDraw {
    length: f64,
    e: f64,
    ei: f64,
    section: Section,
    half_min: f64,
}

/// A circle of diameter `width` or, as often, a rectangle of the same
/// geometric-mean side with aspect ratio 0.5-2 (log-uniform).
fn draw_section(rng: &mut SplitMix64, width: f64) -> Section {
    if rng.chance(0.5) {
        Section::Circle { diameter: width }
    } else {
        let aspect = rng.log_range(0.5, 2.0);
        Section::Rectangle {
            width: width * aspect.sqrt(),
            height: width / aspect.sqrt(),
        }
    }
}

/// The body of one attempt (sizes, material, gravity, tip loads); `None`
/// when rejected as too floppy.
fn draw_body(rng: &mut SplitMix64) -> Option<(Body, BodyDraw)> {
    let length = rng.log_range(0.010, 0.300);
    let e = rng.log_range(10e3, 10e6);
    let poisson = rng.range(0.45, 0.5);
    let density = rng.range(950.0, 1250.0);
    // slenderness L / (characteristic width) in [3, 40]
    let width = (length / rng.log_range(3.0, 40.0)).clamp(2e-3, 60e-3);
    let section = draw_section(rng, width);
    if weight_ratio_of(density, &section, length, e) > MAX_WEIGHT_RATIO {
        return None;
    }
    let mut body = Body::new(length, section, e, poisson, density).ok()?;
    let (_, ix, iy, _) = section.properties();
    let ei = e * ix.min(iy);
    if rng.chance(0.8) {
        body.gravity = rng.unit_vector() * GRAVITY;
    }
    if rng.chance(0.5) {
        // up to 1.5 E I / L^2 (below the Euler load 2.47 E I / L^2 even if axial)
        body.tip_force = rng.unit_vector() * rng.range(0.0, 1.5) * ei / (length * length);
    }
    if rng.chance(0.3) {
        body.tip_moment = rng.unit_vector() * rng.range(0.0, 1.0) * ei / length;
    }
    let half_min = 0.5
        * match section {
            Section::Circle { diameter } => diameter,
            Section::Rectangle { width, height } => width.min(height),
            Section::Custom { .. } => unreachable!(),
        };
    Some((
        body,
        BodyDraw {
            length,
            e,
            ei,
            section,
            half_min,
        },
    ))
}

/// One actuator of a body drawn by [`draw_body`] among `n_act`: the
/// actuator, its input and its kind; `None` when it does not fit.
fn draw_actuator(
    rng: &mut SplitMix64,
    b: &BodyDraw,
    n_act: usize,
) -> Option<(Actuator, f64, ActuatorKind)> {
    let BodyDraw {
        length,
        e,
        ei,
        section,
        half_min,
    } = *b;
    let kind = match rng.below(3) {
        0 => ActuatorKind::Tca,
        1 => ActuatorKind::ConstantTension,
        _ => ActuatorKind::LinearTendon,
    };
    // anchors: each inside the body with probability 0.4
    let s_start = if rng.chance(0.4) {
        rng.range(0.0, 0.5) * length
    } else {
        0.0
    };
    let s_end = if rng.chance(0.4) {
        rng.range(s_start / length + 0.2, 1.0) * length
    } else {
        length
    };
    let span = s_end - s_start;
    // the actuator's own radius: a TCA's coil, a tendon's sheath
    let own = match kind {
        ActuatorKind::Tca => rng.range(0.3e-3, 2.0e-3).min(0.4 * half_min) * 0.5,
        _ => 0.05 * half_min,
    };
    let routing = draw_routing(rng, &section, half_min, own, span);
    let offset = routing.distance();
    // tendon curvature: a tip rotation theta over the span, capped so that
    // the body's surface strain kappa * (half width) stays <= 0.3, and the
    // tension E I kappa / r capped at 0.2 E A / (actuators): the body
    // must not be crushed axially (nu_z = 1 - tau / E A)
    let theta = rng.range(0.1, 3.0);
    let half_max = match section {
        Section::Rectangle { width, height } => 0.5 * width.max(height),
        _ => half_min,
    };
    let ea = e * section.properties().0;
    let kappa = (theta / span)
        .min(0.3 / half_max)
        .min(0.2 * ea / n_act as f64 * offset / ei);
    let (law, input) = draw_law(rng, kind, span, own, ei * kappa / offset, kappa, offset, ei)?;
    Some((Actuator::new(routing, s_start, s_end, law), input, kind))
}

/// The routing of a drawn actuator: a helix (probability 0.3) or a straight
/// line, inside the section less the actuator's own radius `own` \[m\].
fn draw_routing(
    rng: &mut SplitMix64,
    section: &Section,
    half_min: f64,
    own: f64,
    span: f64,
) -> Routing {
    if rng.chance(0.3) {
        let radius = rng.range(0.3, 0.85) * (half_min - own);
        let turns = rng.range(-1.5, 1.5);
        Routing::Helix {
            radius,
            rate: 2.0 * PI * turns / span,
            phase: rng.range(0.0, 2.0 * PI),
        }
    } else {
        let theta = rng.range(0.0, 2.0 * PI);
        let r = rng.range(0.3, 0.85) * (section.edge_distance(theta) - own);
        Routing::Straight {
            x: r * theta.cos(),
            y: r * theta.sin(),
        }
    }
}

/// The force law of a drawn actuator and its input: a TCA at 25-160 C, a
/// constant tension `tension` \[N\] (curvature `kappa` at offset `offset`),
/// or a linear tendon pulled to the same curvature.
#[allow(clippy::too_many_arguments)]
fn draw_law(
    rng: &mut SplitMix64,
    kind: ActuatorKind,
    span: f64,
    own: f64,
    tension: f64,
    kappa: f64,
    offset: f64,
    ei: f64,
) -> Option<(Arc<dyn crate::rod::ForceLaw>, f64)> {
    Some(match kind {
        ActuatorKind::Tca => {
            let chirality = if rng.chance(0.7) {
                Chirality::Extension
            } else {
                Chirality::Contraction
            };
            let alpha0 = rng.range(10.0, 20.0).to_radians();
            let turns = span * rng.range(1000.0, 2500.0);
            let tca = Tca::from_pitch_angle(
                span,
                alpha0,
                2.0 * own,
                turns,
                chirality,
                Material::silver_coated_nylon(),
            )
            .ok()?;
            (Arc::new(TcaLaw(tca)), rng.range(25.0, 160.0))
        }
        ActuatorKind::ConstantTension => (Arc::new(ConstantTension), tension),
        ActuatorKind::LinearTendon => {
            // stiffness k against the bending stiffness seen at the tendon,
            // E I / (r^2 span); pull for curvature kappa:
            // k (pull - kappa r span) = E I kappa / r
            let k_body = ei / (offset * offset * span);
            let k = rng.log_range(1.0, 100.0) * k_body;
            let pull = tension / k + kappa * offset * span;
            (Arc::new(LinearTendon { stiffness: k }), pull)
        }
    })
}

pub use crate::solve::equilibrium::{equilibrium, position_integral, Equilibrium, EQUILIBRIUM_TOL};
