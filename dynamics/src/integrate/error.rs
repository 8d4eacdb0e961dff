//! Why a step failed, and the bounds a step is checked against.

use crate::constraints::ConstraintError;
use crate::state::MAX_COORDINATE;

/// Why a system cannot be integrated by splitting.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SplittingError {
    /// A kick `Ω ← Ω + h W` is the exact flow of `dΩ/dt = W` only if W does not depend on Ω (nor on
    /// time within the step); a custom force may depend on both.
    #[error("force {index} is a custom force, which may depend on the momentum; splitting needs forces of the configuration only")]
    CustomForce {
        /// The index of the custom force in the body's list of forces.
        index: usize,
    },
    /// The splittings are written for one free body (its kinetic energy splits into exact rotations).
    #[error("splitting methods integrate a single free body, not a constrained body or a mechanism")]
    NotAFreeBody,
}

/// The largest angle (rad) a body may turn through in one step, judged from its angular velocity at the start
/// of the step ([`StepError::StepTooLarge`]). The reference scenes turn at most 0.2 rad per step at their
/// largest step (the heavy top, 20 rad/s at dt = 1e-2).
pub const MAX_TURN_PER_STEP: f64 = 1.0;

/// Why a step failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StepError {
    /// The state does not have one entry per body of the system.
    #[error("the state has {got} bodies, the system has {expected}")]
    BodyCount {
        /// The number of bodies of the system.
        expected: usize,
        /// The number of states given.
        got: usize,
    },
    /// A splitting method was asked of a system it cannot integrate (when the stepper is made).
    #[error(transparent)]
    Splitting(#[from] SplittingError),
    /// A method stepping in joint coordinates was asked of a system without them (when the stepper is made).
    #[error(
        "{method} steps in joint coordinates: it needs a mechanism whose joints are all joint models (Mechanism::connect) in a tree, without Baumgarte stabilisation"
    )]
    NoJointCoordinates {
        /// The method's name.
        method: &'static str,
    },
    /// An evaluation of the equations of motion (or the projection after the step) failed; the error names the
    /// joints or constraints involved.
    #[error("at t = {t}: {error}")]
    Constraint {
        /// The time the failing step started at (s).
        t: f64,
        /// What went wrong.
        error: ConstraintError,
    },
    /// The step size is zero, negative, NaN or infinite.
    #[error("the step must be positive and finite, got dt = {dt}")]
    InvalidStep {
        /// The step that was refused (s).
        dt: f64,
    },
    /// The time the step starts at is NaN or infinite.
    #[error("the time must be finite, got t = {t}")]
    InvalidTime {
        /// The start time that was refused.
        t: f64,
    },
    /// A body is farther from the world origin than [`MAX_DISTANCE_IN_GYRATION_RADII`](crate::state::MAX_DISTANCE_IN_GYRATION_RADII) of its radii of gyration,
    /// where positions are resolved to more than 1e-9 of its size.
    #[error(
        "at t = {t}: body {body} is {distance:.3e} m from the world origin, farther than {limit:.3e} m (4.5e6 of its \
         radii of gyration), where positions are resolved only to 1e-9 of its size; put the scene's origin near the \
         bodies"
    )]
    TooFarFromOrigin {
        /// The time the step was to start at (s).
        t: f64,
        /// The index of the first body that is too far.
        body: usize,
        /// Its distance from the origin (m).
        distance: f64,
        /// The farthest it may be (m).
        limit: f64,
    },
    /// A state given to the step has a motor that is not a rigid motion: its rotor part's squared norm is off 1 by
    /// more than [`MAX_ROTOR_NORM_ERROR`] (a zero motor, or one written field by field without normalising).
    #[error(
        "the state given at t = {t} has a motor that is not a rigid motion (body {body}): its rotor part's squared \
         norm is {norm_squared:e}, not 1"
    )]
    NotARigidMotion {
        /// The time the step was to start at (s).
        t: f64,
        /// The index of the first body whose motor is not rigid.
        body: usize,
        /// Its rotor part's squared norm ([`State::rotor_norm_squared`](crate::State::rotor_norm_squared)).
        norm_squared: f64,
    },
    /// A state given to the step has a NaN or infinite coordinate, or one beyond [`MAX_COORDINATE`].
    #[error("the state given at t = {t} is not finite or has a coordinate beyond {MAX_COORDINATE:e} (body {body})")]
    NonFiniteInput {
        /// The time the step was to start at (s).
        t: f64,
        /// The index of the first body whose state is not representable.
        body: usize,
    },
    /// At the start of the step, a body turns by more than [`MAX_TURN_PER_STEP`] within it: no method here
    /// resolves that (RK4's local error is already ~1% of the motion at one radian per step, and beyond its
    /// stability bound of 2.8 the result is noise, finite or not). The states are left as they were.
    #[error(
        "at t = {t}: body {body} turns {turn:.3} rad in the step dt = {dt} (angular velocity {angular_speed:.4e} \
         rad/s), more than {MAX_TURN_PER_STEP} rad per step; take a step below {limit:.3e}",
        limit = MAX_TURN_PER_STEP / angular_speed
    )]
    StepTooLarge {
        /// The time the refused step started at (s).
        t: f64,
        /// The refused step (s).
        dt: f64,
        /// The index of the first body that turns too far.
        body: usize,
        /// The angle it would turn through, `|ω| dt` (rad).
        turn: f64,
        /// Its angular speed `|ω|` at the start of the step (rad/s).
        angular_speed: f64,
    },
    /// A step failed in the constraints (they could not be solved or held together at a stage, or after the
    /// step) where a shorter step from the same state succeeds: the step is too large for the motion of the
    /// joints, or for stiff Baumgarte gains. The states are left as they were.
    #[error(
        "at t = {t}: the step dt = {dt} is too large for the constraints ({error}); a step of {works:.3e} succeeds"
    )]
    ConstraintStepTooLarge {
        /// The time the refused step started at (s).
        t: f64,
        /// The refused step (s).
        dt: f64,
        /// What went wrong in the constraints at the refused step.
        error: ConstraintError,
        /// The longest of dt/2, dt/4, … that succeeds from the same state (s).
        works: f64,
    },
    /// The step is too long for the Baumgarte feedback: its residuals decay at up to `rate` 1/s, which an explicit
    /// step longer than [`MAX_FEEDBACK_STEP`]`/rate` amplifies instead of damping (when the step is made).
    #[error(
        "at t = {t}: the step dt = {dt} is too large for the Baumgarte feedback, whose residuals decay at up to \
         {rate:.4e} 1/s; take a step below {limit:.3e} or lower the gains",
        limit = MAX_FEEDBACK_STEP / rate
    )]
    FeedbackStepTooLarge {
        /// The time the refused step started at (s).
        t: f64,
        /// The refused step (s).
        dt: f64,
        /// The feedback's fastest rate (1/s).
        rate: f64,
    },
    /// The step produced a NaN or infinite state: the step is too large for the motion, or a force or path
    /// returned NaN. The states are left as they were before the step.
    #[error(
        "the state is no longer finite (or beyond {MAX_COORDINATE:e}) at t = {t} (body {body}): the step is too large \
         for this system, or a force is not finite"
    )]
    NonFinite {
        /// The time the step was to reach (s).
        t: f64,
        /// The index of the first body whose state is not representable.
        body: usize,
    },
}

/// How far from 1 a start motor's rotor norm squared may be ([`StepError::NotARigidMotion`]): every step
/// renormalises to round-off, so a larger error is a motor the user wrote, not drift.
pub const MAX_ROTOR_NORM_ERROR: f64 = 1e-6;

/// The largest step, in units of the inverse feedback rate ([`Dynamics::feedback_rate`](crate::Dynamics::feedback_rate)), at which the explicit
/// methods still damp the Baumgarte feedback: RK4's stability region reaches 2.79 on the negative real axis and
/// 2.83 on the imaginary one, the higher-order tableaux a little further.
pub const MAX_FEEDBACK_STEP: f64 = 2.5;
