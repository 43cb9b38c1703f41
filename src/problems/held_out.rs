//! Named seeds of the design sets and the stress family of heavy bodies
//! (re-exported by [`crate::problems`]).
//!
//! # Seeds
//! A solver tuned on a set of designs is measured on that set too well. The
//! seeds are therefore split by use:
//!
//! * [`TUNING_SEED`] (= [`DEFAULT_SEED`]): the set the tests use and the one
//!   a solver may be tuned on (its failures and worst cases studied, its
//!   thresholds chosen on it).
//! * [`HELD_OUT_SEEDS`]: two sets for reporting only. No test uses them and
//!   no solver is tuned on them; a solver change is judged on them after it is made,
//!   and a result that holds on the tuning seed but not here is over-fitted.
//! * [`STRESS_SEED`]: the seed of [`stress_design`], the heavy-body family.
//!
//! # Stress family
//! [`stress_design`]`(seed, index)` draws, like [`random_design`], each
//! design from its own SplitMix64 stream, so a prefix of the set is the set
//! of a smaller `n`. Each body is soft and heavy: its weight ratio
//! `w = psi A |g| L^3 / (E I_min)` ([`weight_ratio`]) is drawn log-uniform in
//! [`STRESS_WEIGHT_RATIO`] = `[20, 3000]`, beyond the random designs' cap
//! ([`MAX_WEIGHT_RATIO`]) and past upright self-weight buckling
//! ([`SELF_WEIGHT_BUCKLING`], 7.837) for every `w`. The geometry is drawn
//! first and the modulus set from `w`:
//!
//! * length 50-500 mm (log-uniform), slenderness `L / width` 10-100
//!   (log-uniform), width clamped to 2-50 mm, circle or rectangle (aspect
//!   0.5-2), density 950-1250 kg/m^3, Poisson's ratio 0.45-0.5;
//! * `E = psi A |g| L^3 / (w I_min)`, kept in [`STRESS_MODULUS`] =
//!   1 kPa-10 MPa (a soft gel to a stiff elastomer): a geometry whose `E`
//!   falls outside is redrawn with the same `w`, so `w` stays log-uniform.
//!
//! The orientation ([`Orientation`]) is the design index mod 3, so every
//! prefix of the set is balanced: hanging (gravity along `+z` of the base
//! frame, the body hanging from its base), upright (gravity along `-z`,
//! standing on its base, past self-weight buckling) and horizontal (gravity
//! perpendicular to the base axis, at a uniform azimuth). Gravity is then
//! tilted by 1-5 degrees (a hanging or upright body's toward a uniform
//! horizontal direction, a horizontal body's up or down), so that no design
//! has gravity exactly along or across its axis (an upright column with
//! axial gravity sits on a bifurcation). Half of the
//! designs carry tip loads (a force up to `1.5 E I / L^2` and a moment up to
//! `E I / L`, uniform directions); the 1-4 actuators are drawn as
//! [`random_design`] draws them.

use nalgebra::Vector3;

use super::{
    draw_section, weight_ratio_of as ratio_of, with_actuators, BodyDraw, Design, SplitMix64,
    DEFAULT_SEED, GRAVITY,
};
#[cfg(doc)]
use super::{random_design, MAX_WEIGHT_RATIO, SELF_WEIGHT_BUCKLING};
use crate::rod::{Body, Section};

/// The seed a solver may be tuned on and the tests use ([`DEFAULT_SEED`]).
pub const TUNING_SEED: u64 = DEFAULT_SEED;

/// Seeds for reporting only: never used by a test or while tuning a solver
/// (see the module docs).
pub const HELD_OUT_SEEDS: [u64; 2] = [0x4e1d_0a7b_93c5_2f61, 0xb2f8_6c04_d17e_5a39];

/// Seed of the stress family ([`stress_design`]).
pub const STRESS_SEED: u64 = 0x57e5_5f0a_3c29_d6b4;

/// Range of the stress family's weight ratio `psi A |g| L^3 / (E I_min)`.
pub const STRESS_WEIGHT_RATIO: (f64, f64) = (20.0, 3000.0);

/// Range of the stress family's Young's modulus \[Pa\].
pub const STRESS_MODULUS: (f64, f64) = (1e3, 10e6);

/// Largest tilt of the stress family's gravity off its orientation \[deg\].
const MAX_TILT_DEG: f64 = 5.0;

/// Smallest tilt \[deg\] (no design exactly on its symmetric orientation).
const MIN_TILT_DEG: f64 = 1.0;

/// How gravity acts on a body relative to its base axis (`+z`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Orientation {
    /// Gravity along `+z`: the body hangs from its base (in tension).
    Hanging,
    /// Gravity along `-z`: the body stands on its base (in compression).
    Upright,
    /// Gravity perpendicular to the base axis: the body is a cantilever.
    Horizontal,
}

impl Orientation {
    /// All three, in the order the stress family cycles through them.
    pub const ALL: [Orientation; 3] = [
        Orientation::Hanging,
        Orientation::Upright,
        Orientation::Horizontal,
    ];

    /// The orientation nearest to `body`'s gravity (angle to the base axis
    /// under 45 degrees: hanging, over 135: upright, else horizontal);
    /// `None` without gravity.
    pub fn of(body: &Body) -> Option<Orientation> {
        let g = body.gravity.norm();
        if g == 0.0 {
            return None;
        }
        let c = body.gravity.z / g;
        let half = std::f64::consts::FRAC_1_SQRT_2;
        Some(if c > half {
            Orientation::Hanging
        } else if c < -half {
            Orientation::Upright
        } else {
            Orientation::Horizontal
        })
    }

    /// Lower-case name (`hanging`, `upright`, `horizontal`).
    pub fn name(self) -> &'static str {
        match self {
            Orientation::Hanging => "hanging",
            Orientation::Upright => "upright",
            Orientation::Horizontal => "horizontal",
        }
    }
}

/// `psi A |g| L^3 / (E I_min)` of `body`, whatever the direction of its
/// gravity (the stress family's weight ratio).
pub fn weight_ratio(body: &Body) -> f64 {
    let (a, ..) = body.section.properties();
    body.density * a * body.gravity.norm() * body.length.powi(3) / body.bending_stiffness()
}

/// Design `index` of the stress family `seed`: see the module docs.
/// Deterministic.
pub fn stress_design(seed: u64, index: usize) -> Design {
    // one stream per design, mixed differently from `random_design`'s so
    // that a seed shared by both families gives unrelated streams
    let mut mix = SplitMix64::new(seed ^ (index as u64).wrapping_mul(0x8cb9_2ba7_2f3d_8dd7));
    mix.next_u64();
    let mut rng = SplitMix64::new(mix.next_u64());
    let (lo, hi) = STRESS_WEIGHT_RATIO;
    let w = rng.log_range(lo, hi);
    let orientation = Orientation::ALL[index % 3];
    let gravity = tilted_gravity(&mut rng, orientation);
    loop {
        if let Some(d) = try_stress(&mut rng, index, w, gravity) {
            return d;
        }
    }
}

/// The first `n` designs of the stress family `seed`.
pub fn stress_designs(seed: u64, n: usize) -> Vec<Design> {
    (0..n).map(|i| stress_design(seed, i)).collect()
}

/// Gravity \[m/s^2\] of `orientation`, tilted by 1-5 degrees: a hanging or
/// upright body's toward a uniform horizontal direction, a horizontal body's
/// up or down (even odds) out of the horizontal plane.
fn tilted_gravity(rng: &mut SplitMix64, orientation: Orientation) -> Vector3<f64> {
    let phi = rng.range(0.0, 2.0 * std::f64::consts::PI);
    let horizontal = Vector3::new(phi.cos(), phi.sin(), 0.0);
    let (axis, across) = match orientation {
        Orientation::Hanging => (Vector3::z(), horizontal),
        Orientation::Upright => (-Vector3::z(), horizontal),
        Orientation::Horizontal => {
            let up = if rng.chance(0.5) { 1.0 } else { -1.0 };
            (horizontal, Vector3::z() * up)
        }
    };
    let tilt = rng.range(MIN_TILT_DEG, MAX_TILT_DEG).to_radians();
    (axis * tilt.cos() + across * tilt.sin()) * GRAVITY
}

/// One attempt at a stress body of weight ratio `w` under `gravity`, with
/// its actuators; `None` when the modulus falls outside [`STRESS_MODULUS`]
/// or an actuator does not fit.
fn try_stress(rng: &mut SplitMix64, index: usize, w: f64, gravity: Vector3<f64>) -> Option<Design> {
    let length = rng.log_range(0.050, 0.500);
    let poisson = rng.range(0.45, 0.5);
    let density = rng.range(950.0, 1250.0);
    let width = (length / rng.log_range(10.0, 100.0)).clamp(2e-3, 50e-3);
    let section = draw_section(rng, width);
    // the ratio at E = 1 Pa over w: the modulus that gives ratio w
    let e = ratio_of(density, &section, length, 1.0) / w;
    if !(STRESS_MODULUS.0..=STRESS_MODULUS.1).contains(&e) {
        return None;
    }
    let mut body = Body::new(length, section, e, poisson, density).ok()?;
    body.gravity = gravity;
    let (_, ix, iy, _) = section.properties();
    let ei = e * ix.min(iy);
    if rng.chance(0.5) {
        body.tip_force = rng.unit_vector() * rng.range(0.0, 1.5) * ei / (length * length);
        body.tip_moment = rng.unit_vector() * rng.range(0.0, 1.0) * ei / length;
    }
    let half_min = 0.5
        * match section {
            Section::Circle { diameter } => diameter,
            Section::Rectangle { width, height } => width.min(height),
            Section::Custom { .. } => unreachable!("the family draws circles and rectangles"),
        };
    let draw = BodyDraw {
        length,
        e,
        ei,
        section,
        half_min,
    };
    with_actuators(rng, index, body, &draw)
}

#[cfg(test)]
mod tests {
    use super::*;

    const N: usize = 60;

    #[test]
    fn stress_weight_ratio_and_modulus_in_range() {
        for d in stress_designs(STRESS_SEED, N) {
            let b = &d.robot.body;
            let w = weight_ratio(b);
            let (lo, hi) = STRESS_WEIGHT_RATIO;
            // w is set by the modulus: equal to the drawn value up to rounding
            assert!(
                (lo * (1.0 - 1e-12)..=hi * (1.0 + 1e-12)).contains(&w),
                "#{}: w {w}",
                d.index
            );
            assert!((STRESS_MODULUS.0..=STRESS_MODULUS.1).contains(&b.youngs_modulus));
            assert!((0.05..=0.5).contains(&b.length));
            assert!(d.past_buckling() || Orientation::of(b) != Some(Orientation::Upright));
            assert!((1..=4).contains(&d.robot.actuators.len()));
            assert_eq!(d.inputs.len(), d.robot.actuators.len());
        }
    }

    #[test]
    fn stress_orientations_all_occur_tilted() {
        let mut seen = [0usize; 3];
        for d in stress_designs(STRESS_SEED, N) {
            let o = Orientation::of(&d.robot.body).expect("every stress design has gravity");
            assert_eq!(o, Orientation::ALL[d.index % 3]);
            seen[d.index % 3] += 1;
            // the tilt off the orientation's axis (or off the horizontal plane)
            let g = d.robot.body.gravity / GRAVITY;
            let off = match o {
                Orientation::Horizontal => g.z.abs().asin(),
                _ => g.z.abs().acos(),
            }
            .to_degrees();
            assert!(
                (MIN_TILT_DEG - 1e-9..=MAX_TILT_DEG + 1e-9).contains(&off),
                "{o:?} {off}"
            );
        }
        assert_eq!(seen, [N / 3; 3]);
    }

    #[test]
    fn stress_design_is_deterministic_per_seed_and_index() {
        for i in [0, 7, 31] {
            let (a, b) = (stress_design(STRESS_SEED, i), stress_design(STRESS_SEED, i));
            assert_eq!(a.summary(), b.summary());
            assert_eq!(a.inputs, b.inputs);
            assert_eq!(a.robot.body.gravity, b.robot.body.gravity);
        }
        // another index or seed draws another design
        let length = |d: Design| d.robot.body.length;
        let a = length(stress_design(STRESS_SEED, 3));
        assert_ne!(a, length(stress_design(STRESS_SEED, 4)));
        assert_ne!(a, length(stress_design(HELD_OUT_SEEDS[0], 3)));
    }

    #[test]
    fn seeds_are_distinct() {
        let all = [
            TUNING_SEED,
            HELD_OUT_SEEDS[0],
            HELD_OUT_SEEDS[1],
            STRESS_SEED,
        ];
        for (i, a) in all.iter().enumerate() {
            assert!(all[i + 1..].iter().all(|b| a != b));
        }
    }
}
