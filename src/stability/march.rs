//! The stabilised march of the verdict's tangent pass: the tangent columns
//! re-orthonormalised at the nodes where they have grown apart (Ascher,
//! Mattheij & Russell, "Numerical Solution of Boundary Value Problems for
//! Ordinary Differential Equations", ch. 4).
//!
//! The verdict reads the span of the tangent columns, not the columns:
//! `K = Y H^-1` and the positive-definiteness test of `sym(H^T Y)` are
//! unchanged by `[H; Y] -> [H; Y] M` for any invertible `M`, and so is (S3)
//! once the actuator consistency rows are carried along (below). The
//! variational equations are linear in the perturbation, so continuing the
//! integration from the columns times `M` gives, at every later node, the
//! plain columns times `M` (to rounding).
//!
//! Each column is the whole perturbation of one direction: the state
//! tangent `d y` (made dimensionless: `p / L`, `q`, `v`, `u L`, `delta / L`)
//! and, when the actuator directions are integrated, the actuator part of
//! the direction itself, `P dz = d (delta_i / L)` (the unknowns do not
//! vary along `s`; the tension tangents are `d tau_i / d delta_i` times it,
//! so they follow). Keeping `P dz` in the column keeps it non-zero where a
//! constant tension gives the direction no state tangent at all, and is
//! what (S3) needs: with the true columns `T = T' C` (`T'` the carried ones,
//! `C` the product of the inverses of the matrices applied), the actuator
//! consistency `E z = 0`, `E = d delta(L) / L dz - P`, reads
//! `E' c = 0` for `z = C^-1 c` with `E' = d delta'(L) / L - P dz'`, so
//! (S3) is `Y' W (H' W)^-1` for any basis `W` of the null space of `E'`.

/// Bound on the spread of the tangent columns: the ratio of the largest to
/// the smallest norm after Gram-Schmidt (the diagonal of `R` in the QR of the
/// dimensionless columns), past which they are replaced by `Q`.
///
/// Rounding puts an error of `eps` relative to its own size in every column,
/// so the component of a column orthogonal to the others, `R_jj`, carries a
/// relative error of `eps max_i R_ii / R_jj`: bounding the spread by
/// `eps^-1/2` keeps that at `eps^1/2` (the accuracy of the forward-difference
/// tangents, [`super::stability_fd`], and below [`super::NEUTRAL`]) at the
/// cost of a re-orthonormalisation per `ln(eps^-1/2) = 18` e-folds of growth.
/// (A pass whose spread stays below it, as on every robot of the paper, is
/// never touched: the plain pass bit for bit.)
pub const GROWTH_BOUND: f64 = 67_108_864.0; // 2^26 = 1 / sqrt(2^-52)

/// The state of the march: what the hook of the tangent pass
/// ([`crate::rod::IvpSpec::integrate_tangent_hooked`]) needs between nodes.
pub(super) struct March {
    bound: f64,
    /// Directions.
    k: usize,
    /// Dimensionless scale of each state row.
    scale: Vec<f64>,
    /// `P dz'`: the actuator part of each carried column (`na x k`, by
    /// columns; `na = 0` when the actuator directions are not integrated).
    pub pdz: Vec<f64>,
    pub na: usize,
    /// `ln det C_6` at each node (`C`: the carried columns' factor to the
    /// true ones, upper triangular with a positive diagonal; `C_6` its
    /// leading 6 x 6 block, the frozen-tension columns').
    pub ldet: Vec<f64>,
    /// Re-orthonormalisations done.
    pub count: usize,
    /// Scratch: the dimensionless columns (`(n + na) x k`, by columns),
    /// `R` and the Gram matrix (`k x k`).
    a: Vec<f64>,
    r: Vec<f64>,
    g: Vec<f64>,
}

impl March {
    /// A march over `k` directions of a robot with `n` states (`n - 13`
    /// actuator elongations) and length `len`; `actuators`: whether the
    /// directions `6 ..` are the actuator unknowns.
    pub(super) fn new(bound: f64, n: usize, k: usize, len: f64, actuators: bool) -> Self {
        let na = if actuators { k - 6 } else { 0 };
        let scale: Vec<f64> = (0..n)
            .map(|r| match r {
                0..=2 => 1.0 / len,
                3..=9 => 1.0,
                10..=12 => len,
                _ => 1.0 / len,
            })
            .collect();
        let mut pdz = vec![0.0; na * k];
        for i in 0..na {
            pdz[(6 + i) * na + i] = 1.0;
        }
        March {
            bound,
            k,
            scale,
            pdz,
            na,
            ldet: Vec::new(),
            count: 0,
            a: vec![0.0; (n + na) * k],
            r: vec![0.0; k * k],
            g: vec![0.0; k * k],
        }
    }

    /// The hook at node `idx` with columns `cols` (`n x k`, by columns): if
    /// their spread passes the bound, `m = R^-1` of their QR (so that the
    /// carried columns become `Q`, orthonormal in the dimensionless metric)
    /// and true.
    pub(super) fn at_node(&mut self, idx: usize, cols: &[f64], m: &mut [f64]) -> bool {
        let (k, na) = (self.k, self.na);
        let n = self.scale.len();
        let rows = n + na;
        debug_assert_eq!(self.ldet.len(), idx);
        let last = self.ldet.last().copied().unwrap_or(0.0);
        for (a, c) in self.a.chunks_exact_mut(rows).zip(cols.chunks_exact(n)) {
            for ((x, y), s) in a.iter_mut().zip(c).zip(&self.scale) {
                *x = y * s;
            }
        }
        if na > 0 {
            for (a, p) in self.a.chunks_exact_mut(rows).zip(self.pdz.chunks_exact(na)) {
                a[n..].copy_from_slice(p);
            }
        }
        // the cheap screen; the decision is the Gram-Schmidt's below
        if spread(&self.a, rows, k, &mut self.g) <= self.bound / 16.0 {
            self.ldet.push(last);
            return false;
        }
        // modified Gram-Schmidt: a = Q R, Q over a's storage
        self.r.fill(0.0);
        let (mut big, mut small) = (0.0f64, f64::INFINITY);
        for j in 0..k {
            let (done, rest) = self.a.split_at_mut(j * rows);
            let v = &mut rest[..rows];
            for i in 0..j {
                let q = &done[i * rows..(i + 1) * rows];
                let d: f64 = q.iter().zip(v.iter()).map(|(a, b)| a * b).sum();
                for (x, qi) in v.iter_mut().zip(q) {
                    *x -= d * qi;
                }
                self.r[j * k + i] = d;
            }
            let nrm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            self.r[j * k + j] = nrm;
            big = big.max(nrm);
            small = small.min(nrm);
            if nrm > 0.0 {
                for x in v.iter_mut() {
                    *x /= nrm;
                }
            }
        }
        // a zero column (or a non-finite one) is left alone: the verdict
        // reports the degenerate tangents as it finds them
        if !(big / small > self.bound && small > 0.0 && big.is_finite()) {
            self.ldet.push(last);
            return false;
        }
        // m = R^-1 (upper triangular, by columns), column by column
        m[..k * k].fill(0.0);
        for c in 0..k {
            m[c * k + c] = 1.0 / self.r[c * k + c];
            for i in (0..c).rev() {
                let s: f64 = (i + 1..=c).map(|l| self.r[l * k + i] * m[c * k + l]).sum();
                m[c * k + i] = -s / self.r[i * k + i];
            }
        }
        // the carried actuator part follows the columns: P dz' m
        if na > 0 {
            let old = self.pdz.clone();
            for c in 0..k {
                for i in 0..na {
                    self.pdz[c * na + i] = (0..k).map(|j| old[j * na + i] * m[c * k + j]).sum();
                }
            }
        }
        // the first six columns (the base strains) span the frozen-tension
        // tangents and stay among themselves (m is upper triangular): the
        // scan's determinants are theirs, scaled by the leading 6 x 6
        // block of R
        let ld: f64 = (0..6).map(|j| self.r[j * k + j].ln()).sum();
        self.ldet.push(last + ld);
        self.count += 1;
        true
    }
}

/// The spread `max R_jj / min R_jj` of the `k` columns of `a` (`rows x k`,
/// by columns) from the pivots of their Gram matrix `A^T A = R^T R`
/// (`d_j = R_jj^2`; `g`: scratch, `k x k`): the screen run at every node,
/// so by dot products of the contiguous columns (four independent sums
/// each) and no square root but the last. The Gram matrix squares the
/// condition: its pivots carry a relative error of about `eps S^2` at a
/// spread `S`, `2^-8` at `S = GROWTH_BOUND / 16`, so below that screen
/// the estimate is good to a percent and the columns are certainly below
/// the bound; above it (where near the bound the estimate is coarse, and
/// past it the elimination may break down, read as infinite spread) the
/// Gram-Schmidt of [`March::at_node`] measures the spread itself and
/// decides.
fn spread(a: &[f64], rows: usize, k: usize, g: &mut [f64]) -> f64 {
    let col = |j: usize| &a[j * rows..(j + 1) * rows];
    for i in 0..k {
        for j in 0..=i {
            g[i * k + j] = dot(col(i), col(j));
        }
    }
    // Gaussian elimination of the symmetric G on its lower triangle: the
    // pivots are the d_j of G = L D L^T
    let (mut big, mut small) = (0.0f64, f64::INFINITY);
    for j in 0..k {
        let dj = g[j * k + j];
        if !(dj > 0.0 && dj.is_finite()) {
            return f64::INFINITY;
        }
        let inv = 1.0 / dj;
        for i in j + 1..k {
            let f = g[i * k + j] * inv;
            for l in j + 1..=i {
                g[i * k + l] -= f * g[l * k + j];
            }
        }
        big = big.max(dj);
        small = small.min(dj);
    }
    (big / small).sqrt()
}

/// `a . b` with four independent partial sums.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for l in 0..4 {
            s[l] += x[l] * y[l];
        }
    }
    (s[0] + s[1]) + (s[2] + s[3]) + tail
}
