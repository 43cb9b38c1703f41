//! Bindings of the material and the TCA law.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use super::{hash_text, pf, ps};

use std::f64::consts::FRAC_PI_2;

use super::errors::finite_output;
use super::Real;
use crate::error::{Error, Result};
use crate::material::Material;
use crate::tca::{Chirality, Tca};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMaterial>()?;
    m.add_class::<PyTca>()?;
    Ok(())
}

/// Temperature-dependent properties of a TCA's twisted fibre.
///
/// `Material(*, youngs_modulus, shear_modulus, expansion, youngs_modulus_slope=0.0,
/// shear_modulus_slope=None, expansion_slope=0.0, t_ref=25.0, t_min=25.0,
/// t_max=160.0, name='custom')`: moduli E [Pa] and G [Pa] at `t_ref` [C] with
/// slopes [Pa/C] (G's default keeps G/E constant), radial expansion `rho` [1/C]
/// at `t_ref` with slope [1/C^2], valid range `t_min..t_max` [C].
/// `Material.silver_coated_nylon()` is the paper's thread (valid 25-160 C,
/// not extrapolated): for a colder ambient build a `Material` with `t_ref` and
/// `t_min` at that ambient. Value object: `==`, hashable, picklable.
#[pyclass(name = "Material", module = "tcarod._core", frozen)]
#[derive(Clone)]
pub struct PyMaterial {
    pub(crate) inner: Material,
}

#[pymethods]
impl PyMaterial {
    #[new]
    #[pyo3(signature = (*, youngs_modulus, shear_modulus, expansion, youngs_modulus_slope=Real(0.0),
        shear_modulus_slope=None, expansion_slope=Real(0.0), t_ref=Real(25.0), t_min=Real(25.0), t_max=Real(160.0),
        name="custom".to_string()),
        text_signature = "(*, youngs_modulus, shear_modulus, expansion, youngs_modulus_slope=0.0, \
            shear_modulus_slope=None, expansion_slope=0.0, t_ref=25.0, t_min=25.0, t_max=160.0, name='custom')")]
    #[allow(clippy::too_many_arguments)]
    fn new(
        youngs_modulus: Real,
        shear_modulus: Real,
        expansion: Real,
        youngs_modulus_slope: Real,
        shear_modulus_slope: Option<Real>,
        expansion_slope: Real,
        t_ref: Real,
        t_min: Real,
        t_max: Real,
        name: String,
    ) -> PyResult<Self> {
        let (Real(youngs_modulus), Real(shear_modulus), Real(expansion)) =
            (youngs_modulus, shear_modulus, expansion);
        let (Real(youngs_modulus_slope), Real(expansion_slope)) =
            (youngs_modulus_slope, expansion_slope);
        let shear_modulus_slope = shear_modulus_slope.map(|r| r.0);
        let (Real(t_ref), Real(t_min), Real(t_max)) = (t_ref, t_min, t_max);
        let g_slope =
            shear_modulus_slope.unwrap_or(youngs_modulus_slope * shear_modulus / youngs_modulus);
        Ok(PyMaterial {
            inner: Material::new(
                name,
                youngs_modulus,
                youngs_modulus_slope,
                shear_modulus,
                g_slope,
                expansion,
                expansion_slope,
                t_ref,
                t_min,
                t_max,
            )?,
        })
    }

    /// The paper's silver-coated nylon 6,6 thread with the documented defaults.
    #[staticmethod]
    fn silver_coated_nylon() -> Self {
        PyMaterial {
            inner: Material::silver_coated_nylon(),
        }
    }

    /// The same thread with the measured radial CTE of oriented nylon 6,6
    /// (Choy et al. 1984) in place of the Sun & Zhao diameter fit.
    #[staticmethod]
    fn nylon66_measured_cte() -> Self {
        PyMaterial {
            inner: Material::nylon66_measured_cte(),
        }
    }
    /// Measured radial CTE [1/K] of oriented nylon 6,6 at `temperature` [C]
    /// (Choy et al. 1984, linear interpolation, -41..160 C).
    #[staticmethod]
    fn measured_radial_cte(temperature: Real) -> PyResult<f64> {
        Ok(crate::material::nylon66_radial_cte(temperature.0)?)
    }
    /// The measured data `[(T [C], alpha_r [1/K]), ...]` behind `measured_radial_cte`.
    #[staticmethod]
    fn measured_radial_cte_data() -> Vec<(f64, f64)> {
        crate::material::NYLON66_RADIAL_CTE.to_vec()
    }
    /// This material with `rho(T)` scaled by `factor` [-] (identification studies).
    fn with_expansion_scale(&self, factor: Real) -> PyResult<Self> {
        Ok(PyMaterial {
            inner: self.inner.with_expansion_scale(factor.0)?,
        })
    }
    /// Instantaneous expansion coefficient `d'(T)/d(T)` [1/C] at `temperature` [C].
    fn instantaneous_expansion(&self, temperature: Real) -> PyResult<f64> {
        Ok(finite_output(
            "instantaneous_expansion [1/C]",
            self.inner.instantaneous_expansion(temperature.0)?,
        )?)
    }

    /// Name of the material (free text, e.g. `"my nylon"`).
    #[getter]
    fn name(&self) -> String {
        self.inner.name().to_string()
    }
    /// Reference (ambient, passive) temperature `t_ref` [C]: the coefficients are given there.
    #[getter]
    fn t_ref(&self) -> f64 {
        self.inner.t_ref()
    }
    /// Lowest valid temperature `t_min` [C]. For an ambient below the preset's
    /// 25 C build `Material(..., t_ref=..., t_min=...)` with coefficients valid there.
    #[getter]
    fn t_min(&self) -> f64 {
        self.inner.t_min()
    }
    /// Highest valid temperature `t_max` [C].
    #[getter]
    fn t_max(&self) -> f64 {
        self.inner.t_max()
    }
    /// `(E_ref [Pa], dE/dT [Pa/C], G_ref [Pa], dG/dT [Pa/C], rho_ref [1/C], drho/dT [1/C^2])`.
    #[getter]
    fn coefficients(&self) -> (f64, f64, f64, f64, f64, f64) {
        self.inner.coefficients()
    }
    /// Young's modulus `E(T)` [Pa] of the fibre at `temperature` [C].
    fn youngs_modulus(&self, temperature: Real) -> PyResult<f64> {
        Ok(finite_output(
            "youngs_modulus [Pa]",
            self.inner.youngs_modulus(temperature.0)?,
        )?)
    }
    /// Shear modulus `G(T)` [Pa] of the fibre at `temperature` [C].
    fn shear_modulus(&self, temperature: Real) -> PyResult<f64> {
        Ok(finite_output(
            "shear_modulus [Pa]",
            self.inner.shear_modulus(temperature.0)?,
        )?)
    }
    /// Radial expansion coefficient `rho(T)` [1/C] at `temperature` [C].
    fn expansion(&self, temperature: Real) -> PyResult<f64> {
        Ok(finite_output(
            "expansion [1/C]",
            self.inner.expansion(temperature.0)?,
        )?)
    }
    /// Fibre diameter ratio `d(T)/d(t_ref) = 1 + rho(T) (T - t_ref)` [-] at `temperature` [C].
    fn diameter_ratio(&self, temperature: Real) -> PyResult<f64> {
        Ok(finite_output(
            "diameter_ratio [-]",
            self.inner.diameter_ratio(temperature.0)?,
        )?)
    }
    fn __repr__(&self) -> String {
        material_repr(&self.inner)
    }
    /// Constructor arguments, for pickle and copy.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let m = &self.inner;
        let (e, es, g, gs, r, rs) = m.coefficients();
        let d = PyDict::new(py);
        for (k, v) in [
            ("youngs_modulus", e),
            ("shear_modulus", g),
            ("expansion", r),
            ("youngs_modulus_slope", es),
            ("shear_modulus_slope", gs),
            ("expansion_slope", rs),
            ("t_ref", m.t_ref()),
            ("t_min", m.t_min()),
            ("t_max", m.t_max()),
        ] {
            d.set_item(k, v)?;
        }
        d.set_item("name", m.name())?;
        Ok((PyTuple::empty(py), d))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> Option<bool> {
        other
            .cast::<PyMaterial>()
            .ok()
            .map(|o| o.get().inner == self.inner)
    }
    fn __hash__(&self) -> u64 {
        hash_text(&material_repr(&self.inner))
    }
}

/// Python-syntax repr of a material: the preset's constructor call if it is
/// the preset, the full keyword call otherwise (round-trips with `eval`).
pub(crate) fn material_repr(m: &Material) -> String {
    if *m == Material::silver_coated_nylon() {
        return "Material.silver_coated_nylon()".into();
    }
    let (e, es, g, gs, r, rs) = m.coefficients();
    format!(
        "Material(youngs_modulus={}, shear_modulus={}, expansion={}, youngs_modulus_slope={}, \
         shear_modulus_slope={}, expansion_slope={}, t_ref={}, t_min={}, t_max={}, name={})",
        pf(e),
        pf(g),
        pf(r),
        pf(es),
        pf(gs),
        pf(rs),
        pf(m.t_ref()),
        pf(m.t_min()),
        pf(m.t_max()),
        ps(m.name())
    )
}

/// Error unless `alpha` is a pitch angle strictly between 0 and 90 degrees.
fn check_alpha(alpha: f64) -> Result<f64> {
    if alpha.is_finite() && alpha > 0.0 && alpha < FRAC_PI_2 {
        Ok(alpha)
    } else {
        Err(Error::param("alpha [rad]", alpha, "0 < alpha < pi/2"))
    }
}

pub(crate) fn parse_chirality(s: &str) -> Result<Chirality> {
    match s {
        "extension" => Ok(Chirality::Extension),
        "contraction" => Ok(Chirality::Contraction),
        _ => Err(Error::input(
            "chirality",
            format!("{s:?} is not one of 'extension', 'contraction'"),
        )),
    }
}

/// Apply `f` elementwise over two equal-length arrays, naming the index of the
/// first failing element in the error; `output` names the result (with its
/// unit) in the error raised if a result is not finite.
fn map2(
    py: Python<'_>,
    output: &str,
    a: &PyReadonlyArray1<'_, f64>,
    b: &PyReadonlyArray1<'_, f64>,
    f: impl Fn(f64, f64) -> Result<f64> + Send + Sync,
) -> PyResult<Py<PyArray1<f64>>> {
    let a = a.as_slice()?.to_vec();
    let b = b.as_slice()?.to_vec();
    if a.len() != b.len() {
        return Err(Error::input(
            "arrays",
            format!("lengths differ ({} and {})", a.len(), b.len()),
        )
        .into());
    }
    let out: Result<Vec<f64>> = py.detach(|| {
        a.iter()
            .zip(&b)
            .enumerate()
            .map(|(i, (&x, &y))| {
                f(x, y)
                    .and_then(|v| finite_output(output, v))
                    .map_err(|e| match e {
                        Error::NoSolution { reason } => Error::NoSolution {
                            reason: format!("element {i}: {reason}"),
                        },
                        other => other.renamed(|name| format!("{name} (element {i})")),
                    })
            })
            .collect()
    });
    Ok(PyArray1::from_vec(py, out?).unbind())
}

/// A twisted-and-coiled actuator (paper Section II):
/// `Tca(fibre_length [m], coiled_length [m], coil_diameter [m], turns,
/// chirality='extension', material=None)`. See `tcarod.Tca` for the
/// NumPy-vectorised law. Value object: `==`, hashable, picklable.
#[pyclass(name = "Tca", module = "tcarod._core", subclass, frozen)]
#[derive(Clone)]
pub struct PyTca {
    pub(crate) inner: Tca,
}

#[pymethods]
impl PyTca {
    #[new]
    #[pyo3(signature = (fibre_length, coiled_length, coil_diameter, turns, chirality="extension", material=None),
        text_signature = "(fibre_length, coiled_length, coil_diameter, turns, chirality='extension', material=None)")]
    fn new(
        fibre_length: Real,
        coiled_length: Real,
        coil_diameter: Real,
        turns: Real,
        chirality: &str,
        material: Option<PyMaterial>,
    ) -> PyResult<Self> {
        let material = material.map_or_else(Material::silver_coated_nylon, |m| m.inner);
        let tca = PyTca {
            inner: Tca::new(
                fibre_length.0,
                coiled_length.0,
                coil_diameter.0,
                turns.0,
                parse_chirality(chirality)?,
                material,
            )?,
        };
        // valid, but perhaps in mm: warn (after validation, so bad values raise first)
        if let Some(msg) = crate::validate::coil_diameter_looks_like_mm(tca.inner.coil_diameter()) {
            Python::attach(|py| super::warn_units(py, msg))?;
        }
        Ok(tca)
    }

    /// Build from coiled length `L` [m] and pitch angle `alpha0` [rad]: `l = L / sin(alpha0)`.
    #[classmethod]
    #[pyo3(signature = (coiled_length, alpha0, coil_diameter, turns, chirality="extension", material=None),
        text_signature = "($cls, coiled_length, alpha0, coil_diameter, turns, chirality='extension', material=None)")]
    fn from_pitch_angle(
        cls: &Bound<'_, pyo3::types::PyType>,
        coiled_length: Real,
        alpha0: Real,
        coil_diameter: Real,
        turns: Real,
        chirality: &str,
        material: Option<PyMaterial>,
    ) -> PyResult<Py<PyAny>> {
        let material = material.map_or_else(Material::silver_coated_nylon, |m| m.inner);
        let t = Tca::from_pitch_angle(
            coiled_length.0,
            alpha0.0,
            coil_diameter.0,
            turns.0,
            parse_chirality(chirality)?,
            material,
        )?;
        let mat = PyMaterial {
            inner: t.material().clone(),
        };
        // Construct through the (possibly Python-subclassed) class.
        Ok(cls
            .call1((
                t.fibre_length(),
                t.coiled_length(),
                t.coil_diameter(),
                t.turns(),
                chirality,
                mat,
            ))?
            .unbind())
    }

    /// The fraction `fraction` (`0 < fraction <= 1`) of this TCA as a
    /// segment in series: fibre length, coiled length and turns scaled by
    /// `fraction`; same coil diameter, `alpha0`, `d0`, twist density,
    /// chirality and material. Returns an instance of this object's class.
    fn segment(slf: &Bound<'_, Self>, fraction: Real) -> PyResult<Py<PyAny>> {
        let t = slf.get().inner.segment(fraction.0)?;
        let chirality = match t.chirality() {
            Chirality::Extension => "extension",
            Chirality::Contraction => "contraction",
        };
        let mat = PyMaterial {
            inner: t.material().clone(),
        };
        Ok(slf
            .get_type()
            .call1((
                t.fibre_length(),
                t.coiled_length(),
                t.coil_diameter(),
                t.turns(),
                chirality,
                mat,
            ))?
            .unbind())
    }

    /// Twisted-fibre length `l` [m] (before coiling).
    #[getter]
    fn fibre_length(&self) -> f64 {
        self.inner.fibre_length()
    }
    /// Coiled length `L` [m] with the coils touching (`0 < L < l/2`).
    #[getter]
    fn coiled_length(&self) -> f64 {
        self.inner.coiled_length()
    }
    /// Outer coil diameter `D` [m].
    #[getter]
    fn coil_diameter(&self) -> f64 {
        self.inner.coil_diameter()
    }
    /// Inserted twist `N` [turns].
    #[getter]
    fn turns(&self) -> f64 {
        self.inner.turns()
    }
    /// `"extension"` (lengthens when heated) or `"contraction"` (shortens when heated).
    #[getter]
    fn chirality(&self) -> &'static str {
        match self.inner.chirality() {
            Chirality::Extension => "extension",
            Chirality::Contraction => "contraction",
        }
    }
    /// The fibre material (`Material`).
    #[getter]
    fn material(&self) -> PyMaterial {
        PyMaterial {
            inner: self.inner.material().clone(),
        }
    }
    /// Initial pitch angle `alpha0 = asin(L/l)` [rad].
    #[getter]
    fn alpha0(&self) -> f64 {
        self.inner.alpha0()
    }
    /// Number of coils `n = 2 cos(alpha0) l / (pi D)` [-].
    #[getter]
    fn n_coils(&self) -> f64 {
        self.inner.n_coils()
    }
    /// Inserted twist angle `phi0 = 2 pi N` [rad].
    #[getter]
    fn phi0(&self) -> f64 {
        self.inner.phi0()
    }
    /// Fibre diameter at the reference temperature `d0 = 2 D L / l` [m].
    #[getter]
    fn d0(&self) -> f64 {
        self.inner.d0()
    }
    /// Elongation [m] at which the fibre would be straight (`l - L`): the upper bound of the law.
    #[getter]
    fn max_displacement(&self) -> f64 {
        self.inner.max_displacement()
    }
    /// Pitch angle [rad] at elongation `displacement` [m], eq (5).
    fn pitch_angle(&self, displacement: Real) -> PyResult<f64> {
        Ok(self.inner.pitch_angle(displacement.0)?)
    }
    /// `f11` [m/N] of eq (3) at pitch angle `alpha` [rad] and `temperature` [C].
    fn f11(&self, alpha: Real, temperature: Real) -> PyResult<f64> {
        let a = check_alpha(alpha.0)?;
        Ok(finite_output(
            "f11 [m/N]",
            self.inner.at(temperature.0)?.f11(a),
        )?)
    }
    /// `f12` [1/N] (m of elongation per N m of torque) of eq (4) at pitch angle `alpha` [rad] and `temperature` [C].
    fn f12(&self, alpha: Real, temperature: Real) -> PyResult<f64> {
        let a = check_alpha(alpha.0)?;
        Ok(finite_output(
            "f12 [1/N]",
            self.inner.at(temperature.0)?.f12(a),
        )?)
    }
    /// Untwisting torque `tau` [N m] of eq (1) at `temperature` [C].
    fn torque(&self, temperature: Real) -> PyResult<f64> {
        Ok(finite_output(
            "torque [N m]",
            self.inner.at(temperature.0)?.tau,
        )?)
    }
    /// Fibre diameter `d` [m] at `temperature` [C].
    fn fibre_diameter(&self, temperature: Real) -> PyResult<f64> {
        Ok(finite_output(
            "fibre_diameter [m]",
            self.inner.at(temperature.0)?.d,
        )?)
    }
    fn _displacement_flat(
        &self,
        py: Python<'_>,
        force: PyReadonlyArray1<'_, f64>,
        temperature: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Py<PyArray1<f64>>> {
        map2(py, "displacement [m]", &force, &temperature, |f, t| {
            self.inner.displacement(f, t)
        })
    }
    fn _force_flat(
        &self,
        py: Python<'_>,
        displacement: PyReadonlyArray1<'_, f64>,
        temperature: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Py<PyArray1<f64>>> {
        map2(py, "force [N]", &displacement, &temperature, |d, t| {
            self.inner.force(d, t)
        })
    }
    fn _temperature_flat(
        &self,
        py: Python<'_>,
        force: PyReadonlyArray1<'_, f64>,
        displacement: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Py<PyArray1<f64>>> {
        map2(py, "temperature [C]", &force, &displacement, |f, d| {
            self.inner.temperature(f, d)
        })
    }
    pub(crate) fn __repr__(slf: &Bound<'_, Self>) -> PyResult<String> {
        let t = &slf.get().inner;
        let mat = if *t.material() == Material::silver_coated_nylon() {
            String::new()
        } else {
            format!(", material={}", material_repr(t.material()))
        };
        Ok(format!(
            "{}(fibre_length={}, coiled_length={}, coil_diameter={}, turns={}, chirality={}{mat})",
            slf.get_type().name()?,
            pf(t.fibre_length()),
            pf(t.coiled_length()),
            pf(t.coil_diameter()),
            pf(t.turns()),
            ps(slf.get().chirality()),
        ))
    }
    /// Constructor arguments, for pickle and copy.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        let t = &self.inner;
        let args = (
            t.fibre_length(),
            t.coiled_length(),
            t.coil_diameter(),
            t.turns(),
            self.chirality(),
            PyMaterial {
                inner: t.material().clone(),
            },
        )
            .into_pyobject(py)?;
        Ok((args, PyDict::new(py)))
    }
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> Option<bool> {
        other
            .cast::<PyTca>()
            .ok()
            .map(|o| o.get().inner == self.inner)
    }
    fn __hash__(&self) -> u64 {
        hash_text(&format!("{:?}", self.inner))
    }
}
