//! The integration tests of `report`: the scene job, the anchors file, plots and a shortened main job, one module per
//! file, built as one test binary so that the runners are compiled once.
//! `cargo test --release -p report --test integration <module>::` runs one file's tests.

mod anchors_file;
mod module_order;
mod plot_smoke;
mod scene_job;
mod scene_job_robots;
mod shortened_job;
