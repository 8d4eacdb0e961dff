//! The mechanism assembled in one algebra (`Assembly`): the robot's bodies and joints first (`urdf_import`), then the
//! file's bodies with their forces and initial states, then the file's joints, each a joint model where it can be (a
//! `[[joint]]`, its body's first of a kind with coordinates, closing no loop) and a constraint otherwise.

use dynamics::constraints::ConstraintError;
use dynamics::limits::JointLimit;
use dynamics::{Algebra, BodyId, JointId, JointKind, Mechanism, Reference, State};
use nalgebra::{Isometry3, Translation3};
use urdf_import::Robot;

use super::constraints::{constraint_of, RoundPins};
use super::joint_models;
use crate::check::bodies::Pose;
use crate::check::geometry::{relative_pose, JointGeometry};
use crate::check::layout::{End, LayoutJoint};
use crate::check::scene::CheckedScene;
use crate::error::{invalid, SceneFileError};
use crate::names::FormulationName;
use crate::syntax::elements::DriveSpec;

/// Where the ends of joints, force elements and contacts are: the robot's links and the file's bodies.
pub(crate) struct Places<A: Algebra> {
    /// The robot, built.
    pub(crate) robot: Option<Robot<A>>,
    /// The file's bodies in the mechanism, by their index in the layout.
    pub(crate) ids: Vec<BodyId>,
}

impl<A: Algebra> Places<A> {
    /// The mechanism's reference of `end` (a body or the world) and the end's frame in that reference's frame (a robot
    /// link's frame, else the identity).
    pub(crate) fn place(&self, end: &End) -> Result<(Reference, Isometry3<f64>), SceneFileError> {
        match end {
            End::World => Ok((Reference::World, Isometry3::identity())),
            End::Body(index) => Ok((Reference::Body(self.ids[*index]), Isometry3::identity())),
            End::Link(link) => (self.robot.as_ref())
                .and_then(|robot| robot.link_frame(link))
                .ok_or_else(|| invalid(format!("link {link}"), "is not a link of the robot")),
        }
    }
}

/// A joint of the file in the mechanism.
pub(crate) struct FileJoint {
    pub(crate) name: String,
    pub(crate) id: JointId,
    /// Its joint model's kind, if it is one.
    pub(crate) model: Option<JointKind>,
    pub(crate) driven: bool,
}

/// The mechanism of a scene being assembled, and what the steps after the joints need to know of it.
pub(crate) struct Assembly<'s, A: Algebra> {
    pub(crate) scene: &'s CheckedScene,
    pub(crate) mechanism: Mechanism<A>,
    /// Every body's state at the start, as the robot's start and the file give it (not yet on the joints).
    pub(crate) states: Vec<State<A>>,
    pub(crate) places: Places<A>,
    /// Per mechanism body: the parent of its joint model, if it has one (the robot's bodies have theirs).
    pub(crate) parent_of: Vec<Option<Option<usize>>>,
    /// The file's joints: their geometry (reference side in the reference body's frame, or the world's), body and
    /// reference, by mechanism index.
    pub(crate) geometries: Vec<JointGeometry>,
    pub(crate) file_joints: Vec<FileJoint>,
    /// The driven joints and their drives.
    pub(crate) driven: Vec<(JointId, DriveSpec)>,
    /// The limited joints by name, and their limits.
    pub(crate) limited: Vec<(String, JointLimit)>,
}

impl<'s, A: RoundPins> Assembly<'s, A> {
    /// The robot's bodies and joints, then the file's bodies with their forces and states.
    pub(crate) fn new(scene: &'s CheckedScene) -> Result<Assembly<'s, A>, SceneFileError> {
        let (robot, mut mechanism, mut states) = match &scene.robot {
            Some(robot) => {
                let (robot, states) = robot.build::<A>()?;
                let mechanism = robot.mechanism().clone();
                (Some(robot), mechanism, states)
            }
            None => (None, Mechanism::<A>::new(), Vec::new()),
        };
        let layout = &scene.layout;
        let mut parent_of: Vec<Option<Option<usize>>> = vec![Some(None); states.len()];
        parent_of.resize(states.len() + layout.bodies.len(), None);
        let mut ids = Vec::with_capacity(layout.bodies.len());
        for entry in &layout.bodies {
            let id = mechanism.add_body(entry.name.clone(), entry.body)?;
            ids.push(id);
            for force in &entry.forces {
                mechanism.add_force(id, force.force())?;
            }
            states.push(entry.initial.state(&entry.body));
        }
        Ok(Assembly {
            scene,
            mechanism,
            states,
            places: Places { robot, ids },
            parent_of,
            geometries: Vec::with_capacity(layout.joints.len()),
            file_joints: Vec::with_capacity(layout.joints.len()),
            driven: Vec::new(),
            limited: Vec::new(),
        })
    }

    /// The file's joints, in file order.
    pub(crate) fn add_joints(&mut self) -> Result<(), SceneFileError> {
        for joint in &self.scene.layout.joints {
            self.add_joint(joint)?;
        }
        Ok(())
    }

    /// A joint: its joint model where it has one, else its constraint.
    fn add_joint(&mut self, joint: &LayoutJoint) -> Result<(), SceneFileError> {
        let name = &joint.name;
        let offset = self.parent_of.len() - self.places.ids.len();
        let child = offset + joint.body;
        let (reference, frame) = self.places.place(&joint.reference)?;
        let checked = (joint.geometry).at_start(|| {
            let reference = self.pose_of(reference, &frame);
            relative_pose(&self.states[child].pose(), Some(&reference))
        });
        let (drive, limit) = (joint.drive, joint.limit);
        let pinned = joint.formulation == FormulationName::Pinning;
        let parent = match reference {
            Reference::World => None,
            Reference::Body(body) => Some(body.index()),
        };
        let model = (joint.entry && self.parent_of[child].is_none() && !self.closes_loop(parent, child))
            .then(|| joint_models::joint_model(name, &checked, &frame, drive))
            .transpose()?
            .flatten();
        let in_body = checked.in_world(&(frame.translation.vector, frame.rotation))?;
        let body = self.places.ids[joint.body];
        match model {
            Some(mut model) => {
                if let Some(limit) = limit {
                    model = model.with_limit(limit).map_err(|error| match error {
                        ConstraintError::InvalidParameter { reason, .. } => {
                            invalid(format!("joint {name}: limit"), reason)
                        }
                        other => other.into(),
                    })?;
                    self.limited.push((name.clone(), limit));
                }
                let kind = *model.kind();
                let rows = joint_models::rows::<A>(&model, pinned, drive)?;
                let id = self.mechanism.connect_with_rows(body, reference, model, rows)?;
                self.parent_of[child] = Some(parent);
                self.file_joints.push(FileJoint {
                    name: name.clone(),
                    id,
                    model: Some(kind),
                    driven: drive.is_some(),
                });
                if let Some(drive) = drive {
                    self.driven.push((id, drive));
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
                                format!("only a body's first joint, its joint model, is {verb}; this one closes a loop")
                            } else {
                                format!("only hinge and prismatic joints are {verb}")
                            },
                        ));
                    }
                }
                let constraint = constraint_of::<A>(name.clone(), in_body, pinned)?;
                let id = self.mechanism.add_joint(body, reference, constraint)?;
                self.file_joints.push(FileJoint {
                    name: name.clone(),
                    id,
                    model: None,
                    driven: false,
                });
            }
        }
        self.geometries.push((in_body, child, parent));
        Ok(())
    }

    /// Whether a chain of joint models from `parent` up reaches `child`: a joint model between them would close a loop.
    fn closes_loop(&self, parent: Option<usize>, child: usize) -> bool {
        let mut above = parent;
        while let Some(body) = above {
            if body == child {
                return true;
            }
            above = self.parent_of[body].flatten();
        }
        false
    }

    /// The pose of the frame `frame` of `reference` at the start, in the world.
    fn pose_of(&self, reference: Reference, frame: &Isometry3<f64>) -> Pose {
        let body = match reference {
            Reference::World => Isometry3::identity(),
            Reference::Body(body) => {
                let (position, orientation) = self.states[body.index()].pose();
                Isometry3::from_parts(Translation3::from(position), orientation)
            }
        };
        let world = body * frame;
        (world.translation.vector, world.rotation)
    }
}
