//! The robot built in an algebra, as the first bodies and joints of the scene's mechanism, and the columns of its joints
//! CSV, `<stem>_joints_<algebra>.csv`, in those of `reference/data/robots/*.csv`.

use dynamics::JointModel;
use dynamics::{Algebra, CoordinateGroup, JointId, JointSpace, Mechanism, Reference, State};
use urdf_import::Robot;

use crate::check::robot::{CheckedRobot, LoadedRobot};
use crate::error::{invalid, SceneFileError};

impl CheckedRobot {
    /// The robot built in algebra `A` (its mechanism the scene's first bodies and joints) and its bodies' states at
    /// the start.
    pub(crate) fn build<A: Algebra>(&self) -> Result<(Robot<A>, Vec<State<A>>), SceneFileError> {
        let robot =
            Robot::<A>::build(self.loaded.model.clone(), &self.options).map_err(|e| invalid("robot", e.to_string()))?;
        let states = robot
            .initial_states(&self.start)
            .map_err(|e| invalid("robot", format!("the start: {e}")))?;
        Ok((robot, states))
    }
}

/// A robot joint's model, its child and parent bodies (mechanism indices; `None`: the world) and where its position
/// coordinates start.
pub(crate) type RobotJoint = (JointModel, usize, Option<usize>, usize);

/// Where a joints-CSV column comes from.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// A position coordinate of the mechanism's joint space.
    Position(usize),
    /// A frozen joint's constant coordinate.
    Constant(f64),
}

/// The columns of `<stem>_joints_<algebra>.csv` between `t` and `energy`: every non-fixed joint in URDF file order
/// (frozen ones at their constant 0), then for a free root `base.x, base.y, base.z, base.qw, base.qx, base.qy,
/// base.qz` (the root link frame, world ← root).
#[derive(Clone, Debug)]
pub(crate) struct RobotColumns {
    /// `joint`, `joint.x`, …, `base.qz`.
    pub(crate) headers: Vec<String>,
    sources: Vec<Source>,
}

impl RobotColumns {
    /// The columns' values at joint positions `q` (the mechanism's joint space).
    pub(crate) fn row(&self, q: &[f64]) -> Vec<f64> {
        self.sources
            .iter()
            .map(|s| match s {
                Source::Position(i) => q[*i],
                Source::Constant(value) => *value,
            })
            .collect()
    }
}

/// The suffixes of a URDF joint kind's coordinates, with the constant value of a frozen one.
fn frozen_coordinates(kind: urdf_import::JointKind) -> &'static [(&'static str, f64)] {
    match kind {
        urdf_import::JointKind::Planar => &[("x", 0.0), ("y", 0.0), ("theta", 0.0)],
        urdf_import::JointKind::Floating => &[
            ("x", 0.0),
            ("y", 0.0),
            ("z", 0.0),
            ("qw", 1.0),
            ("qx", 0.0),
            ("qy", 0.0),
            ("qz", 0.0),
        ],
        urdf_import::JointKind::Fixed => &[],
        _ => &[("", 0.0)],
    }
}

/// A moving URDF joint of `robot` and its coordinates in `space` (the robot's mechanism, with the scene's bodies
/// added).
fn coordinate_group<'s, A: Algebra>(
    robot: &Robot<A>,
    space: &'s JointSpace,
    name: &str,
) -> Result<(JointId, &'s CoordinateGroup), SceneFileError> {
    let id = robot.joint(name).expect("every moving joint is in the mechanism");
    let group = space
        .groups()
        .iter()
        .find(|g| g.joint() == Some(id))
        .ok_or_else(|| invalid("robot", format!("joint {name} has no coordinates")))?;
    Ok((id, group))
}

impl LoadedRobot {
    /// The joints CSV's columns in `mechanism` (the robot's, with the scene's bodies added).
    pub(crate) fn columns<A: Algebra>(
        &self,
        robot: &Robot<A>,
        mechanism: &Mechanism<A>,
    ) -> Result<RobotColumns, SceneFileError> {
        let space = mechanism
            .joint_space()
            .map_err(|e| invalid("robot", format!("no joint coordinates: {e}")))?;
        // Moving and frozen joints in file order (by line).
        let mut entries: Vec<(u32, Vec<(String, Source)>)> = Vec::new();
        for joint in &self.model.joints {
            let (_, group) = coordinate_group(robot, space, &joint.name)?;
            let suffixes = group.model().kind().position_names();
            let columns = suffixes
                .iter()
                .enumerate()
                .map(|(k, suffix)| {
                    let header = if suffix.is_empty() {
                        joint.name.clone()
                    } else {
                        format!("{}.{suffix}", joint.name)
                    };
                    (header, Source::Position(group.position_offset() + k))
                })
                .collect();
            entries.push((joint.line, columns));
        }
        for frozen in &self.model.frozen_joints {
            let columns = frozen_coordinates(frozen.kind)
                .iter()
                .map(|(suffix, value)| {
                    let header = if suffix.is_empty() {
                        frozen.name.clone()
                    } else {
                        format!("{}.{suffix}", frozen.name)
                    };
                    (header, Source::Constant(*value))
                })
                .collect();
            entries.push((frozen.line, columns));
        }
        entries.sort_by_key(|(line, _)| *line);
        let (mut headers, mut sources): (Vec<String>, Vec<Source>) = entries.into_iter().flat_map(|(_, c)| c).unzip();
        if let Some(base) = robot.base() {
            let group = space
                .groups()
                .iter()
                .find(|g| g.body() == base && g.joint().is_none())
                .ok_or_else(|| invalid("robot", "the free root has no coordinates"))?;
            for (k, suffix) in ["x", "y", "z", "qw", "qx", "qy", "qz"].iter().enumerate() {
                headers.push(format!("base.{suffix}"));
                sources.push(Source::Position(group.position_offset() + k));
            }
        }
        Ok(RobotColumns { headers, sources })
    }

    /// Every moving joint's model with its child and parent body (mechanism indices) and where its positions start,
    /// to measure how far the bodies are from the pose their joint coordinates give.
    pub(crate) fn joint_models<A: Algebra>(
        &self,
        robot: &Robot<A>,
        mechanism: &Mechanism<A>,
    ) -> Result<Vec<RobotJoint>, SceneFileError> {
        let space = mechanism
            .joint_space()
            .map_err(|e| invalid("robot", format!("no joint coordinates: {e}")))?;
        self.model
            .joints
            .iter()
            .map(|joint| {
                let (id, group) = coordinate_group(robot, space, &joint.name)?;
                let parent = match mechanism.joint(id).map(|(_, _, reference)| reference) {
                    Some(Reference::Body(body)) => Some(body.index()),
                    _ => None,
                };
                Ok((
                    group.model().clone(),
                    group.body().index(),
                    parent,
                    group.position_offset(),
                ))
            })
            .collect()
    }
}
