//! The integration tests of `ga-macros`: emitted code compiled and checked, and the macro's diagnostics (`ui`),
//! one module per file, built as one test binary.
//! `cargo test --release -p ga-macros --test integration <module>::` runs one file's tests.

mod large_algebras;
mod many_operands;
mod module_order;
mod null_basis;
mod tables;
mod transcendental;
mod ui;
