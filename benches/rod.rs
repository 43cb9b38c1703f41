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
use tcarod::experiments::fig6_square;

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
            ..Default::default()
        };
        g.bench_function(format!("sweep_{n}_threads_{threads}"), |b| {
            b.iter(|| solve_batch(&robot, &inputs, None, &opts).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, rows, batch);
criterion_main!(benches);
