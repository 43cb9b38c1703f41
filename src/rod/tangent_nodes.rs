//! The seed directions of a tangent IVP and its recorded grid nodes (one
//! flat buffer each for the arc lengths, states and tangents).

use std::cell::RefCell;

use nalgebra::DMatrix;

use super::dual::Dual;
use super::lanes::Lanes;

/// Seed directions of a tangent IVP: each column is one direction, giving
/// the derivative of the initial strains and of the tensions along it.
#[derive(Debug, Clone)]
pub struct TangentSeeds {
    /// `d nu(0)` \[-\], `3 x k`.
    pub nu0: DMatrix<f64>,
    /// `d omega(0)` \[1/m\], `3 x k`.
    pub omega0: DMatrix<f64>,
    /// `d tau` \[N\], `n_actuators x k`.
    pub tensions: DMatrix<f64>,
    /// `d y(s_first)`, `n_states x k`: the whole start state of a stretch
    /// ([`crate::rod::IvpSpec::integrate_stretch_tangent`]); `None` from the
    /// base.
    pub state0: Option<DMatrix<f64>>,
}

impl TangentSeeds {
    /// `k` zero directions for a robot with `na` actuators.
    pub fn zeros(na: usize, k: usize) -> Self {
        TangentSeeds {
            nu0: DMatrix::zeros(3, k),
            omega0: DMatrix::zeros(3, k),
            tensions: DMatrix::zeros(na, k),
            state0: None,
        }
    }
    /// Number of directions.
    pub fn directions(&self) -> usize {
        self.nu0.ncols()
    }
}

impl Drop for TangentNodes {
    /// Keep the buffers for the next recording on this thread.
    fn drop(&mut self) {
        if self.tangent.capacity() == 0 || self.tangent.capacity() > SPARE_MAX {
            return;
        }
        let b = (
            std::mem::take(&mut self.s),
            std::mem::take(&mut self.state),
            std::mem::take(&mut self.tangent),
        );
        let _ = SPARE.try_with(|c| {
            if let Ok(mut spare) = c.try_borrow_mut() {
                *spare = Some(b);
            }
        });
    }
}

/// One recorded grid node of a tangent IVP (a view into [`TangentNodes`]).
#[derive(Debug, Clone, Copy)]
pub struct TangentNode<'a> {
    /// Arc length \[m\].
    pub s: f64,
    /// State `y(s)` (`p, q, nu, omega, delta`; see [`crate::rod::BASE_STATES`]).
    pub state: &'a [f64],
    /// `d y(s) / d seed`, `n_states x k` column-major (after the jump at an
    /// anchor node): column `j` is `tangent[j * n_states..(j + 1) * n_states]`.
    pub tangent: &'a [f64],
}

/// The recorded grid nodes of a tangent IVP, in one flat buffer each for
/// the arc lengths, the states and the tangents (no allocation per node).
#[derive(Debug, Clone, Default)]
pub struct TangentNodes {
    /// States per node.
    n: usize,
    /// Directions per node.
    k: usize,
    s: Vec<f64>,
    state: Vec<f64>,
    tangent: Vec<f64>,
}

/// The buffers `(s, state, tangent)` of a recorded [`TangentNodes`].
type Buffers = (Vec<f64>, Vec<f64>, Vec<f64>);

/// Largest tangent buffer kept for reuse (f64s: 1 MB; Fig. 6's verdict
/// takes 12,120), so that a long grid's buffer is not held on to.
const SPARE_MAX: usize = 1 << 17;

thread_local! {
    /// The buffers of the last recorded [`TangentNodes`] dropped on this
    /// thread, reused by the next recording: a stability verdict's tangents
    /// take ~100 kB (Fig. 6: 101 nodes of 15 states by 8 directions), and
    /// freeing them can hand the pages back to the system (glibc trims a heap
    /// top above 128 kB), to be faulted in again by the next verdict.
    static SPARE: RefCell<Option<Buffers>> = const { RefCell::new(None) };
}

impl TangentNodes {
    pub(super) fn new(n: usize, k: usize, capacity: usize) -> Self {
        let spare = match capacity {
            0 => None,
            _ => SPARE.try_with(|c| c.borrow_mut().take()).ok().flatten(),
        };
        let (mut s, mut state, mut tangent) = spare.unwrap_or_default();
        s.clear();
        state.clear();
        tangent.clear();
        s.reserve(capacity);
        state.reserve(capacity * n);
        tangent.reserve(capacity * n * k);
        TangentNodes {
            n,
            k,
            s,
            state,
            tangent,
        }
    }
    /// The recorded states alone, flat (the IVP's nodes: the real parts).
    pub(crate) fn to_flat(&self) -> super::FlatNodes {
        super::FlatNodes {
            s: self.s.clone(),
            y: self.state.clone(),
            n: self.n,
        }
    }
    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.s.len()
    }
    /// True if no node was recorded.
    pub fn is_empty(&self) -> bool {
        self.s.is_empty()
    }
    /// Node `i`.
    pub fn get(&self, i: usize) -> TangentNode<'_> {
        let (n, nk) = (self.n, self.n * self.k);
        TangentNode {
            s: self.s[i],
            state: &self.state[i * n..(i + 1) * n],
            tangent: &self.tangent[i * nk..(i + 1) * nk],
        }
    }
    /// The nodes in order.
    pub fn iter(&self) -> impl Iterator<Item = TangentNode<'_>> {
        (0..self.len()).map(|i| self.get(i))
    }
    /// `d y / d seed` of node `i` as an `n_states x k` matrix.
    pub fn tangent_matrix(&self, i: usize) -> DMatrix<f64> {
        DMatrix::from_column_slice(self.n, self.k, self.get(i).tangent)
    }
    /// [`TangentNodes::record`] from the values `y` and their lanes `yl`
    /// (the hand-linearised pass), with no dual form built: each direction's
    /// column written in order, appended directly by a pass over all of them.
    #[inline(always)]
    pub(super) fn record_lanes<const N: usize>(
        &mut self,
        idx: usize,
        s: f64,
        (y, yl): (&[f64], &[Lanes<N>]),
        c0: usize,
        w: usize,
    ) {
        let (n, nk) = (self.n, self.n * self.k);
        if idx == self.s.len() {
            self.s.push(s);
            self.state.extend_from_slice(y);
            if c0 == 0 && w == self.k {
                for c in 0..w {
                    self.tangent.extend(yl.iter().map(|l| l.0[c]));
                }
                return;
            }
            self.tangent.resize(self.tangent.len() + nk, 0.0);
        }
        let t = &mut self.tangent[idx * nk..(idx + 1) * nk];
        for c in 0..w {
            let col = &mut t[(c0 + c) * n..(c0 + c + 1) * n];
            for (x, l) in col.iter_mut().zip(yl) {
                *x = l.0[c];
            }
        }
    }
    /// Record node `idx` of a pass over directions `c0 .. c0 + w`: the first
    /// pass appends the node, the others fill in their columns.
    #[inline(always)]
    pub(super) fn record<const N: usize>(
        &mut self,
        idx: usize,
        s: f64,
        y: &[Dual<N>],
        c0: usize,
        w: usize,
    ) {
        let (n, nk) = (self.n, self.n * self.k);
        if idx == self.s.len() {
            self.s.push(s);
            self.state.extend(y.iter().map(|d| d.re));
            self.tangent.resize(self.tangent.len() + nk, 0.0);
        }
        let t = &mut self.tangent[idx * nk..(idx + 1) * nk];
        for (r, d) in y.iter().enumerate() {
            for (c, e) in d.eps[..w].iter().enumerate() {
                t[(c0 + c) * n + r] = *e;
            }
        }
    }
}
