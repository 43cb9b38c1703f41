use nalgebra::Vector3;
use tcarod::experiments::*;
use tcarod::inverse::*;
use tcarod::shooting::*;
fn main() {
    let opts = SolveOptions::default();
    // Table I: 20 mm fingers hanging down (gravity +z in body-aligned frame)
    let mut finger = square_manipulator(0.020, false);
    finger.body.gravity = Vector3::new(0.0, 0.0, G0);
    let groups = Groups(vec![0, 0]);
    for m in [1e-3, 2e-3, 3e-3] {
        let t0 = std::time::Instant::now();
        let r = grasp(&finger, &groups, &Vector3::new(-1.0, 0.0, 0.0), m, 1.1, 2, G0, 10, &opts);
        let dt = t0.elapsed();
        match r {
            Ok(r) => {
                let block = Block::new(Vector3::new(0.0, 0.0, r.solution.s.last().copied().unwrap()), Vector3::new(-1.0,0.0,0.0)).unwrap();
                let _ = block;
                println!("mass {m}: T = {:.3} force {:.4e} it {} ev {} {:?}", r.variables[0], r.force, r.iterations, r.evaluations, dt);
            }
            Err(e) => println!("mass {m}: {e}"),
        }
    }
    // direct check
    let start = solve(&finger, &[25.0, 25.0], &opts, None).unwrap();
    let block = Block::new(start.tip_position(), Vector3::new(-1.0, 0.0, 0.0)).unwrap();
    for t in [60.0, 100.0, 140.0, 160.0] {
        let b = blocked_force(&finger, &groups, &block, &[t], &opts, None).unwrap();
        println!("finger T={t}: blocked force {:.4e} N, it {}", b.force, b.iterations);
    }
    let d = blocked_variable_direct(&finger, &groups, &block, 2e-3*9.81/2.2, 100.0, &opts, None).unwrap();
    println!("direct 2g: T={:.4}", d.variables[0]);
    // sensitivities
    let robot = fig6_square(true);
    let sol = solve(&robot, &[100.0, 100.0], &opts, None).unwrap();
    let t0 = std::time::Instant::now();
    let s = sensitivities(&robot, &sol, &Loads::of(&robot), &groups, 100, Scheme::Forward).unwrap();
    println!("J = {:.4e} C = {:.4e} {:?} ev {}", s.jacobian, s.compliance, t0.elapsed(), s.evaluations);
    let sc = sensitivities(&robot, &sol, &Loads::of(&robot), &groups, 100, Scheme::Central).unwrap();
    println!("Jc-J = {:.3e}", (&sc.jacobian - &s.jacobian).norm() / s.jacobian.norm());
    // brute force J by BVP differencing
    let h = 1e-3;
    let sp = solve(&robot, &[100.0 + h, 100.0 + h], &opts, Some(&sol)).unwrap();
    let sm = solve(&robot, &[100.0 - h, 100.0 - h], &opts, Some(&sol)).unwrap();
    println!("J brute pos = {:.4e}", (sp.tip_position() - sm.tip_position()) / (2.0 * h));
    // tip position inverse
    let target = solve(&robot, &[123.0, 123.0], &opts, None).unwrap().tip_position();
    let t0 = std::time::Instant::now();
    let inv = tip_position_inverse(&robot, &groups, &target, None, &[25.0], &InverseOptions::default()).unwrap();
    println!("inverse: z={:?} err={:.3e} it={} reached={} ev={} {:?}", inv.variables, inv.error, inv.iterations, inv.reached, inv.evaluations, t0.elapsed());
    let inv = tip_position_inverse(&robot, &groups, &Vector3::new(0.01, 0.0, 0.03), None, &[25.0], &InverseOptions::default()).unwrap();
    println!("unreachable: z={:?} err={:.3e} it={} reached={} bound={:?}", inv.variables, inv.error, inv.iterations, inv.reached, inv.at_bound);
}
