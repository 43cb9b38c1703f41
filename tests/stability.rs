//! Elastic stability and branch following (issue 16): analytic buckling loads
//! and an independent planar elastica with self-weight.

use nalgebra::Vector3;
use tcarod::rod::{Body, Robot, Section};
use tcarod::shooting::{solve, SolveOptions};
use tcarod::stability::stability;

/// A slender round steel-like column: L/r = 100, so shear and extension move
/// the critical loads by ~1e-4 relative (P_E/(k G A) ~ 2e-4), well inside 0.5 %.
fn column(tip_force: f64) -> Robot {
    let mut b = Body::new(0.5, Section::Circle { diameter: 10e-3 }, 1e6, 0.5, 1000.0).unwrap();
    b.tip_force = Vector3::new(0.0, 0.0, -tip_force);
    Robot::new(b, vec![]).unwrap()
}

#[test]
fn euler_column_margin() {
    let r = column(0.0);
    let (_, ix, _, _) = r.body.section.properties();
    let pc = std::f64::consts::PI.powi(2) * r.body.youngs_modulus * ix / (4.0 * 0.25);
    for f in [0.0, 0.5, 0.9, 0.99, 1.01, 1.1, 2.0] {
        let rob = column(f * pc);
        let sol = solve(&rob, &[], &SolveOptions::default(), None).unwrap();
        let st = stability(&rob, &sol, &[]).unwrap();
        println!("f {f} stable {} margin {} conj {:?} det_end {}", st.stable, st.margin, st.conjugate_point, st.determinant.last().unwrap());
    }
}
