//! Running a system of rigid bodies over time and recording every body on a sample grid (by default every
//! 0.01 s, the grid of the reference scenes, at times `k · 0.01`).
//!
//! A [`Schedule`] fixes the step and checks that it divides the sample interval, so every sample falls on a
//! step and nothing is interpolated (interpolation would add errors far above the references' ~1e-11 rad
//! floor). [`simulate`] is the one entry point, for free bodies, constrained bodies and mechanisms, with any
//! [`Integrator`]; it allocates once (the samples) and measures the CPU time of the stepping alone, for
//! work-precision comparisons.

use std::time::{Duration, Instant};

use nalgebra::{UnitQuaternion, Vector3};

use crate::algebra::Algebra;
use crate::integrate::{Integrator, StepError, Stepper};
use crate::motion::Dynamics;
use crate::state::State;

/// The default sample interval (s), that of the reference scenes.
pub const SAMPLE_INTERVAL: f64 = 0.01;

/// The most samples a run records (120 bytes each: 1.2 GB at this limit).
pub const MAX_SAMPLES: usize = 10_000_000;

/// How far `interval / dt` may be from an integer, relative to it: admits step sizes written in decimal
/// (0.01 / 1e-4 = 100.00000000000001) but not a step that misses the sample times.
const DIVISIBILITY_TOLERANCE: f64 = 1e-9;

/// Why a simulation could not run or did not finish.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SimulationError {
    #[error("{name} must be positive and finite, got {value}")]
    NotPositive { name: &'static str, value: f64 },
    #[error("the step {dt} does not divide the sample interval {interval} into whole steps")]
    StepDoesNotDivideInterval { dt: f64, interval: f64 },
    #[error("the sample interval {interval} does not divide the duration {duration} into whole samples")]
    IntervalDoesNotDivideDuration { interval: f64, duration: f64 },
    #[error(
        "the run would record more than {MAX_SAMPLES} samples or take more than {} steps",
        usize::MAX
    )]
    TooLong,
    /// The initial state does not have one entry per body of the system.
    #[error("the initial state has {got} bodies, the system has {expected}")]
    BodyCount { expected: usize, got: usize },
    /// A step failed (a reaction that could not be solved names its joints), or the integrator does not apply.
    #[error(transparent)]
    Step(#[from] StepError),
}

/// A fixed-step schedule: `intervals` sample intervals, each of `steps_per_sample` steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Schedule {
    sample_interval: f64,
    steps_per_sample: usize,
    intervals: usize,
}

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
    pub fn new(dt: f64, duration: f64) -> Result<Self, SimulationError> {
        Schedule::with_sample_interval(dt, duration, SAMPLE_INTERVAL)
    }

    /// Steps of `dt` for `duration`, sampled every `sample_interval`, which `dt` must divide, as the
    /// interval must divide the duration.
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
        let intervals = whole_ratio(duration, interval)
            .ok_or(SimulationError::IntervalDoesNotDivideDuration { interval, duration })?;
        if intervals.checked_mul(steps_per_sample).is_none() {
            return Err(SimulationError::TooLong);
        }
        Ok(Schedule {
            sample_interval: interval,
            steps_per_sample,
            intervals,
        })
    }

    /// The step actually taken: the sample interval over the whole number of steps in it (equal to the
    /// requested step up to round-off).
    pub fn dt(&self) -> f64 {
        self.sample_interval / self.steps_per_sample as f64
    }

    pub fn steps_per_sample(&self) -> usize {
        self.steps_per_sample
    }

    /// The number of samples, including the initial one.
    pub fn sample_count(&self) -> usize {
        self.intervals + 1
    }

    /// The total number of steps.
    pub fn step_count(&self) -> usize {
        self.intervals * self.steps_per_sample
    }

    /// The simulated time.
    pub fn duration(&self) -> f64 {
        self.intervals as f64 * self.sample_interval
    }

    /// The time of sample `index`: `index · interval`, computed from the index so it does not accumulate
    /// round-off (and equals the reference files' times).
    pub fn sample_time(&self, index: usize) -> f64 {
        index as f64 * self.sample_interval
    }
}

/// One recorded instant of one body, in the reference files' terms (SCENES.md "Files") plus the system's
/// energy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
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
}

/// A finished run.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation<A: Algebra> {
    /// The samples of each body: `bodies[i][k]` is body i at sample k.
    pub bodies: Vec<Vec<Sample>>,
    pub final_state: Vec<State<A>>,
    pub steps: usize,
    /// CPU (wall) time spent stepping, excluding the recording of samples.
    pub stepping_time: Duration,
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
        Duration::from_secs_f64(self.stepping_time.as_secs_f64() / self.steps.max(1) as f64)
    }
}

/// Appends the sample of every body at `t`: pose from the motor (SPEC §2), velocities from the body velocity
/// `Ḃ = M⁻¹[~RΩR]` turned into world axes.
fn record<A: Algebra, D: Dynamics<A> + ?Sized>(dynamics: &D, t: f64, states: &[State<A>], bodies: &mut [Vec<Sample>]) {
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
        });
    }
}

/// Runs any system — a [`crate::FreeBody`], or a [`crate::Mechanism`] of one or more bodies with joints — from
/// `initial` (one state per body) with `integrator` on `schedule`. Splitting methods apply to a single free
/// body. Fails with the first step that fails: its error names the joints involved and the time, or the time
/// the state stopped being finite ([`crate::StepError`]).
pub fn simulate<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    initial: &[State<A>],
    integrator: impl Into<Integrator>,
    schedule: &Schedule,
) -> Result<Simulation<A>, SimulationError> {
    let expected = dynamics.body_count();
    if initial.len() != expected {
        return Err(SimulationError::BodyCount {
            expected,
            got: initial.len(),
        });
    }
    let mut stepper = Stepper::new(dynamics, integrator)?;
    let dt = schedule.dt();
    let mut bodies: Vec<Vec<Sample>> = (0..expected)
        .map(|_| Vec::with_capacity(schedule.sample_count()))
        .collect();
    record(dynamics, 0.0, initial, &mut bodies);
    let mut state = initial.to_vec();
    let mut stepping_time = Duration::ZERO;
    for interval in 0..schedule.intervals {
        let start_time = schedule.sample_time(interval);
        let clock = Instant::now();
        for k in 0..schedule.steps_per_sample {
            stepper.step(start_time + k as f64 * dt, &mut state, dt)?;
        }
        stepping_time += clock.elapsed();
        record(dynamics, schedule.sample_time(interval + 1), &state, &mut bodies);
    }
    Ok(Simulation {
        bodies,
        final_state: state,
        steps: schedule.step_count(),
        stepping_time,
    })
}
