//! The project's reference scenes as `dynamics` systems: the single-body scenes of the reference set
//! ([`single_body`]), the mechanisms ([`mechanisms`]: the double pendulum, the four-bar linkage and the
//! N-link chain), each in either algebra and either constraint formulation, and the joint-limit scenes ([`limits`]).
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

pub mod contacts;
pub mod equal_error;
pub mod limits;
pub mod mechanism_measures;
pub mod mechanisms;
pub mod robots;
pub mod single_body;
pub mod toggle_four_bar;

pub use mechanisms::{build_mechanism, MechanismId, MechanismScene};
pub use robots::{build_robot, RobotScene, RobotSceneError};
pub use single_body::{build, Formulation, Scene, SceneAlgebra, SceneError};

use dynamics::simulate::Sample;
use reference::{Trajectory, TrajectoryError};

/// One body's samples as a reference trajectory, for the metrics of the `reference` crate.
pub fn trajectory(samples: &[Sample]) -> Result<Trajectory, TrajectoryError> {
    Trajectory::new(
        samples
            .iter()
            .map(|s| reference::Sample {
                t: s.t,
                position: s.position,
                orientation: s.orientation,
                velocity: s.velocity,
                angular_velocity: s.angular_velocity,
            })
            .collect(),
    )
}
