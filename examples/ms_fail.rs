use tcarod::problems::{random_design, stress_design};
use tcarod::shooting::{Loads, SolveOptions};
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let seed = u64::from_str_radix(a[1].trim_start_matches("0x"), 16).unwrap();
    let stress = a.get(3).is_some_and(|v| v == "s");
    for i in a[2].split(',').map(|v| v.parse::<usize>().unwrap()) {
        let d = if stress {
            stress_design(seed, i)
        } else {
            random_design(seed, i)
        };
        println!(
            "design {i}: {} past_buckling {}",
            d.summary(),
            d.past_buckling()
        );
        let loads = Loads::of(&d.robot);
        let opts = SolveOptions::default();
        let t = std::time::Instant::now();
        match tcarod::solve::forward::solve(&d.robot, &d.inputs, &loads, &opts, None) {
            Ok(s) => println!(
                "  ok evals {} iters {} path {} {:.1} ms",
                s.evaluations,
                s.iterations,
                s.continuation_steps.len(),
                t.elapsed().as_secs_f64() * 1e3
            ),
            Err(e) => println!("  ERR {e}"),
        }
    }
}
