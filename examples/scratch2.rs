use nalgebra::Vector3;
use tcarod::experiments::*;
use tcarod::inverse::*;
use tcarod::shooting::*;
fn main() {
    let opts = SolveOptions { tol: 1e-12, ..Default::default() };
    let groups = Groups(vec![0]);
    let robot = fig6_circle(true);
    let mut loads = Loads::of(&robot);
    loads.tip_force = Vector3::new(1e-3, -5e-4, 2e-3);
    let inputs = [120.0];
    let base = solve_loaded(&robot, &inputs, &loads, &opts, None).unwrap();
    println!("base res {:e} it {}", base.residual, base.iterations);
    for sch in [Scheme::Forward, Scheme::Central] {
        let s = sensitivities(&robot, &base, &loads, &groups, 100, sch).unwrap();
        println!("{:?} J0 {:.8e} J4 {:.8e}", sch, s.jacobian[0], s.jacobian[4]);
    }
    for rel in [1e-3, 1e-4, 1e-5, 6e-6, 1e-6, 1e-7] {
        let s = sensitivities_with_step(&robot, &base, &loads, &groups, 100, Scheme::Central, rel).unwrap();
        println!("rel {rel:e} central J0 {:.8e}", s.jacobian[0]);
    }
    for h in [1e-1, 1e-2, 1e-3, 1e-4] {
        let sp = solve_loaded(&robot, &[120.0 + h], &loads, &opts, Some(&base)).unwrap();
        let sm = solve_loaded(&robot, &[120.0 - h], &loads, &opts, Some(&base)).unwrap();
        println!("h={h} J0 {:.8e} res {:e} {:e}", (sp.tip_position().x - sm.tip_position().x) / (2.0*h), sp.residual, sm.residual);
    }
}
#[allow(dead_code)]
fn study() {}
