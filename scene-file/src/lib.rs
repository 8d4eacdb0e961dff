//! # scene-file: scenes described in TOML files
//!
//! Bodies with their shape or inertia, initial pose, velocities and forces, joints to the world or between bodies, a
//! URDF robot, force elements between bodies, contacts, and the algebra, integrator, step and duration of the run,
//! written in a TOML file (docs/scene-files.md) and run without writing Rust: the main job's `--scene-file`, whose run
//! and output (CSV, plots, `summary.md`) are the report crate's `scene_job`.
//!
//! A file is read in stages, as a compiler reads a program, and each check is made once:
//! 1. [`syntax`], the parse: plain structs from which serde derives the format ([`SceneFile`]), so toml reports
//!    unknown keys, missing fields and wrong types with their line and column;
//! 2. `check`, every value that does not depend on the algebra ([`CheckedScene::new`]): the robot's URDF read and
//!    its start, the integrator, the schedule, the stabilisation, and the bodies and joints of either layout (a
//!    single `[body]` with `[[constraints]]` to the world, or named `[[body]]` entries and `[[joint]]`s between them),
//!    every name resolved ([`Layout`]);
//! 3. `build`, the system in one algebra ([`SceneSystem`]): the robot's bodies and joints first (`urdf_import`), then
//!    the file's; a joint is any constraint kind (ball, hinge, cylindrical, prismatic, planar, universal, fixed, a
//!    point on a plane, line, sphere, circle, surface or curve) in either formulation, its body's side in body
//!    coordinates and the rest in its reference's frame, and a `[[joint]]` of the first seven kinds is a joint model,
//!    with coordinates, a `drive` or `limit` on a hinge or prismatic joint, and the articulated solve; then the force
//!    elements and contacts, and the start projected onto the joints, where the reactions must solve.
//!
//! [`Scene`] runs the stages, building the system in every algebra the file asks for, so a bad file fails before
//! anything runs, with a message that names the entry and the value.
//!
//! Each module refers only to modules before it in the order declared below, children before their parent (the
//! stages in turn: `error`, `names`; `syntax`: arrays, bodies, surfaces, elements, joints, robot, contacts, file;
//! `check`: values, bodies, surfaces, geometry, elements, robot, layout, scene; `build`: constraints, joint models,
//! robot, assembly, elements, contacts, system; then `scene`), so no import circle can form
//! (`tests/integration/module_order.rs` checks it; docs/architecture.md).

#![deny(missing_docs)]

// What every stage uses: its errors, and the names of integrators, stabilisations, formulations and algebras.
mod error;
pub mod names;
// The stages: the syntax, every value checked, the system built in an algebra.
pub mod syntax;
mod check;
mod build;
// The stages in turn, for every algebra a file asks for.
mod scene;

pub use build::constraints::RoundPins;
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
