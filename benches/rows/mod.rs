//! The performance table's rows, shared by the criterion benches
//! (`benches/rod.rs`) and `tcarod bench` (the bindings include this file as
//! `src/python/bench.rs`'s module `rows`): each row is a prepared problem with
//! a closure that runs the timed operation once. Not library API: the paths
//! are `tcarod::...` so that the file compiles in both places.
//!
//! Problem: Fig. 6 square manipulator ([`fig6_square`]`(true)`: 2 TCAs,
//! gravity), both TCAs at [`BENCH_TEMPERATURE`], 100 RK4 steps unless a row
//! says otherwise.

use nalgebra::Vector3;

use tcarod::error::Result;
use tcarod::experiments::{
    fig6_square, table1_finger, G0, TABLE1_FINGERS, TABLE1_MASSES, TABLE1_MU, TABLE1_NORMAL,
};
use tcarod::experiments::{steel_tendon_robot, STEEL_TENDON_TENSIONS};
use tcarod::inverse::{grasp, sensitivities_exact, sensitivities_fast, Groups, Scheme};
use tcarod::shooting::{solve, Loads, Shot, SolveOptions};

/// Temperature \[C\] of both TCAs in the benches.
pub const BENCH_TEMPERATURE: f64 = 100.0;
/// Temperature step \[C\] of the warm-start row.
pub const WARM_STEP: f64 = 5.0;
/// RK4 steps of the "within 1 um of a 5,000-step reference" row (measured by
/// `tests/integration/perf.rs`: at most 0.43 um over 40-160 C).
pub const ACCURATE_STEPS: usize = 10;

/// One row of the table: name, what it times, its target \[s\].
#[derive(Debug, Clone, Copy)]
pub struct Row {
    /// Short name (`ivp`, `cold`, ...).
    pub name: &'static str,
    /// What is timed.
    pub description: &'static str,
    /// Target time \[s\].
    pub target: f64,
}

/// The rows, in table order.
pub const ROWS: [Row; 6] = [
    Row {
        name: "ivp",
        description: "one IVP (integrate the rod once)",
        target: 25e-6,
    },
    Row {
        name: "cold",
        description: "one forward solve from the straight guess",
        target: 500e-6,
    },
    Row {
        name: "warm",
        description: "one forward solve warm-started 5 C away",
        target: 100e-6,
    },
    Row {
        name: "jc",
        description: "J and C at a solution",
        target: 300e-6,
    },
    Row {
        name: "grasp",
        description: "one blocked-force grasp temperature (Table I, 1 g)",
        target: 5e-3,
    },
    Row {
        name: "cold_1um",
        description: "cold forward solve within 1 um of a 5,000-step reference (10 RK4 steps)",
        target: 100e-6,
    },
];

/// The solver's rows (benches/rod.rs only, not in `tcarod bench`'s table):
/// exact J and C, one tangent IVP, the steel tendon robot
/// ([`steel_tendon_robot`]) cold and warm after +1 % tension.
pub const SOLVER_ROWS: [Row; 4] = [
    Row {
        name: "jc_exact",
        description: "J and C at a solution from one tangent IVP (Scheme::Exact)",
        target: 300e-6,
    },
    Row {
        name: "tangent",
        description: "one tangent IVP: residual and exact shooting Jacobian",
        target: 100e-6,
    },
    Row {
        name: "steel_cold",
        description: "steel tendon robot, cold forward solve",
        target: 300e-6,
    },
    Row {
        name: "steel_warm",
        description: "steel tendon robot, warm solve after +1 % tension",
        target: 300e-6,
    },
];

/// The timed operation of a row: calling it runs the operation once.
pub type Operation = Box<dyn FnMut() -> Result<()>>;

/// A prepared operation of row `name`.
pub fn operation(name: &str) -> Result<Operation> {
    match name {
        "grasp" | "steel_cold" | "steel_warm" => other_robot_row(name),
        _ => fig6_square_row(name),
    }
}

/// The rows on the Fig. 6 square manipulator at [`BENCH_TEMPERATURE`].
fn fig6_square_row(name: &str) -> Result<Operation> {
    let robot = fig6_square(true);
    let t = [BENCH_TEMPERATURE, BENCH_TEMPERATURE];
    let opts = SolveOptions::default();
    Ok(match name {
        "ivp" | "tangent" => {
            // one IVP at the solution, plain or with its tangents (the exact shooting Jacobian)
            let sol = solve(&robot, &t, &opts, None)?;
            let loads = Loads::of(&robot);
            let tangent = name == "tangent";
            Box::new(move || {
                let x = std::hint::black_box(&sol.unknowns);
                if tangent {
                    Shot::new(&robot, &sol.inputs, &loads, opts.steps)
                        .jacobian(x, false)
                        .map(|_| ())
                } else {
                    Shot::new(&robot, &sol.inputs, &loads, opts.steps)
                        .residual(x, false)
                        .map(|_| ())
                }
            })
        }
        "cold" => {
            Box::new(move || solve(&robot, std::hint::black_box(&t), &opts, None).map(|_| ()))
        }
        "warm" => {
            let w = solve(&robot, &[BENCH_TEMPERATURE - WARM_STEP; 2], &opts, None)?;
            Box::new(move || solve(&robot, std::hint::black_box(&t), &opts, Some(&w)).map(|_| ()))
        }
        "jc" | "jc_exact" => {
            // J and C at the solution: forward differences (wrench columns exact) or exact tangents
            let sol = solve(&robot, &t, &opts, None)?;
            let loads = Loads::of(&robot);
            let groups = Groups(vec![0, 0]);
            let exact = name == "jc_exact";
            Box::new(move || {
                let sol = std::hint::black_box(&sol);
                let steps = opts.steps;
                if exact {
                    sensitivities_exact(&robot, sol, &loads, &groups, steps).map(|_| ())
                } else {
                    sensitivities_fast(&robot, sol, &loads, &groups, steps, Scheme::Forward)
                        .map(|_| ())
                }
            })
        }
        "cold_1um" => {
            let o = SolveOptions {
                steps: ACCURATE_STEPS,
                ..opts
            };
            Box::new(move || solve(&robot, std::hint::black_box(&t), &o, None).map(|_| ()))
        }
        other => return Err(unknown_row(other)),
    })
}

/// The rows on the Table I finger and the steel tendon robot.
fn other_robot_row(name: &str) -> Result<Operation> {
    let opts = SolveOptions::default();
    Ok(match name {
        "grasp" => {
            let finger = table1_finger();
            let groups = Groups(vec![0, 0]);
            let normal = Vector3::from(TABLE1_NORMAL);
            Box::new(move || {
                grasp(
                    &finger,
                    &groups,
                    &normal,
                    std::hint::black_box(TABLE1_MASSES[0]),
                    TABLE1_MU,
                    TABLE1_FINGERS,
                    G0,
                    8,
                    &opts,
                )
                .map(|_| ())
            })
        }
        "steel_cold" => {
            let steel = steel_tendon_robot();
            Box::new(move || {
                solve(
                    &steel,
                    std::hint::black_box(&STEEL_TENDON_TENSIONS),
                    &opts,
                    None,
                )
                .map(|_| ())
            })
        }
        "steel_warm" => {
            let steel = steel_tendon_robot();
            let w = solve(&steel, &STEEL_TENDON_TENSIONS, &opts, None)?;
            let up: Vec<f64> = STEEL_TENDON_TENSIONS.iter().map(|x| x * 1.01).collect();
            Box::new(move || solve(&steel, std::hint::black_box(&up), &opts, Some(&w)).map(|_| ()))
        }
        other => return Err(unknown_row(other)),
    })
}

fn unknown_row(name: &str) -> tcarod::error::Error {
    tcarod::error::Error::input("row", format!("unknown bench row {name:?}"))
}
