//! The project's reference scenes as `dynamics` systems: the single-body scenes of the reference set
//! ([`single_body`]), the mechanisms ([`mechanisms`]: the double pendulum, the four-bar linkage and the
//! N-link chain), each in either algebra and either constraint formulation, and the joint-limit scenes ([`limits`]).
//!
//! The modules, declared in this order, each refer only to the ones before it (`tests/integration/module_order.rs`
//! checks it): [`single_body`] (the single-body scenes, and a body's samples as a reference [`trajectory`]) →
//! [`mechanisms`] → [`mechanism_measures`] (what is measured of a mechanism run) → [`toggle_four_bar`] (a four-bar
//! linkage carried through near-toggle configurations) → [`limits`] and [`contacts`] (the joint-limit and contact
//! scenes) → [`robots`] (the reference robots built from their URDFs) → [`equal_error`] (adaptive against fixed
//! steps at equal error, on scenes of the modules before it).
//!
//! This crate exists so that `dynamics` carries no scene catalogue and no reference data: tests, benchmarks,
//! examples and the main job build their systems here, from the GA-independent parameters and reference
//! trajectories of the `reference` crate.
//!
//! Building scene 2 (the hinged rod of `docs/scenes.md`) in PGA by pinning; scene 4 on a sphere needs CGA:
//! ```
//! use dynamics::constraints::Stabilisation;
//! use dynamics::Pga;
//! use reference::SceneId;
//! use scenarios::{build, Formulation};
//!
//! let scene = build::<Pga>(SceneId::Pendulum, Formulation::Pinning, Stabilisation::None)?;
//! assert_eq!(scene.duration, SceneId::Pendulum.parameters().duration);
//! assert!(build::<Pga>(SceneId::RodOnSphere, Formulation::Pinning, Stabilisation::None).is_err());
//! # Ok::<(), scenarios::SceneError>(())
//! ```

#![deny(missing_docs)]

pub mod single_body;
pub mod mechanisms;
pub mod mechanism_measures;
pub mod toggle_four_bar;
pub mod limits;
pub mod contacts;
pub mod robots;
pub mod equal_error;

pub use mechanisms::{build_mechanism, build_mechanism_at, MechanismId, MechanismScene};
pub use robots::{build_robot, RobotScene, RobotSceneError};
pub use single_body::{build, trajectory, Formulation, Scene, SceneAlgebra, SceneError};
