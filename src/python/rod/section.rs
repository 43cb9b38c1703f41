//! Bindings of the cross-section and the actuator routing.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::python::errors::finite_output;
use crate::python::to_py::{call_repr, fields_dict, hash_by_text, reduce_with, vec3, Reduce};
use crate::python::Real;
use crate::rod::{Routing, Section};

/// What `__reduce__` of a section or routing returns: `(kind, values)`.
type KindValues = (&'static str, Vec<f64>);

/// `parameters`, `kind`, `__repr__` (by `$repr`), `__reduce__` (rebuilt by
/// `$restore` from `(kind, values)`) and `__hash__` of a value class whose core
/// value has `kind()` and `parameters()`; `$params_doc` and `$kind_doc` are
/// the getters' docstrings.
macro_rules! by_kind {
    ($ty:ty, $repr:ident, $restore:literal, $params_doc:literal, $kind_doc:literal) => {
        #[pymethods]
        impl $ty {
            #[doc = $params_doc]
            #[getter]
            fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
                fields_dict(py, &self.inner.parameters())
            }
            #[doc = $kind_doc]
            #[getter]
            fn kind(&self) -> &'static str {
                self.inner.kind()
            }
            fn __repr__(&self) -> String {
                $repr(&self.inner)
            }
            /// Pickle support: rebuilt by the same static constructor.
            fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py, KindValues> {
                let values = self
                    .inner
                    .parameters()
                    .into_iter()
                    .map(|(_, v)| v)
                    .collect();
                reduce_with(py, $restore, (self.inner.kind(), values))
            }
        }
        hash_by_text!($ty, |x| $repr(&x.inner));
    };
}

/// Cross-section of a body (sizes in m).
///
/// Build with `Section.circle`, `Section.rectangle` or `Section.custom`.
/// Value object: immutable, `==`, hashable, picklable; `repr` is the
/// constructor call.
///
/// Examples
/// --------
/// >>> s = tcarod.Section.circle(0.01)                 # 10 mm diameter [m]
/// >>> s
/// Section.circle(diameter=0.01)
/// >>> area, ix, iy, j = s.properties                  # [m^2], [m^4]
/// >>> round(area * 1e6, 2), round(ix * 1e12, 1)       # [mm^2], [mm^4]
/// (78.54, 490.9)
/// >>> tcarod.Section.rectangle(0.02, 0.01).edge_distance(0.0)   # along body x [m]
/// 0.01
#[pyclass(name = "Section", module = "tcarod._core", frozen, eq, hash)]
#[derive(Clone, PartialEq)]
pub struct PySection {
    pub(crate) inner: Section,
}

#[pymethods]
impl PySection {
    /// Solid circle of `diameter` [m].
    #[staticmethod]
    fn circle(diameter: Real) -> PyResult<Self> {
        Ok(PySection {
            inner: Section::circle(diameter.0)?,
        })
    }
    /// Solid rectangle: `width` [m] along body x, `height` [m] along body y.
    #[staticmethod]
    fn rectangle(width: Real, height: Real) -> PyResult<Self> {
        Ok(PySection {
            inner: Section::rectangle(width.0, height.0)?,
        })
    }
    /// User-given area [m^2], second moments about body x and y [m^4] and torsion constant [m^4].
    #[staticmethod]
    fn custom(area: Real, ix: Real, iy: Real, j: Real) -> PyResult<Self> {
        Ok(PySection {
            inner: Section::custom(area.0, ix.0, iy.0, j.0)?,
        })
    }
    /// Area, second moments and torsion constant of the section.
    ///
    /// Returns
    /// -------
    /// tuple of 4 float
    ///     `(area [m^2], ix [m^4], iy [m^4], j [m^4])`: second moments about
    ///     body x and y, torsion constant.
    #[getter]
    fn properties(&self) -> (f64, f64, f64, f64) {
        self.inner.properties()
    }
    /// Distance [m] from the centre line to the edge in body-frame direction angle `theta` [rad].
    fn edge_distance(&self, theta: Real) -> PyResult<f64> {
        let theta = crate::error::finite("theta [rad]", theta.0)?;
        Ok(finite_output(
            "edge_distance [m]",
            self.inner.edge_distance(theta),
        )?)
    }
}

by_kind!(
    PySection,
    section_repr,
    "_restore_section",
    "Constructor keywords, exactly as given.\n\n\
     Returns\n\
     -------\n\
     dict of str to float\n    \
     `{\"diameter\": ..}` [m], `{\"width\": .., \"height\": ..}` [m] or \
     `{\"area\": .. [m^2], \"ix\", \"iy\", \"j\": .. [m^4]}`.",
    "Which constructor built the section.\n\n\
     Returns\n\
     -------\n\
     str\n    \
     `\"circle\"`, `\"rectangle\"` or `\"custom\"` (no unit)."
);

/// `Section.circle(diameter=...)` etc. in Python syntax.
pub(crate) fn section_repr(s: &Section) -> String {
    call_repr(&format!("Section.{}", s.kind()), &s.parameters())
}

/// Rebuild a `Section` from `(kind, values)` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_section")]
pub(crate) fn restore_section(kind: &str, values: Vec<Real>) -> PyResult<PySection> {
    let values: Vec<f64> = values.into_iter().map(|r| r.0).collect();
    Ok(PySection {
        inner: Section::from_parameters(kind, &values)?,
    })
}

/// Body-frame path of an actuator: `Routing.straight(x, y)` or `Routing.helix(radius, rate, phase)`.
///
/// Offsets [m] from the centre line in the cross-section's body frame.
/// Value object: immutable, `==`, hashable, picklable.
///
/// Examples
/// --------
/// >>> r = tcarod.Routing.straight(0.004, 0.0)         # 4 mm off the centre line [m]
/// >>> r.kind, r.parameters
/// ('straight', {'x': 0.004, 'y': 0.0})
/// >>> h = tcarod.Routing.helix(0.004, 10.0)           # radius [m], rate [rad/m]
/// >>> r_s, dr_s, ddr_s = h.evaluate(0.0)              # [m], [-], [1/m] at s = 0
/// >>> r_s
/// array([0.004, 0.   , 0.   ])
#[pyclass(name = "Routing", module = "tcarod._core", frozen, eq, hash)]
#[derive(Clone, PartialEq)]
pub struct PyRouting {
    pub(crate) inner: Routing,
}

#[pymethods]
impl PyRouting {
    /// Parallel to the centre line at body-frame offset `(x, y)` [m].
    ///
    /// An offset above 1 m looks like millimetres and warns with
    /// `tcarod.UnitsWarning` (4 mm is 0.004 m).
    #[staticmethod]
    fn straight(py: Python<'_>, x: Real, y: Real) -> PyResult<Self> {
        PyRouting::checked(py, Routing::straight(x.0, y.0)?)
    }
    /// Helix of `radius` [m] turning at `rate` [rad/m] from angle `phase` [rad].
    ///
    /// A radius above 1 m looks like millimetres and warns with
    /// `tcarod.UnitsWarning`.
    #[staticmethod]
    #[pyo3(signature = (radius, rate, phase=Real(0.0)), text_signature = "(radius, rate, phase=0.0)")]
    fn helix(py: Python<'_>, radius: Real, rate: Real, phase: Real) -> PyResult<Self> {
        PyRouting::checked(py, Routing::helix(radius.0, rate.0, phase.0)?)
    }
    /// `(r, r', r'')` at arc length `s` [m] as three length-3 arrays (body frame).
    #[allow(clippy::type_complexity)]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        s: Real,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    )> {
        let s = crate::error::finite("s [m]", s.0)?;
        let (r, rp, rpp) = self.inner.eval(s);
        for (name, v) in [("r [m]", &r), ("r' [-]", &rp), ("r'' [1/m]", &rpp)] {
            for x in v.iter() {
                finite_output(name, *x)?;
            }
        }
        Ok((vec3(py, &r), vec3(py, &rp), vec3(py, &rpp)))
    }
}

impl PyRouting {
    /// `inner`, after a `UnitsWarning` if its distance looks like millimetres.
    fn checked(py: Python<'_>, inner: Routing) -> PyResult<Self> {
        if let Some(msg) = inner.units_warning() {
            crate::python::warn_units(py, msg)?;
        }
        Ok(PyRouting { inner })
    }
}

by_kind!(
    PyRouting,
    routing_repr,
    "_restore_routing",
    "Constructor keywords, exactly as given.\n\n\
     Returns\n\
     -------\n\
     dict of str to float\n    \
     `{\"x\": .., \"y\": ..}` [m] or \
     `{\"radius\": .. [m], \"rate\": .. [rad/m], \"phase\": .. [rad]}`.",
    "Which constructor built the routing.\n\n\
     Returns\n\
     -------\n\
     str\n    \
     `\"straight\"` or `\"helix\"` (no unit)."
);

/// `Routing.straight(x=..., y=...)` etc. in Python syntax.
pub(crate) fn routing_repr(r: &Routing) -> String {
    call_repr(&format!("Routing.{}", r.kind()), &r.parameters())
}

/// Rebuild a `Routing` from `(kind, values)` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_routing")]
pub(crate) fn restore_routing(kind: &str, values: Vec<Real>) -> PyResult<PyRouting> {
    let values: Vec<f64> = values.into_iter().map(|r| r.0).collect();
    Ok(PyRouting {
        inner: Routing::from_parameters(kind, &values)?,
    })
}
