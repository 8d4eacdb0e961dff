//! A mechanism's parts: bodies and joints by index, what a joint holds its body to, and the records the mechanism
//! keeps of each body, limited joint, coupling and contact.

use nalgebra::{Isometry3, Vector3};

use crate::algebra::Algebra;
use crate::body::Body;
use crate::contacts::Friction;
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

/// A contact of a mechanism: `point` (principal body coordinates: from the centre of mass) of `body`, or a sphere of
/// radius `radius` about it, or the rim of a disk about it, kept outside what `against` describes.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Contact {
    pub name: String,
    pub body: usize,
    pub point: Vector3<f64>,
    pub radius: f64,
    /// A disk's unit axis (principal body coordinates) and radius: its rim is what touches (docs/contacts.md "Rims").
    pub rim: Option<(Vector3<f64>, f64)>,
    pub restitution: f64,
    pub friction: Friction,
    pub against: Against,
    /// The face the contact holds on, if bounded: the convex solid `n · x ≤ d` (in the frame `against` is fixed in,
    /// principal coordinates for a body; n unit) its touching point must stay inside while it touches.
    pub face: Vec<(Vector3<f64>, f64)>,
    /// The contact's own edge, from `point`, for an edge on an edge (docs/contacts.md "Edges").
    pub edge: Option<EdgeFeature>,
    /// Whether the contact is one feature pair among all of two convex solids' (docs/contacts.md "Edges"): outside
    /// its face or edges it is not watched and, held, lets go, where another pair takes over; else leaving its face
    /// stops the run.
    pub switching: bool,
    /// Whether `face` bounds the sphere's centre rather than its touching point: a sphere on a vertex, whose touching
    /// point is the vertex itself (docs/contacts.md "Spheres on polyhedra").
    pub region_at_centre: bool,
}

/// Per contact, the first earlier contact it repeats in everything but its name (its body, point, plane or features,
/// restitution and friction), if any: the two give the same row, so the repeat adds nothing but cost
/// (docs/contacts.md "Repeated contacts"). Contacts are grouped by body and point first, so this is linear in their
/// count.
pub(super) fn repeated_contacts(contacts: &[Contact]) -> Vec<Option<usize>> {
    // `+ 0.0` takes −0 to +0, which compare equal.
    let key = |c: &Contact| (c.body, c.point.map(|x| (x + 0.0).to_bits()));
    let mut leaders: std::collections::HashMap<_, Vec<usize>> = std::collections::HashMap::new();
    let mut repeats = vec![None; contacts.len()];
    for (index, contact) in contacts.iter().enumerate() {
        let group = leaders.entry(key(contact)).or_default();
        let same = |&leader: &usize| {
            let renamed = Contact {
                name: contact.name.clone(),
                ..contacts[leader].clone()
            };
            renamed == *contact
        };
        match group.iter().copied().find(same) {
            Some(leader) => repeats[index] = Some(leader),
            None => group.push(index),
        }
    }
    repeats
}

/// A straight edge in principal body coordinates, from a point given with it: its unit direction, its length, and
/// the unit outward normals of the two faces meeting along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct EdgeFeature {
    pub direction: Vector3<f64>,
    pub length: f64,
    pub faces: [Vector3<f64>; 2],
}

/// What a contact's point or sphere stays outside of (docs/contacts.md "Between bodies").
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Against {
    /// The world half-space `normal · x ≥ offset` (normal unit).
    World { normal: Vector3<f64>, offset: f64 },
    /// The half-space `normal · y ≥ offset` fixed in body `body` (its principal coordinates y; normal unit): a face.
    Face {
        body: usize,
        normal: Vector3<f64>,
        offset: f64,
    },
    /// The ball of radius `radius` about `centre` fixed in body `body` (its principal coordinates).
    Ball {
        body: usize,
        centre: Vector3<f64>,
        radius: f64,
    },
    /// The edge from `start` fixed in body `body` (its principal coordinates), outside whose solid the contact's own
    /// edge stays.
    Edge {
        body: usize,
        start: Vector3<f64>,
        edge: EdgeFeature,
    },
}

impl Against {
    /// The body the half-space or ball is fixed in, if not the world.
    pub fn body(&self) -> Option<usize> {
        match *self {
            Against::World { .. } => None,
            Against::Face { body, .. } | Against::Ball { body, .. } | Against::Edge { body, .. } => Some(body),
        }
    }
}

/// A row of a contact in joint space: the speed along `direction` of the body's material point at `point` (world)
/// less the other body's there.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PointDirection {
    pub body: usize,
    pub other: Option<usize>,
    pub point: Vector3<f64>,
    pub direction: Vector3<f64>,
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

/// The plane `n · y = d` of a body's frame F in its principal coordinates `x = F y`: `(R n) · x = d + (R n) · t`.
pub(super) fn placed_plane(frame: &Isometry3<f64>, normal: &Vector3<f64>, offset: f64) -> (Vector3<f64>, f64) {
    let normal = frame.rotation * normal;
    (normal, offset + normal.dot(&frame.translation.vector))
}
