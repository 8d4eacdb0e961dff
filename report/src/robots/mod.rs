//! The reference robots (the UR5 arm and the Solo-12 quadruped from their URDFs) against Pinocchio's reference motion:
//! each measured at every sample of the reference (`measure`), run over algebra × integrator × step (`sweep`),
//! drawn (`figures`) and reported beside MuJoCo's and Pinocchio's figures (`section`).

pub(crate) mod measure;
pub(crate) mod sweep;
pub(crate) mod figures;
pub(crate) mod section;

pub use measure::StickFigure;
pub use sweep::{robot_label, RobotConfig, RobotOutcome, RobotPlan, RobotResult, DEFAULT_STEPS};
