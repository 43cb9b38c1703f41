//! Bindings of the rod model and the shooting solver.

use std::sync::{Arc, OnceLock};

use nalgebra::{Matrix3, Vector3};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::errors::finite_output;
use super::tca::PyTca;
use super::{count_or, hash_text, pf, ps, pv, reals, vec3_arg, Real};
use crate::error::{Error, Result};
use crate::rod::{
    Actuator, Body, ConstantTension, ForceLaw, LinearTendon, Robot, Routing, Section, TcaLaw,
};
use crate::shooting::{Solution, SolveOptions};

/// What `__reduce__` returns: a rebuilding callable and its arguments.
type Reduce<'py, A> = PyResult<(Bound<'py, PyAny>, A)>;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySection>()?;
    m.add_class::<PyRouting>()?;
    m.add_class::<PyBody>()?;
    m.add_class::<PyActuator>()?;
    m.add_class::<PyRobot>()?;
    m.add_class::<PySolution>()?;
    m.add_function(wrap_pyfunction!(experiment_robot, m)?)?;
    m.add_function(wrap_pyfunction!(restore_section, m)?)?;
    m.add_function(wrap_pyfunction!(restore_routing, m)?)?;
    m.add_function(wrap_pyfunction!(restore_actuator, m)?)?;
    m.add_function(wrap_pyfunction!(restore_solution, m)?)?;
    Ok(())
}

/// The Rust fixture `name` of `src/experiments.rs` (`"fig6_circle"`,
/// `"fig6_square"`), standing upright under gravity if `gravity`. For tests
/// that check the Python fixtures of `tcarod.experiments` against the Rust
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
    let body = PyBody {
        inner: robot.body.clone(),
    };
    let actuators = robot
        .actuators
        .iter()
        .map(|a| PyActuator::plain(a.clone(), true))
        .collect();
    Ok(PyRobot {
        inner: Arc::new(robot),
        body,
        actuators,
    })
}

/// Cross-section of a body. Build with `Section.circle`, `Section.rectangle`
/// or `Section.custom`.
#[pyclass(name = "Section", module = "tcarod._core", frozen)]
#[derive(Clone)]
pub struct PySection {
    pub(crate) inner: Section,
}

#[pymethods]
impl PySection {
    /// Solid circle of `diameter` [m].
    #[staticmethod]
    fn circle(diameter: Real) -> PyResult<Self> {
        let diameter = crate::error::positive("diameter [m]", diameter.0)?;
        Ok(checked_section(
            "diameter [m]",
            Section::Circle { diameter },
        )?)
    }
    /// Solid rectangle: `width` [m] along body x, `height` [m] along body y.
    #[staticmethod]
    fn rectangle(width: Real, height: Real) -> PyResult<Self> {
        let width = crate::error::positive("width [m]", width.0)?;
        let height = crate::error::positive("height [m]", height.0)?;
        Ok(checked_section(
            "width [m] / height [m]",
            Section::Rectangle { width, height },
        )?)
    }
    /// User-given area [m^2], second moments about body x and y [m^4] and torsion constant [m^4].
    #[staticmethod]
    fn custom(area: Real, ix: Real, iy: Real, j: Real) -> PyResult<Self> {
        let (area, ix, iy, j) = (area.0, ix.0, iy.0, j.0);
        for (n, v) in [
            ("area [m^2]", area),
            ("ix [m^4]", ix),
            ("iy [m^4]", iy),
            ("j [m^4]", j),
        ] {
            crate::error::positive(n, v)?;
        }
        Ok(checked_section(
            "area [m^2]",
            Section::Custom { area, ix, iy, j },
        )?)
    }
    /// `(area [m^2], ix [m^4], iy [m^4], j [m^4])`.
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
    /// Constructor keywords, exactly as given: `{"diameter": ..}` [m],
    /// `{"width": .., "height": ..}` [m] or `{"area": .. [m^2], "ix", "iy", "j": .. [m^4]}`.
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        match self.inner {
            Section::Circle { diameter } => d.set_item("diameter", diameter)?,
            Section::Rectangle { width, height } => {
                d.set_item("width", width)?;
                d.set_item("height", height)?;
            }
            Section::Custom { area, ix, iy, j } => {
                for (k, v) in [("area", area), ("ix", ix), ("iy", iy), ("j", j)] {
                    d.set_item(k, v)?;
                }
            }
        }
        Ok(d)
    }
    /// `"circle"`, `"rectangle"` or `"custom"`.
    #[getter]
    fn kind(&self) -> &'static str {
        match self.inner {
            Section::Circle { .. } => "circle",
            Section::Rectangle { .. } => "rectangle",
            Section::Custom { .. } => "custom",
        }
    }
    fn __repr__(&self) -> String {
        match self.inner {
            Section::Circle { diameter } => format!("Section.circle(diameter={})", pf(diameter)),
            Section::Rectangle { width, height } => format!(
                "Section.rectangle(width={}, height={})",
                pf(width),
                pf(height)
            ),
            Section::Custom { area, ix, iy, j } => format!(
                "Section.custom(area={}, ix={}, iy={}, j={})",
                pf(area),
                pf(ix),
                pf(iy),
                pf(j)
            ),
        }
    }
    /// Pickle support: rebuilt by the same static constructor.
    fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py, (&'static str, Vec<f64>)> {
        let f = py.import("tcarod._core")?.getattr("_restore_section")?;
        let v = match self.inner {
            Section::Circle { diameter } => vec![diameter],
            Section::Rectangle { width, height } => vec![width, height],
            Section::Custom { area, ix, iy, j } => vec![area, ix, iy, j],
        };
        Ok((f, (self.kind(), v)))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> Option<bool> {
        other
            .cast::<PySection>()
            .ok()
            .map(|o| o.get().inner == self.inner)
    }
    fn __hash__(&self) -> u64 {
        hash_text(&self.__repr__())
    }
}

/// Rebuild a `Section` from `(kind, values)` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_section")]
fn restore_section(kind: &str, values: Vec<Real>) -> PyResult<PySection> {
    let v: Vec<Real> = values;
    match (kind, v.as_slice()) {
        ("circle", [d]) => PySection::circle(*d),
        ("rectangle", [w, h]) => PySection::rectangle(*w, *h),
        ("custom", [a, ix, iy, j]) => PySection::custom(*a, *ix, *iy, *j),
        _ => Err(Error::input(
            "kind",
            format!("{kind:?} with {} values is not a section", v.len()),
        )
        .into()),
    }
}

/// A section whose derived properties (area, second moments, edge distance)
/// are finite and positive: a size so small or large that they under- or
/// overflow is rejected, naming `name`.
fn checked_section(name: &str, inner: Section) -> Result<PySection> {
    let (a, ix, iy, j) = inner.properties();
    for v in [a, ix, iy, j, inner.edge_distance(0.0)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(Error::input(
                name,
                format!("derived section property {v} (area, second moment or edge distance) is not finite and > 0 in double precision"),
            ));
        }
    }
    Ok(PySection { inner })
}

/// Body-frame path of an actuator: `Routing.straight(x, y)` or `Routing.helix(radius, rate, phase)`.
#[pyclass(name = "Routing", module = "tcarod._core", frozen)]
#[derive(Clone)]
pub struct PyRouting {
    pub(crate) inner: Routing,
}

#[pymethods]
impl PyRouting {
    /// Parallel to the centre line at body-frame offset `(x, y)` [m].
    #[staticmethod]
    fn straight(x: Real, y: Real) -> PyResult<Self> {
        let x = crate::error::finite("x [m]", x.0)?;
        let y = crate::error::finite("y [m]", y.0)?;
        Ok(PyRouting {
            inner: Routing::Straight { x, y },
        })
    }
    /// Helix of `radius` [m] turning at `rate` [rad/m] from angle `phase` [rad].
    #[staticmethod]
    #[pyo3(signature = (radius, rate, phase=Real(0.0)), text_signature = "(radius, rate, phase=0.0)")]
    fn helix(radius: Real, rate: Real, phase: Real) -> PyResult<Self> {
        let radius = crate::error::non_negative("radius [m]", radius.0)?;
        let rate = crate::error::finite("rate [rad/m]", rate.0)?;
        let phase = crate::error::finite("phase [rad]", phase.0)?;
        Ok(PyRouting {
            inner: Routing::Helix {
                radius,
                rate,
                phase,
            },
        })
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
    fn __repr__(&self) -> String {
        match self.inner {
            Routing::Straight { x, y } => format!("Routing.straight(x={}, y={})", pf(x), pf(y)),
            Routing::Helix {
                radius,
                rate,
                phase,
            } => format!(
                "Routing.helix(radius={}, rate={}, phase={})",
                pf(radius),
                pf(rate),
                pf(phase)
            ),
        }
    }
    /// Constructor keywords, exactly as given: `{"x": .., "y": ..}` [m] or
    /// `{"radius": .. [m], "rate": .. [rad/m], "phase": .. [rad]}`.
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        match self.inner {
            Routing::Straight { x, y } => {
                d.set_item("x", x)?;
                d.set_item("y", y)?;
            }
            Routing::Helix {
                radius,
                rate,
                phase,
            } => {
                d.set_item("radius", radius)?;
                d.set_item("rate", rate)?;
                d.set_item("phase", phase)?;
            }
        }
        Ok(d)
    }
    /// `"straight"` or `"helix"`.
    #[getter]
    fn kind(&self) -> &'static str {
        match self.inner {
            Routing::Straight { .. } => "straight",
            Routing::Helix { .. } => "helix",
        }
    }
    /// Pickle support: rebuilt by the same static constructor.
    fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py, (&'static str, Vec<f64>)> {
        let f = py.import("tcarod._core")?.getattr("_restore_routing")?;
        let v = match self.inner {
            Routing::Straight { x, y } => vec![x, y],
            Routing::Helix {
                radius,
                rate,
                phase,
            } => vec![radius, rate, phase],
        };
        Ok((f, (self.kind(), v)))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> Option<bool> {
        other
            .cast::<PyRouting>()
            .ok()
            .map(|o| o.get().inner == self.inner)
    }
    fn __hash__(&self) -> u64 {
        hash_text(&self.__repr__())
    }
}

/// Rebuild a `Routing` from `(kind, values)` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_routing")]
fn restore_routing(kind: &str, values: Vec<Real>) -> PyResult<PyRouting> {
    match (kind, values.as_slice()) {
        ("straight", [x, y]) => PyRouting::straight(*x, *y),
        ("helix", [r, k, p]) => PyRouting::helix(*r, *k, *p),
        _ => Err(Error::input(
            "kind",
            format!("{kind:?} with {} values is not a routing", values.len()),
        )
        .into()),
    }
}

fn vec3<'py>(py: Python<'py>, v: &Vector3<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v.as_slice())
}

/// Error unless the body's derived quantities (stiffnesses, weight per
/// length) are finite and the stiffnesses positive, so that no getter can
/// return inf or NaN.
fn check_derived(b: &Body) -> Result<()> {
    let (kv, kw) = b.stiffness();
    for k in 0..3 {
        for (name, v) in [
            ("stiffness K_nu [N]", kv[(k, k)]),
            ("stiffness K_omega [N m^2]", kw[(k, k)]),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::input(name, format!("is {v}: youngs_modulus / shear_modulus times the section properties leave double range")));
            }
        }
    }
    for (k, x) in b.distributed_load().iter().enumerate() {
        finite_output(
            &format!("distributed_load [N/m][{k}] (density x area x gravity)"),
            *x,
        )?;
    }
    Ok(())
}

/// The soft body (Cosserat rod): geometry, material, reference strains, loads.
///
/// `Body(length, section, youngs_modulus, *, poisson=None, shear_modulus=None,
/// density=0.0, shear_coefficient=1.0, nu_star=None, omega_star=None,
/// gravity=None, distributed_force=None, distributed_moment=None,
/// tip_force=None, tip_moment=None)`
///
/// * `length` [m] of the centre line; `section` a `Section` (sizes in m);
///   `youngs_modulus` E_B [Pa]; `poisson` [-] (default 0.5, incompressible
///   silicone) or `shear_modulus` G_B [Pa], not both; `density` [kg/m^3];
///   `shear_coefficient` [-] (Timoshenko; 1 as in the paper).
/// * `nu_star` [-] and `omega_star` [1/m]: reference linear and angular
///   strains, body frame (default `(0, 0, 1)` and zero: straight).
/// * `gravity` [m/s^2], `distributed_force` [N/m], `distributed_moment`
///   [N m/m], `tip_force` [N], `tip_moment` [N m]: world frame, length-3
///   sequences (default zero).
///
/// SI units: a body whose length or section looks like millimetres (length
/// > 10 m, section size > 1 m) warns with `tcarod.UnitsWarning`. Value object:
/// immutable, `==`, hashable, picklable; `repr` is a constructor call.
#[pyclass(name = "Body", module = "tcarod._core", frozen)]
#[derive(Clone)]
pub struct PyBody {
    pub(crate) inner: Body,
}

#[pymethods]
impl PyBody {
    #[new]
    #[pyo3(signature = (length, section, youngs_modulus, *, poisson=None, shear_modulus=None, density=Real(0.0),
        shear_coefficient=Real(1.0), nu_star=None, omega_star=None, gravity=None, distributed_force=None,
        distributed_moment=None, tip_force=None, tip_moment=None),
        text_signature = "(length, section, youngs_modulus, *, poisson=None, shear_modulus=None, density=0.0, \
            shear_coefficient=1.0, nu_star=None, omega_star=None, gravity=None, distributed_force=None, \
            distributed_moment=None, tip_force=None, tip_moment=None)")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        length: Real,
        section: PySection,
        youngs_modulus: Real,
        poisson: Option<Real>,
        shear_modulus: Option<Real>,
        density: Real,
        shear_coefficient: Real,
        nu_star: Option<Bound<'_, PyAny>>,
        omega_star: Option<Bound<'_, PyAny>>,
        gravity: Option<Bound<'_, PyAny>>,
        distributed_force: Option<Bound<'_, PyAny>>,
        distributed_moment: Option<Bound<'_, PyAny>>,
        tip_force: Option<Bound<'_, PyAny>>,
        tip_moment: Option<Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let (length, youngs_modulus, density, shear_coefficient) =
            (length.0, youngs_modulus.0, density.0, shear_coefficient.0);
        let (poisson, shear_modulus) = (poisson.map(|r| r.0), shear_modulus.map(|r| r.0));
        crate::error::positive("length [m]", length)?;
        let mut b = match (poisson, shear_modulus) {
            (Some(_), Some(_)) => {
                return Err(
                    Error::input("poisson / shear_modulus", "give one of them, not both").into(),
                )
            }
            (p, None) => Body::new(
                length,
                section.inner,
                youngs_modulus,
                p.unwrap_or(0.5),
                density,
            )?,
            (None, Some(g)) => {
                let mut b = Body::new(length, section.inner, youngs_modulus, 0.0, density)?;
                b.shear_modulus = g;
                b
            }
        };
        let v = |name: &str, o: &Option<Bound<'_, PyAny>>, d: [f64; 3]| {
            vec3_arg(name, o.as_ref(), d).map(Vector3::from)
        };
        b.shear_coefficient = shear_coefficient;
        b.nu_star = v("nu_star", &nu_star, [0.0, 0.0, 1.0])?;
        b.omega_star = v("omega_star", &omega_star, [0.0; 3])?;
        b.gravity = v("gravity", &gravity, [0.0; 3])?;
        b.distributed_force = v("distributed_force", &distributed_force, [0.0; 3])?;
        b.distributed_moment = v("distributed_moment", &distributed_moment, [0.0; 3])?;
        b.tip_force = v("tip_force", &tip_force, [0.0; 3])?;
        b.tip_moment = v("tip_moment", &tip_moment, [0.0; 3])?;
        b.validate()?;
        check_derived(&b)?;
        if let Some(msg) = crate::validate::body_looks_like_mm(&b) {
            super::warn_units(py, msg)?;
        }
        Ok(PyBody { inner: b })
    }

    /// A copy with some fields replaced (same keywords as the constructor).
    #[pyo3(signature = (**changes))]
    fn replace(&self, py: Python<'_>, changes: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let kw = self.kwargs(py)?;
        if let Some(c) = changes {
            for (k, v) in c.iter() {
                let key: String = k.extract()?;
                if !kw.contains(&key)? {
                    return Err(Error::input("replace", format!("unknown field {key:?}")).into());
                }
                kw.set_item(key, v)?;
            }
        }
        let cls = py.get_type::<PyBody>();
        let obj = cls.call((), Some(&kw))?;
        let b = obj.cast::<PyBody>()?;
        Ok(b.get().clone())
    }

    /// Constructor keywords of this body (for `replace` and serialisation).
    fn kwargs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let b = &self.inner;
        let d = PyDict::new(py);
        d.set_item("length", b.length)?;
        d.set_item("section", PySection { inner: b.section })?;
        d.set_item("youngs_modulus", b.youngs_modulus)?;
        d.set_item("shear_modulus", b.shear_modulus)?;
        d.set_item("density", b.density)?;
        d.set_item("shear_coefficient", b.shear_coefficient)?;
        for (k, v) in [
            ("nu_star", b.nu_star),
            ("omega_star", b.omega_star),
            ("gravity", b.gravity),
            ("distributed_force", b.distributed_force),
            ("distributed_moment", b.distributed_moment),
            ("tip_force", b.tip_force),
            ("tip_moment", b.tip_moment),
        ] {
            d.set_item(k, (v.x, v.y, v.z))?;
        }
        Ok(d)
    }

    /// Length of the centre line [m].
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length
    }
    /// The cross-section (`Section`).
    #[getter]
    fn section(&self) -> PySection {
        PySection {
            inner: self.inner.section,
        }
    }
    /// Young's modulus E_B [Pa].
    #[getter]
    fn youngs_modulus(&self) -> f64 {
        self.inner.youngs_modulus
    }
    /// Shear modulus G_B [Pa].
    #[getter]
    fn shear_modulus(&self) -> f64 {
        self.inner.shear_modulus
    }
    /// Density [kg/m^3].
    #[getter]
    fn density(&self) -> f64 {
        self.inner.density
    }
    /// Reference linear strain `nu*` [-] (body frame), shape `(3,)`.
    #[getter]
    fn nu_star<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.nu_star)
    }
    /// Reference angular strain `omega*` [1/m] (body frame), shape `(3,)`.
    #[getter]
    fn omega_star<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.omega_star)
    }
    /// Gravitational acceleration [m/s^2] (world frame), shape `(3,)`.
    #[getter]
    fn gravity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.gravity)
    }
    /// Force applied to the tip [N] (world frame), shape `(3,)`.
    #[getter]
    fn tip_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.tip_force)
    }
    /// Moment applied to the tip [N m] (world frame), shape `(3,)`.
    #[getter]
    fn tip_moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.tip_moment)
    }
    /// Total distributed force `psi A g + f` [N/m], world frame.
    #[getter]
    fn distributed_load<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.distributed_load())
    }
    /// Distributed moment [N m/m] (world frame), shape `(3,)`.
    #[getter]
    fn distributed_moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.distributed_moment)
    }
    /// `(K_nu, K_omega)` diagonal stiffness matrices, 3x3 each ([N], [N m^2]).
    fn stiffness<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>) {
        let (a, b) = self.inner.stiffness();
        (mat3(py, &a), mat3(py, &b))
    }
    /// Shear coefficient [-] (Timoshenko).
    #[getter]
    fn shear_coefficient(&self) -> f64 {
        self.inner.shear_coefficient
    }
    /// Distributed force [N/m] besides gravity (world frame), shape `(3,)`.
    #[getter]
    fn distributed_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.distributed_force)
    }
    fn __repr__(&self) -> String {
        body_repr(&self.inner)
    }
    /// Constructor arguments, for pickle and copy.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, pyo3::types::PyTuple>, Bound<'py, PyDict>)> {
        Ok((pyo3::types::PyTuple::empty(py), self.kwargs(py)?))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> Option<bool> {
        other
            .cast::<PyBody>()
            .ok()
            .map(|o| o.get().inner == self.inner)
    }
    fn __hash__(&self) -> u64 {
        hash_text(&body_repr(&self.inner))
    }
}

/// Constructor call of a body, defaults left out (round-trips with `eval`).
fn body_repr(b: &Body) -> String {
    let section = PySection { inner: b.section }.__repr__();
    let mut out = format!(
        "Body(length={}, section={section}, youngs_modulus={}, shear_modulus={}",
        pf(b.length),
        pf(b.youngs_modulus),
        pf(b.shear_modulus)
    );
    if b.density != 0.0 {
        out += &format!(", density={}", pf(b.density));
    }
    if b.shear_coefficient != 1.0 {
        out += &format!(", shear_coefficient={}", pf(b.shear_coefficient));
    }
    for (k, v, d) in [
        ("nu_star", b.nu_star, Vector3::z()),
        ("omega_star", b.omega_star, Vector3::zeros()),
        ("gravity", b.gravity, Vector3::zeros()),
        ("distributed_force", b.distributed_force, Vector3::zeros()),
        ("distributed_moment", b.distributed_moment, Vector3::zeros()),
        ("tip_force", b.tip_force, Vector3::zeros()),
        ("tip_moment", b.tip_moment, Vector3::zeros()),
    ] {
        if v != d {
            out += &format!(", {k}={}", pv(v.as_slice()));
        }
    }
    out + ")"
}

fn mat3<'py>(py: Python<'py>, m: &Matrix3<f64>) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<Vec<f64>> = (0..3)
        .map(|i| (0..3).map(|j| m[(i, j)]).collect())
        .collect();
    PyArray2::from_vec2(py, &rows).expect("3x3")
}

/// A string-like actuator embedded in the body. Build with `Actuator.tca`,
/// `Actuator.tendon` (constant tension) or `Actuator.linear_tendon`.
///
/// Sign conventions: tensions [N] are positive when the actuator pulls its
/// anchors together (negative: it pushes); elongations [m] are the
/// actuator's current length minus its relaxed length, so a TCA with its
/// coils touching has elongation 0, a stretched (pre-tensioned) one a
/// positive elongation, and inside a body a pressed one a small negative
/// elongation (the stiff coil-contact column).
///
/// Pre-tension: a contraction TCA does nothing when heated with its coils
/// touching (it cannot get shorter); install it stretched with
/// `Actuator.tca(..., pretension_n=F)`: the TCA carries tension `F` [N] at
/// the reference temperature in the body's undeformed reference shape (the
/// body then deforms under it, so the equilibrium tension is lower). This is
/// the paper's constant length ratio `L_i` (eq 18), which `length_ratio` sets
/// directly. Value object: immutable, `==`, picklable.
#[pyclass(name = "Actuator", module = "tcarod._core", frozen)]
#[derive(Clone)]
pub struct PyActuator {
    pub(crate) inner: Actuator,
    tca: Option<PyTca>,
    /// Pre-tension [N] at the reference temperature (TCAs), resolved to a
    /// length ratio when the robot is assembled.
    pub(crate) pretension: Option<f64>,
    /// Stiffness [N/m] of a linear tendon.
    stiffness: Option<f64>,
    /// Whether `s_end` was given (otherwise: anchored at the tip).
    s_end_given: bool,
}

fn make_actuator(
    routing: PyRouting,
    s_start: Real,
    s_end: Option<Real>,
    length_ratio: Option<Real>,
    law: Arc<dyn ForceLaw>,
) -> PyResult<Actuator> {
    let (s_start, s_end, length_ratio) = (s_start.0, s_end.map(|r| r.0), length_ratio.map(|r| r.0));
    crate::error::non_negative("s_start [m]", s_start)?;
    let mut a = Actuator::new(routing.inner, s_start, s_end.unwrap_or(f64::INFINITY), law);
    if let Some(e) = s_end {
        crate::error::positive("s_end [m]", e)?;
    }
    if let Some(l) = length_ratio {
        crate::error::positive("length_ratio [-]", l)?;
    }
    a.length_ratio = length_ratio;
    Ok(a)
}

impl PyActuator {
    fn plain(inner: Actuator, s_end_given: bool) -> Self {
        PyActuator {
            inner,
            tca: None,
            pretension: None,
            stiffness: None,
            s_end_given,
        }
    }
    /// Everything that defines the actuator, as text (for `==` and hash).
    fn identity(&self) -> String {
        format!(
            "{:?} {:?} {:?} {}",
            self.inner, self.pretension, self.stiffness, self.s_end_given
        )
    }
    fn s_end_arg(&self) -> Option<f64> {
        self.s_end_given.then_some(self.inner.s_end)
    }
}

#[pymethods]
impl PyActuator {
    /// A TCA whose input is its temperature [C], anchored from `s_start` [m]
    /// to `s_end` [m] (`None`: the tip). `length_ratio`: the paper's constant
    /// `L_i` [-] (eq 18; default: computed pointwise so that the reference
    /// shape is unstrained). `pretension_n`: tension [N] the TCA carries at the
    /// reference temperature in the undeformed body (needed for contraction
    /// TCAs to act; sets `L_i`, so not together with `length_ratio`).
    #[staticmethod]
    #[pyo3(signature = (tca, routing, s_start=Real(0.0), s_end=None, length_ratio=None, *, pretension_n=None),
        text_signature = "(tca, routing, s_start=0.0, s_end=None, length_ratio=None, *, pretension_n=None)")]
    fn tca(
        tca: PyTca,
        routing: PyRouting,
        s_start: Real,
        s_end: Option<Real>,
        length_ratio: Option<Real>,
        pretension_n: Option<Real>,
    ) -> PyResult<Self> {
        let given = s_end.is_some();
        let law = Arc::new(TcaLaw(tca.inner.clone()));
        let pretension = match pretension_n {
            None => None,
            Some(f) => {
                if length_ratio.is_some() {
                    return Err(Error::input(
                        "pretension_n / length_ratio",
                        "give one of them, not both",
                    )
                    .into());
                }
                let f = crate::error::non_negative("pretension_n [N]", f.0)?;
                // the pre-stretch it implies must exist (below the straight-fibre limit)
                tca.inner
                    .displacement(f, tca.inner.material().t_ref())
                    .map_err(|e| e.renamed(|n| format!("pretension_n ({n})")))?;
                Some(f)
            }
        };
        Ok(PyActuator {
            inner: make_actuator(routing, s_start, s_end, length_ratio, law)?,
            tca: Some(tca),
            pretension,
            stiffness: None,
            s_end_given: given,
        })
    }
    /// A tendon whose input is its tension [N] (>= 0), anchored from
    /// `s_start` [m] to `s_end` [m] (`None`: the tip); `length_ratio` [-] as
    /// for `Actuator.tca` (irrelevant to the force of a constant-tension tendon).
    #[staticmethod]
    #[pyo3(signature = (routing, s_start=Real(0.0), s_end=None, length_ratio=None),
        text_signature = "(routing, s_start=0.0, s_end=None, length_ratio=None)")]
    fn tendon(
        routing: PyRouting,
        s_start: Real,
        s_end: Option<Real>,
        length_ratio: Option<Real>,
    ) -> PyResult<Self> {
        Ok(PyActuator::plain(
            make_actuator(
                routing,
                s_start,
                s_end,
                length_ratio,
                Arc::new(ConstantTension),
            )?,
            s_end.is_some(),
        ))
    }
    /// An elastic tendon of `stiffness` [N/m] whose input is the length [m]
    /// pulled in at the base; anchors and `length_ratio` as for `Actuator.tca`.
    #[staticmethod]
    #[pyo3(signature = (stiffness, routing, s_start=Real(0.0), s_end=None, length_ratio=None),
        text_signature = "(stiffness, routing, s_start=0.0, s_end=None, length_ratio=None)")]
    fn linear_tendon(
        stiffness: Real,
        routing: PyRouting,
        s_start: Real,
        s_end: Option<Real>,
        length_ratio: Option<Real>,
    ) -> PyResult<Self> {
        let stiffness = crate::error::positive("stiffness [N/m]", stiffness.0)?;
        let mut a = PyActuator::plain(
            make_actuator(
                routing,
                s_start,
                s_end,
                length_ratio,
                Arc::new(LinearTendon { stiffness }),
            )?,
            s_end.is_some(),
        );
        a.stiffness = Some(stiffness);
        Ok(a)
    }
    /// Pre-tension [N] at the reference temperature (`Actuator.tca(..., pretension_n=...)`), or `None`.
    #[getter]
    fn pretension_n(&self) -> Option<f64> {
        self.pretension
    }
    /// Tendon stiffness [N/m] of a linear tendon, else `None`.
    #[getter]
    fn stiffness(&self) -> Option<f64> {
        self.stiffness
    }
    /// Pickle support: rebuilt by the same static constructor.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyAny>,
        (
            &'static str,
            Option<PyTca>,
            Option<f64>,
            PyRouting,
            f64,
            Option<f64>,
            Option<f64>,
            Option<f64>,
        ),
    )> {
        if self.kind() == "tca" && self.tca.is_none() {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "cannot pickle an Actuator built in Rust without its Tca",
            ));
        }
        let f = py.import("tcarod._core")?.getattr("_restore_actuator")?;
        Ok((
            f,
            (
                self.kind(),
                self.tca.clone(),
                self.stiffness,
                PyRouting {
                    inner: self.inner.routing,
                },
                self.inner.s_start,
                self.s_end_arg(),
                self.inner.length_ratio,
                self.pretension,
            ),
        ))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> Option<bool> {
        other
            .cast::<PyActuator>()
            .ok()
            .map(|o| o.get().identity() == self.identity())
    }
    fn __hash__(&self) -> u64 {
        hash_text(&self.identity())
    }
    /// `"tca"`, `"tension"` or `"linear_tendon"`.
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.law.kind()
    }
    /// Name and unit of the input, e.g. `"temperature [C]"`.
    #[getter]
    fn input_name(&self) -> &'static str {
        self.inner.law.input_name()
    }
    /// `(lowest, highest)` valid input (temperature [C] for TCAs, tension [N], pull [m]).
    #[getter]
    fn input_bounds(&self) -> (f64, f64) {
        self.inner.law.input_bounds()
    }
    /// Input of the passive (reference) state (ambient temperature [C] for TCAs).
    #[getter]
    fn reference_input(&self) -> f64 {
        self.inner.law.reference_input()
    }
    /// Body-frame path (`Routing`).
    #[getter]
    fn routing(&self) -> PyRouting {
        PyRouting {
            inner: self.inner.routing,
        }
    }
    /// Proximal anchor [m] (0: the base).
    #[getter]
    fn s_start(&self) -> f64 {
        self.inner.s_start
    }
    /// Distal anchor [m]; `inf` means the tip.
    #[getter]
    fn s_end(&self) -> f64 {
        self.inner.s_end
    }
    /// The paper's constant length ratio `L_i` [-] (eq 18), or `None` (pointwise from the reference shape; `pretension_n` sets it when the robot is built).
    #[getter]
    fn length_ratio(&self) -> Option<f64> {
        self.inner.length_ratio
    }
    /// The TCA (`Tca`) of a TCA actuator, else `None`.
    #[getter]
    fn tca_model(&self) -> Option<PyTca> {
        self.tca.clone()
    }
    /// Tension [N] at total elongation `elongation` [m] and `input`.
    fn tension(&self, elongation: Real, input: Real) -> PyResult<f64> {
        let elongation = crate::error::finite("elongation [m]", elongation.0)?;
        self.inner.law.check_input(input.0)?;
        Ok(finite_output(
            "tension [N]",
            self.inner.law.tension(elongation, input.0)?,
        )?)
    }
    fn __repr__(&self) -> String {
        let routing = PyRouting {
            inner: self.inner.routing,
        }
        .__repr__();
        let mut tail = format!("routing={routing}, s_start={}", pf(self.inner.s_start));
        if let Some(e) = self.s_end_arg() {
            tail += &format!(", s_end={}", pf(e));
        }
        if let Some(l) = self.inner.length_ratio {
            tail += &format!(", length_ratio={}", pf(l));
        }
        match (self.kind(), &self.tca, self.stiffness) {
            ("tca", Some(t), _) => {
                let tca = Python::attach(|py| {
                    Bound::new(py, t.clone()).and_then(|b| PyTca::__repr__(&b))
                })
                .unwrap_or_else(|_| "Tca(...)".into());
                let pre = self
                    .pretension
                    .map(|f| format!(", pretension_n={}", pf(f)))
                    .unwrap_or_default();
                format!("Actuator.tca(tca={tca}, {tail}{pre})")
            }
            ("linear_tendon", _, Some(k)) => {
                format!("Actuator.linear_tendon(stiffness={}, {tail})", pf(k))
            }
            ("tension", _, _) => format!("Actuator.tendon({tail})"),
            (kind, _, _) => format!("<Actuator kind={} {tail}>", ps(kind)),
        }
    }
}

/// Rebuild an `Actuator` (pickle support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_actuator")]
#[allow(clippy::too_many_arguments)]
fn restore_actuator(
    kind: &str,
    tca: Option<PyTca>,
    stiffness: Option<Real>,
    routing: PyRouting,
    s_start: Real,
    s_end: Option<Real>,
    length_ratio: Option<Real>,
    pretension_n: Option<Real>,
) -> PyResult<PyActuator> {
    match (kind, tca, stiffness) {
        ("tca", Some(t), _) => {
            PyActuator::tca(t, routing, s_start, s_end, length_ratio, pretension_n)
        }
        ("tension", _, _) => PyActuator::tendon(routing, s_start, s_end, length_ratio),
        ("linear_tendon", _, Some(k)) => {
            PyActuator::linear_tendon(k, routing, s_start, s_end, length_ratio)
        }
        _ => Err(Error::input(
            "kind",
            format!("{kind:?} with these parameters is not an actuator"),
        )
        .into()),
    }
}

/// A body with its embedded actuators: `Robot(body, actuators=())`.
///
/// `body` is a `Body`; `actuators` a sequence of `Actuator` (inputs are given
/// in this order to `solve`: temperature [C] for TCAs, tension [N] for
/// tendons, pull [m] for linear tendons). Building checks the layout: anchors
/// inside the body, routings inside the section, TCAs no longer than their
/// span (ValueError naming `actuators[i]`). Value object: immutable, `==`
/// (two identically built robots are equal), picklable, so it travels to
/// process pools and Dask workers.
#[pyclass(name = "Robot", module = "tcarod._core", frozen, subclass)]
#[derive(Clone)]
pub struct PyRobot {
    pub(crate) inner: Arc<Robot>,
    pub(crate) body: PyBody,
    pub(crate) actuators: Vec<PyActuator>,
}

/// Solver options from Python arguments: `steps` in `1..=MAX_STEPS`,
/// `max_iter` in `1..=MAX_ITER` (ValueError naming the argument and range
/// beyond; TypeError for non-integers), `tol` finite and > 0.
pub(crate) fn solve_options(
    steps: Option<&Bound<'_, PyAny>>,
    tol: Real,
    max_iter: Option<&Bound<'_, PyAny>>,
) -> PyResult<SolveOptions> {
    use crate::validate::{MAX_ITER, MAX_STEPS};
    let steps = count_or("steps", steps, 100, 1, MAX_STEPS)?;
    let max_iter = count_or("max_iter", max_iter, 50, 1, MAX_ITER)?;
    options(steps, tol.0, max_iter)
}

/// Error naming `inputs[i]` if a TCA input lies below its material's range,
/// with the way to a colder ambient (a custom `Material`).
pub(crate) fn check_ambient(robot: &Robot, inputs: &[f64]) -> PyResult<()> {
    for (i, (a, &x)) in robot.actuators.iter().zip(inputs).enumerate() {
        if a.law.kind() == "tca" {
            let (lo, hi) = a.law.input_bounds();
            crate::validate::ambient_hint(x, lo, hi, &format!("inputs[{i}] (temperature [C])"))?;
        }
    }
    Ok(())
}

pub(crate) fn options(steps: usize, tol: f64, max_iter: usize) -> PyResult<SolveOptions> {
    let o = SolveOptions {
        steps,
        tol,
        max_iter,
        ..Default::default()
    };
    o.validate()?;
    Ok(o)
}

/// Every number of a solution is finite (the IVP rejects non-finite
/// derivatives, so this holds by construction; checked once more at the
/// boundary so that no getter can hand NaN to Python).
pub(crate) fn checked_solution(sol: Solution) -> Result<Solution> {
    let vecs = sol
        .positions
        .iter()
        .chain(&sol.nu)
        .chain(&sol.omega)
        .chain(&sol.internal_force)
        .chain(&sol.internal_moment)
        .chain(sol.actuator_paths.iter().flatten())
        .chain([&sol.base_force, &sol.base_moment]);
    let ok = vecs.flat_map(|v| v.iter()).all(|x| x.is_finite())
        && sol
            .rotations
            .iter()
            .all(|r| r.iter().all(|x| x.is_finite()))
        && sol
            .s
            .iter()
            .chain(&sol.tensions)
            .chain(&sol.elongations)
            .chain(&sol.unknowns)
            .all(|x| x.is_finite())
        && sol
            .elongation_profile
            .iter()
            .flatten()
            .all(|x| x.is_finite())
        && sol.residual.is_finite();
    if ok {
        Ok(sol)
    } else {
        Err(Error::Integration {
            s: sol.s.last().copied().unwrap_or(0.0),
            reason: "the solution holds a non-finite value".into(),
        })
    }
}

#[pymethods]
impl PyRobot {
    #[new]
    #[pyo3(signature = (body, actuators=None), text_signature = "(body, actuators=())")]
    fn new(body: PyBody, actuators: Option<Bound<'_, PyAny>>) -> PyResult<Self> {
        let actuators = match actuators {
            None => Vec::new(),
            Some(seq) => actuator_list(&seq)?,
        };
        let len = body.inner.length;
        let mut acts: Vec<Actuator> = actuators
            .iter()
            .map(|a| {
                let mut x = a.inner.clone();
                if x.s_end.is_infinite() {
                    x.s_end = len;
                }
                x
            })
            .collect();
        // anchors first (the core's rules), then geometry and pre-tension
        Robot::new(body.inner.clone(), acts.clone())?;
        for (i, (a, x)) in actuators.iter().zip(acts.iter_mut()).enumerate() {
            let name = format!("actuators[{i}]");
            crate::validate::routing_in_section(
                &body.inner.section,
                &x.routing,
                &format!("{name}.routing"),
            )?;
            if let Some(t) = &a.tca {
                crate::validate::tca_fits_span(t.inner.coiled_length(), x, &format!("{name}.tca"))?;
                if let Some(f) = a.pretension {
                    let stretch = t.inner.displacement(f, t.inner.material().t_ref())?;
                    x.length_ratio = Some(crate::validate::pretension_length_ratio(
                        &body.inner,
                        x,
                        stretch,
                        &format!("{name}.pretension_n"),
                    )?);
                }
            }
        }
        let robot = Robot::new(body.inner.clone(), acts)?;
        Ok(PyRobot {
            inner: Arc::new(robot),
            body,
            actuators,
        })
    }
    /// The soft body (`Body`).
    #[getter]
    fn body(&self) -> PyBody {
        self.body.clone()
    }
    /// The actuators (list of `Actuator`), in input order.
    #[getter]
    fn actuators(&self) -> Vec<PyActuator> {
        self.actuators.clone()
    }
    /// Passive inputs: ambient temperature [C] for TCAs, zero tension [N] / pull [m] for tendons.
    #[getter]
    fn reference_inputs(&self) -> Vec<f64> {
        self.inner.reference_inputs()
    }

    /// Solve the forward kinetostatics for one input per actuator
    /// (temperature [C] for TCAs, tension [N] for tendons, pull [m] for linear
    /// tendons). `steps`: RK4 steps over the body (1 to 100,000); `tol`:
    /// Newton tolerance on the dimensionless residual; `max_iter`: Newton
    /// iterations (1 to 100,000); `warm_start`: a nearby `Solution` of this
    /// robot, or of a robot with the same actuators under other loads (load
    /// continuation). `stability` (issue 16): `"report"` (default: the
    /// verdict is part of the solve, one tangent IVP, cached in
    /// `Solution.stable`; an unstable equilibrium also emits
    /// `UnstableEquilibriumWarning`), `"require"` (raise
    /// `UnstableEquilibriumError`, attributes `margin` [-] and `solution`),
    /// `"continue"` (move from an unstable equilibrium to a stable one at the
    /// same inputs; `Solution.continued` records how) or `"off"` (no verdict:
    /// hot loops). `require_stable=True` is `stability="require"`. Raises
    /// `ValueError` on bad input, `TypeError` on wrong types and
    /// `ConvergenceError` if Newton fails.
    #[pyo3(signature = (inputs, *, steps=None, tol=Real(1e-10), max_iter=None, warm_start=None, stability="report", require_stable=false),
        text_signature = "($self, inputs, *, steps=100, tol=1e-10, max_iter=50, warm_start=None, stability='report', require_stable=False)")]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        inputs: Bound<'_, PyAny>,
        steps: Option<Bound<'_, PyAny>>,
        tol: Real,
        max_iter: Option<Bound<'_, PyAny>>,
        warm_start: Option<PyRef<'_, PySolution>>,
        stability: &str,
        require_stable: bool,
    ) -> PyResult<PySolution> {
        let this = slf.get();
        let opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
        let mut policy = super::stability::parse_policy(stability)?;
        if require_stable {
            policy = crate::stability::Policy::Require;
        }
        let q = reals("inputs", &inputs, None)?;
        check_ambient(&this.inner, &q)?;
        let warm = warm_start.map(|w| w.inner.clone());
        super::stability::solve_policy(py, slf, &q, &opts, warm, policy)
    }

    /// Solve along rows of `inputs` (shape `(k, n_actuators)`, at most
    /// 10,000,000 rows), each warm-started from the previous one. Returns a
    /// list of `Solution`. Options as for `solve`; `stability`: `"report"`
    /// (default: every solution carries its verdict, one warning names the
    /// unstable rows), `"require"` (raise at the first unstable row),
    /// `"continue"` (the quasi-static path of the physical robot: where an
    /// equilibrium is unstable, move to a stable one and go on from it) or
    /// `"off"`.
    #[pyo3(signature = (inputs, *, steps=None, tol=Real(1e-10), max_iter=None, stability="report"),
        text_signature = "($self, inputs, *, steps=100, tol=1e-10, max_iter=50, stability='report')")]
    fn sweep(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        inputs: Bound<'_, PyAny>,
        steps: Option<Bound<'_, PyAny>>,
        tol: Real,
        max_iter: Option<Bound<'_, PyAny>>,
        stability: &str,
    ) -> PyResult<Vec<PySolution>> {
        let opts = solve_options(steps.as_ref(), tol, max_iter.as_ref())?;
        let policy = super::stability::parse_policy(stability)?;
        let rows_iter = inputs.try_iter().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err("inputs: expected a sequence of rows")
        })?;
        let mut rows: Vec<Vec<f64>> = Vec::new();
        for (k, row) in rows_iter.enumerate() {
            if k >= crate::validate::MAX_BATCH_ROWS {
                return Err(Error::input(
                    "inputs",
                    format!(
                        "more than {} rows per call",
                        crate::validate::MAX_BATCH_ROWS
                    ),
                )
                .into());
            }
            let row = reals(&format!("inputs[{k}]"), &row?, None)?;
            check_ambient(&slf.get().inner, &row)?;
            rows.push(row);
        }
        super::stability::sweep_policy(py, slf, &rows, &opts, policy)
    }

    fn __repr__(&self) -> String {
        let acts: Vec<String> = self.actuators.iter().map(|a| a.__repr__()).collect();
        format!(
            "Robot(body={}, actuators=[{}])",
            body_repr(&self.body.inner),
            acts.join(", ")
        )
    }
    /// Constructor arguments, for pickle and copy.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, pyo3::types::PyTuple>, Bound<'py, PyDict>)> {
        let args = (self.body.clone(), self.actuators.clone()).into_pyobject(py)?;
        Ok((args, PyDict::new(py)))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> Option<bool> {
        other.cast::<PyRobot>().ok().map(|o| o.get().same_as(self))
    }
    fn __hash__(&self) -> u64 {
        hash_text(&self.__repr__())
    }
}

impl PyRobot {
    /// Built from equal bodies and equal actuators.
    pub(crate) fn same_as(&self, other: &PyRobot) -> bool {
        Arc::ptr_eq(&self.inner, &other.inner)
            || (self.body.inner == other.body.inner
                && self.actuators.len() == other.actuators.len()
                && self
                    .actuators
                    .iter()
                    .zip(&other.actuators)
                    .all(|(a, b)| a.identity() == b.identity()))
    }
}

/// `seq` as a list of actuators, at most [`super::MAX_SEQUENCE`] (never
/// trusting `__len__`): `TypeError` for anything else.
fn actuator_list(seq: &Bound<'_, PyAny>) -> PyResult<Vec<PyActuator>> {
    let iter = seq.try_iter().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err("actuators: expected a sequence of Actuator")
    })?;
    let mut out = Vec::new();
    for (k, item) in iter.enumerate() {
        if k >= super::MAX_SEQUENCE {
            return Err(Error::input(
                "actuators",
                format!("more than {} actuators", super::MAX_SEQUENCE),
            )
            .into());
        }
        let item = item?;
        let a = item.cast::<PyActuator>().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "actuators[{k}]: expected an Actuator, not {}",
                item.get_type()
                    .name()
                    .map(|n| n.to_string())
                    .unwrap_or_default()
            ))
        })?;
        out.push(a.get().clone());
    }
    Ok(out)
}

/// A converged forward solution. Arrays are NumPy, SI units, world frame
/// unless noted; `n` nodes along the body.
///
/// SciPy-style fields: `success` (always `True`: a failed solve raises
/// `ConvergenceError`), `status` 0, `message`, `nit` (Newton iterations),
/// `nfev` (IVPs). Naming: `tip_position` [m] per solve, `tip_positions` per
/// batch (`tcarod.batch.BatchResult`). Picklable (with its robot) and `==`.
/// Stability: `stable` and `stability_margin`, computed by the solve (policy
/// `"report"`, the default) or on first access (one tangent IVP), cached;
/// `continued` records a `stability="continue"` solve's route.
#[pyclass(name = "Solution", module = "tcarod._core", frozen)]
pub struct PySolution {
    pub(crate) inner: Solution,
    pub(crate) robot: Py<PyRobot>,
    /// Cached stability verdict `(stable, margin)` (issue 16).
    pub(crate) verdict: OnceLock<(bool, f64)>,
    /// World directions along which the tip translation is held (the block
    /// normal of a blocked-tip solution; empty for a free tip).
    pub(crate) blocked: Vec<Vector3<f64>>,
    /// How `stability="continue"` reached this equilibrium, if it moved.
    pub(crate) continued: Option<Py<super::stability::Continuation>>,
}

impl PySolution {
    /// A solution of `robot`; its stability verdict is computed lazily.
    pub(crate) fn new(inner: Solution, robot: Py<PyRobot>) -> Self {
        PySolution {
            inner,
            robot,
            verdict: OnceLock::new(),
            blocked: Vec::new(),
            continued: None,
        }
    }

    /// The cached verdict, computing it (GIL released) on first use.
    fn verdict(&self, py: Python<'_>) -> PyResult<(bool, f64)> {
        if let Some(v) = self.verdict.get() {
            return Ok(*v);
        }
        let robot = self.robot.bind(py).get().inner.clone();
        let sol = &self.inner;
        let blocked = &self.blocked;
        let st = py.detach(|| crate::stability::stability(&robot, sol, blocked))?;
        let st = super::stability::finite_margin(st);
        Ok(*self.verdict.get_or_init(|| (st.stable, st.margin)))
    }
}

fn stack3<'py>(py: Python<'py>, v: &[Vector3<f64>]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flat_map(|x| [x.x, x.y, x.z]).collect();
    PyArray1::from_vec(py, flat)
        .reshape([v.len(), 3])
        .expect("n x 3")
}

#[pymethods]
impl PySolution {
    /// The `Robot` solved.
    #[getter]
    fn robot(&self, py: Python<'_>) -> Py<PyRobot> {
        self.robot.clone_ref(py)
    }
    /// Arc length of each node [m], shape `(n,)`.
    #[getter]
    fn s<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.s)
    }
    /// Centre-line positions [m], shape `(n, 3)`.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.positions)
    }
    /// Rotation matrices (body to world), shape `(n, 3, 3)`.
    #[getter]
    fn rotations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let flat: Vec<f64> = self
            .inner
            .rotations
            .iter()
            .flat_map(|r| (0..3).flat_map(move |i| (0..3).map(move |j| r[(i, j)])))
            .collect();
        PyArray1::from_vec(py, flat)
            .reshape([self.inner.rotations.len(), 3, 3])
            .expect("n x 3 x 3")
    }
    /// Linear strain `nu` [-] (body frame), shape `(n, 3)`.
    #[getter]
    fn nu<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.nu)
    }
    /// Angular strain `omega` [1/m] (body frame), shape `(n, 3)`.
    #[getter]
    fn omega<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.omega)
    }
    /// Internal force `n` [N], shape `(n, 3)`.
    #[getter]
    fn internal_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.internal_force)
    }
    /// Internal moment `m` [N m], shape `(n, 3)`.
    #[getter]
    fn internal_moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        stack3(py, &self.inner.internal_moment)
    }
    /// Elongation of each actuator accumulated up to each node [m], shape `(n, n_actuators)`.
    #[getter]
    fn elongation_profile<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let na = self.inner.tensions.len();
        let flat: Vec<f64> = self
            .inner
            .elongation_profile
            .iter()
            .flatten()
            .copied()
            .collect();
        PyArray1::from_vec(py, flat)
            .reshape([self.inner.s.len(), na])
            .expect("n x na")
    }
    /// Path of each actuator `p + R r_i` [m] over its span: list of `(k_i, 3)` arrays.
    #[getter]
    fn actuator_paths<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        self.inner
            .actuator_paths
            .iter()
            .map(|p| stack3(py, p))
            .collect()
    }
    /// Actuator tensions [N] (negative: the actuator pushes), shape `(n_actuators,)`.
    #[getter]
    fn tensions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.tensions)
    }
    /// Actuator total elongations [m], shape `(n_actuators,)`.
    #[getter]
    fn elongations<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.elongations)
    }
    /// Inputs solved for (temperature [C] for TCAs).
    #[getter]
    fn inputs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.inputs)
    }
    /// Force [N] transmitted to the base by body and actuators (the base reaction is its negative).
    #[getter]
    fn base_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.base_force)
    }
    /// Moment [N m] about the origin transmitted to the base.
    #[getter]
    fn base_moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.base_moment)
    }
    /// Tip position [m], shape `(3,)`.
    #[getter]
    fn tip_position<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.tip_position())
    }
    /// Tip rotation, shape `(3, 3)`.
    #[getter]
    fn tip_rotation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        mat3(py, &self.inner.tip_rotation())
    }
    /// Newton iterations used (`nit`).
    #[getter]
    fn iterations(&self) -> usize {
        self.inner.iterations
    }
    /// IVPs integrated (`nfev`).
    #[getter]
    fn evaluations(&self) -> usize {
        self.inner.evaluations
    }
    /// Final residual: max-norm of the dimensionless shooting residual [-].
    #[getter]
    fn residual(&self) -> f64 {
        self.inner.residual
    }
    /// Scaled shooting unknowns `[nu(0), L omega(0), delta_i / L]`.
    #[getter]
    fn unknowns<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.inner.unknowns)
    }
    /// 3-D plot of the shape with the actuators (see `tcarod.plotting.plot_solution`).
    #[pyo3(signature = (**kwargs))]
    fn plot<'py>(
        slf: &Bound<'py, Self>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        py.import("tcarod.plotting")?
            .getattr("plot_solution")?
            .call((slf,), kwargs)
    }
    /// True if this equilibrium is stable: a strict local minimum of the
    /// potential energy (Till and Rucker's criterion, extended to the
    /// actuators and dead loads; see `tcarod.stability`). Computed by the
    /// solve (default policy `"report"`) or on first access, from one
    /// tangent integration (GIL released), and cached.
    /// A `BlockedResult.solution` carries the verdict with the tip held on
    /// its plane (mixed boundary condition).
    #[getter]
    fn stable(&self, py: Python<'_>) -> PyResult<bool> {
        Ok(self.verdict(py)?.0)
    }
    /// How `stability="continue"` reached this equilibrium from the unstable
    /// one Newton found first (a `Continuation`), or None.
    #[getter]
    fn continued(&self, py: Python<'_>) -> Option<Py<super::stability::Continuation>> {
        self.continued.as_ref().map(|c| c.clone_ref(py))
    }
    /// Stability margin [-] (dimensionless): the smallest eigenvalue of the
    /// dimensionless tip stiffness, `> 0` iff `stable`. Computed and cached
    /// with `stable`.
    #[getter]
    fn stability_margin(&self, py: Python<'_>) -> PyResult<f64> {
        Ok(self.verdict(py)?.1)
    }
    fn __repr__(&self) -> String {
        let p = self.inner.tip_position();
        let stable = match self.verdict.get() {
            Some((s, _)) => format!(" stable={}", if *s { "True" } else { "False" }),
            None => String::new(),
        };
        format!(
            "<Solution success=True nit={} nfev={} residual={:.2e} inputs={} tip_position={}{}>",
            self.inner.iterations,
            self.inner.evaluations,
            self.inner.residual,
            pv(&self.inner.inputs),
            pv(p.as_slice()),
            stable
        )
    }
    /// Always `True`: a `Solution` is returned only when Newton converged
    /// (otherwise `ConvergenceError` is raised). SciPy `OptimizeResult` naming.
    #[getter]
    fn success(&self) -> bool {
        true
    }
    /// `0` (converged), SciPy naming.
    #[getter]
    fn status(&self) -> i64 {
        0
    }
    /// Why the solve stopped, in words (`str`).
    #[getter]
    fn message(&self) -> String {
        format!(
            "converged: residual {:.3e} after {} Newton iterations",
            self.inner.residual, self.inner.iterations
        )
    }
    /// Newton iterations (same as `iterations`), SciPy naming.
    #[getter]
    fn nit(&self) -> usize {
        self.inner.iterations
    }
    /// IVPs integrated, i.e. function evaluations (same as `evaluations`), SciPy naming.
    #[getter]
    fn nfev(&self) -> usize {
        self.inner.evaluations
    }
    /// RK4 steps over the body used by the solve (`steps` argument).
    #[getter]
    fn steps(&self) -> usize {
        self.inner.steps
    }
    /// Pickle support: the robot and the converged shooting unknowns; the
    /// profile is rebuilt by one IVP from them (bit-identical: the IVP is
    /// deterministic), the Newton Jacobian kept for warm starts.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, pyo3::types::PyTuple>)> {
        let f = py.import("tcarod._core")?.getattr("_restore_solution")?;
        let s = &self.inner;
        let jac = s
            .newton_jacobian
            .as_ref()
            .map(|j| (j.nrows(), j.ncols(), j.as_slice().to_vec()));
        let args = (
            self.robot.clone_ref(py),
            s.inputs.clone(),
            s.unknowns.clone(),
            s.loads.tip_force.as_slice().to_vec(),
            s.loads.tip_moment.as_slice().to_vec(),
            s.steps,
            s.iterations,
            s.evaluations,
            jac,
            self.blocked
                .iter()
                .map(|b| [b.x, b.y, b.z])
                .collect::<Vec<_>>(),
        )
            .into_pyobject(py)?;
        Ok((f, args))
    }
    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> Option<bool> {
        let o = other.cast::<PySolution>().ok()?;
        let o = o.get();
        let (a, b) = (&self.inner, &o.inner);
        Some(
            self.robot.bind(py).get().same_as(o.robot.bind(py).get())
                && a.inputs == b.inputs
                && a.unknowns == b.unknowns
                && a.loads == b.loads
                && a.steps == b.steps
                && a.iterations == b.iterations
                && a.evaluations == b.evaluations
                && a.residual.to_bits() == b.residual.to_bits()
                && a.s == b.s
                && a.positions == b.positions
                && a.rotations == b.rotations
                && a.nu == b.nu
                && a.omega == b.omega
                && a.internal_force == b.internal_force
                && a.internal_moment == b.internal_moment
                && a.tensions == b.tensions
                && a.elongations == b.elongations
                && a.elongation_profile == b.elongation_profile
                && a.actuator_paths == b.actuator_paths
                && a.base_force == b.base_force
                && a.base_moment == b.base_moment
                && a.newton_jacobian == b.newton_jacobian,
        )
    }
}

/// Rebuild a `Solution` from its robot and converged unknowns (pickle
/// support; not public API).
#[pyfunction]
#[pyo3(name = "_restore_solution")]
#[pyo3(signature = (robot, inputs, unknowns, tip_force, tip_moment, steps, iterations, evaluations, jacobian, blocked=None))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
fn restore_solution(
    py: Python<'_>,
    robot: Bound<'_, PyRobot>,
    inputs: Vec<f64>,
    unknowns: Vec<f64>,
    tip_force: [f64; 3],
    tip_moment: [f64; 3],
    steps: usize,
    iterations: usize,
    evaluations: usize,
    jacobian: Option<(usize, usize, Vec<f64>)>,
    blocked: Option<Vec<[f64; 3]>>,
) -> PyResult<PySolution> {
    let r = robot.get().inner.clone();
    let na = r.actuators.len();
    if inputs.len() != na
        || unknowns.len() != 6 + na
        || steps == 0
        || steps > crate::validate::MAX_STEPS
    {
        return Err(Error::input("state", "does not belong to this robot").into());
    }
    r.check_inputs(&inputs)?;
    let loads = crate::shooting::Loads {
        tip_force: Vector3::from(tip_force),
        tip_moment: Vector3::from(tip_moment),
    };
    let jac = match jacobian {
        Some((m, n, v)) if m * n == v.len() && m == unknowns.len() && n == unknowns.len() => {
            Some(nalgebra::DMatrix::from_vec(m, n, v))
        }
        Some(_) => return Err(Error::input("state", "Jacobian of the wrong size").into()),
        None => None,
    };
    let mut sol = py.detach(|| {
        crate::shooting::assemble(
            &r,
            &inputs,
            &loads,
            &unknowns,
            steps,
            iterations,
            evaluations,
        )
        .and_then(checked_solution)
    })?;
    sol.newton_jacobian = jac;
    let mut out = PySolution::new(sol, robot.unbind());
    out.blocked = blocked
        .unwrap_or_default()
        .into_iter()
        .map(Vector3::from)
        .collect();
    if out
        .blocked
        .iter()
        .any(|b| !(b.iter().all(|x| x.is_finite()) && b.norm() > 0.0))
    {
        return Err(Error::input("state", "blocked directions must be finite and non-zero").into());
    }
    Ok(out)
}
