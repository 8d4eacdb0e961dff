//! The run: [`simulate`] steps a system through its schedule, records every body at the sample times, locates
//! events and one-sided transitions, and measures the CPU time of the stepping alone.

use std::time::{Duration, Instant};

use nalgebra::{UnitQuaternion, Vector3};

use crate::algebra::Algebra;
use crate::integrate::step_control::{self, adaptive_step, Controller, StepStatistics};
use crate::integrate::{Integrator, Stepper};
use crate::limits::LimitTransition;
use crate::motion::Dynamics;
use crate::simulate::error::SimulationError;
use crate::simulate::events::{events_in_step, scan_states, state_inside, EventHit, Located, Plan};
use crate::simulate::one_sided::{limit_crossing, limit_values, start_on_bounds, transition, TRANSITIONS_IN_A_ROW};
use crate::simulate::schedule::Schedule;
use crate::state::State;

/// Samples reserved per body before a run; more are allocated as they are recorded.
const RESERVED_SAMPLES: usize = 1 << 14;

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

/// The samples of a run as they are recorded: each body's, the index of the next sample time, and the time of the
/// last sample.
struct Samples {
    bodies: Vec<Vec<Sample>>,
    next: usize,
    count: usize,
    last: f64,
}

impl Samples {
    /// Room for `count` samples of `bodies` bodies, reserved up to a bound and grown as the samples come: a long run of
    /// many bodies must not ask for its whole record before its first step (10⁷ samples of 64 bodies would be 77 GB).
    fn new(bodies: usize, count: usize) -> Self {
        let reserved = count.min(RESERVED_SAMPLES);
        Samples {
            bodies: (0..bodies).map(|_| Vec::with_capacity(reserved)).collect(),
            next: 1,
            count,
            last: f64::NAN,
        }
    }

    /// Appends the sample of every body at `t` ([`record`]).
    fn record<A: Algebra, D: Dynamics<A> + ?Sized>(
        &mut self,
        dynamics: &D,
        (t, work): (f64, f64),
        states: &[State<A>],
    ) {
        record(dynamics, (t, work), states, &mut self.bodies);
        self.last = t;
    }

    /// The samples in the step `k` of length `h` from `(t, start)` to `(end, next)` that fall in `(t, limit]`: at the
    /// step's end from `next` when the step is `whole`, inside it by a partial step into `probe`; a step `cut` by a
    /// one-sided transition at `limit` records the sample there from inside. `work` is the work done up to `t`.
    #[allow(clippy::too_many_arguments)] // the step, the states and the clock the run holds
    fn in_step<A: Algebra, D: Dynamics<A> + ?Sized>(
        &mut self,
        stepper: &mut Stepper<'_, A, D>,
        schedule: &Schedule,
        (k, t, h, end): (usize, f64, f64, f64),
        (limit, whole, cut): (f64, bool, bool),
        (start, next): (&[State<A>], &[State<A>]),
        probe: &mut [State<A>],
        (work, step_work): (f64, f64),
        clock: &mut Stopwatch,
    ) -> Result<(), SimulationError> {
        while self.next < self.count {
            let time = schedule.sample_time(self.next);
            let at_end = schedule.sample_ends_step(k, self.next, (time, end, h));
            if at_end && whole {
                clock.stop();
                self.record(stepper.dynamics(), (time, work + step_work), next);
            } else if !at_end && (time < limit || (cut && time == limit)) {
                let work_inside = state_inside(stepper, (t, h), time - t, start, probe)?;
                clock.stop();
                self.record(stepper.dynamics(), (time, work + work_inside), probe);
            } else {
                break;
            }
            self.next += 1;
            clock.start();
        }
        Ok(())
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

/// The step-size controller of an adaptive schedule (`None` for a fixed one), its first step chosen at `initial`.
fn controller<A: Algebra, D: Dynamics<A> + ?Sized>(
    schedule: &Schedule,
    stepper: &Stepper<'_, A, D>,
    initial: &[State<A>],
) -> Result<Option<Controller>, SimulationError> {
    let Some(tolerance) = schedule.tolerance() else {
        return Ok(None);
    };
    let integrator = stepper.integrator();
    let Some(order) = integrator.estimate_order() else {
        return Err(SimulationError::NoErrorEstimate {
            method: integrator.name(),
        });
    };
    let first = step_control::first_step(&tolerance, order, stepper.dynamics(), initial, schedule.duration());
    Ok(Some(Controller::new(tolerance, order, first)))
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
    let mut controller = controller(schedule, &stepper, initial)?;
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
    start_on_bounds(&mut stepper, start, &mut state, &mut limits, &mut transitions)?;
    let mut samples = Samples::new(expected, schedule.sample_count());
    samples.record(dynamics, (start, 0.0), &state);
    // The work done up to `state`'s time.
    let mut work = 0.0;
    let mut values = events
        .iter_mut()
        .map(|event| event.value(start, &state))
        .collect::<Result<Vec<f64>, _>>()?;
    let (mut hits, mut stopped) = (Vec::new(), None);
    let mut scan = Vec::new();
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
            let step = (t, h, end, reached);
            terminal = events_in_step(
                &mut events,
                &mut values,
                &mut stepper,
                step,
                (&state, &next),
                &scan[..scanned],
                &mut probe,
                &mut hits,
            )?;
            clock.start();
        }
        let limit = terminal.as_ref().map_or(reached, |(time, ..)| *time);
        let whole = cut.is_none() && terminal.is_none();
        let step = (k, t, h, end);
        let reach = (limit, whole, cut.is_some());
        samples.in_step(
            &mut stepper,
            schedule,
            step,
            reach,
            (&state, &next),
            &mut probe,
            (work, step_work),
            &mut clock,
        )?;
        if let Some((time, index, states)) = terminal {
            clock.stop();
            if samples.last != time {
                // The work up to the crossing: the state inside the step once more.
                let work_inside = state_inside(&mut stepper, (t, h), time - t, &state, &mut probe)?;
                samples.record(dynamics, (time, work + work_inside), &states);
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
                if samples.last != now {
                    samples.record(dynamics, (now, work), &state);
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
        bodies: samples.bodies,
        final_state: state,
        statistics,
        stepping_time: clock.total,
        events: hits,
        transitions,
        stopped,
    })
}
