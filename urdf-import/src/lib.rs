//! URDF robot descriptions read into rigid bodies and moving joints, ready to build a `dynamics` mechanism.
//!
//! Real URDF files are messy: massless frames on fixed joints, massless moving links, inertia tensors no mass
//! distribution has, mimics naming joints that do not exist. Every such case is an [`ImportError`] that names the
//! link or joint, the numbers and the line; the repairs are opt-in ([`ImportOptions`]) and each one is listed in
//! [`RobotModel::repairs`].
//!
//! A two-joint arm whose massless `tool0` frame, on a fixed joint, merges into the forearm's body:
//!
//! ```
//! use urdf_import::{read, ImportOptions, JointKind};
//!
//! let urdf = r#"
//! <robot name="arm">
//!   <link name="base_link">
//!     <inertial><mass value="4"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.02"/></inertial>
//!   </link>
//!   <link name="forearm">
//!     <inertial>
//!       <origin xyz="0 0 0.2"/>
//!       <mass value="2"/><inertia ixx="0.03" ixy="0" ixz="0" iyy="0.03" iyz="0" izz="0.004"/>
//!     </inertial>
//!   </link>
//!   <link name="tool0"/>
//!   <joint name="elbow" type="revolute">
//!     <parent link="base_link"/><child link="forearm"/>
//!     <origin xyz="0 0 0.1"/><axis xyz="0 2 0"/>
//!     <limit lower="-3.14" upper="3.14" effort="150" velocity="3.15"/>
//!   </joint>
//!   <joint name="tool0_fixed" type="fixed">
//!     <parent link="forearm"/><child link="tool0"/><origin xyz="0 0 0.4"/>
//!   </joint>
//! </robot>"#;
//!
//! let robot = read(urdf, &ImportOptions::default())?;
//! assert_eq!((robot.bodies.len(), robot.joints.len(), robot.merged_links), (2, 1, 1));
//! let elbow = &robot.joints[0];
//! assert_eq!((elbow.kind, elbow.parent, elbow.child), (JointKind::Revolute, 0, 1));
//! assert_eq!(elbow.axis.into_inner(), nalgebra::Vector3::y()); // normalised
//! let forearm = &robot.bodies[1];
//! assert_eq!(forearm.links[1].name, "tool0");
//! assert_eq!((forearm.mass, forearm.centre_of_mass.z), (2.0, 0.2)); // kg, m in the forearm frame
//! # Ok::<(), urdf_import::ImportError>(())
//! ```
//!
//! The pipeline, one module per stage, declared in this order: [`parse`] (XML text → [`parse::RawModel`], with line
//! numbers) → [`validate`] (names, the tree, axes, mimics, link inertias; the link-level repairs) → [`merge`] (links
//! joined by fixed joints become one rigid body, mass properties merged exactly) → [`bodies`] (every moving body
//! invertible; the body-level repairs) → [`build`] (the model as a `dynamics` mechanism, in either algebra,
//! [`Robot`]). Before them come what every stage speaks of: [`pose`] (URDF's `xyz`/`rpy` convention), the joint
//! types ([`JointKind`]) and [`error`] (why an import failed). Each module refers only to modules before it.

#![deny(missing_docs)]

pub mod pose;
mod joint_kind;
pub mod error;
pub mod parse;
pub mod validate;
pub mod merge;
pub mod bodies;
pub mod build;

use std::path::Path;

pub use build::{BaseStart, BuildError, BuildOptions, Limits, Robot, RobotStart, Root};
pub use error::ImportError;
pub use joint_kind::JointKind;
pub use merge::{FrozenJoint, LinkPlacement, Mimic, MovingJoint, RigidBody, RobotModel};
pub use parse::{Collision, Geometry, Limit};
pub use validate::{ImportOptions, MasslessSubtrees, MimicMode, Repair};

/// Imports URDF text: parse, validate, merge fixed joints, check the bodies.
pub fn read(text: &str, options: &ImportOptions) -> Result<RobotModel, ImportError> {
    let raw = parse::parse(text)?;
    let validated = validate::validate(raw, options)?;
    let mut model = merge::merge(validated);
    bodies::check_bodies(&mut model, options)?;
    Ok(model)
}

/// Imports a URDF file (see [`read`]).
pub fn read_file(path: impl AsRef<Path>, options: &ImportOptions) -> Result<RobotModel, ImportError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|e| ImportError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    read(&text, options)
}

/// Models and errors cross threads: checked at compile time.
const _: () = {
    const fn send_and_sync<T: Send + Sync>() {}
    send_and_sync::<RobotModel>();
    send_and_sync::<ImportError>();
};
