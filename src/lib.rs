//! Geometric algebra compiler and rigid-body dynamics in CGA and PGA.
//!
//! This umbrella crate re-exports the workspace crates:
//! - [`ga_codegen`]: the compiler library (algebra model → product rules → symbolic expansion → emission);
//! - [`algebra!`]: the proc-macro front end;
//! - [`dynamics`]: rigid-body simulators generic over one `Algebra` trait.
pub use dynamics;
pub use ga_codegen;
pub use ga_macros::algebra;

/// The README's examples, compiled and run by `cargo test --doc` so that the landing page cannot go stale.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeExamples;
