//! The contacts (docs/contacts.md): the scenes of `scenarios::contacts` run in both algebras (`sweep`), drawn (`figures`)
//! and reported (`section`).

pub(crate) mod sweep;
pub(crate) mod figures;
pub(crate) mod section;
