//! Running a system over time and recording it on the reference scenes' sample grid (SCENES.md: every
//! 0.01 s, at times `k · 0.01`).
//!
//! A [`Schedule`] fixes the step and checks that it divides the sample interval, so every sample falls on a
//! step and nothing is interpolated (interpolation would add errors far above the references' ~1e-11 rad
//! floor). The loop allocates once (the sample vector) and measures the CPU time of the stepping alone, for
//! work-precision comparisons.

use std::time::{Duration, Instant};

use nalgebra::{UnitQuaternion, Vector3};

use crate::algebra::Algebra;
use crate::integrate::{step, step_free_body, step_splitting, Integrator, KineticSplitting, Method, SplittingError};
use crate::motion::{Dynamics, FreeBody};
use crate::state::State;

/// The sample interval of the reference scenes (s).
pub const SAMPLE_INTERVAL: f64 = reference::scenes::SAMPLE_INTERVAL;

/// The most samples a run records (120 bytes each: 1.2 GB at this limit).
pub const MAX_SAMPLES: usize = 10_000_000;

/// How far `interval / dt` may be from an integer, relative to it: admits step sizes written in decimal
/// (0.01 / 1e-4 = 100.00000000000001) but not a step that misses the sample times.
const DIVISIBILITY_TOLERANCE: f64 = 1e-9;

/// Why a simulation could not run or did not finish.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
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
    #[error("the state is no longer finite at t = {t} (the step is too large for this system)")]
    NonFinite { t: f64 },
    #[error(transparent)]
    Splitting(#[from] SplittingError),
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

/// One recorded instant, in the reference files' terms (SCENES.md "Files") plus the energy.
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
    /// [`Dynamics::energy`].
    pub energy: f64,
}

/// A finished run.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation<A: Algebra> {
    pub samples: Vec<Sample>,
    pub final_state: State<A>,
    pub steps: usize,
    /// CPU (wall) time spent stepping, excluding the recording of samples.
    pub stepping_time: Duration,
}

impl<A: Algebra> Simulation<A> {
    /// The samples as a reference trajectory (without the energies), for the metrics of the `reference`
    /// crate. The sample times always increase, so this fails only on an empty record, which `simulate`
    /// never returns.
    pub fn trajectory(&self) -> Result<reference::Trajectory, reference::TrajectoryError> {
        reference::Trajectory::new(
            self.samples
                .iter()
                .map(|s| reference::Sample {
                    t: s.t,
                    position: s.position,
                    orientation: s.orientation,
                    velocity: s.velocity,
                    angular_velocity: s.angular_velocity,
                })
                .collect(),
        )
    }

    /// Stepping time per step.
    pub fn time_per_step(&self) -> Duration {
        Duration::from_secs_f64(self.stepping_time.as_secs_f64() / self.steps.max(1) as f64)
    }
}

/// The sample of `state` at `t`: pose from the motor (SPEC §2), velocities from the body velocity Ḃ of the
/// system's rates turned into world axes.
fn sample<A: Algebra, D: Dynamics<A> + ?Sized>(dynamics: &D, t: f64, state: &State<A>) -> Sample {
    let (position, orientation) = state.pose();
    let velocity = A::screw_coordinates(dynamics.rates(t, state).body_velocity);
    Sample {
        t,
        position,
        orientation,
        velocity: orientation * velocity.t,
        angular_velocity: orientation * velocity.l,
        energy: dynamics.energy(state),
    }
}

fn is_finite<A: Algebra>(state: &State<A>) -> bool {
    let motor = A::motor_coordinates(state.motor);
    let momentum = A::screw_coordinates(state.momentum);
    motor.scalar.is_finite()
        && motor.pseudoscalar.is_finite()
        && motor.l.iter().chain(motor.t.iter()).all(|x| x.is_finite())
        && momentum.l.iter().chain(momentum.t.iter()).all(|x| x.is_finite())
}

/// The loop shared by all integrators: `advance(t, state, dt)` takes one step.
fn run<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    initial: State<A>,
    schedule: &Schedule,
    mut advance: impl FnMut(f64, &State<A>, f64) -> State<A>,
) -> Result<Simulation<A>, SimulationError> {
    let dt = schedule.dt();
    let mut samples = Vec::with_capacity(schedule.sample_count());
    samples.push(sample(dynamics, 0.0, &initial));
    let mut state = initial;
    let mut stepping_time = Duration::ZERO;
    for interval in 0..schedule.intervals {
        let start_time = schedule.sample_time(interval);
        let clock = Instant::now();
        for k in 0..schedule.steps_per_sample {
            state = advance(start_time + k as f64 * dt, &state, dt);
        }
        stepping_time += clock.elapsed();
        let t = schedule.sample_time(interval + 1);
        if !is_finite(&state) {
            return Err(SimulationError::NonFinite { t });
        }
        samples.push(sample(dynamics, t, &state));
    }
    Ok(Simulation {
        samples,
        final_state: state,
        steps: schedule.step_count(),
        stepping_time,
    })
}

/// Runs any system with a general method.
pub fn simulate<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    initial: State<A>,
    method: Method,
    schedule: &Schedule,
) -> Result<Simulation<A>, SimulationError> {
    run(dynamics, initial, schedule, |t, state, dt| {
        step(method, dynamics, t, state, dt)
    })
}

/// Runs a free body with any integrator (general methods through [`step_free_body`]); splitting methods need
/// forces of the configuration only.
pub fn simulate_free_body<A: Algebra>(
    system: &FreeBody<A>,
    initial: State<A>,
    integrator: Integrator,
    schedule: &Schedule,
) -> Result<Simulation<A>, SimulationError> {
    match integrator {
        Integrator::General(method) => run(system, initial, schedule, |t, state, dt| {
            step_free_body(method, system, t, state, dt)
        }),
        Integrator::Splitting(method) => {
            let splitting = KineticSplitting::new(system)?;
            run(system, initial, schedule, |t, state, dt| {
                step_splitting(method, &splitting, t, state, dt)
            })
        }
    }
}
