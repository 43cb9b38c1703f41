//! The Cosserat rod with embedded string-like actuators (paper Section III,
//! eqs 7-31) and its initial value problem.
//!
//! Frames and signs:
//! * world frame: base at the origin, reference tangent `+z`; `R(s)` maps body
//!   to world; body strains `v = nu` (linear) and `u = omega` (angular);
//! * actuator `i` runs at body-frame offset `r_i(s)` between arc lengths
//!   `s_start` and `s_end`; its scalar force `tau_i` is a *tension* (positive
//!   pulls the anchors together); a heated extension TCA pushes, `tau_i < 0`;
//! * loads are given in the world frame: gravity `g` \[m/s^2\], distributed force
//!   \[N/m\] and moment \[N m/m\], tip force \[N\] and moment \[N m\].
//!
//! Rotation: `R` is carried as a unit quaternion `q` with `q' = q (0, u) / 2`
//! (eq 8), integrated by RK4 and renormalised after every step. `R(q)` is
//! orthogonal to rounding for any unit `q`, so the only drift is the
//! quaternion's norm, which renormalisation removes each step.
//!
//! String mechanics (Rucker & Webster, T-RO 2011): a string of constant tension
//! `tau` on the curve `p_a = p + R r` loads the body by `tau t_a'` per unit
//! length (eqs 14-15) and by point forces `-tau t_a` at its distal anchor and
//! `+tau t_a` at its proximal anchor. The distributed load depends on `v'` and
//! `u'`, which gives the linear system (25) with blocks (26)-(31).

mod actuator;
mod anchors;
mod body;
pub mod dual;
mod eq25;
mod grid;
mod ivp;
mod lanes;
mod ode;
mod ode_tangent;
mod robot;
mod section;
mod tangent;
mod tangent_nodes;

pub use actuator::{Actuator, ConstantTension, ForceLaw, LinearTendon, Routing, TcaLaw};
pub use body::{Body, Shear, DEFAULT_POISSON};
pub use grid::{Grid, Interval, Stretch};
pub(crate) use ivp::integrate_flat;
pub use ivp::{integrate, IvpResult, IvpSpec};
pub use robot::{Robot, BASE_STATES};
pub use section::Section;
pub use tangent::{
    integrate_tangent, with_dual_rhs, Record, TangentIvp, TangentNode, TangentNodes, TangentSeeds,
};

use nalgebra::{Matrix3, Quaternion, Vector3};

/// Rotation matrix of a (unit) quaternion `[w, x, y, z]`.
#[inline]
pub fn rot(q: &Quaternion<f64>) -> Matrix3<f64> {
    let (w, x, y, z) = (q.w, q.i, q.j, q.k);
    Matrix3::new(
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    )
}

/// A state of the rod at one arc length.
#[derive(Debug, Clone, PartialEq)]
pub struct RodState {
    /// Position \[m\], world frame.
    pub p: Vector3<f64>,
    /// Orientation (unit quaternion, body to world).
    pub q: Quaternion<f64>,
    /// Linear strain `nu` \[-\], body frame.
    pub v: Vector3<f64>,
    /// Angular strain `omega` \[1/m\], body frame.
    pub u: Vector3<f64>,
    /// Actuator elongations `delta_i(s)` \[m\].
    pub delta: Vec<f64>,
}

impl RodState {
    pub(crate) fn from_slice(y: &[f64]) -> Self {
        RodState {
            p: Vector3::new(y[0], y[1], y[2]),
            q: Quaternion::new(y[3], y[4], y[5], y[6]),
            v: Vector3::new(y[7], y[8], y[9]),
            u: Vector3::new(y[10], y[11], y[12]),
            delta: y[13..].to_vec(),
        }
    }
    /// Rotation matrix `R` (body to world).
    pub fn rotation(&self) -> Matrix3<f64> {
        rot(&self.q)
    }
}

/// The recorded nodes of one IVP, flat (one allocation for all of them):
/// arc lengths \[m\] and the state vectors, `n` values per node in the
/// IVP's order (`p`, `q`, `v`, `u`, `delta`, as [`RodState`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FlatNodes {
    /// Arc length of each node \[m\].
    pub s: Vec<f64>,
    /// The states, `n` per node.
    pub y: Vec<f64>,
    /// Values per node.
    pub n: usize,
}

impl FlatNodes {
    /// Room for `nodes` nodes of `n` values each.
    pub(crate) fn reserve(&mut self, n: usize, nodes: usize) {
        self.n = n;
        self.s.reserve(nodes);
        self.y.reserve(n * nodes);
    }
    /// Append the node `(s, y)`.
    #[inline(always)]
    pub(crate) fn push(&mut self, s: f64, y: &[f64]) {
        self.s.push(s);
        self.y.extend_from_slice(y);
    }
    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.s.len()
    }
    /// Whether there is no node.
    pub fn is_empty(&self) -> bool {
        self.s.is_empty()
    }
    /// The state vector of node `k`.
    pub fn state(&self, k: usize) -> &[f64] {
        &self.y[k * self.n..(k + 1) * self.n]
    }
    /// The state vectors, in order.
    pub fn states(&self) -> impl Iterator<Item = &[f64]> {
        self.y.chunks_exact(self.n.max(1))
    }
    /// The nodes as `(s, state)` pairs.
    pub fn to_states(&self) -> Vec<(f64, RodState)> {
        (self.s.iter().zip(self.states()))
            .map(|(&s, y)| (s, RodState::from_slice(y)))
            .collect()
    }
    /// The nodes `(s, state)`, flat.
    pub fn from_states(nodes: &[(f64, RodState)]) -> Self {
        let n = nodes
            .first()
            .map_or(0, |(_, st)| BASE_STATES + st.delta.len());
        let mut out = FlatNodes::default();
        out.reserve(n, nodes.len());
        for (s, st) in nodes {
            out.s.push(*s);
            out.y.extend_from_slice(st.p.as_slice());
            // (`y` holds `q` as `w, x, y, z`; nalgebra's `coords` are `x, y, z, w`)
            out.y.extend_from_slice(&[st.q.w, st.q.i, st.q.j, st.q.k]);
            out.y.extend_from_slice(st.v.as_slice());
            out.y.extend_from_slice(st.u.as_slice());
            out.y.extend_from_slice(&st.delta);
        }
        out
    }
}
