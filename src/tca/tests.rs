//! Unit tests of the TCA law.

use super::*;

fn fig5_three_thread() -> Tca {
    Tca::new(
        0.497,
        0.110,
        2e-3,
        300.0,
        Chirality::Extension,
        Material::silver_coated_nylon(),
    )
    .unwrap()
}

#[test]
fn contact_law_is_continuous_and_monotone() {
    let t = fig5_three_thread();
    let at = t.at(25.0).unwrap();
    let e = TcaAt::CONTACT_SMOOTHING;
    let f = |d: f64| at.tension(d).unwrap();
    // continuity at 0 and at -eps (relative 1e-9: rounding of the pieces)
    assert!((f(-1e-18) - f(0.0)).abs() < 1e-12);
    assert!((f(-e * (1.0 - 1e-12)) - f(-e * (1.0 + 1e-12))).abs() < 1e-9 * f(-e).abs().max(1e-12));
    // slope rises from the spring's to the contact stiffness
    let slope = |d: f64| (f(d + 1e-12) - f(d - 1e-12)) / 2e-12;
    assert!(slope(-2.0 * e) > 100.0 * slope(1e-6));
    assert!((slope(-3.0 * e) - at.contact_stiffness()).abs() < 1e-3 * at.contact_stiffness());
    // tension increases with elongation through the whole contact region
    let mut last = f64::NEG_INFINITY;
    for k in 0..50 {
        let d = -3.0 * e + 1e-8 * k as f64;
        assert!(f(d) > last, "not increasing at {d}");
        last = f(d);
    }
}

#[test]
fn contact_elongation_inverts_the_contact_law() {
    // on the smoothed onset, at its end and deep in contact: tension(d) = t
    // back to the elongation exactly (the linear (t - F(0)) / k_c would be
    // off by eps (k_c - k_s) / (2 k_c), half the smoothing width, enough to
    // move a warm start off a converged solution in coil contact)
    let t = fig5_three_thread();
    let at = t.at(60.0).unwrap();
    let e = TcaAt::CONTACT_SMOOTHING;
    for d in [-0.3 * e, -e, -4.877e-7, -1e-5] {
        let t = at.tension(d).unwrap();
        let back = at.contact_elongation(t).unwrap();
        // the inverse's conditioning: a tension known to a few ulp moves the
        // elongation by ulp(t) / slope; plus Brent's tolerance, 4 ulp of |lo|
        let cond = 16.0 * f64::EPSILON * t.abs() / at.tension_slope(d).unwrap();
        assert!((back - d).abs() < cond + 1e-14 * d.abs(), "{d}: {back}");
    }
    assert!(at.contact_elongation(at.force(0.0).unwrap()).is_err());
}

#[test]
fn derived_quantities_follow_the_paper() {
    let t = fig5_three_thread();
    assert!((t.alpha0() - (0.110f64 / 0.497).asin()).abs() < 1e-15);
    assert!((t.n_coils() - 2.0 * t.alpha0().cos() * 0.497 / (PI * 2e-3)).abs() < 1e-12);
    assert!((t.d0() - 2.0 * 2e-3 * 0.110 / 0.497).abs() < 1e-15);
    assert!((t.phi0() - 600.0 * PI).abs() < 1e-12);
}

#[test]
fn reference_temperature_gives_no_torque_and_hookean_response() {
    let t = fig5_three_thread();
    let s = t.at(25.0).unwrap();
    assert_eq!(s.tau, 0.0);
    // compression at T_ref: coils in contact
    assert_eq!(t.displacement(-0.1, 25.0).unwrap(), 0.0);
    // tension: delta = f11(alpha(delta)) F
    let f = 0.05;
    let d = t.displacement(f, 25.0).unwrap();
    let a = t.pitch_angle(d).unwrap();
    assert!((d - s.f11(a) * f).abs() < 1e-14);
}

#[test]
fn force_and_displacement_are_inverse() {
    let t = fig5_three_thread();
    for temp in [25.0, 80.0, 160.0] {
        for f in [0.0, 0.02, 0.2] {
            let d = t.displacement(f, temp).unwrap();
            if d > 0.0 {
                let f2 = t.force(d, temp).unwrap();
                assert!((f2 - f).abs() < 1e-9, "{temp} {f} {f2}");
            }
        }
    }
}

#[test]
fn temperature_inverts_displacement_at_the_ends_of_the_range() {
    // A state computed at t_min or t_max satisfies the law only to the
    // displacement solve's tolerance; the inverse must still find it.
    let t = fig5_three_thread();
    for temp in [25.0, 160.0] {
        for i in 0..=40 {
            let f = -0.3 + 0.02 * f64::from(i);
            let d = t.displacement(f, temp).unwrap();
            if d > 0.0 {
                let back = t.temperature(f, d).unwrap();
                // Brent's 1e-10 C, or the exact end
                assert!((back - temp).abs() < 1e-7, "{temp} {f} {back}");
            }
        }
    }
}

#[test]
fn segment_keeps_geometry_ratios_and_scales_elongation() {
    let t = fig5_three_thread();
    for frac in [0.25, 0.5, 1.0 / 3.0, 1.0] {
        let s = t.segment(frac).unwrap();
        // ratios of scaled lengths: equal to rounding (a few ulps)
        assert!((s.alpha0() - t.alpha0()).abs() < 1e-14, "{frac}");
        assert!((s.d0() - t.d0()).abs() < 1e-15 * t.d0().max(1.0), "{frac}");
        assert!(
            (s.turns() / s.fibre_length() - t.turns() / t.fibre_length()).abs() < 1e-9,
            "{frac}"
        );
        assert!((s.n_coils() - frac * t.n_coils()).abs() < 1e-12 * t.n_coils());
        assert_eq!(s.coil_diameter(), t.coil_diameter());
        assert_eq!(s.chirality(), t.chirality());
        // the law is linear in n at fixed l/n, d, alpha: a segment
        // stretches by `frac` of the whole under the same force and
        // temperature (to the displacement solve's 1e-15 l tolerance,
        // amplified by the conditioning of the root; 1e-9 relative is
        // far above that and far below any modelling difference)
        for (f, temp) in [(0.02, 25.0), (-0.05, 120.0), (0.0, 160.0)] {
            let dw = t.displacement(f, temp).unwrap();
            let ds = s.displacement(f, temp).unwrap();
            assert!(
                (ds - frac * dw).abs() <= 1e-9 * dw.abs().max(1e-12),
                "{frac} {f} {temp}: {ds} vs {}",
                frac * dw
            );
            if dw > 0.0 {
                let fw = t.force(dw, temp).unwrap();
                let fs = s.force(frac * dw, temp).unwrap();
                assert!((fw - fs).abs() < 1e-9 * fw.abs().max(1e-3));
            }
        }
    }
    for bad in [0.0, -0.5, 1.5, f64::NAN] {
        assert!(t.segment(bad).is_err(), "{bad}");
    }
}

#[test]
fn invalid_geometry_rejected() {
    let m = Material::silver_coated_nylon();
    assert!(Tca::new(0.1, 0.11, 2e-3, 300.0, Chirality::Extension, m.clone()).is_err());
    assert!(Tca::new(0.5, 0.11, f64::NAN, 300.0, Chirality::Extension, m.clone()).is_err());
    assert!(Tca::new(0.5, 0.11, 2e-3, -1.0, Chirality::Extension, m).is_err());
}

#[test]
fn temperature_slope_matches_central_differences() {
    // both chiralities, on the law (delta >= 0), at the onset and on both
    // pieces of the contact branch, in the range and at its ends
    let eps = TcaAt::CONTACT_SMOOTHING;
    for chirality in [Chirality::Extension, Chirality::Contraction] {
        let tca = Tca::new(
            0.497,
            0.110,
            2e-3,
            300.0,
            chirality,
            Material::silver_coated_nylon(),
        )
        .unwrap();
        for temp in [25.0f64, 40.0, 95.0, 160.0] {
            for delta in [3e-3, 1e-4, 0.0, -0.4 * eps, -3.0 * eps] {
                let f = |t: f64| tca.at(t).unwrap().tension(delta).unwrap();
                // one-sided at the range's ends, central inside; h = 1e-3 C:
                // truncation h^2 |F'''| / 6 and rounding ulp(F) / h are both
                // below 1e-9 |F'| here (F, F', F''' are smooth polynomials in
                // T over tens of C), the contact branch's k_s (a difference
                // over 1e-9 L) adds ~1e-7 relative noise in k_s, ~1e-11 N/C
                let h: f64 = 1e-3;
                let (a, b) = ((temp - h).max(25.0), (temp + h).min(160.0));
                let fd = if b - a > 1.5 * h {
                    (f(b) - f(a)) / (b - a)
                } else {
                    // second-order one-sided difference
                    let s = if a == temp { 1.0 } else { -1.0 };
                    s * (-3.0 * f(temp) + 4.0 * f(temp + s * h) - f(temp + 2.0 * s * h)) / (2.0 * h)
                };
                let exact = tca
                    .at(temp)
                    .unwrap()
                    .tension_temperature_slope(delta)
                    .unwrap();
                assert!(
                    (exact - fd).abs() < 1e-6 * fd.abs() + 1e-10,
                    "{chirality:?} {temp} C, delta {delta}: {exact} vs {fd}"
                );
            }
        }
    }
}
