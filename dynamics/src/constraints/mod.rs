//! Constraints (`docs/theory.md` §6–§9): by virtual power, by pinning multivectors, parametric paths and linear
//! functions of them. Each is written for one body against a reference frame — the world, or, as a joint of a
//! [`crate::Mechanism`], another body — and evaluated at every evaluation of the equations of motion.
//!
//! # One formulation for all of them
//!
//! Every constraint here reduces, at one state, to scalar **rows** in the body velocity coordinates
//! `x = (ω; v)` of Ḃ (theory §3; for a joint, the velocity relative to the reference) — see [`ConstraintRow`]:
//!
//! * a velocity residual `ė = a·x + s(t)`, linear in x with the Jacobian row `a`;
//! * its rate along the motion `ë = a·ẍ + b`, where `ẍ` are the coordinates of B̈ and b (the *bias*) collects
//!   every term without B̈;
//! * optionally a position residual e with `de/dt = ė`, which the stabilisation uses (theory §10).
//!
//! Virtual power (§6): `ė = ⟨Ḃ ∧ T_b⟩_Π`, so `a` holds the wrench coordinates `(τ; f)` of `T_b = ~R T R`.
//! Pinning (§7–§9): `ė = A[Ḃ × V_b + V̇_b] − U̇`, one row per multivector coefficient, column j of `a` holding
//! `A[Ḃⱼ × V_b]` for the basis velocity Ḃⱼ. With `B̈ = M⁻¹[Ḃ×Ω_b + S + F]` (theory §5), i.e.
//! `ẍ = H⁻¹(g + y)` in wrench coordinates, the acceleration condition `ë = 0` becomes a linear system for the
//! reaction y (theory §6 and §7.1), which [`crate::mechanism`] solves for all joints of a system at once in the
//! kinetic metric, each joint with its known rank.

mod error;
mod rows;
mod kinematics;
pub mod objects;
pub mod paths;
mod constraint;
pub mod stabilise;
mod on_surfaces;
pub mod virtual_power;
mod virtual_power_joints;
pub mod pinning;
pub mod linear;

pub use constraint::{Composite, Constraint};
pub use error::ConstraintError;
pub use kinematics::Kinematics;
pub use objects::{Coefficients, Pinnable, PinningAlgebra};
pub use on_surfaces::{SurfacePin, TANGENT};
pub use paths::{CarriedPath, MotorPath, MotorPoint, Path, PathPoint, ScrewMotion};
pub use pinning::{LinearFunction, Pin};
pub use rows::{ConstraintRow, RowBuffer, MAX_ROWS};
pub use stabilise::Stabilisation;
pub use virtual_power::{VirtualPower, WrenchPath, WrenchPoint};
