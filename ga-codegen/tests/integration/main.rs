//! The integration tests of `ga-codegen`, one module per file, built as one test binary.
//! `cargo test --release -p ga-codegen --test integration <module>::` runs one file's tests.

#[macro_use]
mod common;

mod cost;
mod fusion;
mod large_algebras;
mod lowering;
mod module_order;
mod names;
mod null_basis;
mod properties;
mod snapshots;
mod transform;
