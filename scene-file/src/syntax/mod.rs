//! The first stage: the file's syntax, plain structs from which serde derives the format, so toml reports unknown
//! keys, missing fields and wrong types with their line and column.

pub mod arrays;
pub mod bodies;
pub mod surfaces;
pub mod elements;
pub mod joints;
pub mod robot;
pub mod contacts;
pub mod file;
