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
#[inline(always)]
pub(super) fn pass_lanes<const N: usize>(
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
    let (tau, mut duals) = seeded_start::<N>(p, n);
    let taul: Vec<Lanes<N>> = tau.iter().map(Lanes::of).collect();
    let mut y: Vec<f64> = duals.iter().map(|d| d.re).collect();
    let mut yl: Vec<Lanes<N>> = duals.iter().map(Lanes::of).collect();
    let mut st = LaneStages::<N>::new(n, na);
    let rec = record != Record::Tip;
    let mut idx = 0;
    // record node `idx` at `s` if asked
    macro_rules! node {
        ($s:expr) => {
            if rec {
                nodes.record_lanes(idx, $s, (&y, &yl), c0, w);
                idx += 1;
            }
        };
    }
    let bps = robot.breakpoints();
    let tol = 1e-12 * len;
    let mut elongation = vec![Dual::<N>::cst(0.0); na];
    let mut active: Vec<usize> = Vec::with_capacity(na);
    for win in bps.windows(2) {
        let (a, b) = (win[0], win[1]);
        if a > 0.0 {
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
        let m = (((b - a) / len) * steps as f64).round().max(1.0) as usize;
        let h = (b - a) / m as f64;
        for kk in 0..m {
            let s = a + kk as f64 * h;
            st.step(&fz, s, h, (&mut y, &mut yl), &taul, &active)?;
            if kk + 1 < m {
                node!(s + h);
            }
        }
    }
    to_duals(&y, &yl, &mut duals);
    close(p, &fz, &duals, &tau, &mut elongation, (record, nodes, idx))
}
