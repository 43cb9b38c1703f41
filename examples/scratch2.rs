use tcarod::experiments::*;
use tcarod::inverse::*;
use tcarod::shooting::*;
fn main() {
    let opts = SolveOptions::default();
    let groups = Groups(vec![0, 0]);
    let robot = fig6_square(true);
    let sol = solve(&robot, &[100.0, 100.0], &opts, None).unwrap();
    let s = sensitivities(&robot, &sol, &Loads::of(&robot), &groups, 100, Scheme::Forward).unwrap();
    let sc = sensitivities(&robot, &sol, &Loads::of(&robot), &groups, 100, Scheme::Central).unwrap();
    println!("{:.5e}{:.5e}", s.jacobian.transpose(), sc.jacobian.transpose());
    println!("{:.5e}{:.5e}", s.compliance, sc.compliance);
    let h = 1e-3;
    let sp = solve(&robot, &[100.0 + h, 100.0 + h], &opts, Some(&sol)).unwrap();
    let sm = solve(&robot, &[100.0 - h, 100.0 - h], &opts, Some(&sol)).unwrap();
    let r = nalgebra::Rotation3::from_matrix_unchecked(sp.tip_rotation() * sm.tip_rotation().transpose()).scaled_axis() / (2.0*h);
    println!("brute rot {:.5e}", r.transpose());
}
