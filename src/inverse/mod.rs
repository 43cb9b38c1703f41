//! Inverse kinetostatics (paper Section IV, eqs 34-43): actuation Jacobian,
//! compliance, tip-position inverse, blocked-tip force and grasping.
//!
//! Tip pose perturbations are measured in the world frame as
//! `[dp; dtheta]`, `dtheta` the rotation vector of `R1 R0^T`. Actuation
//! variables `z` map to actuator inputs through [`struct@Groups`] (actuator `i` takes
//! variable `groups\[i\]`, or keeps a fixed input): the two legs of a U-shaped
//! TCA share one temperature; of two opposite TCAs one may be heated while the
//! other is held at ambient. Tip wrenches `W = [F; M]` are in the world frame.

use nalgebra::{DMatrix, Matrix3, Rotation3, Vector3};

use crate::error::{Error, Result};
use crate::rod::Robot;

mod blocked;
mod grasp;
mod mixed;
mod mixed_solve;
mod predictor;
mod sensitivities;
mod tip;

pub use blocked::{
    blocked_force, blocked_temperature, blocked_variable_direct, blocked_variable_from, Block,
    BlockedResult,
};
pub use grasp::{grasp, peak_blocked_force, Grasp, GraspMethod, PeakForce};
pub(crate) use sensitivities::{exact_blocks, ExactBlocks};
pub use sensitivities::{
    sensitivities, sensitivities_exact, sensitivities_fast, sensitivities_with_step,
};
pub use tip::{tip_position_inverse, InverseOptions, InverseResult, InverseStatus};

/// Finite-difference scheme for [`sensitivities`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    /// Forward differences, step `sqrt(eps) max(1, |z|/z_c) z_c`: `12 + 2N` IVPs (the paper's count).
    Forward,
    /// Central differences, step `cbrt(eps) max(1, |z|/z_c) z_c`: twice the IVPs, `O(h^2)` error.
    Central,
    /// Exact: one tangent IVP ([`crate::rod::integrate_tangent`]) along the
    /// unknowns and the actuation variables, the wrench columns in closed
    /// form; no step size, no truncation error (the TCA law's temperature
    /// slope is differenced inside the law, see
    /// [`crate::rod::ForceLaw::tension_derivatives`]).
    Exact,
}

impl Scheme {
    /// Relative finite-difference step by rule: `sqrt(eps)` forward, `cbrt(eps)`
    /// central; `None` for the exact tangents.
    fn relative_step(self) -> Option<f64> {
        match self {
            Scheme::Forward => Some(f64::EPSILON.sqrt()),
            Scheme::Central => Some(f64::EPSILON.cbrt()),
            Scheme::Exact => None,
        }
    }
}

/// Actuation Jacobian and compliance at a solution.
#[derive(Debug, Clone)]
pub struct Sensitivities {
    /// `J = E_q - E_u B_u^-1 B_q` (eq 41): tip pose [m; rad] per unit of each
    /// actuation variable (per C for TCA temperatures), `6 x n_vars`.
    pub jacobian: DMatrix<f64>,
    /// `C = E_W - E_u B_u^-1 B_W` (eq 42): tip pose per unit tip wrench
    /// `[F (N); M (N m)]`, `6 x 6`.
    pub compliance: DMatrix<f64>,
    /// IVPs integrated.
    pub evaluations: usize,
}

/// What drives one actuator in an inverse problem: an actuation variable
/// (its index), or an input held fixed (in the actuator's input unit: C
/// for a TCA, N for a tendon).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Drive {
    /// Actuation variable `k` sets the input.
    Variable(usize),
    /// The input stays at this value.
    Fixed(f64),
}

/// Map of actuation variables to actuator inputs: actuator `i` takes the
/// variable of its [`Drive::Variable`] or keeps its [`Drive::Fixed`] input.
/// `Groups(map)` (every actuator driven, actuator `i` by variable `map[i]`)
/// and [`Groups::identity`] build the common cases; [`Groups::with_fixed`]
/// adds fixed inputs (e.g. one of two opposite TCAs heated, the other
/// held at ambient) and checks them against the robot.
#[derive(Debug, Clone, PartialEq)]
pub struct Groups {
    drives: Vec<Drive>,
}

/// Every actuator driven by a variable: actuator `i` by `map[i]` (the two
/// legs of a U-shaped TCA share one temperature with `Groups(vec![0, 0])`).
#[allow(non_snake_case)]
pub fn Groups(map: Vec<usize>) -> Groups {
    Groups {
        drives: map.into_iter().map(Drive::Variable).collect(),
    }
}

impl Groups {
    /// One variable per actuator.
    pub fn identity(n: usize) -> Self {
        Groups((0..n).collect())
    }

    /// Groups with fixed inputs, checked against `robot`: `fixed` lists
    /// `(actuator, input)` pairs (input in the actuator's unit, within its
    /// range: the same check as a forward solve's inputs); `groups` maps
    /// the other actuators to variables, either one entry per actuator
    /// (`None` for the fixed ones) or one entry per free actuator in order;
    /// `groups = None`: one variable per free actuator, in order. An
    /// actuator both grouped and fixed, or neither, is an error naming
    /// `groups` and `fixed_inputs`.
    pub fn with_fixed(
        robot: &Robot,
        groups: Option<&[Option<usize>]>,
        fixed: &[(usize, f64)],
    ) -> Result<Self> {
        let na = robot.actuators.len();
        let mut value: Vec<Option<f64>> = vec![None; na];
        for &(i, v) in fixed {
            if i >= na {
                return Err(Error::param(
                    "fixed_inputs key (actuator index)",
                    i as f64,
                    format!("0 <= index < {na} (the robot has {na} actuators)"),
                ));
            }
            if value[i].is_some() {
                return Err(Error::input(
                    "fixed_inputs",
                    format!("actuator {i} is given twice"),
                ));
            }
            robot.actuators[i]
                .law
                .check_input(v)
                .map_err(|e| e.renamed(|name| format!("fixed_inputs[{i}] ({name})")))?;
            value[i] = Some(v);
        }
        let n_free = value.iter().filter(|v| v.is_none()).count();
        let map: Vec<Option<usize>> = match groups {
            None => {
                let mut k = 0;
                value
                    .iter()
                    .map(|v| {
                        v.is_none().then(|| {
                            k += 1;
                            k - 1
                        })
                    })
                    .collect()
            }
            Some(g) if g.len() == na => g.to_vec(),
            Some(g) if g.len() == n_free && n_free < na => {
                let mut it = g.iter();
                let mut out = Vec::with_capacity(na);
                for (i, v) in value.iter().enumerate() {
                    if v.is_some() {
                        out.push(None);
                    } else {
                        let Some(&Some(k)) = it.next() else {
                            return Err(neither(i));
                        };
                        out.push(Some(k));
                    }
                }
                out
            }
            Some(g) => {
                let reason = if n_free < na {
                    format!(
                        "expected one entry per actuator ({na}, None for the fixed ones) or one per actuator not in fixed_inputs ({n_free}), got {}",
                        g.len()
                    )
                } else {
                    format!("expected one entry per actuator ({na}), got {}", g.len())
                };
                return Err(Error::input("groups", reason));
            }
        };
        let mut drives = Vec::with_capacity(na);
        for (i, (g, v)) in map.iter().zip(&value).enumerate() {
            drives.push(match (g, v) {
                (Some(k), None) => Drive::Variable(*k),
                (None, Some(v)) => Drive::Fixed(*v),
                (None, None) => return Err(neither(i)),
                (Some(k), Some(_)) => {
                    return Err(Error::input(
                        "groups / fixed_inputs",
                        format!(
                            "actuator {i} is both grouped (groups[{i}] = {k}) and fixed (in fixed_inputs): give it None in groups or leave it out of fixed_inputs"
                        ),
                    ))
                }
            });
        }
        let g = Groups { drives };
        g.validate(robot)?;
        Ok(g)
    }

    /// What drives each actuator.
    pub fn drives(&self) -> &[Drive] {
        &self.drives
    }

    /// The variable driving actuator `i` (`None`: its input is fixed).
    pub fn variable_of(&self, i: usize) -> Option<usize> {
        match self.drives.get(i) {
            Some(Drive::Variable(k)) => Some(*k),
            _ => None,
        }
    }

    /// Number of variables.
    pub fn n_vars(&self) -> usize {
        self.drives
            .iter()
            .filter_map(|d| match d {
                Drive::Variable(k) => Some(k + 1),
                Drive::Fixed(_) => None,
            })
            .max()
            .unwrap_or(0)
    }

    /// Validate against a robot: one entry per actuator, variables `0..n`
    /// without gaps, fixed inputs within their actuators' ranges.
    pub fn validate(&self, robot: &Robot) -> Result<()> {
        if self.drives.len() != robot.actuators.len() {
            return Err(Error::input(
                "groups",
                format!(
                    "expected one entry per actuator ({}), got {}",
                    robot.actuators.len(),
                    self.drives.len()
                ),
            ));
        }
        let n = self.n_vars();
        for k in 0..n {
            if !self.drives.contains(&Drive::Variable(k)) {
                return Err(Error::input(
                    "groups",
                    format!("variable {k} drives no actuator (use 0..n without gaps)"),
                ));
            }
        }
        for (i, (d, a)) in self.drives.iter().zip(&robot.actuators).enumerate() {
            if let Drive::Fixed(v) = d {
                a.law
                    .check_input(*v)
                    .map_err(|e| e.renamed(|name| format!("fixed_inputs[{i}] ({name})")))?;
            }
        }
        Ok(())
    }

    /// Inputs from variables (fixed actuators at their fixed inputs).
    pub fn inputs(&self, z: &[f64]) -> Vec<f64> {
        self.drives
            .iter()
            .map(|d| match d {
                Drive::Variable(g) => z[*g],
                Drive::Fixed(v) => *v,
            })
            .collect()
    }

    /// `inputs` with the fixed actuators set to their fixed inputs (e.g.
    /// the reference inputs of a robot whose idle actuators are held).
    pub fn with_fixed_inputs(&self, inputs: &[f64]) -> Vec<f64> {
        self.drives
            .iter()
            .zip(inputs)
            .map(|(d, x)| match d {
                Drive::Variable(_) => *x,
                Drive::Fixed(v) => *v,
            })
            .collect()
    }

    /// Error unless the actuators with fixed inputs have them in `inputs`
    /// (the inputs of `name`, a solution the inverse starts from or is
    /// linearised at), to rounding (1e-12 relative).
    pub fn check_fixed(&self, inputs: &[f64], name: &str) -> Result<()> {
        for (i, (d, x)) in self.drives.iter().zip(inputs).enumerate() {
            if let Drive::Fixed(v) = d {
                if (x - v).abs() > 1e-12 * v.abs().max(1.0) {
                    return Err(Error::input(
                        &format!("fixed_inputs[{i}]"),
                        format!("{v} differs from the input {x} of actuator {i} in {name} (solve {name} with the fixed input)"),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Variables from inputs (first actuator of each group).
    pub fn vars(&self, inputs: &[f64]) -> Vec<f64> {
        let mut z = vec![0.0; self.n_vars()];
        for (i, d) in self.drives.iter().enumerate().rev() {
            if let Drive::Variable(g) = d {
                z[*g] = inputs[i];
            }
        }
        z
    }

    /// Bounds of each variable: the intersection of its actuators' input bounds.
    pub fn bounds(&self, robot: &Robot) -> Vec<(f64, f64)> {
        let mut b = vec![(f64::NEG_INFINITY, f64::INFINITY); self.n_vars()];
        for (a, d) in robot.actuators.iter().zip(&self.drives) {
            if let Drive::Variable(g) = d {
                let (lo, hi) = a.law.input_bounds();
                b[*g].0 = b[*g].0.max(lo);
                b[*g].1 = b[*g].1.min(hi);
            }
        }
        b
    }

    /// Unit of variable `k`'s input, from its first actuator's input name
    /// (`temperature [C]` gives `C`; empty when unknown).
    pub fn unit(&self, robot: &Robot, k: usize) -> String {
        let name = self
            .drives
            .iter()
            .zip(&robot.actuators)
            .find(|(d, _)| **d == Drive::Variable(k))
            .map_or("", |(_, a)| a.law.input_name());
        match (name.find('['), name.rfind(']')) {
            (Some(a), Some(b)) if b > a => name[a + 1..b].to_string(),
            _ => String::new(),
        }
    }
}

/// The error of an actuator with neither a variable nor a fixed input.
fn neither(i: usize) -> Error {
    Error::input(
        "groups / fixed_inputs",
        format!("actuator {i} has neither a variable in groups nor a value in fixed_inputs"),
    )
}

/// Rotation vector (log map) of a rotation matrix, accurate for tiny angles:
/// `theta = atan2(|w|, (tr R - 1) / 2)` with `w = vee((R - R^T) / 2) = sin(theta) axis`.
/// (An `acos` of the trace loses all digits of angles below ~1e-8 rad, which
/// finite differences produce.)
pub fn rotation_vector(r: &Matrix3<f64>) -> Vector3<f64> {
    let w = Vector3::new(
        r[(2, 1)] - r[(1, 2)],
        r[(0, 2)] - r[(2, 0)],
        r[(1, 0)] - r[(0, 1)],
    ) * 0.5;
    let sn = w.norm();
    let cs = 0.5 * (r.trace() - 1.0);
    if sn < 1e-300 {
        if cs > 0.0 {
            return Vector3::zeros();
        }
        // theta = pi: fall back on nalgebra's eigen-based axis
        return Rotation3::from_matrix_unchecked(*r).scaled_axis();
    }
    let th = sn.atan2(cs);
    if th > 3.1 {
        return Rotation3::from_matrix_unchecked(*r).scaled_axis();
    }
    w * (th / sn)
}

pub(crate) fn pose_delta(
    p0: &Vector3<f64>,
    r0: &Matrix3<f64>,
    p1: &Vector3<f64>,
    r1: &Matrix3<f64>,
) -> [f64; 6] {
    let dp = p1 - p0;
    let th = rotation_vector(&(r1 * r0.transpose()));
    [dp.x, dp.y, dp.z, th.x, th.y, th.z]
}

/// Characteristic force \[N\] and moment \[N m\] of a body: `E I / L^2`, `E I / L`.
pub fn load_scales(robot: &Robot) -> (f64, f64) {
    robot.body.load_scales()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiments::fig6_square;
    use crate::shooting::{solve_loaded, Loads, SolveOptions};

    /// A name in an error's message.
    fn says(e: Error, what: &str) -> bool {
        e.to_string().contains(what)
    }

    #[test]
    fn fixed_inputs_take_no_variable() {
        let robot = fig6_square(false); // two TCA legs, inputs in C, range [25, 160]
        let (lo, hi) = robot.actuators[1].law.input_bounds();
        for g in [
            Groups::with_fixed(&robot, None, &[(1, 40.0)]).unwrap(),
            Groups::with_fixed(&robot, Some(&[Some(0), None]), &[(1, 40.0)]).unwrap(),
            Groups::with_fixed(&robot, Some(&[Some(0)]), &[(1, 40.0)]).unwrap(),
        ] {
            assert_eq!(g.n_vars(), 1);
            assert_eq!(g.inputs(&[90.0]), vec![90.0, 40.0]);
            assert_eq!(g.vars(&[90.0, 40.0]), vec![90.0]);
            assert_eq!(g.variable_of(0), Some(0));
            assert_eq!(g.variable_of(1), None);
            // the variable's bounds are actuator 0's alone
            assert_eq!(
                g.bounds(&robot),
                vec![robot.actuators[0].law.input_bounds()]
            );
            assert_eq!(g.with_fixed_inputs(&[25.0, 25.0]), vec![25.0, 40.0]);
            assert_eq!(g.unit(&robot, 0), "C");
            assert!(g.check_fixed(&[70.0, 40.0], "start").is_ok());
            assert!(says(
                g.check_fixed(&[70.0, 41.0], "start").unwrap_err(),
                "fixed_inputs[1]"
            ));
        }
        // no fixed inputs: the plain map, validated as before
        let plain = Groups::with_fixed(&robot, Some(&[Some(0), Some(0)]), &[]).unwrap();
        assert_eq!(plain, Groups(vec![0, 0]));
        // every actuator fixed: no variable at all
        let none = Groups::with_fixed(&robot, None, &[(0, 30.0), (1, 40.0)]).unwrap();
        assert_eq!((none.n_vars(), none.inputs(&[])), (0, vec![30.0, 40.0]));
        let bad = |groups: Option<&[Option<usize>]>, fixed: &[(usize, f64)], what: &str| {
            let e = Groups::with_fixed(&robot, groups, fixed).unwrap_err();
            assert!(says(e.clone(), what), "{e} does not name {what}");
        };
        bad(None, &[(2, 40.0)], "fixed_inputs key");
        bad(None, &[(1, f64::NAN)], "fixed_inputs[1]");
        bad(None, &[(1, hi + 1.0)], "fixed_inputs[1]");
        bad(None, &[(1, lo - 1.0)], "fixed_inputs[1]");
        bad(None, &[(1, 40.0), (1, 50.0)], "fixed_inputs");
        bad(
            Some(&[Some(0), Some(0)]),
            &[(1, 40.0)],
            "groups / fixed_inputs",
        );
        bad(Some(&[Some(0), None]), &[], "groups / fixed_inputs");
        bad(Some(&[Some(0), Some(1), Some(0)]), &[(1, 40.0)], "groups");
        bad(Some(&[Some(1), None]), &[(1, 40.0)], "drives no actuator");
        // the out-of-range message is the forward solve's, renamed
        let solve_msg = robot
            .check_inputs(&[25.0, hi + 1.0])
            .unwrap_err()
            .to_string();
        let fixed_msg = Groups::with_fixed(&robot, None, &[(1, hi + 1.0)])
            .unwrap_err()
            .to_string();
        assert_eq!(
            fixed_msg.replace("fixed_inputs[1]", "inputs[1]"),
            solve_msg,
            "the fixed-input range error is Robot.solve's"
        );
    }

    /// The Jacobian with actuator 1 fixed is the variable-0 column of the
    /// one-variable-per-actuator Jacobian at the same solution (eq 41: the
    /// columns are independent partial derivatives).
    #[test]
    fn fixed_jacobian_is_the_free_column() {
        let robot = fig6_square(false);
        let opts = SolveOptions::default();
        let loads = Loads::of(&robot);
        let sol = solve_loaded(&robot, &[90.0, 40.0], &loads, &opts, None).unwrap();
        let both = sensitivities_exact(&robot, &sol, &loads, &Groups::identity(2), 100).unwrap();
        let fixed = Groups::with_fixed(&robot, None, &[(1, 40.0)]).unwrap();
        let one = sensitivities_exact(&robot, &sol, &loads, &fixed, 100).unwrap();
        assert_eq!(one.jacobian.ncols(), 1);
        // the same tangent IVP: equal to rounding
        let diff = (one.jacobian.column(0) - both.jacobian.column(0)).norm();
        assert!(diff <= 1e-12 * both.jacobian.norm(), "{diff:e}");
        assert!((&one.compliance - &both.compliance).norm() <= 1e-12 * both.compliance.norm());
    }
}
