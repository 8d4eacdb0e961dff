//! The integration tests of scene-file: reading, checking and building scene files, one module per file, built as one
//! test binary. `cargo test --release -p scene-file --test integration <module>::` runs one file's tests.

mod collisions;
mod fuzz;
mod module_order;
mod robots;
mod scenes;
