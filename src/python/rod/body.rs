//! Bindings of the soft body (Cosserat rod).

use nalgebra::Vector3;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use super::section::{section_repr, PySection};
use crate::error::Error;
use crate::experiments::ECOFLEX10;
use crate::python::to_py::{hash_by_text, keyword_args, mat3, vec3, vec3_getters, NewArgs};
use crate::python::{pf, pv, vec3_arg, Real};
use crate::rod::{Body, Shear};

/// Young's moduli \[Pa\] outside this range look like another unit (a
/// silicone's 50 kPa typed as `50`, i.e. in kPa; a value in MPa or GPa):
/// valid numbers, so a warning rather than an error.
const PLAUSIBLE_MODULUS_PA: (f64, f64) = (1e3, 1e12);

/// A warning text if `youngs_modulus` \[Pa\] lies outside
/// [`PLAUSIBLE_MODULUS_PA`]: a body that soft or that stiff is rarely meant,
/// and a modulus in kPa otherwise shows up far from its cause, as a solve
/// that does not converge.
fn modulus_warning(youngs_modulus: f64) -> Option<String> {
    let (lo, hi) = PLAUSIBLE_MODULUS_PA;
    (youngs_modulus < lo || youngs_modulus > hi).then(|| {
        format!(
            "Body: youngs_modulus = {youngs_modulus} Pa is outside 1 kPa..1 TPa: moduli are in pascals (SI); \
             did you give kPa or MPa? (50 kPa is youngs_modulus=5e4)"
        )
    })
}

/// A warning text if `body` has a density but was built without `gravity`:
/// its weight `psi A g` (eq 24's distributed force) is then zero, so the
/// density has no effect, which is rarely meant. An explicit `gravity`, even
/// zero, says it is.
fn weightless_warning(body: &Body) -> Option<String> {
    (body.density > 0.0 && body.gravity == Vector3::zeros()).then(|| {
        format!(
            "Body: density = {} kg/m^3 but no gravity was given: the body is weightless (gravity defaults \
             to zero). Pass gravity=(0, 0, -9.81) [m/s^2] for a robot standing upright (base at the \
             bottom), or gravity=(0, 0, 0) or density=0 to keep it weightless",
            crate::error::human(body.density)
        )
    })
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
/// > 10 m, section size > 1 m) or whose `youngs_modulus` lies outside
/// 1 kPa..1 TPa warns with `tcarod.UnitsWarning`, as does a body with a
/// `density` but no `gravity` argument (it would be weightless; pass
/// `gravity`, zero if that is meant). Value object:
/// immutable, `==`, hashable, picklable; `repr` is a constructor call.
///
/// Examples
/// --------
/// >>> section = tcarod.Section.circle(0.01)                   # [m]
/// >>> body = tcarod.Body(0.1, section, 5e4, density=1040.0, gravity=(0, 0, -9.81))
/// >>> body.shear_modulus                                      # E / (2 (1 + 0.5)) [Pa]
/// 16666.666666666668
/// >>> body.distributed_load.round(4)                          # psi A g [N/m]
/// array([ 0.    ,  0.    , -0.8013])
/// >>> body.replace(length=0.05).length                        # [m]
/// 0.05
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
        if gravity.is_none() {
            if let Some(msg) = weightless_warning(&b) {
                crate::python::warn_units(py, msg)?;
            }
        }
        if let Some(msg) = b.units_warning() {
            crate::python::warn_units(py, msg)?;
        }
        if let Some(msg) = modulus_warning(b.youngs_modulus) {
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

    /// A body of a catalogued silicone: `Body.from_material(name, length, section, **kwargs)`.
    ///
    /// `name` is one of `Body.materials()` (`"ecoflex-00-10"`,
    /// `"ecoflex-00-30"`, `"ecoflex-00-50"`, `"dragon-skin-10"`,
    /// `"dragon-skin-20"`, `"dragon-skin-30"`, `"sylgard-184"`; case, spaces
    /// and underscores are ignored); `length` [m]; `section` a `Section`.
    /// The preset gives `youngs_modulus` [Pa], `poisson` [-] and `density`
    /// [kg/m^3]; `kwargs` are the constructor's other keywords (`gravity`,
    /// `omega_star`, ...) and may replace a preset value, e.g.
    /// `youngs_modulus=` a modulus identified on the user's own samples.
    ///
    /// The values are nominal: silicone moduli vary with mixing, degassing,
    /// cure temperature and age by tens of percent, so a modulus identified
    /// from a test of the user's own material should replace the preset's.
    /// Each entry of `Body.materials()` names its sources. Raises
    /// `ValueError` for an unknown `name` (listing the known ones).
    #[staticmethod]
    #[pyo3(signature = (name, length, section, **kwargs))]
    fn from_material(
        py: Python<'_>,
        name: &str,
        length: Real,
        section: PySection,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let m = body_material(name)?;
        let kw = PyDict::new(py);
        kw.set_item("length", length.0)?;
        kw.set_item("section", section)?;
        kw.set_item("youngs_modulus", m.youngs_modulus())?;
        kw.set_item("poisson", m.poisson)?;
        kw.set_item("density", m.density)?;
        if let Some(extra) = kwargs {
            for (k, v) in extra.iter() {
                let key: String = k.extract()?;
                if key == "shear_modulus" {
                    kw.del_item("poisson")?;
                }
                kw.set_item(key, v)?;
            }
        }
        let obj = py.get_type::<PyBody>().call((), Some(&kw))?;
        let b = obj.cast::<PyBody>()?;
        Ok(b.get().clone())
    }

    /// The catalogued silicones of `Body.from_material`.
    ///
    /// One dict per material in catalogue order: `name`, `label`, `youngs_modulus` [Pa]
    /// (small-strain Young's modulus used by the model), `modulus_basis`
    /// (which modulus and how it was obtained), `modulus_100` [Pa] (the
    /// manufacturer's stress at 100 % elongation, `None` if not published),
    /// `shore_hardness`, `poisson` [-], `density` [kg/m^3], `sources`
    /// (the publications and technical bulletins the values come from).
    #[staticmethod]
    fn materials(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
        let out = PyList::empty(py);
        for m in BODY_MATERIALS {
            let d = PyDict::new(py);
            d.set_item("name", m.name)?;
            d.set_item("label", m.label)?;
            d.set_item("youngs_modulus", m.youngs_modulus())?;
            d.set_item("modulus_basis", m.modulus.basis())?;
            d.set_item("modulus_100", m.modulus_100())?;
            d.set_item("shore_hardness", m.shore_hardness)?;
            d.set_item("poisson", m.poisson)?;
            d.set_item("density", m.density)?;
            d.set_item("sources", m.sources)?;
            out.append(d)?;
        }
        Ok(out)
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
    ///
    /// Returns
    /// -------
    /// float
    ///     The arc length [m] from base to tip.
    #[getter]
    fn length(&self) -> f64 {
        self.inner.length
    }
    /// The cross-section (`Section`).
    ///
    /// Returns
    /// -------
    /// Section
    ///     Its sizes [m].
    #[getter]
    fn section(&self) -> PySection {
        PySection {
            inner: self.inner.section,
        }
    }
    /// Young's modulus E_B [Pa].
    ///
    /// Returns
    /// -------
    /// float
    ///     The body's Young's modulus [Pa].
    #[getter]
    fn youngs_modulus(&self) -> f64 {
        self.inner.youngs_modulus
    }
    /// Shear modulus G_B [Pa].
    ///
    /// Returns
    /// -------
    /// float
    ///     Given, or `E_B / (2 (1 + poisson))` [Pa].
    #[getter]
    fn shear_modulus(&self) -> f64 {
        self.inner.shear_modulus
    }
    /// Density [kg/m^3].
    ///
    /// Returns
    /// -------
    /// float
    ///     The body's density psi [kg/m^3] (0: massless).
    #[getter]
    fn density(&self) -> f64 {
        self.inner.density
    }
    /// Total distributed force `psi A g + f` [N/m], world frame.
    ///
    /// Returns
    /// -------
    /// numpy.ndarray
    ///     Shape `(3,)`: weight per length plus `distributed_force` [N/m].
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
    ///
    /// Returns
    /// -------
    /// float
    ///     The factor [-] on the shear stiffness `G A` (1 as in the paper).
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

// Each docstring: a summary, then a numpydoc `Returns` section.
vec3_getters!(PyBody {
    nu_star => "Reference linear strain `nu*` [-], body frame.\n\nReturns\n-------\nnumpy.ndarray\n    Shape `(3,)`: the strain [-] of the unloaded body.",
    omega_star => "Reference angular strain `omega*` [1/m], body frame.\n\nReturns\n-------\nnumpy.ndarray\n    Shape `(3,)`: the curvature and twist [1/m] of the unloaded body.",
    gravity => "Gravitational acceleration [m/s^2], world frame.\n\nReturns\n-------\nnumpy.ndarray\n    Shape `(3,)`: the acceleration [m/s^2] acting on the body's density.",
    tip_force => "Force applied to the tip [N], world frame.\n\nReturns\n-------\nnumpy.ndarray\n    Shape `(3,)`: the tip force [N].",
    tip_moment => "Moment applied to the tip [N m], world frame.\n\nReturns\n-------\nnumpy.ndarray\n    Shape `(3,)`: the tip moment [N m].",
    distributed_moment => "Distributed moment [N m/m], world frame.\n\nReturns\n-------\nnumpy.ndarray\n    Shape `(3,)`: the moment per length [N m/m].",
    distributed_force => "Distributed force [N/m] besides gravity, world frame.\n\nReturns\n-------\nnumpy.ndarray\n    Shape `(3,)`: the force per length [N/m]."
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

/// One pascal per psi (the technical bulletins give moduli in psi).
const PA_PER_PSI: f64 = 6_894.757_293_168;

/// How a catalogued silicone's small-strain Young's modulus is obtained.
#[derive(Clone, Copy)]
enum Modulus {
    /// From the manufacturer's stress at 100 % elongation `sigma_100` [psi]
    /// by an incompressible neo-Hookean solid: nominal uniaxial stress
    /// `P = mu (lambda - 1/lambda^2)`, `E = 3 mu`, so at `lambda = 2`
    /// `E = 3 sigma_100 / 1.75 = (12/7) sigma_100`.
    NeoHookeanFrom100 { psi: f64 },
    /// A small-strain modulus [Pa] measured in a published characterisation.
    Published { pa: f64, basis: &'static str },
}

impl Modulus {
    fn youngs_modulus(self) -> f64 {
        match self {
            Modulus::NeoHookeanFrom100 { psi } => 12.0 / 7.0 * psi * PA_PER_PSI,
            Modulus::Published { pa, .. } => pa,
        }
    }
    fn basis(self) -> &'static str {
        match self {
            Modulus::NeoHookeanFrom100 { .. } => {
                "small-strain (initial) Young's modulus of an incompressible neo-Hookean solid \
                 through the technical bulletin's 100 % modulus: E = (12/7) x 100 % modulus"
            }
            Modulus::Published { basis, .. } => basis,
        }
    }
}

/// A catalogued silicone for soft bodies (`Body.from_material`).
struct BodyMaterial {
    name: &'static str,
    label: &'static str,
    modulus: Modulus,
    /// The technical bulletin's stress at 100 % elongation [psi], if published.
    modulus_100_psi: Option<f64>,
    shore_hardness: &'static str,
    poisson: f64,
    /// Density [kg/m^3]: the manufacturer's specific gravity x 1000.
    density: f64,
    sources: &'static str,
}

impl BodyMaterial {
    fn youngs_modulus(&self) -> f64 {
        self.modulus.youngs_modulus()
    }
    fn modulus_100(&self) -> Option<f64> {
        self.modulus_100_psi.map(|p| p * PA_PER_PSI)
    }
}

const ECOFLEX_BULLETIN: &str = "Smooth-On, Ecoflex Series technical bulletin \
    (specific gravity, Shore hardness, 100 % modulus)";
const DRAGON_SKIN_BULLETIN: &str = "Smooth-On, Dragon Skin Series technical bulletin \
    (specific gravity, Shore hardness, 100 % modulus)";

/// The catalogue of `Body.from_material`, defined once. Poisson ratio 0.5:
/// cured silicone rubbers are nearly incompressible (bulk modulus about
/// 10^3 times the shear modulus).
const BODY_MATERIALS: &[BodyMaterial] = &[
    BodyMaterial {
        name: "ecoflex-00-10",
        label: "Ecoflex 00-10",
        modulus: Modulus::Published {
            pa: ECOFLEX10.1,
            basis:
                "small-strain Young's modulus of the EcoFlex 10 bodies of Pawlowski et al. 2019 \
                    (Section V), the value of the paper's fixtures; the neo-Hookean estimate \
                    through the bulletin's 100 % modulus (8 psi) is 94.6 kPa",
        },
        modulus_100_psi: Some(8.0),
        shore_hardness: "00-10",
        poisson: 0.5,
        density: ECOFLEX10.0,
        sources: "Pawlowski, Sun, Xu, Liu, Zhao, \"Modeling of Soft Robots Actuated by \
                  Twisted-and-Coiled Actuators\", IEEE/ASME Trans. Mechatronics 24(1), 2019, \
                  Section V (modulus, density 1040 kg/m^3); Smooth-On, Ecoflex Series \
                  technical bulletin (specific gravity 1.04, Shore 00-10, 100 % modulus 8 psi)",
    },
    BodyMaterial {
        name: "ecoflex-00-30",
        label: "Ecoflex 00-30",
        modulus: Modulus::NeoHookeanFrom100 { psi: 10.0 },
        modulus_100_psi: Some(10.0),
        shore_hardness: "00-30",
        poisson: 0.5,
        density: 1070.0,
        sources: ECOFLEX_BULLETIN,
    },
    BodyMaterial {
        name: "ecoflex-00-50",
        label: "Ecoflex 00-50",
        modulus: Modulus::NeoHookeanFrom100 { psi: 12.0 },
        modulus_100_psi: Some(12.0),
        shore_hardness: "00-50",
        poisson: 0.5,
        density: 1070.0,
        sources: ECOFLEX_BULLETIN,
    },
    BodyMaterial {
        name: "dragon-skin-10",
        label: "Dragon Skin 10",
        modulus: Modulus::NeoHookeanFrom100 { psi: 22.0 },
        modulus_100_psi: Some(22.0),
        shore_hardness: "10A",
        poisson: 0.5,
        density: 1070.0,
        sources: DRAGON_SKIN_BULLETIN,
    },
    BodyMaterial {
        name: "dragon-skin-20",
        label: "Dragon Skin 20",
        modulus: Modulus::NeoHookeanFrom100 { psi: 49.0 },
        modulus_100_psi: Some(49.0),
        shore_hardness: "20A",
        poisson: 0.5,
        density: 1080.0,
        sources: DRAGON_SKIN_BULLETIN,
    },
    BodyMaterial {
        name: "dragon-skin-30",
        label: "Dragon Skin 30",
        modulus: Modulus::NeoHookeanFrom100 { psi: 86.0 },
        modulus_100_psi: Some(86.0),
        shore_hardness: "30A",
        poisson: 0.5,
        density: 1080.0,
        sources: DRAGON_SKIN_BULLETIN,
    },
    BodyMaterial {
        name: "sylgard-184",
        label: "Sylgard 184 (10:1)",
        modulus: Modulus::Published {
            pa: 1.32e6,
            basis: "small-strain tensile Young's modulus of Sylgard 184 mixed 10:1 and cured at \
                    room temperature (Johnston et al. 2014: 1.32 MPa; curing hotter stiffens it, \
                    up to 2.97 MPa when cured at 200 C)",
        },
        modulus_100_psi: None,
        shore_hardness: "43A",
        poisson: 0.5,
        density: 1030.0,
        sources: "Johnston, McCluskey, Tan, Tracey, \"Mechanical characterization of bulk \
                  Sylgard 184 for microfluidics and microengineering\", J. Micromech. Microeng. \
                  24, 035017, 2014 (modulus); Dow, SYLGARD 184 Silicone Elastomer technical \
                  data sheet (specific gravity 1.03, Shore A 43)",
    },
];

/// The catalogued material `name` (case, spaces and underscores ignored).
fn body_material(name: &str) -> Result<&'static BodyMaterial, Error> {
    let key = name.trim().to_lowercase().replace([' ', '_'], "-");
    BODY_MATERIALS
        .iter()
        .find(|m| m.name == key)
        .ok_or_else(|| {
            let known: Vec<&str> = BODY_MATERIALS.iter().map(|m| m.name).collect();
            Error::input(
                "name",
                format!(
                    "{name:?} is not a catalogued body material; known: {}",
                    known.join(", ")
                ),
            )
        })
}
