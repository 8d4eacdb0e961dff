//! The house rules of this workspace, as checks its tests call (`docs/architecture.md` states them):
//!
//! 1. [`order`]: each module of a crate refers only to modules before it in the order its crate root declares
//!    them, children before their parent, so no import circle can form;
//! 2. [`sizes`]: no source file over 1200 lines, no function over 200.
//!
//! The pipeline: [`tree`] (the module tree, read from the files) → [`references`] (the paths in each module's
//! code) → [`order`] and [`sizes`].

#![deny(missing_docs)]

pub mod tree;
pub mod references;
pub mod order;
pub mod sizes;

use std::path::Path;

/// Panics, listing each violation, unless every module of the crate at `manifest_dir` refers only to modules
/// before it in the order its crate root declares them.
pub fn assert_modules_in_order(manifest_dir: &str) {
    let violations = order::order_violations(Path::new(manifest_dir));
    assert!(
        violations.is_empty(),
        "modules referring to later modules (the order: {}):\n{}",
        order::module_order(Path::new(manifest_dir)).join(", "),
        violations.join("\n")
    );
}

/// Panics, listing each violation, unless every source file under `directories` of `root` is at most
/// [`sizes::MAX_FILE_LINES`] long and each of its functions at most [`sizes::MAX_FUNCTION_LINES`].
pub fn assert_sizes(root: &str, directories: &[&str]) {
    let violations = sizes::size_violations(Path::new(root), directories);
    assert!(violations.is_empty(), "too long:\n{}", violations.join("\n"));
}
