//! The model's construction rules live in the core (`src/rod/`, `src/tca/`,
//! `tcarod::experiments`): a Rust user gets the same validation as a Python
//! user, with the same argument names (`tests/test_bad_input.py` and
//! `tests/test_binding_boundary.py` check them through the bindings).
use std::sync::Arc;

use tcarod::experiments::{
    fig5_half_tca, fig5_tca, fig6_square, steel_tendon_robot, table1_finger, Manipulator, HANGING,
};
use tcarod::rod::{
    Actuator, Body, ConstantTension, ForceLaw, Robot, Routing, Section, Shear, TcaLaw,
};
use tcarod::Error;

fn body(length: f64) -> Body {
    Body::new(length, Section::circle(14e-3).unwrap(), 37.8e3, 0.5, 1040.0).unwrap()
}

fn name_of(e: Error) -> String {
    match e {
        Error::InvalidParameter { name, .. } | Error::InvalidInput { name, .. } => name,
        other => panic!("not an argument error: {other}"),
    }
}

#[test]
fn section_and_routing_constructors_name_the_argument() {
    assert_eq!(name_of(Section::circle(-1.0).unwrap_err()), "diameter [m]");
    assert_eq!(
        name_of(Section::rectangle(1e-2, f64::NAN).unwrap_err()),
        "height [m]"
    );
    // a size whose fourth power underflows: derived properties not > 0
    assert_eq!(name_of(Section::circle(1e-90).unwrap_err()), "diameter [m]");
    assert_eq!(
        name_of(Routing::helix(-1e-3, 1.0, 0.0).unwrap_err()),
        "radius [m]"
    );
    let s = Section::rectangle(0.01, 0.02).unwrap();
    assert_eq!(
        Section::from_parameters(s.kind(), &[0.01, 0.02]).unwrap(),
        s
    );
}

#[test]
fn poisson_or_shear_modulus_not_both() {
    let e = Shear::from_options(Some(0.3), Some(1e4)).unwrap_err();
    assert_eq!(name_of(e), "poisson / shear_modulus");
    // neither: incompressible silicone, G = E / 3
    let s = Shear::from_options(None, None).unwrap();
    let b = Body::with_shear(0.04, Section::circle(8e-3).unwrap(), 30e3, s, 0.0).unwrap();
    // 30e3 / 3: rounding only
    assert!((b.shear_modulus - 10e3).abs() < 1e-9);
    let s = Shear::from_options(None, Some(7e3)).unwrap();
    let b = Body::with_shear(0.04, Section::circle(8e-3).unwrap(), 30e3, s, 0.0).unwrap();
    assert_eq!(b.shear_modulus, 7e3);
}

#[test]
fn robot_resolves_the_tip_and_checks_the_layout() {
    let law = Arc::new(ConstantTension);
    let a = Actuator::anchored(
        Routing::straight(3e-3, 0.0).unwrap(),
        0.0,
        None,
        None,
        law.clone(),
    );
    let r = Robot::new(body(0.04), vec![a.unwrap()]).unwrap();
    // `None` means the tip
    assert_eq!(r.actuators[0].s_end, 0.04);
    // a 20 mm offset in a 14 mm body
    let out = Actuator::new(Routing::straight(20e-3, 0.0).unwrap(), 0.0, 0.04, law);
    let e = Robot::new(body(0.04), vec![out]).unwrap_err();
    assert_eq!(name_of(e), "actuators[0].routing");
    // a 70 mm TCA on a 30 mm body
    let tca = Manipulator::square(0.070).tca().unwrap();
    let long = Actuator::new(
        Routing::straight(3e-3, 0.0).unwrap(),
        0.0,
        0.03,
        Arc::new(TcaLaw(tca)),
    );
    assert_eq!(
        name_of(Robot::new(body(0.03), vec![long]).unwrap_err()),
        "actuators[0].tca"
    );
    // the steel tendon robot's tendons run through spacer disks, outside its 2 mm rod
    assert!(steel_tendon_robot().spacer_disks);
}

#[test]
fn pretension_sets_the_length_ratio() {
    let tca = Manipulator::square(0.040).tca().unwrap();
    let routing = Routing::straight(3e-3, 0.0).unwrap();
    let both = Actuator::tca(tca.clone(), routing, 0.0, None, Some(0.9), Some(0.1));
    assert_eq!(name_of(both.unwrap_err()), "pretension_n / length_ratio");
    let a = Actuator::tca(tca.clone(), routing, 0.0, None, None, Some(0.1)).unwrap();
    let r = Robot::new(body(0.04), vec![a]).unwrap();
    // straight, unstretched reference path: ratio = 1 - stretch / span
    let stretch = tca.displacement(0.1, tca.material().t_ref()).unwrap();
    let want = 1.0 - stretch / 0.04;
    // the same closed form in the core: rounding only
    assert!((r.actuators[0].length_ratio.unwrap() - want).abs() < 1e-12);
}

#[test]
fn a_cold_tca_input_points_to_a_custom_material() {
    let law = TcaLaw(fig5_tca(3));
    let e = law.check_input(10.0).unwrap_err().to_string();
    assert!(
        e.starts_with("invalid temperature = 10 C: allowed 25 <= T <= 160 C")
            && e.contains("t_min=<ambient>"),
        "{e}"
    );
    assert!(law.check_input(200.0).is_err() && law.check_input(60.0).is_ok());
}

#[test]
fn fixtures_are_built_once_from_the_design() {
    // Fig. 5 half: the whole TCA's alpha0 and d0, half its lengths and turns
    let (whole, half) = (fig5_tca(4), fig5_half_tca(4));
    assert_eq!(half.coiled_length(), 0.5 * whole.coiled_length());
    assert_eq!(half.turns(), 0.5 * whole.turns());
    // asin(L/l) of halved lengths: the same ratio to rounding
    assert!((half.alpha0() - whole.alpha0()).abs() < 1e-15);
    // the Table I finger hangs; the Fig. 6 square stands upright
    assert_eq!(table1_finger().body.gravity.as_slice(), HANGING);
    let sq = fig6_square(true);
    assert_eq!(sq.body.gravity.z, -tcarod::experiments::G0);
    assert_eq!(sq.actuators.len(), 2);
}
