//! Criterion benches of the TCA law's solves (Fig. 5 three-thread TCA).
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use tcarod::experiments::fig5_tca;

fn tca_solves(c: &mut Criterion) {
    let tca = fig5_tca(3);
    let force = -0.5 * 7.5e-3 * 9.81;
    c.bench_function("tca_displacement_fig5_100C", |b| {
        b.iter(|| {
            tca.displacement(black_box(force), black_box(100.0))
                .unwrap()
        })
    });
    c.bench_function("tca_force_fig5_100C", |b| {
        b.iter(|| tca.force(black_box(5e-3), black_box(100.0)).unwrap())
    });
    c.bench_function("tca_temperature_fig5", |b| {
        b.iter(|| tca.temperature(black_box(force), black_box(5e-3)).unwrap())
    });
    c.bench_function("tca_onset_temperature_fig5", |b| {
        b.iter(|| tca.temperature(black_box(force), black_box(0.0)).unwrap())
    });
}

criterion_group!(benches, tca_solves);
criterion_main!(benches);
