//! A system ready to run in one algebra ([`SceneSystem`]): the mechanism (the robot's bodies and joints first, then the
//! file's), its initial state projected onto the joints, and what the run measures; and running it.

use dynamics::constraints::ConstraintError;
use dynamics::integrate::Integrator;
use dynamics::limits::JointLimit;
use dynamics::simulate::{simulate, Simulation};
use dynamics::{Algebra, Correction, Dynamics, FreeBody, JointId, JointKind, Mechanism, Reference, State};
use nalgebra::{Isometry3, Translation3, Vector3};

use super::constraints::{constraint_of, FileAlgebra};
use super::joint_models;
use super::robot::{RobotColumns, RobotJoint};
use crate::check::geometry::{joint_violations, relative_pose, JointGeometry, Pose};
use crate::check::layout::{named, prefix, End};
use crate::check::values::finite;
use crate::error::{invalid, SceneFileError};
use crate::names::FormulationName;
use crate::syntax::elements::DriveSpec;
use crate::syntax::file::SceneFile;

/// Where an end of a joint or force element is: the mechanism's reference (a body or the world) and the end's frame in
/// that reference's frame (a robot link's frame, else the identity).
pub(crate) type Place<'a> = dyn Fn(&End) -> Result<(Reference, Isometry3<f64>), SceneFileError> + 'a;

/// A system ready to run in one algebra: the mechanism (the robot's bodies and joints first, then the file's), its
/// initial state (one per body) on the joints, and what the run measures.
pub struct SceneSystem<A: Algebra> {
    pub system: Mechanism<A>,
    pub initial: Vec<State<A>>,
    /// Every body's name, in the mechanism's order.
    pub names: Vec<String>,
    /// The file's joints: their geometry (reference side in the reference body's frame, or the world's), body and
    /// reference, by mechanism index.
    pub geometries: Vec<JointGeometry>,
    /// The robot's moving joints: model, child, parent (mechanism indices) and where the coordinates start.
    pub robot_joints: Vec<RobotJoint>,
    /// The joints CSV's columns, with a robot.
    pub robot_columns: Option<RobotColumns>,
    /// How far putting the file's start on the joints moved each body.
    pub start_correction: Correction,
}

impl<A: Algebra> SceneSystem<A> {
    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism<A> {
        &self.system
    }

    /// The initial state, one per body, on the joints.
    pub fn initial(&self) -> &[State<A>] {
        &self.initial
    }

    /// Every body's name, in the mechanism's order (the robot's bodies, named after their links, first).
    pub fn body_names(&self) -> &[String] {
        &self.names
    }

    /// The headers of the joints CSV between `t` and `energy`, with a robot.
    pub fn joint_columns(&self) -> Option<&[String]> {
        self.robot_columns.as_ref().map(|c| c.headers.as_slice())
    }

    /// The joints CSV's values between `t` and `energy` at the mechanism's joint positions `q`.
    pub fn joint_row(&self, q: &[f64]) -> Option<Vec<f64>> {
        self.robot_columns.as_ref().map(|c| c.row(q))
    }

    /// The largest joint violation with the bodies at `poses` (mechanism order): the file's joints measured as
    /// [`CheckedGeometry::violation`](crate::CheckedGeometry::violation) (m), the robot's by how far each child is from where its joint's coordinates
    /// put it relative to its parent (the joint origin's distance, m, and the turn's angle, rad). `q`: the joint
    /// positions at these poses, if known.
    pub fn joint_violation(&self, poses: &[Pose], q: Option<&[f64]>) -> f64 {
        let files = joint_violations(&self.geometries, poses).fold(0.0, f64::max);
        if self.robot_joints.is_empty() {
            return files;
        }
        let read;
        let q = match q {
            Some(q) => q,
            None => {
                let states: Vec<State<A>> = poses
                    .iter()
                    .enumerate()
                    .map(|(i, (position, orientation))| {
                        State::new(
                            self.system.body(i),
                            *position,
                            orientation,
                            Vector3::zeros(),
                            Vector3::zeros(),
                        )
                    })
                    .collect();
                match self.system.joint_positions(&states, None) {
                    Ok(q) => {
                        read = q;
                        &read
                    }
                    Err(_) => return f64::NAN,
                }
            }
        };
        let isometry =
            |(position, orientation): &Pose| Isometry3::from_parts(Translation3::from(*position), *orientation);
        let robot = self
            .robot_joints
            .iter()
            .map(|(model, child, parent, offset)| {
                let parent = parent.map_or(Isometry3::identity(), |p| isometry(&poses[p]));
                let relative = parent.inverse() * isometry(&poses[*child]);
                let actual = model.parent_frame().inverse() * relative * model.child_frame();
                let count = model.kind().position_count();
                match model.joint_pose(&q[*offset..*offset + count]) {
                    Ok(placed) => (actual.translation.vector - placed.translation.vector)
                        .norm()
                        .max(actual.rotation.angle_to(&placed.rotation)),
                    Err(_) => f64::NAN,
                }
            })
            .fold(0.0, f64::max);
        files.max(robot)
    }
}

impl SceneFile {
    /// The system in algebra `A` and its initial state, projected onto the joints; an error if the joints
    /// cannot all hold there or their reactions cannot be solved for.
    pub fn system<A: FileAlgebra>(&self) -> Result<SceneSystem<A>, SceneFileError> {
        let layout = self.layout()?;
        let robot = self.robot()?;
        let built = robot.map(|(spec, loaded)| loaded.build::<A>(spec)).transpose()?;
        let (mut system, mut states) = match &built {
            Some((robot, states)) => (robot.mechanism().clone(), states.clone()),
            None => (Mechanism::<A>::new(), Vec::new()),
        };
        let offset = states.len();
        let mut ids = Vec::with_capacity(layout.bodies.len());
        for entry in &layout.bodies {
            let body = entry.spec.body().map_err(|e| named(&layout, &entry.name, e))?;
            let id = system.add_body(entry.name.clone(), body)?;
            ids.push(id);
            for (index, force) in entry.forces.iter().enumerate() {
                let force = force.force(index + 1).map_err(|e| named(&layout, &entry.name, e))?;
                system.add_force(id, force)?;
            }
            let initial = &entry.initial;
            let at = |what: &str| format!("{}initial.{what}", prefix(&layout, &entry.name));
            states.push(State::new(
                &body,
                finite(&at("position"), initial.position)?,
                &initial
                    .orientation
                    .rotation()
                    .map_err(|e| named(&layout, &entry.name, e))?,
                finite(&at("body_angular_velocity"), initial.body_angular_velocity)?,
                finite(&at("velocity"), initial.velocity)?,
            ));
        }
        if states.is_empty() {
            return Err(invalid(
                "robot",
                "nothing moves: the robot's root is fixed and it has no moving body, and the file has no [[body]]",
            ));
        }
        // Where an end is: the mechanism's reference and the end's frame in that reference's frame.
        let place = |end: &End| -> Result<(Reference, Isometry3<f64>), SceneFileError> {
            match end {
                End::World => Ok((Reference::World, Isometry3::identity())),
                End::Body(index) => Ok((Reference::Body(ids[*index]), Isometry3::identity())),
                End::Link(link) => built
                    .as_ref()
                    .and_then(|(robot, _)| robot.link_frame(link))
                    .ok_or_else(|| invalid(format!("link {link}"), "is not a link of the robot")),
            }
        };
        let index_of = |reference: Reference| match reference {
            Reference::World => None,
            Reference::Body(body) => Some(body.index()),
        };
        let pose_of = |reference: Reference, frame: &Isometry3<f64>, states: &[State<A>]| {
            let body = match reference {
                Reference::World => Isometry3::identity(),
                Reference::Body(body) => {
                    let (position, orientation) = states[body.index()].pose();
                    Isometry3::from_parts(Translation3::from(position), orientation)
                }
            };
            let world = body * frame;
            (world.translation.vector, world.rotation)
        };
        // Per mechanism body: the parent of its joint model, if it has one (the robot's bodies have theirs).
        let mut parent_of: Vec<Option<Option<usize>>> = vec![Some(None); offset];
        parent_of.resize(offset + layout.bodies.len(), None);
        let mut geometries = Vec::with_capacity(layout.joints.len());
        let mut file_joints: Vec<(String, JointId, Option<JointKind>, bool)> = Vec::new();
        let mut driven: Vec<(JointId, DriveSpec)> = Vec::new();
        let mut limited: Vec<(String, JointLimit)> = Vec::new();
        for joint in &layout.joints {
            let name = &joint.name;
            let child = offset + joint.body;
            let (reference, frame) = place(&joint.reference)?;
            let start = joint.geometry.needs_start().then(|| {
                let reference = pose_of(reference, &frame, &states);
                relative_pose(&states[child].pose(), Some(&reference))
            });
            let checked = joint.geometry.checked(name, start)?;
            let drive = joint
                .drive
                .map(|d| d.checked(&format!("joint {name}: drive"), self.duration))
                .transpose()?;
            let limit = joint
                .limit
                .map(|l| l.limit(&format!("joint {name}: limit")))
                .transpose()?;
            let pinned = joint.formulation == FormulationName::Pinning;
            let parent = index_of(reference);
            // A chain of joint models from the reference up that reaches the body would close a loop.
            let mut above = parent;
            let mut cycle = false;
            while let Some(b) = above {
                if b == child {
                    cycle = true;
                    break;
                }
                above = parent_of[b].flatten();
            }
            let model = (joint.entry && parent_of[child].is_none() && !cycle)
                .then(|| joint_models::joint_model(name, &checked, &frame, drive))
                .transpose()?
                .flatten();
            let frame_pose = (frame.translation.vector, frame.rotation);
            let in_body = checked.in_world(&frame_pose)?;
            match model {
                Some(mut model) => {
                    if let Some(limit) = limit {
                        model = model.with_limit(limit).map_err(|error| match error {
                            ConstraintError::InvalidParameter { reason, .. } => {
                                invalid(format!("joint {name}: limit"), reason)
                            }
                            other => other.into(),
                        })?;
                        limited.push((name.clone(), limit));
                    }
                    let kind = *model.kind();
                    let rows = joint_models::rows::<A>(&model, pinned, drive)?;
                    let id = system.connect_with_rows(ids[joint.body], reference, model, rows)?;
                    parent_of[child] = Some(parent);
                    file_joints.push((name.clone(), id, Some(kind), drive.is_some()));
                    if let Some(drive) = drive {
                        driven.push((id, drive));
                    }
                }
                None => {
                    for (key, given, verb) in [
                        ("limit", limit.is_some(), "limited"),
                        ("drive", drive.is_some(), "driven"),
                    ] {
                        if given {
                            return Err(invalid(
                                format!("joint {name}: {key}"),
                                if joint_models::has_model(&checked) {
                                    format!(
                                        "only a body's first joint, its joint model, is {verb}; this one closes a loop"
                                    )
                                } else {
                                    format!("only hinge and prismatic joints are {verb}")
                                },
                            ));
                        }
                    }
                    let constraint = constraint_of::<A>(name.clone(), in_body, pinned)?;
                    let id = system.add_joint(ids[joint.body], reference, constraint)?;
                    file_joints.push((name.clone(), id, None, false));
                }
            }
            geometries.push((in_body, child, parent));
        }
        system.set_stabilisation(self.stabilisation()?)?;
        self.add_elements(
            &layout,
            &mut system,
            &place,
            built.as_ref().map(|(r, _)| r),
            &file_joints,
        )?;
        self.add_contacts(&layout, &mut system, &place)?;
        // Onto the joints (theory §10); joints that cannot hold together are an error naming them, and a start that
        // breaks them by more than the file allows is refused.
        let mut initial = states;
        let start_correction = system.project(0.0, &mut initial)?;
        // Bodies on a joint model are placed by their joint, from the coordinates their state gives; the others' states
        // are where the file puts them.
        let held_as_given: Vec<bool> = (parent_of.iter().enumerate())
            .map(|(index, parent)| {
                let given = |name: &str| layout.bodies.iter().any(|body| body.initial_given && body.name == name);
                parent.is_none() && system.body_names().nth(index).is_some_and(given)
            })
            .collect();
        self.check_start_correction(&start_correction, &system, &held_as_given)?;
        if !driven.is_empty() {
            // The driven joints start on their paths (the projection by joint coordinates leaves them where they are).
            let mut q = system.joint_positions(&initial, None)?;
            let mut v = system.joint_velocities(&initial)?;
            let space = system.joint_space()?;
            for (id, drive) in &driven {
                if let Some(group) = space.groups().iter().find(|g| g.joint() == Some(*id)) {
                    let at = drive.at(0.0);
                    q[group.position_offset()] = at.value;
                    v[group.velocity_offset()] = at.rate;
                }
            }
            initial = system.states_from_joints(&q, &v)?;
            system.project(0.0, &mut initial)?;
        }
        if !limited.is_empty() {
            // A start outside a limit, by the joint's coordinate as the start gives it.
            let q = system.joint_positions(&initial, None)?;
            let space = system.joint_space()?;
            for (name, limit) in &limited {
                let group = space.group(name).expect("a limited joint is a joint model");
                let at = q[group.position_offset()];
                if limit.gap(at) < -dynamics::simulate::AT_BOUND {
                    return Err(invalid(
                        format!("joint {name}: limit"),
                        format!(
                            "the start puts the joint at {at:?}, outside [{:?}, {:?}]",
                            limit.lower(),
                            limit.upper()
                        ),
                    ));
                }
            }
        }
        self.check_contact_start(&system, &initial)?;
        // A rank-deficient or inconsistent reaction solve fails here, with the joints' names.
        system.rates_at(0.0, &initial)?;
        let (robot_columns, robot_joints) = match (&built, robot) {
            (Some((robot, _)), Some((_, loaded))) => (
                Some(loaded.columns(robot, &system)?),
                loaded.joint_models(robot, &system)?,
            ),
            _ => (None, Vec::new()),
        };
        Ok(SceneSystem {
            names: system.body_names().map(str::to_owned).collect(),
            system,
            initial,
            start_correction,
            geometries,
            robot_joints,
            robot_columns,
        })
    }

    /// Refuses a start that the projection onto the joints moved by more than `max_start_correction`, naming the body:
    /// of the bodies `checked` by index, those whose initial state the file gives and no joint model places.
    fn check_start_correction<A: Algebra>(
        &self,
        correction: &Correction,
        system: &Mechanism<A>,
        checked: &[bool],
    ) -> Result<(), SceneFileError> {
        let limit = self.max_start_correction;
        if !(limit.is_finite() && limit > 0.0) {
            return Err(invalid(
                "max_start_correction",
                format!("must be positive and finite (m and rad), got {limit}"),
            ));
        }
        let names: Vec<&str> = system.body_names().collect();
        let largest = (correction.moved.iter().zip(&correction.turned).enumerate())
            .filter(|(body, _)| checked.get(*body).copied().unwrap_or(false))
            .map(|(body, (moved, turned))| (body, moved.max(*turned)))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        match largest {
            Some((body, largest)) if largest > limit => Err(invalid(
                "max_start_correction",
                format!(
                    "the start breaks the joints: putting it on them moves body `{}` by {:.3e} m and turns it by \
                     {:.3e} rad, more than max_start_correction = {limit} (m and rad); correct its initial state or \
                     raise max_start_correction",
                    names[body], correction.moved[body], correction.turned[body],
                ),
            )),
            _ => Ok(()),
        }
    }

    /// Runs the scene in algebra `A`: one body without joints as a free body (where every integrator,
    /// splittings included, applies), otherwise as the mechanism.
    pub fn simulate<A: FileAlgebra>(&self) -> Result<Simulation<A>, SceneFileError> {
        let system = self.system::<A>()?;
        self.run(&system)
    }

    /// Runs `system` (this scene's, [`SceneFile::system`]).
    pub fn run<A: FileAlgebra>(&self, system: &SceneSystem<A>) -> Result<Simulation<A>, SceneFileError> {
        let schedule = self.schedule()?;
        let failed = |message: String| SceneFileError::Run {
            algebra: A::NAME,
            message,
        };
        let integrator = Integrator::from(self.integrator);
        let layout = self.layout()?;
        if self.free_body(&layout) {
            let only = &layout.bodies[0];
            let mut free = FreeBody::<A>::new(only.spec.body()?);
            for (index, force) in only.forces.iter().enumerate() {
                free = free.with_force(force.force(index + 1)?);
            }
            return simulate(&free, &system.initial, integrator, &schedule).map_err(|e| failed(e.to_string()));
        }
        simulate(&system.system, &system.initial, integrator, &schedule).map_err(|e| failed(e.to_string()))
    }
}
