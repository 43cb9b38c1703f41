//! Iterations, IVPs and wall time of cold (and warm) forward solves of the
//! tendon speed benchmarks (`experiments::steel_tendon_robot`,
//! `experiments::soft_tendon_robot`) and the Fig. 6 square: `cargo run
//! --release --example solver_counts` (`-- --compare`: thread-CPU medians
//! with and without the coarse-grid pre-solve, interleaved; `-- --batch-cold`: IVPs
//! and tips of one-row batches against single cold solves of benchmark
//! designs). (Wall time of one run each, median of 21: an indication only;
//! the criterion benches in benches/rod.rs are the timings.)
use std::time::Instant;

#[path = "../benches/clock/mod.rs"]
mod clock;

/// Thread CPU time [s] (Linux; the benches' clock).
fn thread_cpu() -> f64 {
    clock::thread_cpu().expect("thread CPU time needs 64-bit Linux")
}

/// Median thread-CPU time [s] of `f`, over `n` runs of 10 calls.
fn cpu_median(n: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..n)
        .map(|_| {
            let t0 = thread_cpu();
            for _ in 0..10 {
                f();
            }
            (thread_cpu() - t0) / 10.0
        })
        .collect();
    t.sort_by(|a, b| a.partial_cmp(b).unwrap());
    t[n / 2]
}

/// Thread-CPU medians of a solve with and without the coarse-grid pre-solve
/// (interleaved, 15 rounds of 10 solves each), in us and in plain-IVP times.
fn compare(name: &str, robot: &Robot, inputs: &[f64], warm: Option<&Solution>) {
    let [o, off] = [true, false].map(|presolve| SolveOptions {
        presolve,
        ..Default::default()
    });
    let l = tcarod::shooting::Loads::of(robot);
    let at = solve(robot, inputs, &o, None).unwrap();
    let (mut a, mut b, mut u) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..15 {
        a.push(cpu_median(1, || {
            drop(solve(robot, inputs, &o, warm).unwrap())
        }));
        b.push(cpu_median(1, || {
            drop(solve(robot, inputs, &off, warm).unwrap())
        }));
        u.push(cpu_median(1, || {
            drop(
                tcarod::shooting::Shot::new(robot, inputs, &l, 100)
                    .residual(&at.unknowns, false)
                    .unwrap(),
            )
        }));
    }
    for v in [&mut a, &mut b, &mut u] {
        v.sort_by(|x, y| x.partial_cmp(y).unwrap());
    }
    let (ea, eb) = (
        solve(robot, inputs, &o, warm).unwrap().evaluations,
        solve(robot, inputs, &off, warm).unwrap().evaluations,
    );
    println!(
        "{name:<28} thread CPU: pre-solve {:>6.1} us ({:.2} IVPs, {ea} evaluations), full-grid Newton {:>6.1} us ({:.2} IVPs, {eb} evaluations); one IVP {:.1} us",
        a[7] * 1e6,
        a[7] / u[7],
        b[7] * 1e6,
        b[7] / u[7],
        u[7] * 1e6
    );
}

use tcarod::experiments::{
    fig6_square, soft_tendon_robot, soft_tendon_tension, steel_tendon_robot, STEEL_TENDON_TENSIONS,
};
use tcarod::rod::Robot;
use tcarod::shooting::{solve, Solution, SolveOptions};

/// Median wall time [s] of one plain IVP of `robot` at its solution (the unit of "IVP-equivalents").
fn ivp_time(robot: &Robot, inputs: &[f64], steps: usize) -> f64 {
    let s = solve(
        robot,
        inputs,
        &SolveOptions {
            steps,
            ..Default::default()
        },
        None,
    )
    .unwrap();
    let l = tcarod::shooting::Loads::of(robot);
    let mut times: Vec<f64> = (0..21)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..20 {
                tcarod::shooting::Shot::new(robot, inputs, &l, steps)
                    .residual(std::hint::black_box(&s.unknowns), false)
                    .unwrap();
            }
            t.elapsed().as_secs_f64() / 20.0
        })
        .collect();
    times.sort_by(|a, b| a.partial_cmp(b).unwrap());
    times[10]
}

fn run(
    name: &str,
    robot: &Robot,
    inputs: &[f64],
    opts: &SolveOptions,
    warm: Option<&Solution>,
) -> Option<Solution> {
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..21 {
        let t = Instant::now();
        let r = solve(robot, inputs, opts, warm);
        times.push(t.elapsed().as_secs_f64());
        last = Some(r);
    }
    times.sort_by(|a, b| a.partial_cmp(b).unwrap());
    match last.unwrap() {
        Ok(s) => {
            let unit = ivp_time(robot, inputs, opts.steps);
            println!("{name:<28} iterations {:>4}  IVPs {:>5}  residual {:.2e}  {:>9.1} us = {:>6.1} IVP times  tip {:?}", s.iterations, s.evaluations, s.residual, times[10] * 1e6, times[10] / unit, s.tip_position().as_slice());
            Some(s)
        }
        Err(e) => {
            println!("{name:<28} FAILED: {e}  {:>9.1} us", times[10] * 1e6);
            None
        }
    }
}

/// `--compare`: the pre-solve against full-grid Newton, cold and warm, on
/// the Fig. 6 square and the steel tendon robot.
fn compare_all() {
    let sq = fig6_square(true);
    let o = SolveOptions::default();
    let s95 = solve(&sq, &[95.0, 95.0], &o, None).unwrap();
    compare("fig6 square 100 C cold", &sq, &[100.0, 100.0], None);
    compare(
        "fig6 square 100 C warm (95)",
        &sq,
        &[100.0, 100.0],
        Some(&s95),
    );
    let steel = steel_tendon_robot();
    let s0 = solve(&steel, &STEEL_TENDON_TENSIONS, &o, None).unwrap();
    let up: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|x| x * 1.01).collect();
    compare("steel tendon cold", &steel, &STEEL_TENDON_TENSIONS, None);
    compare("steel tendon warm +1 %", &steel, &up, Some(&s0));
}

/// The soft tendon rod at six tip angles and the steel robot, cold and warm.
fn tendon_cases() {
    let soft = soft_tendon_robot();
    let o50 = SolveOptions {
        steps: 50,
        ..Default::default()
    };
    for deg in [10.0f64, 30.0, 45.0, 60.0, 90.0, 120.0] {
        run(
            &format!("soft tendon {deg} deg cold"),
            &soft,
            &[soft_tendon_tension(deg.to_radians())],
            &o50,
            None,
        );
    }
    let steel = steel_tendon_robot();
    let o = SolveOptions::default();
    if let Some(s) = run(
        "steel tendon cold",
        &steel,
        &STEEL_TENDON_TENSIONS,
        &o,
        None,
    ) {
        let t: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|x| x * 1.01).collect();
        run("steel tendon warm +1 %", &steel, &t, &o, Some(&s));
    }
}

/// The Fig. 6 square cold and warm; then J and C, exact and the paper's
/// forward differences, in IVP times.
fn fig6_cases() {
    let sq = fig6_square(true);
    let o = SolveOptions::default();
    let Some(s) = run("fig6 square 100 C cold", &sq, &[100.0, 100.0], &o, None) else {
        return;
    };
    run("fig6 square warm 105 C", &sq, &[105.0, 105.0], &o, Some(&s));
    use tcarod::inverse::{sensitivities, sensitivities_fast, Groups, Scheme};
    let l = tcarod::shooting::Loads::of(&sq);
    let g = Groups(vec![0, 0]);
    let unit = ivp_time(&sq, &[100.0, 100.0], 100);
    for (name, exact) in [("J and C exact", true), ("J and C forward (fast)", false)] {
        let mut times: Vec<f64> = (0..21)
            .map(|_| {
                let t = Instant::now();
                if exact {
                    sensitivities(&sq, &s, &l, &g, 100, Scheme::Exact).unwrap();
                } else {
                    sensitivities_fast(&sq, &s, &l, &g, 100, Scheme::Forward).unwrap();
                }
                t.elapsed().as_secs_f64()
            })
            .collect();
        times.sort_by(|a, b| a.partial_cmp(b).unwrap());
        println!(
            "{name:<28} {:>9.1} us = {:>6.1} IVP times (one IVP {:.1} us)",
            times[10] * 1e6,
            times[10] / unit,
            unit * 1e6
        );
    }
}

/// Table I grasp temperature (1 g, 8 eq-43 increments), in IVP times of the finger.
fn grasp_case() {
    use tcarod::experiments::{
        table1_finger, G0, TABLE1_FINGERS, TABLE1_MASSES, TABLE1_MU, TABLE1_NORMAL,
    };
    use tcarod::inverse::{grasp, Groups};
    let finger = table1_finger();
    let normal = nalgebra::Vector3::from(TABLE1_NORMAL);
    let g = Groups(vec![0, 0]);
    let o = SolveOptions::default();
    let run_grasp = || {
        grasp(
            &finger,
            &g,
            &normal,
            TABLE1_MASSES[0],
            TABLE1_MU,
            TABLE1_FINGERS,
            G0,
            8,
            &o,
        )
    };
    let mut times: Vec<f64> = (0..11)
        .map(|_| {
            let t = Instant::now();
            run_grasp().unwrap();
            t.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let r = run_grasp().unwrap();
    let unit = ivp_time(&finger, &finger.reference_inputs(), 100);
    println!(
        "{:<28} {:>9.1} us = {:>6.1} IVP times (one IVP {:.1} us), IVPs {}, temperature {:.9} C",
        "grasp 1 g",
        times[5] * 1e6,
        times[5] / unit,
        unit * 1e6,
        r.evaluations,
        r.variables[0]
    );
}

/// Cold batch rows against single cold solves on benchmark designs (a few
/// whose cold solves are among the costliest of the set, each reported,
/// then the first 100 in total): IVPs and tip distance.
fn batch_cold() {
    use tcarod::batch::{solve_batch, BatchOptions};
    use tcarod::problems::{random_design, DEFAULT_SEED};
    let bo = BatchOptions {
        threads: 1,
        stability: false,
        ..BatchOptions::default()
    };
    let o = SolveOptions::default();
    let (mut single, mut rows, mut gap, mut worse) = (0, 0, 0.0f64, 0);
    let named = [385, 273, 25, 499, 126, 830, 552, 282];
    for i in named.into_iter().chain(0..100) {
        let d = random_design(DEFAULT_SEED, i);
        let s = solve(&d.robot, &d.inputs, &o, None);
        let b = solve_batch(&d.robot, &d.inputs, None, &bo);
        let (Ok(s), Ok(b)) = (s, b) else {
            println!("#{i}: a solve failed");
            continue;
        };
        let t = s.tip_position();
        let g = (0..3).fold(0.0f64, |m, k| m.max((b.tip_positions[0][k] - t[k]).abs()));
        let e = b.evaluations[0] as usize;
        if named.contains(&i) {
            println!(
                "#{i}: single cold {} IVPs, batch row {} IVPs (converged {}), tip gap {g:.1e} m",
                s.evaluations, e, b.converged[0]
            );
        } else {
            single += s.evaluations;
            rows += e;
            gap = gap.max(g);
            worse += usize::from(e > s.evaluations);
        }
    }
    println!("designs 0-99: single cold {single} IVPs, batch rows {rows} IVPs ({worse} rows more than single), tip gap max {gap:.1e} m");
}

/// `--loop fig6|steel N`: N cold solves and nothing else (for `perf record`).
fn cold_loop(which: &str, n: usize) {
    if which == "designs" {
        use tcarod::problems::{random_design, DEFAULT_SEED};
        let o = SolveOptions::default();
        let mut ivps = 0;
        for i in 0..n {
            let d = random_design(DEFAULT_SEED, i);
            ivps += solve(&d.robot, &d.inputs, &o, None).map_or(0, |s| s.evaluations);
        }
        println!("designs 0-{}: {ivps} IVPs", n - 1);
        return;
    }
    let (robot, inputs) = match which {
        "steel" => (steel_tendon_robot(), STEEL_TENDON_TENSIONS.to_vec()),
        _ => (fig6_square(true), vec![100.0, 100.0]),
    };
    let o = SolveOptions::default();
    for _ in 0..n {
        drop(std::hint::black_box(
            solve(&robot, &inputs, &o, None).unwrap(),
        ));
    }
}

/// `--parts`: thread-CPU medians of the IVPs a cold solve is made of
/// (plain on 10, 20, 30, 100 steps, recorded on 100 with `RodState` nodes,
/// recorded and assembled into a `Solution` as a solve's last IVP, tangent
/// on 10), in plain full-grid IVP times.
fn parts() {
    let cases = [
        ("fig6", fig6_square(true), vec![100.0, 100.0]),
        (
            "steel",
            steel_tendon_robot(),
            STEEL_TENDON_TENSIONS.to_vec(),
        ),
    ];
    for (name, robot, inputs) in cases {
        let s = solve(&robot, &inputs, &SolveOptions::default(), None).unwrap();
        let l = tcarod::shooting::Loads::of(&robot);
        let shot = |n| tcarod::shooting::Shot::new(&robot, &inputs, &l, n);
        let x = &s.unknowns;
        let t = |f: &dyn Fn()| cpu_median(21, f);
        let unit = t(&|| drop(shot(100).residual(x, false).unwrap()));
        let mut line = format!("{name:<6} one IVP {:.1} us:", unit * 1e6);
        for n in [10, 20, 30] {
            let c = t(&|| drop(shot(n).residual(x, false).unwrap()));
            line += &format!(" plain {n} {:.3}", c / unit);
        }
        let c = t(&|| drop(shot(100).residual(x, true).unwrap()));
        line += &format!(" recorded 100 {:.3}", c / unit);
        // the solve's own recorded IVP: nodes flat, then the Solution
        let c = t(&|| drop(tcarod::shooting::assemble(&robot, &inputs, &l, x, 100, 0, 0).unwrap()));
        line += &format!(" assembled 100 {:.3}", c / unit);
        let c = t(&|| drop(shot(10).jacobian(x, false).unwrap()));
        line += &format!(" tangent 10 {:.3}", c / unit);
        let c = t(&|| drop(solve(&robot, &inputs, &SolveOptions::default(), None).unwrap()));
        println!("{line} cold solve {:.3}", c / unit);
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.iter().any(|a| a == "--parts") {
        parts();
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--loop") {
        let which = args.get(i + 1).map_or("fig6", String::as_str);
        let n = args.get(i + 2).and_then(|a| a.parse().ok()).unwrap_or(2000);
        cold_loop(which, n);
        return;
    }
    if std::env::args().any(|a| a == "--batch-cold") {
        batch_cold();
        return;
    }
    if std::env::args().any(|a| a == "--compare") {
        compare_all();
        return;
    }
    tendon_cases();
    fig6_cases();
    grasp_case();
}
