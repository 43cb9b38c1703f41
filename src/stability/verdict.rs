//! The verdict from the tangents: the frozen-tension scan along `s`
//! (determinant (S1), Dirichlet test, positive definiteness of (S2)) and the
//! margin at the tip ((S2), or (S3) restricted to the free directions).

use nalgebra::{DMatrix, DVector, Matrix6, SymmetricEigen, Vector3};

use super::tangents::{Cols6, Tangents};
use super::{Stability, NEUTRAL};

/// Smallest eigenvalue of the symmetric part of a square matrix and its unit
/// eigenvector.
fn min_sym_pair(k: &DMatrix<f64>) -> (f64, DVector<f64>) {
    let sym = (k + k.transpose()) * 0.5;
    let e = SymmetricEigen::new(sym);
    let i = e.eigenvalues.imin();
    (e.eigenvalues[i], e.eigenvectors.column(i).into_owned())
}

/// Result of the frozen-tension scan along `s`.
struct Scan {
    determinant: Vec<f64>,
    min_stiffness: Vec<f64>,
    /// First node where (S2) is not positive definite.
    conjugate: Option<f64>,
    /// First node where `det H` changes sign (Dirichlet conjugate point).
    dirichlet: Option<f64>,
}

/// A 6 x 6 matrix on the stack (by rows or by columns: the determinant is
/// the same).
type M6 = [[f64; 6]; 6];

/// The tangents' columns as a matrix.
fn matrix(c: &Cols6) -> Matrix6<f64> {
    Matrix6::from_fn(|i, j| c[j][i])
}

fn dot6(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5]
}

/// Determinant by Gaussian elimination with partial pivoting (as an LU
/// factorisation, on the stack). The row updates run over all six columns
/// (fixed-length loops the compiler vectorises): the entries left of the
/// pivot are never read again, and those right of it get the arithmetic of
/// the textbook loop, so the result is the same bit for bit.
fn det6(mut a: M6) -> f64 {
    let mut det = 1.0;
    for k in 0..6 {
        let mut p = k;
        for i in k + 1..6 {
            if a[i][k].abs() > a[p][k].abs() {
                p = i;
            }
        }
        if a[p][k] == 0.0 {
            return 0.0;
        }
        if p != k {
            a.swap(p, k);
            det = -det;
        }
        let pivot = a[k];
        det *= pivot[k];
        let inv = 1.0 / pivot[k];
        for row in &mut a[k + 1..] {
            let f = row[k] * inv;
            for (x, p) in row.iter_mut().zip(&pivot) {
                *x -= f * p;
            }
        }
    }
    det
}

/// The node's columns `[H; Y]` (twelve dimensionless rows) made orthonormal:
/// `[H; Y] = [H_q; Y_q] R` with `R` upper triangular and a positive
/// diagonal; `None` if a column vanishes (or is not finite) after the
/// projections, i.e. the columns are numerically dependent.
///
/// Each test of the verdict is invariant to `[H; Y] -> [H; Y] M` for an
/// invertible `M` (`K = Y H^-1`; `sym(H^T Y)` by congruence), but its
/// rounding is not: the entries of `H^T Y` are products of two columns, so
/// at a spread `S` of the columns (the ratio of the largest to the smallest
/// diagonal entry of `R`) the form's smallest pivots carry a relative
/// rounding error of about `eps S^2`. Under tension the columns grow apart
/// exponentially, and the march bounds their spread on the state tangents,
/// where a force enters through the strain `v`, a factor of up to
/// `EA L^2 / EI = 4 (L / r)^2` softer than in `Y`: between two
/// re-orthonormalisations the `[H; Y]` columns may spread by up to
/// `GROWTH_BOUND EA L^2 / EI`, far past `eps^-1/2`, where `eps S^2 > 1`
/// turns the test into a coin toss. Read through an orthonormal basis of the same span, the form
/// `sym(H_q^T Y_q) = H_q^T sym(K) H_q` is as well conditioned as `K`
/// itself allows (`H_q^T H_q + Y_q^T Y_q = I`): the Riccati variable is
/// read from the span as in the Riccati method (Ascher, Mattheij &
/// Russell, ch. 6), never from the raw columns.
///
/// Modified Gram-Schmidt, a column projected a second time where the first
/// projection cancelled more than `1 - 1/sqrt(2)` of its norm (the DGKS
/// criterion: Daniel, Gragg, Kaufman & Stewart, Math. Comp. 30, 1976;
/// "twice is enough": Giraud, Langou & Rozloznik, Comput. Math. Appl. 50,
/// 2005): the basis is orthonormal to a few `eps` for any numerically
/// independent columns,
/// and `[H; Y] + dA = [H_q; Y_q] R` with each column of `dA` a few `eps` of
/// its own column (Bjorck, *Numerical Methods for Least Squares Problems*,
/// SIAM 1996, 2.4), so the span is the one the columns carry.
fn orthonormal(h: &Cols6, y: &Cols6) -> Option<(Cols6, Cols6)> {
    let mut a: [[f64; 12]; 6] =
        std::array::from_fn(|j| std::array::from_fn(|i| if i < 6 { h[j][i] } else { y[j][i - 6] }));
    for j in 0..6 {
        let (done, rest) = a.split_at_mut(j);
        let v = &mut rest[0];
        let norm = |v: &[f64; 12]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut n = norm(v);
        for _ in 0..2 {
            for q in done.iter() {
                let d: f64 = q.iter().zip(v.iter()).map(|(a, b)| a * b).sum();
                for (x, qi) in v.iter_mut().zip(q) {
                    *x -= d * qi;
                }
            }
            let projected = norm(v);
            let cancelled = projected < std::f64::consts::FRAC_1_SQRT_2 * n;
            n = projected;
            if !cancelled {
                break;
            }
        }
        if !(n > 0.0 && n.is_finite()) {
            return None;
        }
        for x in v.iter_mut() {
            *x /= n;
        }
    }
    let hq = std::array::from_fn(|j| std::array::from_fn(|i| a[j][i]));
    let yq = std::array::from_fn(|j| std::array::from_fn(|i| a[j][6 + i]));
    Some((hq, yq))
}

/// True if `sym(H^T Y) + NEUTRAL H^T H` is positive definite (`LDL^T`,
/// stopped at the first non-positive pivot); with `H` invertible this is
/// `sym(K) + NEUTRAL I` for `K = Y H^-1` (S2), by congruence (`x = H z`): no
/// inverse needed, and a singular `H` fails it too. The columns are those of
/// [`orthonormal`] (any basis of the span gives the same answer; an
/// orthonormal one gives it without squaring the columns' spread).
/// `h`, `y` by columns: with `Y' = Y + NEUTRAL H` the matrix is
/// `sym(H^T Y')`, whose entry `(i, j)` is the mean of the dot products of
/// columns `h_i . y'_j` and `y'_i . h_j` (36 dot products of six).
fn positive_definite(h: &Cols6, y: &Cols6) -> bool {
    let yn: Cols6 = std::array::from_fn(|j| std::array::from_fn(|i| y[j][i] + NEUTRAL * h[j][i]));
    let mut a = [[0.0; 6]; 6];
    for i in 0..6 {
        a[i][i] = dot6(&h[i], &yn[i]);
        for j in 0..i {
            a[i][j] = 0.5 * (dot6(&h[i], &yn[j]) + dot6(&yn[i], &h[j]));
        }
    }
    // LDL^T in place, by columns, one division per column and no square
    // root: `a[i][k]` (k < i) becomes `c_ik = L_ik d_k`, and the matrix is
    // positive definite iff every pivot `d_j` is positive
    let mut inv = [0.0; 6];
    for j in 0..6 {
        let dj = a[j][j] - (0..j).map(|k| a[j][k] * a[j][k] * inv[k]).sum::<f64>();
        if !(dj > 0.0) {
            return false;
        }
        inv[j] = 1.0 / dj;
        for i in j + 1..6 {
            let x: f64 = (0..j).map(|k| a[i][k] * a[j][k] * inv[k]).sum();
            a[i][j] -= x;
        }
    }
    true
}

/// (S1) normalised at the base, the Dirichlet test (if `dirichlet`) and a
/// positive-definiteness test of the symmetric part of (S2) at every node (6 x 6
/// algebra on the stack).
fn scan(t: &Tangents, dirichlet: bool) -> Scan {
    let nodes = t.s.len();
    // det Y = det Y^T: the columns serve as rows
    let det0 = t.y.first().map_or(0.0, |y| det6(*y));
    let mut out = Scan {
        determinant: Vec::with_capacity(nodes),
        min_stiffness: Vec::with_capacity(nodes),
        conjugate: None,
        dirichlet: None,
    };
    let mut hdet_sign = 0.0;
    for (k, &sk) in t.s.iter().enumerate() {
        let y = &t.y[k];
        // det(Y(s) Y(0)^-1) = det Y(s) / det Y(0); the true Y is the
        // carried one times a factor of determinant exp(ldet) > 0
        let ld = t.ldet[k];
        out.determinant.push(if det0 == 0.0 {
            f64::NAN
        } else if ld == 0.0 {
            det6(*y) / det0
        } else {
            let d = det6(*y);
            d.signum() * (d.abs().ln() + ld - det0.abs().ln()).exp() * det0.signum()
        });
        if k == 0 || sk <= 0.0 {
            out.min_stiffness.push(f64::INFINITY);
            continue;
        }
        // the span of the node's columns through an orthonormal basis;
        // numerically dependent columns carry no span to test
        let Some((h, y)) = orthonormal(&t.h[k], y) else {
            out.conjugate.get_or_insert(sk);
            out.min_stiffness.push(-1.0);
            continue;
        };
        if dirichlet {
            // det H = det H_q det R, det R > 0
            let hd = det6(h);
            if hdet_sign == 0.0 {
                hdet_sign = hd.signum();
            } else if out.dirichlet.is_none() && hd * hdet_sign <= 0.0 {
                out.dirichlet = Some(sk);
            }
        }
        let pd = positive_definite(&h, &y);
        if out.conjugate.is_none() && !pd {
            out.conjugate = Some(sk);
        }
        out.min_stiffness.push(if pd { 1.0 } else { -1.0 });
    }
    out
}

/// The verdict from the tangents `t`: frozen tensions and a free tip
/// (`full = false`), or the tip stiffness (S3) with the actuator springs in,
/// restricted to the complement of `blocked`.
pub(super) fn verdict(
    t: Tangents,
    len: f64,
    blocked: &[Vector3<f64>],
    full: bool,
    evaluations: usize,
) -> Stability {
    let sc = scan(&t, full);
    let nodes = t.s.len();
    let last = nodes.saturating_sub(1);
    let mut out = Stability {
        stable: false,
        margin: f64::NEG_INFINITY,
        conjugate_point: sc.conjugate,
        s: Vec::new(),
        determinant: sc.determinant,
        min_stiffness: sc.min_stiffness,
        evaluations,
        mode: [0.0; 6],
    };
    // the frozen tip stiffness (S2) at s = L: its smallest eigenvalue is the
    // last node's min_stiffness and, without springs, the margin
    // (with springs the mode is (S3)'s: the eigenvalues only)
    // (from the orthonormal basis of the columns' span, as the scan)
    let tip = (nodes > 1)
        .then(|| orthonormal(&t.h[last], &t.y[last]))
        .flatten();
    if let Some((hq, yq)) = tip {
        if let Some(hi) = matrix(&hq).try_inverse() {
            let kk = matrix(&yq) * hi;
            let sym = (kk + kk.transpose()) * 0.5;
            if full {
                out.min_stiffness[last] = sym.symmetric_eigenvalues().min();
            } else {
                let e = SymmetricEigen::new(sym);
                let i = e.eigenvalues.imin();
                out.min_stiffness[last] = e.eigenvalues[i];
                out.mode
                    .copy_from_slice(e.eigenvectors.column(i).as_slice());
            }
        }
    }
    if !full {
        let m = out.min_stiffness[last];
        out.stable = sc.conjugate.is_none();
        out.margin = match sc.conjugate {
            Some(s) => m.min(-(len - s) / len),
            None => m,
        };
        out.s = t.s;
        return out;
    }
    out.mode = [0.0; 6];
    let tip = full_tip(&t, blocked);
    out.s = t.s;
    let Some((m, mode)) = tip else {
        return out;
    };
    out.mode = mode;
    out.margin = match sc.dirichlet {
        Some(sd) => m.min(-(len - sd) / len),
        None => m,
    };
    out.stable = sc.dirichlet.is_none() && out.margin > -NEUTRAL;
    out
}

/// Smallest eigenvalue and mode of (S3) restricted to tip variations
/// orthogonal to the `blocked` directions; `None` where undefined.
fn full_tip(t: &Tangents, blocked: &[Vector3<f64>]) -> Option<(f64, [f64; 6])> {
    let nz = t.y_tip.ncols();
    let na = nz - 6;
    // basis of the consistent z: d delta = -E_d^-1 E_x dx; of the carried
    // columns' coefficients c (E' c = 0, see `super::march`) once the
    // columns were re-orthonormalised
    let z = if na == 0 {
        DMatrix::identity(6, 6)
    } else if t.carried {
        null_basis(&t.e)?
    } else {
        let ex = t.e.columns(0, 6).into_owned();
        let edi = t.e.columns(6, na).into_owned().try_inverse()?;
        let mut z = DMatrix::zeros(nz, 6);
        z.view_mut((0, 0), (6, 6))
            .copy_from(&DMatrix::identity(6, 6));
        z.view_mut((6, 0), (na, 6)).copy_from(&(-edi * ex));
        z
    };
    // K_full from the orthonormal basis of the span of [H_z Z; Y_z Z], as
    // the scan reads (S2)
    let cols =
        |m: &DMatrix<f64>| -> Cols6 { std::array::from_fn(|j| std::array::from_fn(|i| m[(i, j)])) };
    let (hq, yq) = orthonormal(&cols(&(&t.h_tip * &z)), &cols(&(&t.y_tip * &z)))?;
    let hi = DMatrix::from_fn(6, 6, |i, j| hq[j][i]).try_inverse()?;
    let kfull = DMatrix::from_fn(6, 6, |i, j| yq[j][i]) * hi;
    let basis: Vec<DVector<f64>> = blocked
        .iter()
        .map(|b| {
            let mut v = DVector::zeros(6);
            v.rows_mut(0, 3).copy_from(&(b / b.norm()));
            v
        })
        .collect();
    let mut mode = [0.0; 6];
    if basis.is_empty() {
        // a free tip: (S3) itself (the complement's basis is the identity)
        let (m, v) = min_sym_pair(&kfull);
        mode.copy_from_slice(v.as_slice());
        return Some((m, mode));
    }
    let q = complement(&basis);
    let (m, v) = min_sym_pair(&(q.transpose() * kfull * &q));
    mode.copy_from_slice((&q * v).as_slice());
    Some((m, mode))
}

/// Orthonormal basis (columns) of the complement in R^6 of the span of `vs`.
fn complement(vs: &[DVector<f64>]) -> DMatrix<f64> {
    if vs.is_empty() {
        return DMatrix::identity(6, 6);
    }
    let a = DMatrix::from_columns(vs);
    let svd = a.svd(true, false);
    let Some(u) = svd.u else {
        return DMatrix::identity(6, 6);
    };
    let rank = svd.singular_values.iter().filter(|&&x| x > 1e-12).count();
    // complete the basis by Gram-Schmidt on the unit vectors
    let mut cols: Vec<DVector<f64>> = (0..rank).map(|j| u.column(j).into_owned()).collect();
    let mut out = Vec::new();
    for e in 0..6 {
        let mut v = DVector::zeros(6);
        v[e] = 1.0;
        for c in &cols {
            let d = c.dot(&v);
            v -= c * d;
        }
        let n = v.norm();
        if n > 1e-8 {
            v /= n;
            cols.push(v.clone());
            out.push(v);
        }
        if cols.len() == 6 {
            break;
        }
    }
    DMatrix::from_columns(&out)
}

/// Orthonormal basis (columns) of the null space of the `na x nz` matrix
/// `e` (`na < nz`), or `None` if `e` has not full row rank: its rows
/// orthonormalised, then completed by the unit vectors (each orthogonalised
/// twice against the basis so far, the best-kept first).
fn null_basis(e: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    let (na, nz) = e.shape();
    let scale = e.norm();
    if !(scale > 0.0 && scale.is_finite()) {
        return None;
    }
    let project = |v: &mut DVector<f64>, basis: &[DVector<f64>]| {
        for _ in 0..2 {
            for b in basis {
                let d = b.dot(v);
                *v -= b * d;
            }
        }
    };
    let mut rows: Vec<DVector<f64>> = Vec::with_capacity(nz);
    for i in 0..na {
        let mut v = e.row(i).transpose();
        let n0 = v.norm();
        project(&mut v, &rows);
        let n = v.norm();
        // a row (numerically) in the span of the others: E' is rank deficient
        if !(n > 1e-12 * n0.max(1e-300) && n > 1e-14 * scale) {
            return None;
        }
        rows.push(v / n);
    }
    // the unit vectors, those with the largest component off the row
    // space first
    let mut order: Vec<(usize, f64)> = (0..nz)
        .map(|i| {
            let mut v = DVector::zeros(nz);
            v[i] = 1.0;
            project(&mut v, &rows);
            (i, v.norm())
        })
        .collect();
    order.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut out: Vec<DVector<f64>> = Vec::with_capacity(nz - na);
    for (i, _) in order {
        if out.len() == nz - na {
            break;
        }
        let mut v = DVector::zeros(nz);
        v[i] = 1.0;
        project(&mut v, &rows);
        project(&mut v, &out);
        let n = v.norm();
        if n > 1e-8 {
            out.push(v / n);
        }
    }
    (out.len() == nz - na).then(|| DMatrix::from_columns(&out))
}
