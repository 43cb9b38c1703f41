//! A body with its actuators.

use super::{Actuator, Body, Routing, Section};
use crate::error::{human, length_text, mm_hint, positive, Error, Result};

/// Tolerance of the "fits the span" rule: a TCA may be up to 10% longer
/// than its anchored span (rounding of measured lengths), not more.
const SPAN_SLACK: f64 = 1.1;

/// A body with its actuators.
#[derive(Debug, Clone)]
pub struct Robot {
    /// The soft body.
    pub body: Body,
    /// Embedded actuators.
    pub actuators: Vec<Actuator>,
    /// The actuators are guided by spacer disks outside the backbone's
    /// section (a tendon robot, e.g. [`crate::experiments::steel_tendon_robot`]):
    /// the rule "routing and TCA coil inside the section" is waived.
    pub spacer_disks: bool,
}

/// Number of states besides the actuator elongations: p (3), q (4), v (3), u (3).
pub const BASE_STATES: usize = 13;

impl Robot {
    /// Validate and build. An actuator anchored at [`Actuator::TIP`] is
    /// anchored at the body length; a pre-tensioned TCA
    /// ([`Actuator::pretension`]) gets the constant length ratio that gives it
    /// that tension in the undeformed reference shape. Errors name
    /// `actuators[i]`: anchors outside the body, a routing outside the
    /// section, a TCA whose coil (routing offset plus half the coil's outer
    /// diameter) sticks out of the section, a TCA longer than its span (by
    /// more than 10%).
    pub fn new(body: Body, actuators: Vec<Actuator>) -> Result<Self> {
        Robot::build(body, actuators, false)
    }

    /// [`Robot::new`] for a tendon robot whose actuators run through spacer
    /// disks outside the backbone's section ([`Robot::spacer_disks`]).
    pub fn with_spacer_disks(body: Body, actuators: Vec<Actuator>) -> Result<Self> {
        Robot::build(body, actuators, true)
    }

    fn build(body: Body, mut actuators: Vec<Actuator>, spacer_disks: bool) -> Result<Self> {
        for a in &mut actuators {
            if a.s_end == Actuator::TIP {
                a.s_end = body.length;
            }
        }
        let mut r = Robot {
            body,
            actuators,
            spacer_disks,
        };
        r.validate()?;
        for (i, a) in r.actuators.iter_mut().enumerate() {
            if let (Some(f), Some(tca)) = (a.pretension, a.law.tca()) {
                let stretch = tca.displacement(f, tca.material().t_ref())?;
                let name = format!("actuators[{i}].pretension_n");
                a.length_ratio = Some(pretension_length_ratio(&r.body, a, stretch, &name)?);
            }
        }
        Ok(r)
    }

    /// Validate the body, the anchors and the layout of every actuator.
    pub fn validate(&self) -> Result<()> {
        self.body.validate()?;
        self.validate_anchors()?;
        // names are formatted only for an error (this runs on every solve)
        for (i, a) in self.actuators.iter().enumerate() {
            if !self.spacer_disks {
                // a TCA is a coil of outer diameter D about its routing: all
                // of it must lie in the silicone; a tendon is a line
                let coil_radius = a.law.tca().map_or(0.0, |t| 0.5 * t.coil_diameter());
                let name = || format!("actuators[{i}].routing");
                routing_in_section(&self.body.section, &a.routing, coil_radius, name)?;
            }
            if let Some(tca) = a.law.tca() {
                tca_fits_span(tca.coiled_length(), a, || format!("actuators[{i}].tca"))?;
            }
        }
        Ok(())
    }

    /// Anchors inside the body, a positive length ratio, a path of non-zero length rate.
    fn validate_anchors(&self) -> Result<()> {
        let len = self.body.length;
        for (i, a) in self.actuators.iter().enumerate() {
            a.routing.validate()?;
            if !(a.s_start.is_finite() && a.s_start >= 0.0 && a.s_start < len) {
                return Err(Error::param(
                    &format!("actuators[{i}].s_start [m]"),
                    a.s_start,
                    format!(
                        "0 <= s_start < body length {} m{}",
                        human(len),
                        mm_hint(a.s_start)
                    ),
                ));
            }
            if !(a.s_end.is_finite() && a.s_end > a.s_start && a.s_end <= len * (1.0 + 1e-12)) {
                return Err(Error::param(
                    &format!("actuators[{i}].s_end [m]"),
                    a.s_end,
                    format!(
                        "s_start = {} m < s_end <= body length {} m{}",
                        human(a.s_start),
                        human(len),
                        mm_hint(a.s_end)
                    ),
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
                    return Err(Error::input(
                        &format!("actuators[{i}]"),
                        "its reference path has zero length rate",
                    ));
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
                format!(
                    "expected {} values (shape ({},), one input per actuator), got {}",
                    self.actuators.len(),
                    self.actuators.len(),
                    inputs.len()
                ),
            ));
        }
        for (i, (a, &x)) in self.actuators.iter().zip(inputs).enumerate() {
            a.law
                .check_input(x)
                .map_err(|e| e.renamed(|name| format!("inputs[{i}] ({name})")))?;
        }
        Ok(())
    }

    /// Reference (passive) inputs: ambient temperature for TCAs, zero tension/pull for tendons.
    pub fn reference_inputs(&self) -> Vec<f64> {
        self.actuators
            .iter()
            .map(|a| a.law.reference_input())
            .collect()
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

/// Error unless the routing of actuator `name()`, thickened by
/// `coil_radius` \[m\] (half a TCA coil's outer diameter; 0 for a tendon),
/// lies inside the section (on or inside the edge; a helix is checked in 64
/// directions). A circle (and a custom section, taken as the circle of its
/// area) holds a disc of radius `R` centred at distance `r` if
/// `r + R <= D/2`; a rectangle holds it if `|x| + R <= w/2` and
/// `|y| + R <= h/2`.
fn routing_in_section(
    section: &Section,
    routing: &Routing,
    coil_radius: f64,
    name: impl Fn() -> String,
) -> Result<()> {
    let points = if matches!(routing, Routing::Helix { .. }) {
        64
    } else {
        1
    };
    for k in 0..points {
        let (x, y) = match *routing {
            Routing::Straight { x, y } => (x, y),
            Routing::Helix { radius, .. } => {
                let t = k as f64 * std::f64::consts::TAU / 64.0;
                (radius * t.cos(), radius * t.sin())
            }
        };
        if let Some(reason) = outside_section(section, x, y, coil_radius) {
            return Err(Error::input(&name(), reason));
        }
    }
    Ok(())
}

/// Why a disc of radius `coil_radius` \[m\] centred at body-frame `(x, y)`
/// \[m\] does not fit in `section` (relative tolerance 1e-9), or `None`.
fn outside_section(section: &Section, x: f64, y: f64, coil_radius: f64) -> Option<String> {
    const TOL: f64 = 1.0 + 1e-9;
    // how far the disc reaches, and the room the section leaves (the
    // messages are only formatted for a disc that does not fit)
    let reach = match *section {
        Section::Rectangle { width, height } => {
            let (ex, ey) = (x.abs() + coil_radius, y.abs() + coil_radius);
            if ex <= 0.5 * width * TOL && ey <= 0.5 * height * TOL {
                return None;
            }
            format!(
                "it reaches {} from the axis along x and {} along y, outside the {} x {} rectangular \
                 body section (half-sizes {} and {})",
                length_text(ex),
                length_text(ey),
                length_text(width),
                length_text(height),
                length_text(0.5 * width),
                length_text(0.5 * height),
            )
        }
        _ => {
            let r = x.hypot(y) + coil_radius;
            let edge = section.edge_distance(y.atan2(x));
            if r <= edge * TOL {
                return None;
            }
            let shape = if matches!(section, Section::Circle { .. }) {
                "body section"
            } else {
                "body section (a custom section: the circle of its area)"
            };
            format!(
                "it reaches {} from the axis, outside the {} radius {shape}",
                length_text(r),
                length_text(edge)
            )
        }
    };
    let what = if coil_radius > 0.0 {
        format!("the TCA's coil (outer radius {})", length_text(coil_radius))
    } else {
        "the routing".to_string()
    };
    let at = if x.abs().max(y.abs()) < 1.0 {
        format!("({} mm, {} mm)", human(x * 1e3), human(y * 1e3))
    } else {
        format!("({} m, {} m)", human(x), human(y))
    };
    Some(format!(
        "{what} at offset {at} lies outside the section: {reach}; move it inward, or pass \
         spacer_disks=True to Robot if it runs on spacer disks outside the body{}",
        mm_hint(x.hypot(y))
    ))
}

/// Error unless a TCA of coiled length `coiled_length` \[m\] fits the span
/// `s_end - s_start` \[m\] of actuator `name()`.
fn tca_fits_span(coiled_length: f64, actuator: &Actuator, name: impl Fn() -> String) -> Result<()> {
    let span = actuator.s_end - actuator.s_start;
    if coiled_length > SPAN_SLACK * span {
        return Err(Error::input(
            &name(),
            format!(
                "the TCA's coiled_length {} m exceeds its anchored span s_end - s_start = {} m \
                 (by more than 10%); shorten the TCA or move its anchors",
                human(coiled_length),
                human(span)
            ),
        ));
    }
    Ok(())
}

/// The constant length ratio `L_i` (eq 18) of an actuator installed stretched
/// by `stretch` \[m\] over its span: the reference path's length rate
/// `|nu* + omega* x r + r'|` minus `stretch / span`. Error unless that rate
/// is constant along the span (straight routings; helices in a body without
/// reference curvature) and the ratio stays positive.
fn pretension_length_ratio(
    body: &Body,
    actuator: &Actuator,
    stretch: f64,
    name: &str,
) -> Result<f64> {
    let span = actuator.s_end - actuator.s_start;
    let rate = |s: f64| {
        let (r, rp, _) = actuator.routing.eval(s);
        (body.nu_star + body.omega_star.cross(&r) + rp).norm()
    };
    let r0 = rate(actuator.s_start);
    for k in 1..=16 {
        let s = actuator.s_start + span * k as f64 / 16.0;
        if (rate(s) - r0).abs() > 1e-12 * r0 {
            return Err(Error::input(
                name,
                "pretension_n needs a reference path of constant length rate (a straight routing, or a helix \
                 in a body without reference curvature omega_star); give length_ratio instead",
            ));
        }
    }
    let ratio = r0 - stretch / span;
    if !(ratio.is_finite() && ratio > 0.0) {
        return Err(Error::input(
            name,
            format!(
                "pretension_n stretches the TCA by {} m, more than its span {} m",
                human(stretch),
                human(span)
            ),
        ));
    }
    Ok(ratio)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn name() -> String {
        "actuators[0].routing".to_string()
    }

    #[test]
    fn routing_outside_a_14_mm_body_is_rejected() {
        let s = Section::Circle { diameter: 14e-3 };
        assert!(routing_in_section(&s, &Routing::Straight { x: 5e-3, y: 0.0 }, 0.0, name).is_ok());
        let e =
            routing_in_section(&s, &Routing::Straight { x: 20e-3, y: 0.0 }, 0.0, name).unwrap_err();
        assert!(e.to_string().contains("actuators[0].routing"));
        let helix = Routing::Helix {
            radius: 8e-3,
            rate: 1.0,
            phase: 0.0,
        };
        assert!(routing_in_section(&s, &helix, 0.0, name).is_err());
    }

    /// A 1.7 mm coil (radius 0.85 mm) in a 12 mm body (radius 6 mm): at a
    /// 5 mm offset it reaches 5.85 mm and fits; at 6 mm it reaches 6.85 mm
    /// and sticks out, although its centre line is on the edge.
    #[test]
    fn a_coil_must_lie_inside_a_circular_section() {
        let s = Section::Circle { diameter: 12e-3 };
        let at = |x: f64| Routing::Straight { x, y: 0.0 };
        assert!(routing_in_section(&s, &at(5e-3), 0.85e-3, name).is_ok());
        assert!(routing_in_section(&s, &at(6e-3), 0.0, name).is_ok());
        let e = routing_in_section(&s, &at(6e-3), 0.85e-3, name)
            .unwrap_err()
            .to_string();
        assert!(e.contains("reaches 6.85 mm from the axis"), "{e}");
        assert!(e.contains("outside the 6 mm radius body section"), "{e}");
        assert!(e.contains("spacer_disks=True"), "{e}");
        assert!(routing_in_section(&s, &at(5.5e-3), 0.85e-3, name).is_err());
        // diagonal: |(4.5, 3.5)| = 5.70 mm, + 0.85 = 6.55 mm > 6 mm
        let diag = Routing::Straight {
            x: 4.5e-3,
            y: 3.5e-3,
        };
        assert!(routing_in_section(&s, &diag, 0.85e-3, name).is_err());
    }

    /// A rectangle holds the coil if it fits along x and along y: the
    /// paper's 10 mm square with a leg at (3, 2.5) mm and a 1.7 mm coil
    /// reaches (3.85, 3.35) mm < 5 mm; at y = 4.5 mm it reaches 5.35 mm.
    #[test]
    fn a_coil_must_lie_inside_a_rectangular_section() {
        let s = Section::Rectangle {
            width: 10e-3,
            height: 10e-3,
        };
        let leg = |y: f64| Routing::Straight { x: 3e-3, y };
        assert!(routing_in_section(&s, &leg(2.5e-3), 0.85e-3, name).is_ok());
        let e = routing_in_section(&s, &leg(4.5e-3), 0.85e-3, name)
            .unwrap_err()
            .to_string();
        assert!(e.contains("5.35 mm along y"), "{e}");
        assert!(e.contains("rectangular body section"), "{e}");
        // a thin strip: 20 mm wide, 2 mm high; a coil of radius 1.5 mm on the axis is too thick
        let strip = Section::Rectangle {
            width: 20e-3,
            height: 2e-3,
        };
        let axis = Routing::Straight { x: 0.0, y: 0.0 };
        assert!(routing_in_section(&strip, &axis, 1.5e-3, name).is_err());
        assert!(routing_in_section(&strip, &axis, 0.9e-3, name).is_ok());
    }

    #[test]
    fn an_offset_in_millimetres_is_pointed_out() {
        let s = Section::Circle { diameter: 12e-3 };
        let e = routing_in_section(&s, &Routing::Straight { x: 4.0, y: 0.0 }, 0.0, name)
            .unwrap_err()
            .to_string();
        assert!(e.contains("at offset (4 m, 0 m)"), "{e}");
        assert!(
            e.contains("millimetres? lengths are in metres: 4 mm is 0.004 m"),
            "{e}"
        );
        assert!(!e.contains("e0") && !e.contains("Routing::"), "{e}");
    }

    #[test]
    fn spacer_disks_waive_the_section_rule() {
        let tca = crate::tca::Tca::from_pitch_angle(
            0.04,
            15f64.to_radians(),
            1.7e-3,
            50.0,
            crate::tca::Chirality::Extension,
            crate::material::Material::silver_coated_nylon(),
        )
        .unwrap();
        let body = Body::new(0.04, Section::Circle { diameter: 12e-3 }, 5e4, 0.5, 0.0).unwrap();
        let a = Actuator::tca(
            tca,
            Routing::Straight { x: 6e-3, y: 0.0 },
            0.0,
            None,
            None,
            None,
        )
        .unwrap();
        let e = Robot::new(body.clone(), vec![a.clone()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("actuators[0].routing") && e.contains("6.85 mm"),
            "{e}"
        );
        assert!(Robot::with_spacer_disks(body, vec![a]).is_ok());
    }
}
