//! Step sizes chosen by the error the user asks for (`docs/dynamics.md`, "Adaptive steps"): a [`Tolerance`], the
//! error norm an embedded pair's estimate is measured in, and the step-size controller of an adaptive
//! [`crate::Schedule`].
//!
//! The estimate of a step is the difference of the pair's two solutions, taken where the body-momentum methods
//! compute: in the Lie algebra (the screw `Σ eᵢKᵢ` whose exponential takes the lower-order motor to the kept one)
//! and in the body momentum. Each body contributes four errors in the user's units: the turn of its orientation
//! (rad), the shift of its centre of mass (m), and the errors of its angular velocity (rad/s) and of its
//! centre-of-mass velocity (m/s), the momentum's error through the inverse inertia map. Each is divided by
//! `absolute + relative · size`, the size being the larger of the quantity at the step's two ends (none for the
//! orientation, whose tolerance is absolute: an angle has no scale to be relative to); the step's error is the
//! root mean square over every body's four ratios, and a step is kept when it is at most 1.

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::integrate::error::StepError;
use crate::integrate::error::MAX_TURN_PER_STEP;
use crate::integrate::lie_group::weighted_slopes;
use crate::integrate::methods::{Integrator, JointMethod, Method};
use crate::integrate::stepper::Stepper;
use crate::integrate::tableaux::{DOP853_ERROR_3, DOP853_ERROR_5, DORMAND_PRINCE_5_ERROR};
use crate::motion::Dynamics;
use crate::state::State;

/// The accuracy asked of an adaptive run (see the module docs for the units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    relative: f64,
    absolute: f64,
}

/// The smallest absolute tolerance: below it a body a metre from the origin is asked for less than a few ulps
/// of its position, which no step can deliver.
pub const MIN_ABSOLUTE_TOLERANCE: f64 = 1e-15;

/// Why a tolerance was refused.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ToleranceError {
    /// The relative tolerance is NaN, negative, or not below 1 (which asks for no accuracy at all).
    #[error("the relative tolerance must be at least 0 and below 1, got {0}")]
    Relative(f64),
    /// The absolute tolerance is NaN, infinite, or below [`MIN_ABSOLUTE_TOLERANCE`].
    #[error(
        "the absolute tolerance must be finite and at least {MIN_ABSOLUTE_TOLERANCE:e} (round-off of a position a \
         metre from the origin), got {0}"
    )]
    Absolute(f64),
}

impl Tolerance {
    /// A relative tolerance in [0, 1) and an absolute one of at least [`MIN_ABSOLUTE_TOLERANCE`], finite.
    ///
    /// ```
    /// use dynamics::integrate::step_control::{Tolerance, ToleranceError};
    ///
    /// let tight = Tolerance::new(1e-10, 1e-10)?; // relative, absolute
    /// assert_eq!((tight.relative(), tight.absolute()), (1e-10, 1e-10));
    /// assert_eq!(Tolerance::new(1e-6, 0.0).err(), Some(ToleranceError::Absolute(0.0)));
    /// # Ok::<(), ToleranceError>(())
    /// ```
    pub fn new(relative: f64, absolute: f64) -> Result<Self, ToleranceError> {
        if !(0.0..1.0).contains(&relative) {
            return Err(ToleranceError::Relative(relative));
        }
        if !(absolute.is_finite() && absolute >= MIN_ABSOLUTE_TOLERANCE) {
            return Err(ToleranceError::Absolute(absolute));
        }
        Ok(Tolerance { relative, absolute })
    }

    /// The relative tolerance.
    pub fn relative(&self) -> f64 {
        self.relative
    }

    /// The absolute tolerance (rad, m, rad/s and m/s alike).
    pub fn absolute(&self) -> f64 {
        self.absolute
    }

    /// `error / (absolute + relative · size)`.
    fn ratio(&self, error: f64, size: f64) -> f64 {
        error / (self.absolute + self.relative * size)
    }
}

/// The error norm of a step from `start` to `end` whose estimate per body is `(σ error, body momentum error)`:
/// the root mean square of the four ratios of every body (module docs).
pub(crate) fn error_norm<A: Algebra, D: Dynamics<A> + ?Sized>(
    tolerance: &Tolerance,
    dynamics: &D,
    (start, end): (&[State<A>], &[State<A>]),
    estimates: impl Iterator<Item = (A::Screw, A::Screw)>,
) -> f64 {
    let mut sum = 0.0;
    let mut count = 0;
    for (index, (sigma, momentum)) in estimates.enumerate() {
        let body = dynamics.body(index);
        // exp(σ) of a screw σ = −½ h Ḃ turns by 2|σ_l| and shifts the centre by 2|σ_t| to first order.
        let motion = A::screw_coordinates(sigma);
        let velocity = A::screw_coordinates(body.velocity::<A>(momentum));
        let speeds = |state: &State<A>| {
            let v = A::screw_coordinates(state.body_velocity(body));
            (v.l.norm(), v.t.norm())
        };
        let ((spin0, speed0), (spin1, speed1)) = (speeds(&start[index]), speeds(&end[index]));
        let distance = crate::motor::position_of::<A>(start[index].motor)
            .norm()
            .max(crate::motor::position_of::<A>(end[index].motor).norm());
        let ratios = [
            tolerance.ratio(2.0 * motion.l.norm(), 0.0),
            tolerance.ratio(2.0 * motion.t.norm(), distance),
            tolerance.ratio(velocity.l.norm(), spin0.max(spin1)),
            tolerance.ratio(velocity.t.norm(), speed0.max(speed1)),
        ];
        sum += ratios.iter().map(|r| r * r).sum::<f64>();
        count += ratios.len();
    }
    (sum / count.max(1) as f64).sqrt()
}

impl<A: Algebra, D: Dynamics<A> + ?Sized> Stepper<'_, A, D> {
    /// The error norm (the module docs) of the last successful step from `start` to `end`, for a method with
    /// an error estimate ([`Integrator::estimate_order`]); `None` for the others, or before a step. An embedded
    /// difference is the pair's two solutions apart in the Lie algebra, per body: the motor's `Σ eᵢKᵢ` and the body
    /// momentum's `h Σ eᵢ dΩ_b/dt` (`eᵢ` the difference of the two weights).
    pub(crate) fn error_norm(&self, tolerance: &Tolerance, start: &[State<A>], end: &[State<A>]) -> Option<f64> {
        let (_, dt) = self.last_step?;
        let zero = A::screw(ScrewCoordinates::default());
        let difference = |weights: &[f64]| {
            let estimates = (0..start.len()).map(|b| weighted_slopes(&self.buffers, weights, b, (dt, zero)));
            error_norm(tolerance, self.dynamics, (start, end), estimates)
        };
        // Hairer's combination for DOP853: the 5th-order difference, damped where the 3rd-order one says the
        // asymptotic regime is not reached; it falls as h⁸. A NaN stays a NaN (the step is refused).
        let hairer = |fifth: f64, third: f64| {
            let scale = (fifth * fifth + 0.01 * third * third).sqrt();
            if scale == 0.0 {
                0.0
            } else {
                fifth * fifth / scale
            }
        };
        match self.integrator {
            Integrator::General(Method::Dopri5Body) => Some(difference(&DORMAND_PRINCE_5_ERROR)),
            Integrator::General(Method::Dop853Body) => {
                Some(hairer(difference(&DOP853_ERROR_5), difference(&DOP853_ERROR_3)))
            }
            Integrator::Joint(JointMethod::Dop853) => {
                let joints = self.joints.as_ref()?;
                let difference = |weights: &[f64]| joints.error_norm(|e, size| tolerance.ratio(e, size), weights, dt);
                Some(hairer(difference(&DOP853_ERROR_5), difference(&DOP853_ERROR_3)))
            }
            _ => None,
        }
    }
}

/// The controller's safety factor: the next step aims at 0.9 of the step the estimate allows.
const SAFETY: f64 = 0.9;
/// A step grows at most fivefold and shrinks at most fivefold at a time.
const MAX_GROWTH: f64 = 5.0;
const MAX_SHRINK: f64 = 0.2;
/// The PI controller's exponents over the order k of the estimate: `h ← h·(1/err)^(0.7/k)·err_prev^(0.4/k)`
/// (Gustafsson's controller, in Hairer & Wanner, *Solving ODEs II*, §IV.2).
const PROPORTIONAL: f64 = 0.7;
const INTEGRAL: f64 = 0.4;

/// How many steps an adaptive run took and how long they were.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepStatistics {
    /// Steps kept (for a fixed-step run, every step).
    pub accepted: usize,
    /// Steps tried and refused because their error estimate was above the tolerance, or because they failed
    /// (too large for the motion or for the constraints).
    pub rejected: usize,
    /// Evaluations of the equations of motion, by the steps, the rejected steps and the partial steps that took
    /// samples or located events.
    pub evaluations: usize,
    /// The shortest and the longest step kept (s); the run's last step may be shortened to land on its end.
    pub smallest_step: f64,
    /// See `smallest_step`.
    pub largest_step: f64,
}

impl StepStatistics {
    pub(crate) fn record_accepted(&mut self, h: f64) {
        if self.accepted == 0 {
            (self.smallest_step, self.largest_step) = (h, h);
        }
        self.accepted += 1;
        self.smallest_step = self.smallest_step.min(h);
        self.largest_step = self.largest_step.max(h);
    }
}

/// The step-size controller of an adaptive run.
pub(crate) struct Controller {
    pub(crate) tolerance: Tolerance,
    /// The step to try next (s).
    pub(crate) next: f64,
    /// The error of the last kept step (at least 1e-4, so that a tiny one does not blow the next step up).
    previous_error: f64,
    /// Whether the last attempt was refused: the step after a refusal does not grow.
    after_rejection: bool,
    /// The order of the pair's error estimate ([`crate::Method::estimate_order`]).
    order: f64,
}

impl Controller {
    pub(crate) fn new(tolerance: Tolerance, order: u32, first: f64) -> Self {
        Controller {
            tolerance,
            next: first,
            previous_error: 1.0,
            after_rejection: false,
            order: f64::from(order),
        }
    }

    /// After a step of `h` with error norm `error`: whether to keep it, and the step to try next.
    pub(crate) fn judge(&mut self, h: f64, error: f64) -> bool {
        if error <= 1.0 {
            let factor = SAFETY
                * error.max(1e-10).powf(-PROPORTIONAL / self.order)
                * self.previous_error.powf(INTEGRAL / self.order);
            let ceiling = if self.after_rejection { 1.0 } else { MAX_GROWTH };
            self.next = h * factor.clamp(MAX_SHRINK, ceiling);
            self.previous_error = error.max(1e-4);
            self.after_rejection = false;
            true
        } else {
            // NaN lands here too: a step whose estimate is not finite is refused and shrunk as far as allowed.
            let factor = SAFETY * error.powf(-1.0 / self.order);
            self.next = h * if factor.is_nan() {
                MAX_SHRINK
            } else {
                factor.max(MAX_SHRINK)
            };
            self.after_rejection = true;
            false
        }
    }

    /// After a step of `h` that failed outright (too large for the motion or the constraints): shrink it, to
    /// `suggested` if the failure named a step that works.
    pub(crate) fn refuse(&mut self, h: f64, suggested: Option<f64>) {
        self.next = suggested.unwrap_or(h * MAX_SHRINK).min(h * 0.5);
        self.after_rejection = true;
    }
}

/// The first step to try: what the start's fastest motion ω allows for the tolerance at the estimate's `order` k,
/// which is the kept solution's order for both pairs (5, 8), so a step's local error is about `(ωh)^(k+1)` and
/// `h ≈ tol^{1/(k+1)}/ω`; capped at a fifth of a turn per step and at the run's length. Too long a guess costs one
/// refused step.
pub(crate) fn first_step<A: Algebra, D: Dynamics<A> + ?Sized>(
    tolerance: &Tolerance,
    order: u32,
    dynamics: &D,
    states: &[State<A>],
    duration: f64,
) -> f64 {
    let rate = states
        .iter()
        .enumerate()
        .map(|(index, state)| {
            let body = dynamics.body(index);
            let v = A::screw_coordinates(state.body_velocity(body));
            v.l.norm().max(v.t.norm() / body.smallest_gyration_radius())
        })
        .fold(0.0, f64::max);
    let guess = tolerance.absolute.powf(1.0 / f64::from(order + 1)) / rate;
    let turn = 0.2 / rate;
    // A body at rest: a hundredth of the run, from which the controller grows the step.
    if !(guess.is_finite() && guess > 0.0) {
        return 0.01 * duration;
    }
    guess.min(turn).min(duration)
}

/// The longest step from `states` that turns no body through more than 0.9 of [`MAX_TURN_PER_STEP`] at its
/// starting angular speed (the stepper refuses a step that turns one further); infinite when nothing turns.
pub(crate) fn turn_limit<A: Algebra, D: Dynamics<A> + ?Sized>(dynamics: &D, states: &[State<A>]) -> f64 {
    let fastest = (states.iter().enumerate())
        .map(|(index, state)| A::screw_coordinates(state.body_velocity(dynamics.body(index))).l.norm())
        .fold(0.0, f64::max);
    0.9 * MAX_TURN_PER_STEP / fastest
}

/// Why an adaptive run could not keep a step: its schedule's step limit, a step too short for the clock, or a
/// failed step that a shorter one does not cure ([`crate::SimulationError`] reports each).
#[derive(Debug)]
pub(crate) enum AdaptiveStepError {
    TooManySteps { t: f64, steps: usize },
    StepSizeUnderflow { t: f64, h: f64, reason: String },
    Step(StepError),
}

/// One kept step of an adaptive run from `(t, start)` into `next`, starting with the controller's proposal cut to
/// end at `finish`: steps whose error norm is above 1, or that fail for their size, are refused and retried
/// shorter. Returns the kept step's length.
pub(crate) fn adaptive_step<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    controller: &mut Controller,
    (t, finish): (f64, f64),
    (start, next): (&[State<A>], &mut [State<A>]),
    (statistics, step_limit): (&mut StepStatistics, usize),
) -> Result<f64, AdaptiveStepError> {
    // A step the turn check would refuse is not tried: at loose tolerances the error allows longer steps.
    let turn_limit = turn_limit(stepper.dynamics(), start);
    loop {
        let tried = statistics.accepted + statistics.rejected;
        if tried >= step_limit {
            return Err(AdaptiveStepError::TooManySteps { t, steps: tried });
        }
        let h = controller.next.min(turn_limit).min(finish - t);
        next.copy_from_slice(start);
        let refused = match stepper.step(t, next, h) {
            Ok(()) => {
                let error = stepper
                    .error_norm(&controller.tolerance, start, next)
                    .unwrap_or(f64::INFINITY);
                if controller.judge(h, error) {
                    return Ok(h);
                }
                format!("its error is {error:.3e} times the tolerance")
            }
            Err(error @ StepError::ConstraintStepTooLarge { works, .. }) => {
                controller.refuse(h, Some(works));
                error.to_string()
            }
            Err(
                error @ (StepError::StepTooLarge { .. }
                | StepError::FeedbackStepTooLarge { .. }
                | StepError::NonFinite { .. }),
            ) => {
                controller.refuse(h, None);
                error.to_string()
            }
            Err(error) => return Err(AdaptiveStepError::Step(error)),
        };
        statistics.rejected += 1;
        // The clock resolves times near t to an ulp: a step of a few ulps no longer advances it.
        if controller.next <= 16.0 * f64::EPSILON * t.abs().max(finish.abs()).max(f64::MIN_POSITIVE) {
            return Err(AdaptiveStepError::StepSizeUnderflow {
                t,
                h: controller.next,
                reason: refused,
            });
        }
    }
}
