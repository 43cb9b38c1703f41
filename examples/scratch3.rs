use tcarod::experiments::*;
use tcarod::shooting::*;
fn main() {
    let opts = SolveOptions { tol: 1e-12, ..Default::default() };
    let robot = fig6_circle(true);
    let loads = Loads::of(&robot);
    let base = solve_loaded(&robot, &[120.0], &loads, &opts, None).unwrap();
    let x = base.unknowns.clone();
    println!("x = {:?}", x);
    let r0 = shoot(&robot, &[120.0], &loads, &x, 100, false).unwrap().0;
    for j in 0..x.len() {
        for h in [1e-3, 1e-4, 1e-5] {
            let mut xp = x.clone(); xp[j] += h;
            let mut xm = x.clone(); xm[j] -= h;
            let rp = shoot(&robot, &[120.0], &loads, &xp, 100, false).unwrap().0;
            let rm = shoot(&robot, &[120.0], &loads, &xm, 100, false).unwrap().0;
            let d1: Vec<f64> = (0..r0.len()).map(|i| (rp[i]-rm[i])/(2.0*h)).collect();
            let d2: Vec<f64> = (0..r0.len()).map(|i| (rp[i]+rm[i]-2.0*r0[i])/(h*h)).collect();
            println!("j={j} h={h:e} d1={:.3?}\n      d2={:.3?}", d1, d2);
        }
    }
}
