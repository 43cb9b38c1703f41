//! Warm forward solves of the speed benchmarks, counted: `cargo run
//! --release --example warm_counts` prints, for the Fig. 6 square warm 5 C
//! away and the steel tendon robot warm after +1 % tension, the IVPs
//! (full-grid and coarse) and iterations of the warm solve, the distance of
//! its start from the converged unknowns and the converged result's
//! difference from the cold solve's. `-- --time`: interleaved thread-CPU
//! medians of the warm solve and of one plain full-grid IVP. `-- --batch`:
//! one-thread batch sweeps (Fig. 6 every 1 C and 5 C, steel every 1 %),
//! IVPs and thread CPU a warm row (`--rows`: each row's IVPs too), and
//! the same rows as `sweep` and `sweep_checked` (the verdict's `report`
//! policy, Python's `Robot.sweep`): IVPs a warm row and thread CPU a row.
use tcarod::experiments::{fig6_square, steel_tendon_robot, STEEL_TENDON_TENSIONS};
use tcarod::rod::Robot;
use tcarod::shooting::{initial_guess, solve, Loads, Shot, Solution, SolveOptions};

#[path = "../benches/clock/mod.rs"]
mod clock;

/// Thread CPU time [s] (Linux; the benches' clock).
fn thread_cpu() -> f64 {
    clock::thread_cpu().expect("thread CPU time needs 64-bit Linux")
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Counts of one warm solve from `warm` to `inputs`.
fn counts(name: &str, robot: &Robot, inputs: &[f64], warm: &Solution) {
    let o = SolveOptions::default();
    let cold = solve(robot, inputs, &o, None).unwrap();
    let hot = solve(robot, inputs, &o, Some(warm)).unwrap();
    let plain = initial_guess(robot, inputs, Some(warm));
    let pred = tcarod::solve::predict::predicted_guess(robot, inputs, warm);
    let l = Loads::of(robot);
    let res = |x: &[f64]| {
        let (r, _, _) = Shot::new(robot, inputs, &l, o.steps)
            .residual(x, false)
            .unwrap();
        r.iter().fold(0.0f64, |m, v| m.max(v.abs()))
    };
    println!(
        "{name:<26} warm: {} evaluations, {} iterations (cold {} / {}); start |x - x*| keep-tension {:.2e} (residual {:.2e}), predicted {:.2e} (residual {:.2e}); warm - cold: unknowns {:.1e}, tip {:.1e} m",
        hot.evaluations,
        hot.iterations,
        cold.evaluations,
        cold.iterations,
        max_abs_diff(&plain, &cold.unknowns),
        res(&plain),
        max_abs_diff(&pred, &cold.unknowns),
        res(&pred),
        max_abs_diff(&hot.unknowns, &cold.unknowns),
        (hot.tip_position() - cold.tip_position()).norm(),
    );
}

/// Interleaved thread-CPU medians (15 rounds of 10 calls) of the warm
/// solve and of one plain full-grid IVP at the solution.
fn time(name: &str, robot: &Robot, inputs: &[f64], warm: &Solution) {
    let o = SolveOptions::default();
    let l = Loads::of(robot);
    let at = solve(robot, inputs, &o, None).unwrap();
    let med = |f: &mut dyn FnMut()| {
        let t0 = thread_cpu();
        for _ in 0..10 {
            f();
        }
        (thread_cpu() - t0) / 10.0
    };
    let (mut a, mut u, mut g, mut s) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for _ in 0..15 {
        s.push(med(&mut || {
            drop(
                tcarod::shooting::assemble(robot, inputs, &l, &at.unknowns, o.steps, 0, 0).unwrap(),
            )
        }));
        a.push(med(&mut || {
            drop(solve(robot, inputs, &o, Some(warm)).unwrap())
        }));
        g.push(med(&mut || {
            drop(tcarod::solve::predict::predicted_guess(robot, inputs, warm))
        }));
        u.push(med(&mut || {
            drop(
                Shot::new(robot, inputs, &l, o.steps)
                    .residual(&at.unknowns, false)
                    .unwrap(),
            )
        }));
    }
    for v in [&mut a, &mut u, &mut g, &mut s] {
        v.sort_by(|x, y| x.partial_cmp(y).unwrap());
    }
    println!(
        "{name:<26} thread CPU: warm {:>6.1} us = {:.2} IVPs (its guess {:.1} us); one IVP {:.1} us, assembled {:.1} us",
        a[7] * 1e6,
        a[7] / u[7],
        g[7] * 1e6,
        u[7] * 1e6,
        s[7] * 1e6
    );
}

/// The coarse grid's defect `r_full - r_coarse` at the neighbour's solution
/// and at the new one, and how far it moves between them.
fn defects(name: &str, robot: &Robot, p_w: &[f64], p: &[f64]) {
    let o = SolveOptions::default();
    let l = Loads::of(robot);
    let w = solve(robot, p_w, &o, None).unwrap();
    let s = solve(robot, p, &o, None).unwrap();
    let r =
        |q: &[f64], x: &[f64], n: usize| Shot::new(robot, q, &l, n).residual(x, false).unwrap().0;
    let sub = |a: &[f64], b: &[f64]| -> Vec<f64> { a.iter().zip(b).map(|(x, y)| x - y).collect() };
    let nrm = |a: &[f64]| a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let dw = sub(&r(p_w, &w.unknowns, 100), &r(p_w, &w.unknowns, 10));
    let ds = sub(&r(p, &s.unknowns, 100), &r(p, &s.unknowns, 10));
    let rich = |q: &[f64], x: &[f64], a: usize, b: usize| -> Vec<f64> {
        let f = ((b / a) as f64).powi(4);
        sub(&r(q, x, b), &r(q, x, a))
            .iter()
            .map(|v| v * f / (f - 1.0))
            .collect()
    };
    let dd = sub(&ds, &dw);
    for (a, b) in [(10, 20), (20, 40), (25, 50)] {
        let da = sub(
            &sub(&r(p, &s.unknowns, 100), &r(p, &s.unknowns, a)),
            &sub(&r(p_w, &w.unknowns, 100), &r(p_w, &w.unknowns, a)),
        );
        let est = sub(&rich(p, &s.unknowns, a, b), &rich(p_w, &w.unknowns, a, b));
        println!(
            "  {name}: coarse {a}: defect variation {:.2e}, Richardson {a}/{b} error {:.2e}",
            nrm(&da),
            nrm(&sub(&da, &est))
        );
    }
    println!(
        "{name:<26} defect |d_w| {:.2e}, |d*| {:.2e}, |d* - d_w| {:.2e}; |x* - x_w| {:.2e}; floor {:.2e}",
        nrm(&dw), nrm(&ds), nrm(&dd), max_abs_diff(&s.unknowns, &w.unknowns), s.floor
    );
}

/// Batch rows along a sweep (one thread, no verdicts): IVPs a row after the
/// first, thread CPU a row, and the largest tip distance from cold solves.
fn batch(name: &str, robot: &Robot, rows: &[Vec<f64>]) {
    use tcarod::batch::{solve_batch, BatchOptions};
    let opts = BatchOptions {
        threads: 1,
        stability: false,
        ..BatchOptions::default()
    };
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    let out = solve_batch(robot, &flat, None, &opts).unwrap();
    if std::env::var("TCAROD_TRACE_WARM").is_ok() {
        return;
    }
    // one plain full-grid IVP at the middle row's solution, timed between
    // the batch runs: the row cost in IVP times is comparable across loads
    let mid = rows.len() / 2;
    let o = SolveOptions::default();
    let at = solve(robot, &rows[mid], &o, None).unwrap();
    let l = Loads::of(robot);
    let (mut times, mut ivp) = (Vec::new(), Vec::new());
    for _ in 0..7 {
        let t0 = thread_cpu();
        drop(solve_batch(robot, &flat, None, &opts).unwrap());
        times.push((thread_cpu() - t0) / rows.len() as f64);
        let t0 = thread_cpu();
        for _ in 0..20 {
            drop(
                Shot::new(robot, &rows[mid], &l, o.steps)
                    .residual(&at.unknowns, false)
                    .unwrap(),
            );
        }
        ivp.push((thread_cpu() - t0) / 20.0);
    }
    times.sort_by(|x, y| x.partial_cmp(y).unwrap());
    ivp.sort_by(|x, y| x.partial_cmp(y).unwrap());
    let mut gap = 0.0f64;
    for (q, tip) in rows.iter().zip(&out.tip_positions) {
        let cold = solve(robot, q, &SolveOptions::default(), None).unwrap();
        let t = cold.tip_position();
        gap = gap.max((0..3).fold(0.0f64, |m, k| m.max((tip[k] - t[k]).abs())));
    }
    let ivps: u32 = out.evaluations.iter().skip(1).sum();
    if std::env::args().any(|a| a == "--rows") {
        println!("{name}: IVPs a row {:?}", out.evaluations);
    }
    println!(
        "{name:<24} batch of {} rows: {} converged, {:.2} IVPs a warm row, {:.1} us a row = {:.2} IVP times; tips - cold {:.1e} m",
        rows.len(),
        out.converged.iter().filter(|c| **c).count(),
        f64::from(ivps) / (rows.len() - 1) as f64,
        times[3] * 1e6,
        times[3] / ivp[3],
        gap
    );
}

/// The rows of [`batch`] as `sweep` and as `sweep_checked` under the
/// `report` policy (Python's `Robot.sweep`), each beside the same rows
/// chained through single warm solves (`solve`, `solve_checked`: the
/// single solves' chord policy), interleaved: IVPs a warm row, thread CPU
/// a row (median of 7) in IVP times, and the largest tip distance.
fn sweeps(name: &str, robot: &Robot, rows: &[Vec<f64>]) {
    use tcarod::stability::{solve_checked, sweep_checked, Checked, Policy};
    let o = SolveOptions::default();
    let l = Loads::of(robot);
    let chained = || {
        let mut out: Vec<Solution> = Vec::new();
        for q in rows {
            let s = solve(robot, q, &o, out.last()).unwrap();
            out.push(s);
        }
        out
    };
    let chained_checked = || {
        let mut out: Vec<Checked> = Vec::new();
        for q in rows {
            let w = out.last().map(|c| &c.solution);
            out.push(solve_checked(robot, q, &l, &o, w, Policy::Report).unwrap());
        }
        out.into_iter().map(|c| c.solution).collect::<Vec<_>>()
    };
    let swept = || tcarod::shooting::sweep(robot, rows, &o).unwrap();
    let swept_checked = || {
        let c = sweep_checked(robot, rows, &o, Policy::Report).unwrap();
        c.into_iter().map(|c| c.solution).collect::<Vec<_>>()
    };
    let runs: [(&str, &dyn Fn() -> Vec<Solution>); 4] = [
        ("solve chained", &chained),
        ("sweep", &swept),
        ("solve_checked chained", &chained_checked),
        ("sweep_checked", &swept_checked),
    ];
    let first: Vec<Vec<Solution>> = runs.iter().map(|(_, f)| f()).collect();
    let mid = rows.len() / 2;
    let mut t = vec![Vec::new(); runs.len() + 1];
    for _ in 0..7 {
        for (k, (_, f)) in runs.iter().enumerate() {
            let t0 = thread_cpu();
            drop(f());
            t[k].push((thread_cpu() - t0) / rows.len() as f64);
        }
        let t0 = thread_cpu();
        for _ in 0..20 {
            drop(
                Shot::new(robot, &rows[mid], &l, o.steps)
                    .residual(&first[0][mid].unknowns, false)
                    .unwrap(),
            );
        }
        t[runs.len()].push((thread_cpu() - t0) / 20.0);
    }
    for v in &mut t {
        v.sort_by(|x, y| x.partial_cmp(y).unwrap());
    }
    let ivp = t[runs.len()][3];
    for (k, (what, _)) in runs.iter().enumerate() {
        let ivps: usize = first[k].iter().skip(1).map(|s| s.evaluations).sum();
        let gap = first[k].iter().zip(&first[0]).fold(0.0f64, |m, (a, b)| {
            m.max((a.tip_position() - b.tip_position()).abs().max())
        });
        if std::env::args().any(|a| a == "--rows") {
            let e: Vec<usize> = first[k].iter().map(|s| s.evaluations).collect();
            println!("{name}: {what}: IVPs a row {e:?}");
        }
        println!(
            "{name:<24} {what:<22} {:.2} IVPs a warm row, {:.2} IVP times a row (one IVP {:.1} us); tips - chained solves {gap:.1e} m",
            ivps as f64 / (rows.len() - 1) as f64,
            t[k][3] / ivp,
            ivp * 1e6,
        );
    }
}

fn main() {
    let o = SolveOptions::default();
    let sq = fig6_square(true);
    let s95 = solve(&sq, &[95.0, 95.0], &o, None).unwrap();
    let steel = steel_tendon_robot();
    let s0 = solve(&steel, &STEEL_TENDON_TENSIONS, &o, None).unwrap();
    let up: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|x| x * 1.01).collect();
    let timed = std::env::args().any(|a| a == "--time");
    if std::env::args().any(|a| a == "--batch") {
        for step in [1.0, 5.0] {
            let n = (135.0 / step) as usize;
            let rows: Vec<Vec<f64>> = (0..=n).map(|k| vec![25.0 + step * k as f64; 2]).collect();
            batch(&format!("fig6 square every {step} C"), &sq, &rows);
            sweeps(&format!("fig6 square every {step} C"), &sq, &rows);
        }
        let rows: Vec<Vec<f64>> = (0..=50)
            .map(|k| {
                STEEL_TENDON_TENSIONS
                    .iter()
                    .map(|t| t * (1.0 + 0.01 * k as f64))
                    .collect()
            })
            .collect();
        batch("steel tendon every 1 %", &steel, &rows);
        sweeps("steel tendon every 1 %", &steel, &rows);
        return;
    }
    if std::env::args().any(|a| a == "--defect") {
        defects(
            "fig6 square 100 C (95)",
            &sq,
            &[95.0, 95.0],
            &[100.0, 100.0],
        );
        defects("steel tendon +1 %", &steel, &STEEL_TENDON_TENSIONS, &up);
        return;
    }
    if std::env::args().any(|a| a == "--assemble") {
        // a loop for a profiler: assembling the Fig. 6 solution
        let l = Loads::of(&sq);
        for _ in 0..20000 {
            drop(
                tcarod::shooting::assemble(&sq, &[95.0, 95.0], &l, &s95.unknowns, 100, 0, 0)
                    .unwrap(),
            );
        }
        return;
    }
    if std::env::args().any(|a| a == "--sweep-loop") {
        // a loop for a profiler: Fig. 6 every 1 C under the report policy
        let rows: Vec<Vec<f64>> = (0..=135).map(|k| vec![25.0 + k as f64; 2]).collect();
        for _ in 0..40 {
            drop(
                tcarod::stability::sweep_checked(&sq, &rows, &o, tcarod::stability::Policy::Report)
                    .unwrap(),
            );
        }
        return;
    }
    if std::env::args().any(|a| a == "--warm-loop") {
        // a loop for a profiler: the Fig. 6 warm solve
        for _ in 0..5000 {
            drop(solve(&sq, &[100.0, 100.0], &o, Some(&s95)).unwrap());
        }
        return;
    }
    for (name, robot, inputs, warm) in [
        ("fig6 square 100 C (95)", &sq, &[100.0, 100.0][..], &s95),
        ("steel tendon +1 %", &steel, &up[..], &s0),
    ] {
        if timed {
            time(name, robot, inputs, warm);
        } else {
            counts(name, robot, inputs, warm);
        }
    }
}
