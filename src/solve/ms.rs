//! The forward problem (paper Section III, eqs 22-33) as a multiple-shooting
//! system: the unknowns are the rod's state at the start of each segment of
//! the grid, the residual the continuity defects between segments and the
//! conditions at the tip (Ascher, Mattheij & Russell, *Numerical Solution
//! of Boundary Value Problems for ODEs*, SIAM 1995, sec. 4.3).
//!
//! # Unknowns (scaled to be dimensionless and of order one)
//! * block 0, the base: `nu(0)`, `L omega(0)`, `sigma` (`sigma_i` the law
//!   coordinate of actuator `i`, [`super::law_coordinate`], which sets its
//!   elongation `d_i` and its tension `tau_i(d_i)`);
//! * block `k >= 1`, the state at the first node of segment `k`: `p / L`,
//!   `theta` (the rotation `q = q_ref exp(theta / 2)` from a reference
//!   quaternion fixed for the solve), `nu`, `L omega`, `delta / L` (the
//!   strings' elongations so far), and again `sigma`: the actuators' law
//!   coordinates are carried as constant states (`sigma' = 0`) so that
//!   every equation couples one block with the next only (AMR sec. 1.4).
//!
//! # Residual
//! * block `k` below the last: the end state of segment `k` minus the start
//!   of segment `k + 1` in the same scaling (the rotation as `2 vec(q_b^-1
//!   q_a)`, which is `theta` to first order), `sigma_k - sigma_(k+1)`, and
//!   `(delta_i(s_end,i) - d_i) / L` for the actuators whose distal anchor
//!   the segment leaves;
//! * the last block: the tip balance (32)-(33) as strain errors (`r_F L^2 /
//!   EI`, `r_M L / EI`, as single shooting) and the elongation rows of the
//!   actuators anchored in the last segment or at the tip.
//!
//! With one segment this is single shooting exactly. The Jacobian blocks
//! come from the exact tangents of the discrete RK4 map
//! ([`crate::rod::IvpSpec::integrate_stretch_tangent`]); positions and the
//! strings' elongations enter nothing but themselves, so their columns are
//! identities set here, not integrated.

use nalgebra::{DMatrix, Quaternion, Vector3};

use super::law_coordinate::LawCoordinate;
use super::residual::{residual_scales, Loads};
use crate::error::{Error, Result};
use crate::rod::{Grid, IvpResult, IvpSpec, Robot, Stretch, TangentSeeds, BASE_STATES};

/// Scaled state values per interior block: `p, theta, nu, omega` and the
/// `delta` and `sigma` of each actuator.
fn interior_len(na: usize) -> usize {
    12 + 2 * na
}

/// Number of unknowns in the first `blocks` blocks, with `na` actuators.
pub(crate) fn unknowns(na: usize, blocks: usize) -> usize {
    match blocks {
        0 => 0,
        _ => 6 + na + (blocks - 1) * interior_len(na),
    }
}

/// The multiple-shooting system of one forward problem.
pub struct MultipleShooting<'a> {
    robot: &'a Robot,
    inputs: &'a [f64],
    loads: Loads,
    steps: usize,
    /// First node of each segment (node 0 first), then the tip node.
    bounds: Vec<usize>,
    /// Reference rotation of each block's `theta` (block 0's unused).
    charts: Vec<Quaternion<f64>>,
    /// For each actuator, the segment that records its elongation.
    ends_in: Vec<usize>,
    /// The actuators' law coordinates at their inputs.
    laws: Vec<LawCoordinate<'a>>,
    /// The last elongation \[m\] of each block's actuators, where the next
    /// inversion of the law coordinate starts ([`LawCoordinate::point`]).
    hints: Vec<std::cell::Cell<f64>>,
    /// `D_k` and `E_k` of the last linearisation.
    pub(crate) d: Vec<DMatrix<f64>>,
    pub(crate) e: Vec<DMatrix<f64>>,
    /// IVPs spent over the whole grid (a tangent IVP of `k` directions counts
    /// `1 + k / 8`).
    pub work: f64,
    /// Whether [`MultipleShooting::residual`] records its nodes.
    record: bool,
    /// The recorded nodes of the last residual evaluation.
    recorded: Option<Recording>,
    /// The tip (the last segment's end state) at the last evaluation, and
    /// after a linearisation its position's tangent ([`MultipleShooting::tip_state`]).
    tip: Option<(crate::rod::RodState, Option<DMatrix<f64>>)>,
}

/// The nodes and end results of one residual evaluation, the solution's
/// profile where that evaluation is Newton's last: recording writes the
/// states the IVP computes anyway, and a converged solve then needs no
/// further integration to assemble its solution.
pub(crate) struct Recording {
    /// The unknowns evaluated.
    pub x: Vec<f64>,
    /// Every segment's nodes, base to tip.
    pub nodes: crate::rod::FlatNodes,
    /// The last segment's IVP with every actuator's elongation \[m\] at its
    /// distal anchor (from the segment that records it).
    pub ivp: IvpResult,
    /// The tensions \[N\] of block 0.
    pub tau0: Vec<f64>,
}

/// The state of one block in IVP units, with the elongations and tensions
/// its law coordinates imply.
struct BlockState {
    y: Vec<f64>,
    tau: Vec<f64>,
    /// `d tau_i / d sigma_i` \[N\].
    slope: Vec<f64>,
    /// `d_i / L` and `d (d_i / L) / d sigma_i`.
    d: Vec<f64>,
    dd: Vec<f64>,
}

impl<'a> MultipleShooting<'a> {
    /// The system of `robot` at `inputs` under `loads` on `steps` RK4 steps,
    /// with segments starting at the grid nodes `starts` (node 0 first,
    /// increasing, below the tip) and rotation charts `charts` (one per
    /// segment; the first unused).
    pub fn new(
        robot: &'a Robot,
        inputs: &'a [f64],
        loads: Loads,
        steps: usize,
        starts: &[usize],
        charts: Vec<Quaternion<f64>>,
    ) -> Result<Self> {
        let grid = Grid::new(robot, steps);
        let tip = grid.tip();
        let ok = starts.first() == Some(&0)
            && starts.windows(2).all(|w| w[0] < w[1])
            && starts.last().is_some_and(|&s| s < tip)
            && charts.len() == starts.len();
        if !ok {
            return Err(Error::input(
                "segments",
                format!("increasing start nodes from 0 below the tip node {tip}, one chart each"),
            ));
        }
        let mut bounds = starts.to_vec();
        bounds.push(tip);
        let ends_in = robot
            .actuators
            .iter()
            .map(|a| {
                let node = end_node(&grid, a.s_end.min(robot.body.length));
                // a segment records at the nodes it leaves, the last one at the tip too
                (0..starts.len())
                    .find(|&k| node >= bounds[k] && (node < bounds[k + 1] || k + 1 == starts.len()))
                    .unwrap_or(starts.len() - 1)
            })
            .collect();
        let laws = (robot.actuators.iter().zip(inputs))
            .map(|(a, &input)| LawCoordinate::of_actuator(robot, a, input))
            .collect::<Result<_>>()?;
        Ok(MultipleShooting {
            laws,
            robot,
            inputs,
            loads,
            steps,
            bounds,
            charts,
            ends_in,
            hints: vec![std::cell::Cell::new(0.0); starts.len() * robot.actuators.len()],
            d: Vec::new(),
            e: Vec::new(),
            work: 0.0,
            record: false,
            recorded: None,
            tip: None,
        })
    }

    /// The system with segments at `starts` and the unknowns of the single
    /// shooting unknowns `base` (`nu(0)`, `L omega(0)`, `d / L`), each
    /// segment started where the previous one ends: the charts are those
    /// rotations, so every `theta` is zero and every continuity defect too.
    /// An error where an elongation lies outside its force law.
    pub fn chained(
        robot: &'a Robot,
        inputs: &'a [f64],
        loads: Loads,
        steps: usize,
        starts: &[usize],
        base: &[f64],
    ) -> Result<(Self, Vec<f64>)> {
        let charts = vec![Quaternion::identity(); starts.len()];
        let mut ms = MultipleShooting::new(robot, inputs, loads, steps, starts, charts)?;
        let mut x = vec![0.0; ms.dim()];
        let sigma = ms.set_base(&mut x, base)?;
        let st = ms.block_state(&x, 0)?;
        let (mut y, tau) = (st.y, st.tau);
        for k in 1..ms.segments() {
            let spec = ms.spec(&tau);
            let end = spec.integrate_stretch(ms.stretch(k - 1), &y)?.tip;
            y = crate::rod::FlatNodes::from_states(&[(0.0, end.clone())]).y;
            ms.set_block(&mut x, k, &end, &sigma);
        }
        Ok((ms, x))
    }

    /// Block 0 of the unknowns `x` at the single-shooting unknowns `base`
    /// (`nu(0)`, `L omega(0)`, `d / L`); returns its law coordinates. An
    /// error where an elongation lies outside its force law.
    pub(crate) fn set_base(&self, x: &mut [f64], base: &[f64]) -> Result<Vec<f64>> {
        let (na, len) = (self.na(), self.robot.body.length);
        x[..6].copy_from_slice(&base[..6]);
        for (i, law) in self.laws.iter().enumerate() {
            x[6 + i] = law.of(base[6 + i] * len).map_err(|e| outside_law(e, i))?;
        }
        Ok(x[6..6 + na].to_vec())
    }

    /// The elongations \[m\] where the next inversions of the law
    /// coordinates start, per block and actuator.
    pub(crate) fn hints(&self) -> Vec<f64> {
        self.hints.iter().map(|h| h.get()).collect()
    }

    /// Start the next inversions of the law coordinates at `hints` (as
    /// [`MultipleShooting::hints`] of a system of the same shape).
    pub(crate) fn set_hints(&mut self, hints: &[f64]) {
        for (h, &v) in self.hints.iter().zip(hints) {
            h.set(v);
        }
    }

    /// The single-shooting unknowns (`nu(0)`, `L omega(0)`, `d / L`) of
    /// block 0 of `x`.
    pub fn base(&self, x: &[f64]) -> Result<Vec<f64>> {
        let st = self.block_state(x, 0)?;
        Ok(x[..6].iter().chain(&st.d).copied().collect())
    }

    /// Block `k >= 1` of the unknowns `x` at the rod state `state`, with
    /// the actuators' law coordinates `sigma`: its chart becomes the
    /// state's rotation, so its `theta` is zero.
    pub(crate) fn set_block(
        &mut self,
        x: &mut [f64],
        k: usize,
        state: &crate::rod::RodState,
        sigma: &[f64],
    ) {
        let (na, len, o) = (self.na(), self.robot.body.length, self.offset(k));
        self.charts[k] = state.q;
        for j in 0..3 {
            x[o + j] = state.p[j] / len;
            x[o + 3 + j] = 0.0;
            x[o + 6 + j] = state.v[j];
            x[o + 9 + j] = state.u[j] * len;
        }
        for i in 0..na {
            x[o + 12 + i] = state.delta[i] / len;
            x[o + 12 + na + i] = sigma[i];
        }
    }

    /// The robot.
    pub fn robot(&self) -> &'a Robot {
        self.robot
    }
    /// The rotation charts of the blocks.
    pub fn charts(&self) -> &[Quaternion<f64>] {
        &self.charts
    }
    /// The actuator inputs.
    pub fn inputs(&self) -> &'a [f64] {
        self.inputs
    }
    /// The tip loads.
    pub fn loads(&self) -> Loads {
        self.loads
    }
    /// RK4 steps over the body.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The tip node.
    fn tip(&self) -> usize {
        *self.bounds.last().expect("a system has a tip")
    }

    /// Number of segments.
    pub fn segments(&self) -> usize {
        self.bounds.len() - 1
    }

    fn na(&self) -> usize {
        self.robot.actuators.len()
    }

    /// Column sizes of the blocks.
    pub fn cols(&self) -> Vec<usize> {
        let na = self.na();
        (0..self.segments())
            .map(|k| if k == 0 { 6 + na } else { interior_len(na) })
            .collect()
    }

    /// Row sizes of the blocks.
    pub fn rows(&self) -> Vec<usize> {
        let (na, m) = (self.na(), self.segments());
        (0..m)
            .map(|k| {
                let own = self.ends_in.iter().filter(|&&s| s == k).count();
                own + if k + 1 == m { 6 } else { interior_len(na) }
            })
            .collect()
    }

    /// Offset of block `k` in the unknowns (block 0 has `6 + na`, every
    /// later one [`interior_len`]).
    fn offset(&self, k: usize) -> usize {
        unknowns(self.na(), k)
    }

    /// Number of unknowns.
    pub fn dim(&self) -> usize {
        self.offset(self.segments())
    }

    /// The IVP states of all blocks from the unknowns `x`.
    fn block_states(&self, x: &[f64]) -> Result<Vec<BlockState>> {
        (0..self.segments())
            .map(|k| self.block_state(x, k))
            .collect()
    }

    /// The IVP state of block `k` from the unknowns `x`, and its tensions.
    fn block_state(&self, x: &[f64], k: usize) -> Result<BlockState> {
        let (na, len) = (self.na(), self.robot.body.length);
        let o = self.offset(k);
        let mut y = vec![0.0; BASE_STATES + na];
        let sigma: &[f64];
        if k == 0 {
            y[3] = 1.0;
            y[7..10].copy_from_slice(&x[o..o + 3]);
            for j in 0..3 {
                y[10 + j] = x[o + 3 + j] / len;
            }
            sigma = &x[o + 6..o + 6 + na];
        } else {
            let b = &x[o..o + interior_len(na)];
            for j in 0..3 {
                y[j] = b[j] * len;
                y[7 + j] = b[6 + j];
                y[10 + j] = b[9 + j] / len;
            }
            let q = self.charts[k] * exp_half(&Vector3::new(b[3], b[4], b[5]));
            y[3..7].copy_from_slice(&[q.w, q.i, q.j, q.k]);
            for i in 0..na {
                y[BASE_STATES + i] = b[12 + i] * len;
            }
            sigma = &b[12 + na..12 + 2 * na];
        }
        let mut st = BlockState {
            y,
            tau: Vec::with_capacity(na),
            slope: Vec::with_capacity(na),
            d: Vec::with_capacity(na),
            dd: Vec::with_capacity(na),
        };
        for (i, law) in self.laws.iter().enumerate() {
            let hint = &self.hints[k * na + i];
            let p = law
                .point(sigma[i], hint.get())
                .map_err(|e| outside_law(e, i))?;
            hint.set(p.d);
            st.tau.push(p.tau);
            st.slope.push(p.dtau);
            st.d.push(p.d / len);
            st.dd.push(p.dd / len);
        }
        Ok(st)
    }

    fn spec<'s>(&'s self, tau: &'s [f64]) -> IvpSpec<'s> {
        self.loads.ivp(self.robot, tau, self.steps)
    }

    /// The stretch of the grid that segment `k` integrates.
    pub fn stretch(&self, k: usize) -> Stretch {
        Stretch {
            first: self.bounds[k],
            last: self.bounds[k + 1],
        }
    }

    /// The residual at `x` into `f`; with recording on (the forward
    /// solve's), its nodes are kept for the solution's assembly.
    pub fn residual(&mut self, x: &[f64], f: &mut [f64]) -> Result<()> {
        self.recorded = None;
        self.tip = None;
        let mut row = 0;
        let states = self.block_states(x)?;
        let mut nodes = crate::rod::FlatNodes::default();
        let mut elongation = vec![0.0; self.na()];
        let mut last = None;
        for (k, cur) in states.iter().enumerate() {
            let spec = self.spec(&cur.tau);
            let ivp = match self.record {
                true => spec.integrate_stretch_recorded(self.stretch(k), &cur.y, &mut nodes)?,
                false => spec.integrate_stretch(self.stretch(k), &cur.y)?,
            };
            let next = states.get(k + 1).map(|s| &s.y[..]);
            row += self.segment_rows(x, (k, cur), &ivp, next, &mut f[row..]);
            for i in (0..self.na()).filter(|&i| self.ends_in[i] == k) {
                elongation[i] = ivp.elongation[i];
            }
            last = Some(ivp);
        }
        self.work += 1.0;
        self.tip = last.as_ref().map(|ivp| (ivp.tip.clone(), None));
        if let (true, Some(mut ivp)) = (self.record, last) {
            ivp.elongation = elongation;
            let tau0 = states.into_iter().next().map(|s| s.tau).unwrap_or_default();
            let x = x.to_vec();
            self.recorded = Some(Recording {
                x,
                nodes,
                ivp,
                tau0,
            });
        }
        Ok(())
    }

    /// The tip state (the last segment's end) at the last residual or
    /// linearisation, and after a linearisation the derivatives of the tip
    /// position \[m\] with respect to the last block's scaled unknowns
    /// (`3 x` its column count, offset [`MultipleShooting::last_offset`]):
    /// the position rows of the last segment's exact tangent (an interior
    /// block's own `p / L` enters as `L I`, its `delta` not at all). `None`
    /// before an evaluation or after a failed one. The blocked-tip inverse
    /// (`inverse::mixed`) borders the system with the tip's gap from it.
    pub(crate) fn tip_state(&self) -> Option<(&crate::rod::RodState, Option<&DMatrix<f64>>)> {
        self.tip.as_ref().map(|(s, g)| (s, g.as_ref()))
    }

    /// Offset of the last block in the unknowns.
    pub(crate) fn last_offset(&self) -> usize {
        self.offset(self.segments() - 1)
    }

    /// Record the nodes of every residual evaluation from now on (`on`).
    pub(crate) fn record(&mut self, on: bool) {
        self.record = on;
    }

    /// The recording of the last residual evaluation if it was at `x`.
    pub(crate) fn recorded(&mut self, x: &[f64]) -> Option<Recording> {
        self.recorded.take().filter(|r| r.x == x)
    }

    /// The rows of segment `k` (block state `cur`), whose IVP ended in
    /// `ivp`, into `f`: the continuity rows with the next block (its IVP
    /// state `next`), or the tip balance for the last segment, then the
    /// elongation rows of the actuators the segment records. Returns their
    /// number.
    fn segment_rows(
        &self,
        x: &[f64],
        (k, cur): (usize, &BlockState),
        ivp: &IvpResult,
        next: Option<&[f64]>,
        f: &mut [f64],
    ) -> usize {
        let sigma = (self.sigma_of(x, k), self.sigma_of(x, k + 1));
        let mut row = match next {
            Some(y) => self.continuity(&ivp.tip, y, sigma, f),
            None => {
                let (fs, ms) = residual_scales(self.robot);
                for j in 0..3 {
                    f[j] = ivp.tip_force_residual[j] * fs;
                    f[3 + j] = ivp.tip_moment_residual[j] * ms;
                }
                6
            }
        };
        for i in (0..self.na()).filter(|&i| self.ends_in[i] == k) {
            f[row] = ivp.elongation[i] / self.robot.body.length - cur.d[i];
            row += 1;
        }
        row
    }

    /// The first `lambda` in `(0, 1)` at which a law coordinate of
    /// `x + lambda dx` passes over its force law's kink
    /// ([`LawCoordinate::crossing`]), in any block: where the law changes
    /// from the piece a Newton step was linearised on to another.
    pub(crate) fn breakpoint(&self, x: &[f64], dx: &[f64]) -> Option<f64> {
        let crossings = (0..self.segments()).flat_map(|k| {
            let (s, ds) = (self.sigma_of(x, k), self.sigma_of(dx, k));
            let laws = self.laws.iter().zip(s.iter().zip(ds));
            laws.filter_map(|(law, (&s, &ds))| law.crossing(s, ds))
        });
        crossings.min_by(f64::total_cmp)
    }

    /// Block `k`'s law coordinates `sigma` (empty past the last block).
    fn sigma_of<'x>(&self, x: &'x [f64], k: usize) -> &'x [f64] {
        let (na, o) = (self.na(), self.offset(k));
        let at = if k == 0 { o + 6 } else { o + 12 + na };
        x.get(at..at + na).unwrap_or(&[])
    }

    /// The continuity rows between the end state `end` of a segment and the
    /// next block's start state `start` (an IVP state), with their law
    /// coordinates, into `f`; returns the number of rows.
    fn continuity(
        &self,
        end: &crate::rod::RodState,
        start: &[f64],
        (d_end, d_start): (&[f64], &[f64]),
        f: &mut [f64],
    ) -> usize {
        let (na, len) = (self.na(), self.robot.body.length);
        let qb = Quaternion::new(start[3], start[4], start[5], start[6]);
        let rot = rotation_defect(&qb, &end.q);
        for j in 0..3 {
            f[j] = (end.p[j] - start[j]) / len;
            f[3 + j] = rot[j];
            f[6 + j] = end.v[j] - start[7 + j];
            f[9 + j] = (end.u[j] - start[10 + j]) * len;
        }
        for i in 0..na {
            f[12 + i] = (end.delta[i] - start[BASE_STATES + i]) / len;
            f[12 + na + i] = d_end[i] - d_start[i];
        }
        interior_len(na)
    }
}

mod jacobian;
mod system;
pub use system::ShootingSystem;

#[cfg(test)]
#[path = "ms_tests.rs"]
mod tests;

/// An actuator elongation outside its force law's domain (a TCA stretched
/// past its straight-fibre limit) at a trial point of the iteration: the
/// residual cannot be evaluated there, as where an IVP cannot be
/// integrated ([`Error::Integration`]), and the solver shortens its step.
/// The inputs were checked before the solve, so only the elongation can
/// be out of range.
fn outside_law(e: Error, i: usize) -> Error {
    match e {
        Error::InvalidParameter {
            name,
            value,
            allowed,
        } => Error::Integration {
            s: 0.0,
            reason: format!("actuator {i}: {name} = {value:.6e} outside {allowed}"),
        },
        e => e,
    }
}

/// The column in block `k` of the tangent direction `c` of its segment
/// (see [`MultipleShooting::seeds`]).
fn direction_column(k: usize, na: usize, c: usize) -> usize {
    match k {
        0 => c,
        _ if c < 9 => 3 + c,
        _ => 12 + na + (c - 9),
    }
}

/// The node at arc length `s` \[m\] of `grid` (a breakpoint).
fn end_node(grid: &Grid, s: f64) -> usize {
    let tol = 1e-12 * grid.intervals.last().map_or(1.0, |iv| iv.b);
    grid.intervals
        .iter()
        .find(|iv| (iv.b - s).abs() <= tol)
        .map_or(0, |iv| iv.first_node + iv.m)
}

/// `exp(theta / 2)`, the unit quaternion of the rotation vector `theta`.
pub(crate) fn exp_half(theta: &Vector3<f64>) -> Quaternion<f64> {
    let t = theta.norm();
    let (c, sinc) = if t < 1e-4 {
        // cos and sin(t/2)/t to their t^4 terms: exact in f64 below 1e-4
        (1.0 - t * t / 8.0, 0.5 - t * t / 48.0)
    } else {
        ((0.5 * t).cos(), (0.5 * t).sin() / t)
    };
    Quaternion::new(c, sinc * theta[0], sinc * theta[1], sinc * theta[2])
}

/// The derivatives of [`exp_half`] along the three components of `theta`.
fn dexp_half(theta: &Vector3<f64>) -> [Quaternion<f64>; 3] {
    let t = theta.norm();
    // exp_half = (cos(t/2), f theta), f = sin(t/2) / t: d cos = -f theta / 2,
    // d(f theta) = f I + theta (g theta)^T with g = (cos(t/2) / 2 - f) / t^2
    let (c, f, g) = if t < 1e-4 {
        (
            1.0 - t * t / 8.0,
            0.5 - t * t / 48.0,
            -1.0 / 24.0 + t * t / 960.0,
        )
    } else {
        let (c, f) = ((0.5 * t).cos(), (0.5 * t).sin() / t);
        (c, f, (0.5 * c - f) / (t * t))
    };
    let _ = c;
    std::array::from_fn(|j| {
        let v = theta * (g * theta[j]) + Vector3::ith(j, f);
        Quaternion::new(-0.5 * f * theta[j], v[0], v[1], v[2])
    })
}

/// The rotation from `qb` to `qa` as `2 vec(qb^-1 qa)` (its rotation vector
/// to first order), on the hemisphere `w >= 0` of `qb^-1 qa`.
pub(crate) fn rotation_defect(qb: &Quaternion<f64>, qa: &Quaternion<f64>) -> Vector3<f64> {
    let e = qb.conjugate() * qa;
    let s = if e.w < 0.0 { -2.0 } else { 2.0 };
    Vector3::new(e.i, e.j, e.k) * s
}

impl MultipleShooting<'_> {
    /// The rounding floor of the residual's max-norm: `4 eps` times the
    /// largest term of any row, each continuity row's at most the scaled
    /// state's size grown by [`super::segments::GROWTH_BOUND`] across its
    /// segment, the tip rows' the largest term of the balance (32)-(33) as
    /// single shooting's (`K (strain - strain*)`, the tip loads and the
    /// tensions, scaled).
    pub(crate) fn rounding_floor(&self, x: &[f64]) -> f64 {
        let robot = self.robot;
        let (kse, kbt) = robot.body.stiffness();
        let (fs, ms) = residual_scales(robot);
        let len = robot.body.length;
        let xmax = x.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        let last = self.offset(self.segments() - 1);
        let (v, u) = if self.segments() == 1 {
            (&x[0..3], &x[3..6])
        } else {
            (&x[last + 6..last + 9], &x[last + 9..last + 12])
        };
        let vmax = v.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        let umax = u.iter().fold(0.0f64, |m, a| m.max(a.abs())) / len;
        let tau: f64 = self
            .block_state(x, self.segments() - 1)
            .map_or(0.0, |st| st.tau.iter().map(|t| t.abs()).sum());
        let f = fs * (kse.max() * vmax + self.loads.tip_force.amax() + tau);
        let m = ms * (kbt.max() * umax * len + self.loads.tip_moment.amax() + tau * len);
        let grown = if self.segments() > 1 {
            super::segments::GROWTH_BOUND * xmax
        } else {
            0.0
        };
        4.0 * f64::EPSILON * f.max(m).max(grown)
    }
}
