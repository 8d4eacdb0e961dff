//! Bodies on the ground (docs/contacts.md): the shipped scene files with friction and collision shapes run as the
//! scene job runs them (`section`), drawn (`figures`).

pub(crate) mod figures;
pub(crate) mod section;
