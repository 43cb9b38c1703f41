//! The initial value problem: fixed-step RK4 from the base to the tip on a
//! grid with a node at every anchor.

use nalgebra::{Quaternion, Vector3};

use super::grid::{Interval, Stretch};
use super::ode::{all_finite, RodRhs};
use super::{rot, FlatNodes, Robot, RodState, BASE_STATES};
use crate::error::{Error, Result};

/// Everything an IVP needs besides the state: robot, tensions, loads.
pub struct IvpSpec<'a> {
    /// The robot.
    pub robot: &'a Robot,
    /// Tension of each actuator \[N\] (constant along a string).
    pub tensions: &'a [f64],
    /// Tip force \[N\], world frame (overrides `body.tip_force`, so that
    /// Jacobians can perturb it).
    pub tip_force: Vector3<f64>,
    /// Tip moment \[N m\], world frame.
    pub tip_moment: Vector3<f64>,
    /// RK4 steps over the body length.
    pub steps: usize,
}

/// Output of one IVP.
#[derive(Debug, Clone)]
pub struct IvpResult {
    /// Tip state.
    pub tip: RodState,
    /// Elongation of each actuator at its distal anchor \[m\].
    pub elongation: Vec<f64>,
    /// Tip residual in body frame: `K_nu (v - nu*) - R^T F + sum tau t_b` \[N\]
    /// and `K_omega (u - omega*) - R^T M + sum r x tau t_b` \[N m\] (eqs 32-33).
    pub tip_force_residual: Vector3<f64>,
    /// See `tip_force_residual`.
    pub tip_moment_residual: Vector3<f64>,
    /// Recorded nodes `(s, state)`, if asked for.
    pub nodes: Vec<(f64, RodState)>,
}

/// States held on the stack by [`integrate`] (13 + up to 19 actuators).
const STACK_STATES: usize = 32;

/// `out = y + h k`, elementwise.
#[inline(always)]
fn axpy(out: &mut [f64], y: &[f64], h: f64, k: &[f64]) {
    for ((o, a), b) in out.iter_mut().zip(y).zip(k) {
        *o = a + h * b;
    }
}

/// The RK4 update `y += h/6 (k1 + 2 k2 + 2 k3 + k4)`, then the quaternion
/// renormalised.
#[inline(always)]
fn rk4_update(y: &mut [f64], k1: &[f64], k2: &[f64], k3: &[f64], k4: &[f64], h6: f64) {
    for ((((yj, a), b), c), d) in y
        .iter_mut()
        .zip(k1.iter())
        .zip(k2.iter())
        .zip(k3.iter())
        .zip(k4.iter())
    {
        *yj += h6 * (a + 2.0 * (b + c) + d);
    }
    let qn = (y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]).sqrt();
    for yq in &mut y[3..7] {
        *yq /= qn;
    }
}

/// One RK4 step from `s` with `[h, h/2, h/6]`, the quaternion renormalised,
/// then `y` checked; `ks` (5 n) is scratch for the stages and their state.
#[inline(always)]
fn rk4_step(
    fz: &RodRhs<'_>,
    s: f64,
    [h, h2, h6]: [f64; 3],
    active: &[usize],
    y: &mut [f64],
    ks: &mut [f64],
) -> Result<()> {
    let n = y.len();
    let (k1, rest) = ks.split_at_mut(n);
    let (k2, rest) = rest.split_at_mut(n);
    let (k3, rest) = rest.split_at_mut(n);
    let (k4, yt) = rest.split_at_mut(n);
    fz.deriv(s, y, active, k1)?;
    axpy(yt, y, h2, k1);
    fz.deriv(s + h2, yt, active, k2)?;
    axpy(yt, y, h2, k2);
    fz.deriv(s + h2, yt, active, k3)?;
    axpy(yt, y, h, k3);
    fz.deriv(s + h, yt, active, k4)?;
    rk4_update(y, k1, k2, k3, k4, h6);
    // once per step, not per stage: a non-finite rate in any stage makes
    // `y` non-finite (the quaternion's norm included)
    if !all_finite(y) {
        return Err(Error::Integration {
            s: s + h,
            reason: "non-finite derivative".into(),
        });
    }
    Ok(())
}

/// At a breakpoint `a` inside the body: record the elongation of the strings
/// ending there, then apply all anchor and kink loads at `a` together.
fn anchors_at(
    robot: &Robot,
    fz: &RodRhs<'_>,
    a: f64,
    y: &mut [f64],
    elongation: &mut [f64],
    tol: f64,
) -> Result<()> {
    if anchored_at(robot, a, tol, |i| elongation[i] = y[BASE_STATES + i]) {
        fz.anchor_loads(a, y)?;
    }
    Ok(())
}

/// True if an actuator is anchored at `a` (either end); `on_end(i)` for each
/// actuator `i` whose string ends there.
#[inline(always)]
pub(super) fn anchored_at(robot: &Robot, a: f64, tol: f64, mut on_end: impl FnMut(usize)) -> bool {
    let mut any = false;
    for (i, act) in robot.actuators.iter().enumerate() {
        if (act.s_end - a).abs() <= tol {
            on_end(i);
            any = true;
        }
        any |= (act.s_start - a).abs() <= tol;
    }
    any
}

/// The actuators spanning the grid interval `[a, b]`, into `active`.
#[inline(always)]
pub(super) fn spanning(robot: &Robot, a: f64, b: f64, tol: f64, active: &mut Vec<usize>) {
    active.clear();
    active.extend((0..robot.actuators.len()).filter(|&i| {
        let act = &robot.actuators[i];
        act.s_start <= a + tol && act.s_end >= b - tol
    }));
}

/// The tip balance (32)-(33) at the tip state `y`, closed by the actuators
/// anchored at the tip (their elongations recorded in `elongation`).
fn tip_balance(
    spec: &IvpSpec<'_>,
    fz: &RodRhs<'_>,
    y: &[f64],
    elongation: &mut [f64],
    tol: f64,
) -> (Vector3<f64>, Vector3<f64>) {
    let body = &spec.robot.body;
    let len = body.length;
    let (kse, kbt) = body.stiffness();
    let v = Vector3::new(y[7], y[8], y[9]);
    let u = Vector3::new(y[10], y[11], y[12]);
    let q = Quaternion::new(y[3], y[4], y[5], y[6]);
    let rt = rot(&q).transpose();
    let mut rf = kse * (v - body.nu_star) - rt * spec.tip_force; // (32)
    let mut rm = kbt * (u - body.omega_star) - rt * spec.tip_moment; // (33)
    for (i, act) in spec.robot.actuators.iter().enumerate() {
        if (act.s_end - len).abs() <= tol {
            elongation[i] = y[BASE_STATES + i];
            let (pb, r) = fz.pb(i, len, &v, &u);
            let t = pb / pb.norm();
            let tau = spec.tensions[i];
            rf += t * tau;
            rm += r.cross(&t) * tau;
        }
    }
    (rf, rm)
}

/// Integrate the rod from the base with unknown initial strains `v0`, `u0`
/// (eqs 22-25), by fixed-step RK4 on a grid that has a node at every actuator
/// anchor. Actuator elongations start at zero at their proximal anchors.
///
/// Compiled twice and chosen at run time: for AVX2 + FMA where the CPU has
/// them, else for the x86-64 baseline (SSE2), so one wheel runs everywhere.
/// Rust never fuses a multiply and an add on its own, so both copies do the
/// same IEEE operations in the same order: bit-for-bit the same results.
pub fn integrate(
    spec: &IvpSpec<'_>,
    v0: &Vector3<f64>,
    u0: &Vector3<f64>,
    record: bool,
) -> Result<IvpResult> {
    if !record {
        return dispatch(spec, Start::Base(v0, u0), None);
    }
    let (mut ivp, nodes) = integrate_flat(spec, v0, u0)?;
    ivp.nodes = nodes.to_states();
    Ok(ivp)
}

/// [`integrate`] recording its nodes flat (one allocation for all of
/// them; the result's own `nodes` stay empty).
pub(crate) fn integrate_flat(
    spec: &IvpSpec<'_>,
    v0: &Vector3<f64>,
    u0: &Vector3<f64>,
) -> Result<(IvpResult, FlatNodes)> {
    let mut nodes = FlatNodes::default();
    let ivp = dispatch(spec, Start::Base(v0, u0), Some(&mut nodes))?;
    Ok((ivp, nodes))
}

/// Where an IVP starts: at the base from its initial strains, over the
/// whole grid, or at the first node of a [`Stretch`] from a whole state.
#[derive(Clone, Copy)]
pub(crate) enum Start<'y> {
    /// The base at the origin with the identity rotation, `nu(0)`, `omega(0)`.
    Base(&'y Vector3<f64>, &'y Vector3<f64>),
    /// The state `y0` (`n_states` values) at the stretch's first node.
    Node(Stretch, &'y [f64]),
}

impl Start<'_> {
    /// The stretch integrated (from the base: the whole grid).
    #[inline(always)]
    pub(crate) fn stretch(&self) -> Stretch {
        match self {
            Start::Base(..) => Stretch {
                first: 0,
                last: usize::MAX,
            },
            Start::Node(st, _) => *st,
        }
    }
    /// Write the start state into `y` (`n_states` values).
    #[inline(always)]
    pub(crate) fn write(&self, y: &mut [f64]) {
        match self {
            Start::Base(v0, u0) => {
                y.fill(0.0);
                y[3] = 1.0;
                y[7..10].copy_from_slice(v0.as_slice());
                y[10..13].copy_from_slice(u0.as_slice());
            }
            Start::Node(_, y0) => y.copy_from_slice(y0),
        }
    }
}

impl IvpSpec<'_> {
    /// The IVP over `stretch` of its grid ([`crate::rod::Grid::new`] of this robot and
    /// step count) from the state `y0` at its first node, before that
    /// node's anchor loads (`n_states` values: `p`, unit `q`, `nu`,
    /// `omega`, `delta`): the state at its last node (`tip`; before the
    /// anchor loads there), the elongations \[m\] of the actuators whose
    /// distal anchor the stretch leaves or closes at the tip (the others
    /// zero) and, if the stretch ends at the tip, the tip balance (32)-(33)
    /// (else zero). The arithmetic is the whole IVP's on those steps, so
    /// stretches chained end to start give its states bit for bit.
    pub fn integrate_stretch(&self, stretch: Stretch, y0: &[f64]) -> Result<IvpResult> {
        if y0.len() != self.robot.n_states() || stretch.first > stretch.last {
            return Err(Error::input(
                "stretch",
                format!(
                    "a state of {} values and first <= last node",
                    self.robot.n_states()
                ),
            ));
        }
        dispatch(self, Start::Node(stretch, y0), None)
    }

    /// [`IvpSpec::integrate_stretch`] with its nodes appended to `nodes`:
    /// the states at its first node (after that node's anchor loads, as
    /// [`integrate`] records them) and at every later node but its last,
    /// which the next stretch records; at the tip, the tip too.
    pub(crate) fn integrate_stretch_recorded(
        &self,
        stretch: Stretch,
        y0: &[f64],
        nodes: &mut FlatNodes,
    ) -> Result<IvpResult> {
        dispatch(self, Start::Node(stretch, y0), Some(nodes))
    }
}

/// The compiled copy of [`integrate_plain`] for this CPU.
#[inline(always)]
fn dispatch(
    spec: &IvpSpec<'_>,
    start: Start<'_>,
    record: Option<&mut FlatNodes>,
) -> Result<IvpResult> {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
            // SAFETY: the CPU supports AVX2 and FMA (checked just above).
            return unsafe { integrate_avx2(spec, start, record) };
        }
    }
    integrate_plain(spec, start, record)
}

/// [`integrate_plain`] with AVX2 and FMA enabled.
///
/// # Safety
/// The CPU must support AVX2 and FMA.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn integrate_avx2(
    spec: &IvpSpec<'_>,
    start: Start<'_>,
    record: Option<&mut FlatNodes>,
) -> Result<IvpResult> {
    integrate_plain(spec, start, record)
}

/// The body of [`integrate`] and [`IvpSpec::integrate_stretch`], inlined
/// into each compiled copy; the nodes into `record` if given.
#[inline(always)]
fn integrate_plain(
    spec: &IvpSpec<'_>,
    start: Start<'_>,
    mut record: Option<&mut FlatNodes>,
) -> Result<IvpResult> {
    let robot = spec.robot;
    let body = &robot.body;
    let fz = RodRhs::new(robot, spec.tensions);
    let na = robot.actuators.len();
    let n = robot.n_states();
    let len = body.length;
    let steps = spec.steps.max(1);
    // state and RK4 stages on the stack for up to STACK_STATES states (no
    // allocation per IVP; cheap IVPs of coarse grids are dominated by it)
    let mut stack = [0.0f64; 6 * STACK_STATES];
    let mut heap: Vec<f64>;
    let all: &mut [f64] = if n <= STACK_STATES {
        &mut stack[..6 * n]
    } else {
        heap = vec![0.0; 6 * n];
        &mut heap
    };
    let (y, ks) = all.split_at_mut(n);
    start.write(y);
    let bps = robot.breakpoints();
    let tol = 1e-12 * len;
    if let Some(rec) = record.as_mut() {
        rec.reserve(n, steps + bps.len());
    }
    let stretch = start.stretch();
    let mut elongation = vec![0.0; na];
    let mut active: Vec<usize> = Vec::with_capacity(na);
    let mut first_node = 0;
    for w in bps.windows(2) {
        let (a, b) = (w[0], w[1]);
        let iv = Interval::new(a, b, len, steps, &mut first_node);
        let range = stretch.steps_in(&iv);
        if range.is_empty() {
            continue;
        }
        if stretch.jumps_at_start(&iv) {
            anchors_at(robot, &fz, a, y, &mut elongation, tol)?;
        }
        if let Some(rec) = record.as_mut() {
            rec.push(a + range.start as f64 * iv.h(), y);
        }
        spanning(robot, a, b, tol, &mut active);
        // the stages' rates of the actuators not spanning [a, b] are zero
        // (`RodRhs::deriv` leaves them as they are)
        for k in ks.chunks_exact_mut(n) {
            k[BASE_STATES..].fill(0.0);
        }
        let h = iv.h();
        let hs = [h, 0.5 * h, h / 6.0];
        for k in range {
            let s = a + k as f64 * h;
            rk4_step(&fz, s, hs, &active, y, ks)?;
            let inner = k + 1 < iv.m && iv.first_node + k + 1 < stretch.last;
            if let Some(rec) = record.as_mut().filter(|_| inner) {
                rec.push(s + h, y);
            }
        }
    }
    let at_tip = stretch.last >= first_node;
    let (rf, rm) = if at_tip {
        tip_balance(spec, &fz, y, &mut elongation, tol)
    } else {
        (Vector3::zeros(), Vector3::zeros())
    };
    if let Some(rec) = record.as_mut().filter(|_| at_tip) {
        rec.push(len, y);
    }
    Ok(IvpResult {
        tip: RodState::from_slice(y),
        elongation,
        tip_force_residual: rf,
        tip_moment_residual: rm,
        nodes: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rod::{Body, Section};

    /// The finiteness check runs once per RK4 step, not per stage: a
    /// non-finite rate in a stage must still end the IVP with an error
    /// rather than a non-finite tip. With no actuator, no string check
    /// or singular (25) can catch the NaN first; only the check can.
    #[test]
    fn a_non_finite_rate_in_a_stage_is_an_error() {
        let body = Body::new(
            0.04,
            Section::Circle { diameter: 8e-3 },
            37.8e3,
            0.5,
            1040.0,
        );
        let robot = Robot::new(body.unwrap(), vec![]).unwrap();
        let spec = IvpSpec {
            robot: &robot,
            tensions: &[],
            tip_force: Vector3::zeros(),
            tip_moment: Vector3::zeros(),
            steps: 10,
        };
        let ok = integrate(
            &spec,
            &Vector3::new(0.0, 0.0, 1.0),
            &Vector3::zeros(),
            false,
        );
        assert!(ok.is_ok());
        let u0 = Vector3::new(f64::NAN, 0.0, 0.0);
        match integrate(&spec, &Vector3::new(0.0, 0.0, 1.0), &u0, false) {
            Err(Error::Integration { s, reason }) => {
                assert!(reason.contains("non-finite"), "{reason}");
                // caught at the end of the first step (s = L / 10)
                assert!((s - 0.004).abs() < 1e-12, "{s}");
            }
            other => panic!("expected an integration error, got {other:?}"),
        }
        // with a taut string the NaN reaches the string's length rate first
        // (the next stage): the same reason, not "zero length rate"
        let tendon = crate::rod::Actuator::new(
            crate::rod::Routing::straight(2e-3, 0.0).unwrap(),
            0.0,
            0.04,
            std::sync::Arc::new(crate::rod::ConstantTension),
        );
        let robot = Robot::new(robot.body.clone(), vec![tendon]).unwrap();
        let spec = IvpSpec {
            robot: &robot,
            tensions: &[0.01],
            ..spec
        };
        match integrate(&spec, &Vector3::new(0.0, 0.0, 1.0), &u0, false) {
            Err(Error::Integration { reason, .. }) => {
                assert!(reason.contains("non-finite"), "{reason}")
            }
            other => panic!("expected an integration error, got {other:?}"),
        }
    }
}
