//! The tangent pass on the hand-linearised right-hand side: the state in
//! `f64`, stepped by the IVP's own arithmetic (so bit-for-bit the plain
//! IVP), and its tangents in [`Lanes`] beside it, stepped by the same RK4
//! combination. The anchor jumps, the recorded nodes and the tip balance
//! are rare: they run on the dual form of the state ([`Dual`]).

use super::super::lanes::{lin, Lanes};
use super::super::ode::StringAt;
use super::*;

/// The RK4 stages of a tangent pass: values and lanes (`n` states each),
/// the four stages and the trial state in one buffer each (two allocations
/// per pass, not ten).
struct LaneStages<const N: usize> {
    /// `k1 .. k4` then the trial state `yt`.
    k: Vec<f64>,
    /// Their lanes.
    kl: Vec<Lanes<N>>,
    /// The strings of one evaluation (scratch of [`RodRhs::deriv_lanes`]).
    strings: Vec<StringAt<f64>>,
}

impl<const N: usize> LaneStages<N> {
    fn new(n: usize, na: usize) -> Self {
        LaneStages {
            k: vec![0.0; 5 * n],
            kl: vec![Lanes::ZERO; 5 * n],
            strings: Vec::with_capacity(na),
        }
    }

    /// Zero the stages' rates of the actuators (and their lanes), which
    /// [`RodRhs::deriv_lanes`] writes for the active ones only: once per
    /// grid interval, where the active set may change.
    fn clear_rates(&mut self, n: usize) {
        for k in self.k.chunks_exact_mut(n) {
            k[BASE_STATES..].fill(0.0);
        }
        for k in self.kl.chunks_exact_mut(n) {
            k[BASE_STATES..].fill(Lanes::ZERO);
        }
    }

    /// One RK4 step of length `h` from `s`, then the quaternion
    /// renormalised: the values by the operations of
    /// [`super::super::integrate`] in its order, the lanes by the same
    /// combination and the derivative of the renormalisation. The stages
    /// are a loop so that the right-hand side is inlined once per pass.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn step(
        &mut self,
        fz: &RodRhs<'_>,
        s: f64,
        h: f64,
        (y, yl): (&mut [f64], &mut [Lanes<N>]),
        taul: &[Lanes<N>],
        active: &[usize],
    ) -> Result<()> {
        let (h2, h6) = (0.5 * h, h / 6.0);
        let n = y.len();
        let LaneStages { k, kl, strings } = self;
        let (k, yt) = k.split_at_mut(4 * n);
        let (kl, ytl) = kl.split_at_mut(4 * n);
        for st in 0..4 {
            let (hs, ss) = [(0.0, s), (h2, s + h2), (h2, s + h2), (h, s + h)][st];
            let (done, todo) = k.split_at_mut(st * n);
            let (donel, todol) = kl.split_at_mut(st * n);
            // the first stage reads the state itself (no copy into `yt`)
            let at: (&[f64], &[Lanes<N>]) = if st == 0 {
                (y, yl)
            } else {
                let (kp, kpl) = (&done[(st - 1) * n..], &donel[(st - 1) * n..]);
                for j in 0..n {
                    yt[j] = y[j] + hs * kp[j];
                    ytl[j] = kpl[j].fma(hs, yl[j]);
                }
                (yt, ytl)
            };
            fz.deriv_lanes(
                ss,
                at,
                taul,
                active,
                strings,
                &mut todo[..n],
                &mut todol[..n],
            )?;
        }
        let (k1, k2, k3, k4) = (&k[..n], &k[n..2 * n], &k[2 * n..3 * n], &k[3 * n..]);
        let (l1, l2, l3, l4) = (&kl[..n], &kl[n..2 * n], &kl[2 * n..3 * n], &kl[3 * n..]);
        for j in 0..n {
            y[j] += h6 * (k1[j] + 2.0 * (k2[j] + k3[j]) + k4[j]);
            yl[j] = ((l2[j] + l3[j]).fma(2.0, l1[j]) + l4[j]).fma(h6, yl[j]);
        }
        // q / |q| and its lanes (dq - q/|q| d|q|) / |q|, d|q| = q . dq / |q|
        let qn = (y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]).sqrt();
        let inv = 1.0 / qn;
        let dqn = lin([(yl[3], y[3]), (yl[4], y[4]), (yl[5], y[5]), (yl[6], y[6])]) * inv;
        for j in 3..7 {
            y[j] /= qn;
            yl[j] = dqn.fma(-y[j], yl[j]) * inv;
        }
        Ok(())
    }
}

/// The dual form of the state `y` with lanes `yl`, into `out`.
#[inline(always)]
fn to_duals<const N: usize>(y: &[f64], yl: &[Lanes<N>], out: &mut [Dual<N>]) {
    for (d, (re, l)) in out.iter_mut().zip(y.iter().zip(yl)) {
        *d = Dual::new(*re, l.0);
    }
}

/// [`super::pass`] on the hand-linearised right-hand side
/// ([`RodRhs::deriv_lanes`]).
///
/// With a `hook` every node is recorded and handed to it first, the tip
/// included (before its balance); where the hook returns true, the pass
/// continues from the columns times the matrix it wrote (see
/// [`hook_node`]). The variational equations are linear in the lanes and
/// the real part never reads them, so the tangents after a node are the
/// plain pass's times the product of the matrices applied so far (to
/// rounding), and the real part is the plain IVP's bit for bit unless the
/// hook writes the state (linearising about a given trajectory). With a hook
/// that never asks, or none, the arithmetic is the plain pass's.
#[inline(always)]
pub(super) fn pass_lanes<const N: usize>(
    p: &Pass<'_, '_>,
    record: Record,
    nodes: &mut TangentNodes,
    mut hook: Option<&mut ColumnHook<'_>>,
) -> Result<TangentIvp> {
    let (spec, c0, w) = (p.spec, p.c0, p.w);
    let robot = spec.robot;
    let fz = RodRhs::new(robot, spec.tensions);
    let na = robot.actuators.len();
    let n = robot.n_states();
    let len = robot.body.length;
    let steps = spec.steps.max(1);
    let (mut tau, mut duals) = seeded_start::<N>(p, n);
    let mut taul: Vec<Lanes<N>> = tau.iter().map(Lanes::of).collect();
    let mut y: Vec<f64> = duals.iter().map(|d| d.re).collect();
    let mut yl: Vec<Lanes<N>> = duals.iter().map(Lanes::of).collect();
    let mut st = LaneStages::<N>::new(n, na);
    let record = if hook.is_some() {
        Record::Tangents
    } else {
        record
    };
    let rec = record != Record::Tip;
    // the hook's scratch: the node's columns and the matrix it writes
    let hooked = if hook.is_some() { w } else { 0 };
    let (mut cols, mut m) = (vec![0.0; n * hooked], vec![0.0; hooked * hooked]);
    let mut elongation = vec![Dual::<N>::cst(0.0); na];
    let mut idx = 0;
    // hand node `idx` to the hook, if any
    macro_rules! hook {
        () => {
            if let Some(h) = hook.as_deref_mut() {
                let at = (&mut y[..], &mut yl[..], &mut cols[..], &mut m[..]);
                hook_node(h, idx, at, &mut taul, &mut tau, &mut elongation, w);
            }
        };
    }
    // record node `idx` at `s` if asked
    macro_rules! node {
        ($s:expr) => {
            if rec {
                hook!();
                nodes.record_lanes(idx, $s, (&y, &yl), c0, w);
                idx += 1;
            }
        };
    }
    let bps = robot.breakpoints();
    let tol = 1e-12 * len;
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
        if stretch.jumps_at_start(&iv) {
            to_duals(&y, &yl, &mut duals);
            if anchored_at(robot, a, tol, |i| elongation[i] = duals[BASE_STATES + i]) {
                fz.anchor_tangent(a, &mut duals, &tau)?;
                for (j, d) in duals.iter().enumerate() {
                    (y[j], yl[j]) = (d.re, Lanes::of(d));
                }
            }
        }
        node!(a);
        spanning(robot, a, b, tol, &mut active);
        st.clear_rates(n);
        let h = iv.h();
        for kk in range {
            let s = a + kk as f64 * h;
            st.step(&fz, s, h, (&mut y, &mut yl), &taul, &active)?;
            if kk + 1 < iv.m {
                node!(s + h);
            }
        }
    }
    let at_tip = stretch.last >= first_node;
    hook!();
    to_duals(&y, &yl, &mut duals);
    let at = (record, nodes, idx, at_tip);
    close(p, &fz, &duals, &tau, &mut elongation, at)
}

/// Replace the `w` columns of lanes `l` (lane `c` is column `c`) by
/// `l m`: column `c` becomes `sum_j l_j m[j + c w]` (`m` is `w x w`, by
/// columns); the lanes from `w` on stay zero.
#[inline(always)]
fn mix_lanes<const N: usize>(l: &mut [f64; N], m: &[f64], w: usize) {
    let old = *l;
    for (c, x) in l.iter_mut().enumerate().take(w) {
        let mc = &m[c * w..(c + 1) * w];
        *x = old[..w].iter().zip(mc).map(|(a, b)| a * b).sum();
    }
}

/// At node `idx`, the state `y` and the tangent columns (`n x w`, by
/// columns) handed to `hook`; if it asks for it, every lane of the pass
/// (state, tensions in both forms, elongations recorded so far) replaced by
/// its columns times the hook's `w x w` matrix. The real parts other than
/// the state are untouched; the state is what the hook leaves in `y`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn hook_node<const N: usize>(
    hook: &mut ColumnHook<'_>,
    idx: usize,
    (y, yl, cols, m): (&mut [f64], &mut [Lanes<N>], &mut [f64], &mut [f64]),
    taul: &mut [Lanes<N>],
    tau: &mut [Dual<N>],
    elongation: &mut [Dual<N>],
    w: usize,
) {
    let n = yl.len();
    for (c, col) in cols.chunks_exact_mut(n).enumerate().take(w) {
        for (x, l) in col.iter_mut().zip(yl.iter()) {
            *x = l.0[c];
        }
    }
    if !hook(idx, y, &cols[..n * w], &mut m[..w * w]) {
        return;
    }
    for l in yl.iter_mut().chain(taul.iter_mut()) {
        mix_lanes(&mut l.0, m, w);
    }
    for d in tau.iter_mut().chain(elongation.iter_mut()) {
        mix_lanes(&mut d.eps, m, w);
    }
}
