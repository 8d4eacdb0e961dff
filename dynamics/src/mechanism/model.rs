//! The mechanism itself: its bodies, joints, forces and one-sided constraints with the structures of its solves
//! (docs/mechanisms.md), the scratch of its evaluations, and what can be read off it by name and index.

use std::collections::HashSet;
use std::fmt;

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::{Constraint, Kinematics, RowBuffer, Stabilisation};
use crate::forces::Force;
use crate::limits::Bound;
use crate::mechanism::articulated::{ArticulatedScratch, Articulation, Row};
use crate::mechanism::force_elements::ForceElement;
use crate::mechanism::joint_rows::{BodyKinematics, Joint, JointRows};
use crate::mechanism::joint_space::{JointSpace, WorldBody};
use crate::mechanism::parts::{
    repeated_contacts, BodyId, Contact, Coupling, JointId, Limit, MechanismBody, Reference, Slip,
};
use crate::mechanism::solve::{SolverSettings, SystemMatrix};
use crate::mechanism::topology::{Slot, Topology};
use crate::motor;

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
    pub(super) bodies: Vec<MechanismBody<A>>,
    pub(super) joints: Vec<Joint<A>>,
    pub(super) stabilisation: Stabilisation,
    pub(super) settings: SolverSettings,
    pub(super) topology: Topology,
    /// The joint-model tree, when the articulated solve applies (docs/mechanisms.md §M7).
    pub(super) articulation: Option<Articulation>,
    /// The coordinates of the joint models and free roots, if the joint models form a forest.
    /// Built on first use after a change (a robot adds its bodies and joints one by one).
    pub(super) joint_space: std::sync::OnceLock<Option<JointSpace>>,
    /// Linear relations between joint coordinates (URDF mimics).
    pub(super) couplings: Vec<Coupling>,
    /// The couplings' acceleration rows for the articulated solve.
    pub(super) coupling_rows: Vec<Row>,
    /// Forces between bodies (docs/mechanisms.md §M8).
    pub(super) elements: Vec<ForceElement<A>>,
    /// The joint models' limits, in the order of their joints.
    pub(super) limits: Vec<Limit>,
    /// Body points kept above world planes (docs/contacts.md).
    pub(super) contacts: Vec<Contact>,
    /// The contacts with friction, in order: each has a friction value after every limit and contact.
    pub(super) frictional: Vec<usize>,
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

/// The scratch of a mechanism's evaluations ([`Dynamics::Workspace`](crate::Dynamics::Workspace)): made once per run, so an evaluation
/// does not allocate.
pub struct MechanismWorkspace<A: Algebra> {
    pub(super) bodies: Vec<BodyKinematics<A>>,
    /// External wrench per body, body coordinates.
    pub(super) external: Vec<ScrewCoordinates>,
    /// Reaction per body, wrench coordinates `(τ; f)`, body frame.
    pub(super) reactions: Vec<[f64; 6]>,
    pub(super) joints: Vec<JointRows>,
    pub(super) raw: RowBuffer,
    pub(super) matrix: SystemMatrix,
    pub(super) tree: Vec<f64>,
    pub(super) loops: Vec<f64>,
    pub(super) inverse_metric: Vec<[f64; 6]>,
    pub(super) motors: Vec<A::Motor>,
    pub(super) momenta: Vec<A::Screw>,
    /// Whether `matrix` holds the factors of the last dynamics evaluation with every joint's rows its own (not a
    /// basis the reduction chose): the projection after a step may use them as a chord (docs/mechanisms.md M5).
    pub(super) stage_factors: bool,
    pub(super) articulated: ArticulatedScratch,
    /// The joint positions of the last projection by coordinates, so that angles read the next time unwrap from them.
    pub(super) previous_positions: Vec<f64>,
    /// The non-conservative power at the last evaluation (W): the force elements', the bodies' forces other than
    /// gravity, the drives'.
    pub(super) power: f64,
    /// The force elements' wrench on each body at the last evaluation (body frame; also in `external`).
    pub(super) element_wrenches: Vec<ScrewCoordinates>,
    /// The bodies placed by forward kinematics (stepping in joint coordinates).
    pub(super) placed: Vec<WorldBody>,
    /// Per one-sided constraint (limits, then contacts), the bound it is held at, if it is (docs/limits.md; a
    /// contact's plane is its lower bound).
    pub(super) held: Vec<Option<Bound>>,
    /// The articulated solve's rows: the couplings', then one per held limit and per held contact, and two more per
    /// sticking contact.
    pub(super) rows: Vec<Row>,
    /// Per contact, the tangential state it has while held (docs/contacts.md "Friction").
    pub(super) slips: Vec<Slip>,
    /// Per one-sided constraint (limits, then contacts), the index in `rows` of its row (a contact's normal row)
    /// while it is held.
    pub(super) held_rows: Vec<Option<usize>>,
    /// Per contact, whether a switching contact is watched (docs/contacts.md "Edges"); renewed before every step.
    pub(super) watched: Vec<bool>,
    /// Whether `watched` has been renewed from a state since the workspace was made.
    pub(super) switches_renewed: bool,
    /// Per contact, the earlier contact it repeats in all but its name, if any ([`repeated_contacts`]): a repeat is
    /// never watched nor held, its leader takes the load for both (docs/contacts.md "Repeated contacts").
    pub(super) repeats: Vec<Option<usize>>,
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
pub(super) enum Condition {
    Acceleration = 0,
    Position = 1,
    Velocity = 2,
}

/// What an evaluation computes of each body besides its kinematics.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum BodyTerms {
    /// Nothing: positions and velocities only (projection, violation).
    Kinematics,
    /// The external wrenches (the articulated solve).
    Forces,
    /// The external wrenches and the free accelerations `H⁻¹(Ḃ × Ω_b + S_b)` (the constraint-space solve).
    FreeAccelerations,
}

impl<A: Algebra> Mechanism<A> {
    #[inline]
    pub(super) fn joint_rank(joint: &Joint<A>) -> usize {
        joint
            .reaction_basis
            .as_ref()
            .map_or(joint.constraint.rank(), |basis| basis.len())
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

    /// Where a body's reference frame (the frame its joint models, contacts and points use: the one given to
    /// [`Mechanism::add_body_with_frame`], else the principal frame) is in its principal frame, whose pose a
    /// [`State`](crate::State) gives: a point `x` of the reference frame is at `position + rotation · (frame · x)` in
    /// the world. An error for a body of another mechanism.
    ///
    /// ```
    /// use dynamics::{Body, Mechanism, Pga};
    /// use nalgebra::{Matrix3, Vector3};
    ///
    /// // A link whose centre of mass is 0.2 m along its frame's z axis: the frame's origin is 0.2 m below it.
    /// let inertia = Matrix3::from_diagonal(&Vector3::new(0.02, 0.02, 0.01));
    /// let (link, frame) = Body::from_inertia_tensor(2.0, inertia, Vector3::z() * 0.2, Vector3::z() * 0.2)?;
    /// let mut robot = Mechanism::<Pga>::new();
    /// let id = robot.add_body_with_frame("link", link, frame)?;
    /// let origin = robot.reference_frame(id)? * nalgebra::Point3::origin();
    /// assert!((origin.coords - Vector3::z() * -0.2).norm() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn reference_frame(&self, body: BodyId) -> Result<nalgebra::Isometry3<f64>, crate::MechanismError> {
        let index = self.check_body(body)?;
        Ok(self.bodies[index].frame)
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
    pub(super) fn names(&self, joints: impl IntoIterator<Item = usize>) -> String {
        let mut seen = HashSet::new();
        joints
            .into_iter()
            .filter(|j| seen.insert(*j))
            .map(|j| self.joints[j].name())
            .collect::<Vec<_>>()
            .join(" + ")
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
                self.couplings.len() + self.limit_count() + self.frictional.len(),
            ),
            previous_positions: Vec::new(),
            power: 0.0,
            element_wrenches: vec![ScrewCoordinates::default(); self.bodies.len()],
            placed: Vec::new(),
            held: vec![None; self.limits.len() + self.contacts.len()],
            rows: self.coupling_rows.clone(),
            slips: vec![Slip::Sticking; self.contacts.len()],
            held_rows: vec![None; self.limits.len() + self.contacts.len()],
            watched: vec![false; self.contacts.len()],
            switches_renewed: false,
            repeats: repeated_contacts(&self.contacts),
        }
    }
}
