//! The reference robots of `reference::robots` (UR5, Solo-12) built as mechanisms from their URDFs, with the start
//! state of their reference motion.

use dynamics::{Algebra, State};
use reference::robots::{RobotId, RobotReference};
use urdf_import::{BaseStart, BuildOptions, ImportOptions, Robot, RobotStart, Root};

/// Why a reference robot could not be built.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RobotSceneError {
    /// The embedded reference data did not read.
    #[error(transparent)]
    Data(#[from] reference::robots::RobotDataError),
    /// The URDF did not import.
    #[error(transparent)]
    Import(#[from] urdf_import::ImportError),
    /// The model did not build, or the start state was refused.
    #[error(transparent)]
    Build(#[from] urdf_import::BuildError),
}

/// A reference robot in algebra A: the robot, its reference and its start state.
#[derive(Debug)]
pub struct RobotScene<A: Algebra> {
    /// The robot (its mechanism and imported model).
    pub robot: Robot<A>,
    /// The reference motion.
    pub reference: RobotReference,
    /// The bodies' states at t = 0.
    pub initial: Vec<State<A>>,
}

/// Builds `id` as the reference simulates it: the URDF with default import options, the root fixed or free as the
/// reference has it, gravity as the reference's, the joints and base at the reference's start.
pub fn build_robot<A: Algebra>(id: RobotId) -> Result<RobotScene<A>, RobotSceneError> {
    let reference = id.reference()?;
    let model = urdf_import::read(id.urdf(), &ImportOptions::default())?;
    let options = BuildOptions {
        root: if reference.free_base { Root::Free } else { Root::Fixed },
        gravity: reference.gravity,
        // Pinocchio's reference motions (ABA) do not enforce the limits.
        limits: urdf_import::Limits::Ignore,
    };
    let robot = Robot::<A>::build(model, &options)?;
    let base = reference.base.map_or_else(BaseStart::default, |b| BaseStart {
        position: b.position,
        orientation: b.orientation,
        velocity: b.velocity,
        angular_velocity: b.angular_velocity,
    });
    let start = RobotStart {
        positions: reference.named_positions(),
        velocities: reference.named_velocities(),
        base,
    };
    let initial = robot.initial_states(&start)?;
    Ok(RobotScene {
        robot,
        reference,
        initial,
    })
}
