//! The Rust integration tests, one test crate (one link, one binary; run with
//! `cargo test --profile fast`): each module is one concern, listed with what
//! it checks in `tests/README.md`. Physics is tested here against the core's
//! fixtures (`tcarod::experiments`, `tcarod::problems`); `common` holds the
//! constants, builders and comparisons the modules share. Unit tests live
//! beside the code in `src/`.

mod common;

mod analytic;
mod branch;
mod cold_presolve;
mod design_solves;
mod designs;
mod inverse;
mod model_rules;
mod multiple_shooting;
mod paper;
mod perf;
mod properties;
mod rod;
mod sensitivities;
mod solver;
mod stability;
mod stability_batch;
mod stability_growth;
mod stability_heavy;
mod stability_policy;
mod tangent;
mod tca_law;
mod warm;
