//! The contacts (docs/contacts.md): the scenes of `scenarios::contacts` run in both algebras (`sweep`) and reported
//! with their figures (`section`).

pub(crate) mod sweep;
pub(crate) mod section;
