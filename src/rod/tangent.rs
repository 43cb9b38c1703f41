//! Tangents (forward sensitivities) of the IVP: the variational equations
//! integrated with the state on the same RK4 grid.
//!
//! The right-hand side (eqs 22-31), the RK4 stages and the quaternion
//! renormalisation are differentiated by hand (`tangent_lanes.rs`,
//! `ode_tangent.rs`: the state in `f64` by the IVP's own code, its tangents
//! in lanes beside it), the anchor jumps and the tip balance (32)-(33) in
//! [`Dual`] arithmetic, so the tangents are the exact derivatives of the
//! *discrete* map (to rounding): `d y(s_k) / d seed` at every grid node.
//! Directions are seeded on the initial strains `nu(0)`, `omega(0)` and on
//! the actuator tensions; the force laws' derivatives are applied by the
//! caller (the shooting residual, J and C). All directions share one
//! evaluation of the real part (the eq-25 block factorisation included),
//! which is bit-for-bit the plain IVP's.
//!
//! The reference pass ([`with_dual_rhs`]) runs everything in [`Dual`]
//! arithmetic on the generic right-hand side, the plain twin of the
//! hand-tuned `f64` fast path in `ode.rs`; `f64` instances of both agree to
//! rounding (tested).

use std::cell::Cell;

use nalgebra::{DMatrix, Vector3};

use super::dual::{c_cross, cross_c, dot, rot_t, rt_mul, Dual, Real, V3};
use super::grid::{Interval, Stretch};
use super::ivp::{anchored_at, spanning, Start};
use super::ode::RodRhs;
pub use super::tangent_nodes::{TangentNode, TangentNodes, TangentSeeds};
use super::{IvpResult, IvpSpec, RodState, BASE_STATES};
use crate::error::{Error, Result};

/// A tangent IVP: the IVP (its real part) and its derivatives along the seeds.
///
/// Each derivative field is `d / d seed` of the [`IvpResult`] field of the
/// same name (its meaning and unit there, per unit of seed), one column per
/// seed direction (`k` columns; the tip state as a vector).
#[derive(Debug, Clone)]
pub struct TangentIvp {
    /// The IVP itself (nodes recorded if asked for by [`integrate_tangent`]).
    pub ivp: IvpResult,
    /// `n_states x k`.
    pub tip: DMatrix<f64>,
    /// `n_actuators x k`.
    pub elongation: DMatrix<f64>,
    /// `3 x k`.
    pub tip_force_residual: DMatrix<f64>,
    /// `3 x k`.
    pub tip_moment_residual: DMatrix<f64>,
    /// Every grid node with its tangents, if recorded (anchor nodes after their jump).
    pub nodes: TangentNodes,
}

/// Largest number of directions integrated in one pass (more are split into passes).
const MAX_PASS: usize = 16;

thread_local! {
    /// Tangent passes on this thread run the reference right-hand side ([`with_dual_rhs`]).
    static DUAL_RHS: Cell<bool> = const { Cell::new(false) };
}

/// Run `f` with this thread's tangent passes on the reference right-hand
/// side: [`RodRhs::deriv_generic`] in [`Dual`] arithmetic throughout,
/// instead of the linearisation of [`RodRhs::deriv_lanes`]. The same
/// derivatives to rounding, at several times the cost: for the tests that
/// compare the two and for benchmarks, not for use.
#[doc(hidden)]
pub fn with_dual_rhs<R>(f: impl FnOnce() -> R) -> R {
    let old = DUAL_RHS.with(|d| d.replace(true));
    let out = f();
    DUAL_RHS.with(|d| d.set(old));
    out
}

/// What a tangent pass records at the grid nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Record {
    /// Nothing (the tip only); `false`.
    Tip,
    /// States and tangents ([`TangentIvp::nodes`]), what a stability
    /// verdict reads; the IVP's own node list stays empty.
    Tangents,
    /// Tangents and the IVP's nodes ([`IvpResult::nodes`]) too; `true`.
    All,
}

impl From<bool> for Record {
    fn from(all: bool) -> Self {
        if all {
            Record::All
        } else {
            Record::Tip
        }
    }
}

/// Integrate the IVP (eqs 22-31, as [`crate::rod::integrate`]) together with
/// its tangents along `seeds`, on the same RK4 grid, through the anchor
/// jumps and the tip balance. The tangents are the exact derivatives of the
/// discrete map. `record` (a [`Record`], or `true` for [`Record::All`]) says
/// which grid nodes are returned.
pub fn integrate_tangent(
    spec: &IvpSpec<'_>,
    v0: &Vector3<f64>,
    u0: &Vector3<f64>,
    seeds: &TangentSeeds,
    record: impl Into<Record>,
) -> Result<TangentIvp> {
    passes(spec, Start::Base(v0, u0), seeds, record.into())
}

impl IvpSpec<'_> {
    /// [`integrate_tangent`] over `stretch` of the grid from the state
    /// `y0` at its first node, as [`IvpSpec::integrate_stretch`]: the
    /// tangents along `seeds`, whose `state0` (`n_states x k`) seeds the
    /// whole start state (`nu0` and `omega0` unused). The tip tangent is
    /// that of the state at the stretch's last node; the tip balance's
    /// tangents are zero unless the stretch ends at the tip. `record`:
    /// nodes from the stretch's first interval start (for whole IVPs).
    pub fn integrate_stretch_tangent(
        &self,
        stretch: Stretch,
        y0: &[f64],
        seeds: &TangentSeeds,
    ) -> Result<TangentIvp> {
        let n = self.robot.n_states();
        let k = seeds.directions();
        match &seeds.state0 {
            Some(m) if m.nrows() == n && m.ncols() == k && y0.len() == n => {}
            _ => {
                return Err(Error::input(
                    "seeds",
                    format!("a start state of {n} values and state0 seeds of {n} rows"),
                ))
            }
        }
        passes(self, Start::Node(stretch, y0), seeds, Record::Tip)
    }
}

/// The tangent passes of [`integrate_tangent`] from `start`, at most
/// [`MAX_PASS`] directions each, their columns joined.
fn passes(
    spec: &IvpSpec<'_>,
    start: Start<'_>,
    seeds: &TangentSeeds,
    record: Record,
) -> Result<TangentIvp> {
    let k = checked_directions(seeds, spec.robot.actuators.len())?;
    let n = spec.robot.n_states();
    let capacity = if record == Record::Tip {
        0
    } else {
        spec.steps.max(1) + spec.robot.breakpoints().len()
    };
    let mut nodes = TangentNodes::new(n, k, capacity);
    let mut out: Option<TangentIvp> = None;
    let mut c0 = 0;
    loop {
        let w = (k - c0).min(MAX_PASS);
        let p = Pass {
            spec,
            start,
            seeds,
            c0,
            w,
        };
        let part = match w {
            0..=4 => dispatch::<4>(&p, record, &mut nodes, None)?,
            5..=8 => dispatch::<8>(&p, record, &mut nodes, None)?,
            9..=12 => dispatch::<12>(&p, record, &mut nodes, None)?,
            _ => dispatch::<MAX_PASS>(&p, record, &mut nodes, None)?,
        };
        out = Some(match out {
            None => part,
            Some(mut o) => {
                let cat = |a: &DMatrix<f64>, b: &DMatrix<f64>| {
                    let mut m = a.clone().resize_horizontally(a.ncols() + b.ncols(), 0.0);
                    m.columns_mut(a.ncols(), b.ncols()).copy_from(b);
                    m
                };
                o.tip = cat(&o.tip, &part.tip);
                o.elongation = cat(&o.elongation, &part.elongation);
                o.tip_force_residual = cat(&o.tip_force_residual, &part.tip_force_residual);
                o.tip_moment_residual = cat(&o.tip_moment_residual, &part.tip_moment_residual);
                o
            }
        });
        c0 += w;
        if c0 >= k {
            break;
        }
    }
    let mut out = out.expect("at least one pass");
    out.nodes = nodes;
    Ok(out)
}

/// The arguments of one pass: directions `c0 .. c0 + w` of `seeds`.
struct Pass<'s, 'a> {
    spec: &'s IvpSpec<'a>,
    start: Start<'s>,
    seeds: &'s TangentSeeds,
    c0: usize,
    w: usize,
}

/// The number of directions of `seeds`, checked against their shapes (three
/// rows each for the base strains, one per actuator for the tensions).
fn checked_directions(seeds: &TangentSeeds, na: usize) -> Result<usize> {
    let k = seeds.directions();
    if seeds.nu0.nrows() != 3
        || seeds.omega0.nrows() != 3
        || seeds.tensions.nrows() != na
        || seeds.omega0.ncols() != k
        || seeds.tensions.ncols() != k
    {
        return Err(Error::input(
            "seeds",
            format!("expected 3, 3 and {na} rows and equal column counts"),
        ));
    }
    Ok(k)
}

/// [`pass`] compiled for the widest vector unit the CPU has: the
/// directions of a [`Dual`] are independent lanes, so AVX-512 carries eight
/// of them per instruction (SSE2, the x86-64 baseline, two). The lanes'
/// products are fused with their sums (`f64::mul_add`, one FMA instruction
/// each where the CPU has FMA, a correctly rounded library call elsewhere),
/// so every copy gives bit-for-bit the same tangents; the values are the
/// plain IVP's (no fused operation), bit for bit.
fn dispatch<const N: usize>(
    p: &Pass<'_, '_>,
    record: Record,
    nodes: &mut TangentNodes,
    hook: Option<&mut ColumnHook<'_>>,
) -> Result<TangentIvp> {
    #[cfg(target_arch = "x86_64")]
    {
        let fma = std::is_x86_feature_detected!("fma");
        if fma && std::is_x86_feature_detected!("avx512f") {
            // SAFETY: the CPU supports AVX-512F and FMA (checked just above).
            return unsafe { pass_avx512::<N>(p, record, nodes, hook) };
        }
        if fma && std::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2 and FMA (checked just above).
            return unsafe { pass_avx2::<N>(p, record, nodes, hook) };
        }
    }
    pass::<N>(p, record, nodes, hook)
}

/// [`pass`] compiled with a target feature enabled.
macro_rules! pass_with {
    ($name:ident, $feature:literal) => {
        #[doc = concat!("[`pass`] with ", $feature, " enabled.")]
        ///
        /// # Safety
        /// The CPU must support the feature.
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = $feature)]
        unsafe fn $name<const N: usize>(
            p: &Pass<'_, '_>,
            record: Record,
            nodes: &mut TangentNodes,
            hook: Option<&mut ColumnHook<'_>>,
        ) -> Result<TangentIvp> {
            pass::<N>(p, record, nodes, hook)
        }
    };
}
pass_with!(pass_avx512, "avx512f,fma");
pass_with!(pass_avx2, "avx2,fma");

/// The RK4 stages of the reference pass in dual arithmetic (`n` states each).
struct Stages<const N: usize> {
    k: [Vec<Dual<N>>; 4],
    yt: Vec<Dual<N>>,
}

impl<const N: usize> Stages<N> {
    fn new(n: usize) -> Self {
        let zero = vec![Dual::<N>::cst(0.0); n];
        Stages {
            k: std::array::from_fn(|_| zero.clone()),
            yt: zero,
        }
    }

    /// One RK4 step of length `h` from `s`, then the quaternion
    /// renormalised, as in [`super::integrate`]; the right-hand side in
    /// dual arithmetic throughout ([`RodRhs::deriv_generic`], the
    /// reference). The stages are a loop so that the right-hand side is
    /// inlined once per compiled pass.
    #[inline(always)]
    fn step(
        &mut self,
        fz: &RodRhs<'_>,
        s: f64,
        h: f64,
        y: &mut [Dual<N>],
        tau: &[Dual<N>],
        active: &[usize],
    ) -> Result<()> {
        let (h2, h6) = (0.5 * h, h / 6.0);
        let n = y.len();
        let Stages { k, yt } = self;
        for st in 0..4 {
            let (hs, ss) = [(0.0, s), (h2, s + h2), (h2, s + h2), (h, s + h)][st];
            let (done, todo) = k.split_at_mut(st);
            if st == 0 {
                yt.copy_from_slice(y);
            } else {
                let kp = &done[st - 1];
                for j in 0..n {
                    yt[j] = y[j] + kp[j] * hs;
                }
            }
            fz.deriv_generic(ss, yt, tau, active, &mut todo[0])?;
        }
        let [k1, k2, k3, k4] = &*k;
        for j in 0..n {
            y[j] += (k1[j] + (k2[j] + k3[j]) * 2.0 + k4[j]) * h6;
        }
        let qn = (y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]).sqrt();
        for yq in &mut y[3..7] {
            *yq = *yq / qn;
        }
        Ok(())
    }
}

/// The tip balance (32)-(33) in the body frame, in dual arithmetic, closed
/// by the actuators anchored at the tip (their elongations recorded).
#[inline(always)]
fn tip_balance<const N: usize>(
    spec: &IvpSpec<'_>,
    fz: &RodRhs<'_>,
    y: &[Dual<N>],
    tau: &[Dual<N>],
    elongation: &mut [Dual<N>],
    tol: f64,
) -> (V3<Dual<N>>, V3<Dual<N>>) {
    let body = &spec.robot.body;
    let len = body.length;
    let rm = rot_t(&[y[3], y[4], y[5], y[6]]);
    let v = [y[7], y[8], y[9]];
    let u = [y[10], y[11], y[12]];
    let rtf = rt_mul(&rm, &spec.tip_force.into());
    let rtm = rt_mul(&rm, &spec.tip_moment.into());
    let mut rf: V3<Dual<N>> =
        std::array::from_fn(|k| (v[k] - body.nu_star[k]) * fz.kse[k] - rtf[k]);
    let mut rmm: V3<Dual<N>> =
        std::array::from_fn(|k| (u[k] - body.omega_star[k]) * fz.kbt[k] - rtm[k]);
    for (i, act) in spec.robot.actuators.iter().enumerate() {
        if (act.s_end - len).abs() <= tol {
            elongation[i] = y[BASE_STATES + i];
            let (r, rp, _) = act.routing.eval(len);
            let (r, rp): (V3<f64>, V3<f64>) = (r.into(), rp.into());
            let ucr = cross_c(&u, &r);
            let pb: V3<Dual<N>> = std::array::from_fn(|k| v[k] + ucr[k] + rp[k]);
            let nrm = dot(&pb, &pb).sqrt();
            let p: V3<Dual<N>> = std::array::from_fn(|k| pb[k] / nrm * tau[i]);
            let rxp = c_cross(&r, &p);
            for k in 0..3 {
                rf[k] += p[k];
                rmm[k] += rxp[k];
            }
        }
    }
    (rf, rmm)
}

/// One pass of [`integrate_tangent`] over directions `c0 .. c0 + w` (`w <= N`),
/// recording into `nodes` as asked: on the hand-linearised right-hand side
/// ([`lanes_pass::pass_lanes`]), or the reference in dual arithmetic
/// throughout ([`with_dual_rhs`]). A `hook` ([`IvpSpec::integrate_tangent_hooked`])
/// runs on the hand-linearised side only.
#[inline(always)]
fn pass<const N: usize>(
    p: &Pass<'_, '_>,
    record: Record,
    nodes: &mut TangentNodes,
    hook: Option<&mut ColumnHook<'_>>,
) -> Result<TangentIvp> {
    if hook.is_none() && DUAL_RHS.with(Cell::get) {
        pass_dual::<N>(p, record, nodes)
    } else {
        lanes_pass::pass_lanes::<N>(p, record, nodes, hook)
    }
}

/// [`pass`] in dual arithmetic throughout (the reference).
#[inline(always)]
fn pass_dual<const N: usize>(
    p: &Pass<'_, '_>,
    record: Record,
    nodes: &mut TangentNodes,
) -> Result<TangentIvp> {
    let (spec, c0, w) = (p.spec, p.c0, p.w);
    let robot = spec.robot;
    let fz = RodRhs::new(robot, spec.tensions);
    let na = robot.actuators.len();
    let n = robot.n_states();
    let len = robot.body.length;
    let steps = spec.steps.max(1);
    let (tau, mut y) = seeded_start::<N>(p, n);
    let zero = Dual::<N>::cst(0.0);
    let mut st = Stages::<N>::new(n);
    let rec = record != Record::Tip;
    let mut idx = 0;
    // record node `idx` at `s` if asked
    macro_rules! node {
        ($s:expr) => {
            if rec {
                nodes.record(idx, $s, &y, c0, w);
                idx += 1;
            }
        };
    }
    let bps = robot.breakpoints();
    let tol = 1e-12 * len;
    let mut elongation = vec![zero; na];
    let mut active: Vec<usize> = Vec::with_capacity(na);
    let stretch = p.start.stretch();
    let mut first_node = 0;
    for win in bps.windows(2) {
        let (a, b) = (win[0], win[1]);
        let iv = Interval::new(a, b, len, steps, &mut first_node);
        let range = stretch.steps_in(&iv);
        if range.is_empty() {
            continue;
        }
        if stretch.jumps_at_start(&iv)
            && anchored_at(robot, a, tol, |i| elongation[i] = y[BASE_STATES + i])
        {
            fz.anchor_tangent(a, &mut y, &tau)?;
        }
        node!(a);
        spanning(robot, a, b, tol, &mut active);
        let h = iv.h();
        for kk in range {
            let s = a + kk as f64 * h;
            st.step(&fz, s, h, &mut y, &tau, &active)?;
            if kk + 1 < iv.m {
                node!(s + h);
            }
        }
    }
    let at_tip = stretch.last >= first_node;
    close(
        p,
        &fz,
        &y,
        &tau,
        &mut elongation,
        (record, nodes, idx, at_tip),
    )
}

/// The end of a pass at the tip state `y`: the tip balance, the check that
/// every tangent is finite, the last node recorded as asked (`idx` is its
/// index) and the result.
#[inline(always)]
fn close<const N: usize>(
    p: &Pass<'_, '_>,
    fz: &RodRhs<'_>,
    y: &[Dual<N>],
    tau: &[Dual<N>],
    elongation: &mut [Dual<N>],
    (record, nodes, idx, at_tip): (Record, &mut TangentNodes, usize, bool),
) -> Result<TangentIvp> {
    let len = p.spec.robot.body.length;
    let tol = 1e-12 * len;
    let (rf, rmm) = if at_tip {
        tip_balance(p.spec, fz, y, tau, elongation, tol)
    } else {
        let zero = [Dual::<N>::cst(0.0); 3];
        (zero, zero)
    };
    // the stages check only the real parts: the derivatives once, here
    let all_finite = |v: &[Dual<N>]| v.iter().all(|d| d.eps.iter().all(|e| e.is_finite()));
    if !(all_finite(y) && all_finite(elongation) && all_finite(&rf) && all_finite(&rmm)) {
        return Err(Error::Integration {
            s: len,
            reason: "non-finite tangent".into(),
        });
    }
    if record != Record::Tip && at_tip {
        nodes.record(idx, len, y, p.c0, p.w);
    }
    let ivp_nodes = if record == Record::All && p.c0 == 0 {
        nodes
            .iter()
            .map(|nd| (nd.s, RodState::from_slice(nd.state)))
            .collect()
    } else {
        Vec::new()
    };
    Ok(finish(y, elongation, &rf, &rmm, ivp_nodes, p.w))
}

/// The dual tensions and initial state of a pass: directions `c0 .. c0 + w`
/// of the seeds on the tensions and on `nu(0)`, `omega(0)` (the base at the
/// origin with the identity rotation), or on the whole start state of a
/// stretch.
fn seeded_start<const N: usize>(p: &Pass<'_, '_>, n: usize) -> (Vec<Dual<N>>, Vec<Dual<N>>) {
    let (seeds, c0, w) = (p.seeds, p.c0, p.w);
    let seed = |m: &DMatrix<f64>, row: usize| -> [f64; N] {
        std::array::from_fn(|d| if d < w { m[(row, c0 + d)] } else { 0.0 })
    };
    let na = p.spec.robot.actuators.len();
    let tau = (0..na)
        .map(|i| Dual::new(p.spec.tensions[i], seed(&seeds.tensions, i)))
        .collect();
    let mut re = vec![0.0; n];
    p.start.write(&mut re);
    let mut y: Vec<Dual<N>> = re.iter().map(|&v| Dual::cst(v)).collect();
    match (p.start, &seeds.state0) {
        (Start::Node(..), Some(m)) => {
            for (j, yj) in y.iter_mut().enumerate() {
                *yj = Dual::new(re[j], seed(m, j));
            }
        }
        _ => {
            for k in 0..3 {
                y[7 + k] = Dual::new(re[7 + k], seed(&seeds.nu0, k));
                y[10 + k] = Dual::new(re[10 + k], seed(&seeds.omega0, k));
            }
        }
    }
    (tau, y)
}

/// The tangent IVP's result from the final dual state: the real parts as
/// the IVP (with its recorded nodes `ivp_nodes`), the derivative parts (`w`
/// directions) as tangents; the tangent nodes are filled in by the caller.
fn finish<const N: usize>(
    y: &[Dual<N>],
    elongation: &[Dual<N>],
    rf: &V3<Dual<N>>,
    rmm: &V3<Dual<N>>,
    ivp_nodes: Vec<(f64, RodState)>,
    w: usize,
) -> TangentIvp {
    let yr: Vec<f64> = y.iter().map(|d| d.re).collect();
    let tip = RodState::from_slice(&yr);
    let tan = |v: &[Dual<N>]| DMatrix::from_fn(v.len(), w, |r, c| v[r].eps[c]);
    TangentIvp {
        ivp: IvpResult {
            tip,
            elongation: elongation.iter().map(|d| d.re).collect(),
            tip_force_residual: Vector3::new(rf[0].re, rf[1].re, rf[2].re),
            tip_moment_residual: Vector3::new(rmm[0].re, rmm[1].re, rmm[2].re),
            nodes: ivp_nodes,
        },
        tip: tan(y),
        elongation: tan(elongation),
        tip_force_residual: tan(rf),
        tip_moment_residual: tan(rmm),
        nodes: TangentNodes::default(),
    }
}

/// The hook of [`IvpSpec::integrate_tangent_hooked`]: `(node index,
/// state, tangent columns, matrix to write) -> whether to apply it`. The
/// state (`n_states`) may be overwritten: the pass continues from it.
pub(crate) type ColumnHook<'h> = dyn FnMut(usize, &mut [f64], &[f64], &mut [f64]) -> bool + 'h;

impl IvpSpec<'_> {
    /// [`integrate_tangent`] with every node recorded ([`Record::Tangents`])
    /// and `hook` called at every node, the tip included (before its
    /// balance): `hook(idx, y, cols, m)` gets the node's index, its state
    /// `y` and its tangent columns `cols` (`n_states x k`, by columns); if
    /// it returns true the integration continues from the columns times `m`
    /// (`k x k`, by columns, written by the hook), the tension and
    /// elongation tangents transformed alike, and the node is recorded so.
    /// The variational equations are linear, so every later tangent is the
    /// plain pass's times the product of the matrices applied (to
    /// rounding). A hook that leaves `y` alone keeps the real part the plain
    /// IVP's bit for bit; one that writes a given trajectory's state into
    /// `y` at every node linearises the pass about that trajectory (each
    /// step's tangent map is then taken at the trajectory's own state, as
    /// multiple shooting takes each segment's). One pass of `k <= 16`
    /// directions on the hand-linearised right-hand side; with more
    /// directions (several passes, whose columns never meet) the plain
    /// [`integrate_tangent`], the hook not called.
    pub(crate) fn integrate_tangent_hooked(
        &self,
        v0: &Vector3<f64>,
        u0: &Vector3<f64>,
        seeds: &TangentSeeds,
        hook: &mut ColumnHook<'_>,
    ) -> Result<TangentIvp> {
        let k = checked_directions(seeds, self.robot.actuators.len())?;
        if k > MAX_PASS {
            return integrate_tangent(self, v0, u0, seeds, Record::Tangents);
        }
        let n = self.robot.n_states();
        let capacity = self.steps.max(1) + self.robot.breakpoints().len();
        let mut nodes = TangentNodes::new(n, k, capacity);
        let p = Pass {
            spec: self,
            start: Start::Base(v0, u0),
            seeds,
            c0: 0,
            w: k,
        };
        let (rec, hook) = (Record::Tangents, Some(hook));
        let mut out = match k {
            0..=4 => dispatch::<4>(&p, rec, &mut nodes, hook)?,
            5..=8 => dispatch::<8>(&p, rec, &mut nodes, hook)?,
            9..=12 => dispatch::<12>(&p, rec, &mut nodes, hook)?,
            _ => dispatch::<MAX_PASS>(&p, rec, &mut nodes, hook)?,
        };
        out.nodes = nodes;
        Ok(out)
    }
}

#[path = "tangent_lanes.rs"]
mod lanes_pass;

#[cfg(test)]
#[path = "tangent_tests.rs"]
mod tests;
