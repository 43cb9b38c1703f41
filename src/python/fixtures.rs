//! Bindings of the paper's fixtures (`src/experiments.rs`): the Python
//! package presents these instead of keeping its own copies. Functions are
//! prefixed `fixture_` in `tcarod._core`; constants come as one dict.

use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::args::count;
use super::material::PyMaterial;
use super::rod::{PyActuator, PyBody, PyRobot};
use super::tca::PyTca;
use super::{vec3_arg, Real, MAX_SEQUENCE};
use crate::error::{Error, Result};
use crate::experiments::{self as ex, Manipulator, TurnsReading};
use crate::rod::{Actuator, Robot};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fixture_constants, m)?)?;
    m.add_function(wrap_pyfunction!(fixture_manipulator, m)?)?;
    m.add_function(wrap_pyfunction!(fixture_leg_turns, m)?)?;
    m.add_function(wrap_pyfunction!(fixture_fig5_tca, m)?)?;
    m.add_function(wrap_pyfunction!(fixture_fig5_half_tca, m)?)?;
    m.add_function(wrap_pyfunction!(fixture_tendon_robot, m)?)?;
    Ok(())
}

/// A Python `Robot` of a core robot; an actuator anchored at the tip reads
/// as `Actuator.tca(...)` without `s_end`, as the Python fixtures build it,
/// so that the two compare equal.
pub(crate) fn py_robot(robot: Robot) -> PyRobot {
    let body = PyBody {
        inner: robot.body.clone(),
    };
    let actuators = robot
        .actuators
        .iter()
        .map(|a| {
            let mut a = a.clone();
            if a.s_end == robot.body.length {
                a.s_end = Actuator::TIP;
            }
            PyActuator::plain(a)
        })
        .collect();
    PyRobot {
        inner: Arc::new(robot),
        body,
        actuators,
    }
}

/// The paper's constants by name, SI units (temperatures in C).
///
/// Returns
/// -------
/// dict
///     ``ecoflex10_density`` [kg/m^3], ``ecoflex10_youngs_modulus`` [Pa],
///     ``ecoflex10_poisson`` [-], ``gravity`` [m/s^2], ``tca_offset`` [m],
///     ``u_leg_half_spacing`` [m], ``square_side`` [m], ``circle_diameter``
///     [m], ``circle_precurvature_radius`` [m], ``manipulator_turns`` [-],
///     ``turns_anchor_length`` [m], ``manipulator_coil_diameter`` [m],
///     ``manipulator_pitch_deg`` [deg], ``fig6_length``, ``fig8_length``,
///     ``table1_length`` [m], ``table1_mu`` [-], ``table1_fingers`` [-],
///     ``table1_contact_temperature`` [C], and the benchmarks' values.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> c = _core.fixture_constants()
/// >>> c["ecoflex10_youngs_modulus"], c["tca_offset"]      # [Pa], [m]
/// (37800.0, 0.003)
#[pyfunction]
fn fixture_constants(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let (psi, e, nu) = ex::ECOFLEX10;
    let d = PyDict::new(py);
    for (k, v) in [
        ("ecoflex10_density", psi),
        ("ecoflex10_youngs_modulus", e),
        ("ecoflex10_poisson", nu),
        ("gravity", ex::G0),
        ("tca_offset", ex::TCA_OFFSET),
        ("u_leg_half_spacing", ex::U_LEG_HALF_SPACING),
        ("square_side", ex::SQUARE_SIDE),
        ("circle_diameter", ex::CIRCLE_DIAMETER),
        ("circle_precurvature_radius", ex::CIRCLE_PRECURVATURE_RADIUS),
        ("manipulator_turns", ex::MANIPULATOR_TURNS),
        ("turns_anchor_length", ex::TURNS_ANCHOR_LENGTH),
        ("manipulator_coil_diameter", ex::MANIPULATOR_COIL_DIAMETER),
        ("manipulator_pitch_deg", ex::MANIPULATOR_PITCH_DEG),
        ("fig6_length", ex::FIG6_LENGTH),
        ("fig8_length", ex::FIG8_LENGTH),
        ("table1_length", ex::TABLE1_LENGTH),
        ("table1_mu", ex::TABLE1_MU),
        ("table1_fingers", ex::TABLE1_FINGERS as f64),
        (
            "table1_contact_temperature",
            ex::table1_contact_temperature(),
        ),
    ] {
        d.set_item(k, v)?;
    }
    d.set_item("table1_masses", ex::TABLE1_MASSES.to_vec())?;
    d.set_item("steel_tendon_tensions", ex::STEEL_TENDON_TENSIONS.to_vec())?;
    d.set_item(
        "table1_paper_predictions",
        ex::TABLE1_PAPER_PREDICTIONS.to_vec(),
    )?;
    d.set_item("table1_normal", ex::TABLE1_NORMAL.to_vec())?;
    Ok(d)
}

/// `"per_tca"`, `"per_leg"` or `"per_length"` as a [`TurnsReading`].
fn parse_turns_reading(name: &str) -> Result<TurnsReading> {
    match name {
        "per_tca" => Ok(TurnsReading::PerTca),
        "per_leg" => Ok(TurnsReading::PerLeg),
        "per_length" => Ok(TurnsReading::PerLength),
        _ => Err(Error::input(
            "turns_reading",
            format!("{name:?} is not one of 'per_tca', 'per_leg', 'per_length'"),
        )),
    }
}

/// One of the paper's manipulator designs, with any parameter replaced.
///
/// Parameters
/// ----------
/// name : {"square", "fig6_square", "fig6_circle", "fig8", "table1_finger"}
///     The design: the Fig. 6 square and circle manipulators, the Fig. 8
///     blocked-force manipulator, the Table I gripper finger.
/// length : float, optional
///     Body length [m] (default the design's; ``"square"``: 40 mm).
/// gravity : sequence of 3 float, optional
///     Gravity [m/s^2] in the body-aligned world frame (default: upright,
///     the finger hanging).
/// material : Material, optional
///     TCA fibre material (default: the documented default material).
/// youngs_modulus : float, optional
///     Body Young's modulus [Pa].
/// tca_offset : float, optional
///     TCA distance from the neutral axis [m].
/// coil_diameter : float, optional
///     TCA coil diameter [m].
/// turns_reading : {"per_tca", "per_leg", "per_length"}, optional
///     How the paper's 76.4 turns are read (default ``"per_tca"``).
///
/// Returns
/// -------
/// Robot
///     The design.
///
/// Raises
/// ------
/// ValueError
///     An unknown ``name`` or ``turns_reading``, or a value out of range.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> robot = _core.fixture_manipulator("fig6_square")
/// >>> robot.body.length, len(robot.actuators)     # [m], the U-shaped TCA's two legs
/// (0.04, 2)
#[pyfunction]
#[pyo3(signature = (name, *, length=None, gravity=None, material=None, youngs_modulus=None, tca_offset=None,
    coil_diameter=None, turns_reading="per_tca"),
    text_signature = "(name, *, length=None, gravity=None, material=None, youngs_modulus=None, tca_offset=None, \
        coil_diameter=None, turns_reading='per_tca')")]
#[allow(clippy::too_many_arguments)]
fn fixture_manipulator(
    name: &str,
    length: Option<Real>,
    gravity: Option<Bound<'_, PyAny>>,
    material: Option<PyMaterial>,
    youngs_modulus: Option<Real>,
    tca_offset: Option<Real>,
    coil_diameter: Option<Real>,
    turns_reading: &str,
) -> PyResult<PyRobot> {
    let mut m = match name {
        "square" | "fig6_square" => Manipulator::square(ex::FIG6_LENGTH),
        "fig6_circle" => Manipulator::fig6_circle(),
        "fig8" => Manipulator::square(ex::FIG8_LENGTH),
        "table1_finger" => Manipulator::table1_finger(),
        _ => {
            return Err(Error::input(
                "name",
                format!(
                    "{name:?} is not one of 'square', 'fig6_circle', 'fig6_square', 'fig8', \
                     'table1_finger'"
                ),
            )
            .into())
        }
    };
    if let Some(l) = length {
        m.length = crate::error::positive("length [m]", l.0)?;
    }
    m.gravity = vec3_arg("gravity", gravity.as_ref(), m.gravity)?;
    if let Some(mat) = material {
        m.material = mat.inner;
    }
    if let Some(e) = youngs_modulus {
        m.youngs_modulus = e.0;
    }
    if let Some(x) = tca_offset {
        m.tca_offset = x.0;
    }
    if let Some(d) = coil_diameter {
        m.coil_diameter = d.0;
    }
    m.turns_reading = parse_turns_reading(turns_reading)?;
    Ok(py_robot(m.build()?))
}

/// Turns of one leg of a manipulator TCA [-].
///
/// Parameters
/// ----------
/// length : float
///     Coiled length of the leg [m].
/// legs : int
///     Legs of the TCA (1 straight, 2 U-shaped).
/// reading : {"per_tca", "per_leg", "per_length"}, optional
///     How the paper's 76.4 turns are read (default ``"per_tca"``).
///
/// Returns
/// -------
/// float
///     Turns of the leg [-].
///
/// Raises
/// ------
/// ValueError
///     A non-positive ``length``, ``legs`` < 1 or an unknown ``reading``.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> _core.fixture_leg_turns(0.040, 2), _core.fixture_leg_turns(0.060, 1, "per_length")
/// (38.2, 114.6...)
#[pyfunction]
#[pyo3(signature = (length, legs, reading="per_tca"))]
fn fixture_leg_turns(length: Real, legs: Bound<'_, PyAny>, reading: &str) -> PyResult<f64> {
    let length = crate::error::positive("length [m]", length.0)?;
    let legs = count("legs", &legs, 1, MAX_SEQUENCE)?;
    Ok(parse_turns_reading(reading)?.leg_turns(length, legs))
}

/// The whole Fig. 5 TCA of ``threads`` threads.
///
/// Parameters
/// ----------
/// threads : {3, 4}
///     Threads of the TCA.
///
/// Returns
/// -------
/// Tca
///     The TCA.
///
/// Raises
/// ------
/// ValueError
///     ``threads`` other than 3 or 4.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> _core.fixture_fig5_tca(3).chirality
/// 'extension'
#[pyfunction]
fn fixture_fig5_tca(threads: Bound<'_, PyAny>) -> PyResult<PyTca> {
    let threads = fig5_threads(&threads)?;
    Ok(PyTca {
        inner: ex::fig5_tca(threads),
    })
}

/// One folded half of the Fig. 5 TCA of ``threads`` threads.
///
/// ``Tca.segment(0.5)`` of the whole: the displacement measured is one
/// half's elongation.
///
/// Parameters
/// ----------
/// threads : {3, 4}
///     Threads of the TCA.
///
/// Returns
/// -------
/// Tca
///     The half TCA.
///
/// Raises
/// ------
/// ValueError
///     ``threads`` other than 3 or 4.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> half, whole = _core.fixture_fig5_half_tca(4), _core.fixture_fig5_tca(4)
/// >>> round(half.coiled_length / whole.coiled_length, 6)
/// 0.5
#[pyfunction]
fn fixture_fig5_half_tca(threads: Bound<'_, PyAny>) -> PyResult<PyTca> {
    let threads = fig5_threads(&threads)?;
    Ok(PyTca {
        inner: ex::fig5_half_tca(threads),
    })
}

/// The Fig. 5 thread count, 3 or 4.
fn fig5_threads(obj: &Bound<'_, PyAny>) -> PyResult<u32> {
    Ok(count("threads", obj, 3, 4)? as u32)
}

/// A tendon robot of the speed benchmarks (not from the paper).
///
/// Parameters
/// ----------
/// name : {"steel", "soft"}
///     ``"steel"``: L 0.5 m, radius 1 mm, E 200 GPa, G 80 GPa, 8000 kg/m^3,
///     gravity along ``+x``, four tendons at 15.06 mm on spacer disks
///     (benchmark tensions ``fixture_constants()["steel_tendon_tensions"]``
///     [N]); ``"soft"``: 0.2 m, 10 mm, 1 MPa, one tendon at 4 mm.
///
/// Returns
/// -------
/// Robot
///     The robot.
///
/// Raises
/// ------
/// ValueError
///     An unknown ``name``.
///
/// Examples
/// --------
/// >>> from tcarod import _core
/// >>> robot = _core.fixture_tendon_robot("soft")
/// >>> robot.body.length, len(robot.actuators)     # [m]
/// (0.2, 1)
#[pyfunction]
fn fixture_tendon_robot(name: &str) -> PyResult<PyRobot> {
    let robot = match name {
        "steel" => ex::steel_tendon_robot(),
        "soft" => ex::soft_tendon_robot(),
        _ => {
            return Err(
                Error::input("name", format!("{name:?} is not one of 'steel', 'soft'")).into(),
            )
        }
    };
    Ok(py_robot(robot))
}
