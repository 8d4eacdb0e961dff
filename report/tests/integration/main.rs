//! The integration tests of `report`: scene files, the anchors file, plots and a shortened main job, one module
//! per file, built as one test binary so that the scene runner is compiled once.
//! `cargo test --release -p report --test integration <module>::` runs one file's tests.

mod anchors_file;
mod plot_smoke;
mod scene_file;
mod scene_file_fuzz;
mod scene_file_robots;
mod shortened_job;
