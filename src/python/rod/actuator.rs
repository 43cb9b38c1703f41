//! Bindings of the actuators (TCAs, tendons).

use std::sync::Arc;

use pyo3::prelude::*;

use super::section::{routing_repr, PyRouting};
use crate::error::Error;
use crate::python::errors::finite_output;
use crate::python::tca::PyTca;
use crate::python::to_py::{hash_by_text, reduce_with, Reduce};
use crate::python::{pf, ps, Real};
use crate::rod::{Actuator, ConstantTension, LinearTendon};

/// `_restore_actuator` arguments: kind, TCA, stiffness [N/m], routing,
/// s_start [m], s_end [m] (`None`: the tip), length ratio [-], pre-tension [N].
type ActuatorArgs = (
    &'static str,
    Option<PyTca>,
    Option<f64>,
    PyRouting,
    f64,
    Option<f64>,
    Option<f64>,
    Option<f64>,
);

/// A string-like actuator embedded in the body.
///
/// Build with `Actuator.tca`, `Actuator.tendon` (constant tension) or
/// `Actuator.linear_tendon`.
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
///
/// Examples
/// --------
/// >>> tca = tcarod.Tca(0.15, 0.04, 0.0017, 38.2)     # l, L, D [m], N [turns]
/// >>> a = tcarod.Actuator.tca(tca, tcarod.Routing.straight(0.003, 0.0))
/// >>> a.kind, a.input_name, a.input_bounds           # input range [C]
/// ('tca', 'temperature [C]', (25.0, 160.0))
/// >>> t = tcarod.Actuator.tendon(tcarod.Routing.straight(0.003, 0.0), s_end=0.05)
/// >>> t.input_name, t.s_end                          # anchored at 50 mm [m]
/// ('tension [N]', 0.05)
#[pyclass(name = "Actuator", module = "tcarod._core", frozen, eq, hash)]
#[derive(Clone)]
pub struct PyActuator {
    /// The core actuator as given (`s_end` [`Actuator::TIP`] if not given;
    /// the robot resolves it and the pre-tension).
    pub(crate) inner: Actuator,
    /// Stiffness [N/m] of a linear tendon.
    stiffness: Option<f64>,
}

impl PyActuator {
    pub(crate) fn plain(inner: Actuator) -> Self {
        PyActuator {
            inner,
            stiffness: None,
        }
    }
    /// Everything that defines the actuator, as text (for `==` and hash).
    pub(crate) fn identity(&self) -> String {
        format!("{:?} {:?}", self.inner, self.stiffness)
    }
    /// This actuator, after a `UnitsWarning` if an anchor looks like
    /// millimetres ([`Actuator::units_warning`]).
    fn warn_units(self) -> PyResult<Self> {
        if let Some(msg) = self.inner.units_warning() {
            Python::attach(|py| crate::python::warn_units(py, msg))?;
        }
        Ok(self)
    }
    /// `s_end` as given (`None`: the tip).
    fn s_end_arg(&self) -> Option<f64> {
        (self.inner.s_end != Actuator::TIP).then_some(self.inner.s_end)
    }
}

impl PartialEq for PyActuator {
    fn eq(&self, other: &Self) -> bool {
        self.identity() == other.identity()
    }
}

hash_by_text!(PyActuator, |a| a.identity());

#[pymethods]
impl PyActuator {
    /// A TCA whose input is its temperature [C].
    ///
    /// Anchored from `s_start` [m] to `s_end` [m] (`None`: the tip).
    /// `length_ratio`: the paper's constant
    /// `L_i` [-] (eq 18; default: computed pointwise so that the reference
    /// shape is unstrained). `pretension_n`: tension [N] the TCA carries at the
    /// reference temperature in the undeformed body (needed for contraction
    /// TCAs to act; sets `L_i`, so not together with `length_ratio`).
    ///
    /// A TCA shorter than its span: the elongation is measured over the whole
    /// span from `s_start` to `s_end`, so the model takes the TCA in series
    /// with inextensible leads (knots, crimps, wire) filling the rest of the
    /// span; in the reference shape it is relaxed with its coils touching
    /// (unless pre-tensioned) and all of the span's elongation goes into the
    /// TCA's law. Its coiled length must not exceed the span by more than 10%.
    /// Anchors above 10 m look like millimetres and warn with
    /// `tcarod.UnitsWarning`.
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
        PyActuator::plain(Actuator::tca(
            tca.inner,
            routing.inner,
            s_start.0,
            s_end.map(|r| r.0),
            length_ratio.map(|r| r.0),
            pretension_n.map(|r| r.0),
        )?)
        .warn_units()
    }
    /// A tendon whose input is its tension [N] (>= 0).
    ///
    /// Anchored from `s_start` [m] to `s_end` [m] (`None`: the tip);
    /// `length_ratio` [-] as for `Actuator.tca` (irrelevant to the force of a
    /// constant-tension tendon).
    #[staticmethod]
    #[pyo3(signature = (routing, s_start=Real(0.0), s_end=None, length_ratio=None),
        text_signature = "(routing, s_start=0.0, s_end=None, length_ratio=None)")]
    fn tendon(
        routing: PyRouting,
        s_start: Real,
        s_end: Option<Real>,
        length_ratio: Option<Real>,
    ) -> PyResult<Self> {
        PyActuator::plain(Actuator::anchored(
            routing.inner,
            s_start.0,
            s_end.map(|r| r.0),
            length_ratio.map(|r| r.0),
            Arc::new(ConstantTension),
        )?)
        .warn_units()
    }
    /// An elastic tendon of `stiffness` [N/m] whose input is the length [m] pulled in at the base.
    ///
    /// Anchors [m] and `length_ratio` [-] as for `Actuator.tca`.
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
        let inner = Actuator::anchored(
            routing.inner,
            s_start.0,
            s_end.map(|r| r.0),
            length_ratio.map(|r| r.0),
            Arc::new(LinearTendon { stiffness }),
        )?;
        PyActuator {
            inner,
            stiffness: Some(stiffness),
        }
        .warn_units()
    }
    /// Pre-tension [N] at the reference temperature.
    ///
    /// Returns
    /// -------
    /// float or None
    ///     The `pretension_n` [N] given to `Actuator.tca`, or `None`.
    #[getter]
    fn pretension_n(&self) -> Option<f64> {
        self.inner.pretension
    }
    /// Tendon stiffness [N/m] of a linear tendon.
    ///
    /// Returns
    /// -------
    /// float or None
    ///     The stiffness [N/m]; `None` for a TCA or a constant-tension tendon.
    #[getter]
    fn stiffness(&self) -> Option<f64> {
        self.stiffness
    }
    /// Pickle support: rebuilt by the same static constructor.
    fn __reduce__<'py>(&self, py: Python<'py>) -> Reduce<'py, ActuatorArgs> {
        let a = &self.inner;
        let routing = PyRouting { inner: a.routing };
        let args = (
            self.kind(),
            self.tca_model(),
            self.stiffness,
            routing,
            a.s_start,
            self.s_end_arg(),
            a.length_ratio,
            a.pretension,
        );
        reduce_with(py, "_restore_actuator", args)
    }
    /// Which law the actuator follows.
    ///
    /// Returns
    /// -------
    /// str
    ///     `"tca"`, `"tension"` or `"linear_tendon"` (no unit).
    #[getter]
    fn kind(&self) -> &'static str {
        self.inner.law.kind()
    }
    /// Name and unit of the input.
    ///
    /// Returns
    /// -------
    /// str
    ///     `"temperature [C]"`, `"tension [N]"` or `"pull [m]"`.
    #[getter]
    fn input_name(&self) -> &'static str {
        self.inner.law.input_name()
    }
    /// Range of valid inputs.
    ///
    /// Returns
    /// -------
    /// tuple of 2 float
    ///     `(lowest, highest)` input: temperature [C] for TCAs, tension [N],
    ///     pull [m].
    #[getter]
    fn input_bounds(&self) -> (f64, f64) {
        self.inner.law.input_bounds()
    }
    /// Input of the passive (reference) state.
    ///
    /// Returns
    /// -------
    /// float
    ///     Ambient temperature [C] for a TCA, zero tension [N] or pull [m] for a
    ///     tendon.
    #[getter]
    fn reference_input(&self) -> f64 {
        self.inner.law.reference_input()
    }
    /// Body-frame path of the actuator.
    ///
    /// Returns
    /// -------
    /// Routing
    ///     Its offsets [m] from the centre line.
    #[getter]
    fn routing(&self) -> PyRouting {
        PyRouting {
            inner: self.inner.routing,
        }
    }
    /// Proximal anchor [m].
    ///
    /// Returns
    /// -------
    /// float
    ///     Arc length [m] of the anchor nearer the base (0: the base).
    #[getter]
    fn s_start(&self) -> f64 {
        self.inner.s_start
    }
    /// Distal anchor [m].
    ///
    /// Returns
    /// -------
    /// float
    ///     Arc length [m] of the anchor nearer the tip; `inf` means the tip.
    #[getter]
    fn s_end(&self) -> f64 {
        self.inner.s_end
    }
    /// The paper's constant length ratio `L_i` [-] (eq 18).
    ///
    /// Returns
    /// -------
    /// float or None
    ///     `L_i` [-], or `None`: computed pointwise from the reference shape
    ///     (`pretension_n` sets it when the robot is built).
    #[getter]
    fn length_ratio(&self) -> Option<f64> {
        self.inner.length_ratio
    }
    /// The TCA of a TCA actuator.
    ///
    /// Returns
    /// -------
    /// Tca or None
    ///     Its geometry [m] and material; `None` for a tendon.
    #[getter]
    fn tca_model(&self) -> Option<PyTca> {
        self.inner.law.tca().map(|t| PyTca { inner: t.clone() })
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
    pub(crate) fn __repr__(&self) -> String {
        let routing = routing_repr(&self.inner.routing);
        let mut tail = format!("routing={routing}, s_start={}", pf(self.inner.s_start));
        if let Some(e) = self.s_end_arg() {
            tail += &format!(", s_end={}", pf(e));
        }
        if let Some(l) = self.inner.length_ratio {
            tail += &format!(", length_ratio={}", pf(l));
        }
        match (self.kind(), self.tca_model(), self.stiffness) {
            ("tca", Some(t), _) => {
                let tca = Python::attach(|py| Bound::new(py, t).and_then(|b| PyTca::__repr__(&b)))
                    .unwrap_or_else(|_| "Tca(...)".into());
                let pre = self
                    .inner
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
pub(crate) fn restore_actuator(
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
