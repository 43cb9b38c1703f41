//! Bindings of the rod model and the shooting solver.

use std::sync::Arc;

use nalgebra::{Matrix3, Vector3};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::errors::{finite_output, Real};
use super::tca::PyTca;
use crate::error::{Error, Result};
use crate::rod::{Actuator, Body, ConstantTension, ForceLaw, LinearTendon, Robot, Routing, Section, TcaLaw};
use crate::shooting::{solve, SolveOptions, Solution};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySection>()?;
    m.add_class::<PyRouting>()?;
    m.add_class::<PyBody>()?;
    m.add_class::<PyActuator>()?;
    m.add_class::<PyRobot>()?;
    m.add_class::<PySolution>()?;
    m.add_function(wrap_pyfunction!(experiment_robot, m)?)?;
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
        _ => return Err(Error::input("name", format!("unknown fixture {name:?} (fig6_circle, fig6_square)")).into()),
    };
    let body = PyBody { inner: robot.body.clone() };
    let actuators = robot
        .actuators
        .iter()
        .map(|a| PyActuator {
            inner: a.clone(),
            tca: None,
        })
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
        Ok(checked_section("diameter [m]", Section::Circle { diameter })?)
    }
    /// Solid rectangle: `width` [m] along body x, `height` [m] along body y.
    #[staticmethod]
    fn rectangle(width: Real, height: Real) -> PyResult<Self> {
        let width = crate::error::positive("width [m]", width.0)?;
        let height = crate::error::positive("height [m]", height.0)?;
        Ok(checked_section("width [m] / height [m]", Section::Rectangle { width, height })?)
    }
    /// User-given area [m^2], second moments about body x and y [m^4] and torsion constant [m^4].
    #[staticmethod]
    fn custom(area: Real, ix: Real, iy: Real, j: Real) -> PyResult<Self> {
        let (area, ix, iy, j) = (area.0, ix.0, iy.0, j.0);
        for (n, v) in [("area [m^2]", area), ("ix [m^4]", ix), ("iy [m^4]", iy), ("j [m^4]", j)] {
            crate::error::positive(n, v)?;
        }
        Ok(checked_section("area [m^2]", Section::Custom { area, ix, iy, j })?)
    }
    /// `(area [m^2], ix [m^4], iy [m^4], j [m^4])`.
    #[getter]
    fn properties(&self) -> (f64, f64, f64, f64) {
        self.inner.properties()
    }
    /// Distance [m] from the centre line to the edge in body-frame direction angle `theta` [rad].
    fn edge_distance(&self, theta: Real) -> PyResult<f64> {
        let theta = crate::error::finite("theta [rad]", theta.0)?;
        Ok(finite_output("edge_distance [m]", self.inner.edge_distance(theta))?)
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
        format!("Section({:?})", self.inner)
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
        Ok(PyRouting { inner: Routing::Straight { x, y } })
    }
    /// Helix of `radius` [m] turning at `rate` [rad/m] from angle `phase` [rad].
    #[staticmethod]
    #[pyo3(signature = (radius, rate, phase=Real(0.0)), text_signature = "(radius, rate, phase=0.0)")]
    fn helix(radius: Real, rate: Real, phase: Real) -> PyResult<Self> {
        let radius = crate::error::non_negative("radius [m]", radius.0)?;
        let rate = crate::error::finite("rate [rad/m]", rate.0)?;
        let phase = crate::error::finite("phase [rad]", phase.0)?;
        Ok(PyRouting { inner: Routing::Helix { radius, rate, phase } })
    }
    /// `(r, r', r'')` at arc length `s` [m] as three length-3 arrays (body frame).
    #[allow(clippy::type_complexity)]
    fn evaluate<'py>(&self, py: Python<'py>, s: Real) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>)> {
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
        format!("Routing({:?})", self.inner)
    }
}

fn vec3<'py>(py: Python<'py>, v: &Vector3<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v.as_slice())
}

fn v3(name: &str, v: Option<[Real; 3]>, default: Vector3<f64>) -> PyResult<Vector3<f64>> {
    match v {
        None => Ok(default),
        Some(a) => {
            for (k, x) in a.iter().enumerate() {
                crate::error::finite(&format!("{name}[{k}]"), x.0)?;
            }
            Ok(Vector3::new(a[0].0, a[1].0, a[2].0))
        }
    }
}

/// Error unless the body's derived quantities (stiffnesses, weight per
/// length) are finite and the stiffnesses positive, so that no getter can
/// return inf or NaN.
fn check_derived(b: &Body) -> Result<()> {
    let (kv, kw) = b.stiffness();
    for k in 0..3 {
        for (name, v) in [("stiffness K_nu [N]", kv[(k, k)]), ("stiffness K_omega [N m^2]", kw[(k, k)])] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::input(name, format!("is {v}: youngs_modulus / shear_modulus times the section properties leave double range")));
            }
        }
    }
    for (k, x) in b.distributed_load().iter().enumerate() {
        finite_output(&format!("distributed_load [N/m][{k}] (density x area x gravity)"), *x)?;
    }
    Ok(())
}

/// The soft body (Cosserat rod): geometry, material, reference strains, loads.
///
/// All vectors are length-3 in the world frame unless noted; SI units.
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
        length: Real,
        section: PySection,
        youngs_modulus: Real,
        poisson: Option<Real>,
        shear_modulus: Option<Real>,
        density: Real,
        shear_coefficient: Real,
        nu_star: Option<[Real; 3]>,
        omega_star: Option<[Real; 3]>,
        gravity: Option<[Real; 3]>,
        distributed_force: Option<[Real; 3]>,
        distributed_moment: Option<[Real; 3]>,
        tip_force: Option<[Real; 3]>,
        tip_moment: Option<[Real; 3]>,
    ) -> PyResult<Self> {
        let (length, youngs_modulus, density, shear_coefficient) = (length.0, youngs_modulus.0, density.0, shear_coefficient.0);
        let (poisson, shear_modulus) = (poisson.map(|r| r.0), shear_modulus.map(|r| r.0));
        crate::error::positive("length [m]", length)?;
        let mut b = match (poisson, shear_modulus) {
            (Some(_), Some(_)) => {
                return Err(Error::input("poisson / shear_modulus", "give one of them, not both").into())
            }
            (p, None) => Body::new(length, section.inner, youngs_modulus, p.unwrap_or(0.5), density)?,
            (None, Some(g)) => {
                let mut b = Body::new(length, section.inner, youngs_modulus, 0.0, density)?;
                b.shear_modulus = g;
                b
            }
        };
        b.shear_coefficient = shear_coefficient;
        b.nu_star = v3("nu_star", nu_star, Vector3::z())?;
        b.omega_star = v3("omega_star", omega_star, Vector3::zeros())?;
        b.gravity = v3("gravity", gravity, Vector3::zeros())?;
        b.distributed_force = v3("distributed_force", distributed_force, Vector3::zeros())?;
        b.distributed_moment = v3("distributed_moment", distributed_moment, Vector3::zeros())?;
        b.tip_force = v3("tip_force", tip_force, Vector3::zeros())?;
        b.tip_moment = v3("tip_moment", tip_moment, Vector3::zeros())?;
        b.validate()?;
        check_derived(&b)?;
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

    #[getter]
    fn length(&self) -> f64 {
        self.inner.length
    }
    #[getter]
    fn section(&self) -> PySection {
        PySection { inner: self.inner.section }
    }
    #[getter]
    fn youngs_modulus(&self) -> f64 {
        self.inner.youngs_modulus
    }
    #[getter]
    fn shear_modulus(&self) -> f64 {
        self.inner.shear_modulus
    }
    #[getter]
    fn density(&self) -> f64 {
        self.inner.density
    }
    #[getter]
    fn nu_star<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.nu_star)
    }
    #[getter]
    fn omega_star<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.omega_star)
    }
    #[getter]
    fn gravity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.gravity)
    }
    #[getter]
    fn tip_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.tip_force)
    }
    #[getter]
    fn tip_moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.tip_moment)
    }
    /// Total distributed force `psi A g + f` [N/m], world frame.
    #[getter]
    fn distributed_load<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.distributed_load())
    }
    #[getter]
    fn distributed_moment<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.distributed_moment)
    }
    /// `(K_nu, K_omega)` diagonal stiffness matrices, 3x3 each ([N], [N m^2]).
    fn stiffness<'py>(&self, py: Python<'py>) -> (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>) {
        let (a, b) = self.inner.stiffness();
        (mat3(py, &a), mat3(py, &b))
    }
    fn __repr__(&self) -> String {
        format!("Body({:?})", self.inner)
    }
}

fn mat3<'py>(py: Python<'py>, m: &Matrix3<f64>) -> Bound<'py, PyArray2<f64>> {
    let rows: Vec<Vec<f64>> = (0..3).map(|i| (0..3).map(|j| m[(i, j)]).collect()).collect();
    PyArray2::from_vec2(py, &rows).expect("3x3")
}

/// A string-like actuator embedded in the body. Build with `Actuator.tca`,
/// `Actuator.tendon` (constant tension) or `Actuator.linear_tendon`.
#[pyclass(name = "Actuator", module = "tcarod._core", frozen)]
#[derive(Clone)]
pub struct PyActuator {
    pub(crate) inner: Actuator,
    tca: Option<PyTca>,
}

fn make_actuator(routing: PyRouting, s_start: Real, s_end: Option<Real>, length_ratio: Option<Real>, law: Arc<dyn ForceLaw>) -> PyResult<Actuator> {
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

#[pymethods]
impl PyActuator {
    /// A TCA whose input is its temperature [C]. `s_end=None` anchors it at the tip.
    #[staticmethod]
    #[pyo3(signature = (tca, routing, s_start=Real(0.0), s_end=None, length_ratio=None),
        text_signature = "(tca, routing, s_start=0.0, s_end=None, length_ratio=None)")]
    fn tca(tca: PyTca, routing: PyRouting, s_start: Real, s_end: Option<Real>, length_ratio: Option<Real>) -> PyResult<Self> {
        let law = Arc::new(TcaLaw(tca.inner.clone()));
        Ok(PyActuator {
            inner: make_actuator(routing, s_start, s_end, length_ratio, law)?,
            tca: Some(tca),
        })
    }
    /// A tendon whose input is its tension [N] (>= 0).
    #[staticmethod]
    #[pyo3(signature = (routing, s_start=Real(0.0), s_end=None, length_ratio=None),
        text_signature = "(routing, s_start=0.0, s_end=None, length_ratio=None)")]
    fn tendon(routing: PyRouting, s_start: Real, s_end: Option<Real>, length_ratio: Option<Real>) -> PyResult<Self> {
        Ok(PyActuator {
            inner: make_actuator(routing, s_start, s_end, length_ratio, Arc::new(ConstantTension))?,
            tca: None,
        })
    }
    /// An elastic tendon of `stiffness` [N/m] whose input is the length pulled in at the base [m].
    #[staticmethod]
    #[pyo3(signature = (stiffness, routing, s_start=Real(0.0), s_end=None, length_ratio=None),
        text_signature = "(stiffness, routing, s_start=0.0, s_end=None, length_ratio=None)")]
    fn linear_tendon(stiffness: Real, routing: PyRouting, s_start: Real, s_end: Option<Real>, length_ratio: Option<Real>) -> PyResult<Self> {
        let stiffness = crate::error::positive("stiffness [N/m]", stiffness.0)?;
        Ok(PyActuator {
            inner: make_actuator(routing, s_start, s_end, length_ratio, Arc::new(LinearTendon { stiffness }))?,
            tca: None,
        })
    }
    /// `"tca"`, `"tension"` or `"linear_tendon"`.
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.law.kind()
    }
    /// Name and unit of the input.
    #[getter]
    fn input_name(&self) -> &'static str {
        self.inner.law.input_name()
    }
    /// `(lowest, highest)` valid input.
    #[getter]
    fn input_bounds(&self) -> (f64, f64) {
        self.inner.law.input_bounds()
    }
    /// Input of the passive (reference) state.
    #[getter]
    fn reference_input(&self) -> f64 {
        self.inner.law.reference_input()
    }
    #[getter]
    fn routing(&self) -> PyRouting {
        PyRouting { inner: self.inner.routing }
    }
    #[getter]
    fn s_start(&self) -> f64 {
        self.inner.s_start
    }
    /// Distal anchor [m]; `inf` means the tip.
    #[getter]
    fn s_end(&self) -> f64 {
        self.inner.s_end
    }
    #[getter]
    fn length_ratio(&self) -> Option<f64> {
        self.inner.length_ratio
    }
    /// The TCA, for TCA actuators.
    #[getter]
    fn tca_model(&self) -> Option<PyTca> {
        self.tca.clone()
    }
    /// Tension [N] at total elongation `elongation` [m] and `input`.
    fn tension(&self, elongation: Real, input: Real) -> PyResult<f64> {
        let elongation = crate::error::finite("elongation [m]", elongation.0)?;
        self.inner.law.check_input(input.0)?;
        Ok(finite_output("tension [N]", self.inner.law.tension(elongation, input.0)?)?)
    }
    fn __repr__(&self) -> String {
        format!(
            "Actuator(kind={:?}, routing={:?}, s_start={}, s_end={})",
            self.kind(),
            self.inner.routing,
            self.inner.s_start,
            self.inner.s_end
        )
    }
}

/// A body with its embedded actuators.
#[pyclass(name = "Robot", module = "tcarod._core", frozen, subclass)]
#[derive(Clone)]
pub struct PyRobot {
    pub(crate) inner: Arc<Robot>,
    pub(crate) body: PyBody,
    pub(crate) actuators: Vec<PyActuator>,
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

#[derive(FromPyObject)]
pub(crate) enum Inputs {
    One(Real),
    Many(Vec<Real>),
}

impl Inputs {
    pub(crate) fn into_vec(self) -> Vec<f64> {
        match self {
            Inputs::One(x) => vec![x.0],
            Inputs::Many(v) => v.into_iter().map(|x| x.0).collect(),
        }
    }
}

/// A non-negative integer argument (a count): saturates instead of raising
/// `OverflowError`, so that out-of-range values reach validation and fail
/// with a `ValueError` naming the argument (negative -> 0, beyond `usize`
/// -> `usize::MAX`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Count(pub usize);

impl<'py> FromPyObject<'_, 'py> for Count {
    type Error = PyErr;

    fn extract(obj: Borrowed<'_, 'py, PyAny>) -> PyResult<Self> {
        match obj.extract::<usize>() {
            Ok(v) => Ok(Count(v)),
            Err(e) if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(obj.py()) => {
                Ok(Count(if obj.gt(0)? { usize::MAX } else { 0 }))
            }
            Err(e) => Err(e),
        }
    }
}

/// Every number of a solution is finite (the IVP rejects non-finite
/// derivatives, so this holds by construction; checked once more at the
/// boundary so that no getter can hand NaN to Python).
fn checked_solution(sol: Solution) -> Result<Solution> {
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
        && sol.rotations.iter().all(|r| r.iter().all(|x| x.is_finite()))
        && sol.s.iter().chain(&sol.tensions).chain(&sol.elongations).chain(&sol.unknowns).all(|x| x.is_finite())
        && sol.elongation_profile.iter().flatten().all(|x| x.is_finite())
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
    #[pyo3(signature = (body, actuators=Vec::new()))]
    fn new(body: PyBody, actuators: Vec<PyActuator>) -> PyResult<Self> {
        let len = body.inner.length;
        let acts: Vec<Actuator> = actuators
            .iter()
            .map(|a| {
                let mut x = a.inner.clone();
                if x.s_end.is_infinite() {
                    x.s_end = len;
                }
                x
            })
            .collect();
        let robot = Robot::new(body.inner.clone(), acts)?;
        Ok(PyRobot {
            inner: Arc::new(robot),
            body,
            actuators,
        })
    }
    #[getter]
    fn body(&self) -> PyBody {
        self.body.clone()
    }
    #[getter]
    fn actuators(&self) -> Vec<PyActuator> {
        self.actuators.clone()
    }
    /// Passive inputs (ambient temperature for TCAs, zero for tendons).
    #[getter]
    fn reference_inputs(&self) -> Vec<f64> {
        self.inner.reference_inputs()
    }

    /// Solve the forward kinetostatics for one input per actuator (temperature
    /// [C] for TCAs). `warm_start`: a nearby `Solution` of this robot.
    /// Raises `ValueError` on bad input and `ConvergenceError` if Newton fails.
    #[pyo3(signature = (inputs, *, steps=Count(100), tol=Real(1e-10), max_iter=Count(50), warm_start=None),
        text_signature = "($self, inputs, *, steps=100, tol=1e-10, max_iter=50, warm_start=None)")]
    fn solve(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        inputs: Inputs,
        steps: Count,
        tol: Real,
        max_iter: Count,
        warm_start: Option<PyRef<'_, PySolution>>,
    ) -> PyResult<PySolution> {
        let this = slf.get();
        let opts = options(steps.0, tol.0, max_iter.0)?;
        let q = inputs.into_vec();
        let robot = this.inner.clone();
        let warm = warm_start.map(|w| w.inner.clone());
        let sol = super::errors::detach_interruptible(py, || solve(&robot, &q, &opts, warm.as_ref()).and_then(checked_solution))?;
        Ok(PySolution {
            inner: sol,
            robot: slf.clone().unbind(),
        })
    }

    /// Solve along rows of `inputs` (shape `(k, n_actuators)`), each warm-started
    /// from the previous one. Returns a list of `Solution`.
    #[pyo3(signature = (inputs, *, steps=Count(100), tol=Real(1e-10), max_iter=Count(50)),
        text_signature = "($self, inputs, *, steps=100, tol=1e-10, max_iter=50)")]
    fn sweep(slf: &Bound<'_, Self>, py: Python<'_>, inputs: Vec<Vec<Real>>, steps: Count, tol: Real, max_iter: Count) -> PyResult<Vec<PySolution>> {
        let opts = options(steps.0, tol.0, max_iter.0)?;
        let inputs: Vec<Vec<f64>> = inputs.into_iter().map(|row| row.into_iter().map(|x| x.0).collect()).collect();
        let robot = slf.get().inner.clone();
        let sols = super::errors::detach_interruptible(py, || {
            crate::shooting::sweep(&robot, &inputs, &opts)?.into_iter().map(checked_solution).collect::<Result<Vec<_>>>()
        })?;
        Ok(sols
            .into_iter()
            .map(|s| PySolution {
                inner: s,
                robot: slf.clone().unbind(),
            })
            .collect())
    }

    fn __repr__(&self) -> String {
        format!("Robot(body length={} m, actuators={})", self.inner.body.length, self.inner.actuators.len())
    }
}

/// A converged forward solution. Arrays are NumPy, SI units, world frame
/// unless noted; `n` nodes along the body.
#[pyclass(name = "Solution", module = "tcarod._core", frozen)]
pub struct PySolution {
    pub(crate) inner: Solution,
    pub(crate) robot: Py<PyRobot>,
}

fn stack3<'py>(py: Python<'py>, v: &[Vector3<f64>]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flat_map(|x| [x.x, x.y, x.z]).collect();
    PyArray1::from_vec(py, flat).reshape([v.len(), 3]).expect("n x 3")
}

#[pymethods]
impl PySolution {
    /// The robot solved.
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
        PyArray1::from_vec(py, flat).reshape([self.inner.rotations.len(), 3, 3]).expect("n x 3 x 3")
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
        let flat: Vec<f64> = self.inner.elongation_profile.iter().flatten().copied().collect();
        PyArray1::from_vec(py, flat).reshape([self.inner.s.len(), na]).expect("n x na")
    }
    /// Path of each actuator `p + R r_i` [m] over its span: list of `(k_i, 3)` arrays.
    #[getter]
    fn actuator_paths<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        self.inner.actuator_paths.iter().map(|p| stack3(py, p)).collect()
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
    /// Newton iterations used.
    #[getter]
    fn iterations(&self) -> usize {
        self.inner.iterations
    }
    /// IVPs integrated.
    #[getter]
    fn evaluations(&self) -> usize {
        self.inner.evaluations
    }
    /// Final residual (max-norm, dimensionless strain units).
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
    fn plot<'py>(slf: &Bound<'py, Self>, kwargs: Option<&Bound<'py, PyDict>>) -> PyResult<Bound<'py, PyAny>> {
        let py = slf.py();
        py.import("tcarod.plotting")?.getattr("plot_solution")?.call((slf,), kwargs)
    }
    fn __repr__(&self) -> String {
        let p = self.inner.tip_position();
        format!(
            "Solution(tip=[{:.6e}, {:.6e}, {:.6e}] m, iterations={}, residual={:.2e})",
            p.x, p.y, p.z, self.inner.iterations, self.inner.residual
        )
    }
}
