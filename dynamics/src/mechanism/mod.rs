//! Mechanisms: N rigid bodies under forces, held to each other and to the world by joints, in maximal
//! coordinates (each body its motor and momentum). The derivation is in `docs/mechanisms.md`; in short:
//!
//! * a **joint** is any [`Constraint`] of [`crate::constraints`] — pinned multivectors, linear functions of
//!   them, parametric paths, virtual power — between a body and its **reference**: the world, or another body,
//!   whose frame then plays the world's part (`joint`, §M2). Its rows are reduced to its rank (`reduce`,
//!   §M3);
//! * the reactions solve `J G Jᵀ λ = rhs` in the kinetic metric, `G` the bodies' inverse inertias, by a sparse
//!   LDLᵀ over a spanning tree of the joints (linear in N for chains and trees) with loop-closing joints
//!   through a rank-revealing Schur complement (`solve`, `topology`, §M4);
//! * stabilisation by Baumgarte feedback or by projection of the whole system onto the joint manifold after
//!   each step (§M5).
//!
//! A single body held by the world is the case N = 1 ([`Mechanism::single`]): there is no other code path
//! for constrained bodies.

mod articulated;
mod contacts;
mod elements;
mod joint;
mod joint_space;
mod reduce;
mod solve;
mod spatial;
mod topology;
mod unilateral;

use std::collections::HashSet;
use std::fmt;
use std::sync::Arc;

use nalgebra::{Isometry3, Vector3};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::body::{Body, PrincipalFrame};
use crate::constraints::{Constraint, ConstraintError, Kinematics, RowBuffer, Stabilisation};
use crate::exponential::exp;
use crate::force_elements::ForceElement;
use crate::forces::Force;
use crate::joints::{JointKind, JointModel, Unconstrained};
use crate::limits::{Bound, JointLimit, LimitChange};
use crate::motion::{BodyRates, Dynamics, Rates};
use crate::motor;
use crate::state::State;

use articulated::{ArticulatedScratch, Articulation, Row};
use joint::{velocity_screw, wrench_coordinates, wrench_screw, BodyKinematics, Joint, JointContext, JointRows};
pub use joint_space::{CoordinateGroup, JointSpace};
pub(crate) use solve::symmetric_eigen;
use solve::{dot6, Consistency, SolveFailure, SystemMatrix};
pub use solve::{SolverSettings, ROUND_OFF};
use topology::{Side, Slot, Topology};

/// A body of a mechanism, by its index in the order the bodies were added.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BodyId(usize);

impl BodyId {
    /// The body's index: its position in states and samples.
    pub fn index(self) -> usize {
        self.0
    }
}

/// A joint of a mechanism, by its index in the order the joints were added.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct JointId(usize);

impl JointId {
    /// The joint's index: its position in the order the joints were added.
    pub fn index(self) -> usize {
        self.0
    }
}

/// What a joint holds its body to: the frame in which the constraint's "world" objects are fixed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Reference {
    /// The world frame.
    World,
    /// The body frame of another body of the mechanism.
    Body(BodyId),
}

impl From<BodyId> for Reference {
    fn from(body: BodyId) -> Self {
        Reference::Body(body)
    }
}

/// Why a mechanism cannot be built as asked.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MechanismError {
    /// A body was added with the name of one already there (the name is held).
    #[error("two bodies are named {0:?}; names identify bodies in errors and output")]
    DuplicateBody(String),
    /// A contact was added with the name of a joint or contact already there (the name is held).
    #[error("a joint or contact is already named {0:?}; names identify contacts in transitions and errors")]
    DuplicateContact(String),
    /// A body, joint or force element was added with an empty name (what it was is held).
    #[error("a {0} needs a non-empty name")]
    EmptyName(&'static str),
    /// A [`BodyId`] (its index held) that is not a body of this mechanism.
    #[error("body index {0} is not a body of this mechanism")]
    UnknownBody(usize),
    /// A [`JointId`] (its index held) that is not a joint of this mechanism; also index 0 for
    /// [`Mechanism::with_reaction_basis`] before any joint was added.
    #[error("joint index {0} is not a joint of this mechanism")]
    UnknownJoint(usize),
    /// A joint would hold a body to the body itself.
    #[error("joint {joint}: holds body {body} to itself")]
    SelfJoint {
        /// The name of the joint's constraint.
        joint: String,
        /// The name of the body.
        body: String,
    },
    /// A reaction basis that is empty, has more than 6 wrenches or a non-finite one
    /// ([`Mechanism::set_reaction_basis`]).
    #[error("joint {joint}: a reaction basis needs 1 to 6 finite wrenches, got {count}")]
    ReactionBasis {
        /// The name of the joint.
        joint: String,
        /// The number of wrenches given.
        count: usize,
    },
    /// A joint or stabilisation was refused by the constraint checks (rank, rows, position residual, parameters).
    #[error(transparent)]
    Constraint(#[from] ConstraintError),
    /// Joint coordinates were asked of a mechanism whose joint models do not form a forest (a body reached twice
    /// through parents), or of one without bodies.
    #[error("this mechanism has no joint coordinates: {0}")]
    NoJointSpace(String),
    /// A state or coordinate that is not finite (or beyond 1e50): which, and its index.
    #[error("{what} {index} is not finite or has a coordinate beyond 1e50")]
    NotFinite {
        /// "state" (of the body with that index), "joint acceleration", ….
        what: &'static str,
        /// Its index.
        index: usize,
    },
    /// A slice with the wrong number of entries: states (one per body) or joint coordinates.
    #[error("{what}: expected {expected} entries, got {got}")]
    Count {
        /// What was counted: "states", "joint positions", "joint velocities", "joint accelerations".
        what: &'static str,
        /// The number the mechanism has.
        expected: usize,
        /// The number given.
        got: usize,
    },
}

/// The largest residuals over the joints at one state: `max |e|` (rows with a position residual) and `max |ė|`.
/// Units are those of each constraint's residual (metres for a force-line row, multivector coefficients for
/// pins).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Violation {
    /// `max |e|` over the joints' rows that have a position residual.
    pub position: f64,
    /// `max |ė|` over all the joints' rows.
    pub velocity: f64,
}

#[derive(Clone, Debug)]
struct MechanismBody<A: Algebra> {
    name: String,
    body: Body,
    forces: Vec<Force<A>>,
    /// The body's reference frame (the frame its inertia was described in) in its body frame: a free root's
    /// joint coordinates are this frame's pose and twist.
    frame: Isometry3<f64>,
}

/// N rigid bodies, their forces and the joints between them (see the module docs).
///
/// A double pendulum: two rods, the first hinged to the world at its top end about world x, the second hinged
/// to the first's bottom end about the first's body y, released from 1 rad; the hinges hold to round-off.
///
/// ```
/// use std::sync::Arc;
/// use dynamics::constraints::{Stabilisation, VirtualPower};
/// use dynamics::{simulate, Body, Force, Mechanism, Method, Pga, Reference, Schedule, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let rod = Body::cuboid(1.0, Vector3::new(0.1, 0.1, 1.0))?; // 1 kg, 1 m along body z
/// let (top, bottom) = (Vector3::new(0.0, 0.0, 0.5), Vector3::new(0.0, 0.0, -0.5));
/// let mut pendulum = Mechanism::<Pga>::new();
/// let upper = pendulum.add_body("upper", rod)?;
/// let lower = pendulum.add_body("lower", rod)?;
/// for body in [upper, lower] {
///     pendulum.add_force(body, Force::gravity())?;
/// }
/// // A hinge: (body point, body axis) of the held body, (point, axis) in the reference's frame.
/// let hinge_1 = VirtualPower::hinge("hinge 1", (top, Vector3::x()), (Vector3::zeros(), Vector3::x()))?;
/// let hinge_2 = VirtualPower::hinge("hinge 2", (top, Vector3::y()), (bottom, Vector3::y()))?;
/// pendulum.add_joint(upper, Reference::World, Arc::new(hinge_1))?;
/// pendulum.add_joint(lower, upper, Arc::new(hinge_2))?;
/// pendulum.set_stabilisation(Stabilisation::PROJECTION)?;
///
/// // Both rods along the line from the pivot at 1 rad about x, at rest (the projection would correct a
/// // state that breaks the joints slightly).
/// let tilt = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 1.0);
/// let at = |k: f64| State::new(&rod, tilt * Vector3::new(0.0, 0.0, -k), &tilt, Vector3::zeros(), Vector3::zeros());
/// let run = simulate(&pendulum, &[at(0.5), at(1.5)], Method::Rkmk6Body, &Schedule::new(2e-3, 2.0)?)?;
///
/// let end = run.body(1).last().unwrap();
/// let lower_top = end.position + end.orientation * top;
/// let upper_end = run.body(0).last().unwrap();
/// assert!((lower_top - (upper_end.position + upper_end.orientation * bottom)).norm() < 1e-12);
/// assert!((end.energy - run.body(1)[0].energy).abs() < 1e-9); // energy of the whole system, J
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone)]
pub struct Mechanism<A: Algebra> {
    bodies: Vec<MechanismBody<A>>,
    joints: Vec<Joint<A>>,
    stabilisation: Stabilisation,
    settings: SolverSettings,
    topology: Topology,
    /// The joint-model tree, when the articulated solve applies (docs/mechanisms.md §M7).
    articulation: Option<Articulation>,
    /// The coordinates of the joint models and free roots, if the joint models form a forest.
    /// Built on first use after a change (a robot adds its bodies and joints one by one).
    joint_space: std::sync::OnceLock<Option<JointSpace>>,
    /// Linear relations between joint coordinates (URDF mimics).
    couplings: Vec<Coupling>,
    /// The couplings' acceleration rows for the articulated solve.
    coupling_rows: Vec<Row>,
    /// Forces between bodies (docs/mechanisms.md §M8).
    elements: Vec<ForceElement<A>>,
    /// The joint models' limits, in the order of their joints.
    limits: Vec<Limit>,
    /// Body points kept above world planes (docs/contacts.md).
    contacts: Vec<contacts::Contact>,
}

/// A limited joint model: its joint index and range.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Limit {
    joint: usize,
    range: JointLimit,
}

/// `q_follower = multiplier · q_leader + offset` between two one-coordinate joint models (joint indices).
#[derive(Clone, Debug, PartialEq)]
struct Coupling {
    follower: usize,
    leader: usize,
    multiplier: f64,
    offset: f64,
}

impl<A: Algebra> fmt::Debug for Mechanism<A> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Mechanism")
            .field("bodies", &self.bodies)
            .field("joints", &self.joints)
            .field("stabilisation", &self.stabilisation)
            .finish()
    }
}

impl<A: Algebra> Default for Mechanism<A> {
    fn default() -> Self {
        Self::new()
    }
}

/// The projection leaves a system alone whose joints are within these: position residuals below
/// `POSITION_TOLERANCE` (m, or unit-size coefficients of pinned objects) and velocity residuals below
/// `VELOCITY_TOLERANCE`, each raised to [`ROUND_OFF_ULPS`] ulp of the largest coordinate (body position, body
/// velocity). A Gauss–Newton step cannot improve on the round-off of the coordinates: 40 m out on a 64-link
/// chain an ulp is 7e-15, and a fixed 1e-14 made two Gauss–Newton steps and two factorisations in most steps.
const POSITION_TOLERANCE: f64 = 1e-14;
/// Drift up to which one Gauss–Newton step brings the joints to round-off (it squares the residual, in units of
/// the joints' size): the projection after a step takes the one-factorisation path below it.
const ONE_STEP_DRIFT: f64 = 1e-8;
const VELOCITY_TOLERANCE: f64 = 1e-12;
const ROUND_OFF_ULPS: f64 = 16.0;

/// A position residual still above this after a projection's Gauss–Newton steps means the joints cannot hold
/// together (a step leaves about 1e-10 before projection and round-off after it; two contradictory joints
/// leave their whole disagreement): an error, never a run with a broken joint.
const UNREACHABLE_RESIDUAL: f64 = 1e-6;

/// How far [`Mechanism::project`] moved each body of a start onto its joints, by body index.
#[derive(Clone, Debug, PartialEq)]
pub struct Correction {
    /// How far each body's centre of mass moved (m).
    pub moved: Vec<f64>,
    /// How far each body turned (rad).
    pub turned: Vec<f64>,
}

impl Correction {
    /// The body that moved or turned the most, and by how much (m or rad, whichever is larger); `None` without
    /// bodies.
    pub fn largest(&self) -> Option<(usize, f64)> {
        (self.moved.iter().zip(&self.turned))
            .map(|(moved, turned)| moved.max(*turned))
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// Gauss–Newton steps at most when projecting initial conditions, which may start far from the joints.
const INITIAL_PROJECTION_STEPS: usize = 50;

/// The scratch of a mechanism's evaluations ([`Dynamics::Workspace`]): made once per run, so an evaluation
/// does not allocate.
pub struct MechanismWorkspace<A: Algebra> {
    bodies: Vec<BodyKinematics<A>>,
    /// External wrench per body, body coordinates.
    external: Vec<ScrewCoordinates>,
    /// Reaction per body, wrench coordinates `(τ; f)`, body frame.
    reactions: Vec<[f64; 6]>,
    joints: Vec<JointRows>,
    raw: RowBuffer,
    matrix: SystemMatrix,
    tree: Vec<f64>,
    loops: Vec<f64>,
    inverse_metric: Vec<[f64; 6]>,
    motors: Vec<A::Motor>,
    momenta: Vec<A::Screw>,
    /// Whether `matrix` holds the factors of the last dynamics evaluation with every joint's rows its own (not a
    /// basis the reduction chose): the projection after a step may use them as a chord (docs/mechanisms.md M5).
    stage_factors: bool,
    articulated: ArticulatedScratch,
    /// The joint positions of the last projection by coordinates, so that angles read the next time unwrap from them.
    previous_positions: Vec<f64>,
    /// The non-conservative power at the last evaluation (W): the force elements', the bodies' forces other than
    /// gravity, the drives'.
    power: f64,
    /// The force elements' wrench on each body at the last evaluation (body frame; also in `external`).
    element_wrenches: Vec<ScrewCoordinates>,
    /// The bodies placed by forward kinematics (stepping in joint coordinates).
    placed: Vec<joint_space::WorldBody>,
    /// Per one-sided constraint (limits, then contacts), the bound it is held at, if it is (docs/limits.md; a
    /// contact's plane is its lower bound).
    held: Vec<Option<Bound>>,
    /// The articulated solve's rows: the couplings', then one per held limit and per held contact.
    rows: Vec<Row>,
}

impl<A: Algebra> fmt::Debug for MechanismWorkspace<A> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("MechanismWorkspace")
            .field("bodies", &self.bodies.len())
            .field("joints", &self.joints.len())
            .finish_non_exhaustive()
    }
}

/// Which right-hand side of the reduced rows a solve uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Condition {
    Acceleration = 0,
    Position = 1,
    Velocity = 2,
}

/// What an evaluation computes of each body besides its kinematics.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum BodyTerms {
    /// Nothing: positions and velocities only (projection, violation).
    Kinematics,
    /// The external wrenches (the articulated solve).
    Forces,
    /// The external wrenches and the free accelerations `H⁻¹(Ḃ × Ω_b + S_b)` (the constraint-space solve).
    FreeAccelerations,
}

/// What the joints' rows are evaluated for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Rows {
    /// The equations of motion: the acceleration condition, stabilised, reduced.
    Dynamics,
    /// The projection onto the joint manifold: position and velocity conditions, reduced.
    Projection,
    /// A violation query: the residuals alone, not reduced (they exist where the rows lose rank).
    Residuals,
}

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
    /// root's joint coordinates are its pose and twist ([`JointSpace`]).
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

    fn check_body(&self, body: BodyId) -> Result<usize, MechanismError> {
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
    /// positions, velocities, mass matrix and inverse dynamics are in [`JointSpace`].
    ///
    /// A double pendulum from its joint angles: the elbow hinge sits at the upper link's bottom end and the lower
    /// link's top end, both about y.
    ///
    /// ```
    /// use dynamics::joints::{JointKind, JointModel};
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
    /// use dynamics::joints::{JointKind, JointModel};
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
    fn keep_joint_space_rows(&self, change: &str) -> Result<(), ConstraintError> {
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

    fn joint_rank(joint: &Joint<A>) -> usize {
        joint
            .reaction_basis
            .as_ref()
            .map_or(joint.constraint.rank(), |basis| basis.len())
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

    /// The stabilisation in use.
    pub fn stabilisation(&self) -> Stabilisation {
        self.stabilisation
    }

    /// The bodies' names, in index order.
    pub fn body_names(&self) -> impl Iterator<Item = &str> {
        self.bodies.iter().map(|b| b.name.as_str())
    }

    /// The body with this name.
    pub fn body_id(&self, name: &str) -> Option<BodyId> {
        self.bodies.iter().position(|b| b.name == name).map(BodyId)
    }

    /// The forces on a body.
    pub fn forces(&self, body: BodyId) -> &[Force<A>] {
        self.bodies.get(body.0).map_or(&[], |b| &b.forces)
    }

    /// The joints' names, in index order.
    pub fn joint_names(&self) -> impl Iterator<Item = &str> {
        self.joints.iter().map(|j| j.name())
    }

    /// The constraint of a joint, the body it holds and its reference.
    pub fn joint(&self, joint: JointId) -> Option<(&dyn Constraint<A>, BodyId, Reference)> {
        self.joints.get(joint.0).map(|j| {
            let reference = j.reference.map_or(Reference::World, |r| Reference::Body(BodyId(r)));
            (&*j.constraint, BodyId(j.body), reference)
        })
    }

    /// The number of joints.
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }

    /// The joints that close loops (the others form a spanning forest of the bodies and the world).
    pub fn loop_joints(&self) -> impl Iterator<Item = JointId> + '_ {
        self.topology
            .slots
            .iter()
            .enumerate()
            .filter(|&(j, slot)| matches!(slot, Slot::Loop { .. }) && self.joints[j].rank > 0)
            .map(|(j, _)| JointId(j))
    }

    /// The names of joints, joined for an error message.
    fn names(&self, joints: impl IntoIterator<Item = usize>) -> String {
        let mut seen = HashSet::new();
        joints
            .into_iter()
            .filter(|j| seen.insert(*j))
            .map(|j| self.joints[j].name())
            .collect::<Vec<_>>()
            .join(" + ")
    }

    fn failure(&self, failure: SolveFailure) -> ConstraintError {
        match failure {
            SolveFailure::TreeRank {
                joint,
                singular_value,
                largest,
            } => ConstraintError::RankDeficient {
                names: self.names([joint]),
                rank: Self::joint_rank(&self.joints[joint]),
                singular_value,
                largest,
            },
            SolveFailure::Inconsistent {
                joint,
                relative_residual,
            } => ConstraintError::Inconsistent {
                names: self.names(std::iter::once(joint).chain(self.topology.cycles[joint].iter().copied())),
                relative_residual,
            },
        }
    }

    /// The world wrench of the external forces on body `index` (for world-momentum rates), at its kinematics:
    /// gravity acts along the line through the centre of mass the frame already holds (the image of the origin,
    /// the same point [`Force::wrench`] finds by moving the origin with the motor).
    fn external_wrench(&self, index: usize, t: f64, state: &State<A>, kinematics: &Kinematics<A>) -> A::Screw {
        let body = &self.bodies[index];
        body.forces.iter().fold(A::screw(Default::default()), |total, force| {
            total
                + match force {
                    Force::Gravity { acceleration } => {
                        crate::forces::force_line::<A>(body.body.mass() * acceleration, kinematics.frame.position)
                    }
                    _ => force.wrench(&body.body, t, state),
                }
        })
    }

    /// The external wrench on body `index` in its own frame (gravity rotated into it directly), and the power of
    /// its forces other than gravity (gravity's is the rate of its potential, in the energy).
    fn external_body_wrench(
        &self,
        index: usize,
        kinematics: &Kinematics<A>,
        body_momentum: A::Screw,
    ) -> (ScrewCoordinates, f64) {
        let body = &self.bodies[index];
        body.forces.iter().fold(
            (ScrewCoordinates::default(), 0.0),
            |(total, power), force| match force {
                Force::Gravity { acceleration } => {
                    let weight = ScrewCoordinates {
                        l: kinematics
                            .frame
                            .rotation
                            .inverse_transform_vector(&(body.body.mass() * acceleration)),
                        t: Vector3::zeros(),
                    };
                    (total + weight, power)
                }
                _ => {
                    let world = force.wrench_at(&body.body, kinematics.t, kinematics.motor, || {
                        kinematics.to_world(body_momentum)
                    });
                    let wrench = kinematics.to_body_coordinates(&A::screw_coordinates(world));
                    (
                        total + wrench,
                        power + wrench_power(&wrench_coordinates(&wrench), &kinematics.velocity),
                    )
                }
            },
        )
    }

    /// The power of the joints' reactions in `workspace` (`Σ yᵢ·xᵢ`, body frames): a drive's work, and for the
    /// joints that prescribe nothing zero up to the constraint drift (docs/mechanisms.md §M8).
    pub(crate) fn reaction_power(&self, workspace: &MechanismWorkspace<A>) -> f64 {
        workspace
            .reactions
            .iter()
            .zip(&workspace.bodies)
            .map(|(reaction, body)| wrench_power(reaction, &body.kinematics.velocity))
            .sum()
    }

    /// A workspace for this mechanism.
    pub fn new_workspace(&self) -> MechanismWorkspace<A> {
        let zero_motor = motor::identity::<A>();
        let zero_screw = A::screw(ScrewCoordinates::default());
        let kinematics = Kinematics::new(0.0, zero_motor, zero_screw);
        MechanismWorkspace {
            bodies: vec![
                BodyKinematics {
                    kinematics,
                    free_acceleration: [0.0; 6],
                };
                self.bodies.len()
            ],
            external: vec![ScrewCoordinates::default(); self.bodies.len()],
            reactions: vec![[0.0; 6]; self.bodies.len()],
            joints: vec![JointRows::default(); self.joints.len()],
            raw: RowBuffer::new(),
            matrix: SystemMatrix::new(&self.topology),
            tree: vec![0.0; self.topology.tree_size],
            loops: vec![0.0; self.topology.loop_size],
            inverse_metric: self
                .bodies
                .iter()
                .map(|b| {
                    let (i, m) = (b.body.moments(), b.body.mass());
                    [1.0 / i.x, 1.0 / i.y, 1.0 / i.z, 1.0 / m, 1.0 / m, 1.0 / m]
                })
                .collect(),
            motors: vec![zero_motor; self.bodies.len()],
            momenta: vec![zero_screw; self.bodies.len()],
            stage_factors: false,
            articulated: ArticulatedScratch::new(
                self.bodies.len(),
                self.joints.len(),
                self.couplings.len() + self.limit_count(),
            ),
            previous_positions: Vec::new(),
            power: 0.0,
            element_wrenches: vec![ScrewCoordinates::default(); self.bodies.len()],
            placed: Vec::new(),
            held: vec![None; self.limit_count()],
            rows: self.coupling_rows.clone(),
        }
    }

    /// Every body's kinematics from its motor and body momentum; with `dynamics`, also its external wrench and
    /// free acceleration `H⁻¹(Ḃ × Ω_b + S_b)` (theory §5).
    fn body_kinematics(
        &self,
        t: f64,
        motors: &[A::Motor],
        body_momenta: &[A::Screw],
        workspace: &mut MechanismWorkspace<A>,
        terms: BodyTerms,
    ) -> Result<(), ConstraintError> {
        for (i, entry) in self.bodies.iter().enumerate() {
            let velocity = entry.body.velocity::<A>(body_momenta[i]);
            // Written in place (the kinematics are a few hundred bytes, built for every body at every evaluation).
            workspace.bodies[i].kinematics = Kinematics::new(t, motors[i], velocity);
        }
        self.body_forces(t, body_momenta, workspace, terms)
    }

    /// Every body's external wrench (its forces and the force elements'; `workspace.power` the elements' power) and,
    /// for the constraint-space solve, its free acceleration, at the kinematics in `workspace`.
    fn body_forces(
        &self,
        t: f64,
        body_momenta: &[A::Screw],
        workspace: &mut MechanismWorkspace<A>,
        terms: BodyTerms,
    ) -> Result<(), ConstraintError> {
        workspace.power = 0.0;
        for body in workspace.bodies.iter_mut() {
            body.free_acceleration = [0.0; 6];
        }
        if terms == BodyTerms::Kinematics {
            return Ok(());
        }
        for (i, body) in workspace.bodies.iter().enumerate() {
            let (wrench, power) = self.external_body_wrench(i, &body.kinematics, body_momenta[i]);
            workspace.external[i] = wrench;
            workspace.power += power;
        }
        if !self.elements.is_empty() {
            let MechanismWorkspace {
                bodies,
                external,
                element_wrenches,
                ..
            } = workspace;
            element_wrenches
                .iter_mut()
                .for_each(|w| *w = ScrewCoordinates::default());
            let kinematics = |i: usize| &bodies[i].kinematics;
            workspace.power += self.apply_elements(t, &kinematics, element_wrenches, true)?;
            for (total, element) in external.iter_mut().zip(element_wrenches.iter()) {
                *total = *total + *element;
            }
        }
        if terms == BodyTerms::FreeAccelerations {
            for (i, body) in workspace.bodies.iter_mut().enumerate() {
                let drive = A::screw_coordinates(A::commutator(body.kinematics.body_velocity, body_momenta[i]))
                    + workspace.external[i];
                let g = wrench_coordinates(&drive);
                body.free_acceleration = std::array::from_fn(|k| g[k] * workspace.inverse_metric[i][k]);
            }
        }
        Ok(())
    }

    /// Every joint's reduced rows at the bodies' kinematics.
    /// Every joint's rows for `purpose` at the bodies' kinematics in `workspace`.
    fn joint_rows(&self, t: f64, workspace: &mut MechanismWorkspace<A>, purpose: Rows) -> Result<(), ConstraintError> {
        let context = JointContext {
            t,
            stabilisation: if purpose == Rows::Dynamics {
                self.stabilisation
            } else {
                Stabilisation::None
            },
            settings: &self.settings,
            inverse_metric: &workspace.inverse_metric,
            loops: self.topology.loop_size > 0,
            purpose,
        };
        for (joint, rows) in self.joints.iter().zip(workspace.joints.iter_mut()) {
            joint.evaluate(&context, &workspace.bodies, &mut workspace.raw, rows)?;
        }
        Ok(())
    }

    /// Assembles and factors `K`, solves it for `condition`'s right-hand sides and accumulates the reactions
    /// `Jᵀλ` per body (wrench coordinates, body frames) into `workspace.reactions`.
    fn solve_reactions(
        &self,
        workspace: &mut MechanismWorkspace<A>,
        condition: Condition,
        consistency: Consistency,
    ) -> Result<(), ConstraintError> {
        self.factor_system(workspace)?;
        self.solve_factored(workspace, condition, consistency)
    }

    /// Assembles and factors `K` at the joints' current rows.
    fn factor_system(&self, workspace: &mut MechanismWorkspace<A>) -> Result<(), ConstraintError> {
        workspace.stage_factors = false;
        let MechanismWorkspace {
            joints,
            matrix,
            inverse_metric,
            ..
        } = workspace;
        let rows = |joint: usize, side: Side| -> &[[f64; 6]] {
            let rows = &joints[joint];
            match side {
                Side::Body => &rows.reduced.rows[..rows.reduced.rank],
                Side::Reference => &rows.reference_rows[..rows.reduced.rank],
            }
        };
        matrix.assemble(&self.topology, inverse_metric, rows);
        matrix
            .factor(&self.topology, &self.settings)
            .map_err(|f| self.failure(f))
    }

    /// Solves the factored `K` for `condition`'s right-hand sides and accumulates the reactions `Jᵀλ` per body
    /// into `workspace.reactions`.
    fn solve_factored(
        &self,
        workspace: &mut MechanismWorkspace<A>,
        condition: Condition,
        consistency: Consistency,
    ) -> Result<(), ConstraintError> {
        let MechanismWorkspace {
            joints,
            matrix,
            tree,
            loops,
            reactions,
            ..
        } = workspace;
        for (j, rows) in joints.iter().enumerate() {
            let values = &rows.reduced.values[condition as usize][..rows.reduced.rank];
            let target = match self.topology.slots[j] {
                Slot::Tree { offset, .. } => &mut tree[offset..offset + values.len()],
                Slot::Loop { offset } => &mut loops[offset..offset + values.len()],
            };
            target.copy_from_slice(values);
        }
        matrix
            .solve(&self.topology, tree, loops, consistency, &self.settings)
            .map_err(|f| self.failure(f))?;
        reactions.iter_mut().for_each(|y| *y = [0.0; 6]);
        for (j, (joint, rows)) in self.joints.iter().zip(joints.iter()).enumerate() {
            let (on_body, on_reference) = rows.reactions(self.multipliers(j, rows.reduced.rank, tree, loops));
            add(&mut reactions[joint.body], &on_body);
            if let Some(r) = joint.reference {
                add(&mut reactions[r], &on_reference);
            }
        }
        Ok(())
    }

    /// The equations of motion at the given motors and body momenta: every body's kinematics and reaction
    /// (docs/mechanisms.md §M4: `K λ = z`, reactions `Jᵀλ`).
    fn evaluate(
        &self,
        t: f64,
        motors: &[A::Motor],
        body_momenta: &[A::Screw],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        let terms = if self.articulation.is_some() {
            BodyTerms::Forces
        } else {
            BodyTerms::FreeAccelerations
        };
        self.body_kinematics(t, motors, body_momenta, workspace, terms)?;
        if self.joints.is_empty() && workspace.rows.is_empty() {
            workspace.reactions.iter_mut().for_each(|y| *y = [0.0; 6]);
            return Ok(());
        }
        if self.articulation.is_none() {
            self.keep_joint_space_rows("the general solve")?;
        }
        if let Some(articulation) = &self.articulation {
            self.solve_articulated(articulation, t, workspace, true)
                .map_err(|body| ConstraintError::NonFinite {
                    name: self.names(self.topology.incidences[body].iter().map(|incidence| incidence.joint)),
                    t,
                })?;
            self.check_reactions(t, workspace)?;
            workspace.power += self.reaction_power(workspace);
            return Ok(());
        }
        self.joint_rows(t, workspace, Rows::Dynamics)?;
        // The round-off floor of the loop consistency check: the size of the terms in the joints' conditions.
        let scale = workspace
            .joints
            .iter()
            .map(|rows| rows.acceleration_scale.powi(2))
            .sum::<f64>()
            .sqrt();
        self.solve_reactions(workspace, Condition::Acceleration, Consistency::Check { scale })?;
        workspace.stage_factors = workspace.joints.iter().all(|rows| rows.reduced.direct);
        self.check_reactions(t, workspace)?;
        workspace.power += self.reaction_power(workspace);
        Ok(())
    }

    /// [`Mechanism::evaluate`] at the bodies' states.
    fn evaluate_states(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        let (mut motors, mut momenta) = (
            std::mem::take(&mut workspace.motors),
            std::mem::take(&mut workspace.momenta),
        );
        for (i, state) in states.iter().enumerate() {
            motors[i] = state.motor;
            // The sandwich `~RΩR`, as the paper's RK4 has it: its stage motors are not unit, and the sandwich
            // scales by ⟨R~R⟩₀ (the frame map would divide it out and change the method).
            momenta[i] = state.body_momentum();
        }
        let result = self.evaluate(t, &motors, &momenta, workspace);
        workspace.motors = motors;
        workspace.momenta = momenta;
        result
    }

    /// The articulated solve (docs/mechanisms.md §M7) on the workspace's body kinematics and external wrenches,
    /// with the joints' reactions when `reactions` is set; fails with the body whose articulated inertia is not
    /// positive definite.
    fn solve_articulated(
        &self,
        articulation: &Articulation,
        t: f64,
        workspace: &mut MechanismWorkspace<A>,
        reactions: bool,
    ) -> Result<(), usize> {
        let MechanismWorkspace {
            bodies,
            external,
            reactions: reaction_wrenches,
            articulated,
            rows,
            ..
        } = workspace;
        articulation.solve(
            t,
            &self.joints,
            &self.bodies,
            bodies,
            external,
            rows,
            articulated,
            reactions.then_some(reaction_wrenches.as_mut_slice()),
        )
    }

    /// An error naming the joints at the first body whose reaction is not finite.
    fn check_reactions(&self, t: f64, workspace: &MechanismWorkspace<A>) -> Result<(), ConstraintError> {
        for (i, reaction) in workspace.reactions.iter().enumerate() {
            if !reaction.iter().all(|y| y.is_finite()) {
                let names = self.names(self.topology.incidences[i].iter().map(|incidence| incidence.joint));
                return Err(ConstraintError::NonFinite { name: names, t });
            }
        }
        Ok(())
    }

    /// Joint j's multipliers in the solved tree and loop vectors.
    fn multipliers<'v>(&self, joint: usize, rank: usize, tree: &'v [f64], loops: &'v [f64]) -> &'v [f64] {
        match self.topology.slots[joint] {
            Slot::Tree { offset, .. } => &tree[offset..offset + rank],
            Slot::Loop { offset } => &loops[offset..offset + rank],
        }
    }

    /// An error unless `got` (the length of a slice of states) is the number of bodies.
    fn check_count(&self, what: &'static str, got: usize) -> Result<(), ConstraintError> {
        if got == self.bodies.len() {
            Ok(())
        } else {
            Err(ConstraintError::Count {
                what,
                expected: self.bodies.len(),
                got,
            })
        }
    }

    /// The kinetic plus potential energy of the system: the bodies' kinetic energies, their forces' potentials
    /// (gravity) and the conservative force elements' (springs). An error unless there is one state per body.
    pub fn energy(&self, states: &[State<A>]) -> Result<f64, ConstraintError> {
        self.check_count("states", states.len())?;
        Ok(self.total_energy(states))
    }

    /// [`Mechanism::energy`] of states already counted.
    fn total_energy(&self, states: &[State<A>]) -> f64 {
        let bodies: f64 = self
            .bodies
            .iter()
            .zip(states)
            .map(|(entry, state)| {
                state.kinetic_energy(&entry.body)
                    + entry
                        .forces
                        .iter()
                        .map(|f| f.potential_energy(&entry.body, state))
                        .sum::<f64>()
            })
            .sum();
        if self.elements.is_empty() {
            return bodies;
        }
        bodies + self.elements_potential(states)
    }

    /// The total momentum `Σ Ωᵢ` (world frame): linear momentum in the l-part, angular momentum about the world
    /// origin in the t-part (theory §3). An error unless there is one state per body.
    pub fn momentum(&self, states: &[State<A>]) -> Result<A::Screw, ConstraintError> {
        self.check_count("states", states.len())?;
        Ok(states
            .iter()
            .fold(A::screw(ScrewCoordinates::default()), |total, s| total + s.momentum))
    }

    /// The largest position and velocity residuals over the joints at this state; a contact's depth below its plane
    /// counts as a position residual (m).
    pub fn violation(&self, t: f64, states: &[State<A>]) -> Result<Violation, ConstraintError> {
        self.check_count("states", states.len())?;
        let mut workspace = self.new_workspace();
        self.position_rows(t, states, &mut workspace, Rows::Residuals)?;
        let (mut position, velocity) = self.coupling_violation(states);
        for contact in 0..self.contacts.len() {
            position = position.max(-self.contact_motion(contact, states).0);
        }
        Ok(workspace
            .joints
            .iter()
            .fold(Violation { position, velocity }, |v, rows| Violation {
                position: v.position.max(rows.position_residual),
                velocity: v.velocity.max(rows.velocity_residual),
            }))
    }

    /// The rates of every body at this state (Ḃ and dΩ/dt), or why the reactions could not be found: the
    /// evaluation the integrators make, for diagnostics (it allocates a workspace).
    pub fn rates_at(&self, t: f64, states: &[State<A>]) -> Result<Vec<Rates<A>>, ConstraintError> {
        self.check_count("states", states.len())?;
        let mut workspace = self.new_workspace();
        let zero = A::screw(ScrewCoordinates::default());
        let mut rates = vec![
            Rates {
                body_velocity: zero,
                momentum_rate: zero,
            };
            states.len()
        ];
        Dynamics::rates(self, t, states, &mut rates, &mut workspace)?;
        Ok(rates)
    }

    /// The world wrench each joint exerts on its body (its reference receives the opposite), at this state.
    pub fn reactions(&self, t: f64, states: &[State<A>]) -> Result<Vec<A::Screw>, ConstraintError> {
        self.check_count("states", states.len())?;
        let mut workspace = self.new_workspace();
        for (i, state) in states.iter().enumerate() {
            workspace.motors[i] = state.motor;
            workspace.momenta[i] = crate::motion::to_body::<A>(state.motor, state.momentum);
        }
        let (motors, momenta) = (workspace.motors.clone(), workspace.momenta.clone());
        self.evaluate(t, &motors, &momenta, &mut workspace)?;
        Ok(self
            .joints
            .iter()
            .enumerate()
            .map(|(j, joint)| {
                let rows = &workspace.joints[j];
                let lambda = self.multipliers(j, rows.reduced.rank, &workspace.tree, &workspace.loops);
                let (y, _) = rows.reactions(lambda);
                let kinematics = &workspace.bodies[joint.body].kinematics;
                A::screw(kinematics.to_world_coordinates(&wrench_screw(&y)))
            })
            .collect())
    }

    /// The joints' rows (positions and velocities only) at `states`.
    fn position_rows(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
        purpose: Rows,
    ) -> Result<(), ConstraintError> {
        for (i, state) in states.iter().enumerate() {
            workspace.motors[i] = state.motor;
            workspace.momenta[i] = crate::motion::to_body::<A>(state.motor, state.momentum);
        }
        let motors = std::mem::take(&mut workspace.motors);
        let momenta = std::mem::take(&mut workspace.momenta);
        self.body_kinematics(t, &motors, &momenta, workspace, BodyTerms::Kinematics)?;
        workspace.motors = motors;
        workspace.momenta = momenta;
        self.joint_rows(t, workspace, purpose)
    }

    /// Projects states onto the joint manifold (theory §10, docs/mechanisms.md §M5): normalise every motor,
    /// Gauss–Newton steps on the positions of the whole system (at most as many as [`Stabilisation::Projection`]
    /// says and at least enough to converge from afar, stopping once the residuals are round-off; skipped if a
    /// joint has no position residual), then the kinetic-metric velocity projection. Use it on initial
    /// conditions, which must satisfy both the position and the velocity constraints; joints that cannot hold
    /// together are an error naming them. Returns how far each body moved: a start off its joints by round-off moves
    /// by round-off, one that breaks a joint moves by as much as it breaks it, which the caller may refuse.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use dynamics::constraints::VirtualPower;
    /// use dynamics::{Body, Mechanism, Pga, Reference, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let rod = Body::cuboid(1.0, Vector3::new(0.1, 0.1, 1.0))?;
    /// let mut pendulum = Mechanism::<Pga>::new();
    /// let arm = pendulum.add_body("arm", rod)?;
    /// let top = (Vector3::new(0.0, 0.0, 0.5), Vector3::x());
    /// pendulum.add_joint(arm, Reference::World, Arc::new(VirtualPower::hinge("pivot", top, (Vector3::zeros(), Vector3::x()))?))?;
    /// // The rod's top end 13 cm below its pivot.
    /// let still = Vector3::zeros();
    /// let mut start = [State::new(&rod, Vector3::new(0.0, 0.0, -0.63), &UnitQuaternion::identity(), still, still)];
    /// let correction = pendulum.project(0.0, &mut start)?;
    /// assert!((correction.moved[0] - 0.13).abs() < 1e-12); // m
    /// assert!(correction.turned[0] < 1e-15); // rad
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn project(&self, t: f64, states: &mut [State<A>]) -> Result<Correction, ConstraintError> {
        self.check_count("states", states.len())?;
        let iterations = match self.stabilisation {
            Stabilisation::Projection { position_iterations } => position_iterations,
            _ => 2,
        };
        let mut workspace = self.new_workspace();
        let before: Vec<_> = states.iter().map(State::pose).collect();
        self.project_with(t, states, iterations.max(INITIAL_PROJECTION_STEPS), &mut workspace)?;
        let (moved, turned) = (before.iter().zip(states.iter()))
            .map(|((position, orientation), state)| {
                let (now, turned_to) = state.pose();
                ((now - position).norm(), orientation.angle_to(&turned_to))
            })
            .unzip();
        Ok(Correction { moved, turned })
    }

    fn project_with(
        &self,
        t: f64,
        states: &mut [State<A>],
        iterations: usize,
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        if self.articulation.is_some() {
            self.project_coordinates(t, states, &mut workspace.previous_positions, &workspace.held)?;
            return self.place_held_contacts(t, states, workspace);
        }
        for state in states.iter_mut() {
            state.motor = motor::normalise::<A>(state.motor);
        }
        if self.joints.is_empty() {
            return Ok(());
        }
        let position_level = self.joints.iter().all(|j| j.constraint.has_position_residual());
        self.position_rows(t, states, workspace, Rows::Projection)?;
        let mut tolerances = Tolerances::of(workspace);
        let drift = largest_position_residual(workspace);
        // The factors of the integrator's last stage, if any, serve only this projection.
        let stage_factors = std::mem::take(&mut workspace.stage_factors);
        let mut steps = 0;
        if position_level && iterations > 0 && drift > tolerances.position && drift <= ONE_STEP_DRIFT {
            // The common case after a step, a drift so small that one Gauss–Newton step squares it to round-off
            // (docs/mechanisms.md M5). Its factorisation of K can be a chord: the factors of the integrator's
            // last stage, whose K is this one to O(dt²) for the usual methods. Whether a chord step (or one with
            // factors from before a move) reached round-off is checked exactly to first order, e and ė being
            // `e + J δ` and `ė + J Δx` after the bodies move by δ or change velocity by Δx (the second order is
            // the square of the drift), and what is left is solved again with fresh factors.
            let mut fresh = !stage_factors || !workspace.joints.iter().all(|rows| rows.reduced.direct);
            if fresh {
                self.factor_system(workspace)?;
            }
            self.solve_factored(workspace, Condition::Position, Consistency::Skip)?;
            self.move_positions(states, workspace);
            if !fresh && self.remaining_residual(workspace, Condition::Position) > tolerances.position {
                self.factor_system(workspace)?;
                fresh = true;
                self.solve_factored(workspace, Condition::Position, Consistency::Skip)?;
                self.move_positions(states, workspace);
            }
            steps = 1;
            // The velocity projection can use the rows from before the move when that leaves ė = O(|δ| |x|) —
            // about drift × the largest body velocity — within the velocity tolerance: one evaluation for the
            // whole projection. Otherwise (a rod end on a sphere, RK4 at dt = 1e-3, ended 3.5e-9 from the exact
            // projection's run after 2 s) the rows are evaluated again at the moved positions, which also checks
            // the position step, and K's factors from before the move serve as a chord.
            let evaluate_again = drift * tolerances.velocity_scale > tolerances.velocity;
            if !evaluate_again {
                // Rows and (fresh) factors both from before the move need no check.
                return self.project_velocities(states, workspace, !fresh, tolerances.velocity);
            }
            self.position_rows(t, states, workspace, Rows::Projection)?;
            if largest_position_residual(workspace) <= tolerances.position
                && workspace.joints.iter().all(|rows| rows.reduced.direct)
            {
                return self.project_velocities(states, workspace, true, tolerances.velocity);
            }
            // Not at round-off after all, or rows whose basis the reduction chose afresh: the checked loop.
            tolerances = Tolerances::of(workspace);
        }
        // Initial conditions and large drifts: Gauss–Newton steps, each checked by an evaluation.
        while position_level && steps < iterations && largest_position_residual(workspace) > tolerances.position {
            self.solve_reactions(workspace, Condition::Position, Consistency::Skip)?;
            self.move_positions(states, workspace);
            steps += 1;
            self.position_rows(t, states, workspace, Rows::Projection)?;
            tolerances = Tolerances::of(workspace);
        }
        let unreachable: Vec<usize> = (0..self.joints.len())
            .filter(|&j| workspace.joints[j].position_residual > UNREACHABLE_RESIDUAL)
            .collect();
        if position_level && !unreachable.is_empty() {
            let residual = unreachable
                .iter()
                .map(|&j| workspace.joints[j].position_residual)
                .fold(0.0, f64::max);
            return Err(ConstraintError::Unreachable {
                names: self.names(unreachable),
                residual,
            });
        }
        // Positions left alone and velocities within round-off: nothing to do.
        if steps == 0
            && workspace
                .joints
                .iter()
                .all(|rows| rows.velocity_residual <= tolerances.velocity)
        {
            return Ok(());
        }
        if steps == 0 && stage_factors && workspace.joints.iter().all(|rows| rows.reduced.direct) {
            // Positions left alone: the last stage's factors serve as a chord, checked.
            return self.project_velocities(states, workspace, true, tolerances.velocity);
        }
        self.solve_reactions(workspace, Condition::Velocity, Consistency::Skip)?;
        self.change_momenta(states, workspace);
        Ok(())
    }

    /// The velocity projection with the factors in `workspace`; with `check`, when they are not those of the
    /// current rows, its result is checked ([`Mechanism::remaining_residual`]) and what is left solved again with
    /// fresh factors.
    fn project_velocities(
        &self,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
        check: bool,
        tolerance: f64,
    ) -> Result<(), ConstraintError> {
        self.solve_factored(workspace, Condition::Velocity, Consistency::Skip)?;
        self.change_momenta(states, workspace);
        if check && self.remaining_residual(workspace, Condition::Velocity) > tolerance {
            self.factor_system(workspace)?;
            self.solve_factored(workspace, Condition::Velocity, Consistency::Skip)?;
            self.change_momenta(states, workspace);
        }
        Ok(())
    }

    /// The residuals of `condition` left after the bodies moved by the reactions in `workspace`
    /// ([`Mechanism::move_positions`] or [`Mechanism::change_momenta`]): ė is linear in the velocities and e is to
    /// first order (the rest is the square of the step), so each joint's row gains `a·Δ_b + a'·Δ_a` from the
    /// bodies' changes `Δ = G Jᵀλ` (a' the row acting on the reference). Stores the new right-hand sides `−e` or
    /// `−ė` and returns their largest size.
    fn remaining_residual(&self, workspace: &mut MechanismWorkspace<A>, condition: Condition) -> f64 {
        let MechanismWorkspace {
            joints,
            reactions,
            inverse_metric,
            ..
        } = workspace;
        let change =
            |body: usize| -> [f64; 6] { std::array::from_fn(|k| reactions[body][k] * inverse_metric[body][k]) };
        let mut largest = 0.0f64;
        for (joint, rows) in self.joints.iter().zip(joints.iter_mut()) {
            let body = change(joint.body);
            let reference = joint.reference.map(change);
            let reduced = &mut rows.reduced;
            for k in 0..reduced.rank {
                let mut gained = dot6(&reduced.rows[k], &body);
                if let Some(reference) = &reference {
                    gained += dot6(&rows.reference_rows[k], reference);
                }
                let value = &mut reduced.values[condition as usize][k];
                *value -= gained;
                largest = largest.max(value.abs());
            }
        }
        largest
    }

    /// The Gauss–Newton position step from the reactions λ of `K λ = −e`: `δᵢ = Gᵢ Jᵢᵀλ`,
    /// `Rᵢ ← Rᵢ exp(−½δᵢ)`, the motion with body velocity δᵢ for unit time.
    fn move_positions(&self, states: &mut [State<A>], workspace: &MechanismWorkspace<A>) {
        for (i, state) in states.iter_mut().enumerate() {
            let y = workspace.reactions[i];
            let delta: [f64; 6] = std::array::from_fn(|k| y[k] * workspace.inverse_metric[i][k]);
            let step = A::screw(velocity_screw(&delta)) * -0.5;
            state.motor = motor::normalise::<A>(A::compose(state.motor, exp::<A>(step)));
        }
    }

    /// The velocity projection from the reactions λ of `K λ = −ė`: `Δxᵢ = Gᵢ Jᵢᵀλ`, so the momentum changes by
    /// `H Δx = Jᵀλ`. Only this (tiny) change goes through the frame change, not Ω itself: a round trip
    /// Ω → Ω_b → Ω every step biases the energy by about an ulp per step (measured: +1e-15 J per step on a
    /// pendulum, 1e-10 rad after 1e5 steps).
    fn change_momenta(&self, states: &mut [State<A>], workspace: &MechanismWorkspace<A>) {
        for (i, state) in states.iter_mut().enumerate() {
            let change = wrench_screw(&workspace.reactions[i]);
            let frame = &workspace.bodies[i].kinematics.frame;
            state.momentum = state.momentum + A::screw(frame.to_world(&change));
        }
    }
}

/// The projection's tolerances at the bodies' kinematics (see [`POSITION_TOLERANCE`]).
struct Tolerances {
    position: f64,
    velocity: f64,
    /// The largest body velocity coordinate (rad/s or m/s).
    velocity_scale: f64,
}

impl Tolerances {
    fn of<A: Algebra>(workspace: &MechanismWorkspace<A>) -> Self {
        let (position, velocity_scale) = workspace.bodies.iter().fold((0.0f64, 0.0f64), |(p, v), body| {
            let kinematics = &body.kinematics;
            (
                p.max(kinematics.frame.position.amax()),
                v.max(kinematics.velocity.amax()),
            )
        });
        let ulps = ROUND_OFF_ULPS * f64::EPSILON;
        Tolerances {
            position: POSITION_TOLERANCE.max(ulps * position),
            velocity: VELOCITY_TOLERANCE.max(ulps * velocity_scale),
            velocity_scale,
        }
    }
}

/// The largest position residual over the joints.
fn largest_position_residual<A: Algebra>(workspace: &MechanismWorkspace<A>) -> f64 {
    workspace
        .joints
        .iter()
        .map(|rows| rows.position_residual)
        .fold(0.0, f64::max)
}

/// `total += y` over six coordinates.
/// The power `y·x` of a wrench `y = (τ; f)` on a body moving with velocity `x = (ω; v)` (the same axes and point).
fn wrench_power(y: &[f64; 6], x: &nalgebra::Vector6<f64>) -> f64 {
    dot6(y, &(*x).into())
}

fn add(total: &mut [f64; 6], y: &[f64; 6]) {
    total.iter_mut().zip(y).for_each(|(t, y)| *t += y);
}

impl<A: Algebra> Dynamics<A> for Mechanism<A> {
    type Workspace = MechanismWorkspace<A>;

    fn feedback_rate(&self) -> f64 {
        self.stabilisation.feedback_rate()
    }

    fn drift(&self, t: f64, states: &[State<A>]) -> f64 {
        self.violation(t, states)
            .map_or(f64::INFINITY, |violation| violation.position)
    }

    fn workspace(&self) -> MechanismWorkspace<A> {
        self.new_workspace()
    }

    fn body_count(&self) -> usize {
        self.bodies.len()
    }

    fn body(&self, index: usize) -> &Body {
        &self.bodies[index].body
    }

    /// In the body frames; the world momentum rate is the world external wrench (as for an unconstrained body)
    /// plus the reaction moved to the world.
    fn rates(
        &self,
        t: f64,
        states: &[State<A>],
        rates: &mut [Rates<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        self.check_count("rates", rates.len())?;
        self.evaluate_states(t, states, workspace)?;
        for (i, (rate, state)) in rates.iter_mut().zip(states).enumerate() {
            let kinematics = &workspace.bodies[i].kinematics;
            // The reactions and the force elements' wrenches, body frame, moved to the world together.
            let mut internal = wrench_screw(&workspace.reactions[i]);
            if !self.elements.is_empty() {
                internal = internal + workspace.element_wrenches[i];
            }
            let reaction = A::screw(kinematics.to_world_coordinates(&internal));
            *rate = Rates {
                body_velocity: kinematics.body_velocity,
                momentum_rate: self.external_wrench(i, t, state, kinematics) + reaction,
            };
        }
        Ok(())
    }

    /// In the body frames throughout: no world momentum is built (unless a custom force asks for it) and the
    /// reactions are not moved to the world and back.
    fn body_rates(
        &self,
        t: f64,
        motors: &[A::Motor],
        body_momenta: &[A::Screw],
        rates: &mut [BodyRates<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("motors", motors.len())?;
        self.check_count("body momenta", body_momenta.len())?;
        self.check_count("rates", rates.len())?;
        self.evaluate(t, motors, body_momenta, workspace)?;
        for (i, rate) in rates.iter_mut().enumerate() {
            let total = workspace.external[i] + wrench_screw(&workspace.reactions[i]);
            *rate = BodyRates {
                body_velocity: workspace.bodies[i].kinematics.body_velocity,
                body_wrench: A::screw(total),
            };
        }
        Ok(())
    }

    fn after_joint_step(
        &self,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        match self.stabilisation {
            Stabilisation::Projection { .. } => self.place_held_contacts(t, states, workspace),
            _ => Ok(()),
        }
    }

    fn after_step(
        &self,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        match self.stabilisation {
            Stabilisation::Projection { position_iterations } => {
                self.project_with(t, states, position_iterations, workspace)
            }
            _ => {
                for state in states.iter_mut() {
                    state.motor = motor::normalise::<A>(state.motor);
                }
                Ok(())
            }
        }
    }

    fn energy(&self, states: &[State<A>]) -> f64 {
        self.total_energy(states)
    }

    fn power(&self, workspace: &MechanismWorkspace<A>) -> f64 {
        workspace.power
    }

    fn conserves_world_momenta(&self) -> bool {
        self.joints.is_empty()
            && self.contacts.is_empty()
            && self.elements.is_empty()
            && self.bodies.iter().all(|body| body.forces.is_empty())
    }

    fn joint_layout(&self) -> Option<crate::joint_integration::JointLayout> {
        self.articulation.as_ref()?;
        self.coordinates().map(JointSpace::layout)
    }

    fn read_joints(
        &self,
        states: &[State<A>],
        positions: &mut [f64],
        velocities: &mut [f64],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        self.read_joints_into(states, positions, velocities, &mut workspace.previous_positions)
    }

    fn write_joints(
        &self,
        t: f64,
        positions: &[f64],
        velocities: &[f64],
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        self.write_joints_into(t, positions, velocities, states, &mut workspace.placed)
    }

    fn joint_rates(
        &self,
        t: f64,
        positions: &[f64],
        velocities: &[f64],
        accelerations: &mut [f64],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.joint_rates_at(t, positions, velocities, accelerations, workspace)
    }

    fn limit_count(&self) -> usize {
        Mechanism::limit_count(self)
    }

    fn limit_name(&self, index: usize) -> Option<&str> {
        Mechanism::limit_name(self, index)
    }

    fn limit_values(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
        values: &mut [f64],
    ) -> Result<(), ConstraintError> {
        Mechanism::limit_values(self, t, states, workspace, values)
    }

    fn limit_transition(
        &self,
        index: usize,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        Mechanism::limit_transition(self, index, t, states, workspace)
    }
}
