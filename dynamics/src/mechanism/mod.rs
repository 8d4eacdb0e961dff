//! Mechanisms: N rigid bodies under forces, held to each other and to the world by joints, in maximal
//! coordinates (each body its motor and momentum). The derivation is in `docs/mechanisms.md`; in short:
//!
//! * a **joint** is any [`Constraint`](crate::Constraint) of [`crate::constraints`] — pinned multivectors, linear functions of
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
mod topology;
mod solve;
mod reduce;
mod load_split;
mod spatial;
mod parts;
mod error;
mod joint_rows;
mod articulated;
mod joint_space;
pub mod force_elements;
mod model;
mod build;
mod evaluate;
mod elements;
mod configuration;
mod mass_matrix;
mod forward_dynamics;
mod inverse_dynamics;
mod projection;
mod contact_frames;
mod contacts;
mod polyhedra;
mod friction;
mod contact_impacts;
mod unilateral;
mod system;

pub use error::MechanismError;
pub use evaluate::Violation;
pub use joint_space::{CoordinateGroup, JointSpace};
pub use model::{Mechanism, MechanismWorkspace};
pub use parts::{BodyId, JointId, Reference};
pub use projection::Correction;
pub use solve::{SolverSettings, ROUND_OFF};
