//! The mechanisms (docs/scenes.md M1–M3): the double pendulum and the four-bar over algebra × joint formulation ×
//! integrator × step, and the chain's cost per step against its length (`sweep`), drawn (`figures`) and reported
//! beside MuJoCo's and Pinocchio's figures (`section`).

pub(crate) mod sweep;
pub(crate) mod figures;
pub(crate) mod section;

pub use sweep::{MechanismConfig, MechanismKind, MechanismOutcome, MechanismPlan, MechanismResult};
