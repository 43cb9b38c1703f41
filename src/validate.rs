//! Geometric and size sanity rules for user-built models, and the caps on
//! work per call (issue 12/14). Pyo3-free; the Python bindings call these
//! when a `Robot` is assembled. Each rule names the argument it rejects.
//!
//! Rules:
//! * an actuator's routing must lie inside the cross-section (a 20 mm
//!   offset in a 14 mm body is an error);
//! * a TCA must not be longer than the span it is anchored over (a 70 mm
//!   TCA on a 30 mm body): `coiled_length <= 1.1 x span`;
//! * sizes that look like millimetres (body length above 10 m, section
//!   size above 1 m, TCA coil diameter above 0.1 m) are reported as a
//!   warning text, not an error, because they are valid SI numbers.

use crate::error::{Error, Result};
use crate::rod::{Actuator, Body, Routing, Section};

/// Largest number of RK4 steps over the body accepted per solve.
pub const MAX_STEPS: usize = 100_000;
/// Largest Newton (or inverse) iteration budget accepted per call.
pub const MAX_ITER: usize = 100_000;
/// Largest number of eq-43 increments of `blocked_temperature`.
pub const MAX_INCREMENTS: usize = 10_000;
/// Largest number of rows of one batch call (`solve_batch`, `sweep`).
pub const MAX_BATCH_ROWS: usize = 10_000_000;
/// Largest chunk size of a batch call.
pub const MAX_CHUNK: usize = 10_000_000;
/// Largest worker-thread count of a batch call.
pub const MAX_THREADS: usize = 1024;

/// Tolerance of the "fits the span" rule: a TCA may be up to 10% longer
/// than its anchored span (rounding of measured lengths), not more.
const SPAN_SLACK: f64 = 1.1;

/// A warning text if the body's sizes look like millimetres given as metres.
pub fn body_looks_like_mm(b: &Body) -> Option<String> {
    let (w, h) = section_extent(&b.section);
    if b.length > 10.0 || w.max(h) > 1.0 {
        Some(format!(
            "Body: length = {} m, section {} m x {} m: sizes are in metres (SI); \
             did you give millimetres? (40 mm is length=0.04)",
            b.length, w, h
        ))
    } else {
        None
    }
}

/// A warning text if a TCA's coil diameter \[m\] looks like millimetres.
pub fn coil_diameter_looks_like_mm(coil_diameter: f64) -> Option<String> {
    (coil_diameter > 0.1).then(|| {
        format!("Tca: coil_diameter = {coil_diameter} m: sizes are in metres (SI); did you give millimetres? (1.7 mm is 1.7e-3)")
    })
}

/// Width and height [m] of the section's bounding box (custom sections:
/// the edge distances along x and y, twice).
fn section_extent(s: &Section) -> (f64, f64) {
    match *s {
        Section::Circle { diameter } => (diameter, diameter),
        Section::Rectangle { width, height } => (width, height),
        Section::Custom { .. } => (
            2.0 * s.edge_distance(0.0),
            2.0 * s.edge_distance(std::f64::consts::FRAC_PI_2),
        ),
    }
}

/// Error unless the routing of actuator `name` lies inside the section
/// (on or inside the edge; checked in 64 directions for a helix).
pub fn routing_in_section(section: &Section, routing: &Routing, name: &str) -> Result<()> {
    let points: Vec<(f64, f64)> = match *routing {
        Routing::Straight { x, y } => vec![(x, y)],
        Routing::Helix { radius, .. } => (0..64)
            .map(|k| {
                let t = k as f64 * std::f64::consts::TAU / 64.0;
                (radius * t.cos(), radius * t.sin())
            })
            .collect(),
    };
    for (x, y) in points {
        let r = x.hypot(y);
        if r == 0.0 {
            continue;
        }
        let edge = section.edge_distance(y.atan2(x));
        if r > edge * (1.0 + 1e-9) {
            return Err(Error::input(
                name,
                format!(
                    "routing offset {r:.6e} m at ({x:.6e}, {y:.6e}) m lies outside the section \
                     (edge at {edge:.6e} m in that direction)"
                ),
            ));
        }
    }
    Ok(())
}

/// Error unless a TCA of coiled length `coiled_length` \[m\] fits the span
/// `s_end - s_start` \[m\] of actuator `name`.
pub fn tca_fits_span(coiled_length: f64, actuator: &Actuator, name: &str) -> Result<()> {
    let span = actuator.s_end - actuator.s_start;
    if coiled_length > SPAN_SLACK * span {
        return Err(Error::input(
            name,
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
pub fn pretension_length_ratio(
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

/// Error if an input lies below a TCA material's `t_min`, with the way out:
/// a custom `Material` valid at that ambient.
pub fn ambient_hint(input: f64, t_min: f64, t_max: f64, name: &str) -> Result<()> {
    if input.is_finite() && input < t_min {
        return Err(Error::param(
            name,
            input,
            format!(
                "{t_min} <= T <= {t_max} C, the material's valid range (the preset's fits start at 25 C and are \
                 not extrapolated). For a colder ambient build Material(..., t_ref=<ambient>, t_min=<ambient>) \
                 with coefficients valid there and pass it to Tca(..., material=...)"
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn routing_outside_a_14_mm_body_is_rejected() {
        let s = Section::Circle { diameter: 14e-3 };
        assert!(routing_in_section(&s, &Routing::Straight { x: 5e-3, y: 0.0 }, "a").is_ok());
        let e = routing_in_section(
            &s,
            &Routing::Straight { x: 20e-3, y: 0.0 },
            "actuators[0].routing",
        )
        .unwrap_err();
        assert!(e.to_string().contains("actuators[0].routing"));
        assert!(routing_in_section(
            &s,
            &Routing::Helix {
                radius: 8e-3,
                rate: 1.0,
                phase: 0.0
            },
            "a"
        )
        .is_err());
    }
}
