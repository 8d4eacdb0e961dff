//! The main job: every reference scene in both algebras with each integrator over a sweep of step sizes;
//! work-precision tables (`report.md`), PNG plots and trajectories as CSV; and scenes described in TOML files.
//!
//! Shared machinery first: `markdown` (escaping, numbers, row order), the charts of [`plot`] and their `panels`,
//! [`csv`] trajectories, what the sweeps share about running ([`runs`]) and measuring ([`measure`]), and MuJoCo's and
//! Pinocchio's figures: `recorded_anchors`, the constants, and [`measured_anchors`], those `--anchors FILE` measured
//! beside the run.
//!
//! Then the families, each its sweep, its section of `report.md` and its figures: [`single_bodies`] (docs/scenes.md
//! scenes 1–4), [`mechanisms`] (M1–M3), [`robots`] (URDF robots against Pinocchio), [`adaptive`] (the embedded pairs
//! over tolerances), `limits` and `contacts`.
//!
//! A scene can also come from a TOML file (the `scene-file` crate), run by [`scene_job`] (`--scene-file`). [`job`]
//! runs it all in parallel with a progress bar, and [`cli`] is the command line.
//!
//! Each module refers only to modules before it in the order declared below, children before their parent, so no
//! import circle can form (`tests/integration/module_order.rs` checks it; docs/architecture.md).

#![deny(missing_docs)]

// Shared machinery: text, plots and CSV; running and measuring; MuJoCo's and Pinocchio's figures.
mod markdown;
pub mod plot;
mod panels;
pub mod csv;
pub mod runs;
pub mod measure;
mod recorded_anchors;
pub mod measured_anchors;
// The families, each its sweep, section and figures.
pub mod single_bodies;
pub mod mechanisms;
pub mod robots;
pub mod adaptive;
mod limits;
mod contacts;
// Scene files, run and written out.
pub mod scene_job;
// Bodies on the ground: shipped scene files with friction and collision shapes, run as the scene job runs them.
mod ground;
// The main job and its command line.
pub mod job;
pub mod cli;
