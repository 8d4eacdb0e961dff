//! Running a system of rigid bodies over time: recording every body at chosen times, calling an observer after
//! every step, and locating events.
//!
//! A [`Schedule`] fixes the step and the sample times: a grid (by default every 0.01 s, the grid of the reference
//! scenes), which the step must divide so every sample falls on a step, or any list of times
//! ([`Schedule::at_times`]), any step size. A sample between two steps is taken by a partial step from the
//! last step's state — the method's own solution at that time, of its order and on the group (motors stay
//! motors) — which does not change the steps that follow.
//!
//! A [`Plan`] adds to a schedule an observer called after every step, which may stop the run, and [`Event`]s:
//! scalar functions of the state whose zero crossings are located to round-off by partial steps (a pendulum's
//! turning points, a body point reaching a plane), with a direction filter, and optionally terminal.
//!
//! A system with joint limits ([`crate::limits`], `docs/limits.md`) has each limit watched like an event: a step is
//! cut where a limit's gap closes or its reaction stops pushing, located to round-off, the impact, hold or release
//! made there ([`Simulation::transitions`]), and the run continues from it.
//!
//! [`simulate`] is the one entry point, for free bodies, constrained bodies and mechanisms, with any
//! [`Integrator`]; it allocates once (the samples) and measures the CPU time of the stepping alone, for
//! work-precision comparisons.

use std::ops::ControlFlow;
use std::time::{Duration, Instant};

use nalgebra::{UnitQuaternion, Vector3};

use crate::algebra::Algebra;
use crate::integrate::{Integrator, StepError, Stepper};
use crate::limits::LimitTransition;
use crate::motion::Dynamics;
use crate::state::State;
use crate::step_control::{self, Controller, StepStatistics, Tolerance};

/// The default sample interval (s), that of the reference scenes.
pub const SAMPLE_INTERVAL: f64 = 0.01;

/// Samples reserved per body before a run; more are allocated as they are recorded.
const RESERVED_SAMPLES: usize = 1 << 14;

/// The most samples a run records (120 bytes each: 1.2 GB at this limit).
pub const MAX_SAMPLES: usize = 10_000_000;

/// How far `interval / dt` may be from an integer, relative to it: admits step sizes written in decimal
/// (0.01 / 1e-4 = 100.00000000000001) but not a step that misses the sample times.
const DIVISIBILITY_TOLERANCE: f64 = 1e-9;

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
    /// An adaptive run tried as many steps as its schedule allows ([`Schedule::with_step_limit`]) before its end.
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
    /// A limited joint starts beyond its limit, or a contact point below its plane, by more than [`AT_BOUND`].
    #[error("{constraint}: starts {depth:e} (rad or m) beyond its limit or below its plane")]
    BeyondLimit {
        /// The limited joint's or the contact's name.
        constraint: String,
        /// How far beyond its nearer bound or below its plane it starts (rad or m).
        depth: f64,
    },
    /// Impacts came ever closer together ([`TRANSITIONS_IN_A_ROW`] with no whole step between them) without coming
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

/// A schedule: the step, fixed or chosen by a tolerance, and the sample times (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    /// The fixed step, or the longest step of an adaptive schedule (its duration).
    dt: f64,
    /// The accuracy an adaptive schedule chooses its steps by; `None` for fixed steps.
    tolerance: Option<Tolerance>,
    /// The most steps (kept and refused) an adaptive run may try.
    step_limit: usize,
    samples: Samples,
    /// The time the run starts at (s); every time of the schedule is counted from it.
    start: f64,
}

#[derive(Clone, Debug, PartialEq)]
enum Samples {
    /// `intervals` sample intervals, each of `steps_per_sample` steps.
    Grid {
        sample_interval: f64,
        steps_per_sample: usize,
        intervals: usize,
    },
    /// Samples at these times (after the one at 0), steps on the grid `k·dt`.
    Times(Vec<f64>),
}

/// A sample time this close to the end of a step, relative to the step, is taken as the step's end rather than
/// by a partial step of a few ulps.
const SAME_TIME: f64 = 1e-9;

/// `whole / part` if it is an integer within [`DIVISIBILITY_TOLERANCE`].
fn whole_ratio(whole: f64, part: f64) -> Option<usize> {
    let ratio = whole / part;
    let rounded = ratio.round();
    (rounded >= 1.0 && (ratio - rounded).abs() <= DIVISIBILITY_TOLERANCE * rounded).then_some(rounded as usize)
}

fn positive(name: &'static str, value: f64) -> Result<f64, SimulationError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(SimulationError::NotPositive { name, value })
    }
}

impl Schedule {
    /// Steps of `dt` for `duration`, sampled every [`SAMPLE_INTERVAL`].
    ///
    /// ```
    /// use dynamics::{Schedule, SimulationError};
    ///
    /// let schedule = Schedule::new(1e-3, 0.5)?; // 1 ms steps for 0.5 s
    /// assert_eq!(schedule.sample_count(), 51); // every 10 ms, and t = 0
    /// assert_eq!((schedule.step_count(), schedule.steps_per_sample()), (500, Some(10)));
    /// // 3 ms steps would miss the 10 ms sample times.
    /// assert!(matches!(Schedule::new(3e-3, 0.5), Err(SimulationError::StepDoesNotDivideInterval { .. })));
    /// # Ok::<(), SimulationError>(())
    /// ```
    pub fn new(dt: f64, duration: f64) -> Result<Self, SimulationError> {
        Schedule::with_sample_interval(dt, duration, SAMPLE_INTERVAL)
    }

    /// Steps of `dt` for `duration`, sampled every `sample_interval`, which `dt` must divide; a duration that is
    /// not a whole number of intervals ends with a shorter one, sampled at its end.
    ///
    /// ```
    /// use dynamics::Schedule;
    ///
    /// let schedule = Schedule::with_sample_interval(1e-3, 2.0, 0.1)?; // s
    /// assert_eq!((schedule.sample_count(), schedule.step_count()), (21, 2000));
    /// assert_eq!(schedule.sample_time(5), 0.5); // s
    /// // 0.3 s does not divide 2 s: samples every 0.3 s up to 1.8 s, then at 2 s.
    /// let uneven = Schedule::with_sample_interval(1e-3, 2.0, 0.3)?;
    /// assert_eq!((uneven.sample_count(), uneven.sample_time(7)), (8, 2.0));
    /// assert!(Schedule::with_sample_interval(0.07, 2.0, 0.3).is_err()); // 0.07 s does not divide 0.3 s
    /// # Ok::<(), dynamics::SimulationError>(())
    /// ```
    pub fn with_sample_interval(dt: f64, duration: f64, sample_interval: f64) -> Result<Self, SimulationError> {
        let dt = positive("the step", dt)?;
        let duration = positive("the duration", duration)?;
        let interval = positive("the sample interval", sample_interval)?;
        // Counts beyond 2⁵³ are not exact in f64 (and would not finish anyway).
        if interval / dt > (1u64 << 53) as f64 || duration / interval >= MAX_SAMPLES as f64 {
            return Err(SimulationError::TooLong);
        }
        let steps_per_sample =
            whole_ratio(interval, dt).ok_or(SimulationError::StepDoesNotDivideInterval { dt, interval })?;
        let Some(intervals) = whole_ratio(duration, interval) else {
            // A last, shorter interval: samples at the whole intervals and at the end, reached by a partial step.
            let whole = (duration / interval).floor() as usize;
            let times = (1..=whole)
                .map(|k| k as f64 * interval)
                .chain(std::iter::once(duration));
            return Schedule::at_times(interval / steps_per_sample as f64, times);
        };
        // Step counts beyond 2⁵³ are not exact in f64 (and would not finish anyway).
        if intervals
            .checked_mul(steps_per_sample)
            .is_none_or(|steps| steps as f64 > (1u64 << 53) as f64)
        {
            return Err(SimulationError::TooLong);
        }
        Ok(Schedule {
            // The step actually taken: the interval over the whole number of steps in it.
            dt: interval / steps_per_sample as f64,
            tolerance: None,
            step_limit: usize::MAX,
            samples: Samples::Grid {
                sample_interval: interval,
                steps_per_sample,
                intervals,
            },
            start: 0.0,
        })
    }

    /// The same schedule starting at `start` (s) instead of 0: to continue a run from where another stopped (at an
    /// event, say) with the clock the forces, paths and events read.
    ///
    /// ```
    /// use dynamics::{simulate, Body, FreeBody, Method, Pga, Schedule, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let body = Body::sphere(1.0, 0.1)?;
    /// let start = State::<Pga>::from_world_twist(&body, Vector3::zeros(), &UnitQuaternion::identity(), Vector3::zeros(), Vector3::x());
    /// let later = Schedule::new(1e-3, 0.5)?.starting_at(2.0)?;
    /// let run = simulate(&FreeBody::new(body), &[start], Method::Rk4, &later)?;
    /// assert_eq!((run.body(0)[0].t, run.body(0).last().unwrap().t), (2.0, 2.5));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn starting_at(self, start: f64) -> Result<Self, SimulationError> {
        // The clock must still tell the steps apart: f64 times near `start` are spaced by its ulp.
        if !(start.is_finite() && f64::EPSILON * (start.abs() + self.duration()) <= 1e-6 * self.dt) {
            return Err(SimulationError::StartTime(start));
        }
        Ok(Schedule { start, ..self })
    }

    /// The time the run starts at (s).
    pub fn start(&self) -> f64 {
        self.start
    }

    /// Steps of `dt` (any size) on the grid `k·dt`, with samples at t = 0 and at each of `times` (finite,
    /// positive, increasing); the run ends at the last. A time between two steps is sampled by a partial step.
    ///
    /// ```
    /// use dynamics::{simulate, Body, FreeBody, Method, Pga, Schedule, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let body = Body::sphere(1.0, 0.1)?;
    /// let start = State::<Pga>::from_world_twist(&body, Vector3::zeros(), &UnitQuaternion::identity(), Vector3::zeros(), Vector3::x());
    /// let schedule = Schedule::at_times(0.03, [0.05, 0.1])?;
    /// let run = simulate(&FreeBody::new(body), &[start], Method::Rkmk4Body, &schedule)?;
    /// let x: Vec<f64> = run.body(0).iter().map(|s| s.position.x).collect();
    /// assert!((x[1] - 0.05).abs() < 1e-15 && (x[2] - 0.1).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn at_times(dt: f64, times: impl IntoIterator<Item = f64>) -> Result<Self, SimulationError> {
        let dt = positive("the step", dt)?;
        let times: Vec<f64> = times.into_iter().collect();
        for (index, &time) in times.iter().enumerate() {
            let previous = if index == 0 { 0.0 } else { times[index - 1] };
            if !(time.is_finite() && time > previous) {
                return Err(SimulationError::OutputTime { index, time });
            }
        }
        let duration = positive("the duration", times.last().copied().unwrap_or(0.0))?;
        if times.len() >= MAX_SAMPLES || duration / dt > (1u64 << 53) as f64 {
            return Err(SimulationError::TooLong);
        }
        Ok(Schedule {
            dt,
            tolerance: None,
            step_limit: usize::MAX,
            samples: Samples::Times(times),
            start: 0.0,
        })
    }

    /// Steps chosen by the error estimate of an embedded pair ([`crate::Method::Dopri5Body`],
    /// [`crate::Method::Dop853Body`]) to meet `tolerance`
    /// ([`crate::step_control`]), for `duration`, sampled every `sample_interval` (and at the end, if the interval
    /// does not divide the duration). Samples and events inside a step come from the method's continuous
    /// extension: they never shorten a step.
    ///
    /// A body spinning at 3 rad/s about a tilted axis for 2 s, to 1e-9: the orientation is right to about the
    /// tolerance, in far fewer steps than samples.
    ///
    /// ```
    /// use dynamics::{simulate, Body, FreeBody, Method, Pga, Schedule, State, Tolerance};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.1)?;
    /// let axis = Vector3::new(1.0, 2.0, 2.0) / 3.0;
    /// let start = State::<Pga>::from_world_twist(&ball, Vector3::zeros(), &UnitQuaternion::identity(), axis * 3.0, Vector3::zeros());
    /// let schedule = Schedule::adaptive(Tolerance::new(1e-9, 1e-9)?, 2.0, 0.01)?; // s
    /// let run = simulate(&FreeBody::new(ball), &[start], Method::Dopri5Body, &schedule)?;
    /// let exact = UnitQuaternion::from_scaled_axis(axis * 6.0);
    /// assert!(run.body(0).last().unwrap().orientation.angle_to(&exact) < 1e-8); // rad
    /// assert_eq!(run.body(0).len(), 201);
    /// assert!(run.statistics.accepted < 50);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn adaptive(tolerance: Tolerance, duration: f64, sample_interval: f64) -> Result<Self, SimulationError> {
        let duration = positive("the duration", duration)?;
        let interval = positive("the sample interval", sample_interval)?;
        if duration / interval >= MAX_SAMPLES as f64 {
            return Err(SimulationError::TooLong);
        }
        let whole = whole_ratio(duration, interval).unwrap_or((duration / interval).floor() as usize);
        let mut times: Vec<f64> = (1..=whole).map(|k| k as f64 * interval).collect();
        match times.last_mut() {
            Some(last) if (*last - duration).abs() <= SAME_TIME * interval => *last = duration,
            _ => times.push(duration),
        }
        Ok(Schedule {
            dt: duration,
            tolerance: Some(tolerance),
            step_limit: MAX_ADAPTIVE_STEPS,
            samples: Samples::Times(times),
            start: 0.0,
        })
    }

    /// The same adaptive schedule with at most `limit` steps tried (kept and refused; [`MAX_ADAPTIVE_STEPS`]
    /// unless set): a run that needs more ends with [`SimulationError::TooManySteps`] at the time it reached,
    /// instead of running on for hours at a tolerance too tight for its length.
    ///
    /// ```
    /// use dynamics::{simulate, Body, FreeBody, Method, Pga, Schedule, SimulationError, State, Tolerance};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let body = Body::new(1.0, Vector3::new(13.0, 10.0, 5.0) / 12.0)?; // kg, kg m²
    /// let tumbling = Vector3::new(0.1, 10.0, 0.0); // rad/s, near the middle axis
    /// let start = State::<Pga>::new(&body, Vector3::zeros(), &UnitQuaternion::identity(), tumbling, Vector3::zeros());
    /// let schedule = Schedule::adaptive(Tolerance::new(1e-12, 1e-12)?, 100.0, 0.1)?.with_step_limit(1000)?;
    /// let error = simulate(&FreeBody::new(body), &[start], Method::Dop853Body, &schedule).unwrap_err();
    /// assert!(matches!(error, SimulationError::TooManySteps { steps: 1000, .. }), "{error}");
    /// assert!(Schedule::new(1e-3, 1.0)?.with_step_limit(10).is_err()); // a fixed schedule's steps are known
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_step_limit(self, limit: usize) -> Result<Self, SimulationError> {
        if self.tolerance.is_none() || limit == 0 {
            let schedule = if self.tolerance.is_some() {
                "an adaptive"
            } else {
                "a fixed"
            };
            return Err(SimulationError::StepLimit { limit, schedule });
        }
        Ok(Schedule {
            step_limit: limit,
            ..self
        })
    }

    /// The most steps an adaptive run of this schedule may try (`usize::MAX` for fixed steps).
    pub fn step_limit(&self) -> usize {
        self.step_limit
    }

    /// The tolerance of an adaptive schedule; `None` for fixed steps.
    pub fn tolerance(&self) -> Option<Tolerance> {
        self.tolerance
    }

    /// The step: on a grid schedule the sample interval over the whole number of steps in it (equal to the
    /// requested step up to round-off); on an adaptive schedule the longest step allowed, its duration.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// On a grid schedule, the number of steps between samples.
    pub fn steps_per_sample(&self) -> Option<usize> {
        match self.samples {
            Samples::Grid { steps_per_sample, .. } => Some(steps_per_sample),
            Samples::Times(_) => None,
        }
    }

    /// The number of samples, including the initial one.
    pub fn sample_count(&self) -> usize {
        match &self.samples {
            Samples::Grid { intervals, .. } => intervals + 1,
            Samples::Times(times) => times.len() + 1,
        }
    }

    /// The number of whole steps (a schedule at given times may add partial ones); 0 for an adaptive schedule,
    /// whose steps are chosen as the run goes.
    pub fn step_count(&self) -> usize {
        if self.tolerance.is_some() {
            return 0;
        }
        match &self.samples {
            Samples::Grid {
                intervals,
                steps_per_sample,
                ..
            } => intervals * steps_per_sample,
            Samples::Times(_) => self.step_time_count(),
        }
    }

    /// Steps of `dt` to cover the duration, the last one possibly shortened; at least one, however short the
    /// duration (a sample at 1e-12 s with dt = 1e-3 is one step of 1e-12 s).
    fn step_time_count(&self) -> usize {
        let steps = self.duration() / self.dt;
        // A duration that is a whole number of steps up to round-off takes that many.
        let whole = steps.round();
        (if whole >= 1.0 && (steps - whole).abs() <= SAME_TIME * whole {
            whole
        } else {
            steps.ceil().max(1.0)
        }) as usize
    }

    /// Whether sample `sample` (at `time`) falls at the end of step `k`, which ends at `end` after `h`. On a grid by
    /// counting steps (exact, however many: the times' round-off grows past any tolerance of a tiny step); at given
    /// times within round-off of the end.
    fn sample_ends_step(&self, k: usize, sample: usize, (time, end, h): (f64, f64, f64)) -> bool {
        match &self.samples {
            Samples::Grid { steps_per_sample, .. } => k + 1 == sample * steps_per_sample,
            Samples::Times(_) => (time - end).abs() <= SAME_TIME * h + 4.0 * f64::EPSILON * end.abs(),
        }
    }

    /// The simulated time.
    pub fn duration(&self) -> f64 {
        match &self.samples {
            Samples::Grid {
                intervals,
                sample_interval,
                ..
            } => *intervals as f64 * sample_interval,
            Samples::Times(times) => times[times.len() - 1],
        }
    }

    /// The time of sample `index`: on a grid the start plus `index · interval`, computed from the index so it does not
    /// accumulate round-off (and equals the reference files' times).
    pub fn sample_time(&self, index: usize) -> f64 {
        self.start
            + match &self.samples {
                Samples::Grid { sample_interval, .. } => index as f64 * sample_interval,
                Samples::Times(times) => {
                    if index == 0 {
                        0.0
                    } else {
                        times[index - 1]
                    }
                }
            }
    }

    /// Step `k`: its start time and length. On a grid, `k` runs through the sample intervals (times computed from
    /// the interval's start, as the reference files' are); at given times, through `k·dt`, the last step ending on
    /// the last time.
    fn step(&self, k: usize) -> (f64, f64) {
        let (start, h) = self.step_from_start(k);
        (self.start + start, h)
    }

    /// [`Schedule::step`] counted from the schedule's start.
    fn step_from_start(&self, k: usize) -> (f64, f64) {
        match &self.samples {
            Samples::Grid {
                sample_interval,
                steps_per_sample,
                ..
            } => (
                (k / steps_per_sample) as f64 * sample_interval + (k % steps_per_sample) as f64 * self.dt,
                self.dt,
            ),
            Samples::Times(_) => {
                let start = k as f64 * self.dt;
                let end = if k + 1 == self.step_time_count() {
                    self.duration()
                } else {
                    (k + 1) as f64 * self.dt
                };
                (start, end - start)
            }
        }
    }
}

/// Which zero crossings of an [`Event`]'s function count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Crossing {
    /// From negative to zero or positive.
    Rising,
    /// From positive to zero or negative.
    Falling,
    /// In either direction.
    Either,
}

/// An event's function of the time and the states.
type EventFunction<'a, A> = Box<dyn FnMut(f64, &[State<A>]) -> f64 + 'a>;

/// A scalar function of the time and the states whose zero crossings [`simulate`] locates: after every step the
/// function is evaluated, and a sign change (in the chosen [`Crossing`] direction) is bracketed and closed by
/// partial steps from the step's start, or the method's continuous extension (regula falsi with the Illinois
/// modification), until the bracket is a few ulps of the time wide. With a continuous extension (the embedded
/// pairs) every step is also scanned at ten equal parts, so two crossings inside one step are both found unless they
/// are closer than a tenth of it. A terminal event ends the run at its crossing.
pub struct Event<'a, A: Algebra> {
    name: String,
    function: EventFunction<'a, A>,
    crossing: Crossing,
    terminal: bool,
}

impl<'a, A: Algebra> Event<'a, A> {
    /// Crossings of `function` in either direction, not terminal.
    ///
    /// A ball dropped from 1 m reaches the floor at `t = √(2h/g)`; the terminal event ends the run there.
    ///
    /// ```
    /// use dynamics::simulate::{Event, Plan, Stop};
    /// use dynamics::{simulate, Body, Force, FreeBody, Method, Pga, Schedule, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.1)?;
    /// let system = FreeBody::<Pga>::new(ball).with_force(Force::gravity());
    /// let start = State::new(&ball, Vector3::z(), &UnitQuaternion::identity(), Vector3::zeros(), Vector3::zeros());
    /// let height = |_t: f64, states: &[State<Pga>]| states[0].pose().0.z; // m
    /// let schedule = Schedule::new(1e-3, 1.0)?;
    /// let plan = Plan::new(&schedule).event(Event::new("floor", height).terminal());
    /// let run = simulate(&system, &[start], Method::Rkmk4Body, plan)?;
    /// assert!((run.events[0].t - (2.0 / 9.81f64).sqrt()).abs() < 1e-12); // s
    /// assert_eq!(run.stopped, Some(Stop::Event(0)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(name: impl Into<String>, function: impl FnMut(f64, &[State<A>]) -> f64 + 'a) -> Self {
        Event {
            name: name.into(),
            function: Box::new(function),
            crossing: Crossing::Either,
            terminal: false,
        }
    }

    /// Only crossings in this direction.
    pub fn crossing(mut self, crossing: Crossing) -> Self {
        self.crossing = crossing;
        self
    }

    /// The run ends at the first crossing.
    pub fn terminal(mut self) -> Self {
        self.terminal = true;
        self
    }

    /// The function's value, which must be finite: a NaN would hide every crossing.
    fn value(&mut self, t: f64, states: &[State<A>]) -> Result<f64, SimulationError> {
        let value = (self.function)(t, states);
        if value.is_finite() {
            Ok(value)
        } else {
            Err(SimulationError::EventNotFinite {
                name: self.name.clone(),
                t,
                value,
            })
        }
    }

    fn crosses(&self, before: f64, after: f64) -> bool {
        let rising = before < 0.0 && after >= 0.0;
        let falling = before > 0.0 && after <= 0.0;
        match self.crossing {
            Crossing::Rising => rising,
            Crossing::Falling => falling,
            Crossing::Either => rising || falling,
        }
    }
}

/// An observer: called after every step with the time and the states; `ControlFlow::Break` ends the run there.
type Observer<'a, A> = Box<dyn FnMut(f64, &[State<A>]) -> ControlFlow<()> + 'a>;

/// What a run records and watches: a [`Schedule`], [`Event`]s and an observer. A `&Schedule` converts into a plan
/// without either, so `simulate(…, &schedule)` is the plain run.
pub struct Plan<'a, A: Algebra> {
    schedule: &'a Schedule,
    events: Vec<Event<'a, A>>,
    observer: Option<Observer<'a, A>>,
}

impl<'a, A: Algebra> Plan<'a, A> {
    /// The schedule alone: no events and no observer.
    ///
    /// An observer that ends the run once the body has moved 5 cm:
    ///
    /// ```
    /// use std::ops::ControlFlow;
    /// use dynamics::simulate::{Plan, Stop};
    /// use dynamics::{simulate, Body, FreeBody, Method, Pga, Schedule, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.1)?;
    /// let still = UnitQuaternion::identity();
    /// let start = State::<Pga>::new(&ball, Vector3::zeros(), &still, Vector3::zeros(), Vector3::x()); // 1 m/s
    /// let schedule = Schedule::new(1e-3, 1.0)?; // 1000 steps of 1 ms at most
    /// let far_enough = |_t: f64, states: &[State<Pga>]| {
    ///     if states[0].pose().0.x > 0.05 - 1e-9 { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
    /// };
    /// let run = simulate(&FreeBody::new(ball), &[start], Method::Rk4, Plan::new(&schedule).observer(far_enough))?;
    /// assert_eq!((run.statistics.accepted, run.stopped), (50, Some(Stop::Observer))); // 1 m/s for 50 ms
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(schedule: &'a Schedule) -> Self {
        Plan {
            schedule,
            events: Vec::new(),
            observer: None,
        }
    }

    /// Locate this event's crossings (see [`Event`]).
    pub fn event(mut self, event: Event<'a, A>) -> Self {
        self.events.push(event);
        self
    }

    /// Call `observer` after every step (not after the partial steps that take samples or locate events); it
    /// ends the run by returning `ControlFlow::Break(())`.
    pub fn observer(mut self, observer: impl FnMut(f64, &[State<A>]) -> ControlFlow<()> + 'a) -> Self {
        self.observer = Some(Box::new(observer));
        self
    }
}

impl<'a, A: Algebra> From<&'a Schedule> for Plan<'a, A> {
    fn from(schedule: &'a Schedule) -> Self {
        Plan::new(schedule)
    }
}

/// A located event crossing: which event (its index in the plan and name), the time, and the states there.
#[derive(Clone, Debug, PartialEq)]
pub struct EventHit<A: Algebra> {
    /// The event's index in the plan, in the order the events were added.
    pub event: usize,
    /// The event's name.
    pub name: String,
    /// The time of the crossing (s): the first time found at or after it, within a few ulps.
    pub t: f64,
    /// The state of every body at that time.
    pub states: Vec<State<A>>,
}

/// Why a run ended before its schedule's end.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    /// The terminal event with this index crossed zero.
    Event(usize),
    /// The observer returned `ControlFlow::Break`.
    Observer,
}

/// One recorded instant of one body, in the reference files' terms (`docs/scenes.md` "Files") plus the system's
/// energy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The time of the sample (s).
    pub t: f64,
    /// Centre-of-mass position, world frame.
    pub position: Vector3<f64>,
    /// Orientation body → world.
    pub orientation: UnitQuaternion<f64>,
    /// Centre-of-mass velocity, world frame.
    pub velocity: Vector3<f64>,
    /// Angular velocity, world frame.
    pub angular_velocity: Vector3<f64>,
    /// [`Dynamics::energy`] of the whole system.
    pub energy: f64,
    /// The work done on the system since the start by its non-conservative forces (dampers, actuators,
    /// controllers, drives, a body's forces other than gravity; [`Dynamics::power`] integrated by the method):
    /// `energy − energy at the start` equals it up to the integration error (and the projection's drift
    /// corrections). The splitting methods integrate no power: with them it stays zero.
    pub work: f64,
}

impl Sample {
    /// The body's state at this sample (its mass properties `body`): to evaluate anything of a recorded run, such as
    /// a mechanism's joint positions.
    ///
    /// ```
    /// use dynamics::{simulate, Body, FreeBody, Method, Pga, Schedule, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let brick = Body::cuboid(1.0, Vector3::new(0.1, 0.2, 0.3))?;
    /// let spin = Vector3::new(0.0, 3.0, 0.1); // rad/s, world
    /// let start = State::<Pga>::from_world_twist(&brick, Vector3::zeros(), &UnitQuaternion::identity(), spin, Vector3::x());
    /// let run = simulate(&FreeBody::new(brick), &[start], Method::Rkmk4Body, &Schedule::new(1e-3, 0.1)?)?;
    /// let end = run.body(0).last().unwrap().state::<Pga>(&brick);
    /// assert!((end.world_velocity(&brick).linear - Vector3::x()).norm() < 1e-12); // m/s: nothing pushes it
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn state<A: Algebra>(&self, body: &crate::Body) -> State<A> {
        State::from_world_twist(
            body,
            self.position,
            &self.orientation,
            self.angular_velocity,
            self.velocity,
        )
    }
}

/// A finished run.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation<A: Algebra> {
    /// The samples of each body: `bodies[i][k]` is body i at sample k.
    pub bodies: Vec<Vec<Sample>>,
    /// The state of every body where the run ended: after the last step, or at a terminal event's crossing.
    pub final_state: Vec<State<A>>,
    /// The steps kept and refused, the evaluations of the equations of motion, the shortest and longest step.
    pub statistics: StepStatistics,
    /// CPU (wall) time spent stepping, excluding the recording of samples.
    pub stepping_time: Duration,
    /// The located event crossings, in time order.
    pub events: Vec<EventHit<A>>,
    /// The joint limits' impacts, holds and releases, in time order ([`crate::limits`]); at the start, those of
    /// joints that start on a bound.
    pub transitions: Vec<LimitTransition>,
    /// Why the run ended early, if it did; it then ends with a sample at that time.
    pub stopped: Option<Stop>,
}

impl<A: Algebra> Simulation<A> {
    /// The samples of body `index` (the only body of a single-body system is 0).
    pub fn body(&self, index: usize) -> &[Sample] {
        &self.bodies[index]
    }

    /// The system's energy at each sample.
    pub fn energies(&self) -> impl Iterator<Item = f64> + '_ {
        self.bodies[0].iter().map(|s| s.energy)
    }

    /// Stepping time per step.
    pub fn time_per_step(&self) -> Duration {
        Duration::from_secs_f64(self.stepping_time.as_secs_f64() / self.statistics.accepted.max(1) as f64)
    }
}

/// Appends the sample of every body at `t`: pose from the motor (theory §2), velocities from the body velocity
/// `Ḃ = M⁻¹[~RΩR]` turned into world axes.
fn record<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    (t, work): (f64, f64),
    states: &[State<A>],
    bodies: &mut [Vec<Sample>],
) {
    let energy = dynamics.energy(states);
    for (index, (state, samples)) in states.iter().zip(bodies).enumerate() {
        let (position, orientation) = state.pose();
        let velocity = A::screw_coordinates(state.body_velocity(dynamics.body(index)));
        samples.push(Sample {
            t,
            position,
            orientation,
            velocity: orientation * velocity.t,
            angular_velocity: orientation * velocity.l,
            energy,
            work,
        });
    }
}

/// A clock that runs only while it is stepping.
struct Stopwatch {
    since: Option<Instant>,
    total: Duration,
}

impl Stopwatch {
    fn start(&mut self) {
        self.since = Some(Instant::now());
    }

    fn stop(&mut self) {
        if let Some(since) = self.since.take() {
            self.total += since.elapsed();
        }
    }
}

/// The most steps an adaptive run tries unless its schedule says otherwise ([`Schedule::with_step_limit`]): a
/// hundred million, the most a scene file's fixed steps may be.
pub const MAX_ADAPTIVE_STEPS: usize = 100_000_000;

/// Event crossings are closed to a bracket this many ulps of the time wide.
const EVENT_ULPS: f64 = 4.0;
/// Regula falsi steps at most per crossing (the Illinois modification converges superlinearly; a bracket of
/// 1e-3 s closes to round-off in about ten).
const EVENT_ITERATIONS: usize = 200;

/// Where a method has a continuous extension, each step is scanned for an event's crossings at this many equal
/// parts (DifferentialEquations.jl's `interp_points` default is also ten): two crossings closer together than a part
/// cancel at its ends and are not seen.
const EVENT_SCAN_PARTS: usize = 10;

/// A located crossing: its time (s), the index of the event or limit, and the states there.
type Located<A> = (f64, usize, Vec<State<A>>);

/// A part of a step where an event crosses: `((a, value), (b, value))`, offsets into the step (s) and the event's
/// values there.
type Bracket = ((f64, f64), (f64, f64));

/// The states inside a step at which its crossings are looked for: with a continuous extension, the
/// [`EVENT_SCAN_PARTS`] parts of the step of length `h` (offsets into it, the states unprojected: a scan, not a
/// location); none without one. `scan` keeps its allocations from step to step.
fn scan_states<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    h: f64,
    scan: &mut Vec<(f64, Vec<State<A>>)>,
    probe: &mut [State<A>],
) -> Result<usize, SimulationError> {
    let mut count = 0;
    if stepper.integrator().estimate_order().is_some() {
        for part in 1..EVENT_SCAN_PARTS {
            let theta = part as f64 / EVENT_SCAN_PARTS as f64;
            if stepper.dense_output(theta, probe)?.is_none() {
                break;
            }
            match scan.get_mut(count) {
                Some((offset, states)) => {
                    *offset = theta * h;
                    states.copy_from_slice(probe);
                }
                None => scan.push((theta * h, probe.to_vec())),
            }
            count += 1;
        }
    }
    Ok(count)
}

/// The brackets of the crossings (by `crosses`) in the values `points`, `(offset into the step, value)` in order.
fn brackets(points: &[(f64, f64)], crosses: impl Fn(f64, f64) -> bool) -> Vec<Bracket> {
    points
        .windows(2)
        .filter(|pair| crosses(pair[0].1, pair[1].1))
        .map(|pair| (pair[0], pair[1]))
        .collect()
}

/// The crossing of the watched `value` within the part `((a, value), (b, value))` of the step of length `h` from
/// `(t, start)` (offsets into the step), where it goes from not zero to the other sign or zero: regula falsi on the
/// partial step length with the Illinois modification (the retained end's value halved when the same end is kept
/// twice), bisection where the secant leaves the bracket. With `from_bound`, a bracket starting at +0 (a one-sided
/// constraint that has just left its bound) is the value's return below `−AT_BOUND`, found by bisection until the
/// value has risen above zero. Returns the first time found at or after the crossing, within [`EVENT_ULPS`] of the
/// crossing, and the states there.
#[allow(clippy::too_many_arguments)]
fn locate<'d, A: Algebra, D: Dynamics<A> + ?Sized>(
    value: &mut impl FnMut(&mut Stepper<'d, A, D>, f64, &[State<A>]) -> Result<f64, SimulationError>,
    stepper: &mut Stepper<'d, A, D>,
    (t, h): (f64, f64),
    start: &[State<A>],
    end: &[State<A>],
    ((mut a, mut value_a), (mut b, mut value_b)): Bracket,
    probe: &mut [State<A>],
    from_bound: bool,
) -> Result<(f64, Vec<State<A>>), SimulationError> {
    let before = value_a;
    let mut at_b = end.to_vec();
    if b < h {
        state_inside(stepper, (t, h), b, start, &mut at_b)?;
    }
    let mut kept = 0i8;
    for _ in 0..EVENT_ITERATIONS {
        if value_b == 0.0 || b - a <= EVENT_ULPS * f64::EPSILON * (t + b).abs().max(h) {
            break;
        }
        // From +0 (a limit or contact that has just left its bound: `limit_crossing`) the crossing is where the value
        // comes back below −AT_BOUND, after it has risen: bisection, with values within AT_BOUND of zero counted as
        // still at the bound, until a value above zero gives the secant a bracket (the secant from a zero end would
        // stay at the start, where the constraint is leaving).
        let leaving = from_bound && value_a == 0.0;
        let mut m = if leaving {
            0.5 * (a + b)
        } else {
            b - value_b * (b - a) / (value_b - value_a)
        };
        if !(m > a && m < b) {
            m = 0.5 * (a + b);
        }
        state_inside(stepper, (t, h), m, start, probe)?;
        let value = value(stepper, t + m, probe)?;
        let crossed = if leaving {
            value < -AT_BOUND
        } else {
            value == 0.0 || value.signum() != before.signum()
        };
        if crossed {
            (b, value_b) = (m, value);
            at_b.copy_from_slice(probe);
            if kept == -1 {
                value_a *= 0.5;
            }
            kept = -1;
        } else {
            (a, value_a) = (m, if leaving { value.max(0.0) } else { value });
            if kept == 1 {
                value_b *= 0.5;
            }
            kept = 1;
        }
    }
    Ok((t + b, at_b))
}

/// The system's limit values at `(t, states)` into `values` ([`Dynamics::limit_values`]).
fn limit_values<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    t: f64,
    states: &[State<A>],
    values: &mut [f64],
) -> Result<(), SimulationError> {
    let dynamics = stepper.dynamics();
    dynamics
        .limit_values(t, states, stepper.workspace(), values)
        .map_err(|error| StepError::Constraint { t, error }.into())
}

/// The earliest limit transition in the step of length `h` from `(t, start)` to `end`, the limits' values at the
/// step's start being `before` and, on return, at its end `after`: the crossings of every limit's value to zero or
/// below, scanned at the step's ends and at `scan` inside it, the earliest part's located ([`locate`]). Returns its
/// time, the limit's index and the states there.
#[allow(clippy::too_many_arguments)]
fn limit_crossing<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    (t, h): (f64, f64),
    (start, end): (&[State<A>], &[State<A>]),
    (before, after): (&[f64], &mut [f64]),
    scan: &[(f64, Vec<State<A>>)],
    probe: &mut [State<A>],
) -> Result<Option<Located<A>>, SimulationError> {
    let mut values = vec![0.0; before.len()];
    // points[i]: (offset, value) of limit i along the step. A value within AT_BOUND of zero at the start is a joint
    // that has just left its bound (bounced or released) or the reaction of one just held: it starts at +0, and falls
    // only below -AT_BOUND, so that round-off about zero is no transition while a bounce too short for the scan to
    // see between two points (it is then past the bound) is one.
    let mut points: Vec<Vec<(f64, f64)>> = (before.iter())
        .map(|&value| vec![(0.0, if value.abs() <= AT_BOUND { 0.0 } else { value })])
        .collect();
    for (offset, states) in scan
        .iter()
        .map(|(offset, states)| (*offset, states.as_slice()))
        .chain([(h, end)])
    {
        limit_values(stepper, t + offset, states, &mut values)?;
        points
            .iter_mut()
            .zip(&values)
            .for_each(|(p, &value)| p.push((offset, value)));
    }
    after.copy_from_slice(&values);
    let falls = |before: f64, after: f64| (before > 0.0 && after <= 0.0) || (before == 0.0 && after < -AT_BOUND);
    let mut earliest: Option<Located<A>> = None;
    for (index, points) in points.iter().enumerate() {
        let Some(&bracket) = brackets(points, falls).first() else {
            continue;
        };
        if earliest.as_ref().is_some_and(|(time, ..)| t + bracket.0 .0 >= *time) {
            continue;
        }
        let mut watched = |stepper: &mut Stepper<'_, A, D>, time: f64, states: &[State<A>]| {
            limit_values(stepper, time, states, &mut values)?;
            Ok(values[index])
        };
        let (time, states) = locate(&mut watched, stepper, (t, h), start, end, bracket, probe, true)?;
        if earliest.as_ref().is_none_or(|(first, ..)| time < *first) {
            earliest = Some((time, index, states));
        }
    }
    Ok(earliest)
}

/// The state `offset` into the step of length `h` from `(t, start)`, into `probe`, and the work done from the step's
/// start to there: from the method's continuous extension where it has one (projected onto the constraints as a
/// step's end is), else by a partial step from the start.
fn state_inside<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    (t, h): (f64, f64),
    offset: f64,
    start: &[State<A>],
    probe: &mut [State<A>],
) -> Result<f64, SimulationError> {
    if let Some(work) = stepper.dense_output(offset / h, probe)? {
        let dynamics = stepper.dynamics();
        dynamics
            .after_step(t + offset, probe, stepper.workspace())
            .map_err(|error| StepError::Constraint { t, error })?;
        return Ok(work);
    }
    probe.copy_from_slice(start);
    stepper.step(t, probe, offset)?;
    Ok(stepper.last_work())
}

/// One kept step of an adaptive run from `(t, start)` into `next`, starting with the controller's proposal cut to
/// end at `finish`: steps whose error norm is above 1, or that fail for their size, are refused and retried
/// shorter. Returns the kept step's length.
fn adaptive_step<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    controller: &mut Controller,
    (t, finish): (f64, f64),
    (start, next): (&[State<A>], &mut [State<A>]),
    (statistics, step_limit): (&mut StepStatistics, usize),
) -> Result<f64, SimulationError> {
    // A step the turn check would refuse is not tried: at loose tolerances the error allows longer steps.
    let turn_limit = step_control::turn_limit(stepper.dynamics(), start);
    loop {
        let tried = statistics.accepted + statistics.rejected;
        if tried >= step_limit {
            return Err(SimulationError::TooManySteps { t, steps: tried });
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
            Err(error) => return Err(error.into()),
        };
        statistics.rejected += 1;
        // The clock resolves times near t to an ulp: a step of a few ulps no longer advances it.
        if controller.next <= 16.0 * f64::EPSILON * t.abs().max(finish.abs()).max(f64::MIN_POSITIVE) {
            return Err(SimulationError::StepSizeUnderflow {
                t,
                h: controller.next,
                reason: refused,
            });
        }
    }
}

/// Runs any system — a [`crate::FreeBody`], or a [`crate::Mechanism`] of one or more bodies with joints — from
/// `initial` (one state per body) with `integrator` on `plan`: a `&Schedule`, or a [`Plan`] with events and an
/// observer. Splitting methods apply to a single free body. Fails with the first step that fails: its error
/// names the joints involved and the time, or the time the state stopped being finite ([`crate::StepError`]).
///
/// The period of a pendulum from its turning points, where its angular velocity changes sign, against the
/// exact period `4√(I/mgd) K(sin(θ₀/2))` (K by the arithmetic-geometric mean):
///
/// ```
/// use dynamics::constraints::VirtualPower;
/// use dynamics::simulate::{Crossing, Event, Plan};
/// use dynamics::{simulate, Body, Force, Mechanism, Method, Pga, Schedule, State};
/// use nalgebra::{UnitQuaternion, Vector3};
///
/// let rod = Body::rod(1.0, 1.0, 1e-3)?; // 1 kg, 1 m, hinged at its top end
/// let top = (Vector3::new(0.0, 0.0, 0.5), Vector3::x());
/// let pendulum = Mechanism::<Pga>::single(rod)
///     .with_force(Force::gravity())?
///     .with_constraint(VirtualPower::hinge("pivot", top, (Vector3::zeros(), Vector3::x()))?)?;
/// let tilted = UnitQuaternion::from_scaled_axis(Vector3::new(0.3, 0.0, 0.0));
/// let hanging = tilted * Vector3::new(0.0, 0.0, -0.5);
/// let start = State::from_world_twist(&rod, hanging, &tilted, Vector3::zeros(), Vector3::zeros());
/// let swing = |_t: f64, states: &[State<Pga>]| states[0].world_velocity(&rod).angular.x;
/// let schedule = Schedule::new(1e-3, 5.0)?;
/// let plan = Plan::new(&schedule).event(Event::new("turning point", swing).crossing(Crossing::Rising));
/// let run = simulate(&pendulum, &[start], Method::Rkmk6Body, plan)?;
/// let period = run.events[1].t - run.events[0].t;
///
/// let (mut a, mut b) = (1.0, 0.15f64.cos()); // K(k) = π / 2 AGM(1, √(1 − k²)), k = sin 0.15
/// for _ in 0..6 {
///     (a, b) = (0.5 * (a + b), (a * b).sqrt());
/// }
/// let exact = 4.0 * (2.0 / (3.0 * 9.81f64)).sqrt() * std::f64::consts::PI / (2.0 * a);
/// assert!((period - exact).abs() < 1e-10 * exact, "{period} vs {exact}");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn simulate<'a, A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    initial: &[State<A>],
    integrator: impl Into<Integrator>,
    plan: impl Into<Plan<'a, A>>,
) -> Result<Simulation<A>, SimulationError> {
    let Plan {
        schedule,
        mut events,
        mut observer,
    } = plan.into();
    let expected = dynamics.body_count();
    if expected == 0 {
        return Err(SimulationError::NoBodies);
    }
    if initial.len() != expected {
        return Err(SimulationError::BodyCount {
            expected,
            got: initial.len(),
        });
    }
    let mut stepper = Stepper::new(dynamics, integrator)?;
    let start = schedule.start();
    let finish = start + schedule.duration();
    let mut controller = match schedule.tolerance() {
        None => None,
        Some(tolerance) => {
            let integrator = stepper.integrator();
            let Some(order) = integrator.estimate_order() else {
                return Err(SimulationError::NoErrorEstimate {
                    method: integrator.name(),
                });
            };
            let first = step_control::first_step(&tolerance, order, dynamics, initial, schedule.duration());
            Some(Controller::new(tolerance, order, first))
        }
    };
    let mut statistics = StepStatistics::default();
    let (mut state, mut next, mut probe) = (initial.to_vec(), initial.to_vec(), initial.to_vec());
    // Joint limits and contacts: refused beyond their bounds, and those that start on one make their transition
    // first (each may change others: a contact's impact holds every contact touching, so the values are read anew).
    let mut limits = vec![0.0; dynamics.limit_count()];
    // The limits' values at the end of the step taken, which are the next step's start values unless it is cut.
    let mut limits_after = limits.clone();
    let mut transitions = Vec::new();
    // Transitions since the last step that none cut short.
    let mut in_a_row = 0;
    if !limits.is_empty() {
        limit_values(&mut stepper, start, &state, &mut limits)?;
        if let Some((index, gap)) = (limits.iter().enumerate()).find(|(_, &gap)| gap < -AT_BOUND) {
            return Err(SimulationError::BeyondLimit {
                constraint: dynamics.limit_name(index).unwrap_or_default().to_owned(),
                depth: -gap,
            });
        }
        for index in 0..limits.len() {
            if limits[index] <= AT_BOUND {
                transition(&mut stepper, (index, start), &mut state, &mut transitions)?;
                limit_values(&mut stepper, start, &state, &mut limits)?;
            }
        }
    }
    let sample_count = schedule.sample_count();
    // Reserved up to a bound, grown as the samples come: a long run of many bodies must not ask for its whole
    // record before its first step (10⁷ samples of 64 bodies would be 77 GB).
    let reserved = sample_count.min(RESERVED_SAMPLES);
    let mut bodies: Vec<Vec<Sample>> = (0..expected).map(|_| Vec::with_capacity(reserved)).collect();
    record(dynamics, (start, 0.0), &state, &mut bodies);
    // The work done up to `state`'s time.
    let mut work = 0.0;
    let mut values = events
        .iter_mut()
        .map(|event| event.value(start, &state))
        .collect::<Result<Vec<f64>, _>>()?;
    let (mut hits, mut stopped) = (Vec::new(), None);
    let mut scan = Vec::new();
    let mut sample = 1;
    let mut last_recorded = start;
    let mut clock = Stopwatch {
        since: None,
        total: Duration::ZERO,
    };
    let mut now = start;
    // The fixed step being taken (its index), and where it ends when a limit's transition cut it.
    let (mut k, mut resume) = (0, None);
    clock.start();
    loop {
        let (t, h, end) = match controller.as_mut() {
            None => {
                let (t, h) = match resume {
                    Some(end) => (now, end - now),
                    None if k == schedule.step_count() => break,
                    None => schedule.step(k),
                };
                next.copy_from_slice(&state);
                stepper.step(t, &mut next, h)?;
                (t, h, resume.unwrap_or(t + h))
            }
            Some(_) if now >= finish => break,
            Some(controller) => {
                let h = adaptive_step(
                    &mut stepper,
                    controller,
                    (now, finish),
                    (&state, &mut next),
                    (&mut statistics, schedule.step_limit()),
                )?;
                // The last step ends on the run's end exactly.
                (now, h, if h == finish - now { finish } else { now + h })
            }
        };
        let step_work = stepper.last_work();
        let scanned = if events.is_empty() && limits.is_empty() {
            0
        } else {
            clock.stop();
            let count = scan_states(&mut stepper, h, &mut scan, &mut probe)?;
            clock.start();
            count
        };
        // A joint limit's transition ends the step where it happens (the motion after it is another).
        let cut = if limits.is_empty() {
            None
        } else {
            limit_crossing(
                &mut stepper,
                (t, h),
                (&state, &next),
                (&limits, &mut limits_after),
                &scan[..scanned],
                &mut probe,
            )?
        };
        let reached = cut.as_ref().map_or(end, |(time, ..)| *time);
        statistics.record_accepted(reached - t);
        // Events in (t, reached]: the earliest terminal one ends the run.
        let mut terminal: Option<Located<A>> = None;
        if !events.is_empty() {
            clock.stop();
            let mut found = Vec::new();
            for (index, event) in events.iter_mut().enumerate() {
                let after = event.value(end, &next)?;
                let mut points = vec![(0.0, values[index])];
                for (offset, states) in &scan[..scanned] {
                    points.push((*offset, event.value(t + offset, states)?));
                }
                points.push((h, after));
                for bracket in brackets(&points, |before, after| event.crosses(before, after)) {
                    let mut watched =
                        |_: &mut Stepper<'_, A, D>, time: f64, states: &[State<A>]| event.value(time, states);
                    let (time, states) = locate(
                        &mut watched,
                        &mut stepper,
                        (t, h),
                        &state,
                        &next,
                        bracket,
                        &mut probe,
                        false,
                    )?;
                    if time > reached {
                        continue;
                    }
                    if event.terminal && terminal.as_ref().is_none_or(|(first, ..)| time < *first) {
                        terminal = Some((time, index, states.clone()));
                    }
                    found.push(EventHit {
                        event: index,
                        name: event.name.clone(),
                        t: time,
                        states,
                    });
                }
                values[index] = after;
            }
            let limit = terminal.as_ref().map_or(reached, |(time, ..)| *time);
            found.retain(|hit| hit.t <= limit);
            found.sort_by(|x, y| x.t.total_cmp(&y.t));
            hits.extend(found);
            clock.start();
        }
        let limit = terminal.as_ref().map_or(reached, |(time, ..)| *time);
        let whole = cut.is_none() && terminal.is_none();
        // Samples in (t, limit]: at the step's end from its states, inside it by a partial step.
        while sample < sample_count {
            let time = schedule.sample_time(sample);
            let at_end = schedule.sample_ends_step(k, sample, (time, end, h));
            if at_end && whole {
                clock.stop();
                record(dynamics, (time, work + step_work), &next, &mut bodies);
            } else if !at_end && (time < limit || (cut.is_some() && time == limit)) {
                let work_inside = state_inside(&mut stepper, (t, h), time - t, &state, &mut probe)?;
                clock.stop();
                record(dynamics, (time, work + work_inside), &probe, &mut bodies);
            } else {
                break;
            }
            last_recorded = time;
            sample += 1;
            clock.start();
        }
        if let Some((time, index, states)) = terminal {
            clock.stop();
            if last_recorded != time {
                // The work up to the crossing: the state inside the step once more.
                let work_inside = state_inside(&mut stepper, (t, h), time - t, &state, &mut probe)?;
                record(dynamics, (time, work + work_inside), &states, &mut bodies);
            }
            state = states;
            stopped = Some(Stop::Event(index));
            break;
        }
        if let Some((time, index, states)) = cut {
            // The step's work up to the transition, then the transition, from the states there.
            work += state_inside(&mut stepper, (t, h), time - t, &state, &mut probe)?;
            state = states;
            in_a_row += 1;
            if in_a_row > TRANSITIONS_IN_A_ROW {
                return Err(SimulationError::Zeno {
                    constraint: dynamics.limit_name(index).unwrap_or_default().to_owned(),
                    t: time,
                    count: in_a_row,
                });
            }
            transition(&mut stepper, (index, time), &mut state, &mut transitions)?;
            limit_values(&mut stepper, time, &state, &mut limits)?;
            for (event, value) in events.iter_mut().zip(values.iter_mut()) {
                *value = event.value(time, &state)?;
            }
            now = time;
            resume = (controller.is_none() && time < end).then_some(end);
        } else {
            std::mem::swap(&mut state, &mut next);
            work += step_work;
            now = end;
            resume = None;
            std::mem::swap(&mut limits, &mut limits_after);
            in_a_row = 0;
        }
        if controller.is_none() && resume.is_none() {
            k += 1;
        }
        if let Some(observer) = observer.as_mut() {
            clock.stop();
            if observer(now, &state).is_break() {
                if last_recorded != now {
                    record(dynamics, (now, work), &state, &mut bodies);
                }
                stopped = Some(Stop::Observer);
                break;
            }
            clock.start();
        }
    }
    clock.stop();
    statistics.evaluations = stepper.evaluations();
    Ok(Simulation {
        bodies,
        final_state: state,
        statistics,
        stepping_time: clock.total,
        events: hits,
        transitions,
        stopped,
    })
}

/// A limited joint this close to a bound (rad or m) at the start is on it; further beyond it is an error.
pub const AT_BOUND: f64 = 1e-12;

/// More transitions than this with no whole step between them end the run ([`SimulationError::Zeno`]): impacts that
/// come ever closer together without coming to rest.
pub const TRANSITIONS_IN_A_ROW: usize = 10_000;

/// Limit `index`'s transition at `time` ([`Dynamics::limit_transition`]) on `state`, recorded in `transitions`.
fn transition<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    (index, time): (usize, f64),
    state: &mut [State<A>],
    transitions: &mut Vec<LimitTransition>,
) -> Result<(), SimulationError> {
    let dynamics = stepper.dynamics();
    let before = dynamics.energy(state);
    let changes = dynamics
        .limit_transition(index, time, state, stepper.workspace())
        .map_err(|error| StepError::Constraint { t: time, error })?;
    let energy_change = dynamics.energy(state) - before;
    // A hold and its release at once share the impact's energy change: it is the hold's.
    transitions.extend(
        changes
            .into_iter()
            .enumerate()
            .map(|(k, (changed, change))| LimitTransition {
                t: time,
                constraint: dynamics.limit_name(changed).unwrap_or_default().to_owned(),
                change,
                energy_change: if k == 0 { energy_change } else { 0.0 },
            }),
    );
    Ok(())
}
