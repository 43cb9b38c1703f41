//! Properties of the forward kinetostatics that hold for every design, signs and
//! convergence of the Fig. 6 sweeps.
//!
//! * equilibrium at interior anchors shared or passed by other strings;
//! * the reference state: at 25 C, unloaded and weightless, the body keeps its
//!   reference shape, with zero elongation and tension;
//! * symmetries: mirroring the actuator layout mirrors the shape; rotating it
//!   about the axis rotates the shape; two equal TCAs opposite each other only
//!   stretch the body;
//! * sign: a heated extension TCA at +x pushes and bends the body toward -x;
//! * a passive TCA pressed into coil contact converges (smoothed onset).
//!
//! The random designs are drawn from a seeded [`SplitMix64`] (the same on every
//! machine), as the Python hypothesis strategy of `tests/test_rod_properties.py`
//! draws them; global equilibrium over random designs is
//! `tests/integration/designs.rs`, the convergence of the Fig. 6 sweeps cold and
//! warm `tests/integration/solver.rs`.
//! Frame: base at the origin, reference tangent +z. SI units, temperatures in C.
use crate::common;

use std::f64::consts::PI;

use common::{solve_default, span_tca, tca_actuator, tendon};
use nalgebra::{Matrix3, Vector3};
use tcarod::experiments::{fig6_circle, fig6_square, manipulator_tca};
use tcarod::problems::SplitMix64;
use tcarod::rod::{Actuator, Body, Robot, Routing, Section};

const G0: f64 = 9.81;
/// Random designs per property (the Python hypothesis tests draw 25).
const EXAMPLES: usize = 40;

// ------------------------------------------------------------ random designs

#[derive(Debug, Clone)]
struct Spec {
    tca: bool,
    x: f64,
    y: f64,
    s_start: f64, // [m]
    s_end: f64,   // [m]
    value: f64,   // temperature [C] or tension [N]
}

#[derive(Debug, Clone)]
struct Design {
    length: f64,
    section: Section,
    half_width: f64,
    half_height: f64,
    youngs_modulus: f64,
    density: f64,
    specs: Vec<Spec>,
}

impl Design {
    fn body(&self, gravity: Vector3<f64>) -> Body {
        let mut b = Body::new(
            self.length,
            self.section,
            self.youngs_modulus,
            0.5,
            self.density,
        )
        .unwrap();
        b.gravity = gravity;
        b
    }
    fn actuators(&self, xy: &[(f64, f64)]) -> Vec<Actuator> {
        self.specs
            .iter()
            .zip(xy)
            .map(|(a, &(x, y))| {
                let routing = Routing::Straight { x, y };
                if a.tca {
                    tca_actuator(span_tca(a.s_end - a.s_start), routing, a.s_start, a.s_end)
                } else {
                    tendon(routing, a.s_start, a.s_end)
                }
            })
            .collect()
    }
    fn layout(&self) -> Vec<(f64, f64)> {
        self.specs.iter().map(|a| (a.x, a.y)).collect()
    }
    fn inputs(&self) -> Vec<f64> {
        self.specs.iter().map(|a| a.value).collect()
    }
}

/// A circle (7-12 mm) or a rectangle (7-12 mm sides) and the half extents
/// \[m\] inside which actuators are placed (the inscribed square for a circle).
fn draw_section(rng: &mut SplitMix64) -> (Section, f64, f64) {
    if rng.chance(0.5) {
        let d = rng.range(7e-3, 12e-3);
        let h = d / 2.0 / 2f64.sqrt();
        (Section::Circle { diameter: d }, h, h)
    } else {
        let (w, h) = (rng.range(7e-3, 12e-3), rng.range(7e-3, 12e-3));
        (
            Section::Rectangle {
                width: w,
                height: h,
            },
            w / 2.0,
            h / 2.0,
        )
    }
}

/// A random body with 1-3 actuators (TCAs or tendons) at random offsets.
/// `nested`: random anchors. Otherwise one actuator with a random span, or several
/// that run base to tip or along consecutive disjoint pieces, so that no anchor
/// inside the body is shared or passed by another actuator.
fn design(rng: &mut SplitMix64, nested: bool) -> Design {
    let length = rng.range(0.02, 0.06);
    let (section, hw, hh) = draw_section(rng);
    let e = rng.range(3e4, 2e5);
    let (area, ix, iy, _) = section.properties();
    let ei = e * ix.min(iy);
    let n_act = 1 + rng.below(3);
    let single = (
        rng.range(0.0, 0.4),
        if rng.chance(0.5) {
            1.0
        } else {
            rng.range(0.7, 1.0)
        },
    );
    let disjoint = rng.chance(0.5);
    let mut specs = Vec::new();
    for k in 0..n_act {
        let tca = rng.chance(0.5);
        let (x, y) = (rng.range(-0.7, 0.7) * hw, rng.range(-0.7, 0.7) * hh);
        let (s0, s1) = if nested {
            let s0 = rng.range(0.0, 0.4);
            (
                s0,
                if rng.chance(0.5) {
                    1.0
                } else {
                    rng.range(s0 + 0.3, 1.0)
                },
            )
        } else if n_act == 1 {
            single
        } else if disjoint {
            (k as f64 / n_act as f64, (k + 1) as f64 / n_act as f64)
        } else {
            (0.0, 1.0)
        };
        // tendon tension up to tau r L / EI ~ 0.5 (bends ~30 degrees); TCAs from
        // 40 C: near 25 C a load that closes the coils makes Newton fail
        let value = if tca {
            rng.range(40.0, 120.0)
        } else {
            rng.range(0.0, 0.5 * ei / (length * 5e-3))
        };
        specs.push(Spec {
            tca,
            x,
            y,
            s_start: s0 * length,
            s_end: s1 * length,
            value,
        });
    }
    // Self-weight: an upright column buckles at rho A g L^3 / EI = 7.84; keep the
    // weight parameter <= 2 (the Fig. 6 square has 2.1), clear of that.
    let density = rng
        .range(0.0, 2000.0)
        .min(2.0 * ei / (area * G0 * length.powi(3)));
    Design {
        length,
        section,
        half_width: hw,
        half_height: hh,
        youngs_modulus: e,
        density,
        specs,
    }
}

// ------------------------------------------------------- interior anchors

/// At an interior anchor the strains jump, so strings passing or sharing it have a
/// kink there; the kink forces are applied together with the anchor loads.
#[test]
fn anchor_inside_the_body_with_other_strings_keeps_equilibrium() {
    let len = 0.04;
    let cases = [
        ("passing", [(0.0, len), (0.02, len)]), // the first passes the second's proximal anchor
        ("shared-distal", [(0.0, 0.02), (0.0, 0.02)]),
        ("shared-proximal", [(0.02, len), (0.02, len)]),
    ];
    for (name, spans) in cases {
        let tip_force = Vector3::new(0.0, 0.005, 0.0);
        let mut body = common::weightless_body();
        body.tip_force = tip_force;
        let ea = body.stiffness().0[(2, 2)];
        let offsets = if spans[1].0 > spans[0].0 {
            [(1e-3, 0.0), (1e-3, 0.0)]
        } else {
            [(1e-3, 0.0), (-1e-3, 1e-3)]
        };
        let acts = offsets
            .iter()
            .zip(spans)
            .map(|(&(x, y), (s0, s1))| tendon(Routing::Straight { x, y }, s0, s1))
            .collect();
        let sol = solve_default(&Robot::new(body, acts).unwrap(), &[0.03, 0.03]);
        // solver tolerance 1e-10 on K_nu^-1 r_F with margin 100: 100 x 1e-10 x EA
        // (here 1.9e-8 N; kink forces left out of the anchor loads would leave
        // ~6e-6 N)
        let err = (sol.base_force - tip_force).amax();
        assert!(err <= 100.0 * 1e-10 * ea, "{name}: {err}");
    }
}

/// Coil contact is C1-smoothed over 0.1 um (`TcaAt::tension`; docs/choices.md,
/// "Coil contact inside a body"), so Newton converges through contact onset when
/// a passive TCA is pressed.
#[test]
fn tca_pressed_into_coil_contact_converges() {
    for tip_force_y in [0.5e-3, 2.86e-3] {
        let length = 0.03125;
        let section = Section::Rectangle {
            width: 7.8125e-3,
            height: 7.8125e-3,
        };
        let mut body = Body::new(length, section, 3e4, 0.5, 0.0).unwrap();
        body.tip_force = Vector3::new(0.0, tip_force_y, 0.0);
        let routing = Routing::Straight {
            x: 0.0,
            y: 1.953125e-3,
        };
        let act = tca_actuator(span_tca(length), routing, 0.0, length);
        let sol = solve_default(&Robot::new(body, vec![act]).unwrap(), &[25.0]);
        assert!(
            sol.tensions[0] < 0.0,
            "pressed into contact, the TCA pushes back"
        );
        assert!(sol.tip_position().y > 0.0);
    }
}

// -------------------------------------------------------- reference state

#[test]
fn reference_temperature_keeps_reference_shape() {
    let mut rng = SplitMix64::new(11);
    for case in 0..EXAMPLES {
        let d = design(&mut rng, true);
        // a straight body every fourth case, else pre-curved up to 8 1/m
        let omega_star = if case % 4 == 0 {
            Vector3::zeros()
        } else {
            Vector3::new(rng.range(-8.0, 8.0), rng.range(-8.0, 8.0), 0.0)
        };
        // every actuator a TCA at 25 C; no load, no gravity
        let mut body = d.body(Vector3::zeros());
        body.omega_star = omega_star;
        let acts = d
            .specs
            .iter()
            .map(|a| {
                let routing = Routing::Straight { x: a.x, y: a.y };
                tca_actuator(span_tca(a.s_end - a.s_start), routing, a.s_start, a.s_end)
            })
            .collect();
        let robot = Robot::new(body, acts).unwrap();
        let inputs = robot.reference_inputs();
        assert_eq!(inputs, vec![25.0; d.specs.len()]);
        let sol = solve_default(&robot, &inputs);
        // The reference guess is the exact solution: zero residual, no Newton step.
        // The tolerances below are rounding of the reference configuration.
        assert_eq!(sol.iterations, 0, "case {case}");
        for (k, (w, nu)) in sol.omega.iter().zip(&sol.nu).enumerate() {
            assert!(
                (w - omega_star).amax() <= 1e-12,
                "case {case} node {k}: {w}"
            );
            assert!(
                (nu - Vector3::z()).amax() <= 1e-12,
                "case {case} node {k}: {nu}"
            );
        }
        assert!(sol.tensions.iter().all(|t| t.abs() < 1e-12), "case {case}");
        assert!(
            sol.elongations.iter().all(|e| e.abs() < 1e-15),
            "case {case}"
        );
        if omega_star == Vector3::zeros() {
            for (p, s) in sol.positions.iter().zip(&sol.s) {
                assert!(p.x.abs() <= 1e-15 && p.y.abs() <= 1e-15, "case {case}: {p}");
                assert!((p.z - s).abs() <= 1e-14 * s, "case {case}: {p} at {s}");
            }
        }
        assert!(sol.base_force.amax() <= 1e-15, "case {case}");
    }
}

// ------------------------------------------------------------- symmetries

#[test]
fn mirrored_layout_mirrors_shape() {
    let mut rng = SplitMix64::new(12);
    for case in 0..EXAMPLES {
        let d = design(&mut rng, false);
        // x -> -x for every actuator; sections are symmetric in x, gravity along z
        // keeps the symmetry
        let g = if rng.chance(0.5) { -G0 } else { 0.0 };
        let xy = d.layout();
        let mirrored: Vec<_> = xy.iter().map(|&(x, y)| (-x, y)).collect();
        let run = |layout: &[(f64, f64)]| {
            let robot = Robot::new(d.body(Vector3::new(0.0, 0.0, g)), d.actuators(layout));
            solve_default(&robot.unwrap(), &d.inputs())
        };
        let (a, b) = (run(&xy), run(&mirrored));
        let mirror = Vector3::new(-1.0, 1.0, 1.0);
        // same equations mirrored; each solve meets its tolerance (strain 1e-10 ->
        // positions ~L * 1e-10 * (K ratio) ~1e-11 m); 1e-9 m leaves a margin of ~100
        for (pa, pb) in a.positions.iter().zip(&b.positions) {
            assert!(
                (pb - pa.component_mul(&mirror)).amax() <= 1e-9,
                "case {case}"
            );
        }
        // tensions: the same solve tolerance, relative to the tension (with an
        // absolute floor for a tension near zero)
        for (ta, tb) in a.tensions.iter().zip(&b.tensions) {
            assert!((ta - tb).abs() <= 1e-12 + 1e-7 * ta.abs(), "case {case}");
        }
    }
}

#[test]
fn rotated_layout_rotates_shape() {
    let mut rng = SplitMix64::new(13);
    for case in 0..EXAMPLES {
        let d = design(&mut rng, false);
        let angle = rng.range(-PI, PI);
        let helix = rng.chance(0.5);
        // A circle (or square: I_x = I_y) is isotropic in bending, so the model is
        // invariant under rotation of the actuator layout about the axis (no
        // gravity). Offsets are up to 0.7 of each half-size, so |(x, y)| <= 0.99 max
        // (half sizes): sized by the larger half-size, every rotated layout stays
        // inside the section.
        let w = 2.0 * d.half_width.max(d.half_height);
        let section = match d.section {
            Section::Circle { .. } => Section::Circle {
                diameter: w * 2f64.sqrt(),
            },
            _ => Section::Rectangle {
                width: w,
                height: w,
            },
        };
        let body = Body::new(d.length, section, d.youngs_modulus, 0.5, 0.0).unwrap();
        let (s, c) = angle.sin_cos();
        let rot = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0);
        let routing = |x: f64, y: f64, turn: f64| {
            if helix {
                // a helix starting at (x, y), turning once over the body
                Routing::Helix {
                    radius: x.hypot(y),
                    rate: 2.0 * PI / d.length,
                    phase: y.atan2(x) + turn,
                }
            } else {
                let (ss, cc) = turn.sin_cos();
                Routing::Straight {
                    x: cc * x - ss * y,
                    y: ss * x + cc * y,
                }
            }
        };
        // tendons only (TCA forces would be identical, but a tendon's tension is the input)
        let robot = |turn: f64| {
            let acts = d
                .specs
                .iter()
                .map(|a| tendon(routing(a.x, a.y, turn), a.s_start, d.length))
                .collect();
            Robot::new(body.clone(), acts).unwrap()
        };
        let (_, ix, _, _) = section.properties();
        let tension = 0.2 * d.youngs_modulus * ix / (d.length * 5e-3);
        let n = d.specs.len();
        let inputs: Vec<f64> = (0..n)
            .map(|k| tension * (k + 1) as f64 / n as f64)
            .collect();
        let a = solve_default(&robot(0.0), &inputs);
        let b = solve_default(&robot(angle), &inputs);
        // tolerance as for the mirror test
        for (pa, pb) in a.positions.iter().zip(&b.positions) {
            assert!((pb - rot * pa).amax() <= 1e-9, "case {case}");
        }
        // rotation entries (order 1): the solve tolerance in curvature (~1e-10 / L)
        // integrated over L, with margin
        let want = rot * a.tip_rotation() * rot.transpose();
        assert!((b.tip_rotation() - want).amax() <= 1e-7, "case {case}");
    }
}

#[test]
fn opposite_equal_tcas_only_stretch() {
    let mut rng = SplitMix64::new(14);
    let tca40 = manipulator_tca(0.040, 76.4);
    for case in 0..EXAMPLES {
        // the first case at the reference temperature, the rest drawn
        let temperature = if case == 0 {
            25.0
        } else {
            rng.range(25.0, 160.0)
        };
        let offset = rng.range(1e-3, 3.5e-3);
        let angle = rng.range(-PI, PI);
        let section = if rng.chance(0.5) {
            Section::Rectangle {
                width: 10e-3,
                height: 10e-3,
            }
        } else {
            Section::Circle { diameter: 9e-3 }
        };
        // two identical TCAs at r and -r (opposite each other through the axis)
        let body = Body::new(0.04, section, 37.8e3, 0.5, 0.0).unwrap();
        let (x, y) = (offset * angle.cos(), offset * angle.sin());
        let acts = [1.0, -1.0]
            .iter()
            .map(|sx| {
                let r = Routing::Straight {
                    x: sx * x,
                    y: sx * y,
                };
                tca_actuator(tca40.clone(), r, 0.0, 0.04)
            })
            .collect();
        let sol = solve_default(&Robot::new(body, acts).unwrap(), &[temperature; 2]);
        // equal forces at opposite offsets: their moments cancel, no bending (to the
        // solver tolerance: curvature ~1e-10 / L = 2.5e-9 1/m; 1e-7 leaves margin)
        for (w, p) in sol.omega.iter().zip(&sol.positions) {
            assert!(w.x.abs() <= 1e-7 && w.y.abs() <= 1e-7, "case {case}: {w}");
            assert!(p.x.abs() <= 1e-10 && p.y.abs() <= 1e-10, "case {case}: {p}");
        }
        // equal by symmetry, to the solve tolerance relative to the tension
        let (t0, t1) = (sol.tensions[0], sol.tensions[1]);
        assert!((t0 - t1).abs() <= 1e-15 + 1e-8 * t1.abs(), "case {case}");
        if temperature > 26.0 {
            // heated extension TCAs push (tension < 0): the body is stretched
            assert!(t0 < 0.0, "case {case}");
            assert!(sol.tip_position().z > 0.04, "case {case}");
        }
    }
}

// ------------------------------------------------------------------- sign

#[test]
fn heated_extension_tcas_of_fig6_bend_toward_minus_x() {
    for temperature in [60.0, 100.0, 160.0] {
        for robot in [fig6_circle(false), fig6_square(false)] {
            let n = robot.actuators.len();
            let reference = solve_default(&robot, &vec![25.0; n]);
            let sol = solve_default(&robot, &vec![temperature; n]);
            // further toward -x, by > 1 mm
            assert!(sol.tip_position().x < reference.tip_position().x - 1e-3);
            assert!(
                sol.tensions.iter().all(|&t| t < 0.0),
                "a heated extension TCA pushes"
            );
            assert!(sol.elongations.iter().all(|&e| e > 0.0), "and lengthens");
            // planar: the TCAs are symmetric about y = 0 (y is rounding only)
            assert!(sol.tip_position().y.abs() < 1e-12);
        }
    }
}
