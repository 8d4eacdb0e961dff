//! Why a simulation could not run or did not finish.

use crate::integrate::step_control::AdaptiveStepError;
use crate::integrate::StepError;

/// The most samples a run records (120 bytes each: 1.2 GB at this limit).
pub const MAX_SAMPLES: usize = 10_000_000;

/// Why a simulation could not run or did not finish.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SimulationError {
    /// A schedule's step, duration or sample interval is zero, negative, NaN or infinite.
    #[error("{name} must be positive and finite, got {value}")]
    NotPositive {
        /// Which quantity: "the step", "the duration" or "the sample interval".
        name: &'static str,
        /// The value that was refused.
        value: f64,
    },
    /// The sample interval is not a whole number of steps (to a relative 1e-9).
    #[error("the step {dt} does not divide the sample interval {interval} into whole steps")]
    StepDoesNotDivideInterval {
        /// The step that was refused (s).
        dt: f64,
        /// The sample interval (s).
        interval: f64,
    },
    /// The schedule would record more than [`MAX_SAMPLES`] samples, or count more steps than are exact in `f64`
    /// or fit in a `usize`.
    #[error(
        "the run would record more than {MAX_SAMPLES} samples or take more than {} steps",
        1u64 << 53
    )]
    TooLong,
    /// A step limit that is zero, or given to a fixed schedule (whose steps are known: its step and duration).
    #[error("a step limit must be at least 1 and is for adaptive schedules only, got {limit} for {schedule} schedule")]
    StepLimit {
        /// The refused limit.
        limit: usize,
        /// "an adaptive" or "a fixed".
        schedule: &'static str,
    },
    /// An adaptive run tried as many steps as its schedule allows ([`Schedule::with_step_limit`](crate::Schedule::with_step_limit)) before its end.
    #[error(
        "at t = {t}: the run has tried {steps} steps, the limit of its schedule; loosen the tolerance, shorten the \
         run or raise the limit"
    )]
    TooManySteps {
        /// The time the run had reached (s).
        t: f64,
        /// The steps tried, kept and refused.
        steps: usize,
    },
    /// The system has no bodies: there is nothing to simulate.
    #[error("the system has no bodies")]
    NoBodies,
    /// The initial state does not have one entry per body of the system.
    #[error("the initial state has {got} bodies, the system has {expected}")]
    BodyCount {
        /// The number of bodies of the system.
        expected: usize,
        /// The number of initial states given.
        got: usize,
    },
    /// An event's function returned NaN or an infinity (it would never cross zero, or cross it anywhere).
    #[error("event {name}: its function is {value} at t = {t}")]
    EventNotFinite {
        /// The event's name.
        name: String,
        /// The time it was evaluated at (s).
        t: f64,
        /// The value it returned.
        value: f64,
    },
    /// Output times must be finite, positive and increasing.
    #[error("output time {index} ({time}) is not finite, not positive or not after the one before")]
    OutputTime {
        /// The position of the refused time in the list.
        index: usize,
        /// The refused time (s).
        time: f64,
    },
    /// A schedule of output times was given none.
    #[error("no output times were given: the schedule needs at least one, the last the run's end")]
    NoOutputTimes,
    /// A schedule's start time is not finite, or so large that f64 times near it do not resolve the step to a
    /// millionth of it.
    #[error("the start time must be finite and small enough for the clock to resolve the step to 1e-6 of it, got {0}")]
    StartTime(f64),
    /// A step failed (a reaction that could not be solved names its joints), or the integrator does not apply.
    #[error(transparent)]
    Step(#[from] StepError),
    /// An adaptive schedule was given an integrator without an error estimate.
    #[error(
        "{method} has no error estimate to choose its steps by: an adaptive schedule needs an embedded pair \
         (DP5(4)-body, DOP853-body), or give a fixed step"
    )]
    NoErrorEstimate {
        /// The integrator's name.
        method: &'static str,
    },
    /// A limited joint starts beyond its limit, or a contact point below its plane, by more than [`AT_BOUND`](crate::limits::AT_BOUND).
    #[error("{constraint}: starts {depth:e} (rad or m) beyond its limit or below its plane")]
    BeyondLimit {
        /// The limited joint's or the contact's name.
        constraint: String,
        /// How far beyond its nearer bound or below its plane it starts (rad or m).
        depth: f64,
    },
    /// Impacts came ever closer together ([`TRANSITIONS_IN_A_ROW`](crate::simulate::TRANSITIONS_IN_A_ROW) with no whole step between them) without coming
    /// to rest: a restitution near 1 on a contact that cannot settle, or bounds that trap a joint.
    #[error(
        "{constraint}: {count} transitions in a row up to t = {t} s, with no whole step between them: the impacts do \
         not come to rest"
    )]
    Zeno {
        /// The limited joint's or the contact's name, at the last transition.
        constraint: String,
        /// The time of the last transition (s).
        t: f64,
        /// The transitions in a row.
        count: usize,
    },
    /// An adaptive run needed a step too short for the clock to advance by: the motion is singular there (a
    /// collision of the bodies' paths, a force without bound) or the tolerance is below what round-off allows.
    #[error("at t = {t}: the step the tolerance needs fell to {h:e} s, which the clock cannot resolve ({reason})")]
    StepSizeUnderflow {
        /// The time the step was to start at (s).
        t: f64,
        /// The step last tried (s).
        h: f64,
        /// Why the last step tried was refused.
        reason: String,
    },
}

impl From<AdaptiveStepError> for SimulationError {
    fn from(error: AdaptiveStepError) -> Self {
        match error {
            AdaptiveStepError::TooManySteps { t, steps } => SimulationError::TooManySteps { t, steps },
            AdaptiveStepError::StepSizeUnderflow { t, h, reason } => {
                SimulationError::StepSizeUnderflow { t, h, reason }
            }
            AdaptiveStepError::Step(error) => SimulationError::Step(error),
        }
    }
}
