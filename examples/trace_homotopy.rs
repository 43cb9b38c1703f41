//! Trace of the cold homotopy of one benchmark design (diagnostics for the
//! continuation's step control): `cargo run --release --example
//! trace_homotopy -- INDEX`, the design's index in the set of
//! `tcarod::problems::random_design` (the default is a soft, heavily loaded
//! body whose homotopy path bends strongly). Follows the path accurately
//! (exact full-grid Newton, steps of 1/128), then, from points on it,
//! compares predictors (secant, quadratic through three points, tangent) at
//! several step lengths by the residual sequence of undamped exact Newton
//! from each. The quadratic predictor of `solve::continuation` rests on this
//! comparison (`docs/choices.md`, the solver's quadratic predictor).
use nalgebra::DVector;
use tcarod::problems::{random_design, Design, DEFAULT_SEED};
use tcarod::rod::Robot;
use tcarod::shooting::{reference_guess, Loads, Shooting, Shot};
use tcarod::solve::{continuation, NewtonOptions};

/// The homotopy problem at `lam` (the solver's own, loads scaled).
fn at(robot: &Robot, loads: &Loads, inputs: &[f64], lam: f64) -> (Robot, Vec<f64>, Loads) {
    continuation::at(robot, &robot.reference_inputs(), inputs, loads, true, lam)
}

fn norm(r: &[f64]) -> f64 {
    r.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Undamped exact Newton from `x`: the residual sequence (at most `n` steps).
fn newton(shot: &Shot, x: &[f64], n: usize, tol: f64) -> (Vec<f64>, Vec<f64>) {
    let mut x = x.to_vec();
    let mut seq = Vec::new();
    for _ in 0..n {
        let Ok((r, j, _, _)) = shot.jacobian(&x, false) else {
            seq.push(f64::NAN);
            break;
        };
        seq.push(norm(&r));
        if norm(&r) < tol {
            break;
        }
        let Some(d) = j.lu().solve(&(-DVector::from_vec(r))) else {
            break;
        };
        x.iter_mut().zip(d.iter()).for_each(|(a, b)| *a += b);
    }
    (x, seq)
}

/// The design's exact path: the unknowns at `lambda = k / n`, `k = 0..=n`
/// (full-grid Newton from a secant guess; the guess where it fails).
fn accurate_path(d: &Design, loads: &Loads, steps: usize, n: usize) -> Vec<Vec<f64>> {
    let mut path: Vec<Vec<f64>> = vec![reference_guess(&d.robot)];
    for k in 1..=n {
        let lam = k as f64 / n as f64;
        let (r, inp, l) = at(&d.robot, loads, &d.inputs, lam);
        let prev = path.last().unwrap();
        let guess: Vec<f64> = if k >= 2 {
            prev.iter()
                .zip(&path[k - 2])
                .map(|(a, b)| 2.0 * a - b)
                .collect()
        } else {
            prev.clone()
        };
        let mut sys = Shooting::new(&r, &inp, &l, steps, false);
        let o = NewtonOptions::new(1e-9, 60, 1e-8);
        let x = match tcarod::solve::newton(&mut sys, &guess, &o, "path") {
            Ok(nr) => nr.x,
            Err(e) => {
                println!("path inaccurate at lambda {lam}: {e}");
                let p = path.last().unwrap().clone();
                // keep going from the best we have: a looser tolerance, else the last point
                let mut sys = Shooting::new(&r, &inp, &l, steps, false);
                let o = NewtonOptions::new(1e-5, 60, 1e-8);
                match tcarod::solve::newton(&mut sys, &guess, &o, "path") {
                    Ok(nr) => nr.x,
                    Err(_) => p,
                }
            }
        };
        path.push(x);
    }
    path
}

/// The secant, quadratic and tangent predictors from `path[k]` (at
/// `lam`, Jacobian `j0` there) to `lam + dl`, `dl = m / n`.
fn predictors(
    d: &Design,
    loads: &Loads,
    steps: usize,
    path: &[Vec<f64>],
    j0: &nalgebra::DMatrix<f64>,
    (k, m, n): (usize, usize, usize),
) -> [(&'static str, Vec<f64>); 3] {
    let lam = k as f64 / n as f64;
    let dl = m as f64 / n as f64;
    let x = &path[k];
    let secant: Vec<f64> = if k >= m {
        x.iter()
            .zip(&path[k - m])
            .map(|(a, b)| 2.0 * a - b)
            .collect()
    } else {
        x.clone()
    };
    // tangent: dx/dl = -J^-1 dr/dl, dr/dl by a difference in lambda
    let eps = 1e-6;
    let (re, ie, le) = at(&d.robot, loads, &d.inputs, lam + eps);
    let r_e = Shot::new(&re, &ie, &le, steps)
        .residual(x, false)
        .unwrap()
        .0;
    let drl = DVector::from_vec(r_e) / eps;
    let t = j0.clone().lu().solve(&(-drl)).unwrap();
    let tangent: Vec<f64> = x.iter().zip(t.iter()).map(|(a, b)| a + dl * b).collect();
    let quad: Vec<f64> = if k >= 2 * m {
        x.iter()
            .zip(&path[k - m])
            .zip(&path[k - 2 * m])
            .map(|((a, b), c)| 3.0 * a - 3.0 * b + c)
            .collect()
    } else {
        x.clone()
    };
    [("secant", secant), ("quad", quad), ("tangent", tangent)]
}

/// Compare the predictors from `lambda = k / n` at steps `m / n` (m = 2, 4,
/// 8): their distance from the path and undamped Newton's residuals.
fn compare_at(d: &Design, loads: &Loads, steps: usize, path: &[Vec<f64>], k: usize, n: usize) {
    let lam = k as f64 / n as f64;
    let (r0, inp0, l0) = at(&d.robot, loads, &d.inputs, lam);
    let shot0 = Shot::new(&r0, &inp0, &l0, steps);
    let (_, j0, _, _) = shot0.jacobian(&path[k], false).unwrap();
    for &m in &[2usize, 4, 8] {
        if k + m > n {
            continue;
        }
        let dl = m as f64 / n as f64;
        let (r1, inp1, l1) = at(&d.robot, loads, &d.inputs, lam + dl);
        let shot1 = Shot::new(&r1, &inp1, &l1, steps);
        let exact = &path[k + m];
        for (name, p) in predictors(d, loads, steps, path, &j0, (k, m, n)) {
            let err: f64 = p
                .iter()
                .zip(exact)
                .fold(0.0, |s, (a, b)| s.max((a - b).abs()));
            let (_, seq) = newton(&shot1, &p, 8, 1e-10);
            println!(
                "lam {lam:.4} dl {dl:.4} {name:7} |x err| {err:.2e} newton [{}]",
                seq.iter()
                    .map(|v| format!("{v:.1e}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            );
        }
    }
}

fn main() {
    let idx: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(126);
    let d = random_design(DEFAULT_SEED, idx);
    let loads = Loads::of(&d.robot);
    let steps = 100;
    let n = 128;
    let path = accurate_path(&d, &loads, steps, n);
    println!("#{idx} {}", d.summary());
    for k in (0..=n).step_by(8) {
        let x = &path[k];
        println!(
            "lam {:.4} x [{}]",
            k as f64 / n as f64,
            x.iter()
                .map(|v| format!("{v:+.4}"))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    // predictors from lambda_k with steps dl = m/128
    for &k in &[32usize, 40, 64, 96, 112] {
        compare_at(&d, &loads, steps, &path, k, n);
    }
}
