//! Schedules: the step, fixed or chosen by a tolerance, and the sample times (see [`crate::simulate`]).

use crate::integrate::step_control::Tolerance;
use crate::simulate::error::{SimulationError, MAX_SAMPLES};

/// The default sample interval (s), that of the reference scenes.
pub const SAMPLE_INTERVAL: f64 = 0.01;

/// How far `interval / dt` may be from an integer, relative to it: admits step sizes written in decimal
/// (0.01 / 1e-4 = 100.00000000000001) but not a step that misses the sample times.
const DIVISIBILITY_TOLERANCE: f64 = 1e-9;

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
    /// positive, increasing, at least one); the run ends at the last. A time between two steps is sampled by a partial
    /// step.
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
        let duration = positive("the duration", *times.last().ok_or(SimulationError::NoOutputTimes)?)?;
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
    /// ([`crate::integrate::step_control`]), for `duration`, sampled every `sample_interval` (and at the end, if the interval
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
    pub(super) fn sample_ends_step(&self, k: usize, sample: usize, (time, end, h): (f64, f64, f64)) -> bool {
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
    pub(super) fn step(&self, k: usize) -> (f64, f64) {
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

/// The most steps an adaptive run tries unless its schedule says otherwise ([`Schedule::with_step_limit`]): a
/// hundred million, the most a scene file's fixed steps may be.
pub const MAX_ADAPTIVE_STEPS: usize = 100_000_000;
