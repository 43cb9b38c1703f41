//! Staircase (almost block diagonal) linear systems of multiple shooting:
//! storage, LU factorisation with row partial pivoting that keeps the block
//! structure, solves with the matrix and its transpose, and a 1-norm
//! condition estimate.
//!
//! # Structure
//! The unknowns are split into column blocks `z_0 .. z_{m-1}` of sizes
//! `c_k`, the equations into row blocks of sizes `r_k`. Row block `k` holds
//! `D_k` (`r_k x c_k`) on column block `k` and `E_k` (`r_k x c_{k+1}`) on
//! column block `k + 1` (none for the last row block); nothing else is
//! nonzero:
//! ```text
//! [ D_0  E_0                 ]
//! [      D_1  E_1            ]
//! [            ...   ...     ]
//! [                  D_{m-1} ]
//! ```
//! In multiple shooting (Ascher, Mattheij & Russell, *Numerical Solution of
//! Boundary Value Problems for ODEs*, SIAM 1995, ch. 4, "AMR") row block
//! `k < m-1` is the continuity defect `y_k(end; z_k) - z_{k+1}` (`D_k` the
//! segment's sensitivity matrix, `E_k` a padded `-I`) plus any side
//! conditions of that segment; the last row block holds the far boundary
//! conditions. Only the whole matrix is square. Row blocks `i..=k` meet only
//! column blocks `i..=k+1`; by Hall's theorem the matrix is structurally
//! nonsingular exactly when no such run has more rows than those columns.
//!
//! # Algorithm
//! Gaussian elimination with row partial pivoting, column by column as for a
//! dense matrix, with the pivot search and the updates restricted to the rows
//! that can be nonzero in the pivot column: the almost block diagonal
//! elimination of de Boor & Weiss ("SOLVEBLOK", ACM TOMS 6, 1980; AMR ch. 7).
//! Stage `k` eliminates the `c_k` columns of block `k` from the working
//! matrix `W_k = [S_k 0; D_k E_k]`, where the `s_k = (r_0 + .. + r_{k-1}) -
//! (c_0 + .. + c_{k-1})` rows of `S_k` are those not yet used as pivots; they
//! are zero outside column block `k`. After `c_k` pivots the `s_{k+1}` rows
//! left are zero in block `k` and form `S_{k+1}`: fill never leaves column
//! block `k + 1`. The rows skipped are structural zeros, so this *is* the
//! partial-pivoting LU `P A = L U` of the whole matrix, at the cost of the
//! blocks alone.
//!
//! Stability: the computed solution solves `(A + dA) x = b` with
//! `|dA| <= gamma_3n |L| |U|`, i.e. `|dA| ~ n u rho |A|` with growth factor
//! `rho` (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.,
//! SIAM 2002, ch. 9). Multipliers are bounded by one and each stage combines
//! rows of one segment with the rows carried from the previous one; no
//! products `D_{k+1} D_k` are formed, unlike condensation, whose `prod D_k`
//! has entries of size `e^{L |lambda|}` (single shooting's growth). So the
//! error is governed by the conditioning of the multiple-shooting matrix,
//! which a BVP with a dichotomy keeps moderate (AMR ch. 3, 6). Growth can
//! still accumulate along the staircase in principle: Wright ("A collection
//! of problems for which Gaussian elimination with partial pivoting is
//! unstable", SIAM J. Sci. Comput. 14, 1993) built such multiple-shooting
//! matrices, with non-separated boundary conditions (a border this structure
//! does not have). [`Staircase::factorise`] reports `rho` (as
//! `max |U| / max |A|`) and the smallest pivot so a caller can check. The
//! alternative with the same structure and cost is the alternate row and
//! column elimination of Varah (SIAM J. Numer. Anal. 13, 1976) and Diaz,
//! Fairweather & Keast (ACM TOMS 9, 1983).
//!
//! # Storage and solves
//! The matrix is kept block by block as given (for [`Staircase::mul`],
//! residuals and iterative refinement); the factors per stage in LAPACK
//! `getrf` layout: after elimination `W_k` holds `L` below and `U` on and
//! above the diagonal of its first `c_k` columns, `U_12` in the first `c_k`
//! rows of its last `c_{k+1}` columns, and `S_{k+1}` below. The factors
//! are a snapshot taken by [`Staircase::factorise`]: editing blocks
//! afterwards changes [`Staircase::mul`], not the solves (so a frozen
//! Jacobian can be reused). Solves run in place: stage `k` of the forward
//! substitution works on entries `c_0 + .. + c_{k-1}` onwards of the
//! right-hand side (`s_k` carried entries, then row block `k`) and leaves
//! the `c_k` entries of `L^{-1} P b` that back substitution overwrites with
//! `z_k`. Nothing is allocated after [`Staircase::new`] except by
//! [`Staircase::rcond_estimate`] and [`Staircase::to_dense`].

use nalgebra::{DMatrix, DMatrixViewMut, DVectorView, DVectorViewMut};

use crate::error::{Error, Result};

/// Sizes of a staircase system: `rows[k] = r_k`, `cols[k] = c_k`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Shape {
    /// Rows of each row block.
    pub rows: Vec<usize>,
    /// Columns of each column block.
    pub cols: Vec<usize>,
}

/// A pivot too small for the factorisation to go on: the matrix is singular
/// to working precision, or has a non-finite entry in that column.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("singular staircase matrix: pivot {pivot:.3e} in column {column} of scale {scale:.3e}")]
pub struct Singular {
    /// Global column index of the failed pivot.
    pub column: usize,
    /// The largest candidate pivot (exactly 0 for an exactly singular column).
    pub pivot: f64,
    /// The column's scale `max_i |a_ij|` in the matrix as given; NaN if the
    /// column has a non-finite entry.
    pub scale: f64,
}

/// Pivot statistics of a successful factorisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PivotReport {
    /// `min_j |u_jj| / max_i |a_ij|`: the smallest pivot relative to its
    /// column's scale, invariant under column scaling (units of the
    /// unknowns). Near `n eps` the matrix is singular to working precision.
    pub min_pivot_ratio: f64,
    /// Growth factor `max |u_ij| / max |a_ij|`; the backward error bound
    /// grows with it (module doc).
    pub growth: f64,
}

/// A staircase matrix, stored block by block, with its LU factors; reused
/// across factorisations of one shape with no allocation.
#[derive(Debug, Clone)]
pub struct Staircase {
    shape: Shape,
    /// `row_off[k] = r_0 + .. + r_{k-1}`, `k = 0..=m`.
    row_off: Vec<usize>,
    /// `col_off[k] = c_0 + .. + c_{k-1}`, `k = 0..=m`.
    col_off: Vec<usize>,
    /// Row block `k` as given, `[D_k E_k]`: `r_k x (c_k + c_{k+1})`.
    blocks: Vec<DMatrix<f64>>,
    /// Stage `k` of the factorisation: `(s_k + r_k) x (c_k + c_{k+1})`.
    stages: Vec<DMatrix<f64>>,
    /// At global column `j = col_off[k] + i`, local rows `i` and
    /// `pivots[j]` of stage `k` were swapped.
    pivots: Vec<usize>,
    /// `max_i |a_ij|` per column at the last factorisation (NaN if not finite).
    scale: Vec<f64>,
    /// `|A|_1` at the last factorisation.
    norm1: f64,
    factorised: bool,
}

impl Staircase {
    /// A zero matrix of the given shape. `Err(InvalidInput)` unless there
    /// are `m >= 1` row and column blocks, the matrix is square and nonempty,
    /// and no run of row blocks `i..=k` has more rows than the column blocks
    /// `i..=k+1` it meets have columns (structural singularity, module doc).
    pub fn new(shape: Shape) -> Result<Self> {
        let m = shape.rows.len();
        let offsets = |sizes: &[usize]| -> Vec<usize> {
            let mut off = vec![0];
            sizes.iter().for_each(|s| off.push(off[off.len() - 1] + s));
            off
        };
        let (row_off, col_off) = (offsets(&shape.rows), offsets(&shape.cols));
        let n = col_off[col_off.len() - 1];
        let fail = |reason: String| Err(Error::input("staircase shape", reason));
        if m == 0 || shape.cols.len() != m || n == 0 || row_off[m] != n {
            return fail(format!(
                "{shape:?}: need m >= 1 row and column blocks, sum r = sum c > 0"
            ));
        }
        for (i, k) in (0..m).flat_map(|i| (i..m).map(move |k| (i, k))) {
            let (rows, cols) = (
                row_off[k + 1] - row_off[i],
                col_off[(k + 2).min(m)] - col_off[i],
            );
            if rows > cols {
                return fail(format!(
                    "row blocks {i}..={k} have {rows} rows but meet {cols} columns: structurally singular"
                ));
            }
        }
        let width = |k: usize| shape.cols[k] + shape.cols.get(k + 1).copied().unwrap_or(0);
        let blocks = (0..m)
            .map(|k| DMatrix::zeros(shape.rows[k], width(k)))
            .collect();
        let stages = (0..m)
            .map(|k| DMatrix::zeros(row_off[k + 1] - col_off[k], width(k)))
            .collect();
        Ok(Self {
            shape,
            row_off,
            col_off,
            blocks,
            stages,
            pivots: vec![0; n],
            scale: vec![0.0; n],
            norm1: 0.0,
            factorised: false,
        })
    }

    /// The shape given to [`Staircase::new`].
    pub fn shape(&self) -> &Shape {
        &self.shape
    }

    /// Order `n` of the matrix.
    pub fn dim(&self) -> usize {
        self.pivots.len()
    }

    /// `D_k` (`r_k x c_k`), to fill. Panics if `k >= m`.
    pub fn d_mut(&mut self, k: usize) -> DMatrixViewMut<'_, f64> {
        let c = self.shape.cols[k];
        self.blocks[k].columns_mut(0, c)
    }

    /// `E_k` (`r_k x c_{k+1}`), to fill. Panics if `k + 1 >= m`.
    pub fn e_mut(&mut self, k: usize) -> DMatrixViewMut<'_, f64> {
        assert!(
            k + 1 < self.blocks.len(),
            "E_{k}: the last row block has no E"
        );
        let (c, w) = (self.shape.cols[k], self.shape.cols[k + 1]);
        self.blocks[k].columns_mut(c, w)
    }

    /// Set every block to zero (the factors stay those of the last
    /// [`Staircase::factorise`]).
    pub fn clear(&mut self) {
        self.blocks.iter_mut().for_each(|b| b.fill(0.0));
    }

    /// Whether the last [`Staircase::factorise`] succeeded.
    pub fn is_factorised(&self) -> bool {
        self.factorised
    }

    /// The matrix as given, assembled densely (allocates; for tests and
    /// diagnostics).
    pub fn to_dense(&self) -> DMatrix<f64> {
        let n = self.dim();
        let mut a = DMatrix::zeros(n, n);
        for (k, b) in self.blocks.iter().enumerate() {
            a.view_mut((self.row_off[k], self.col_off[k]), b.shape())
                .copy_from(b);
        }
        a
    }

    /// `out = A x` with the matrix as given (not the factors).
    /// `Err(InvalidInput)` if a slice is not of length `n`.
    pub fn mul(&self, x: &[f64], out: &mut [f64]) -> Result<()> {
        self.check_len("x", x.len())?;
        self.check_len("out", out.len())?;
        for (k, b) in self.blocks.iter().enumerate() {
            let (r, c) = (self.row_off[k], self.col_off[k]);
            let xk = DVectorView::from_slice(&x[c..c + b.ncols()], b.ncols());
            let mut yk = DVectorViewMut::from_slice(&mut out[r..r + b.nrows()], b.nrows());
            yk.gemv(1.0, b, &xk, 0.0);
        }
        Ok(())
    }

    /// `out = A^T y` with the matrix as given (not the factors).
    /// `Err(InvalidInput)` if a slice is not of length `n`.
    pub fn mul_transpose(&self, y: &[f64], out: &mut [f64]) -> Result<()> {
        self.check_len("y", y.len())?;
        self.check_len("out", out.len())?;
        out.fill(0.0);
        for (k, b) in self.blocks.iter().enumerate() {
            let (r, c) = (self.row_off[k], self.col_off[k]);
            let yk = DVectorView::from_slice(&y[r..r + b.nrows()], b.nrows());
            let mut xk = DVectorViewMut::from_slice(&mut out[c..c + b.ncols()], b.ncols());
            xk.gemv_tr(1.0, b, &yk, 1.0);
        }
        Ok(())
    }

    /// LU factorisation with row partial pivoting (module doc). Stops at the
    /// first column with a non-finite entry or whose largest candidate pivot
    /// is at most `n eps max_i |a_ij|` (its scale in the matrix as given),
    /// and returns it as [`Singular`]; the solves then refuse until a
    /// factorisation succeeds.
    pub fn factorise(&mut self) -> std::result::Result<PivotReport, Singular> {
        self.factorised = false;
        self.measure();
        let tol = self.dim() as f64 * f64::EPSILON;
        let (mut min_ratio, mut max_u) = (f64::INFINITY, 0.0_f64);
        for k in 0..self.blocks.len() {
            let (g, c) = (self.col_off[k], self.shape.cols[k]);
            let (done, rest) = self.stages.split_at_mut(k);
            let w = &mut rest[0];
            let prev = done.last().map(|p| (p, self.shape.cols[k - 1]));
            load_stage(w, prev, &self.blocks[k]);
            let (piv, scale) = (&mut self.pivots[g..g + c], &self.scale[g..g + c]);
            let ratio = eliminate(w, piv, scale, tol).map_err(|(j, pivot)| Singular {
                column: g + j,
                pivot,
                scale: scale[j],
            })?;
            min_ratio = min_ratio.min(ratio);
            for q in 0..w.ncols() {
                let u = &col(w, q)[..c.min(q + 1)];
                max_u = u.iter().fold(max_u, |a, u| a.max(u.abs()));
            }
        }
        self.factorised = true;
        let max_a = self.scale.iter().fold(0.0, |a: f64, &s| a.max(s));
        Ok(PivotReport {
            min_pivot_ratio: min_ratio,
            growth: max_u / max_a,
        })
    }

    /// `det A` of the last successful [`Staircase::factorise`] (`None`
    /// without factors): the product of the pivots `u_jj`, negated for each
    /// row swap (`P A = L U`, `det P = (-1)^swaps`). Its sign changes where
    /// an eigenvalue of `A` crosses zero, which continuation uses to detect
    /// bifurcations (Allgower & Georg, *Introduction to Numerical
    /// Continuation Methods*, SIAM 2003, sec. 8.1). The product is formed in
    /// `f64`; a matrix whose pivots lie far from one over hundreds of
    /// columns may over- or underflow it, its sign stays right.
    pub fn determinant(&self) -> Option<f64> {
        if !self.factorised {
            return None;
        }
        let mut det = 1.0;
        for (k, f) in self.stages.iter().enumerate() {
            let (g, c) = (self.col_off[k], self.shape.cols[k]);
            for (j, &p) in self.pivots[g..g + c].iter().enumerate() {
                det *= if p == j { f[(j, j)] } else { -f[(j, j)] };
            }
        }
        Some(det)
    }

    /// Solve `A x = b` in place (`b` becomes `x`) with the factors of the
    /// last successful [`Staircase::factorise`]; allocates nothing.
    /// `Err(InvalidInput)` if `b` is not of length `n` or there are no factors.
    pub fn solve(&self, b: &mut [f64]) -> Result<()> {
        self.check_solve(b.len())?;
        for (k, f) in self.stages.iter().enumerate() {
            let (g, c) = (self.col_off[k], self.shape.cols[k]);
            let w = &mut b[g..g + f.nrows()];
            for (j, &p) in self.pivots[g..g + c].iter().enumerate() {
                w.swap(j, p);
            }
            // w <- L^{-1} w, L unit lower trapezoidal (f.nrows() x c).
            for j in 0..c {
                let v = w[j];
                let l = &col(f, j)[j + 1..];
                w[j + 1..].iter_mut().zip(l).for_each(|(x, l)| *x -= l * v);
            }
        }
        for (k, f) in self.stages.iter().enumerate().rev() {
            let (g, c) = (self.col_off[k], self.shape.cols[k]);
            let (z, next) = b[g..].split_at_mut(c);
            // z <- U_11^{-1} (z - U_12 z_next).
            for (q, &v) in next[..f.ncols() - c].iter().enumerate() {
                z.iter_mut()
                    .zip(&col(f, c + q)[..c])
                    .for_each(|(x, u)| *x -= u * v);
            }
            for j in (0..c).rev() {
                let u = &col(f, j)[..=j];
                z[j] /= u[j];
                let v = z[j];
                z[..j]
                    .iter_mut()
                    .zip(&u[..j])
                    .for_each(|(x, u)| *x -= u * v);
            }
        }
        Ok(())
    }

    /// Solve `A^T x = b` in place with the factors of the last successful
    /// [`Staircase::factorise`]: `U^T w = b` block by block forwards, then
    /// `x = P^T L^{-T} w` stage by stage backwards; allocates nothing.
    /// `Err(InvalidInput)` if `b` is not of length `n` or there are no factors.
    pub fn solve_transpose(&self, b: &mut [f64]) -> Result<()> {
        self.check_solve(b.len())?;
        for (k, f) in self.stages.iter().enumerate() {
            let (g, c) = (self.col_off[k], self.shape.cols[k]);
            if k > 0 {
                // Subtract U_12^T (of stage k-1) w_{k-1}.
                let (fp, cp) = (&self.stages[k - 1], self.shape.cols[k - 1]);
                let (wp, w) = b[self.col_off[k - 1]..g + c].split_at_mut(cp);
                for (q, x) in w.iter_mut().enumerate() {
                    *x -= dot(&col(fp, cp + q)[..cp], wp);
                }
            }
            let w = &mut b[g..g + c];
            for j in 0..c {
                let u = &col(f, j)[..=j];
                w[j] = (w[j] - dot(&u[..j], &w[..j])) / u[j];
            }
        }
        for (k, f) in self.stages.iter().enumerate().rev() {
            let (g, c) = (self.col_off[k], self.shape.cols[k]);
            let w = &mut b[g..g + f.nrows()];
            for j in (0..c).rev() {
                let (head, tail) = w.split_at_mut(j + 1);
                head[j] -= dot(&col(f, j)[j + 1..], tail);
            }
            for (j, &p) in self.pivots[g..g + c].iter().enumerate().rev() {
                w.swap(j, p);
            }
        }
        Ok(())
    }

    /// Reciprocal 1-norm condition number `1 / (|A|_1 |A^{-1}|_1)` of the
    /// factorised matrix, with `|A^{-1}|_1` estimated from below by Hager's
    /// method (SIAM J. Sci. Stat. Comput. 5, 1984) and Higham's extra test
    /// vector (ACM TOMS 14, 1988; Higham 2002, ch. 15): a few solves with `A`
    /// and `A^T`. The estimate is rarely more than 3x low, so the result is
    /// an upper bound of `rcond`, usually within 3x. Allocates two vectors.
    /// `Err(InvalidInput)` if there are no factors.
    pub fn rcond_estimate(&self) -> Result<f64> {
        let n = self.dim();
        let nf = n as f64;
        let (mut y, mut z) = (vec![1.0 / nf; n], vec![0.0; n]);
        let norm1 = |v: &[f64]| v.iter().map(|a| a.abs()).sum::<f64>();
        let mut est = 0.0_f64;
        // Hager: maximise |A^{-1} x|_1 over |x|_1 = 1 by gradient steps,
        // from x = (1/n, .., 1/n), then at vertices x = e_j.
        let mut vertex: Option<usize> = None;
        for _ in 0..5 {
            self.solve(&mut y)?;
            est = est.max(norm1(&y));
            z.iter_mut()
                .zip(&y)
                .for_each(|(z, y)| *z = if *y >= 0.0 { 1.0 } else { -1.0 });
            self.solve_transpose(&mut z)?;
            let j = argmax_abs(&z);
            let z_dot_x = vertex.map_or(z.iter().sum::<f64>() / nf, |v| z[v]);
            if z[j].abs() <= z_dot_x || vertex == Some(j) {
                break;
            }
            vertex = Some(j);
            y.fill(0.0);
            y[j] = 1.0;
        }
        // Higham's x_i = (-1)^i (1 + i / (n-1)), against a stall at a local maximum.
        for (i, v) in y.iter_mut().enumerate() {
            *v = (1.0 + i as f64 / (nf - 1.0).max(1.0)) * if i % 2 == 0 { 1.0 } else { -1.0 };
        }
        self.solve(&mut y)?;
        est = est.max(2.0 * norm1(&y) / (3.0 * nf));
        let rcond = 1.0 / (self.norm1 * est);
        Ok(if rcond.is_finite() { rcond } else { 0.0 })
    }

    /// Column scales `max_i |a_ij|` (NaN where a column has a non-finite
    /// entry) and `|A|_1` of the blocks as given. Column block `k` meets row
    /// blocks `k-1` (through `E_{k-1}`) and `k` (through `D_k`).
    fn measure(&mut self) {
        self.norm1 = 0.0;
        for k in 0..self.blocks.len() {
            let c = self.shape.cols[k];
            for q in 0..c {
                let d = self.blocks[k].column(q);
                let e = k
                    .checked_sub(1)
                    .map(|p| self.blocks[p].column(self.shape.cols[p] + q));
                let (mut max, mut sum) = (0.0_f64, 0.0);
                for a in d.iter().chain(e.iter().flat_map(|e| e.iter())) {
                    max = if a.is_finite() && !max.is_nan() {
                        max.max(a.abs())
                    } else {
                        f64::NAN
                    };
                    sum += a.abs();
                }
                self.scale[self.col_off[k] + q] = max;
                self.norm1 = self.norm1.max(sum);
            }
        }
    }

    fn check_len(&self, name: &str, len: usize) -> Result<()> {
        if len == self.dim() {
            return Ok(());
        }
        Err(Error::input(
            name,
            format!(
                "length {len} for a staircase matrix of order {}",
                self.dim()
            ),
        ))
    }

    fn check_solve(&self, len: usize) -> Result<()> {
        self.check_len("b", len)?;
        if !self.factorised {
            return Err(Error::input(
                "staircase",
                "not factorised (or found singular)",
            ));
        }
        Ok(())
    }
}

/// Fill stage matrix `w = [S_k 0; D_k E_k]`; `S_k` is the trailing block of
/// the previous stage `prev` (given with its `c_{k-1}`) below its pivot rows.
fn load_stage(w: &mut DMatrix<f64>, prev: Option<(&DMatrix<f64>, usize)>, block: &DMatrix<f64>) {
    let s = w.nrows() - block.nrows();
    w.rows_mut(0, s).fill(0.0);
    if let Some((p, cp)) = prev {
        let carried = p.view((cp, cp), (s, p.ncols() - cp));
        w.view_mut((0, 0), carried.shape()).copy_from(&carried);
    }
    w.rows_mut(s, block.nrows()).copy_from(block);
}

/// Partial-pivoting LU of the first `piv.len()` columns of `w`, applying
/// the row operations to all its columns, in place (`getrf` layout);
/// `piv[j]` receives the row swapped with row `j`. Returns the smallest
/// `|pivot| / scale`, or the local column and largest candidate of the first
/// pivot not above `tol * scale` (NaN-safe: a NaN scale fails the test).
fn eliminate(
    w: &mut DMatrix<f64>,
    piv: &mut [usize],
    scale: &[f64],
    tol: f64,
) -> std::result::Result<f64, (usize, f64)> {
    let (h, ncols) = w.shape();
    let mut min_ratio = f64::INFINITY;
    for j in 0..piv.len() {
        let p = j + argmax_abs(&col(w, j)[j..]);
        let d = w[(p, j)];
        if !(d.abs() > tol * scale[j]) || !d.is_finite() {
            return Err((j, d));
        }
        min_ratio = min_ratio.min(d.abs() / scale[j]);
        piv[j] = p;
        w.swap_rows(j, p);
        let (left, right) = w.as_mut_slice().split_at_mut((j + 1) * h);
        let l = &mut left[j * h + j + 1..];
        l.iter_mut().for_each(|l| *l /= d);
        for q in 0..ncols - j - 1 {
            let a = &mut right[q * h + j..(q + 1) * h];
            let u = a[0];
            if u != 0.0 {
                a[1..].iter_mut().zip(&*l).for_each(|(a, l)| *a -= l * u);
            }
        }
    }
    Ok(min_ratio)
}

/// Column `j` of a column-major matrix.
fn col(f: &DMatrix<f64>, j: usize) -> &[f64] {
    let h = f.nrows();
    &f.as_slice()[j * h..(j + 1) * h]
}

/// Index of the first entry of largest modulus (0 for an empty slice).
fn argmax_abs(v: &[f64]) -> usize {
    (0..v.len()).fold(0, |a, i| if v[i].abs() > v[a].abs() { i } else { a })
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
#[path = "abd_tests.rs"]
mod tests;
