//! A body with its actuators.

use super::{Actuator, Body, Routing, Section};
use crate::error::{positive, Error, Result};

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
    /// the rule "routing inside the section" is waived.
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
    /// section, a TCA longer than its span (by more than 10%).
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
                let name = || format!("actuators[{i}].routing");
                routing_in_section(&self.body.section, &a.routing, name)?;
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
                    format!("0 <= s_start < body length {len} m"),
                ));
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
                    "expected {} values (one per actuator), got {}",
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

/// Error unless the routing of actuator `name()` lies inside the section
/// (on or inside the edge; checked in 64 directions for a helix).
fn routing_in_section(
    section: &Section,
    routing: &Routing,
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
        let r = x.hypot(y);
        if r == 0.0 {
            continue;
        }
        let edge = section.edge_distance(y.atan2(x));
        if r > edge * (1.0 + 1e-9) {
            return Err(Error::input(
                &name(),
                format!(
                    "routing offset {r:.6e} m at ({x:.6e}, {y:.6e}) m lies outside the section \
                     (edge at {edge:.6e} m in that direction); for actuators guided by spacer \
                     disks outside the backbone use `Robot(..., spacer_disks=True)` \
                     (Rust: `Robot::with_spacer_disks`)"
                ),
            ));
        }
    }
    Ok(())
}

/// Error unless a TCA of coiled length `coiled_length` \[m\] fits the span
/// `s_end - s_start` \[m\] of actuator `name()`.
fn tca_fits_span(coiled_length: f64, actuator: &Actuator, name: impl Fn() -> String) -> Result<()> {
    let span = actuator.s_end - actuator.s_start;
    if coiled_length > SPAN_SLACK * span {
        return Err(Error::input(
            &name(),
            format!(
                "the TCA's coiled_length {coiled_length} m exceeds its anchored span s_end - s_start = {span} m \
                 (by more than 10%); shorten the TCA or move its anchors"
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
            format!("pretension_n stretches the TCA by {stretch} m, more than its span {span} m"),
        ));
    }
    Ok(ratio)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn routing_outside_a_14_mm_body_is_rejected() {
        let s = Section::Circle { diameter: 14e-3 };
        let a = || "a".to_string();
        assert!(routing_in_section(&s, &Routing::Straight { x: 5e-3, y: 0.0 }, a).is_ok());
        let e = routing_in_section(&s, &Routing::Straight { x: 20e-3, y: 0.0 }, || {
            "actuators[0].routing".to_string()
        })
        .unwrap_err();
        assert!(e.to_string().contains("actuators[0].routing"));
        assert!(routing_in_section(
            &s,
            &Routing::Helix {
                radius: 8e-3,
                rate: 1.0,
                phase: 0.0
            },
            a
        )
        .is_err());
    }
}
