//! Bindings of the TCA law.

use std::f64::consts::FRAC_PI_2;

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyType;

use super::errors::finite_output;
use super::material::{material_repr, PyMaterial};
use super::to_py::{hash_by_text, positional_args, NewArgs};
use super::{pf, ps, Real};
use crate::error::{Error, Result};
use crate::material::Material;
use crate::tca::{Chirality, Tca};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyTca>()?;
    Ok(())
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
    let a = a.as_slice()?;
    let b = b.as_slice()?;
    if a.len() != b.len() {
        return Err(Error::input(
            "arrays",
            format!("lengths differ ({} and {})", a.len(), b.len()),
        )
        .into());
    }
    let pairs: Vec<(f64, f64)> = a.iter().copied().zip(b.iter().copied()).collect();
    map_elements(py, output, &pairs, |&(x, y)| f(x, y))
}

/// [`map2`] over one array.
fn map1(
    py: Python<'_>,
    output: &str,
    a: &PyReadonlyArray1<'_, f64>,
    f: impl Fn(f64) -> Result<f64> + Send + Sync,
) -> PyResult<Py<PyArray1<f64>>> {
    map_elements(py, output, a.as_slice()?, |&x| f(x))
}

/// `f` of every element, without the GIL; errors name the element's index.
fn map_elements<T: Sync>(
    py: Python<'_>,
    output: &str,
    elements: &[T],
    f: impl Fn(&T) -> Result<f64> + Send + Sync,
) -> PyResult<Py<PyArray1<f64>>> {
    let out: Result<Vec<f64>> = py.detach(|| {
        elements
            .iter()
            .enumerate()
            .map(|(i, x)| {
                f(x).and_then(|v| finite_output(output, v))
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

/// A twisted-and-coiled actuator (paper Section II).
///
/// `Tca(fibre_length [m], coiled_length [m], coil_diameter [m], turns,
/// chirality='extension', material=None)`. See `tcarod.Tca` for the
/// NumPy-vectorised law. Value object: `==`, hashable, picklable.
///
/// Examples
/// --------
/// >>> tca = tcarod._core.Tca(0.15, 0.04, 0.0017, 38.2)   # l, L, D [m], N [turns]
/// >>> round(tca.alpha0, 4), round(tca.d0 * 1e3, 4)       # [rad], [mm]
/// (0.2699, 0.9067)
#[pyclass(name = "Tca", module = "tcarod._core", subclass, frozen, eq, hash)]
#[derive(Clone, PartialEq)]
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
        if let Some(msg) = tca.inner.units_warning() {
            Python::attach(|py| super::warn_units(py, msg))?;
        }
        Ok(tca)
    }

    /// Build from coiled length `L` [m] and pitch angle `alpha0` [rad]: `l = L / sin(alpha0)`.
    #[classmethod]
    #[pyo3(signature = (coiled_length, alpha0, coil_diameter, turns, chirality="extension", material=None),
        text_signature = "($cls, coiled_length, alpha0, coil_diameter, turns, chirality='extension', material=None)")]
    fn from_pitch_angle(
        cls: &Bound<'_, PyType>,
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
        // Construct through the (possibly Python-subclassed) class.
        Ok(cls.call1(constructor_args(&t))?.unbind())
    }

    /// The fraction `fraction` [-] (`0 < fraction <= 1`) of this TCA as a segment in series.
    ///
    /// Fibre length, coiled length and turns scaled by
    /// `fraction`; same coil diameter, `alpha0`, `d0`, twist density,
    /// chirality and material. Returns an instance of this object's class.
    fn segment(slf: &Bound<'_, Self>, fraction: Real) -> PyResult<Py<PyAny>> {
        let t = slf.get().inner.segment(fraction.0)?;
        Ok(slf.get_type().call1(constructor_args(&t))?.unbind())
    }

    /// Twisted-fibre length `l` [m] (before coiling).
    ///
    /// Returns
    /// -------
    /// float
    ///     `l` [m].
    #[getter]
    fn fibre_length(&self) -> f64 {
        self.inner.fibre_length()
    }
    /// Coiled length `L` [m] with the coils touching.
    ///
    /// Returns
    /// -------
    /// float
    ///     `L` [m], `0 < L < l/2`.
    #[getter]
    fn coiled_length(&self) -> f64 {
        self.inner.coiled_length()
    }
    /// Outer coil diameter `D` [m].
    ///
    /// Returns
    /// -------
    /// float
    ///     `D` [m].
    #[getter]
    fn coil_diameter(&self) -> f64 {
        self.inner.coil_diameter()
    }
    /// Inserted twist `N` [turns].
    ///
    /// Returns
    /// -------
    /// float
    ///     `N` [turns].
    #[getter]
    fn turns(&self) -> f64 {
        self.inner.turns()
    }
    /// Which way the TCA moves when heated.
    ///
    /// Returns
    /// -------
    /// str
    ///     `"extension"` (lengthens when heated) or `"contraction"` (shortens
    ///     when heated); no unit.
    #[getter]
    fn chirality(&self) -> &'static str {
        chirality_name(self.inner.chirality())
    }
    /// The fibre material.
    ///
    /// Returns
    /// -------
    /// Material
    ///     Its moduli [Pa] and expansion [1/C] over its range [C].
    #[getter]
    fn material(&self) -> PyMaterial {
        PyMaterial {
            inner: self.inner.material().clone(),
        }
    }
    /// Initial pitch angle `alpha0 = asin(L/l)` [rad].
    ///
    /// Returns
    /// -------
    /// float
    ///     `alpha0` [rad].
    #[getter]
    fn alpha0(&self) -> f64 {
        self.inner.alpha0()
    }
    /// Number of coils `n = 2 cos(alpha0) l / (pi D)` [-].
    ///
    /// Returns
    /// -------
    /// float
    ///     `n` [-].
    #[getter]
    fn n_coils(&self) -> f64 {
        self.inner.n_coils()
    }
    /// Inserted twist angle `phi0 = 2 pi N` [rad].
    ///
    /// Returns
    /// -------
    /// float
    ///     `phi0` [rad].
    #[getter]
    fn phi0(&self) -> f64 {
        self.inner.phi0()
    }
    /// Fibre diameter at the reference temperature `d0 = 2 D L / l` [m].
    ///
    /// Returns
    /// -------
    /// float
    ///     `d0` [m].
    #[getter]
    fn d0(&self) -> f64 {
        self.inner.d0()
    }
    /// Elongation [m] at which the fibre would be straight (`l - L`).
    ///
    /// Returns
    /// -------
    /// float
    ///     `l - L` [m], the upper bound of the law.
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
    fn _free_stroke_flat(
        &self,
        py: Python<'_>,
        temperature: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Py<PyArray1<f64>>> {
        map1(py, "free_stroke [m]", &temperature, |t| {
            self.inner.free_stroke(t)
        })
    }
    fn _blocked_force_flat(
        &self,
        py: Python<'_>,
        temperature: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Py<PyArray1<f64>>> {
        map1(py, "blocked_force [N]", &temperature, |t| {
            self.inner.blocked_force(t)
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
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> NewArgs<'py> {
        positional_args(constructor_args(&self.inner), py)
    }
}

hash_by_text!(PyTca, |t| format!("{:?}", t.inner));

/// `Tca(...)` positional constructor arguments of `t`.
fn constructor_args(t: &Tca) -> (f64, f64, f64, f64, &'static str, PyMaterial) {
    let material = PyMaterial {
        inner: t.material().clone(),
    };
    let (l, big_l, d, n) = (
        t.fibre_length(),
        t.coiled_length(),
        t.coil_diameter(),
        t.turns(),
    );
    (l, big_l, d, n, chirality_name(t.chirality()), material)
}

/// `"extension"` or `"contraction"`, as Python spells the chirality.
fn chirality_name(c: Chirality) -> &'static str {
    match c {
        Chirality::Extension => "extension",
        Chirality::Contraction => "contraction",
    }
}
