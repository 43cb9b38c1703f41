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

/// Two slack actuators (unknowns 6 and 7) 3 mm below their onsets; the
/// second's elongation row does not respond to either tension, so every
/// model's step puts it at `x_7 + r_7`, 2 mm below the onset.
fn two_slack_case() -> (f64, Vec<SlackTangent>, Vec<f64>, Vec<f64>, DMatrix<f64>) {
    let (len, a, x7, r7, jac7) = slack_case(0.5);
    let mut jac = DMatrix::zeros(8, 8);
    jac.view_mut((0, 0), (7, 7)).copy_from(&jac7);
    jac[(7, 7)] = -1.0;
    let mut ga = a.response.clone().insert_row(7, 0.0);
    ga[6] = 0.5;
    let a = SlackTangent { response: ga, ..a };
    let mut gb = DVector::from_column_slice(&[-0.1, 0.2, 0.3, -0.05, 0.1, 0.4, 0.0, 0.0]);
    gb[6] = 0.0; // no response of row 6 either: its step is the one-actuator case's
    let b = SlackTangent {
        index: 1,
        slope: 80.0,
        onset: 1e-3,
        response: gb,
    };
    let mut x = x7;
    x.push(-2e-3 / len);
    let mut r = r7;
    r.push(0.005); // s_7 = r_7: -2 mm + 1 mm, still slack
    (len, vec![a, b], x, r, jac)
}

/// A step carrying two slack actuators taut whose taut model lands one of
/// them slack again: that one is taken slack and the step re-solved with
/// the other's taut piece alone (main's step gave up: `None`).
#[test]
fn a_taut_model_that_lands_an_actuator_slack_is_re_solved_with_it_slack() {
    let (len, slack, x, r, jac) = two_slack_case();
    let dx = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.05, 0.05]; // both cross
    let step = taut_step(len, &slack, &x, &dx, &r, &jac).expect("one actuator lands taut");
    // the model with the first actuator's taut piece only, zero to
    // rounding (an 8x8 LU solve of entries of order one: 1e-12)
    let (a, b) = (&slack[0], &slack[1]);
    let s = DVector::from_column_slice(&step);
    let da = (x[6] + step[6]) * len;
    let model =
        DVector::from_column_slice(&r) + &jac * &s + &a.response * (a.slope * (da - a.onset));
    assert!(model.amax() < 1e-12, "model residual {}", model.amax());
    assert!((step[6] - 0.071 / 4.0).abs() < 1e-14, "s_6 {}", step[6]);
    assert!(da > a.onset, "the first lands taut: {da}");
    let db = (x[7] + step[7]) * len;
    assert!(db < b.onset, "the second stays slack: {db}");
    assert!(
        (step[7] - r[7]).abs() < 1e-15,
        "its slack row: s_7 {}",
        step[7]
    );
}
