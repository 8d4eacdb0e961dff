//! Integrators for the state of N rigid bodies, one `[R, Ω]` per body (`docs/theory.md` §5, §10), one step of
//! a length the caller chooses.
//!
//! Two families:
//! * [`Method`]: general methods, valid for any [`Dynamics`](crate::Dynamics) (free bodies, constrained bodies, mechanisms):
//!   the paper's RK4 on `(R, Ω)` as vectors plus renormalisation, and Runge–Kutta–Munthe-Kaas (RKMK) methods
//!   that move each R only by motor products with exponentials of screws, with the momentum in the world
//!   frame (RKMK4) or in the body frame (RKMK4-body, RKMK6-body). Every body takes the same stages, so a
//!   mechanism advances on the product of its bodies' motor groups and each motor stays an exact motor.
//! * [`SplittingMethod`]: Hamiltonian splittings of a free body ([`KineticSplitting`], built from a
//!   [`FreeBody`](crate::FreeBody) whose forces allow it). Every sub-step is the exact flow of one piece of the Hamiltonian,
//!   so for a free or gravitating body the energy error stays bounded over long times instead of drifting.
//!
//! [`Integrator`] names any of them; a [`Stepper`] takes steps of one integrator on one system, with its
//! buffers made once (a step allocates nothing).
//!
//! A step's length is the caller's: [`crate::simulate()`] takes it from a fixed schedule, or from the step-size
//! controller of an adaptive one ([`crate::integrate::step_control`]), which reads the error estimate of an embedded pair
//! ([`Method::Dopri5Body`], [`Method::Dop853Body`]) and takes samples and events from its continuous extension.

mod methods;
mod error;
mod tableaux;
mod lie_group;
mod splitting;
pub mod joint_coordinates;
mod stepper;
pub mod step_control;

pub use error::{SplittingError, StepError, MAX_FEEDBACK_STEP, MAX_ROTOR_NORM_ERROR, MAX_TURN_PER_STEP};
pub use methods::{Integrator, JointMethod, Method, SplittingMethod};
pub use splitting::KineticSplitting;
pub use stepper::Stepper;
