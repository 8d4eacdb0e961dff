//! Scenes described in a TOML file (docs/scene-files.md): bodies with their shape or inertia, initial pose
//! and velocities and forces, joints to the world or between bodies, a URDF robot, force elements between bodies,
//! algebra, integrator, step and duration, run without writing Rust (`--scene-file`; the run and its output are in
//! the report crate's `scene_job`).
//!
//! Two layouts, one system: a single `[body]` with its `[initial]` state, `[[forces]]` and `[[constraints]]`
//! to the world; or named `[[body]]` entries, each with its `initial` state and `forces`, and `[[joint]]`
//! entries `between = ["body", "other body", "world" or a robot link]`, with or without a `[robot]`. Both become the
//! same list of bodies and joints ([`Layout`]) and one [`Mechanism`](dynamics::Mechanism): the robot's bodies and joints
//! first (`urdf_import`), then the file's. A joint is any constraint kind (`Geometry`: ball, hinge, cylindrical,
//! prismatic, planar, universal, fixed, point on plane, line, sphere or circle) in either formulation, its body's
//! side in body coordinates and the rest in its reference's frame; a `[[joint]]` of the first seven kinds is a joint
//! model (`joint_models`), with coordinates, a `drive` if it is a hinge or prismatic joint, and the articulated solve.
//! Force elements (`[[spring]]`, `[[couple]]`, `[[joint_torque]]`, `[[joint_damping]]`, `[[pd]]`) are in `elements`,
//! the robot in `robot`. The run's output, its CSV columns included, is described in the report crate's `scene_job`.
//!
//! [`SceneFile::parse`] checks everything a run needs, down to building the system in each requested
//! algebra, so a bad file fails before anything runs, with a message that names the offending entry. The
//! format is derived from the structs below (serde), so toml reports unknown keys, missing fields and wrong
//! types with their line and column.

mod error;
pub mod names;
pub mod syntax;
pub mod check;
pub mod build;
mod scene;

pub use build::system::SceneSystem;
pub use check::bodies::{BodyForce, InitialState, Pose};
pub use check::geometry::{joint_violations, AxisFreedom, CheckedGeometry, HeldGeometry, JointGeometry};
pub use check::layout::{End, Layout, LayoutBody, LayoutJoint};
pub use check::robot::{CheckedRobot, LoadedRobot};
pub use check::scene::{CheckedScene, Stepping, MAX_SAMPLES, MAX_STEPS};
pub use error::SceneFileError;
pub use names::{AlgebraChoice, AlgebraKind};
pub use scene::{FileAlgebra, Scene};
pub use syntax::file::{SceneFile, MAX_FILE_BYTES};
