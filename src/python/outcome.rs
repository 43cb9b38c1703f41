//! The SciPy `OptimizeResult` fields (`success`, `status`, `message`, `nit`,
//! `nfev`) shared by every result class: one trait, one macro that adds the
//! getters (pyo3's `multiple-pymethods` lets a class have this second
//! `#[pymethods]` block).

/// What a result class knows about how its solve ended.
pub(crate) trait Outcome {
    /// `0` success; the other codes are the class's own (its `status`
    /// docstring, given to [`scipy_fields`]).
    fn status_code(&self) -> i64;
    /// Why the solve stopped, in words.
    fn status_message(&self) -> String;
    /// Iterations (Newton iterations, inverse iterations or eq-43 increments).
    fn iteration_count(&self) -> usize;
    /// IVPs integrated (function evaluations).
    fn ivp_count(&self) -> usize;
    /// Whether the solve succeeded (default: `status_code() == 0`; a class
    /// with several success codes overrides it).
    fn succeeded(&self) -> bool {
        self.status_code() == 0
    }
}

/// Adds the getters `success`, `status`, `message`, `nit` and `nfev` to a
/// `#[pyclass]` that implements [`Outcome`]; `$codes` is the `status`
/// getter's docstring, which lists the class's codes.
macro_rules! scipy_fields {
    ($ty:ty, $codes:literal) => {
        #[pyo3::pymethods]
        impl $ty {
            /// Whether the solve succeeded (SciPy naming).
            ///
            /// Returns
            /// -------
            /// bool
            ///     `True` if `status` is one of the class's success codes.
            #[getter]
            fn success(&self) -> bool {
                $crate::python::outcome::Outcome::succeeded(self)
            }
            #[doc = $codes]
            #[getter]
            fn status(&self) -> i64 {
                $crate::python::outcome::Outcome::status_code(self)
            }
            /// Why the solve stopped, in words (`str`, SciPy naming).
            ///
            /// Returns
            /// -------
            /// str
            ///     The stopping reason with its numbers and their units.
            #[getter]
            fn message(&self) -> String {
                $crate::python::outcome::Outcome::status_message(self)
            }
            /// Iterations of the solve (SciPy naming).
            ///
            /// Returns
            /// -------
            /// int
            ///     Iterations [-], the same as `iterations`.
            #[getter]
            fn nit(&self) -> usize {
                $crate::python::outcome::Outcome::iteration_count(self)
            }
            /// Function evaluations of the solve (SciPy naming).
            ///
            /// Returns
            /// -------
            /// int
            ///     IVPs integrated [-], the same as `evaluations`.
            #[getter]
            fn nfev(&self) -> usize {
                $crate::python::outcome::Outcome::ivp_count(self)
            }
        }
    };
}
pub(crate) use scipy_fields;

/// Adds the getter `tip_position` (of the result's `solution`) to a result class.
macro_rules! tip_of_solution {
    ($ty:ty) => {
        #[pyo3::pymethods]
        impl $ty {
            /// Tip position [m] of `solution`, world frame.
            ///
            /// Returns
            /// -------
            /// numpy.ndarray
            ///     Shape `(3,)`: the tip position `p(L)` [m].
            #[getter]
            fn tip_position<'py>(
                &self,
                py: pyo3::Python<'py>,
            ) -> pyo3::Bound<'py, numpy::PyArray1<f64>> {
                let tip = self.solution.get().inner.tip_position();
                $crate::python::to_py::vec3(py, &tip)
            }
        }
    };
}
pub(crate) use tip_of_solution;
