//! The tangent pass's cost: the hand-linearised lanes (`RodRhs::deriv_lanes`,
//! the default) against the reference pass in dual arithmetic throughout
//! (`tcarod::rod::with_dual_rhs`), interleaved
//! in one run by thread CPU time, on the Fig. 6 square at
//! `rows::BENCH_TEMPERATURE` (100 RK4 steps): one plain IVP, tangent passes
//! of 6 and 8 directions (tip only), the exact shooting Jacobian
//! (`rows` "tangent"), exact J and C ("jc_exact"), and the steel tendon
//! robot's cold and warm solves (their Newton Jacobians are tangent passes).
//! `cargo bench --bench tangent` (`TCAROD_ROUNDS`, default 300, rounds;
//! `TCAROD_REF=0` times the lane pass only, for profiling it with perf).
use std::hint::black_box;

#[allow(dead_code)]
mod rows;

#[path = "clock/mod.rs"]
mod clock;
use clock::thread_cpu;

use rows::{operation, Operation, BENCH_TEMPERATURE};
use tcarod::experiments::{fig6_square, steel_tendon_robot, STEEL_TENDON_TENSIONS};
use tcarod::rod::{integrate_tangent, with_dual_rhs, Record, Robot, TangentSeeds};
use tcarod::shooting::{base_strains, solve, tensions, Loads, SolveOptions};

/// A tangent pass of `k` directions (the 6 base strains, then the
/// tensions) at the solution of `robot` for `inputs`.
fn pass(robot: Robot, inputs: &[f64], k: usize) -> Operation {
    let sol = solve(&robot, inputs, &SolveOptions::default(), None).unwrap();
    let len = robot.body.length;
    let d: Vec<f64> = sol.unknowns[6..].iter().map(|x| x * len).collect();
    let tau = tensions(&robot, &sol.inputs, &d).unwrap();
    let loads = Loads::of(&robot);
    let mut seeds = TangentSeeds::zeros(robot.actuators.len(), k);
    for j in 0..k {
        match j {
            0..=2 => seeds.nu0[(j, j)] = 1.0,
            3..=5 => seeds.omega0[(j - 3, j)] = 1.0,
            _ => seeds.tensions[(j - 6, j)] = 1.0,
        }
    }
    Box::new(move || {
        let spec = loads.ivp(&robot, &tau, sol.steps);
        let (v0, u0) = base_strains(&sol.unknowns, len);
        black_box(integrate_tangent(&spec, &v0, &u0, &seeds, Record::Tip)?);
        Ok(())
    })
}

/// IVPs and iterations of the steel robot's cold and warm (+1 % tension) solves.
fn steel_counts() {
    let (steel, opts) = (steel_tendon_robot(), SolveOptions::default());
    let cold = solve(&steel, &STEEL_TENDON_TENSIONS, &opts, None).unwrap();
    let up: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|x| x * 1.01).collect();
    let warm = solve(&steel, &up, &opts, Some(&cold)).unwrap();
    for (name, s) in [("steel_cold", &cold), ("steel_warm", &warm)] {
        let (it, ev) = (s.iterations, s.evaluations);
        println!("{name}: {it} iterations, {ev} IVPs (plain or tangent)");
    }
}

fn main() {
    steel_counts();
    let rounds: usize = std::env::var("TCAROD_ROUNDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(300);
    let mut cs: Vec<(String, Operation)> = vec![
        ("ivp".into(), operation("ivp").unwrap()),
        (
            "tan6".into(),
            pass(fig6_square(true), &[BENCH_TEMPERATURE; 2], 6),
        ),
        (
            "tan8".into(),
            pass(fig6_square(true), &[BENCH_TEMPERATURE; 2], 8),
        ),
        (
            "steel_tan10".into(),
            pass(steel_tendon_robot(), &STEEL_TENDON_TENSIONS, 10),
        ),
        ("tangent".into(), operation("tangent").unwrap()),
        ("jc_exact".into(), operation("jc_exact").unwrap()),
        ("steel_cold".into(), operation("steel_cold").unwrap()),
        ("steel_warm".into(), operation("steel_warm").unwrap()),
    ];
    // TCAROD_REF=0: the lane pass only (for profiling it with perf)
    let with_ref = std::env::var("TCAROD_REF").map_or(true, |v| v != "0");
    let n = cs.len();
    // (name, dual?) per contender: every operation twice, lanes then reference
    let mut t = vec![vec![Vec::new(); 2]; n];
    for _ in 0..rounds {
        for (k, (_, f)) in cs.iter_mut().enumerate() {
            for (m, dual) in [false, true].into_iter().enumerate() {
                if dual && (k == 0 || !with_ref) {
                    continue; // the plain IVP has no tangents
                }
                let t0 = thread_cpu().expect("thread CPU clock");
                if dual {
                    with_dual_rhs(&mut *f).unwrap();
                } else {
                    f().unwrap();
                }
                t[k][m].push(thread_cpu().expect("thread CPU clock") - t0);
            }
        }
    }
    let med = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let ivp = med(&mut t[0][0]);
    println!("interleaved thread-CPU medians over {rounds} rounds (Fig. 6 square, 100 steps)");
    println!(
        "{:>11} {:>10} {:>6} {:>10} {:>6} {:>6}",
        "", "lanes us", "IVPs", "ref us", "IVPs", "ratio"
    );
    println!("{:>11} {:>10.1} {:>6.2}", "ivp", ivp * 1e6, 1.0);
    for (k, (name, _)) in cs.iter().enumerate().skip(1) {
        let a = med(&mut t[k][0]);
        let b = if with_ref {
            med(&mut t[k][1])
        } else {
            f64::NAN
        };
        println!(
            "{name:>11} {:>10.1} {:>6.2} {:>10.1} {:>6.2} {:>6.2}",
            a * 1e6,
            a / ivp,
            b * 1e6,
            b / ivp,
            b / a
        );
    }
}
