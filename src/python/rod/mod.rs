//! Bindings of the rod model: section and routing, body, actuators, robot
//! and its forward solution.

mod actuator;
mod body;
mod restore;
mod robot;
mod section;
mod solution;

use pyo3::prelude::*;

use crate::error::Error;
pub(crate) use crate::python::args::solve_options;
pub(crate) use actuator::PyActuator;
pub(crate) use body::PyBody;
pub(crate) use robot::PyRobot;
pub(crate) use section::{PyRouting, PySection};
pub(crate) use solution::{checked_solution, PySolution};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySection>()?;
    m.add_class::<PyRouting>()?;
    m.add_class::<PyBody>()?;
    m.add_class::<PyActuator>()?;
    m.add_class::<PyRobot>()?;
    m.add_function(wrap_pyfunction!(experiment_robot, m)?)?;
    m.add_function(wrap_pyfunction!(section::restore_section, m)?)?;
    m.add_function(wrap_pyfunction!(section::restore_routing, m)?)?;
    m.add_function(wrap_pyfunction!(actuator::restore_actuator, m)?)?;
    Ok(())
}

/// The forward solution, its unpickling and the plot and export hooks (the `_solution`
/// part of the module).
pub(crate) fn register_solution(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySolution>()?;
    m.add_function(wrap_pyfunction!(restore::restore_solution, m)?)?;
    m.add_function(wrap_pyfunction!(solution::register_plotter, m)?)?;
    m.add_function(wrap_pyfunction!(solution::register_exporter, m)?)?;
    m.add_function(wrap_pyfunction!(solution::restore_solution_verdict, m)?)?;
    Ok(())
}

/// The Rust fixture `name` of `src/experiments.rs` (`"fig6_circle"`,
/// `"fig6_square"`), standing upright under gravity if `gravity`. For tests
/// that check the Python fixtures of `tcarod.paper` against the Rust
/// ones; not public API.
#[pyfunction]
#[pyo3(name = "_experiment_robot")]
fn experiment_robot(name: &str, gravity: bool) -> PyResult<PyRobot> {
    let robot = match name {
        "fig6_circle" => crate::experiments::fig6_circle(gravity),
        "fig6_square" => crate::experiments::fig6_square(gravity),
        _ => {
            return Err(Error::input(
                "name",
                format!("unknown fixture {name:?} (fig6_circle, fig6_square)"),
            )
            .into())
        }
    };
    Ok(crate::python::fixtures::py_robot(robot))
}
