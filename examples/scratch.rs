use tcarod::experiments::*;
use tcarod::shooting::*;
fn main() {
    for (name, robot) in [("square", fig6_square(false)), ("squareg", fig6_square(true)), ("circle", fig6_circle(true)), ("circle-nog", fig6_circle(false))] {
        let na = robot.actuators.len();
        let opts = SolveOptions::default();
        let mut prev: Option<Solution> = None;
        let (mut tw, mut tc) = (vec![], vec![]);
        for k in 0..28 {
            let t = 25.0 + 5.0 * k as f64;
            let w = solve(&robot, &vec![t; na], &opts, prev.as_ref()).unwrap();
            let c = solve(&robot, &vec![t; na], &opts, None).unwrap();
            tw.push(w.iterations); tc.push(c.iterations);
            prev = Some(w);
        }
        println!("{name}: warm {:?}\n   cold {:?}", tw, tc);
    }
}
