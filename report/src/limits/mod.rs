//! The joint limits (docs/limits.md): the scenes of `scenarios::limits` run in both algebras (`sweep`), drawn (`figures`)
//! and reported (`section`).

pub(crate) mod sweep;
pub(crate) mod figures;
pub(crate) mod section;
