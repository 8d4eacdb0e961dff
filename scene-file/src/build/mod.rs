//! The third stage: the system built in an algebra, the robot's bodies and joints first, then the file's.

pub mod constraints;
pub mod joint_models;
pub mod robot;
pub mod assembly;
pub mod elements;
pub mod contacts;
pub mod pairs;
pub mod system;
