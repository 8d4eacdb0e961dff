//! The second stage: every value checked, every name resolved.

pub mod values;
pub mod bodies;
pub mod surfaces;
pub mod geometry;
pub mod elements;
pub mod robot;
pub mod layout;
pub mod collisions;
pub mod pairs;
pub mod scene;
