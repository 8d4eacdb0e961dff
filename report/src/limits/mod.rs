//! The joint limits (docs/limits.md): the scenes of `scenarios::limits` run in both algebras (`sweep`) and reported
//! with their figures (`section`).

pub(crate) mod sweep;
pub(crate) mod section;
