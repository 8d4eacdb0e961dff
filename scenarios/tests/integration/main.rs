//! The integration tests of `scenarios`: the reference scenes, mechanisms and robots against their reference
//! trajectories, one module per file, built as one test binary so that the generic dynamics is compiled once.
//! `cargo test --release -p scenarios --test integration <module>::` runs one file's tests.

#[macro_use]
mod common;

mod adaptive;

mod constraint_scenes;
mod contacts;
mod errors;
mod hard_cases;
mod joint_space;
mod limits;
mod mechanisms;
mod module_order;
mod robots;
mod scene1_free_body;
mod simulate;
mod single_body_is_the_one_body_mechanism;
