//! A body with its actuators.

use super::{Actuator, Body};
use crate::error::{positive, Error, Result};

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
