//! Work of cold and warm forward solves of the speed fixtures, in IVP
//! times: `cargo run --release --example fixture_costs`. For the Fig. 6
//! square at 100 C (warm from 95 C) and the steel tendon robot at 15 N
//! (warm from its solution after +1 % tension), the thread-CPU median of
//! each solve over that of one plain full-grid IVP at the solution,
//! interleaved round by round (a shared machine's load moves all of them
//! alike), and the solve's own IVP count (`Solution.evaluations`).
use tcarod::experiments::{fig6_square, steel_tendon_robot, STEEL_TENDON_TENSIONS};
use tcarod::shooting::{solve, Loads, Shot, SolveOptions};

#[path = "../benches/clock/mod.rs"]
mod clock;

/// Thread CPU time [s] of `n` calls of `f`.
fn cpu(n: usize, mut f: impl FnMut()) -> f64 {
    let t0 = clock::thread_cpu().expect("thread CPU time needs 64-bit Linux");
    for _ in 0..n {
        f();
    }
    clock::thread_cpu().expect("thread CPU time") - t0
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let o = SolveOptions::default();
    let steel_up: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|t| t * 1.01).collect();
    let cases = [
        (
            "Fig. 6 square",
            fig6_square(true),
            vec![100.0, 100.0],
            vec![95.0, 95.0],
        ),
        (
            "steel tendon",
            steel_tendon_robot(),
            steel_up,
            STEEL_TENDON_TENSIONS.to_vec(),
        ),
    ];
    for (name, robot, q, q_warm) in cases {
        let loads = Loads::of(&robot);
        let warm = solve(&robot, &q_warm, &o, None).unwrap();
        let sol = solve(&robot, &q, &o, None).unwrap();
        let hot = solve(&robot, &q, &o, Some(&warm)).unwrap();
        let shot = Shot::new(&robot, &q, &loads, o.steps);
        let (mut ivp, mut cold, mut warm_t) = (vec![], vec![], vec![]);
        let n = 200;
        for _ in 0..21 {
            ivp.push(cpu(n, || drop(shot.residual(&sol.unknowns, false))));
            cold.push(cpu(n, || drop(solve(&robot, &q, &o, None))));
            warm_t.push(cpu(n, || drop(solve(&robot, &q, &o, Some(&warm)))));
        }
        let unit = median(ivp);
        println!(
            "{name}: one IVP {:.1} us; cold {:.2} IVP times ({} IVPs); warm {:.2} IVP times ({} IVPs)",
            unit / n as f64 * 1e6,
            median(cold) / unit,
            sol.evaluations,
            median(warm_t) / unit,
            hot.evaluations
        );
    }
}
