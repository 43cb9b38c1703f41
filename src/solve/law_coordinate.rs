//! The actuator unknown of the multiple-shooting system: a coordinate along
//! the force law's curve instead of the elongation.
//!
//! An actuator's tension `tau(d)` can stiffen by orders of magnitude within
//! a fraction of a micrometre (a TCA's coils touching: `k_c / k_s ~ 400`).
//! With the elongation `d` as the unknown, a Newton step computed on the
//! soft side lands deep in the stiff side and its tension overshoots by that
//! ratio; damping then shrinks every step to the kink's width. Circuit
//! simulators limit such steps through the device law (Nagel, *SPICE2*,
//! UCB/ERL M520, 1975): the limited step approximates Newton's step in a
//! coordinate along the law's curve, which this module makes the unknown
//! itself:
//!
//! `sigma L = d + c (tau(d) - tau(0))`
//!
//! the actuator's elongation plus the elongation its added tension imposes
//! on the body: `c = l (1 / EA + r^2 / EI)` \[m/N\] is the body's compliance
//! seen by an actuator of span `l` at offset `r` from the centre line
//! (axial compression and bending under the eccentric pull; `EI` the
//! smaller bending stiffness). Where the law is softer than the body (`tau'
//! c << 1`) `sigma` moves with the elongation, where it is stiffer with the
//! tension; each term of the elongation row `(delta_i(s_end) - d) / L`
//! changes by at most one unit per unit of `sigma` either way (`d d / d
//! sigma = L / (1 + c tau')`), so a kink of the law is an `O(1)` change of
//! the Jacobian instead of a factor `k_c / k_s`. A tension that does not
//! depend on the elongation (a tendon pulled with a given force) leaves
//! `sigma = d / L`. Every force law is non-decreasing in the elongation
//! ([`ForceLaw`]), so `d sigma / d d >= 1 / L` and `sigma` fixes `d`
//! uniquely.

use crate::error::Result;
use crate::rod::{Actuator, ForceLaw, Robot};

/// An actuator at law coordinate `sigma`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LawPoint {
    /// Elongation \[m\].
    pub d: f64,
    /// Tension \[N\].
    pub tau: f64,
    /// `d d / d sigma` \[m\].
    pub dd: f64,
    /// `d tau / d sigma` \[N\].
    pub dtau: f64,
}

/// The law coordinate of one actuator at one input.
#[derive(Debug, Clone)]
pub(crate) struct LawCoordinate<'a> {
    law: &'a dyn ForceLaw,
    input: f64,
    /// The body length `L` \[m\] and its compliance `c` \[m/N\].
    len: f64,
    c: f64,
    /// `tau(0)` \[N\].
    tau0: f64,
    /// The law's kink interval ([`ForceLaw::kink`]) in the coordinate.
    kink: Option<(f64, f64)>,
}

impl<'a> LawCoordinate<'a> {
    /// The coordinate of actuator `a` of `robot` at `input` (see the
    /// module docs).
    pub(crate) fn of_actuator(robot: &Robot, a: &'a Actuator, input: f64) -> Result<Self> {
        let body = &robot.body;
        let (k_nu, k_omega) = body.stiffness();
        let (ea, ei) = (k_nu[(2, 2)], k_omega[(0, 0)].min(k_omega[(1, 1)]));
        let r = a.routing.distance();
        let span = a.s_end.min(body.length) - a.s_start;
        let c = span * (1.0 / ea + r * r / ei);
        Self::new(a.law.as_ref(), input, body.length, c)
    }

    /// The coordinate of `law` at `input` for a body of length `len` \[m\]
    /// whose compliance seen by the actuator is `c` \[m/N\].
    pub(crate) fn new(law: &'a dyn ForceLaw, input: f64, len: f64, c: f64) -> Result<Self> {
        let tau0 = law.tension(0.0, input)?;
        Ok(LawCoordinate {
            law,
            input,
            len,
            c,
            tau0,
            kink: None,
        }
        .with_kink())
    }

    /// `self` with the law's kink interval mapped to the coordinate (none
    /// where the law cannot be evaluated at its ends).
    fn with_kink(mut self) -> Self {
        let ends = self.law.kink(self.input);
        self.kink = ends.and_then(|(a, b)| Some((self.of(a).ok()?, self.of(b).ok()?)));
        self
    }

    /// The fraction `lambda` in `(0, 1)` of the step `dsigma` from `sigma`
    /// at which the coordinate reaches the far end of the law's kink
    /// interval, if the whole step passes over the interval from one side
    /// to the other: up to there the law is the smooth piece the Jacobian
    /// was linearised on, beyond it the other piece.
    pub(crate) fn crossing(&self, sigma: f64, dsigma: f64) -> Option<f64> {
        let (a, b) = self.kink?;
        let end = sigma + dsigma;
        let far = match (sigma, end) {
            _ if sigma >= b && end < a => a,
            _ if sigma <= a && end > b => b,
            _ => return None,
        };
        Some((far - sigma) / dsigma).filter(|l| *l > 0.0 && *l < 1.0)
    }

    /// The coordinate of elongation `d` \[m\].
    pub(crate) fn of(&self, d: f64) -> Result<f64> {
        Ok((d + self.c * (self.law.tension(d, self.input)? - self.tau0)) / self.len)
    }

    /// `g(d) = sigma(d) - sigma` with the tension \[N\] and its slope \[N/m\].
    fn defect(&self, d: f64, sigma: f64) -> Result<(f64, f64, f64)> {
        let (tau, slope) = self.law.tension_and_slope(d, self.input)?;
        Ok((
            (d + self.c * (tau - self.tau0)) / self.len - sigma,
            tau,
            slope,
        ))
    }

    /// The point whose coordinate is `sigma`: the root of
    /// `g(d) = sigma(d) - sigma` by Newton's method safeguarded by
    /// bisection (Press et al., *Numerical Recipes*, 3rd ed., sec. 9.4,
    /// `rtsafe`) from the elongation
    /// `start` \[m\] (a nearby root, e.g. the last one found), or from the
    /// unstretched actuator `d = 0`, where every law is defined, if the law
    /// cannot be evaluated at `start`. Since `g' >= 1 / L`, the root lies
    /// within `L |g(d0)|` of any `d0`, which brackets it from the first
    /// evaluation. A trial point where the law cannot be evaluated (outside
    /// its domain) moves halfway back to the last point that could; the
    /// law's error if 60 halvings (the step below `1e-18` of itself) do not
    /// reach its domain.
    pub(crate) fn point(&self, sigma: f64, start: f64) -> Result<LawPoint> {
        let slope_of = |slope: f64| (1.0 + self.c * slope) / self.len;
        let mut d = start;
        let mut at = match self.defect(d, sigma) {
            Ok(v) => v,
            Err(_) => {
                d = 0.0;
                self.defect(d, sigma)?
            }
        };
        let (mut lo, mut hi) = match at.0 > 0.0 {
            true => (d - self.len * at.0, d),
            false => (d, d - self.len * at.0),
        };
        // each step at least halves the bracket or is a Newton step inside
        // it: 200 bisections reach any f64 bracket's rounding width
        for _ in 0..200 {
            let g = at.0;
            if g == 0.0 || hi - lo <= 4.0 * f64::EPSILON * d.abs().max(hi.abs()) {
                break;
            }
            if g > 0.0 {
                hi = d;
            } else {
                lo = d;
            }
            let newton = d - g / slope_of(at.2);
            let mut next = match newton > lo && newton < hi {
                true => newton,
                false => 0.5 * (lo + hi),
            };
            if next == d {
                break;
            }
            let mut halvings = 0;
            at = loop {
                match self.defect(next, sigma) {
                    Ok(v) => break v,
                    Err(e) if halvings == 60 => return Err(e),
                    Err(_) => (next, halvings) = (0.5 * (next + d), halvings + 1),
                }
            };
            d = next;
        }
        let (_, tau, slope) = at;
        let dd = 1.0 / slope_of(slope);
        Ok(LawPoint {
            d,
            tau,
            dd,
            dtau: slope * dd,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rod::{ConstantTension, LinearTendon};
    use std::sync::Arc;

    fn laws() -> Vec<(Arc<dyn ForceLaw>, Vec<f64>)> {
        let tca = crate::experiments::fig6_square(true).actuators[0]
            .law
            .clone();
        vec![
            (tca, vec![25.0, 60.0, 100.0, 160.0]),
            (Arc::new(ConstantTension), vec![0.0, 0.3, 5.0]),
            (Arc::new(LinearTendon { stiffness: 200.0 }), vec![0.0, 1e-3]),
        ]
    }

    /// Every built-in law is non-decreasing in the elongation, as the
    /// coordinate requires ([`ForceLaw`]): sampled on 2,000 elongations from
    /// coil contact to past a TCA's straight-fibre limit (where its law
    /// stops), at each input.
    #[test]
    fn every_law_is_non_decreasing() {
        for (law, inputs) in laws() {
            for &input in &inputs {
                let tension = |i: usize| law.tension(-1e-3 + 6e-5 * i as f64, input).ok();
                let taus: Vec<f64> = (0..2000).map_while(tension).collect();
                assert!(taus.len() > 100, "{} at {input}", law.kind());
                assert!(
                    taus.windows(2).all(|w| w[1] >= w[0]),
                    "{} at {input}",
                    law.kind()
                );
            }
        }
    }

    /// The point of a coordinate has that coordinate, to rounding (a few
    /// eps of the coordinate's terms), and its derivatives are the law's
    /// chained through `d d / d sigma = 1 / (1 / L + fs tau')`, checked
    /// against central differences of the inversion (step 1e-6, error
    /// O(h^2) away from the law's kinks, which the samples avoid).
    #[test]
    fn point_inverts_the_coordinate_with_its_derivatives() {
        for (law, inputs) in laws() {
            for &input in &inputs {
                let c = LawCoordinate::new(law.as_ref(), input, 0.06, 3.0).unwrap();
                for d in [-3e-4, -1e-6, 1e-5, 2e-3, 8e-3] {
                    let Ok(sigma) = c.of(d) else {
                        continue;
                    };
                    let p = c.point(sigma, 0.0).unwrap();
                    let back = c.of(p.d).unwrap();
                    let size = (d.abs() + c.c * (p.tau.abs() + c.tau0.abs())) / c.len;
                    assert!((back - sigma).abs() <= 8.0 * f64::EPSILON * size.max(1e-300));
                    let h = 1e-6;
                    let up = c.point(sigma + h, p.d).unwrap();
                    let down = c.point(sigma - h, 0.0).unwrap();
                    let dd = (up.d - down.d) / (2.0 * h);
                    let dtau = (up.tau - down.tau) / (2.0 * h);
                    assert!(
                        (dd - p.dd).abs() <= 1e-6 * p.dd.abs().max(1e-15),
                        "{dd} {}",
                        p.dd
                    );
                    assert!((dtau - p.dtau).abs() <= 1e-6 * p.dtau.abs().max(1e-9));
                }
            }
        }
    }

    /// A TCA's contact kink is an O(1) change in the coordinate: across the
    /// coils touching, `d tau / d sigma` stays below the tension scale `1 /
    /// fs` (it is `tau' / (1 / L + fs tau')`), while `d tau / d d` jumps by
    /// the contact stiffness ratio.
    #[test]
    fn contact_is_bounded_in_the_coordinate() {
        let (law, _) = laws().remove(0);
        let c = LawCoordinate::new(law.as_ref(), 100.0, 0.06, 3.0).unwrap();
        let (_, soft, _) = law.tension_derivatives(1e-4, 100.0).unwrap();
        let (_, stiff, _) = law.tension_derivatives(-1e-4, 100.0).unwrap();
        assert!(stiff > 50.0 * soft, "{soft} {stiff}");
        for d in [1e-4, -1e-4] {
            let p = c.point(c.of(d).unwrap(), 0.0).unwrap();
            assert!(p.dtau > 0.0 && p.dtau < c.len / c.c);
            assert!(p.dd > 0.0 && p.dd <= c.len);
        }
    }

    /// A step of the coordinate over a law's kink interval stops at its far
    /// end, whose elongation is the interval's end (to the inversion's
    /// rounding, a few eps of the coordinate's terms), in either direction;
    /// a step that stays on one side, or starts inside, has no crossing.
    #[test]
    fn a_step_over_a_kink_stops_at_its_far_end() {
        for (law, inputs) in laws() {
            for &input in &inputs {
                let c = LawCoordinate::new(law.as_ref(), input, 0.06, 3.0).unwrap();
                let Some((a, b)) = law.kink(input) else {
                    assert!(c.crossing(1.0, -2.0).is_none());
                    continue;
                };
                let (sa, sb) = (c.of(a).unwrap(), c.of(b).unwrap());
                let w = sb - sa + 1e-3;
                for (from, step, end) in [(sb + 1e-3, -2.0 * w, a), (sa - 1e-3, 2.0 * w, b)] {
                    let l = c.crossing(from, step).unwrap();
                    let d = c.point(from + l * step, end).unwrap().d;
                    let size = (end.abs() + c.c * c.tau0.abs()) / c.len + from.abs();
                    assert!(
                        (c.of(d).unwrap() - c.of(end).unwrap()).abs() <= 8.0 * f64::EPSILON * size
                    );
                }
                assert!(c.crossing(sb + 1e-3, 1e-3).is_none());
                assert!(c.crossing(sa - 1e-3, -1e-3).is_none());
                assert!(c.crossing(0.5 * (sa + sb), -w).is_none() || sa == sb);
            }
        }
    }
}
