//! Where the segments of multiple shooting start: chosen once, before the
//! Newton solve, from the body's stiffness and its external loads.
//!
//! Linearised about a straight state carrying an axial tension `T`, the
//! bending of the rod obeys the beam-column equation `EI w'''' - T w'' =
//! 0`, whose solutions `cosh`, `sinh(s / l_T)` grow by `e` every `l_T =
//! sqrt(EI / T)` (Timoshenko & Gere, *Theory of Elastic Stability*, ch. 1).
//! The shooting map's sensitivity across a stretch `[a, b]` therefore grows
//! like `exp(int_a^b sqrt(T(s) / EI) ds)`, and single shooting fails once
//! that exceeds `1 / eps` (Ascher, Mattheij & Russell, *Numerical Solution
//! of Boundary Value Problems for ODEs*, SIAM 1995, sec. 4.1-4.3). Before
//! the solve, `T(s)` is bounded by the magnitude of the external load
//! resultant beyond `s`, `|F_tip + (psi A g + f)(L - s)|` (taken as all
//! tension, the worst case); a string's tension does not enter, since its
//! pull on the body is balanced by its pressure along its path. A segment
//! ends where the exponent reaches `ln G`, [`GROWTH_BOUND`]: then Newton's
//! linear model holds over each segment as it does on an unloaded rod, and
//! the rounding of a segment's end state is at most `eps G` of its size.
//! Unloaded bodies, and light ones, are one segment: single shooting.
//!
//! Segments never start at an actuator anchor: the anchor loads are applied
//! inside a segment, so a segment's start state is the rod's state at that
//! node without ambiguity.

use super::residual::Loads;
use crate::rod::{Grid, Robot};

/// The growth `G` of the shooting map's sensitivity allowed across one
/// segment. Newton's step on a segment is then as well conditioned as on a
/// body whose `int sqrt(T / EI) ds` is `ln G ~ 4.6`, which single shooting
/// solves from the straight configuration in a few iterations; the
/// rounding of each segment stays at `eps G ~ 2e-14`.
pub const GROWTH_BOUND: f64 = 100.0;

/// `lambda(s) = sqrt(T(s) / EI)` \[1/m\] with `T(s)` the a priori bound on
/// the axial tension at `s` (see the module docs).
fn rate(robot: &Robot, loads: &Loads) -> impl Fn(f64) -> f64 {
    let body = &robot.body;
    let ei = body.bending_stiffness();
    let (len, q, f) = (body.length, body.distributed_load(), loads.tip_force);
    move |s: f64| ((f + q * (len - s)).norm() / ei).sqrt()
}

/// The largest `lambda` \[1/m\] along the body: the fastest growth or decay
/// rate of the bending tangents. `|F_tip + q (L - s)|` is convex in `s`,
/// so its largest value is at the base or the tip.
pub fn largest_rate(robot: &Robot, loads: &Loads) -> f64 {
    let lambda = rate(robot, loads);
    lambda(0.0).max(lambda(robot.body.length))
}

/// The first node of each segment of `robot` under `loads` on `steps` RK4
/// steps (node 0 first; see the module docs).
pub fn segment_starts(robot: &Robot, loads: &Loads, steps: usize) -> Vec<usize> {
    let grid = Grid::new(robot, steps);
    let lambda = rate(robot, loads);
    let limit = GROWTH_BOUND.ln();
    let mut starts = vec![0];
    let mut exponent = 0.0;
    let tip = grid.tip();
    for node in 0..tip {
        let (a, b) = (grid.s(node), grid.s(node + 1));
        exponent += 0.5 * (lambda(a) + lambda(b)) * (b - a);
        let next = node + 1;
        if exponent > limit && next < tip && !grid.is_breakpoint(next) {
            starts.push(next);
            exponent = 0.0;
        }
    }
    starts
}
