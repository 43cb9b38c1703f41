//! Bindings of the TCA fibre material.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::errors::finite_output;
use super::to_py::{hash_by_text, keyword_args, NewArgs};
use super::{pf, ps, Real};
use crate::material::Material;

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMaterial>()?;
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
///
/// Examples
/// --------
/// >>> m = tcarod.Material.silver_coated_nylon()      # the paper's thread
/// >>> m.t_ref, m.t_max                                # valid range [C]
/// (25.0, 160.0)
/// >>> round(m.youngs_modulus(100.0) / 1e9, 3)         # E at 100 C [GPa]
/// 1.101
/// >>> cold = tcarod.Material(youngs_modulus=1.2e9, shear_modulus=2.2e8, expansion=1e-4,
/// ...                        t_ref=10.0, t_min=10.0, name="nylon at 10 C")
/// >>> cold.t_min                                      # [C]
/// 10.0
#[pyclass(name = "Material", module = "tcarod._core", frozen, eq, hash)]
#[derive(Clone, PartialEq)]
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
        let g_slope = shear_modulus_slope.unwrap_or_else(|| {
            Material::proportional_shear_slope(youngs_modulus, youngs_modulus_slope, shear_modulus)
        });
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

    /// The paper's thread with the measured radial CTE of oriented nylon 6,6.
    ///
    /// The expansion `rho(T)` [1/C] follows Choy et al. 1984 in place of the
    /// Sun & Zhao diameter fit; moduli and range as `silver_coated_nylon`.
    #[staticmethod]
    fn nylon66_measured_cte() -> Self {
        PyMaterial {
            inner: Material::nylon66_measured_cte(),
        }
    }
    /// Measured radial CTE [1/K] of oriented nylon 6,6 at `temperature` [C].
    ///
    /// Choy et al. 1984, linear interpolation between the measured points,
    /// valid from -41 to 160 C (`ValueError` outside).
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
    ///
    /// Returns
    /// -------
    /// str
    ///     The name given to the constructor (no unit).
    #[getter]
    fn name(&self) -> String {
        self.inner.name().to_string()
    }
    /// Reference (ambient, passive) temperature `t_ref` [C].
    ///
    /// Returns
    /// -------
    /// float
    ///     The temperature [C] at which the coefficients are given.
    #[getter]
    fn t_ref(&self) -> f64 {
        self.inner.t_ref()
    }
    /// Lowest valid temperature `t_min` [C].
    ///
    /// For an ambient below the preset's 25 C build
    /// `Material(..., t_ref=..., t_min=...)` with coefficients valid there.
    ///
    /// Returns
    /// -------
    /// float
    ///     The lower end [C] of the valid temperature range.
    #[getter]
    fn t_min(&self) -> f64 {
        self.inner.t_min()
    }
    /// Highest valid temperature `t_max` [C].
    ///
    /// Returns
    /// -------
    /// float
    ///     The upper end [C] of the valid temperature range.
    #[getter]
    fn t_max(&self) -> f64 {
        self.inner.t_max()
    }
    /// The six coefficients of the linear temperature laws.
    ///
    /// Returns
    /// -------
    /// tuple of 6 float
    ///     `(E_ref [Pa], dE/dT [Pa/C], G_ref [Pa], dG/dT [Pa/C], rho_ref [1/C],
    ///     drho/dT [1/C^2])`, at `t_ref` [C].
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
    fn __getnewargs_ex__<'py>(&self, py: Python<'py>) -> NewArgs<'py> {
        let d = PyDict::new(py);
        for (k, v) in material_fields(&self.inner) {
            d.set_item(k, v)?;
        }
        d.set_item("name", self.inner.name())?;
        keyword_args(d)
    }
}

hash_by_text!(PyMaterial, |m| material_repr(&m.inner));

/// The constructor keywords of a material with their values (SI units).
fn material_fields(m: &Material) -> [(&'static str, f64); 9] {
    let (e, es, g, gs, r, rs) = m.coefficients();
    [
        ("youngs_modulus", e),
        ("shear_modulus", g),
        ("expansion", r),
        ("youngs_modulus_slope", es),
        ("shear_modulus_slope", gs),
        ("expansion_slope", rs),
        ("t_ref", m.t_ref()),
        ("t_min", m.t_min()),
        ("t_max", m.t_max()),
    ]
}

/// Python-syntax repr of a material: the preset's constructor call if it is
/// the preset, the full keyword call otherwise (round-trips with `eval`).
pub(crate) fn material_repr(m: &Material) -> String {
    if *m == Material::silver_coated_nylon() {
        return "Material.silver_coated_nylon()".into();
    }
    let fields = material_fields(m).map(|(k, v)| format!("{k}={}", pf(v)));
    format!("Material({}, name={})", fields.join(", "), ps(m.name()))
}
