//! Running a scene file (`--scene-file`, the `scene-file` crate): the scene in each requested algebra (`run`), then
//! its trajectories (CSV), energy and constraint-violation plots (`figures`) and `summary.md` (`describe`, `summary`)
//! in the output folder (`write`).
//!
//! The trajectory `<stem>_<algebra>.csv` of named `[[body]]` entries or a robot has the columns `t`, then per body in
//! the mechanism's order (the robot's bodies, named after their links, first) `NAME.x, NAME.y, NAME.z` (centre of
//! mass, world, m) and `NAME.qw, NAME.qx, NAME.qy, NAME.qz` (orientation quaternion, body → world), then `energy`
//! (the whole system's, J); a single `[body]` keeps the reference files' columns ([`crate::csv::HEADER`]). With a
//! robot, `<stem>_joints_<algebra>.csv` has the columns of `reference/data/robots/*.csv`: `t`, every non-fixed joint's
//! position in URDF file order (rad or m, continuous joints unwrapped), for a free root `base.x, base.y, base.z,
//! base.qw, base.qx, base.qy, base.qz` (the root link frame, world ← root, the quaternion continuous in time), then
//! `energy`. The summary gives per algebra the energy change, the largest joint violation over all joints, and the
//! work done by the force elements against the energy change.

pub(crate) mod run;
pub(crate) mod describe;
pub(crate) mod figures;
pub(crate) mod summary;
pub(crate) mod write;

pub use run::{AlgebraRun, ABSOLUTE_ENERGY_BELOW, ENERGY_WARNING};
pub use write::{run_scene_file, SceneJobError, SceneJobSummary};
