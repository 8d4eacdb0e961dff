//! Rigid-body dynamics with constraints in CGA and PGA, from one generic source.
//!
//! Implements Hadfield & Lasenby, *Constrained Dynamics in Conformal and Projective Geometric
//! Algebra*, as corrected in the project's SPEC. The pipeline, one module per stage:
//! [`algebra`] (the trait; [`Pga`] and [`Cga`] built with `algebra!`) → [`motor`] and
//! [`exponential`] (rigid transforms) → body and state → forces → constraints → integrators → scenes.

pub mod algebra;
pub mod cga;
pub mod equivalence;
pub mod exponential;
pub mod motor;
pub mod pga;

pub use algebra::{Algebra, MotorCoordinates, ScrewCoordinates};
pub use cga::Cga;
pub use pga::Pga;
