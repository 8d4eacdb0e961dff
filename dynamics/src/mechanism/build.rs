//! Building a mechanism: adding bodies, forces, joints and couplings, choosing its stabilisation and solver
//! settings, and the structures of its solves rebuilt after each change (docs/mechanisms.md §M2–§M4).

use std::sync::Arc;

use nalgebra::Isometry3;

use crate::algebra::Algebra;
use crate::body::{Body, PrincipalFrame};
use crate::constraints::{Constraint, ConstraintError, Stabilisation};
use crate::forces::Force;
use crate::joint_models::{JointKind, JointModel, Unconstrained};
use crate::mechanism::articulated::{Articulation, Row};
use crate::mechanism::error::MechanismError;
use crate::mechanism::joint_rows::Joint;
use crate::mechanism::model::Mechanism;
use crate::mechanism::parts::{BodyId, Coupling, JointId, Limit, MechanismBody, Reference};
use crate::mechanism::solve::SolverSettings;
use crate::mechanism::topology::Topology;

impl<A: Algebra> Mechanism<A> {
    /// A mechanism with no bodies, stabilised by projection ([`Stabilisation::PROJECTION`]: the joints hold to
    /// round-off unless [`Mechanism::set_stabilisation`] chooses otherwise) and the default solver settings.
    ///
    /// Two rods joined end to end by a ball joint, floating free: the joint's reactions on the two bodies are equal
    /// and opposite, so the total momentum does not change.
    ///
    /// ```
    /// use dynamics::constraints::VirtualPower;
    /// use dynamics::{Algebra, Body, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?;
    /// let (top, bottom) = (Vector3::new(0.0, 0.0, 0.5), Vector3::new(0.0, 0.0, -0.5)); // body points, m
    /// let mut pair = Mechanism::<Pga>::new();
    /// let (a, b) = (pair.add_body("a", rod)?, pair.add_body("b", rod)?);
    /// pair.add_joint(b, a, VirtualPower::ball_joint("elbow", top, bottom))?;
    /// // a spins about x at 1 rad/s, b follows a's bottom end (0.5 m/s along y) without turning.
    /// let still = UnitQuaternion::identity();
    /// let states = [
    ///     State::new(&rod, Vector3::zeros(), &still, Vector3::x(), Vector3::zeros()),
    ///     State::new(&rod, Vector3::z() * -1.0, &still, Vector3::zeros(), Vector3::y() * 0.5),
    /// ];
    /// let rates = pair.rates_at(0.0, &states)?;
    /// let pull = Pga::screw_coordinates(rates[0].momentum_rate);
    /// let total = Pga::screw_coordinates(rates[0].momentum_rate + rates[1].momentum_rate);
    /// assert!(pull.l.norm() > 0.1); // N: the joint pulls
    /// assert!(total.l.norm() < 1e-12 && total.t.norm() < 1e-12); // N, N m
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new() -> Self {
        Mechanism {
            bodies: Vec::new(),
            joints: Vec::new(),
            stabilisation: Stabilisation::PROJECTION,
            settings: SolverSettings::default(),
            topology: Topology::default(),
            articulation: None,
            joint_space: std::sync::OnceLock::new(),
            couplings: Vec::new(),
            coupling_rows: Vec::new(),
            frictional: Vec::new(),
            limits: Vec::new(),
            contacts: Vec::new(),
            elements: Vec::new(),
        }
    }

    /// One body, named "body", and nothing else: the constrained single body, with [`Mechanism::with_force`]
    /// and [`Mechanism::with_constraint`] holding it to the world.
    ///
    /// Without constraints it moves as a [`crate::FreeBody`]:
    ///
    /// ```
    /// use dynamics::{Body, Force, FreeBody, Mechanism, Pga, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let top = Body::solid_cone(0.5, 0.4, 0.1)?;
    /// let single = Mechanism::<Pga>::single(top).with_force(Force::gravity())?;
    /// assert_eq!((single.body_names().collect::<Vec<_>>(), single.joint_count()), (vec!["body"], 0));
    /// let free = FreeBody::<Pga>::new(top).with_force(Force::gravity());
    /// let turned = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 0.0, 0.1));
    /// let state = State::new(&top, Vector3::z(), &turned, Vector3::new(0.5, 0.0, 30.0), Vector3::x());
    /// let (ours, theirs) = (single.rates_at(0.0, &[state])?[0], free.rates_at(0.0, &state));
    /// assert_eq!(ours.momentum_rate, theirs.momentum_rate);
    /// assert_eq!(ours.body_velocity, theirs.body_velocity);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn single(body: Body) -> Self {
        let mut mechanism = Mechanism::new();
        mechanism.bodies.push(MechanismBody {
            name: "body".to_owned(),
            body,
            forces: Vec::new(),
            frame: Isometry3::identity(),
        });
        mechanism.rebuild();
        mechanism
    }

    /// Adds a body; its name must be unique (it names the body in errors and output).
    pub fn add_body(&mut self, name: impl Into<String>, body: Body) -> Result<BodyId, MechanismError> {
        self.push_body(name.into(), body, Isometry3::identity())
    }

    /// Adds a body whose inertia was given in another frame (a CAD part's, a URDF link's): `frame` is where its
    /// principal frame sits there ([`Body::from_inertia_tensor`]). That frame is the body's reference frame: a free
    /// root's joint coordinates are its pose and twist ([`JointSpace`](crate::JointSpace)).
    ///
    /// ```
    /// use dynamics::{Body, Mechanism, Pga};
    /// use nalgebra::{Matrix3, Vector3};
    ///
    /// // A link whose centre of mass is 0.2 m along its frame's z axis.
    /// let inertia = Matrix3::from_diagonal(&Vector3::new(0.02, 0.02, 0.01));
    /// let (link, frame) = Body::from_inertia_tensor(2.0, inertia, Vector3::z() * 0.2, Vector3::z() * 0.2)?;
    /// let mut robot = Mechanism::<Pga>::new();
    /// let base = robot.add_body_with_frame("base", link, frame)?;
    /// assert_eq!(robot.body_id("base"), Some(base));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn add_body_with_frame(
        &mut self,
        name: impl Into<String>,
        body: Body,
        frame: PrincipalFrame,
    ) -> Result<BodyId, MechanismError> {
        let principal = Isometry3::from_parts(frame.centre_of_mass.into(), frame.rotation);
        self.push_body(name.into(), body, principal.inverse())
    }

    fn push_body(&mut self, name: String, body: Body, frame: Isometry3<f64>) -> Result<BodyId, MechanismError> {
        if name.is_empty() {
            return Err(MechanismError::EmptyName("body"));
        }
        if self.bodies.iter().any(|b| b.name == name) {
            return Err(MechanismError::DuplicateBody(name));
        }
        let finite = frame
            .translation
            .vector
            .iter()
            .chain(frame.rotation.coords.iter())
            .all(|x| x.is_finite());
        if !finite {
            return Err(ConstraintError::InvalidParameter {
                name,
                reason: "the body's frame is not finite".to_owned(),
            }
            .into());
        }
        self.bodies.push(MechanismBody {
            name,
            body,
            forces: Vec::new(),
            frame,
        });
        self.rebuild();
        Ok(BodyId(self.bodies.len() - 1))
    }

    pub(super) fn check_body(&self, body: BodyId) -> Result<usize, MechanismError> {
        (body.0 < self.bodies.len())
            .then_some(body.0)
            .ok_or(MechanismError::UnknownBody(body.0))
    }

    /// Adds an external force on a body.
    pub fn add_force(&mut self, body: BodyId, force: Force<A>) -> Result<(), MechanismError> {
        let index = self.check_body(body)?;
        self.bodies[index].forces.push(force);
        Ok(())
    }

    /// Adds a joint: `constraint` holds `body` to `reference` — its "body" objects are fixed in `body`, its
    /// "world" objects in the reference (the world, or another body's frame). Checks the declared rank (1 to 6,
    /// at most the rows), the row capacity and, with projection, that the constraint has a position residual.
    pub fn add_joint(
        &mut self,
        body: BodyId,
        reference: impl Into<Reference>,
        constraint: impl Constraint<A> + 'static,
    ) -> Result<JointId, MechanismError> {
        self.keep_joint_space_rows(constraint.name())?;
        self.push_joint(body, reference.into(), constraint)
    }

    /// [`Mechanism::add_joint`] without the check that couplings and limits keep the articulated solve (a joint model
    /// keeps it).
    fn push_joint(
        &mut self,
        body: BodyId,
        reference: Reference,
        constraint: impl Constraint<A> + 'static,
    ) -> Result<JointId, MechanismError> {
        let index = self.check_body(body)?;
        let reference = self.reference_index(index, reference, constraint.name())?;
        let name = constraint.name().to_owned();
        let (rank, rows) = (constraint.rank(), constraint.row_count());
        if rank == 0 || rank > rows.min(6) {
            return Err(ConstraintError::InvalidRank { name, rank, rows }.into());
        }
        if rows > crate::constraints::MAX_ROWS {
            return Err(ConstraintError::TooManyRows {
                name,
                rows,
                capacity: crate::constraints::MAX_ROWS,
            }
            .into());
        }
        if matches!(self.stabilisation, Stabilisation::Projection { .. }) && !constraint.has_position_residual() {
            return Err(ConstraintError::NoPositionResidual { name }.into());
        }
        self.joints.push(Joint {
            uses_motor: constraint.uses_motor(),
            rank: constraint.rank(),
            constraint: Arc::new(constraint),
            body: index,
            reference,
            reaction_basis: None,
            model: None,
        });
        self.rebuild();
        Ok(JointId(self.joints.len() - 1))
    }

    /// Connects `child` to `parent` by a joint model (docs/mechanisms.md §M7): a joint with coordinates, whose rows
    /// are its virtual-power rows ([`JointModel::virtual_power`]). Mechanisms whose joints are all joint models in a
    /// tree are solved by the articulated recursion, in O(N) with one column per degree of freedom; their joint
    /// positions, velocities, mass matrix and inverse dynamics are in [`JointSpace`](crate::JointSpace).
    ///
    /// A double pendulum from its joint angles: the elbow hinge sits at the upper link's bottom end and the lower
    /// link's top end, both about y.
    ///
    /// ```
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use dynamics::{Body, Force, Mechanism, Pga, Reference};
    /// use nalgebra::{Isometry3, Vector3};
    ///
    /// let link = Body::cuboid(1.0, Vector3::new(0.05, 0.05, 1.0))?;
    /// let hinge = |name: &str, above: f64| {
    ///     let (parent, child) = (Isometry3::translation(0.0, 0.0, above), Isometry3::translation(0.0, 0.0, 0.5));
    ///     JointModel::new(name, JointKind::Revolute { axis: Vector3::y() }, parent, child)
    /// };
    /// let mut pendulum = Mechanism::<Pga>::new();
    /// let upper = pendulum.add_body("upper", link)?;
    /// let lower = pendulum.add_body("lower", link)?;
    /// pendulum.add_force(upper, Force::gravity())?;
    /// pendulum.add_force(lower, Force::gravity())?;
    /// pendulum.connect(upper, Reference::World, hinge("shoulder", 0.0)?)?;
    /// pendulum.connect(lower, upper, hinge("elbow", -0.5)?)?;
    /// let states = pendulum.states_from_joints(&[0.3, -0.2], &[1.0, 0.5])?;
    /// let q = pendulum.joint_positions(&states, None)?;
    /// assert!((q[0] - 0.3).abs() < 1e-15 && (q[1] + 0.2).abs() < 1e-15); // rad
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn connect(
        &mut self,
        child: BodyId,
        parent: impl Into<Reference>,
        model: JointModel,
    ) -> Result<JointId, MechanismError> {
        match model.virtual_power::<A>()? {
            Some(rows) => self.connect_with_rows(child, parent, model, rows),
            None => {
                let name = model.name().to_owned();
                self.connect_with_rows(child, parent, model, Arc::new(Unconstrained { name }))
            }
        }
    }

    /// [`Mechanism::connect`] with the joint's rows given (e.g. by pinning, `constraints::pinning`), for the general
    /// solve and the violation; they must describe the same joint as `model`.
    pub fn connect_with_rows(
        &mut self,
        child: BodyId,
        parent: impl Into<Reference>,
        model: JointModel,
        rows: Arc<dyn Constraint<A>>,
    ) -> Result<JointId, MechanismError> {
        let index = self.check_body(child)?;
        let parent = parent.into();
        self.reference_index(index, parent, model.name())?;
        if let Some(other) = self.joints.iter().find(|j| j.model.is_some() && j.body == index) {
            return Err(ConstraintError::InvalidParameter {
                name: model.name().to_owned(),
                reason: format!(
                    "body {} already has a parent joint model ({}); a second joint to it is a constraint (add_joint)",
                    self.bodies[index].name,
                    other.name()
                ),
            }
            .into());
        }
        let id = if matches!(model.kind(), JointKind::Free) {
            // A free joint constrains nothing: it joins the mechanism for its coordinates only (rank 0).
            let reference = self.reference_index(index, parent, model.name())?;
            self.joints.push(Joint {
                uses_motor: false,
                rank: 0,
                constraint: rows,
                body: index,
                reference,
                reaction_basis: None,
                model: None,
            });
            JointId(self.joints.len() - 1)
        } else {
            self.push_joint(child, parent, rows)?
        };
        self.joints[id.0].model = Some(model);
        self.rebuild();
        Ok(id)
    }

    /// Couples two one-coordinate joint models, `q_follower = multiplier · q_leader + offset` (a URDF `<mimic>`):
    /// a constraint between joint coordinates, which the articulated solve enforces at the acceleration level by a
    /// joint-space row (docs/mechanisms.md §M7) and the projection at the position and velocity levels. It needs the
    /// articulated solve (joint models in a tree, no Baumgarte stabilisation); a follower has one leader, and a
    /// leader follows no joint.
    ///
    /// A gripper's second finger mirroring the first:
    ///
    /// ```
    /// use dynamics::constraints::Stabilisation;
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use dynamics::{Body, Force, Mechanism, Pga, Reference};
    /// use nalgebra::{Isometry3, Vector3};
    ///
    /// let finger = Body::cuboid(0.05, Vector3::new(0.01, 0.01, 0.06))?;
    /// let mut gripper = Mechanism::<Pga>::new();
    /// let slide = |name: &str, x: f64, direction: f64| {
    ///     let frame = Isometry3::translation(x, 0.0, 0.0);
    ///     JointModel::new(name, JointKind::Prismatic { axis: Vector3::x() * direction }, frame, Isometry3::identity())
    /// };
    /// let left = gripper.add_body("left", finger)?;
    /// let right = gripper.add_body("right", finger)?;
    /// let leader = gripper.connect(left, Reference::World, slide("left", -0.02, -1.0)?)?;
    /// let follower = gripper.connect(right, Reference::World, slide("right", 0.02, 1.0)?)?;
    /// gripper.couple(follower, leader, 1.0, 0.0)?;
    /// gripper.set_stabilisation(Stabilisation::PROJECTION)?;
    /// gripper.add_force(left, Force::Line { force: Vector3::x() * -1.0, point: Vector3::zeros() })?; // opening, N
    /// let states = gripper.states_from_joints(&[0.0, 0.0], &[0.0, 0.0])?;
    /// let q_ddot = gripper.joint_accelerations(0.0, &states)?;
    /// assert!((q_ddot[0] - 10.0).abs() < 1e-12 && (q_ddot[1] - 10.0).abs() < 1e-12); // m/s²: 1 N on 0.1 kg
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn couple(
        &mut self,
        follower: JointId,
        leader: JointId,
        multiplier: f64,
        offset: f64,
    ) -> Result<(), MechanismError> {
        let name = |j: JointId| self.joints.get(j.0).map(|joint| joint.name().to_owned());
        let (Some(follower_name), Some(leader_name)) = (name(follower), name(leader)) else {
            let unknown = if follower.0 >= self.joints.len() {
                follower.0
            } else {
                leader.0
            };
            return Err(MechanismError::UnknownJoint(unknown));
        };
        let refuse = |reason: String| -> Result<(), MechanismError> {
            Err(ConstraintError::InvalidParameter {
                name: format!("{follower_name} (following {leader_name})"),
                reason,
            }
            .into())
        };
        for j in [follower, leader] {
            match &self.joints[j.0].model {
                Some(model) if model.kind().velocity_count() == 1 => {}
                _ => {
                    return refuse(format!(
                        "{} must be a joint model with one coordinate",
                        self.joints[j.0].name()
                    ))
                }
            }
        }
        if follower == leader {
            return refuse("a joint cannot follow itself".to_owned());
        }
        if self.joints[follower.0].model.as_ref().is_some_and(|m| m.is_driven()) {
            return refuse("a driven joint cannot follow another".to_owned());
        }
        if self.limits.iter().any(|limit| limit.joint == follower.0) {
            return refuse("a limited joint cannot follow another: limit its leader".to_owned());
        }
        if !(multiplier.is_finite() && offset.is_finite()) {
            return refuse(format!("multiplier {multiplier} and offset {offset} must be finite"));
        }
        if let Some(c) = self
            .couplings
            .iter()
            .find(|c| c.follower == follower.0 || c.follower == leader.0 || c.leader == follower.0)
        {
            return refuse(format!(
                "{} already follows {}; couplings do not chain and a joint follows one leader",
                self.joints[c.follower].name(),
                self.joints[c.leader].name()
            ));
        }
        if self.articulation.is_none() {
            return refuse(
                "couplings need the articulated solve: every joint a joint model, in a tree, no Baumgarte stabilisation"
                    .to_owned(),
            );
        }
        self.couplings.push(Coupling {
            follower: follower.0,
            leader: leader.0,
            multiplier,
            offset,
        });
        self.coupling_rows = self
            .couplings
            .iter()
            .map(|c| Row::Joints {
                follower: c.follower,
                leader: c.leader,
                multiplier: c.multiplier,
            })
            .collect();
        Ok(())
    }

    /// An error if `change` would leave couplings or limits without the articulated solve their joint-space rows
    /// need.
    pub(super) fn keep_joint_space_rows(&self, change: &str) -> Result<(), ConstraintError> {
        let (name, what) = match (self.couplings.first(), self.limits.first(), self.contacts.first()) {
            (Some(c), _, _) => (self.joints[c.follower].name(), "couples joint coordinates"),
            (None, Some(limit), _) => (self.joints[limit.joint].name(), "limits joint coordinates"),
            (None, None, Some(contact)) => (contact.name.as_str(), "has contacts"),
            (None, None, None) => return Ok(()),
        };
        Err(ConstraintError::InvalidParameter {
            name: name.to_owned(),
            reason: format!(
                "{change}: this mechanism {what}, which needs every joint a joint model in a tree and no Baumgarte \
                 stabilisation"
            ),
        })
    }

    fn reference_index(&self, index: usize, reference: Reference, name: &str) -> Result<Option<usize>, MechanismError> {
        if name.is_empty() {
            return Err(MechanismError::EmptyName("joint"));
        }
        match reference {
            Reference::World => Ok(None),
            Reference::Body(other) => {
                let other = self.check_body(other)?;
                if other == index {
                    return Err(MechanismError::SelfJoint {
                        joint: name.to_owned(),
                        body: self.bodies[index].name.clone(),
                    });
                }
                Ok(Some(other))
            }
        }
    }

    /// Restricts a joint's reaction to the span of `wrenches` (in its reference's frame; theory §7.1 method 2)
    /// instead of the span of its rows. Rows the basis cannot express are reported as inconsistent.
    pub fn set_reaction_basis(&mut self, joint: JointId, wrenches: Vec<A::Screw>) -> Result<(), MechanismError> {
        self.keep_joint_space_rows("reaction basis")?;
        let entry = self
            .joints
            .get_mut(joint.0)
            .ok_or(MechanismError::UnknownJoint(joint.0))?;
        let finite = wrenches.iter().all(|w| {
            let c = A::screw_coordinates(*w);
            c.l.iter().chain(c.t.iter()).all(|x| x.is_finite())
        });
        if wrenches.is_empty() || wrenches.len() > 6 || !finite {
            return Err(MechanismError::ReactionBasis {
                joint: entry.name().to_owned(),
                count: wrenches.len(),
            });
        }
        // The basis replaces the joint's rank in the solve.
        entry.reaction_basis = Some(wrenches);
        self.rebuild();
        Ok(())
    }

    /// Chooses the stabilisation; projection needs every joint to have a position residual.
    pub fn set_stabilisation(&mut self, stabilisation: Stabilisation) -> Result<(), MechanismError> {
        if let Some(reason) = stabilisation.invalid_reason() {
            return Err(ConstraintError::InvalidParameter {
                name: "stabilisation".to_owned(),
                reason,
            }
            .into());
        }
        if matches!(stabilisation, Stabilisation::Baumgarte { .. }) {
            self.keep_joint_space_rows("Baumgarte stabilisation")?;
        }
        if matches!(stabilisation, Stabilisation::Projection { .. }) {
            if let Some(joint) = self.joints.iter().find(|j| !j.constraint.has_position_residual()) {
                return Err(ConstraintError::NoPositionResidual {
                    name: joint.name().to_owned(),
                }
                .into());
            }
        }
        self.stabilisation = stabilisation;
        self.rebuild();
        Ok(())
    }

    /// Sets the solver's thresholds: `rank_tolerance` in (0, 1) and `consistency_tolerance` in (0, 1] (a relative
    /// residual above 1 is no solution: an infinite tolerance would pass any contradiction).
    ///
    /// ```
    /// use dynamics::{Mechanism, Pga, SolverSettings};
    ///
    /// let mut system = Mechanism::<Pga>::new();
    /// system.set_settings(SolverSettings { rank_tolerance: 1e-8, ..SolverSettings::default() })?;
    /// let loose = SolverSettings { consistency_tolerance: f64::INFINITY, ..SolverSettings::default() };
    /// assert!(system.set_settings(loose).is_err());
    /// # Ok::<(), dynamics::MechanismError>(())
    /// ```
    pub fn set_settings(&mut self, settings: SolverSettings) -> Result<(), MechanismError> {
        let SolverSettings {
            rank_tolerance,
            consistency_tolerance,
        } = settings;
        let refuse = |reason: String| -> Result<(), MechanismError> {
            Err(ConstraintError::InvalidParameter {
                name: "solver settings".to_owned(),
                reason,
            }
            .into())
        };
        if !(rank_tolerance > 0.0 && rank_tolerance < 1.0) {
            return refuse(format!("rank_tolerance must be in (0, 1), got {rank_tolerance:?}"));
        }
        if !(consistency_tolerance > 0.0 && consistency_tolerance <= 1.0) {
            return refuse(format!(
                "consistency_tolerance must be in (0, 1], got {consistency_tolerance:?}"
            ));
        }
        self.settings = settings;
        Ok(())
    }

    /// [`Mechanism::add_force`] on body 0, builder style (for [`Mechanism::single`]); a mechanism without bodies
    /// refuses it ([`MechanismError::UnknownBody`]) rather than dropping the force.
    pub fn with_force(mut self, force: Force<A>) -> Result<Self, MechanismError> {
        self.add_force(BodyId(0), force)?;
        Ok(self)
    }

    /// [`Mechanism::add_joint`] of body 0 to the world, builder style (for [`Mechanism::single`]).
    pub fn with_constraint(mut self, constraint: impl Constraint<A> + 'static) -> Result<Self, MechanismError> {
        self.add_joint(BodyId(0), Reference::World, constraint)?;
        Ok(self)
    }

    /// [`Mechanism::set_stabilisation`], builder style.
    pub fn with_stabilisation(mut self, stabilisation: Stabilisation) -> Result<Self, MechanismError> {
        self.set_stabilisation(stabilisation)?;
        Ok(self)
    }

    /// [`Mechanism::set_reaction_basis`] of the last joint added, builder style.
    pub fn with_reaction_basis(mut self, wrenches: Vec<A::Screw>) -> Result<Self, MechanismError> {
        let last = self
            .joints
            .len()
            .checked_sub(1)
            .ok_or(MechanismError::UnknownJoint(0))?;
        self.set_reaction_basis(JointId(last), wrenches)?;
        Ok(self)
    }

    fn rebuild(&mut self) {
        let joints: Vec<(usize, Option<usize>, usize)> = self
            .joints
            .iter()
            .map(|j| (j.body, j.reference, Self::joint_rank(j)))
            .collect();
        self.topology = Topology::new(self.bodies.len(), &joints);
        let tree: Vec<(usize, Option<usize>, bool)> = self
            .joints
            .iter()
            .map(|j| (j.body, j.reference, j.model.is_some() && j.reaction_basis.is_none()))
            .collect();
        let articulated = !matches!(self.stabilisation, Stabilisation::Baumgarte { .. });
        self.articulation = Articulation::new(self.bodies.len(), &tree).filter(|_| articulated);
        self.joint_space = std::sync::OnceLock::new();
        self.limits = (self.joints.iter().enumerate())
            .filter_map(|(joint, j)| {
                let range = *j.model.as_ref()?.limit()?;
                Some(Limit { joint, range })
            })
            .collect();
    }
}
