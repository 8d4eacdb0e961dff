//! The integration tests of `dynamics`, one module per file, built as one test binary: the generic code
//! they instantiate (both algebras, every integrator) is compiled once instead of once per file.
//! `cargo test --release -p dynamics --test integration <module>::` runs one file's tests.

#[macro_use]
mod common;

mod adaptive;
mod algebra_layer;
mod bodies_and_states;
mod bodies_meeting;
mod constraint_machinery;
mod contacts;
mod convert;
mod errors;
pub(crate) mod events;
mod force_elements;
mod force_line;
mod friction;
mod joint_integration;
mod joint_space_errors;
mod joints;
mod limits;
mod long_run;
mod mechanism_solve;
mod module_order;
mod newton_euler;
mod orders;
mod polyhedra;
mod repeated_contacts;
mod rims;
mod surfaces;
