//! Bindings of the soft body (Cosserat rod).

use nalgebra::Vector3;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::section::{section_repr, PySection};
use crate::error::Error;
use crate::python::to_py::{hash_by_text, keyword_args, mat3, vec3, vec3_getters, NewArgs};
use crate::python::{pf, pv, vec3_arg, Real};
use crate::rod::{Body, Shear};

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
#[pyclass(name = "Body", module = "tcarod._core", frozen, eq, hash)]
#[derive(Clone, PartialEq)]
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
        let shear = Shear::from_options(poisson.map(|r| r.0), shear_modulus.map(|r| r.0))?;
        let mut b = Body::with_shear(length.0, section.inner, youngs_modulus.0, shear, density.0)?;
        let v = |name: &str, o: &Option<Bound<'_, PyAny>>, d: [f64; 3]| {
            vec3_arg(name, o.as_ref(), d).map(Vector3::from)
        };
        b.shear_coefficient = shear_coefficient.0;
        b.nu_star = v("nu_star", &nu_star, [0.0, 0.0, 1.0])?;
        b.omega_star = v("omega_star", &omega_star, [0.0; 3])?;
        b.gravity = v("gravity", &gravity, [0.0; 3])?;
        b.distributed_force = v("distributed_force", &distributed_force, [0.0; 3])?;
        b.distributed_moment = v("distributed_moment", &distributed_moment, [0.0; 3])?;
        b.tip_force = v("tip_force", &tip_force, [0.0; 3])?;
        b.tip_moment = v("tip_moment", &tip_moment, [0.0; 3])?;
        b.validate()?;
        if let Some(msg) = b.units_warning() {
            crate::python::warn_units(py, msg)?;
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
    /// Total distributed force `psi A g + f` [N/m], world frame.
    #[getter]
    fn distributed_load<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        vec3(py, &self.inner.distributed_load())
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
    fn __repr__(&self) -> String {
        body_repr(&self.inner)
    }
    /// Constructor arguments, for pickle and copy.
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> NewArgs<'py> {
        keyword_args(self.kwargs(py)?)
    }
}

hash_by_text!(PyBody, |b| body_repr(&b.inner));

vec3_getters!(PyBody {
    nu_star => "Reference linear strain `nu*` [-] (body frame), shape `(3,)`.",
    omega_star => "Reference angular strain `omega*` [1/m] (body frame), shape `(3,)`.",
    gravity => "Gravitational acceleration [m/s^2] (world frame), shape `(3,)`.",
    tip_force => "Force applied to the tip [N] (world frame), shape `(3,)`.",
    tip_moment => "Moment applied to the tip [N m] (world frame), shape `(3,)`.",
    distributed_moment => "Distributed moment [N m/m] (world frame), shape `(3,)`.",
    distributed_force => "Distributed force [N/m] besides gravity (world frame), shape `(3,)`."
});

/// Constructor call of a body, defaults left out (round-trips with `eval`).
pub(crate) fn body_repr(b: &Body) -> String {
    let section = section_repr(&b.section);
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
