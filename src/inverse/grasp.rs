//! The grasp temperature (eq 44): `mu n F(T) = m g` on the blocked-tip
//! finger, by the paper's incremental method (eq 43) or a direct solve.

use nalgebra::Vector3;

use super::{
    blocked_force, blocked_temperature, blocked_variable_direct, blocked_variable_from, Block,
    BlockedResult, Groups,
};
use crate::error::{significant, Error, Result};
use crate::rod::Robot;
use crate::shooting::{solve_loaded, Loads, Solution, SolveOptions};
use crate::stability::Policy;

/// How the grasp temperature is found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GraspMethod {
    /// The paper's incremental inverse (eq 43) in this many force steps.
    Incremental(usize),
    /// One damped Newton solve of the multiple-shooting system with the
    /// actuation variable as one more unknown and the blocked-tip
    /// condition as one more row (a bordered solve), from the eq-43
    /// predictor of the whole force with the force law kept exact
    /// ([`super::blocked_variable_from`]).
    Direct,
}

/// A gripper of `fingers` identical fingers holding `mass` \[kg\] by
/// friction `mu` \[-\] under `gravity` \[m/s^2\]; each fingertip touches
/// the object where it rests at the `contact` inputs (`None`: the
/// reference inputs) and presses along `normal`.
#[derive(Debug, Clone, PartialEq)]
pub struct Grasp {
    pub normal: Vector3<f64>,
    pub mass: f64,
    pub mu: f64,
    pub fingers: usize,
    pub gravity: f64,
    pub contact: Option<Vec<f64>>,
    pub stability: Policy,
}

impl Grasp {
    /// Normal force \[N\] each finger must press with: `F = m g / (mu n)` (eq 44).
    pub fn force_per_finger(&self) -> Result<f64> {
        crate::error::positive("mass [kg]", self.mass)?;
        crate::error::positive("mu [-]", self.mu)?;
        crate::error::positive("gravity [m/s^2]", self.gravity)?;
        if self.fingers == 0 {
            return Err(Error::param("fingers", 0.0, ">= 1"));
        }
        Ok(self.mass * self.gravity / (self.mu * self.fingers as f64)) // eq (44)
    }

    /// The blocked result of one finger at the grasp temperature (its
    /// `evaluations` include the free solve at contact), and the point \[m\]
    /// where its tip is blocked (its free position at contact).
    pub fn solve(
        &self,
        robot: &Robot,
        groups: &Groups,
        method: GraspMethod,
        opts: &SolveOptions,
    ) -> Result<(BlockedResult, Vector3<f64>)> {
        let force = self.force_per_finger()?;
        groups.validate(robot)?;
        // the fixed actuators keep their fixed inputs at contact too
        let contact = groups.with_fixed_inputs(&match &self.contact {
            Some(c) => {
                robot.check_inputs(c)?;
                c.clone()
            }
            None => robot.reference_inputs(),
        });
        let start = solve_loaded(robot, &contact, &Loads::of(robot), opts, None)?;
        let block =
            Block::new(start.tip_position(), self.normal)?.with_stability(self.stability)?;
        let solved = match method {
            GraspMethod::Incremental(increments) => {
                blocked_temperature(robot, groups, &block, &start, force, increments, opts)
            }
            GraspMethod::Direct => {
                blocked_variable_from(robot, groups, &block, &start, force, opts)
            }
        };
        let mut res = match solved {
            Ok(res) => res,
            // either method fails alike when no input in range holds the
            // mass (the increments leave the range, Newton finds no root):
            // the error then gives the largest holdable mass
            Err(e @ (Error::NoSolution { .. } | Error::NotConverged { .. })) => {
                let Ok(sweep) = sweep(robot, groups, &block, &start, opts) else {
                    return Err(e);
                };
                if sweep.peak.force < force {
                    let unstable =
                        crate::stability::stability(robot, &sweep.at_peak, &[block.normal])
                            .ok()
                            .filter(|st| !st.stable)
                            .map(|st| st.margin);
                    return Err(self.cannot_hold(robot, groups, force, &sweep.peak, unstable));
                }
                // a force in reach: Newton on the same bordered system from
                // the sweep's blocked solve just past the root
                match (method, sweep.restart(robot, groups, &block, force, opts)) {
                    (GraspMethod::Direct, Some(mut res)) => {
                        // the IVPs of the first Newton and of the sweep count too
                        res.evaluations += e.evaluations() + sweep.peak.evaluations;
                        res
                    }
                    _ => return Err(e),
                }
            }
            Err(e) => return Err(e),
        };
        res.evaluations += start.evaluations; // the free solve at contact
        Ok((res, block.point))
    }

    /// The mass \[kg\] that a blocked-tip force `f` \[N\] per finger holds (eq 44).
    pub fn mass_held(&self, f: f64) -> f64 {
        f * self.mu * self.fingers as f64 / self.gravity
    }

    /// [`Error::NoSolution`] saying that the largest blocked force over the
    /// variable's range, `peak`, is below `force` \[N\], with the mass it holds.
    /// `unstable`: the stability margin of the finger at the peak with its
    /// tip held, if that equilibrium is unstable (then said too).
    fn cannot_hold(
        &self,
        robot: &Robot,
        groups: &Groups,
        force: f64,
        peak: &PeakForce,
        unstable: Option<f64>,
    ) -> Error {
        let (lo, hi) = groups.bounds(robot)[0];
        let unit = groups.unit(robot, 0);
        let mut reason = format!(
            "the finger cannot hold {} g (it needs a blocked force of {} N per finger): the largest blocked force in [{lo}, {hi}] {unit} is {} N ({} g) at {} {unit}",
            significant(self.mass * 1e3),
            significant(force),
            significant(peak.force),
            significant(self.mass_held(peak.force.max(0.0)) * 1e3),
            significant(peak.variable),
        );
        let driven = (0..robot.actuators.len())
            .filter(|&i| groups.variable_of(i).is_some())
            .count();
        if peak.force < 1e-6 * force && driven > 1 {
            reason += &format!(" (the {driven} actuators heated together do not press the tip along the normal: hold some at a fixed input with fixed_inputs, e.g. the one on the far side at ambient)");
        }
        if let Some(margin) = unstable {
            reason += &format!(" (an unstable equilibrium with the tip held, stability margin {}: the finger may not hold even that)", significant(margin));
        }
        Error::NoSolution { reason }
    }
}

/// The largest blocked-tip force over the variable's range.
#[derive(Debug, Clone, Copy)]
pub struct PeakForce {
    /// Force \[N\] the tip presses with at `variable`.
    pub force: f64,
    /// The actuation variable (input unit, C for a TCA) where the force peaks.
    pub variable: f64,
    /// IVPs integrated.
    pub evaluations: usize,
}

/// Samples of the blocked force on the variable's range above the start's
/// value, and golden-section steps on an interior peak.
const PEAK_SAMPLES: usize = 8;
const PEAK_REFINE: usize = 30;

/// The largest force \[N\] the tip blocked at `block` presses with for the
/// single actuation variable between its value at `start` (the contact,
/// zero force) and its upper bound: the direct blocked solve
/// ([`blocked_force`]) at 8 evenly spaced values, warm
/// started along the range, then golden-section refinement if the largest
/// sample is inside the range (a TCA's blocked force usually rises up to
/// the material's limit, so the peak is the bound itself, solved exactly).
pub fn peak_blocked_force(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    start: &Solution,
    opts: &SolveOptions,
) -> Result<PeakForce> {
    Ok(sweep(robot, groups, block, start, opts)?.peak)
}

/// The blocked-force samples of [`peak_blocked_force`] (variable, force
/// \[N\], blocked solution; sample 0 the contact) and the peak.
struct Sweep {
    samples: Vec<(f64, f64, Solution)>,
    peak: PeakForce,
    /// The blocked solution at the peak.
    at_peak: Solution,
}

impl Sweep {
    /// The direct solve for `force` \[N\] (the variable an extra unknown)
    /// from the first sample at or above it, its variable interpolated
    /// linearly between that sample and the one before; `None` if no
    /// sample brackets the force or Newton fails.
    fn restart(
        &self,
        robot: &Robot,
        groups: &Groups,
        block: &Block,
        force: f64,
        opts: &SolveOptions,
    ) -> Option<BlockedResult> {
        let k = self.samples.iter().position(|s| s.1 >= force)?;
        let (z1, f1, sol) = &self.samples[k];
        let guess = match k.checked_sub(1).map(|j| &self.samples[j]) {
            Some((z0, f0, _)) if f1 > f0 => z0 + (z1 - z0) * (force - f0) / (f1 - f0),
            _ => *z1,
        };
        blocked_variable_direct(robot, groups, block, force, guess, opts, Some(sol)).ok()
    }
}

/// The samples and peak of [`peak_blocked_force`].
fn sweep(
    robot: &Robot,
    groups: &Groups,
    block: &Block,
    start: &Solution,
    opts: &SolveOptions,
) -> Result<Sweep> {
    super::blocked::one_variable(robot, groups, "blocked-force peak")?;
    let quiet = block.with_stability(Policy::Off)?;
    let (_, hi) = groups.bounds(robot)[0];
    let z0 = groups.vars(&start.inputs)[0].min(hi);
    let mut evaluations = 0;
    let solve = |z: f64, warm: &(Solution, f64), evals: &mut usize| {
        let r = blocked_force(robot, groups, &quiet, &[z], opts, Some((&warm.0, warm.1)))?;
        *evals += r.evaluations;
        Ok::<_, Error>(r)
    };
    // samples z_k, k = 0..=PEAK_SAMPLES, z_0 the contact (force zero)
    let zk = |k: usize| z0 + (hi - z0) * k as f64 / PEAK_SAMPLES as f64;
    let mut warm: (Solution, f64) = (start.clone(), 0.0);
    let mut samples = vec![(z0, 0.0, start.clone())];
    for k in 1..=PEAK_SAMPLES {
        // a sample whose solve fails is left out (the sweep goes on warm
        // from the last converged one)
        if let Ok(r) = solve(zk(k), &warm, &mut evaluations) {
            samples.push((zk(k), r.force, r.solution.clone()));
            warm = (r.solution, r.force);
        }
    }
    let kmax = (0..samples.len())
        .max_by(|&a, &b| samples[a].1.total_cmp(&samples[b].1))
        .unwrap_or(0);
    let (zmax, fmax, _) = samples[kmax];
    if kmax == 0 || kmax + 1 == samples.len() {
        let peak = PeakForce {
            force: fmax,
            variable: zmax,
            evaluations,
        };
        let at_peak = samples[kmax].2.clone();
        return Ok(Sweep {
            samples,
            peak,
            at_peak,
        });
    }
    // golden section between the neighbouring samples (unimodal there by the samples)
    let phi = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (samples[kmax - 1].0, samples[kmax + 1].0);
    let mut best = (fmax, zmax, samples[kmax].2.clone());
    warm = (samples[kmax].2.clone(), fmax);
    let at = |z: f64, warm: &mut (Solution, f64), evals: &mut usize| -> f64 {
        match solve(z, warm, evals) {
            Ok(r) => {
                let f = r.force;
                *warm = (r.solution, r.force);
                f
            }
            Err(_) => f64::NEG_INFINITY,
        }
    };
    let (mut c, mut d) = (b - phi * (b - a), a + phi * (b - a));
    let mut fc = at(c, &mut warm, &mut evaluations);
    if fc > best.0 {
        best = (fc, c, warm.0.clone());
    }
    let mut fd = at(d, &mut warm, &mut evaluations);
    if fd > best.0 {
        best = (fd, d, warm.0.clone());
    }
    for _ in 0..PEAK_REFINE {
        if fc > fd {
            (b, d, fd) = (d, c, fc);
            c = b - phi * (b - a);
            fc = at(c, &mut warm, &mut evaluations);
            if fc > best.0 {
                best = (fc, c, warm.0.clone());
            }
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + phi * (b - a);
            fd = at(d, &mut warm, &mut evaluations);
            if fd > best.0 {
                best = (fd, d, warm.0.clone());
            }
        }
    }
    let peak = PeakForce {
        force: best.0,
        variable: best.1,
        evaluations,
    };
    Ok(Sweep {
        samples,
        peak,
        at_peak: best.2,
    })
}
/// Grasp temperature (eq 44) with the tip blocked where it rests at the
/// reference inputs, by `increments` eq-43 steps, with its stability
/// verdict (see [`Grasp`]).
#[allow(clippy::too_many_arguments)]
pub fn grasp(
    robot: &Robot,
    groups: &Groups,
    normal: &Vector3<f64>,
    mass: f64,
    mu: f64,
    fingers: usize,
    gravity: f64,
    increments: usize,
    opts: &SolveOptions,
) -> Result<BlockedResult> {
    let spec = Grasp {
        normal: *normal,
        mass,
        mu,
        fingers,
        gravity,
        contact: None,
        stability: Policy::Report,
    };
    Ok(spec
        .solve(robot, groups, GraspMethod::Incremental(increments), opts)?
        .0)
}
