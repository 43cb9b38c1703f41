//! The TCA law (paper Section II, eqs 1-6): analytic limits and signs.
//!
//! Units: m, N, rad, degrees C. Sign convention: force > 0 is tension,
//! displacement > 0 is extension.
//!
//! Numerical floor used in the tolerances below: the core solves for the
//! displacement with Brent's method to an absolute tolerance of 1e-15 * l (about
//! 5e-16 m for these TCAs) and for temperatures to 1e-10 C; the law itself is
//! evaluated with a handful of flops, so rounding adds a few ulp of the
//! displacement. The inverses and the reference-temperature spring law are unit
//! tests in src/tca/tests.rs (and hypothesis properties at the Python API,
//! tests/test_tca.py).
use tcarod::experiments::fig5_tca;
use tcarod::{Chirality, Material, Tca};

const T_REF: f64 = 25.0;
const T_MAX: f64 = 160.0;

/// The paper's three-thread Fig. 5 TCA (whole, unfolded) of either chirality.
fn fig5(chirality: Chirality) -> Tca {
    let t = fig5_tca(3);
    Tca::new(
        t.fibre_length(),
        t.coiled_length(),
        t.coil_diameter(),
        t.turns(),
        chirality,
        Material::silver_coated_nylon(),
    )
    .unwrap()
}

#[test]
fn reference_temperature_compression_is_exactly_zero() {
    // Coils touch before actuation (d0 = 2 D L / l assumes it): no shortening.
    for chirality in [Chirality::Extension, Chirality::Contraction] {
        for force in [-1e-6, -0.05, -3.0] {
            assert_eq!(fig5(chirality).displacement(force, T_REF).unwrap(), 0.0);
        }
    }
}

/// Close-coiled helical spring with direct shear: 8 n Dc^3/(G d^4) (1 + d^2/(2 Dc^2)),
/// mean coil diameter Dc = l cos(alpha)/(n pi).
fn classical_spring_compliance(tca: &Tca, alpha: f64, temperature: f64) -> f64 {
    let n = tca.n_coils();
    let dc = tca.fibre_length() * alpha.cos() / (n * std::f64::consts::PI);
    let d = tca.at(temperature).unwrap().d;
    let g = tca.material().shear_modulus(temperature).unwrap();
    8.0 * n * dc.powi(3) / (g * d.powi(4)) * (1.0 + d * d / (2.0 * dc * dc))
}

#[test]
fn small_pitch_angle_gives_classical_spring() {
    for alpha0 in [1e-3, 3e-3, 1e-2] {
        let tca = Tca::from_pitch_angle(
            0.01,
            alpha0,
            2e-3,
            50.0,
            Chirality::Extension,
            Material::silver_coated_nylon(),
        )
        .unwrap();
        let f11 = tca.at(T_REF).unwrap().f11(alpha0);
        let ratio = f11 / classical_spring_compliance(&tca, alpha0, T_REF);
        // Expanding eq (3) with l/n = pi Dc / cos(alpha): the bending term is the
        // classical one times cos(a) + 2 sin^2(a) G/(cos(a) E) and the shear term
        // times cos(a) + sin^2(a) G/(cos(a) E), i.e. 1 + (k G/E - 1/2) a^2 + O(a^4)
        // with k = 2 or 1. With G/E = 0.185 the relative error is at most 0.32 a^2,
        // so |ratio - 1| <= a^2 holds with a 3x margin (and fails for an O(a) error).
        assert!((ratio - 1.0).abs() <= alpha0 * alpha0, "{alpha0}: {ratio}");
        // ... and it is genuinely second order, not exact by accident.
        assert!(
            (ratio - 1.0).abs() >= 0.05 * alpha0 * alpha0,
            "{alpha0}: {ratio}"
        );
    }
}

#[test]
fn free_stroke_rises_monotonically_with_temperature() {
    let ext = fig5(Chirality::Extension);
    let stroke: Vec<f64> = (0..271)
        .map(|k| ext.free_stroke(T_REF + 0.5 * k as f64).unwrap()) // every 0.5 C
        .collect();
    assert_eq!(stroke[0], 0.0); // no expansion at t_ref, so no stroke

    // strictly increasing above the onset (t_ref for a free TCA): the smallest
    // step is ~2.5e-5 m, ten orders above the 1e-15 m solve tolerance.
    assert!(stroke.windows(2).all(|w| w[1] > w[0]));
    assert!(stroke[270] > 0.01); // centimetres at 160 C, as the paper's TCAs
}

#[test]
fn contraction_tca_mirrors_extension_under_tension() {
    let (ext, con) = (fig5(Chirality::Extension), fig5(Chirality::Contraction));
    // A small tension keeps the contraction TCA's coils open over the step.
    let (force, dt) = (0.01, 0.01);
    let d0 = ext.displacement(force, T_REF).unwrap();
    assert_eq!(d0, con.displacement(force, T_REF).unwrap()); // tau = 0: chirality is irrelevant
    let slope_ext = (ext.displacement(force, T_REF + dt).unwrap() - d0) / dt;
    let slope_con = (con.displacement(force, T_REF + dt).unwrap() - d0) / dt;
    assert!(slope_ext > 0.0 && 0.0 > slope_con);
    // The magnitudes differ by the chirality-independent softening of the loaded
    // spring, 2 b with b = F (df11/dT) / (1 - F df11/ddelta) (G_T and E_T fall and d
    // grows with T), ~0.35% here, plus the one-sided difference's truncation, O(dt):
    // measured 0.6% of b at dt = 1 C, so ~1e-4 of b at dt = 0.01 C. Rounding:
    // 1e-15 m / 0.01 C = 1e-13 m/C, 1e-9 of the slope.
    let at = ext.at(T_REF).unwrap();
    let alpha = ext.pitch_angle(d0).unwrap();
    let h = f64::EPSILON.cbrt() * d0.max(1.0); // central-difference step [m]
    let f11_at = |d: f64| at.f11(ext.pitch_angle(d).unwrap());
    let df11_ddelta = (f11_at(d0 + h) - f11_at(d0 - h)) / (2.0 * h);
    let df11_dt = (ext.at(T_REF + dt).unwrap().f11(alpha) - at.f11(alpha)) / dt;
    let b = force * df11_dt / (1.0 - force * df11_ddelta);
    assert!(b > 0.0);
    // Magnitudes agree to 1%: 2b is 0.35% of the slope, truncation < 0.1%.
    assert!((slope_ext.abs() - slope_con.abs()).abs() <= 1e-2 * slope_ext.abs());
    // And the whole mismatch is that chirality-independent term, to 1% of b (100x
    // the truncation estimate above).
    let mean = (slope_ext + slope_con) / 2.0;
    assert!((mean - b).abs() <= 1e-2 * b, "{mean} vs {b}");
}

#[test]
fn blocked_force_pushes_and_is_the_force_at_zero_displacement() {
    let (ext, con) = (fig5(Chirality::Extension), fig5(Chirality::Contraction));
    for temperature in [30.0, 60.0, 100.0, 160.0] {
        let fb = ext.blocked_force(temperature).unwrap();
        assert!(fb < 0.0); // heated extension TCA pushes on whatever blocks it
        assert_eq!(fb, ext.force(0.0, temperature).unwrap()); // same definition

        // It is the onset load: slightly more compression keeps the coils closed,
        // slightly less opens them (1e-9 relative >> the 1e-16 rounding of F).
        assert_eq!(
            ext.displacement(fb * (1.0 + 1e-9), temperature).unwrap(),
            0.0
        );
        assert!(ext.displacement(fb * (1.0 - 1e-6), temperature).unwrap() > 0.0);
        // and the onset temperature under that load is this temperature (1e-7 C:
        // Brent's 1e-10 C tolerance with margin)
        let onset = ext.temperature(fb, 0.0).unwrap();
        assert!(
            (onset - temperature).abs() <= 1e-7,
            "{onset} vs {temperature}"
        );
        // The contraction TCA pulls instead, with the same magnitude (the
        // untwisting term's sign reversed: rounding only).
        let fc = con.blocked_force(temperature).unwrap();
        assert!((fc + fb).abs() <= 1e-12 * fb.abs());
    }
    assert_eq!(ext.blocked_force(T_REF).unwrap(), 0.0);
    assert!(ext.blocked_force(T_MAX).unwrap() < ext.blocked_force(100.0).unwrap());
}

#[test]
fn material_preset_reproduces_documented_values() {
    let m = Material::silver_coated_nylon();
    assert_eq!((m.t_ref(), m.t_min(), m.t_max()), (25.0, 25.0, 160.0));
    // docs/choices.md, "Material (silver-coated nylon 6,6)": E_T(25 C) = 1.198e9 Pa,
    // G_T(25 C) = 2.218e8 Pa, slope -1.3e6 Pa/C (Sun & Zhao's T-RO 2022 code)
    // (the preset's own numbers: rounding only, 1e-12 relative)
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
    assert!(close(m.youngs_modulus(25.0).unwrap(), 1.198e9));
    assert!(close(m.shear_modulus(25.0).unwrap(), 2.218e8));
    assert!(close(
        m.youngs_modulus(160.0).unwrap(),
        1.198e9 - 1.3e6 * 135.0
    ));
}
