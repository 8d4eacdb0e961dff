//! The workspace's own tests: the sizes of its sources, the command line, an algebra no crate declares, the dependency tree, doc examples on
//! every public constructor and the product vectors of an independent library, built as one test binary.
//! `cargo test --release --test integration <module>::` runs one file's tests.

mod architecture;
mod cli;
mod custom_algebra;
mod dependencies;
mod doc_examples;
mod refdata;
