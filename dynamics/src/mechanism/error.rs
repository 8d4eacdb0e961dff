//! Why a mechanism cannot be built as asked.

use crate::constraints::ConstraintError;

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
    /// A [`BodyId`](crate::BodyId) (its index held) that is not a body of this mechanism.
    #[error("body index {0} is not a body of this mechanism")]
    UnknownBody(usize),
    /// A [`JointId`](crate::JointId) (its index held) that is not a joint of this mechanism; also index 0 for
    /// [`Mechanism::with_reaction_basis`](crate::Mechanism::with_reaction_basis) before any joint was added.
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
    /// ([`Mechanism::set_reaction_basis`](crate::Mechanism::set_reaction_basis)).
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

/// The names of an error's constraints, joined by " + ": the first few of them and how many more (two boxes bring 240
/// contacts).
pub(super) fn listed<'n>(names: impl Iterator<Item = &'n str>) -> String {
    const SHOWN: usize = 4;
    let names: Vec<&str> = names.collect();
    match names.len().checked_sub(SHOWN) {
        Some(more) if more > 0 => format!("{} + {more} more", names[..SHOWN].join(" + ")),
        _ => names.join(" + "),
    }
}
