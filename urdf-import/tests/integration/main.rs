//! The integration tests of `urdf-import`, one module per importer stage and one for the module order, built as
//! one test binary. `cargo test --release -p urdf-import --test integration <module>::` runs one file's tests.

#[macro_use]
mod common;

mod bodies;
mod inertia;
mod limits;
mod merge;
mod mimic;
mod module_order;
mod parse;
mod pose;
mod structure;
