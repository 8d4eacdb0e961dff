//! Rigid-body dynamics with constraints in CGA and PGA, from one generic source.
//!
//! Implements Hadfield & Lasenby, *Constrained Dynamics in Conformal and Projective Geometric
//! Algebra*, as corrected in the project's SPEC. The pipeline, one module per stage:
//! [`algebra`] (the trait; [`Pga`] and [`Cga`] built with `algebra!`) → [`motor`] and
//! [`exponential`] (rigid transforms) → [`body`], [`inertia`] and [`state`] → [`forces`] →
//! [`motion`] (the equations of motion) → constraints → integrators → scenes.

pub mod algebra;
pub mod body;
pub mod cga;
pub mod constraints;
pub mod convert;
pub mod equivalence;
pub mod exponential;
pub mod forces;
pub mod inertia;
pub mod integrate;
pub mod motion;
pub mod motor;
pub mod pga;
pub mod scenes;
pub mod simulate;
pub mod state;

pub use algebra::{Algebra, MotorCoordinates, ScrewCoordinates};
pub use body::{Body, BodyError};
pub use cga::Cga;
pub use constraints::{ConstrainedBody, ConstraintError, Stabilisation};
pub use forces::Force;
pub use integrate::{step, step_free_body, step_splitting, Integrator, KineticSplitting, Method, SplittingMethod};
pub use motion::{BodyRates, Dynamics, FreeBody, Rates};
pub use pga::Pga;
pub use simulate::{simulate, simulate_free_body, Schedule, Simulation, SimulationError};
pub use state::{State, WorldVelocity};
