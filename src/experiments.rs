//! The paper's experiments (Section V) as test problems, shared by the unit
//! tests and the criterion benches. The Python package's
//! `tcarod.experiments` holds the same fixtures with their published data.

use crate::material::Material;
use crate::tca::{Chirality, Tca};

/// Fig. 5 TCA, `threads` = 3 or 4 (NOTES.md section 1: `l` and `L` swapped in
/// the paper's text; `L = 110 mm` coiled, `l = 497 / 471 mm` fibre).
pub fn fig5_tca(threads: u32) -> Tca {
    let (l, turns, d) = match threads {
        3 => (0.497, 300.0, 2.0e-3),
        4 => (0.471, 259.0, 2.13e-3),
        _ => panic!("Fig. 5 has three- and four-thread TCAs only"),
    };
    Tca::new(l, 0.110, d, turns, Chirality::Extension, Material::silver_coated_nylon())
        .expect("Fig. 5 TCA is valid")
}

use std::sync::Arc;

use nalgebra::Vector3;

use crate::rod::{Actuator, Body, Robot, Routing, Section, TcaLaw};

/// EcoFlex 10 (Section V): density \[kg/m^3\], Young's modulus \[Pa\], Poisson ratio.
pub const ECOFLEX10: (f64, f64, f64) = (1040.0, 37.8e3, 0.5);
/// Standard gravity \[m/s^2\].
pub const G0: f64 = 9.81;
/// Offset of the manipulators' TCAs from the neutral axis \[m\] (Section V-B).
pub const TCA_OFFSET: f64 = 3e-3;
/// Half the spacing of the two legs of a U-shaped TCA along body `y` \[m\]. Not
/// printed in the paper; any symmetric spacing gives the same planar bending.
pub const U_LEG_HALF_SPACING: f64 = 2.5e-3;
/// Assumed initial (pre-curvature) radius of the circular manipulator \[m\];
/// the paper states it had initial bending but prints no value.
pub const CIRCLE_PRECURVATURE_RADIUS: f64 = 0.2;

/// The manipulators' TCA: `D = 1.7 mm`, `alpha0 = 15 deg`, `N = 76.4`, coiled
/// length = body length (Section V-B).
pub fn manipulator_tca(length: f64) -> Tca {
    Tca::from_pitch_angle(
        length,
        15f64.to_radians(),
        1.7e-3,
        76.4,
        Chirality::Extension,
        Material::silver_coated_nylon(),
    )
    .expect("manipulator TCA is valid")
}

/// A square EcoFlex body of side 10 mm with a U-shaped TCA (two legs at
/// `x = +3 mm`, `y = +-2.5 mm`), standing upright (gravity `-z`) if `gravity`.
pub fn square_manipulator(length: f64, gravity: bool) -> Robot {
    let (psi, e, nu) = ECOFLEX10;
    let mut body = Body::new(length, Section::Rectangle { width: 10e-3, height: 10e-3 }, e, nu, psi).expect("valid");
    if gravity {
        body.gravity = Vector3::new(0.0, 0.0, -G0);
    }
    let law = Arc::new(TcaLaw(manipulator_tca(length)));
    let legs = [U_LEG_HALF_SPACING, -U_LEG_HALF_SPACING]
        .iter()
        .map(|&y| Actuator::new(Routing::Straight { x: TCA_OFFSET, y }, 0.0, length, law.clone()))
        .collect();
    Robot::new(body, legs).expect("valid")
}

/// Fig. 6 top: circular EcoFlex body, 8 mm diameter, 40 mm long, one TCA at
/// `x = +3 mm`, pre-curved toward `-x` with radius [`CIRCLE_PRECURVATURE_RADIUS`].
pub fn fig6_circle(gravity: bool) -> Robot {
    let (psi, e, nu) = ECOFLEX10;
    let length = 0.040;
    let mut body = Body::new(length, Section::Circle { diameter: 8e-3 }, e, nu, psi).expect("valid");
    body.omega_star = Vector3::new(0.0, -1.0 / CIRCLE_PRECURVATURE_RADIUS, 0.0);
    if gravity {
        body.gravity = Vector3::new(0.0, 0.0, -G0);
    }
    let law = Arc::new(TcaLaw(manipulator_tca(length)));
    Robot::new(body, vec![Actuator::new(Routing::Straight { x: TCA_OFFSET, y: 0.0 }, 0.0, length, law)]).expect("valid")
}

/// Fig. 6 bottom: square manipulator, 40 mm long.
pub fn fig6_square(gravity: bool) -> Robot {
    square_manipulator(0.040, gravity)
}

/// Table I finger: square manipulator 20 mm long, hanging tip-down (gravity
/// `+z` in the base frame), its U-shaped TCA's two legs sharing one
/// temperature; it presses along `-x` on the grasped mass.
pub fn table1_finger() -> Robot {
    let mut finger = square_manipulator(0.020, false);
    finger.body.gravity = Vector3::new(0.0, 0.0, G0);
    finger
}

/// Table I grasp constants: friction coefficient, fingers, the direction a
/// finger presses in, and the masses \[kg\].
pub const TABLE1_MU: f64 = 1.1;
/// Number of fingers of the Table I gripper.
pub const TABLE1_FINGERS: usize = 2;
/// Masses \[kg\] of Table I.
pub const TABLE1_MASSES: [f64; 3] = [1e-3, 2e-3, 3e-3];
/// Unit direction a Table I finger presses in (world frame).
pub const TABLE1_NORMAL: [f64; 3] = [-1.0, 0.0, 0.0];

/// The issue-10 steel tendon robot, a shared speed benchmark (not from the
/// paper): steel rod `L = 0.5 m`, radius 1 mm, `E = 200 GPa`, `G = 80 GPa`,
/// 8000 kg/m^3, gravity 9.81 m/s^2 along base-frame `+x`, four straight
/// constant-tension tendons at 15.06 mm offset at 0/90/180/270 deg ending at
/// the tip. Inputs: the tensions \[N\], [`STEEL_TENDON_TENSIONS`].
pub fn steel_tendon_robot() -> Robot {
    use crate::rod::ConstantTension;
    let length = 0.5;
    let mut body = Body::new(length, Section::Circle { diameter: 2e-3 }, 200e9, 0.25, 8000.0).expect("valid");
    body.shear_modulus = 80e9;
    body.gravity = Vector3::new(G0, 0.0, 0.0);
    let law = Arc::new(ConstantTension);
    let offset = 15.06e-3;
    let tendons = (0..4)
        .map(|k| {
            let a = k as f64 * std::f64::consts::FRAC_PI_2;
            Actuator::new(Routing::Straight { x: offset * a.cos(), y: offset * a.sin() }, 0.0, length, law.clone())
        })
        .collect();
    Robot::new(body, tendons).expect("valid")
}

/// Tendon tensions \[N\] of [`steel_tendon_robot`]'s benchmark case.
pub const STEEL_TENDON_TENSIONS: [f64; 4] = [15.0, 0.0, 0.0, 0.0];

/// The issue-10 soft tendon rod: 0.2 m long, 10 mm diameter, 1 MPa
/// (Poisson 0.5), weightless, one straight constant-tension tendon at
/// [`SOFT_TENDON_OFFSET`] from the centre line to the tip.
pub fn soft_tendon_robot() -> Robot {
    use crate::rod::ConstantTension;
    let length = 0.2;
    let body = Body::new(length, Section::Circle { diameter: 10e-3 }, 1e6, 0.5, 0.0).expect("valid");
    let law = Arc::new(ConstantTension);
    Robot::new(body, vec![Actuator::new(Routing::Straight { x: SOFT_TENDON_OFFSET, y: 0.0 }, 0.0, length, law)]).expect("valid")
}

/// Tendon offset \[m\] of [`soft_tendon_robot`].
pub const SOFT_TENDON_OFFSET: f64 = 4e-3;

/// Tension \[N\] that bends [`soft_tendon_robot`] by `angle` \[rad\] at its tip
/// in the inextensible, unsheared limit: a constant tendon moment
/// `tau r = E I theta / L`.
pub fn soft_tendon_tension(angle: f64) -> f64 {
    let r = soft_tendon_robot();
    let (_, ix, _, _) = r.body.section.properties();
    angle * r.body.youngs_modulus * ix / (SOFT_TENDON_OFFSET * r.body.length)
}
