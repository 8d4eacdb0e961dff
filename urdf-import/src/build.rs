//! Stage 5: a merged [`RobotModel`] built into a `dynamics` [`Mechanism`] — one body per rigid body (its inertia
//! diagonalised, the reference link's frame kept as the body's frame), one joint model per moving joint in file
//! order (with its `<limit>` if [`Limits::Enforce`]), gravity on every body, a coupling per mimic (in
//! [`MimicMode::Constraint`]), and projection onto the joints after every step. The root is fixed to the world (its
//! body is the world) or free (a floating base).

use dynamics::constraints::Stabilisation;
use dynamics::{
    Algebra, Body, BodyError, BodyId, Force, JointId, JointKind, JointModel, Mechanism, MechanismError, Reference,
    State,
};
use nalgebra::{Isometry3, Matrix3, UnitQuaternion, Vector3};

use dynamics::limits::JointLimit;

use crate::merge::{RigidBody, RobotModel};
use crate::parse::JointKind as UrdfJoint;
use crate::validate::MimicMode;

/// What the URDF's root link is attached to.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Root {
    /// Fixed to the world: the root body does not move (an arm bolted down); its links are the world frame.
    #[default]
    Fixed,
    /// Free: a floating base (a legged robot, a humanoid), with six coordinates of its own.
    Free,
}

/// Whether the URDF's `<limit lower upper>` of revolute and prismatic joints are enforced.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Limits {
    /// Not enforced: the joints move freely, as in Pinocchio's and most URDF simulators' dynamics without contacts.
    #[default]
    Ignore,
    /// Enforced exactly (`dynamics::limits`): impacts at the bounds with this restitution coefficient in [0, 1],
    /// held there while the bound pushes. A missing `lower` or `upper` is no bound on that side; a continuous joint
    /// is never limited; a mimic follower (coupled to its leader) has its leader's limit only.
    Enforce {
        /// Newton's restitution coefficient of every bound (0: the joint stops there).
        restitution: f64,
    },
}

/// How a model is built into a mechanism.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildOptions {
    /// Fixed or floating base.
    pub root: Root,
    /// The gravitational acceleration (m/s², world axes), on every body.
    pub gravity: Vector3<f64>,
    /// Whether the joints' position limits are enforced.
    pub limits: Limits,
}

impl Default for BuildOptions {
    /// A fixed root, 9.81 m/s² along −z, limits ignored.
    fn default() -> Self {
        BuildOptions {
            root: Root::Fixed,
            gravity: Vector3::new(0.0, 0.0, -dynamics::forces::STANDARD_GRAVITY),
            limits: Limits::Ignore,
        }
    }
}

/// What a free root that cannot move freely lacks: mass, or (with mass) moments of inertia.
fn root_advice(mass: f64) -> &'static str {
    if mass > 0.0 && mass.is_finite() {
        "give its links moments of inertia (the mass is there; the inertia about some axis is not)"
    } else {
        "give its links mass"
    }
}

/// Why a model cannot be built, or a start state cannot be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BuildError {
    /// A free root whose body has no mass or a singular inertia.
    #[error(
        "root body `{body}`: a free root needs mass and an invertible inertia, got {mass:e} kg and principal moments \
         {moments:?} kg m²; fix the root to the world, or {}",
        root_advice(*.mass)
    )]
    RootNotFree {
        /// The root body's name.
        body: String,
        /// Its mass (kg).
        mass: f64,
        /// Its principal moments (kg m²).
        moments: [f64; 3],
    },
    /// A body's mass properties were refused by `dynamics`.
    #[error("body `{body}`: {source}")]
    Body {
        /// The body's name.
        body: String,
        /// Why.
        source: BodyError,
    },
    /// The gravity vector is not finite.
    #[error("gravity must be finite, got {0:?}")]
    Gravity([f64; 3]),
    /// A start state names a joint the robot does not move.
    #[error("no moving joint is named `{name}`{hint}")]
    UnknownJoint {
        /// The name given.
        name: String,
        /// Why it is not there, if known (frozen, fixed).
        hint: String,
    },
    /// A start state gives a mimic follower a value its leader contradicts.
    #[error("joint `{joint}` follows `{leader}` (q = {multiplier} q_leader + {offset}): {what} {given} given, {implied} implied")]
    Mimic {
        /// The follower.
        joint: String,
        /// Its leader.
        leader: String,
        /// The mimic's multiplier.
        multiplier: f64,
        /// The mimic's offset.
        offset: f64,
        /// "position" or "velocity".
        what: &'static str,
        /// The value given.
        given: f64,
        /// The value the leader implies.
        implied: f64,
    },
    /// A start state names a joint twice among its positions, or twice among its velocities.
    #[error("the start gives the {what} of joint `{name}` twice ({first} and {second})")]
    Repeated {
        /// The joint's name.
        name: String,
        /// "position" or "velocity".
        what: &'static str,
        /// The first value given.
        first: f64,
        /// The second.
        second: f64,
    },
    /// A start state gives a base pose or twist to a robot whose root is fixed.
    #[error("the root is fixed to the world: a base {0} cannot be given")]
    FixedBase(&'static str),
    /// A value of the start state that is not finite (the name held).
    #[error("{what} must be finite, got {value:?}")]
    NotFinite {
        /// What it is: "position of joint `elbow`", "base orientation".
        what: String,
        /// The value.
        value: Vec<f64>,
    },
    /// A joint's `<limit>` cannot be enforced: its range is empty (`lower = upper`: the joint cannot move; make it
    /// fixed), or the restitution is outside [0, 1].
    #[error("joint `{joint}`: {reason}")]
    Limit {
        /// The joint's name.
        joint: String,
        /// Why.
        reason: String,
    },
    /// The mechanism refused a body, joint or coupling, or the start state (named in the message).
    #[error(transparent)]
    Mechanism(#[from] MechanismError),
}

/// A floating base's start: the root link frame's pose, the velocity of its origin and its angular velocity, all
/// in world axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BaseStart {
    /// The root link frame's origin (m, world).
    pub position: Vector3<f64>,
    /// The root link frame's orientation (world ← root).
    pub orientation: UnitQuaternion<f64>,
    /// The velocity of the root link frame's origin (m/s, world axes).
    pub velocity: Vector3<f64>,
    /// The angular velocity (rad/s, world axes).
    pub angular_velocity: Vector3<f64>,
}

impl Default for BaseStart {
    /// At the world origin, unrotated, at rest.
    fn default() -> Self {
        BaseStart {
            position: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
            velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
        }
    }
}

/// A robot's start: joint positions and velocities by joint name (rad or m; joints not named start at 0), and for a
/// floating base its pose and twist.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RobotStart {
    /// Joint positions by name.
    pub positions: Vec<(String, f64)>,
    /// Joint velocities by name.
    pub velocities: Vec<(String, f64)>,
    /// The floating base's start (must be the default for a fixed root).
    pub base: BaseStart,
}

/// A URDF robot built as a mechanism.
#[derive(Clone, Debug)]
pub struct Robot<A: Algebra> {
    mechanism: Mechanism<A>,
    model: RobotModel,
    root: Root,
    /// Per moving joint (file order): its joint in the mechanism.
    joints: Vec<JointId>,
    /// Per rigid body: its body in the mechanism (`None` for a fixed root, the world).
    bodies: Vec<Option<BodyId>>,
    /// Per rigid body: its reference-link frame in its body frame (the world's: identity).
    frames: Vec<Isometry3<f64>>,
}

fn finite(v: &Vector3<f64>) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The body of a rigid body (its inertia diagonalised about the centre) and the body's pose in the reference-link
/// frame.
fn rigid_body(body: &RigidBody) -> Result<(Body, dynamics::PrincipalFrame), BuildError> {
    let inertia: Matrix3<f64> = body.inertia;
    Body::from_inertia_tensor(body.mass, inertia, body.centre_of_mass, body.centre_of_mass).map_err(|source| {
        BuildError::Body {
            body: body.name.clone(),
            source,
        }
    })
}

impl<A: Algebra> Robot<A> {
    /// Builds `model` as a mechanism (see the module docs).
    ///
    /// ```
    /// use dynamics::Pga;
    /// use urdf_import::{read, BuildOptions, ImportOptions, Robot, RobotStart};
    ///
    /// let urdf = r#"<robot name="pendulum">
    ///   <link name="base"/>
    ///   <link name="rod"><inertial><origin xyz="0 0 -0.5"/><mass value="1"/>
    ///     <inertia ixx="0.0833" ixy="0" ixz="0" iyy="0.0833" iyz="0" izz="0.001"/></inertial></link>
    ///   <joint name="pivot" type="continuous"><parent link="base"/><child link="rod"/><axis xyz="1 0 0"/></joint>
    /// </robot>"#;
    /// let robot = Robot::<Pga>::build(read(urdf, &ImportOptions::default())?, &BuildOptions::default())?;
    /// assert_eq!((robot.mechanism().body_names().count(), robot.joint_names().count()), (1, 1));
    /// let start = RobotStart { positions: vec![("pivot".into(), 0.5)], ..RobotStart::default() };
    /// let states = robot.initial_states(&start)?;
    /// let q = robot.mechanism().joint_positions(&states, None)?;
    /// assert!((q[0] - 0.5).abs() < 1e-15); // rad
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn build(model: RobotModel, options: &BuildOptions) -> Result<Self, BuildError> {
        if !finite(&options.gravity) {
            let g = options.gravity;
            return Err(BuildError::Gravity([g.x, g.y, g.z]));
        }
        let mut mechanism = Mechanism::<A>::new();
        let mut bodies = Vec::with_capacity(model.bodies.len());
        let mut frames = Vec::with_capacity(model.bodies.len());
        for (index, rigid) in model.bodies.iter().enumerate() {
            if index == 0 && options.root == Root::Fixed {
                bodies.push(None);
                frames.push(Isometry3::identity());
                continue;
            }
            let (body, principal) = rigid_body(rigid).map_err(|error| match error {
                BuildError::Body { .. } if index == 0 => BuildError::RootNotFree {
                    body: rigid.name.clone(),
                    mass: rigid.mass,
                    moments: rigid.principal_moments().unwrap_or([f64::NAN; 3]),
                },
                other => other,
            })?;
            let id = mechanism.add_body_with_frame(rigid.name.clone(), body, principal)?;
            mechanism.add_force(
                id,
                Force::Gravity {
                    acceleration: options.gravity,
                },
            )?;
            bodies.push(Some(id));
            frames.push(Isometry3::from_parts(principal.centre_of_mass.into(), principal.rotation).inverse());
        }
        let mut joints = Vec::with_capacity(model.joints.len());
        for joint in &model.joints {
            let axis = joint.axis.into_inner();
            let kind = match joint.kind {
                UrdfJoint::Revolute | UrdfJoint::Continuous => JointKind::Revolute { axis },
                UrdfJoint::Prismatic => JointKind::Prismatic { axis },
                UrdfJoint::Planar => JointKind::Planar { normal: axis },
                UrdfJoint::Floating => JointKind::Free,
                UrdfJoint::Fixed => unreachable!("fixed joints are merged"),
            };
            // The joint frame is the child link frame at q = 0: `origin` in the parent's reference-link frame, the
            // identity in the child's.
            let parent_frame = frames[joint.parent] * joint.origin;
            let child_frame = frames[joint.child];
            let mut model_joint =
                JointModel::new(joint.name.clone(), kind, parent_frame, child_frame).map_err(MechanismError::from)?;
            let follows =
                model.mimic == MimicMode::Constraint && joint.mimic.as_ref().is_some_and(|m| m.index.is_some());
            if let (Limits::Enforce { restitution }, Some(range), false) =
                (options.limits, joint.position_range(), follows)
            {
                let refused = |error: dynamics::ConstraintError| BuildError::Limit {
                    joint: joint.name.clone(),
                    reason: match error {
                        dynamics::ConstraintError::InvalidParameter { reason, .. } => reason,
                        other => other.to_string(),
                    },
                };
                let limit = JointLimit::new(range.0, range.1)
                    .and_then(|limit| limit.with_restitution(restitution))
                    .map_err(refused)?;
                model_joint = model_joint.with_limit(limit).map_err(refused)?;
            }
            let child = bodies[joint.child].expect("a joint's child is a moving body");
            let parent = bodies[joint.parent].map_or(Reference::World, Reference::Body);
            joints.push(mechanism.connect(child, parent, model_joint)?);
        }
        if model.mimic == MimicMode::Constraint {
            for (index, joint) in model.joints.iter().enumerate() {
                if let Some(mimic) = &joint.mimic {
                    if let Some(leader) = mimic.index {
                        mechanism.couple(joints[index], joints[leader], mimic.multiplier, mimic.offset)?;
                    }
                }
            }
        }
        mechanism.set_stabilisation(Stabilisation::PROJECTION)?;
        Ok(Robot {
            mechanism,
            model,
            root: options.root,
            joints,
            bodies,
            frames,
        })
    }

    /// The mechanism.
    pub fn mechanism(&self) -> &Mechanism<A> {
        &self.mechanism
    }

    /// The mechanism, to add forces, bodies and joints to it.
    pub fn mechanism_mut(&mut self) -> &mut Mechanism<A> {
        &mut self.mechanism
    }

    /// The imported model (its bodies, joints, repairs and warnings).
    pub fn model(&self) -> &RobotModel {
        &self.model
    }

    /// The root's attachment.
    pub fn root(&self) -> Root {
        self.root
    }

    /// The moving joints' names, in file order.
    pub fn joint_names(&self) -> impl Iterator<Item = &str> {
        self.model.joints.iter().map(|j| j.name.as_str())
    }

    /// The mechanism's joint of a moving joint, by name.
    pub fn joint(&self, name: &str) -> Option<JointId> {
        self.model
            .joints
            .iter()
            .position(|j| j.name == name)
            .map(|i| self.joints[i])
    }

    /// Where a link is: the body carrying it (or the world, for a fixed root's links) and the link frame in that
    /// body's frame — to attach further bodies to a robot by link name.
    pub fn link_frame(&self, link: &str) -> Option<(Reference, Isometry3<f64>)> {
        self.model.bodies.iter().enumerate().find_map(|(b, body)| {
            body.links.iter().find(|l| l.name == link).map(|placement| {
                let reference = self.bodies[b].map_or(Reference::World, Reference::Body);
                (reference, self.frames[b] * placement.pose)
            })
        })
    }

    /// The floating base's body, for a free root.
    pub fn base(&self) -> Option<BodyId> {
        self.bodies[0]
    }

    /// The bodies' states at `start` (exact forward kinematics, [`Mechanism::states_from_joints`]). Mimic followers
    /// take the position and velocity their leader implies; a value given for one must agree with it.
    ///
    /// One state per body of the mechanism, in its body order — bodies attached after the build included, which
    /// their joint models place at zero coordinates (`start` names the URDF's joints only; a driven joint is moved
    /// onto its drive by the simulation's first projection). It fails if a joint added after the build is not a
    /// joint model: there are then no joint coordinates to place the bodies by.
    pub fn initial_states(&self, start: &RobotStart) -> Result<Vec<State<A>>, BuildError> {
        let space = self.mechanism.joint_space()?;
        let mut q = space.neutral_positions();
        let mut v = vec![0.0; space.velocity_count()];
        let lookup = |name: &str| {
            self.model
                .joints
                .iter()
                .position(|j| j.name == name)
                .ok_or_else(|| BuildError::UnknownJoint {
                    name: name.to_owned(),
                    hint: if self.model.frozen_joints.iter().any(|f| f.name == name) {
                        " (it is frozen: its subtree has no mass)".to_owned()
                    } else {
                        String::new()
                    },
                })
        };
        let slot = |index: usize, velocities: bool| -> usize {
            let group = space
                .groups()
                .iter()
                .find(|g| g.joint() == Some(self.joints[index]))
                .expect("every moving joint has coordinates");
            if velocities {
                group.velocity_offset()
            } else {
                group.position_offset()
            }
        };
        for (values, velocities, target) in [(&start.positions, false, &mut q), (&start.velocities, true, &mut v)] {
            for (k, (name, value)) in values.iter().enumerate() {
                if let Some((_, first)) = values[..k].iter().find(|(other, _)| other == name) {
                    return Err(BuildError::Repeated {
                        name: name.clone(),
                        what: if velocities { "velocity" } else { "position" },
                        first: *first,
                        second: *value,
                    });
                }
                let index = lookup(name)?;
                if !value.is_finite() {
                    let what = if velocities { "velocity" } else { "position" };
                    return Err(BuildError::NotFinite {
                        what: format!("{what} of joint `{name}`"),
                        value: vec![*value],
                    });
                }
                let dof = self.model.joints[index].kind.degrees_of_freedom();
                if dof != 1 {
                    return Err(BuildError::UnknownJoint {
                        name: name.clone(),
                        hint: format!(
                            " with one coordinate (it is {}, with {dof})",
                            self.model.joints[index].kind
                        ),
                    });
                }
                target[slot(index, velocities)] = *value;
            }
        }
        if self.model.mimic == MimicMode::Constraint {
            for (index, joint) in self.model.joints.iter().enumerate() {
                let (Some(mimic), Some(leader)) = (&joint.mimic, joint.mimic.as_ref().and_then(|m| m.index)) else {
                    continue;
                };
                for (what, given, velocities, target) in [
                    ("position", &start.positions, false, &mut q),
                    ("velocity", &start.velocities, true, &mut v),
                ] {
                    let offset = if velocities { 0.0 } else { mimic.offset };
                    let implied = mimic.multiplier * target[slot(leader, velocities)] + offset;
                    if let Some((_, value)) = given.iter().find(|(n, _)| *n == joint.name) {
                        if (value - implied).abs() > 1e-12 * (1.0 + implied.abs()) {
                            return Err(BuildError::Mimic {
                                joint: joint.name.clone(),
                                leader: self.model.joints[leader].name.clone(),
                                multiplier: mimic.multiplier,
                                offset: mimic.offset,
                                what,
                                given: *value,
                                implied,
                            });
                        }
                    }
                    target[slot(index, velocities)] = implied;
                }
            }
        }
        let base = &start.base;
        let parts = [
            ("base position", base.position.as_slice().to_vec()),
            ("base orientation", base.orientation.coords.as_slice().to_vec()),
            ("base velocity", base.velocity.as_slice().to_vec()),
            ("base angular velocity", base.angular_velocity.as_slice().to_vec()),
        ];
        if let Some((what, value)) = parts.iter().find(|(_, v)| !v.iter().all(|x| x.is_finite())) {
            return Err(BuildError::NotFinite {
                what: (*what).to_owned(),
                value: value.clone(),
            });
        }
        match self.bodies[0] {
            Some(root) => {
                let group = space
                    .groups()
                    .iter()
                    .find(|g| g.body() == root && g.joint().is_none())
                    .expect("a free root has coordinates");
                let (at, rate) = (group.position_offset(), group.velocity_offset());
                let rotation = base.orientation;
                let quaternion = rotation.quaternion();
                q[at..at + 7].copy_from_slice(&[
                    base.position.x,
                    base.position.y,
                    base.position.z,
                    quaternion.w,
                    quaternion.i,
                    quaternion.j,
                    quaternion.k,
                ]);
                // The free root's velocities are in its own axes (Pinocchio's free flyer).
                let (linear, angular) = (
                    rotation.inverse() * base.velocity,
                    rotation.inverse() * base.angular_velocity,
                );
                v[rate..rate + 6].copy_from_slice(&[linear.x, linear.y, linear.z, angular.x, angular.y, angular.z]);
            }
            None => {
                if *base != BaseStart::default() {
                    let what = if base.position != Vector3::zeros() || base.orientation != UnitQuaternion::identity() {
                        "pose"
                    } else {
                        "twist"
                    };
                    return Err(BuildError::FixedBase(what));
                }
            }
        }
        Ok(self.mechanism.states_from_joints(&q, &v)?)
    }
}
