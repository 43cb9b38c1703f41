//! Criterion benches of the rod model: one per row of the performance table
//! (`rows::ROWS`), on the problems of `rows/mod.rs` (Fig. 6 square
//! manipulator, shared with the tests through `tcarod::experiments`), plus
//! batch throughput on 1 and 2 threads.
// the rows' descriptions and targets are read by `tcarod bench` (src/python/bench.rs)
#[allow(dead_code)]
mod rows;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use rows::{operation, ROWS, SOLVER_ROWS};
use tcarod::batch::{solve_batch, BatchOptions};
use tcarod::experiments::{fig6_circle, fig6_square};
use tcarod::shooting::{sweep, SolveOptions};

fn rows(c: &mut Criterion) {
    for row in ROWS.iter().chain(SOLVER_ROWS.iter()) {
        let mut op = operation(row.name).expect("bench problem solves");
        let mut g = c.benchmark_group("rod");
        if row.name == "grasp" {
            g.sample_size(20);
        }
        g.bench_function(row.name, |b| {
            b.iter(|| op().expect("bench operation succeeds"))
        });
        g.finish();
    }
}

fn batch(c: &mut Criterion) {
    let robot = fig6_square(true);
    let n = 400;
    let inputs: Vec<f64> = (0..n)
        .flat_map(|k| [40.0 + 100.0 * k as f64 / n as f64; 2])
        .collect();
    let mut g = c.benchmark_group("batch");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n as u64));
    for threads in [1, 2] {
        let opts = BatchOptions {
            threads,
            chunk_size: 50,
            // no stability verdict: the throughput of the solves alone
            stability: false,
            ..Default::default()
        };
        g.bench_function(format!("sweep_{n}_threads_{threads}"), |b| {
            b.iter(|| solve_batch(&robot, &inputs, None, &opts).unwrap())
        });
    }
    g.finish();
}

/// Whole warm-started Fig. 6 sweeps (25-160 C every 5 C, with gravity, as
/// `tcarod.paper.fig6`), with the coarse-grid pre-solve (the default) and
/// with full-grid Newton: the pre-solve's cost along a sweep, where its
/// warm Jacobians are passed on from step to step.
fn sweeps(c: &mut Criterion) {
    let mut g = c.benchmark_group("sweep");
    g.sample_size(10);
    for (name, robot, n) in [
        ("circle", fig6_circle(true), 1),
        ("square", fig6_square(true), 2),
    ] {
        let rows: Vec<Vec<f64>> = (0..28).map(|k| vec![25.0 + 5.0 * k as f64; n]).collect();
        for presolve in [true, false] {
            let opts = SolveOptions {
                presolve,
                ..Default::default()
            };
            let label = if presolve { "presolve" } else { "full_grid" };
            g.bench_function(format!("fig6_{name}_{label}"), |b| {
                b.iter(|| sweep(&robot, &rows, &opts).unwrap())
            });
        }
    }
    g.finish();
}

criterion_group!(benches, rows, batch, sweeps);
criterion_main!(benches);
