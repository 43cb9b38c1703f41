//! The paper's experiments (Section V) as test problems, shared by the unit
//! tests and the criterion benches. The Python package's
//! `tcarod.paper` holds the same fixtures with their published data.

use std::sync::Arc;

use nalgebra::Vector3;

use crate::error::Result;
use crate::material::Material;
use crate::rod::{Actuator, Body, Robot, Routing, Section, TcaLaw};
use crate::tca::{Chirality, Tca};

/// Fig. 5 TCA, `threads` = 3 or 4 (`l` and `L` are swapped in Section V-A's
/// text, see `docs/choices.md`; `L = 110 mm` coiled, `l = 497 / 471 mm` fibre).
pub fn fig5_tca(threads: u32) -> Tca {
    let (l, turns, d) = match threads {
        3 => (0.497, 300.0, 2.0e-3),
        4 => (0.471, 259.0, 2.13e-3),
        _ => panic!("Fig. 5 has three- and four-thread TCAs only"),
    };
    Tca::new(
        l,
        0.110,
        d,
        turns,
        Chirality::Extension,
        Material::silver_coated_nylon(),
    )
    .expect("Fig. 5 TCA is valid")
}

/// One folded half of the Fig. 5 TCA (the displacement is one half's
/// elongation): [`Tca::segment`]`(0.5)` of [`fig5_tca`], i.e. `Tca(l/2, L/2,
/// D, N/2)` with the whole TCA's `alpha0` and `d0`.
pub fn fig5_half_tca(threads: u32) -> Tca {
    fig5_tca(threads).segment(0.5).expect("half of a valid TCA")
}

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

/// Turns printed for "all the TCAs used in the manipulator" (Section V-B).
pub const MANIPULATOR_TURNS: f64 = 76.4;
/// Coiled length \[m\] of the circular manipulator's single TCA, the one TCA
/// whose printed turns are unambiguous (anchor of [`TurnsReading::PerLength`]).
pub const TURNS_ANCHOR_LENGTH: f64 = 0.040;

/// How to read the paper's "N = 76.4 rotations" for a manipulator TCA whose
/// U shape makes two legs (the paper does not say; the evidence for each
/// reading is in `docs/table1.md`, the choice in `docs/choices.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TurnsReading {
    /// 76.4 turns per fabricated TCA; a U-shaped TCA's two legs share them
    /// (38.2 per leg), as the folded Fig. 5 TCA's halves do. The default: the
    /// paper calls the U "a TCA" / "a single extension TCA" and considers its
    /// halves "as separate TCAs" only for their length.
    PerTca,
    /// 76.4 turns in every leg (each leg read as a TCA of its own).
    PerLeg,
    /// A twist density: 76.4 turns per 40 mm of coiled length (the circle's
    /// single TCA), so a leg of length `L` has `76.4 L / 40 mm` turns.
    PerLength,
}

impl TurnsReading {
    /// Turns [-] of one leg of coiled length `length` \[m\] of a TCA with `legs` legs.
    pub fn leg_turns(self, length: f64, legs: usize) -> f64 {
        match self {
            TurnsReading::PerTca => MANIPULATOR_TURNS / legs as f64,
            TurnsReading::PerLeg => MANIPULATOR_TURNS,
            TurnsReading::PerLength => MANIPULATOR_TURNS * length / TURNS_ANCHOR_LENGTH,
        }
    }
}

/// The default turns reading of the fixtures ([`TurnsReading::PerTca`]).
pub const DEFAULT_TURNS_READING: TurnsReading = TurnsReading::PerTca;

/// The manipulators' TCA: `D = 1.7 mm`, `alpha0 = 15 deg`, `turns` turns,
/// coiled length = body length (Section V-B).
pub fn manipulator_tca(length: f64, turns: f64) -> Tca {
    Tca::from_pitch_angle(
        length,
        MANIPULATOR_PITCH_DEG.to_radians(),
        MANIPULATOR_COIL_DIAMETER,
        turns,
        Chirality::Extension,
        Material::silver_coated_nylon(),
    )
    .expect("manipulator TCA is valid")
}

/// Side \[m\] of the manipulators' square section (Section V-B).
pub const SQUARE_SIDE: f64 = 10e-3;
/// Diameter \[m\] of the Fig. 6 circular manipulator.
pub const CIRCLE_DIAMETER: f64 = 8e-3;
/// Coil diameter `D` \[m\] of the manipulators' TCA (Section V-B).
pub const MANIPULATOR_COIL_DIAMETER: f64 = 1.7e-3;
/// Pitch angle `alpha0` \[deg\] of the manipulators' TCA (Section V-B).
pub const MANIPULATOR_PITCH_DEG: f64 = 15.0;
/// Length \[m\] of the Fig. 6 manipulators.
pub const FIG6_LENGTH: f64 = 0.040;
/// Length \[m\] of the Fig. 8 square manipulator.
pub const FIG8_LENGTH: f64 = 0.026;
/// Length \[m\] of a Table I finger.
pub const TABLE1_LENGTH: f64 = 0.020;

/// Shape of a manipulator's cross-section.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// Solid circle of diameter [`Manipulator::size`].
    Circle,
    /// Square of side [`Manipulator::size`].
    Square,
}

/// The design of the paper's EcoFlex manipulators (Section V): a body with
/// one extension TCA whose legs run straight at body `x = tca_offset`,
/// `y = tca_y[k]`, base to tip. [`Manipulator::square`] gives the paper's
/// values; the fields are the knobs of sensitivity studies.
#[derive(Debug, Clone, PartialEq)]
pub struct Manipulator {
    /// Body length \[m\] (= the TCA's coiled length).
    pub length: f64,
    /// Section shape.
    pub shape: Shape,
    /// Side or diameter \[m\].
    pub size: f64,
    /// Offset \[m\] of the legs along body x.
    pub tca_offset: f64,
    /// Body-frame y \[m\] of each leg (two for a U-shaped TCA).
    pub tca_y: Vec<f64>,
    /// Radius \[m\] of the reference shape, bent toward `-x` (`None`: straight).
    pub precurvature_radius: Option<f64>,
    /// Gravity \[m/s^2\] in the body-aligned frame ([`UPRIGHT`], [`HANGING`], or zero).
    pub gravity: [f64; 3],
    /// Young's modulus of the body \[Pa\] (EcoFlex 10: [`ECOFLEX10`]).
    pub youngs_modulus: f64,
    /// The TCA's fibre material.
    pub material: Material,
    /// The TCA's coil diameter \[m\].
    pub coil_diameter: f64,
    /// How the printed turns apply to the legs.
    pub turns_reading: TurnsReading,
}

/// Gravity \[m/s^2\] of a body standing upright (base down) in its body-aligned frame.
pub const UPRIGHT: [f64; 3] = [0.0, 0.0, -G0];
/// Gravity \[m/s^2\] of a finger hanging tip-down (the gripper of Section V-D).
pub const HANGING: [f64; 3] = [0.0, 0.0, G0];

impl Manipulator {
    /// The square manipulator of `length` \[m\]: 10 mm EcoFlex square, a
    /// U-shaped TCA (legs at `x = +3 mm`, `y = +-2.5 mm`), upright, turns per
    /// [`DEFAULT_TURNS_READING`].
    pub fn square(length: f64) -> Self {
        Manipulator {
            length,
            shape: Shape::Square,
            size: SQUARE_SIDE,
            tca_offset: TCA_OFFSET,
            tca_y: vec![U_LEG_HALF_SPACING, -U_LEG_HALF_SPACING],
            precurvature_radius: None,
            gravity: UPRIGHT,
            youngs_modulus: ECOFLEX10.1,
            material: Material::silver_coated_nylon(),
            coil_diameter: MANIPULATOR_COIL_DIAMETER,
            turns_reading: DEFAULT_TURNS_READING,
        }
    }

    /// Fig. 6 top: 8 mm circle, 40 mm, one TCA at `x = +3 mm`, pre-curved
    /// toward `-x` with radius [`CIRCLE_PRECURVATURE_RADIUS`], upright.
    pub fn fig6_circle() -> Self {
        Manipulator {
            shape: Shape::Circle,
            size: CIRCLE_DIAMETER,
            tca_y: vec![0.0],
            precurvature_radius: Some(CIRCLE_PRECURVATURE_RADIUS),
            ..Manipulator::square(FIG6_LENGTH)
        }
    }

    /// Table I finger: the 20 mm square manipulator hanging tip-down.
    pub fn table1_finger() -> Self {
        Manipulator {
            gravity: HANGING,
            ..Manipulator::square(TABLE1_LENGTH)
        }
    }

    /// The TCA of one leg: coiled length = body length, turns per
    /// [`Manipulator::turns_reading`].
    pub fn tca(&self) -> Result<Tca> {
        let turns = self.turns_reading.leg_turns(self.length, self.tca_y.len());
        Tca::from_pitch_angle(
            self.length,
            MANIPULATOR_PITCH_DEG.to_radians(),
            self.coil_diameter,
            turns,
            Chirality::Extension,
            self.material.clone(),
        )
    }

    /// The body: EcoFlex 10 (density, Poisson 0.5) of this size and stiffness.
    pub fn body(&self) -> Result<Body> {
        let (psi, _, nu) = ECOFLEX10;
        let section = match self.shape {
            Shape::Circle => Section::circle(self.size)?,
            Shape::Square => Section::rectangle(self.size, self.size)?,
        };
        let mut body = Body::new(self.length, section, self.youngs_modulus, nu, psi)?;
        if let Some(r) = self.precurvature_radius {
            // curvature about body -y turns the tangent toward -x
            body.omega_star = Vector3::new(0.0, -1.0 / r, 0.0);
        }
        body.gravity = Vector3::from(self.gravity);
        body.validate()?;
        Ok(body)
    }

    /// The robot: [`Manipulator::body`] with one actuator per leg, all sharing
    /// one TCA law (one temperature drives a U's legs: `groups = [0, 0]`).
    pub fn build(&self) -> Result<Robot> {
        let law = Arc::new(TcaLaw(self.tca()?));
        let legs = self
            .tca_y
            .iter()
            .map(|&y| {
                let routing = Routing::straight(self.tca_offset, y)?;
                Ok(Actuator::new(routing, 0.0, self.length, law.clone()))
            })
            .collect::<Result<Vec<_>>>()?;
        Robot::new(self.body()?, legs)
    }
}

/// A square EcoFlex body of side 10 mm with a U-shaped TCA (two legs at
/// `x = +3 mm`, `y = +-2.5 mm`; turns per [`DEFAULT_TURNS_READING`]),
/// standing upright (gravity `-z`) if `gravity`.
pub fn square_manipulator(length: f64, gravity: bool) -> Robot {
    let gravity = if gravity { UPRIGHT } else { [0.0; 3] };
    Manipulator {
        gravity,
        ..Manipulator::square(length)
    }
    .build()
    .expect("valid")
}

/// Fig. 6 top: circular EcoFlex body, 8 mm diameter, 40 mm long, one TCA at
/// `x = +3 mm`, pre-curved toward `-x` with radius [`CIRCLE_PRECURVATURE_RADIUS`].
pub fn fig6_circle(gravity: bool) -> Robot {
    let gravity = if gravity { UPRIGHT } else { [0.0; 3] };
    Manipulator {
        gravity,
        ..Manipulator::fig6_circle()
    }
    .build()
    .expect("valid")
}

/// Fig. 6 bottom: square manipulator, 40 mm long.
pub fn fig6_square(gravity: bool) -> Robot {
    square_manipulator(FIG6_LENGTH, gravity)
}

/// Table I finger: square manipulator 20 mm long, hanging tip-down (gravity
/// `+z` in the base frame), its U-shaped TCA's two legs sharing one
/// temperature; it closes freely until its tip touches the grasped mass at
/// [`table1_contact_temperature`], then presses along `-x`.
pub fn table1_finger() -> Robot {
    Manipulator::table1_finger().build().expect("valid")
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

/// The Table I grasp of one `mass` \[kg\] (one of [`TABLE1_MASSES`]) by
/// [`table1_finger`]s: friction [`TABLE1_MU`], [`TABLE1_FINGERS`] fingers
/// pressing along [`TABLE1_NORMAL`], standard gravity, contact at the
/// reference inputs, with the verdict policy `stability`.
pub fn table1_grasp(mass: f64, stability: crate::stability::Policy) -> crate::inverse::Grasp {
    crate::inverse::Grasp {
        normal: Vector3::from(TABLE1_NORMAL),
        mass,
        mu: TABLE1_MU,
        fingers: TABLE1_FINGERS,
        gravity: G0,
        contact: None,
        stability,
    }
}

/// The steel tendon robot, a speed benchmark shared by the tests and the
/// benches (not from the paper): steel rod `L = 0.5 m`, radius 1 mm,
/// `E = 200 GPa`, `G = 80 GPa`, 8000 kg/m^3, gravity 9.81 m/s^2 along
/// base-frame `+x`, four straight constant-tension tendons at 15.06 mm
/// offset at 0/90/180/270 deg ending at the tip. Inputs: the tensions
/// \[N\], [`STEEL_TENDON_TENSIONS`].
pub fn steel_tendon_robot() -> Robot {
    use crate::rod::ConstantTension;
    let length = 0.5;
    let mut body = Body::new(
        length,
        Section::Circle { diameter: 2e-3 },
        200e9,
        0.25,
        8000.0,
    )
    .expect("valid");
    body.shear_modulus = 80e9;
    body.gravity = Vector3::new(G0, 0.0, 0.0);
    let law = Arc::new(ConstantTension);
    let offset = 15.06e-3;
    let tendons = (0..4)
        .map(|k| {
            let a = k as f64 * std::f64::consts::FRAC_PI_2;
            Actuator::new(
                Routing::Straight {
                    x: offset * a.cos(),
                    y: offset * a.sin(),
                },
                0.0,
                length,
                law.clone(),
            )
        })
        .collect();
    Robot::with_spacer_disks(body, tendons).expect("valid")
}

/// Tendon tensions \[N\] of [`steel_tendon_robot`]'s benchmark case.
pub const STEEL_TENDON_TENSIONS: [f64; 4] = [15.0, 0.0, 0.0, 0.0];

/// The soft tendon rod, a speed benchmark of large deflections (not from
/// the paper): 0.2 m long, 10 mm diameter, 1 MPa (Poisson 0.5), weightless,
/// one straight constant-tension tendon at [`SOFT_TENDON_OFFSET`] from the
/// centre line to the tip.
pub fn soft_tendon_robot() -> Robot {
    use crate::rod::ConstantTension;
    let length = 0.2;
    let body =
        Body::new(length, Section::Circle { diameter: 10e-3 }, 1e6, 0.5, 0.0).expect("valid");
    let law = Arc::new(ConstantTension);
    Robot::new(
        body,
        vec![Actuator::new(
            Routing::Straight {
                x: SOFT_TENDON_OFFSET,
                y: 0.0,
            },
            0.0,
            length,
            law,
        )],
    )
    .expect("valid")
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

/// The paper's own Table I predictions \[C\] for [`TABLE1_MASSES`].
pub const TABLE1_PAPER_PREDICTIONS: [f64; 3] = [93.7, 114.8, 136.3];

/// Default contact temperature \[C\] of the Table I fingers: the zero-force
/// intercept of the paper's predictions, which are linear in the force per
/// finger `m g / (mu n)` (least-squares line of temperature on force,
/// evaluated at zero force: 72.33 C). The paper prints no gap between the
/// fingertips and the object; this is the contact its model implies.
pub fn table1_contact_temperature() -> f64 {
    let f: Vec<f64> = TABLE1_MASSES
        .iter()
        .map(|m| m * G0 / (TABLE1_MU * TABLE1_FINGERS as f64))
        .collect();
    let t = TABLE1_PAPER_PREDICTIONS;
    let n = f.len() as f64;
    let (fm, tm) = (f.iter().sum::<f64>() / n, t.iter().sum::<f64>() / n);
    let sff: f64 = f.iter().map(|x| (x - fm) * (x - fm)).sum();
    let sft: f64 = f.iter().zip(&t).map(|(x, y)| (x - fm) * (y - tm)).sum();
    tm - sft / sff * fm
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_readings() {
        // the Table I finger's 20 mm legs: per TCA and per length agree (38.2)
        assert_eq!(TurnsReading::PerTca.leg_turns(0.020, 2), 38.2);
        assert!((TurnsReading::PerLength.leg_turns(0.020, 2) - 38.2).abs() < 1e-12);
        assert_eq!(TurnsReading::PerLeg.leg_turns(0.020, 2), 76.4);
        // Fig. 8's 26 mm legs: 38.2 / 76.4 / 49.66
        assert!((TurnsReading::PerLength.leg_turns(0.026, 2) - 49.66).abs() < 1e-12);
        // the circle's single TCA has 76.4 turns in every reading
        for r in [
            TurnsReading::PerTca,
            TurnsReading::PerLeg,
            TurnsReading::PerLength,
        ] {
            assert!((r.leg_turns(0.040, 1) - 76.4).abs() < 1e-12);
        }
    }

    #[test]
    fn contact_temperature_is_the_papers_intercept() {
        // by hand: equally spaced forces, so the line runs through the mean
        // (114.933 C at 2 g) with 21.3 C per gram: 114.933 - 2 * 21.3 = 72.333 C
        let t = table1_contact_temperature();
        assert!((t - (344.8 / 3.0 - 42.6)).abs() < 1e-9, "{t}");
    }
}
