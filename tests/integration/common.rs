//! Constants, builders and comparisons shared by the integration test modules
//! (a module pulls them in with `use crate::common;`). The paper's fixtures
//! themselves come from the core (`tcarod::experiments`, `tcarod::problems`).
#![allow(dead_code)]

use std::sync::Arc;

use nalgebra::Vector3;
use tcarod::experiments::{manipulator_tca, MANIPULATOR_TURNS, TURNS_ANCHOR_LENGTH};
use tcarod::rod::{Actuator, Body, ConstantTension, Robot, Routing, Section, TcaLaw};
use tcarod::shooting::{solve, Solution, SolveOptions};
use tcarod::Tca;

/// Body length \[m\] of the paper's manipulators.
pub const LENGTH: f64 = 0.04;
/// Fig. 6 circle diameter \[m\].
pub const DIAMETER: f64 = 8e-3;
/// EcoFlex 10 Young's modulus \[Pa\] (Section V).
pub const E_B: f64 = 37.8e3;

/// A weightless straight EcoFlex rod of the Fig. 6 circle's section.
pub fn weightless_body() -> Body {
    Body::new(
        LENGTH,
        Section::Circle { diameter: DIAMETER },
        E_B,
        0.5,
        0.0,
    )
    .unwrap()
}

/// A constant-tension tendon from `s_start` to `s_end` \[m\].
pub fn tendon(routing: Routing, s_start: f64, s_end: f64) -> Actuator {
    Actuator::new(routing, s_start, s_end, Arc::new(ConstantTension))
}

/// A TCA actuator from `s_start` to `s_end` \[m\].
pub fn tca_actuator(tca: Tca, routing: Routing, s_start: f64, s_end: f64) -> Actuator {
    Actuator::new(routing, s_start, s_end, Arc::new(TcaLaw(tca)))
}

/// The paper's manipulator TCA cut to a span \[m\], twist per length kept
/// (76.4 turns per 40 mm; a TCA may not be longer than its span).
pub fn span_tca(span: f64) -> Tca {
    manipulator_tca(span, MANIPULATOR_TURNS * span / TURNS_ANCHOR_LENGTH)
}

/// Solve with the default options from the reference guess.
pub fn solve_default(robot: &Robot, inputs: &[f64]) -> Solution {
    solve(robot, inputs, &SolveOptions::default(), None).unwrap()
}

/// Largest absolute difference of two vector lists.
pub fn max_diff(a: &[nalgebra::Vector3<f64>], b: &[nalgebra::Vector3<f64>]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).amax())
        .fold(0.0, f64::max)
}

/// An upright 10 x 9 mm rectangular column with gravity `-z`, scaled so
/// that the gravity parameter equals rho A g L^3 / EI (weak axis). Not
/// round: a round (or square) column's buckled shapes form a circle of
/// equilibria turned about the vertical (a neutral mode), along which a
/// path cannot be continued uniquely; the verdict of such a column is tested
/// in `stability.rs`, `euler_column_*`.
pub fn heavy_column() -> Robot {
    let mut b = Body::new(
        0.5,
        Section::Rectangle {
            width: 10e-3,
            height: 9e-3,
        },
        1e6,
        0.5,
        1000.0,
    )
    .unwrap();
    let (a, ix, iy, _) = b.section.properties();
    let g0 = b.youngs_modulus * ix.min(iy) / (b.density * a * 0.125);
    b.gravity = Vector3::new(0.0, 0.0, -g0);
    Robot::new(b, vec![]).unwrap()
}
