//! Benches of the stability verdict: a warm solve of the Fig. 6
//! square at 100 C without the verdict (`Policy::Off`) and with it
//! (`Policy::Report`, the default), the verdict alone, and the tangent IVP
//! it must not exceed (the solver's exact Jacobian on the full grid, no
//! nodes recorded). `cargo bench --bench stability`.
//!
//! First an interleaved run (each round times every contender once, by
//! thread CPU time; medians over the rounds) prints the cost target's
//! ratio `(report - off) / tangent IVP` (set `TCAROD_ROUNDS`, default 300)
//! and the same as one `JSON ` line; then the work of `stability="continue"`
//! on an upright round column past its self-weight buckling load (IVPs and
//! thread CPU in plain IVPs, against the budget of 10 IVPs per unit of the
//! load factor); then criterion (wall clock).
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use tcarod::experiments::fig6_square;
use tcarod::rod::Robot;
use tcarod::shooting::{solve, Loads, Shot, Solution, SolveOptions};
use tcarod::stability::{solve_checked, stability, Policy};

#[path = "clock/mod.rs"]
mod clock;
use clock::thread_cpu;

/// The contenders, each a closure run once per round.
type Contender<'a> = (&'static str, Box<dyn Fn() + 'a>);

fn contenders<'a>(
    robot: &'a Robot,
    sol: &'a Solution,
    warm: &'a Solution,
    opts: &'a SolveOptions,
    loads: &'a Loads,
) -> Vec<Contender<'a>> {
    let q = [100.0, 100.0];
    let solve_with = move |policy| {
        black_box(solve_checked(robot, &q, loads, opts, Some(warm), policy).unwrap());
    };
    let base: Vec<Contender<'a>> = vec![
        ("solve_off", Box::new(move || solve_with(Policy::Off))),
        ("solve_report", Box::new(move || solve_with(Policy::Report))),
        (
            "verdict",
            Box::new(move || {
                black_box(stability(robot, sol, &[]).unwrap());
            }),
        ),
        (
            "tangent_ivp",
            Box::new(move || {
                let (x, st) = (&sol.unknowns, sol.steps);
                black_box(
                    Shot::new(robot, &sol.inputs, loads, st)
                        .jacobian(x, false)
                        .unwrap(),
                );
            }),
        ),
        (
            "plain_ivp",
            Box::new(move || {
                let (x, st) = (&sol.unknowns, sol.steps);
                black_box(
                    Shot::new(robot, &sol.inputs, loads, st)
                        .residual(x, false)
                        .unwrap(),
                );
            }),
        ),
    ];
    base.into_iter().chain(widths(robot, sol, loads)).collect()
}

/// Tangent passes (`integrate_tangent`, no residual assembled) of 4, 6 and
/// 8 directions, and of 8 with every node recorded (what the verdict
/// integrates): the cost of a direction. 6 directions run in the 8-wide
/// dual, so they cost what 8 do; the verdict needs 6 along `s` and all
/// `6 + N` at the tip, so its pass cannot be cheaper than the Jacobian's.
fn widths<'a>(robot: &'a Robot, sol: &'a Solution, loads: &'a Loads) -> Vec<Contender<'a>> {
    use tcarod::rod::{integrate_tangent, Record, TangentSeeds};
    use tcarod::shooting::{base_strains, tensions};
    let len = robot.body.length;
    let d: Vec<f64> = sol.unknowns[6..].iter().map(|x| x * len).collect();
    let tau = tensions(robot, &sol.inputs, &d).unwrap();
    let tau: &'a [f64] = Box::leak(tau.into_boxed_slice());
    let mk = move |k: usize, rec: Record| -> Box<dyn Fn() + 'a> {
        Box::new(move || {
            let mut seeds = TangentSeeds::zeros(robot.actuators.len(), k);
            for j in 0..k.min(6) {
                if j < 3 {
                    seeds.nu0[(j, j)] = 1.0
                } else {
                    seeds.omega0[(j - 3, j)] = 1.0
                }
            }
            let spec = loads.ivp(robot, tau, sol.steps);
            let (v0, u0) = base_strains(&sol.unknowns, len);
            black_box(integrate_tangent(&spec, &v0, &u0, &seeds, rec).unwrap());
        })
    };
    let v: Vec<Contender<'a>> = vec![
        ("tan4", mk(4, Record::Tip)),
        ("tan6", mk(6, Record::Tip)),
        ("tan8", mk(8, Record::Tip)),
        ("tan8rec", mk(8, Record::Tangents)),
    ];
    v
}

/// Median thread-CPU time \[s\] of each contender over `rounds` interleaved
/// rounds.
fn interleaved(cs: &[Contender<'_>], rounds: usize) -> Option<Vec<f64>> {
    let mut t = vec![Vec::with_capacity(rounds); cs.len()];
    for _ in 0..rounds {
        for (k, (_, f)) in cs.iter().enumerate() {
            let t0 = thread_cpu()?;
            f();
            t[k].push(thread_cpu()? - t0);
        }
    }
    Some(
        t.into_iter()
            .map(|mut v| {
                v.sort_by(f64::total_cmp);
                v[v.len() / 2]
            })
            .collect(),
    )
}

fn verdict(c: &mut Criterion) {
    let robot = fig6_square(true);
    let opts = SolveOptions::default();
    let q = [100.0, 100.0];
    let loads = Loads::of(&robot);
    let sol = solve(&robot, &q, &opts, None).expect("fig6 square solves");
    // a warm start from a neighbouring input, as in a sweep
    let warm = solve(&robot, &[98.0, 98.0], &opts, None).expect("fig6 square solves");
    let cs = contenders(&robot, &sol, &warm, &opts, &loads);
    let rounds = std::env::var("TCAROD_ROUNDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(300);
    if let Some(m) = interleaved(&cs, rounds) {
        for ((name, _), t) in cs.iter().zip(&m) {
            println!(
                "interleaved thread-CPU median {name:>13}: {:8.1} us",
                t * 1e6
            );
        }
        println!(
            "(report - off) / tangent IVP = {:.3}; verdict / tangent IVP = {:.3}",
            (m[1] - m[0]) / m[3],
            m[2] / m[3]
        );
        let medians: Vec<String> = cs
            .iter()
            .zip(&m)
            .map(|((name, _), t)| format!("\"{name}\":{t:.9e}"))
            .collect();
        println!(
            "JSON {{\"bench\":\"stability\",\"rounds\":{rounds},\"thread_cpu_median_s\":{{{}}},\"report_minus_off_per_tangent\":{:.4},\"verdict_per_tangent\":{:.4}}}",
            medians.join(","),
            (m[1] - m[0]) / m[3],
            m[2] / m[3]
        );
    }
    let mut g = c.benchmark_group("stability");
    for (name, f) in &cs {
        g.bench_function(*name, |b| b.iter(f));
    }
    g.finish();
}

/// `Policy::Continue` on the upright round silicone column (L 100 mm,
/// d 12 mm, E 70 kPa, 1,070 kg/m^3) at 1.1, 2, 3.7 and 5 times its
/// self-weight buckling load (Greenhill, `rho A g L^3 / EI = 7.837`), cold:
/// the work counted (IVP-equivalents) and the thread CPU of the whole solve
/// in plain IVPs of the same column (medians of 21 runs).
fn greenhill_continue() {
    use tcarod::problems::overloaded_column;
    use tcarod::rod::{Body, Section};
    let opts = SolveOptions::default();
    let mut rows = vec![];
    for factor in [1.1, 2.0, 3.7, 5.0] {
        let b = Body::new(0.1, Section::Circle { diameter: 12e-3 }, 70e3, 0.5, 1070.0)
            .expect("a valid body");
        let robot = overloaded_column(b, factor);
        let loads = Loads::of(&robot);
        let run = || solve_checked(&robot, &[], &loads, &opts, None, Policy::Continue);
        let c = run().expect("the column lands on a stable shape");
        let x = c.solution.unknowns.clone();
        let cs: Vec<Contender<'_>> = vec![
            ("continue", Box::new(|| drop(black_box(run())))),
            (
                "plain_ivp",
                Box::new(|| {
                    let shot = Shot::new(&robot, &[], &loads, opts.steps);
                    black_box(shot.residual(&x, false).unwrap());
                }),
            ),
        ];
        let Some(m) = interleaved(&cs, 21) else {
            return;
        };
        let (work, cpu) = (c.solution.evaluations, m[0] / m[1]);
        println!(
            "continue at {factor} x Greenhill: {work} IVPs counted, thread CPU {cpu:.1} plain IVPs \
             (budget {:.0}), stable {}",
            10.0 * factor,
            c.stability.is_some_and(|s| s.stable)
        );
        rows.push(format!(
            "{{\"factor\":{factor},\"ivps\":{work},\"cpu_ivps\":{cpu:.2}}}"
        ));
    }
    println!(
        "JSON {{\"bench\":\"greenhill_continue\",\"rows\":[{}]}}",
        rows.join(",")
    );
}

fn all(c: &mut Criterion) {
    verdict(c);
    greenhill_continue();
}

criterion_group!(benches, all);
criterion_main!(benches);
