//! The adaptive runs: every selected scene in PGA with each embedded pair over a sweep of tolerances (`sweep`), drawn
//! beside the fixed-step runs of the same scene (`figures`) and reported (`section`).

pub(crate) mod sweep;
pub(crate) mod figures;
pub(crate) mod section;

pub use sweep::{AdaptiveCase, AdaptiveConfig, AdaptiveOutcome, AdaptivePlan, AdaptiveResult, DEFAULT_TOLERANCES};
