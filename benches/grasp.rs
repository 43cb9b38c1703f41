//! The Table I grasp temperature (eq 44, 1 g, the finger blocked where it
//! rests at the reference inputs) by the direct bordered Newton solve and
//! by the paper's eq-43 increments (8), with and without the stability
//! verdict of the blocked finger, and the pieces it is made of: one IVP and
//! one full-grid tangent IVP of the finger, the free solve at contact.
//!
//! Before the criterion rows it prints each method's IVP count (a tangent
//! IVP counts as one) and its median time over 21 runs in IVP times of the
//! finger (thread-unaware wall clock: quote the load).

use std::time::Instant;

use criterion::{criterion_group, criterion_main, Criterion};
use tcarod::experiments::{table1_finger, table1_grasp, TABLE1_MASSES};
use tcarod::inverse::{Grasp, GraspMethod, Groups};
use tcarod::rod::Robot;
use tcarod::shooting::{solve, Loads, Shot, SolveOptions};
use tcarod::stability::Policy;

/// The Table I grasp of the lightest mass under a stability policy.
fn spec(stability: Policy) -> Grasp {
    table1_grasp(TABLE1_MASSES[0], stability)
}

const CASES: [(&str, GraspMethod, Policy); 4] = [
    ("direct", GraspMethod::Direct, Policy::Off),
    ("incremental", GraspMethod::Incremental(8), Policy::Off),
    ("direct_verdict", GraspMethod::Direct, Policy::Report),
    (
        "incremental_verdict",
        GraspMethod::Incremental(8),
        Policy::Report,
    ),
];

/// Median wall time \[s\] of `f` over 21 runs.
fn median(mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..21)
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[10]
}

fn report(finger: &Robot, groups: &Groups, opts: &SolveOptions) {
    let sol = solve(finger, &finger.reference_inputs(), opts, None).expect("free solve");
    let loads = Loads::of(finger);
    let ivp = median(|| {
        Shot::new(finger, &sol.inputs, &loads, opts.steps)
            .residual(&sol.unknowns, false)
            .expect("IVP");
    });
    println!("one IVP of the finger: {:.1} us", ivp * 1e6);
    let free = median(|| {
        solve(finger, &sol.inputs, opts, None).expect("free solve");
    });
    println!(
        "free solve at contact        {:>8.1} us = {:>5.1} IVP times, IVPs {:>3}, iterations {:>2}",
        free * 1e6,
        free / ivp,
        sol.evaluations,
        sol.iterations
    );
    for (name, method, policy) in CASES {
        let s = spec(policy);
        let (r, _) = s.solve(finger, groups, method, opts).expect("grasp");
        let t = median(|| {
            s.solve(finger, groups, method, opts).expect("grasp");
        });
        println!(
            "grasp {name:<20} {:>8.1} us = {:>5.1} IVP times, IVPs {:>3}, iterations {:>2}, temperature {:.9} C",
            t * 1e6,
            t / ivp,
            r.evaluations,
            r.iterations,
            r.variables[0]
        );
    }
}

fn rows(c: &mut Criterion) {
    let finger = table1_finger();
    let groups = Groups(vec![0, 0]);
    let opts = SolveOptions::default();
    report(&finger, &groups, &opts);
    let mut g = c.benchmark_group("grasp");
    g.sample_size(20);
    for (name, method, policy) in CASES {
        let s = spec(policy);
        g.bench_function(name, |b| {
            b.iter(|| s.solve(&finger, &groups, method, &opts).expect("grasp"))
        });
    }
    let inputs = finger.reference_inputs();
    g.bench_function("free_solve", |b| {
        b.iter(|| solve(&finger, std::hint::black_box(&inputs), &opts, None).expect("solve"))
    });
    let sol = solve(&finger, &inputs, &opts, None).expect("solve");
    let loads = Loads::of(&finger);
    g.bench_function("tangent", |b| {
        b.iter(|| {
            let x = std::hint::black_box(&sol.unknowns);
            Shot::new(&finger, &inputs, &loads, opts.steps)
                .jacobian(x, false)
                .expect("tangent")
        })
    });
    g.finish();
}

criterion_group!(benches, rows);
criterion_main!(benches);
