//! Tests of the semismooth step across an actuator's onset ([`super::taut_step`]).

use super::{taut_step, SlackTangent};
use nalgebra::{DMatrix, DVector};

/// One slack actuator (unknown 6) below its onset, a Jacobian whose
/// column 6 is the slack one (`-e_6`), and the residual's response `g`
/// to the actuator's tension.
fn slack_case(g6: f64) -> (f64, SlackTangent, Vec<f64>, Vec<f64>, DMatrix<f64>) {
    let len = 0.2;
    let mut jac = DMatrix::from_fn(7, 7, |i, j| {
        if i == j {
            2.0 + i as f64
        } else {
            0.1 * (i + 2 * j) as f64
        }
    });
    // the slack column, and an elongation row that depends on the
    // elongation only (so that its step is known: see the tests)
    jac.column_mut(6).fill(0.0);
    jac.row_mut(6).fill(0.0);
    jac[(6, 6)] = -1.0;
    let response = DVector::from_column_slice(&[0.3, -0.2, 0.1, 0.05, -0.4, 0.2, g6]);
    let slack = SlackTangent {
        index: 0,
        slope: 50.0,
        onset: 1e-3,
        response,
    };
    let mut x = vec![0.01, -0.02, 0.0, 0.3, 0.0, -0.1, 0.0];
    x[6] = -2e-3 / len; // elongation -2 mm: slack, 3 mm below the onset
    let r = vec![0.02, 0.01, -0.03, 0.0, 0.05, -0.01, 0.004];
    (len, slack, x, r, jac)
}

#[test]
fn a_step_carrying_a_slack_actuator_taut_solves_the_taut_pieces_linear_model() {
    let (len, slack, x, r, jac) = slack_case(0.5);
    let dx = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.05]; // crosses: -2 mm + 10 mm
    let step = taut_step(len, std::slice::from_ref(&slack), &x, &dx, &r, &jac)
        .expect("a crossing step that lands taut");
    // the model with the taut piece extended: r + J s + g k (d + s_6 L - d0),
    // J the slack Jacobian (its column 6 carries no tension); zero to
    // rounding (a 7x7 LU solve of entries of order one: 1e-12)
    let s = DVector::from_column_slice(&step);
    let d_new = x[6] * len + step[6] * len;
    let model = DVector::from_column_slice(&r)
        + &jac * &s
        + &slack.response * (slack.slope * (d_new - slack.onset));
    assert!(model.amax() < 1e-12, "model residual {}", model.amax());
    // row 6 alone: r_6 - s_6 + g_6 k (d + s_6 L - d0) = 0, s_6 = 0.071 / 4
    assert!((step[6] - 0.071 / 4.0).abs() < 1e-14, "s_6 {}", step[6]);
    assert!(d_new > slack.onset, "lands taut: {d_new}");
}

#[test]
fn no_taut_step_where_the_step_stays_slack_or_the_taut_model_lands_slack() {
    let (len, slack, x, r, jac) = slack_case(0.5);
    let stays = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.005]; // -2 mm + 1 mm: still slack
    assert!(taut_step(len, std::slice::from_ref(&slack), &x, &stays, &r, &jac).is_none());
    // with no response of the elongation row (g_6 = 0) the taut model's
    // row 6 is r_6 - s_6 = 0: s_6 = r_6 = 0.004, an elongation of
    // -2 mm + 0.8 mm, below the 1 mm onset: not taken
    let (len, slack, x, r, jac) = slack_case(0.0);
    let crosses = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.05];
    assert!(taut_step(len, std::slice::from_ref(&slack), &x, &crosses, &r, &jac).is_none());
    assert!(taut_step(len, &[], &x, &crosses, &r, &jac).is_none());
}
