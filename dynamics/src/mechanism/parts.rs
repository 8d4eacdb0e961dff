//! A mechanism's parts: bodies and joints by index, what a joint holds its body to, and the records the mechanism
//! keeps of each body, limited joint, coupling and contact.

use nalgebra::{Isometry3, Vector3};

use crate::algebra::Algebra;
use crate::body::Body;
use crate::contacts::PlaneContact;
use crate::forces::Force;
use crate::limits::JointLimit;

/// A body of a mechanism, by its index in the order the bodies were added.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BodyId(pub(super) usize);

impl BodyId {
    /// The body's index: its position in states and samples.
    pub fn index(self) -> usize {
        self.0
    }
}

/// A joint of a mechanism, by its index in the order the joints were added.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct JointId(pub(super) usize);

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

#[derive(Clone, Debug)]
pub(super) struct MechanismBody<A: Algebra> {
    pub(super) name: String,
    pub(super) body: Body,
    pub(super) forces: Vec<Force<A>>,
    /// The body's reference frame (the frame its inertia was described in) in its body frame: a free root's
    /// joint coordinates are this frame's pose and twist.
    pub(super) frame: Isometry3<f64>,
}

/// A limited joint model: its joint index and range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Limit {
    pub(super) joint: usize,
    pub(super) range: JointLimit,
}

/// `q_follower = multiplier · q_leader + offset` between two one-coordinate joint models (joint indices).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Coupling {
    pub(super) follower: usize,
    pub(super) leader: usize,
    pub(super) multiplier: f64,
    pub(super) offset: f64,
}

/// A contact of a mechanism: `point` (principal body coordinates: from the centre of mass) of `body` above the
/// plane of `contact`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Contact {
    pub name: String,
    pub body: usize,
    pub point: Vector3<f64>,
    pub contact: PlaneContact,
}

/// The tangential state of a held contact with friction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Slip {
    /// Sliding: the friction force `−μ N ŝ` opposes the slip ŝ. `reference` is the slip's direction at the start of
    /// the step: the friction keeps the orientation it has along it, so that a slide that stops inside a step
    /// continues smoothly past the stop, where the step is cut (docs/contacts.md "Friction").
    Sliding { reference: Vector3<f64> },
    /// Sticking: the slip held at zero by two tangential rows.
    Sticking,
}
