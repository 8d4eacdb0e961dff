//! Events and the plan that carries them: scalar functions of the state whose zero crossings a run locates to
//! round-off by partial steps, with a direction filter and optionally terminal, and an observer called after every
//! step; the states inside a step they are located with.

use std::ops::ControlFlow;

use crate::algebra::Algebra;
use crate::integrate::{Integrator, StepError, Stepper};
use crate::limits::AT_BOUND;
use crate::motion::Dynamics;
use crate::simulate::error::SimulationError;
use crate::simulate::schedule::Schedule;
use crate::state::State;

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

/// A scalar function of the time and the states whose zero crossings [`simulate`](crate::simulate()) locates: after every step the
/// function is evaluated, and a sign change (in the chosen [`Crossing`] direction) is bracketed and closed by
/// partial steps from the step's start, or the method's continuous extension (regula falsi with the Illinois
/// modification), until the bracket is a few ulps of the time wide. With a continuous extension (the embedded
/// pairs) every step is also scanned at ten equal parts, so two crossings inside one step are both found unless they
/// are closer than a tenth of it. A terminal event ends the run at its crossing.
pub struct Event<'a, A: Algebra> {
    pub(super) name: String,
    pub(super) function: EventFunction<'a, A>,
    pub(super) crossing: Crossing,
    pub(super) terminal: bool,
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
    pub(super) fn value(&mut self, t: f64, states: &[State<A>]) -> Result<f64, SimulationError> {
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

    pub(super) fn crosses(&self, before: f64, after: f64) -> bool {
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
    pub(super) schedule: &'a Schedule,
    pub(super) events: Vec<Event<'a, A>>,
    pub(super) observer: Option<Observer<'a, A>>,
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
pub(super) type Located<A> = (f64, usize, Vec<State<A>>);

/// A part of a step where an event crosses: `((a, value), (b, value))`, offsets into the step (s) and the event's
/// values there.
pub(super) type Bracket = ((f64, f64), (f64, f64));

/// The states inside a step at which its crossings are looked for: with a continuous extension, the
/// [`EVENT_SCAN_PARTS`] parts of the step of length `h` (offsets into it, the states unprojected: a scan, not a
/// location); none without one. `scan` keeps its allocations from step to step.
pub(super) fn scan_states<A: Algebra, D: Dynamics<A> + ?Sized>(
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
pub(super) fn brackets(points: &[(f64, f64)], crosses: impl Fn(f64, f64) -> bool) -> Vec<Bracket> {
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
pub(super) fn locate<'d, A: Algebra, D: Dynamics<A> + ?Sized>(
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

/// The state `offset` into the step of length `h` from `(t, start)`, into `probe`, and the work done from the step's
/// start to there: from the method's continuous extension where it has one (projected onto the constraints as a
/// step's end is), else by a partial step from the start.
pub(super) fn state_inside<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    (t, h): (f64, f64),
    offset: f64,
    start: &[State<A>],
    probe: &mut [State<A>],
) -> Result<f64, SimulationError> {
    // A crossing a round-off into the step, lost in `t + offset`, is at its start.
    if offset <= 0.0 {
        probe.copy_from_slice(start);
        return Ok(0.0);
    }
    if let Some(work) = stepper.dense_output(offset / h, probe)? {
        let (dynamics, joint) = (stepper.dynamics(), matches!(stepper.integrator(), Integrator::Joint(_)));
        // As a step's end: in joint coordinates the joints hold by construction, and only held contacts are placed.
        let placed = if joint {
            dynamics.after_joint_step(t + offset, probe, stepper.workspace())
        } else {
            dynamics.after_step(t + offset, probe, stepper.workspace())
        };
        placed.map_err(|error| StepError::Constraint { t, error })?;
        return Ok(work);
    }
    probe.copy_from_slice(start);
    stepper.step(t, probe, offset)?;
    Ok(stepper.last_work())
}

/// The crossings of `events` in the step of length `h` from `(t, start)` to `(end, next)` that come no later than
/// `reached` (where a one-sided transition cut the step), appended to `hits` in time order, with each event's value
/// at the step's end put in `values`. Returns the earliest terminal crossing, after which no hit is kept.
#[allow(clippy::too_many_arguments)] // the step, its states and its scan, as `locate` takes them
pub(super) fn events_in_step<A: Algebra, D: Dynamics<A> + ?Sized>(
    events: &mut [Event<'_, A>],
    values: &mut [f64],
    stepper: &mut Stepper<'_, A, D>,
    (t, h, end, reached): (f64, f64, f64, f64),
    (start, next): (&[State<A>], &[State<A>]),
    scan: &[(f64, Vec<State<A>>)],
    probe: &mut [State<A>],
    hits: &mut Vec<EventHit<A>>,
) -> Result<Option<Located<A>>, SimulationError> {
    let mut terminal: Option<Located<A>> = None;
    let mut found = Vec::new();
    for (index, event) in events.iter_mut().enumerate() {
        let after = event.value(end, next)?;
        let mut points = vec![(0.0, values[index])];
        for (offset, states) in scan {
            points.push((*offset, event.value(t + offset, states)?));
        }
        points.push((h, after));
        for bracket in brackets(&points, |before, after| event.crosses(before, after)) {
            let mut watched = |_: &mut Stepper<'_, A, D>, time: f64, states: &[State<A>]| event.value(time, states);
            let (time, states) = locate(&mut watched, stepper, (t, h), start, next, bracket, probe, false)?;
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
    Ok(terminal)
}
