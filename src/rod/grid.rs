//! The IVP's grid, numbered node by node, and the stretches of it that a
//! segment of multiple shooting integrates.
//!
//! The grid has a breakpoint at the base, the tip and every actuator anchor
//! ([`Robot::breakpoints`]); the interval `[a, b]` between two breakpoints
//! takes `m = round((b - a) / L * steps)` (at least one) RK4 steps of
//! `h = (b - a) / m`, the node `k` of the interval at `a + k h`. Nodes are
//! numbered from the base (node 0) to the tip ([`Grid::tip`]); the node at a
//! breakpoint inside the body is the last of one interval and the first of
//! the next. The anchor loads at a breakpoint are applied as the integration
//! leaves its node, so a state *at* a node is the state before them.

use super::Robot;

/// One interval between two breakpoints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// Its start \[m\].
    pub a: f64,
    /// Its end \[m\].
    pub b: f64,
    /// RK4 steps in it.
    pub m: usize,
    /// Number of its first node.
    pub first_node: usize,
}

impl Interval {
    /// The interval `[a, b]` of a body of length `len` on `steps` RK4 steps
    /// over its length, its first node `*first_node`, which moves on to the
    /// next interval's.
    #[inline(always)]
    pub fn new(a: f64, b: f64, len: f64, steps: usize, first_node: &mut usize) -> Self {
        let m = (((b - a) / len) * steps.max(1) as f64).round().max(1.0) as usize;
        let iv = Interval {
            a,
            b,
            m,
            first_node: *first_node,
        };
        *first_node += m;
        iv
    }

    /// Step length \[m\], as the IVP computes it.
    #[inline(always)]
    pub fn h(&self) -> f64 {
        (self.b - self.a) / self.m as f64
    }
}

/// The grid of a robot's IVP on `steps` RK4 steps.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// The intervals from the base to the tip.
    pub intervals: Vec<Interval>,
}

impl Grid {
    /// The grid of `robot` on `steps` RK4 steps over its length.
    pub fn new(robot: &Robot, steps: usize) -> Self {
        let len = robot.body.length;
        let mut first_node = 0;
        let intervals = robot
            .breakpoints()
            .windows(2)
            .map(|w| Interval::new(w[0], w[1], len, steps, &mut first_node))
            .collect();
        Grid { intervals }
    }

    /// Number of the tip node (the number of RK4 steps).
    pub fn tip(&self) -> usize {
        self.intervals.last().map_or(0, |iv| iv.first_node + iv.m)
    }

    /// Arc length \[m\] of `node`, as the IVP steps to it.
    pub fn s(&self, node: usize) -> f64 {
        let iv = self.interval_of(node);
        let k = node - iv.first_node;
        if k == iv.m {
            iv.b
        } else {
            iv.a + k as f64 * iv.h()
        }
    }

    /// Whether `node` is a breakpoint (base, tip or an anchor).
    pub fn is_breakpoint(&self, node: usize) -> bool {
        node == 0 || self.intervals.iter().any(|iv| iv.first_node + iv.m == node)
    }

    /// The interval whose steps start at `node` (the last interval for the tip).
    fn interval_of(&self, node: usize) -> &Interval {
        self.intervals
            .iter()
            .find(|iv| node < iv.first_node + iv.m)
            .unwrap_or_else(|| self.intervals.last().expect("a grid has an interval"))
    }

    /// The whole grid, base to tip.
    pub fn whole(&self) -> Stretch {
        Stretch {
            first: 0,
            last: self.tip(),
        }
    }
}

/// The nodes `first ..= last` of a [`Grid`], integrated from the state at
/// `first` (before its anchor loads) to the state at `last` (before its
/// anchor loads; at the tip, the tip balance closes it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Stretch {
    /// The first node.
    pub first: usize,
    /// The last node.
    pub last: usize,
}

impl Stretch {
    /// The steps of `iv` inside this stretch, as a range of step indices
    /// within the interval (empty if none).
    #[inline(always)]
    pub fn steps_in(&self, iv: &Interval) -> std::ops::Range<usize> {
        let lo = self.first.saturating_sub(iv.first_node).min(iv.m);
        let hi = self.last.saturating_sub(iv.first_node).min(iv.m);
        lo..hi.max(lo)
    }
    /// Whether the anchor loads at the start of `iv` are applied in this
    /// stretch: the interval starts inside the body at a node this
    /// stretch leaves.
    #[inline(always)]
    pub fn jumps_at_start(&self, iv: &Interval) -> bool {
        iv.a > 0.0 && iv.first_node >= self.first && iv.first_node < self.last
    }
}
