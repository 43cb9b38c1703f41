//! Criterion benches of the stability verdict (issue 16): a warm solve of the
//! Fig. 6 square at 100 C without the verdict (`Policy::Off`) and with it
//! (`Policy::Report`, the default), the verdict alone, and the tangent IVP
//! it must not exceed (the solver's exact Jacobian on the full grid, no
//! nodes recorded). `cargo bench --bench stability`.
use criterion::{criterion_group, criterion_main, Criterion};
use tcarod::experiments::fig6_square;
use tcarod::shooting::{shoot_jacobian, solve, Loads, SolveOptions};
use tcarod::stability::{solve_checked, stability, Policy};

fn verdict(c: &mut Criterion) {
    let robot = fig6_square(true);
    let opts = SolveOptions::default();
    let q = [100.0, 100.0];
    let loads = Loads::of(&robot);
    let sol = solve(&robot, &q, &opts, None).expect("fig6 square solves");
    // a warm start from a neighbouring input, as in a sweep
    let warm = solve(&robot, &[98.0, 98.0], &opts, None).expect("fig6 square solves");
    let mut g = c.benchmark_group("stability");
    for (name, policy) in [("solve_off", Policy::Off), ("solve_report", Policy::Report)] {
        g.bench_function(name, |b| {
            b.iter(|| solve_checked(&robot, &q, &loads, &opts, Some(&warm), policy).unwrap())
        });
    }
    g.bench_function("verdict", |b| {
        b.iter(|| stability(&robot, &sol, &[]).unwrap())
    });
    g.bench_function("tangent_ivp", |b| {
        b.iter(|| {
            shoot_jacobian(
                &robot,
                &sol.inputs,
                &sol.loads,
                &sol.unknowns,
                sol.steps,
                false,
            )
            .unwrap()
        })
    });
    g.finish();
}

criterion_group!(benches, verdict);
criterion_main!(benches);
