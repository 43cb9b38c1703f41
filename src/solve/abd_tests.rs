//! Tests of [`super`].

use super::*;
use nalgebra::{DVector, Matrix2, Vector2};

const EPS: f64 = f64::EPSILON;

/// xorshift64*: deterministic test data without a dev-dependency.
struct Rng(u64);

impl Rng {
    /// Uniform in [-1, 1).
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn below(&mut self, n: usize) -> usize {
        ((self.uniform() + 1.0) * 0.5 * n as f64) as usize % n
    }

    fn vec(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.uniform()).collect()
    }
}

fn staircase(rows: &[usize], cols: &[usize]) -> Staircase {
    Staircase::new(Shape {
        rows: rows.to_vec(),
        cols: cols.to_vec(),
    })
    .unwrap()
}

/// A random staircase matrix and the same matrix assembled densely here,
/// independently of `to_dense`: entries uniform in [-1, 1), each column
/// then scaled by `10^(3u)`, `u` uniform in [-1, 1) (unknowns in units
/// six decades apart; row pivoting does not see column scaling).
fn random_pair(rows: &[usize], cols: &[usize], rng: &mut Rng) -> (Staircase, DMatrix<f64>) {
    let mut a = staircase(rows, cols);
    let n = a.dim();
    let mut dense = DMatrix::zeros(n, n);
    for k in 0..rows.len() {
        let (r, c) = (a.row_off[k], a.col_off[k]);
        let width = cols[k] + cols.get(k + 1).copied().unwrap_or(0);
        dense
            .view_mut((r, c), (rows[k], width))
            .iter_mut()
            .for_each(|v| *v = rng.uniform());
    }
    for mut column in dense.column_iter_mut() {
        column *= 10f64.powf(3.0 * rng.uniform());
    }
    for k in 0..rows.len() {
        let (r, c) = (a.row_off[k], a.col_off[k]);
        a.d_mut(k)
            .copy_from(&dense.view((r, c), (rows[k], cols[k])));
        if k + 1 < rows.len() {
            a.e_mut(k)
                .copy_from(&dense.view((r, c + cols[k]), (rows[k], cols[k + 1])));
        }
    }
    (a, dense)
}

/// `m` blocks, `c_0 = 7`, `c_k` in 6..=20, `s_k` in 0..=3 carried rows
/// (`r_k = c_k + s_{k+1} - s_k`): rectangular blocks throughout.
fn random_shape(m: usize, rng: &mut Rng) -> (Vec<usize>, Vec<usize>) {
    let cols: Vec<usize> = (0..m)
        .map(|k| if k == 0 { 7 } else { 6 + rng.below(15) })
        .collect();
    let s: Vec<usize> = (0..=m)
        .map(|k| if k == 0 || k == m { 0 } else { rng.below(4) })
        .collect();
    ((0..m).map(|k| cols[k] + s[k + 1] - s[k]).collect(), cols)
}

/// `|A x - b| / | |A| |x| |` (inf-norm). GEPP keeps it at `~ n u rho`
/// (`|A x - b| <= gamma_3n |L| |U| |x|`, Higham 2002, ch. 9); unlike
/// `|A| |x|` with matrix norms it does not depend on column scaling.
fn rel_residual(a: &DMatrix<f64>, x: &[f64], b: &[f64]) -> f64 {
    let (x, b) = (DVector::from_column_slice(x), DVector::from_column_slice(b));
    (a * &x - b).amax() / (a.abs() * x.abs()).amax()
}

/// Random systems of several shapes (one with empty blocks), both
/// orientations, beside nalgebra's dense LU of the same matrix. In
/// practice GEPP's residual is a small multiple of `u` (observed <= 2 eps
/// for both solvers here); 16 eps leaves margin yet catches any error in
/// the structured elimination (a wrong pivot row or a lost update gives
/// O(1)). `mul` and `mul_transpose` agree with dense products within
/// twice the rounding bound `gamma_46 |A| |x|` of sums of <= 46 products
/// (Higham 2002, ch. 3), i.e. `100 eps |A| |x|`.
#[test]
fn random_staircases_solve_like_dense_lu() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let shapes = [
        (vec![12], vec![12]),
        (vec![20, 7], vec![7, 20]),
        (
            vec![20, 20, 20, 20, 20, 20, 7],
            vec![7, 20, 20, 20, 20, 20, 20],
        ),
        (
            vec![21, 20, 19, 21, 20, 6, 7],
            vec![7, 20, 20, 20, 20, 20, 7],
        ),
        (vec![2, 2, 0, 2], vec![2, 0, 2, 2]),
        random_shape(30, &mut rng),
    ];
    for (rows, cols) in &shapes {
        for _ in 0..2 {
            let (mut a, dense) = random_pair(rows, cols, &mut rng);
            assert_eq!(a.to_dense(), dense);
            a.factorise().unwrap();
            let (n, at) = (a.dim(), dense.transpose());
            let b = rng.vec(n);
            let (mut x, mut xt) = (b.clone(), b.clone());
            a.solve(&mut x).unwrap();
            a.solve_transpose(&mut xt).unwrap();
            let bv = DVector::from_column_slice(&b);
            let x_lu = dense.clone().lu().solve(&bv).unwrap();
            let xt_lu = at.clone().lu().solve(&bv).unwrap();
            let lu = [
                rel_residual(&dense, x_lu.as_slice(), &b),
                rel_residual(&at, xt_lu.as_slice(), &b),
            ];
            let ours = [rel_residual(&dense, &x, &b), rel_residual(&at, &xt, &b)];
            assert!(
                lu.iter().chain(&ours).all(|r| *r < 16.0 * EPS),
                "{rows:?} {cols:?}: {ours:?}, dense {lu:?}"
            );
            let (mut ax, mut aty) = (vec![0.0; n], vec![0.0; n]);
            a.mul(&x, &mut ax).unwrap();
            a.mul_transpose(&xt, &mut aty).unwrap();
            for (m, v, out) in [(&dense, &x, &ax), (&at, &xt, &aty)] {
                let v = DVector::from_column_slice(v);
                let err = DVector::from_column_slice(out) - m * &v;
                let bound = m.abs() * v.abs() * (100.0 * EPS);
                assert!(err.iter().zip(bound.iter()).all(|(e, b)| e.abs() <= *b));
            }
        }
    }
}

/// Propagator of `(y, y')` for `y'' = lambda y` over a step `h`.
fn propagator(lambda: f64, h: f64) -> Matrix2<f64> {
    let w = lambda.abs().sqrt();
    if lambda >= 0.0 {
        let (ch, sh) = ((w * h).cosh(), (w * h).sinh());
        Matrix2::new(ch, sh / w, w * sh, ch)
    } else {
        let (c, s) = ((w * h).cos(), (w * h).sin());
        Matrix2::new(c, s / w, -w * s, c)
    }
}

/// Multiple shooting for `y'' = lambda y`, `y(0) = y0`, `y(1) = y1` on
/// `m` equal segments, unknowns `z_k = (y, y')(t_k)`: row block 0 is the
/// left condition and continuity `Phi z_0 - z_1 = 0`, blocks 1..m-2
/// continuity, block m-1 the right condition `e_1^T Phi z_{m-1} = y1`.
fn shooting_system(lambda: f64, m: usize, y0: f64, y1: f64) -> (Staircase, Vec<f64>) {
    let mut rows = vec![2; m];
    (rows[0], rows[m - 1]) = (3, 1);
    let mut a = staircase(&rows, &vec![2; m]);
    let phi = propagator(lambda, 1.0 / m as f64);
    for (k, &r) in rows.iter().enumerate() {
        let top = usize::from(k == 0);
        a.d_mut(k)[(0, 0)] = 1.0; // the left condition; overwritten by Phi for k > 0
        a.d_mut(k)
            .rows_mut(top, r - top)
            .copy_from(&phi.rows(0, r - top));
        if k + 1 < m {
            a.e_mut(k).rows_mut(top, 2).fill_with_identity();
            a.e_mut(k).neg_mut();
        }
    }
    let mut b = vec![0.0; 2 * m];
    (b[0], b[2 * m - 1]) = (y0, y1);
    (a, b)
}

/// `y'' = 1600 y` (modes `e^{+-40 t}`), `y(0) = 1`, `y(1) = 2`, 20
/// segments of growth `e^2`. The multiple-shooting matrix has
/// `kappa_1 ~ 7e3` (from `rcond_estimate`, next test), so the bound
/// `kappa n u` is ~ 3e-11; observed 3e-16, asserted 1e-12. Single
/// shooting, condensed to the 2x2 system in `z_0` with `Phi^20` (entries
/// `~ e^40 / 2 ~ 1e17`), gets `z_0` to working precision, but the states
/// recovered from it carry that error times `e^40`: observed 2.4 relative,
/// asserted > 1e-2.
#[test]
fn multiple_shooting_is_accurate_where_single_shooting_fails() {
    let (mu, m) = (40.0_f64, 20);
    let (mut a, mut z) = shooting_system(mu * mu, m, 1.0, 2.0);
    a.factorise().unwrap();
    a.solve(&mut z).unwrap();
    let exact: Vec<f64> = (0..m)
        .flat_map(|k| {
            let (t, s) = (k as f64 / m as f64, mu.sinh());
            let (u, v) = (mu * (1.0 - t), mu * t);
            [
                (u.sinh() + 2.0 * v.sinh()) / s,
                mu * (2.0 * v.cosh() - u.cosh()) / s,
            ]
        })
        .collect();
    let size = exact.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let err = |z: &[f64]| {
        z.iter()
            .zip(&exact)
            .fold(0.0_f64, |a, (x, e)| a.max((x - e).abs()))
            / size
    };
    assert!(err(&z) < 1e-12, "multiple shooting error {:e}", err(&z));

    let phi = propagator(mu * mu, 1.0 / m as f64);
    let total = (1..m).fold(phi, |p, _| phi * p);
    let single = Matrix2::new(1.0, 0.0, total[(0, 0)], total[(0, 1)]);
    let mut zk = single.lu().solve(&Vector2::new(1.0, 2.0)).unwrap();
    let mut states = Vec::new();
    for _ in 0..m {
        states.extend_from_slice(zk.as_slice());
        zk = phi * zk;
    }
    assert!(
        err(&states) > 1e-2,
        "single shooting error {:e}",
        err(&states)
    );
}

/// The Hager-Higham estimate of `|A^{-1}|_1` is a lower bound (it is
/// `|A^{-1} x|_1` for some `|x|_1 = 1`) and rarely more than 3x low
/// (Higham 2002, ch. 15): `rcond <= estimate <= 10 rcond` against the
/// exact inverse (observed exact to 1e-14 here).
#[test]
fn rcond_estimate_brackets_the_exact_value() {
    let mut rng = Rng(5);
    let norm1 = |x: &DMatrix<f64>| x.column_iter().map(|c| c.abs().sum()).fold(0.0, f64::max);
    let (shooting, _) = shooting_system(1600.0, 20, 1.0, 2.0);
    let shapes = [
        random_shape(1, &mut rng),
        random_shape(3, &mut rng),
        random_shape(8, &mut rng),
    ];
    let mut cases: Vec<_> = shapes
        .iter()
        .map(|(r, c)| random_pair(r, c, &mut rng).0)
        .collect();
    cases.push(shooting);
    for mut a in cases {
        a.factorise().unwrap();
        let est = a.rcond_estimate().unwrap();
        let dense = a.to_dense();
        let exact = 1.0 / (norm1(&dense) * norm1(&dense.clone().try_inverse().unwrap()));
        assert!(
            exact <= est * (1.0 + 1e-10) && est <= 10.0 * exact,
            "est {est:e}, exact {exact:e}"
        );
    }
}

/// A zero leading entry (no pivot without a row swap) and a 1e-20 one (a
/// multiplier of 1e20 without a swap, which would lose `x` entirely).
/// The matrix has `kappa ~ 10`, so the error bound is ~ 10 n eps < 1e-14.
#[test]
fn row_pivoting_handles_zero_and_tiny_leading_entries() {
    for lead in [0.0, 1e-20] {
        let mut a = staircase(&[3, 1], &[2, 2]);
        a.d_mut(0).copy_from(&DMatrix::from_row_slice(
            3,
            2,
            &[lead, 2.0, 1.0, 0.0, 3.0, 1.0],
        ));
        a.e_mut(0).copy_from(&DMatrix::from_row_slice(
            3,
            2,
            &[1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        ));
        a.d_mut(1)
            .copy_from(&DMatrix::from_row_slice(1, 2, &[1.0, 1.0]));
        let x_true = [1.0, 2.0, 3.0, 4.0];
        let mut b = vec![0.0; 4];
        a.mul(&x_true, &mut b).unwrap();
        a.factorise().unwrap();
        assert_ne!(a.pivots[0], 0, "the first pivot must come from another row");
        a.solve(&mut b).unwrap();
        let err = b
            .iter()
            .zip(&x_true)
            .fold(0.0_f64, |e, (x, t)| e.max((x - t).abs()));
        assert!(err < 1e-14, "leading entry {lead:e}: error {err:e}");
    }
}

/// Singular matrices are reported and the solves then refuse, leaving
/// `b` as it was rather than NaN: an exactly zero column (pivot exactly
/// 0), the shooting matrix of `y'' = -pi^2 y`, `y(0) = y(1) = 0`
/// (singular since `sin(pi t)` solves it: linearised Euler buckling),
/// whose last pivot is rounding noise (observed 0.3 eps, below the
/// `n eps = 20 eps` threshold), and a NaN entry.
#[test]
fn singular_matrices_are_reported() {
    let (mut a, _) = random_pair(&[8, 6, 4], &[5, 6, 7], &mut Rng(7));
    a.d_mut(1).column_mut(2).fill(0.0);
    a.e_mut(0).column_mut(2).fill(0.0);
    let s = a.factorise().unwrap_err();
    assert_eq!((s.column, s.pivot, s.scale), (7, 0.0, 0.0));
    let mut b = vec![1.0; a.dim()];
    assert!(a.solve(&mut b).is_err() && a.solve_transpose(&mut b).is_err());
    assert!(b.iter().all(|&v| v == 1.0) && !a.is_factorised());

    let (mut a, _) = shooting_system(-std::f64::consts::PI.powi(2), 10, 0.0, 0.0);
    let s = a.factorise().unwrap_err();
    assert!(
        s.column == 19 && s.pivot.abs() <= 20.0 * EPS * s.scale,
        "{s}"
    );
    assert!(a.rcond_estimate().is_err());

    a.e_mut(3)[(1, 0)] = f64::NAN;
    let s = a.factorise().unwrap_err();
    assert!(s.column == 8 && s.scale.is_nan(), "{s}");
}

/// One block: the same algorithm as nalgebra's dense LU, so the two
/// solutions agree within the forward error bound `kappa 4 n eps` of two
/// backward-stable solves.
#[test]
fn single_block_equals_dense_lu() {
    let mut rng = Rng(11);
    let (mut a, dense) = random_pair(&[15], &[15], &mut rng);
    let b = rng.vec(15);
    let report = a.factorise().unwrap();
    assert!(report.min_pivot_ratio > 15.0 * EPS && report.growth >= 1.0);
    let mut x = b.clone();
    a.solve(&mut x).unwrap();
    let x_lu = dense
        .clone()
        .lu()
        .solve(&DVector::from_column_slice(&b))
        .unwrap();
    let sv = dense.singular_values();
    let kappa = sv.max() / sv.min();
    let diff = (DVector::from_column_slice(&x) - &x_lu).amax() / x_lu.amax();
    assert!(
        diff <= kappa * 4.0 * 15.0 * EPS,
        "difference {diff:e}, kappa {kappa:e}"
    );
}

/// One staircase refactorised and solved 1,000 times with changing
/// entries: the factor storage is never reallocated and every solve
/// keeps the residual of the random tests (16 eps).
#[test]
fn reuse_without_reallocation() {
    let mut rng = Rng(3);
    let (mut a, mut dense) = random_pair(&[6, 6, 6, 6, 4], &[4, 6, 6, 6, 6], &mut rng);
    let ptr = a.stages[2].as_ptr();
    for i in 0..1000 {
        let v = (i as f64 * 0.37).sin();
        a.d_mut(2)[(1, 3)] = v;
        dense[(13, 13)] = v;
        a.factorise().unwrap();
        let b = rng.vec(28);
        let mut x = b.clone();
        a.solve(&mut x).unwrap();
        assert!(rel_residual(&dense, &x, &b) < 16.0 * EPS);
    }
    assert_eq!(ptr, a.stages[2].as_ptr());
}

#[test]
fn invalid_shapes_and_lengths_are_rejected() {
    let bad = [
        (vec![], vec![]),
        (vec![3], vec![2, 1]),
        (vec![0], vec![0]),
        (vec![2, 4], vec![3, 3]),
    ];
    let more = [
        (vec![5, 1, 0], vec![1, 3, 2]),
        (vec![3, 0, 3], vec![2, 2, 2]),
    ];
    for (rows, cols) in bad.into_iter().chain(more) {
        let shape = Shape { rows, cols };
        assert!(
            matches!(
                Staircase::new(shape.clone()),
                Err(Error::InvalidInput { .. })
            ),
            "{shape:?}"
        );
    }
    let mut a = staircase(&[4, 2], &[3, 3]);
    assert!(a.mul(&[0.0; 5], &mut [0.0; 6]).is_err());
    assert!(a.mul_transpose(&[0.0; 6], &mut [0.0; 7]).is_err());
    assert!(a.solve(&mut [0.0; 6]).is_err(), "not factorised");
    a.d_mut(0).fill_with_identity();
    a.e_mut(0)[(3, 0)] = 1.0;
    a.d_mut(1).copy_from(&DMatrix::from_row_slice(
        2,
        3,
        &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
    ));
    assert!(a.factorise().is_ok());
    assert!(a.solve(&mut [0.0; 5]).is_err() && a.solve(&mut [0.0; 6]).is_ok());
    fn send_sync<T: Send + Sync>() {}
    send_sync::<Staircase>();
}

/// The determinant from the staircase factors equals nalgebra's dense LU
/// determinant: the same pivots up to the order of elimination, so the two
/// agree within `n eps kappa`-sized rounding of the product (`1e-10`
/// relative leaves room for `kappa ~ 1e4` on these 27-column matrices);
/// its sign flips with a swap of two columns inside one block.
#[test]
fn determinant_equals_dense() {
    let mut rng = Rng(17);
    for (rows, cols) in [(vec![7, 20], vec![7, 20]), (vec![20, 7], vec![7, 20])] {
        let (mut a, dense) = random_pair(&rows, &cols, &mut rng);
        assert_eq!(a.determinant(), None);
        a.factorise().unwrap();
        let (ours, exact) = (a.determinant().unwrap(), dense.clone().determinant());
        assert!(
            (ours - exact).abs() <= 1e-10 * exact.abs(),
            "{ours:e} vs {exact:e}"
        );
        // columns 0 and 1 of block 0 swapped: the determinant changes sign
        let mut d0 = a.d_mut(0).clone_owned();
        d0.swap_columns(0, 1);
        a.d_mut(0).copy_from(&d0);
        a.factorise().unwrap();
        let swapped = a.determinant().unwrap();
        assert!((swapped + ours).abs() <= 1e-10 * ours.abs(), "{swapped:e}");
    }
}
