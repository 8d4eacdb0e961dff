//! The main job: every reference scene in both algebras with each integrator over a sweep of step
//! sizes; work-precision tables (`report.md`), PNG plots and trajectories as CSV.
//!
//! The pipeline, one module per stage: [`sweep`] (configurations, running one) → [`measure`] (metrics
//! against the `reference` crate) → [`markdown`] (the report), `figures` (the plots, drawn by
//! [`plot`]) and [`csv`] (trajectories); [`job`] runs it all in parallel with a progress bar.
//!
//! The mechanisms of docs/scenes.md (M1–M3) follow the same stages: [`mechanism_sweep`] (configurations, running
//! one; measured by `scenarios::mechanism_measures`) → `mechanism_report` (their section and plots).
//!
//! The adaptive runs (the embedded pairs over tolerances) follow them: [`adaptive_sweep`] → `adaptive_report`.
//!
//! A scene can also come from a TOML file (the `scene-file` crate), run by [`scene_job`] (`--scene-file`).
//!
//! MuJoCo's and Pinocchio's times come from [`anchors`] where `--anchors FILE` measured them beside the run,
//! else from the recorded constants.
//!
//! The command line is [`cli`]; the integrators and stabilisations by the names it and scene files use are in
//! `scene_file::names`.

#![deny(missing_docs)]

mod adaptive_report;
pub mod adaptive_sweep;
pub mod anchors;
pub mod cli;
mod contacts_report;
pub mod csv;
mod figures;
pub mod job;
mod limits_report;
pub mod markdown;
pub mod measure;
mod mechanism_report;
pub mod mechanism_sweep;
mod mujoco;
pub mod plot;
mod robot_figures;
mod robot_report;
pub mod robot_sweep;
pub mod scene_job;
pub mod sweep;
