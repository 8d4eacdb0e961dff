//! The single bodies (docs/scenes.md scenes 1–4): every reference scene in both algebras and formulations with each
//! integrator over a sweep of step sizes (`sweep`), measured against the reference trajectories (`measure`),
//! drawn (`figures`) and reported per scene with the CGA-vs-PGA agreement and MuJoCo's figures (`section`).

pub(crate) mod measure;
pub(crate) mod sweep;
pub(crate) mod figures;
pub(crate) mod section;

pub use measure::{Feature, Measurements};
pub use sweep::{Config, Outcome, SweepPlan};
