//! Caps on the work of one call: far above any robot of the
//! paper, far below what could exhaust memory or run unbounded. The core
//! checks them ([`crate::batch::BatchOptions::validate`],
//! [`SolveOptions::check_limits`], ...); the Python bindings read integer
//! arguments against them.

use crate::error::{Error, Result};
use crate::shooting::SolveOptions;

/// Largest number of RK4 steps over the body accepted per solve.
pub const MAX_STEPS: usize = 100_000;
/// Largest Newton (or inverse) iteration budget accepted per call.
pub const MAX_ITER: usize = 100_000;
/// Largest number of eq-43 increments of `blocked_temperature`.
pub const MAX_INCREMENTS: usize = 10_000;
/// Largest number of rows of one batch call (`solve_batch`, `sweep`).
pub const MAX_BATCH_ROWS: usize = 10_000_000;
/// Largest chunk size of a batch call.
pub const MAX_CHUNK: usize = 10_000_000;
/// Largest worker-thread count of a batch call.
pub const MAX_THREADS: usize = 1024;
/// Largest IVP budget of one solve (`SolveOptions::max_evaluations`).
pub const MAX_EVALUATIONS: usize = 100_000_000;
/// Longest wall-time limit of one solve (`SolveOptions::time_limit`) \[s\].
pub const MAX_TIME_LIMIT_S: f64 = 1e9;

/// The allowed range `lo..=hi` of an integer option, with the option's name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CountLimit {
    /// Name of the option in errors.
    pub name: &'static str,
    /// Smallest value allowed.
    pub lo: usize,
    /// Largest value allowed (the cap).
    pub hi: usize,
}

impl CountLimit {
    /// The range as errors show it: `lo <= name <= hi`.
    pub fn allowed(&self) -> String {
        format!("{} <= {} <= {}", self.lo, self.name, self.hi)
    }

    /// `value`, or [`Error::InvalidParameter`] naming the option and its range.
    pub fn check(&self, value: usize) -> Result<usize> {
        if (self.lo..=self.hi).contains(&value) {
            Ok(value)
        } else {
            Err(Error::param(self.name, value as f64, self.allowed()))
        }
    }
}

/// RK4 steps over the body of one solve.
pub const STEPS: CountLimit = CountLimit {
    name: "steps",
    lo: 1,
    hi: MAX_STEPS,
};
/// Newton iterations of one solve.
pub const ITERATIONS: CountLimit = CountLimit {
    name: "max_iter",
    lo: 1,
    hi: MAX_ITER,
};
/// IVP budget of one solve.
pub const EVALUATIONS: CountLimit = CountLimit {
    name: "max_evaluations",
    lo: 1,
    hi: MAX_EVALUATIONS,
};
/// The allowed wall-time limit of one solve, as errors show it.
pub const TIME_LIMIT_ALLOWED: &str = "0 < time_limit <= 1e9 s";

impl SolveOptions {
    /// Error unless the work of one solve is within the caps: `steps` in
    /// [`STEPS`], `max_iter` in [`ITERATIONS`], `max_evaluations` in
    /// [`EVALUATIONS`], `time_limit` (if any) in `(0, MAX_TIME_LIMIT_S]`.
    /// The ranges of the other options (`tol`, `equilibrium_tol`) are
    /// [`SolveOptions::validate`]'s.
    pub fn check_limits(&self) -> Result<()> {
        STEPS.check(self.steps)?;
        ITERATIONS.check(self.max_iter)?;
        EVALUATIONS.check(self.max_evaluations)?;
        if let Some(t) = self.time_limit.map(|t| t.as_secs_f64()) {
            if !(t > 0.0 && t <= MAX_TIME_LIMIT_S) {
                return Err(Error::param("time_limit [s]", t, TIME_LIMIT_ALLOWED));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_options_beyond_a_cap_name_the_option_and_its_range() {
        assert!(SolveOptions::default().check_limits().is_ok());
        let cases = [
            (
                SolveOptions {
                    steps: 0,
                    ..Default::default()
                },
                "invalid steps = 0: allowed 1 <= steps <= 100000",
            ),
            (
                SolveOptions {
                    max_iter: MAX_ITER + 1,
                    ..Default::default()
                },
                "invalid max_iter = 100001: allowed 1 <= max_iter <= 100000",
            ),
            (
                SolveOptions {
                    max_evaluations: 0,
                    ..Default::default()
                },
                "invalid max_evaluations = 0: allowed 1 <= max_evaluations <= 100000000",
            ),
            (
                SolveOptions {
                    time_limit: Some(std::time::Duration::from_secs(2_000_000_000)),
                    ..Default::default()
                },
                "invalid time_limit = 2000000000 s: allowed 0 < time_limit <= 1e9 s",
            ),
            (
                SolveOptions {
                    time_limit: Some(std::time::Duration::ZERO),
                    ..Default::default()
                },
                "invalid time_limit = 0 s: allowed 0 < time_limit <= 1e9 s",
            ),
        ];
        for (opts, message) in cases {
            assert_eq!(opts.check_limits().unwrap_err().to_string(), message);
        }
        // the largest values allowed pass
        let most = SolveOptions {
            steps: MAX_STEPS,
            max_iter: MAX_ITER,
            max_evaluations: MAX_EVALUATIONS,
            time_limit: Some(std::time::Duration::from_secs_f64(MAX_TIME_LIMIT_S)),
            ..Default::default()
        };
        assert!(most.check_limits().is_ok());
    }
}
