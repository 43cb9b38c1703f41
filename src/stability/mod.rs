//! Elastic stability of a shooting equilibrium (beyond the paper; see
//! `docs/stability.md`).
//!
//! # Criterion
//!
//! Till and Rucker ("Elastic Stability of Cosserat Rods and Parallel
//! Continuum Robots", IEEE T-RO 2017) test an equilibrium of a rod with a
//! fixed base and a free (natural) tip under conservative loads by Jacobi's
//! conjugate-point condition: it is stable iff the tangent map from the base
//! unknowns to the wrench at `s`,
//!
//! `Y(s) = d(n, m)(s) / d(n(0), m(0))`                                  (S1)
//!
//! is non-singular for every `s` in `(0, L]`: at a zero of `det Y(s)` the
//! truncated rod `[0, s]` under the same dead loads admits a neutral
//! perturbation. We carry the positions and rotations along too,
//! `H(s) = d(p, theta)(s) / d(n(0), m(0))` (`delta R R^T = [theta]x`), and use
//! the tip stiffness of the truncated rod
//!
//! `K(s) = Y(s) H(s)^-1`                                                (S2)
//!
//! (dimensionless: forces by `L^2/EI`, moments by `L/EI`, displacements by
//! `L`). `K(0+)` is positive definite (it grows like `1/s`); an eigenvalue
//! of `K` passes through zero exactly where `det Y` does. Testing the smallest
//! eigenvalue of the symmetric part of `K(s)` on the nodes, instead of the
//! sign of `det Y`, also catches the double roots of symmetric sections
//! (a round column buckles in two planes at once and `det Y` touches zero
//! without changing sign).
//!
//! # Extensions
//!
//! * Strings with a fixed tension (constant-tension tendons) add the
//!   string-length integrand `tau |p_i'|` to a local Lagrangian: (S1)-(S2)
//!   hold with the total wrench (body plus the strings crossing `s`). The
//!   tangent is taken with the tensions frozen.
//! * Tensions that depend on strain (TCA law, coil contact, linear tendon)
//!   add `sum_i k_i (d Lambda_i)^2 >= 0` to the second variation, with
//!   `k_i = d tau_i / d delta_i` and `Lambda_i` the actuator length, a
//!   non-local term. The Morse index of the second variation is then the
//!   number of Dirichlet conjugate points of the frozen-tension problem
//!   (zeros of `det H(s)` in `(0, L)`; none for a stable rod) plus the number
//!   of negative eigenvalues of the full tip stiffness
//!
//!   `K_full = Y_z Z (H_z Z)^-1`                                        (S3)
//!
//!   where `z = (v(0), u(0), delta_i)` are all shooting unknowns and the
//!   columns of `Z` span the `z` that keep every actuator consistent
//!   (`d(delta_i(L) - delta_i) = 0`): the tip stiffness with the actuator
//!   springs in. With constant tensions (S3) is `K(L)`.
//! * Dead loads (gravity, distributed and tip force) enter the wrench
//!   balance only; a world-fixed tip moment is not conservative in 3-D and
//!   is treated like a dead load (its non-symmetric part is dropped with the
//!   antisymmetric part of `K`).
//! * A blocked tip (mixed boundary condition: tip translation along some
//!   world directions held, contact force a Lagrange multiplier) restricts
//!   the tip variations: the index is that of (S3) restricted to the
//!   complement of the blocked directions.
//!
//! # Margin
//!
//! The smallest eigenvalue of the symmetric part of the dimensionless tip
//! stiffness at the tip: (S2) at `s = L` (free tip, no strain-dependent
//! actuator), or (S3) restricted to the free directions.
//! Positive iff stable (above `-NEUTRAL`: neutral symmetry modes count as
//! stable); it passes through zero at a buckling load or a fold.
//! If a conjugate point lies inside the body it is at most `-(L - s_c)/L`
//! (continuous at a first conjugate point reaching the tip). Along `s` only
//! positive definiteness is tested (`LDL^T`), to keep the verdict cheap.
//!
//! # Cost
//!
//! One tangent integration (the IVP with its exact variational equations,
//! [`crate::rod::integrate_tangent`]) gives every node's `Y`, `H` and the
//! actuator rows: along the six base strains only when the tensions are
//! frozen and the tip free, along all `6 + N` shooting unknowns otherwise.
//! The scan along `s` uses fixed-size 6 x 6 algebra on column arrays (no
//! allocation per node). [`stability_fd`] does the same from `7 + N`
//! recorded IVPs by forward differences (a cross-check).
//!
//! What the criterion needs, and why the pass cannot be narrower than the
//! Newton Jacobian's: along `s`, the Dirichlet test (`det H(s)`) and (S2)
//! need all six frozen-tension columns at every node; at the tip, (S3)
//! needs the `N` actuator columns and `E` as well. A tension change is a
//! source distributed along its string, so its tip response is an integral
//! of the full fundamental matrix (`12 + N` columns) over the string's span,
//! not a combination of the six base columns: the `N` actuator directions
//! must be integrated over the actuators' spans, which for strings that
//! start at the base is the whole body. The directions of a tangent pass
//! are lanes of one dual number (4, 8, 12 or 16 wide), and 6 directions
//! cost what 8 do, so the verdict's pass is the Jacobian's pass plus the
//! recorded nodes (measured in `benches/stability.rs`). It does not reuse
//! the solver's tangents: those are taken on a tenth of the grid and at the
//! last Newton iterate, not at the solution on the full grid. Under a
//! policy ([`solve_checked`]) the verdict is this pass at the solution the
//! forward solve hands back (with the accuracy control on, at the refined
//! solution).
//!
//! # Growth
//!
//! Under large tension the tangent columns grow apart exponentially and all
//! turn toward the dominant direction, so `H(s)` from one plain integration
//! becomes numerically singular. The verdict reads only their span, so the
//! pass re-orthonormalises them where their spread passes
//! [`GROWTH_BOUND`] (a stabilised march, Ascher, Mattheij & Russell, ch. 4;
//! the module `march`), within the same single integration: the check is a
//! `k x k` Gram matrix per node. The march bounds the spread of the state
//! columns; the `[H; Y]` columns the verdict reads can spread further (a
//! force enters the state through the strain, a factor `EA L^2 / EI`
//! softer), and a test form multiplying two columns squares that spread.
//! So every test reads the span through an orthonormal basis of the node's
//! `[H; Y]` columns (the module `verdict`): the tip stiffness `K` and the
//! form congruent to it are then as well conditioned as `K` itself.
//!
//! The equilibrium itself can be as hard to reproduce from the base: a
//! heavy body's IVP amplifies the rounding of its base unknowns past the
//! solution's accuracy, which is why the solver shoots from several nodes
//! (multiple shooting, [`crate::solve::forward`]). A verdict of a recorded
//! [`Solution`] therefore restarts the pass's state at every node where it
//! has left the solution's own (the hook of the tangent pass writes it), so
//! each step's tangent map is taken at the equilibrium, as the solver's
//! segments take theirs, while the tangent columns run on unbroken from the
//! base. On a solution of one IVP the pass never leaves it and is that IVP
//! bit for bit. (Above 16 directions, more than one pass of dual lanes, the
//! pass is the plain IVP's.)
//!
//! # Policy
//!
//! [`solve_checked`] wraps the forward solve with a [`Policy`]: report the
//! verdict with the solution (the default), require a stable one, continue
//! to a stable one at the same inputs ([`land`]), or skip the verdict.

use nalgebra::Vector3;

use crate::error::{Error, Result};
use crate::rod::Robot;
use crate::shooting::{Loads, Solution};

mod landing;
mod march;
mod policy;
mod tangents;
mod verdict;

pub use landing::land;
pub use landing::{Landing, Route};
pub use march::GROWTH_BOUND;
pub use policy::{solve_checked, sweep_checked, unstable_error, Checked, Continued, Policy};

/// Margins above `-NEUTRAL` count as stable: a symmetry leaves a neutral
/// mode (a buckled round column can turn about the vertical at no cost, so
/// its smallest tip stiffness is zero up to the ~1e-10 noise of the
/// finite-difference tangents).
pub const NEUTRAL: f64 = 1e-6;

/// Stability verdict of one equilibrium.
#[derive(Debug, Clone)]
pub struct Stability {
    /// True if the equilibrium is a strict local minimum of the energy.
    pub stable: bool,
    /// Smallest eigenvalue of the symmetric dimensionless tip stiffness
    /// (see the module docs); > 0 iff stable.
    pub margin: f64,
    /// Arc length \[m\] of the first conjugate point of the frozen-tension
    /// problem (first node where (S2) is no longer positive definite), if any.
    pub conjugate_point: Option<f64>,
    /// Arc length \[m\] of the nodes.
    pub s: Vec<f64>,
    /// Till and Rucker's determinant (S1) normalised to 1 at the base,
    /// `det(Y(s) Y(0)^-1)`, at each node (frozen tensions).
    pub determinant: Vec<f64>,
    /// At the tip node, the smallest eigenvalue of the symmetric part of
    /// (S2); at the other nodes `+1` where it is positive definite (above
    /// `-NEUTRAL`) and `-1` where not (an `LDL^T` test: no eigenvalue is
    /// computed there); the base node, where `K` is infinite, carries `+inf`.
    pub min_stiffness: Vec<f64>,
    /// Integrations for the verdict: 1 tangent IVP ([`stability`]) or
    /// `7 + N` IVPs ([`stability_fd`]).
    pub evaluations: usize,
    /// Softest tip mode: unit eigenvector `(p / L, theta)` (world frame) of
    /// the smallest eigenvalue of the symmetric tip stiffness at `s = L`
    /// (zeros if the stiffness is undefined).
    pub mode: [f64; 6],
}

/// What a verdict needs of an equilibrium: its scaled shooting unknowns
/// (`v(0)`, `u(0) L`, `delta_i / L`), inputs, loads and RK4 grid, and, where
/// its states are recorded, the recorded solution. A [`Solution`] gives one
/// (with itself as `along`); so does a batch row's tip solution (without).
#[derive(Debug, Clone, Copy)]
pub struct Equilibrium<'a> {
    /// The equilibrium's states at the grid nodes, if recorded: the verdict
    /// linearises about them, node by node (see # Growth in the module
    /// docs). `None`: about the IVP from the unknowns.
    pub along: Option<&'a Solution>,
    /// Scaled shooting unknowns (`6 + N`).
    pub unknowns: &'a [f64],
    /// Actuator inputs (`N`; temperature \[C\] for a TCA).
    pub inputs: &'a [f64],
    /// Tip loads (world frame).
    pub loads: Loads,
    /// RK4 steps over the body length.
    pub steps: usize,
}

impl<'a> From<&'a Solution> for Equilibrium<'a> {
    fn from(sol: &'a Solution) -> Self {
        Equilibrium {
            along: Some(sol),
            unknowns: &sol.unknowns,
            inputs: &sol.inputs,
            loads: sol.loads,
            steps: sol.steps,
        }
    }
}

/// Stiffness of each actuator's law, `d tau / d delta` \[N/m\], at the
/// equilibrium (central differences, so a kink nearby counts).
fn actuator_stiffness(robot: &Robot, eq: &Equilibrium<'_>) -> Result<Vec<f64>> {
    let len = robot.body.length;
    robot
        .actuators
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let d = eq.unknowns[6 + i] * len;
            let h = 1e-9 * len;
            let tp = a.law.tension(d + h, eq.inputs[i])?;
            let tm = a.law.tension(d - h, eq.inputs[i])?;
            Ok((tp - tm) / (2.0 * h))
        })
        .collect()
}

/// Validate the arguments; true if the verdict needs the full tip stiffness
/// (S3): an actuator whose tension depends on strain, or a blocked tip.
fn check(robot: &Robot, eq: &Equilibrium<'_>, blocked: &[Vector3<f64>]) -> Result<bool> {
    robot.validate()?;
    check_equilibrium(robot, eq, blocked)
}

/// [`check`] of a robot already validated (by the solve that found `eq`).
fn check_equilibrium(
    robot: &Robot,
    eq: &Equilibrium<'_>,
    blocked: &[Vector3<f64>],
) -> Result<bool> {
    let na = robot.actuators.len();
    if eq.unknowns.len() != 6 + na || eq.inputs.len() != na {
        return Err(Error::input(
            "solution",
            format!(
                "solution of a robot with {} actuators, this one has {na}",
                eq.inputs.len()
            ),
        ));
    }
    for (j, b) in blocked.iter().enumerate() {
        if !(b.iter().all(|v| v.is_finite()) && b.norm() > 0.0) {
            return Err(Error::input(
                &format!("blocked[{j}]"),
                "must be a finite non-zero vector",
            ));
        }
    }
    let springy = actuator_stiffness(robot, eq)?.iter().any(|k| k.abs() > 0.0);
    Ok(springy || !blocked.is_empty())
}

/// Stability of the equilibrium `sol` of `robot` (see the module docs), from
/// one tangent integration.
/// `blocked`: world directions along which the tip translation is held (a
/// blocked-tip solution's block normal); empty for a free tip.
pub fn stability(robot: &Robot, sol: &Solution, blocked: &[Vector3<f64>]) -> Result<Stability> {
    stability_at(robot, &Equilibrium::from(sol), blocked)
}

/// [`stability`] of an equilibrium given by its parts.
pub fn stability_at(
    robot: &Robot,
    eq: &Equilibrium<'_>,
    blocked: &[Vector3<f64>],
) -> Result<Stability> {
    let full = check(robot, eq, blocked)?;
    let (t, _, _, _) = tangents::exact_tangents(robot, eq, full, false, GROWTH_BOUND)?;
    Ok(verdict::verdict(t, robot.body.length, blocked, full, 1))
}

/// [`stability`] with the tangent columns re-orthonormalised where their
/// spread passes `bound` instead of [`GROWTH_BOUND`] (`f64::INFINITY`: the
/// plain fundamental matrix; `1.0`: at every node), and the number of
/// re-orthonormalisations done; for tests and comparisons.
#[doc(hidden)]
pub fn stability_with_bound(
    robot: &Robot,
    sol: &Solution,
    blocked: &[Vector3<f64>],
    bound: f64,
) -> Result<(Stability, usize)> {
    let eq = Equilibrium::from(sol);
    let full = check(robot, &eq, blocked)?;
    let (pass, _) = tangents::integrate_pass(robot, &eq, full, None, bound)?;
    let count = pass.reorthonormalised;
    let t = tangents::tangents_of(robot, &pass);
    Ok((
        verdict::verdict(t, robot.body.length, blocked, full, 1),
        count,
    ))
}

/// [`stability`] from forward-difference tangents (`7 + N` IVPs); for
/// cross-checks.
pub fn stability_fd(robot: &Robot, sol: &Solution, blocked: &[Vector3<f64>]) -> Result<Stability> {
    let full = check(robot, &Equilibrium::from(sol), blocked)?;
    let t = tangents::fd_tangents(robot, sol)?;
    let n = 7 + robot.actuators.len();
    Ok(verdict::verdict(t, robot.body.length, blocked, full, n))
}
