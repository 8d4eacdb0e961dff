//! Joint limits and contacts as a run sees them (`docs/limits.md`, `docs/contacts.md`): their values watched like
//! events, a step cut where one crosses, and the transition made there.

use crate::algebra::Algebra;
use crate::integrate::{StepError, Stepper};
use crate::limits::{LimitTransition, AT_BOUND};
use crate::motion::Dynamics;
use crate::simulate::error::SimulationError;
use crate::simulate::events::{brackets, locate, Bracket, Located};
use crate::state::State;

/// The system's limit values at `(t, states)` into `values` ([`Dynamics::limit_values`]).
pub(super) fn limit_values<A: Algebra, D: Dynamics<A> + ?Sized>(
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
pub(super) fn limit_crossing<A: Algebra, D: Dynamics<A> + ?Sized>(
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
    let mut earliest: Option<Located<A>> = None;
    for (index, points) in points.iter().enumerate() {
        let Some(bracket) = first_fall(points) else {
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

/// The first part of a step, between two of its `(offset, value)` points, where a one-sided value falls to its bound:
/// from above zero to zero or below, or from within AT_BOUND of zero (at the bound, inside the step as at its start)
/// to below −AT_BOUND. One that has left the bound and drifts down by round-off (−2e-13 at one point) falls where it
/// passes −AT_BOUND (−4e-12 at the next); that part starts at +0, so that [`locate`] finds it as one leaving the bound.
fn first_fall(points: &[(f64, f64)]) -> Option<Bracket> {
    let at_bound = |value: f64| value.abs() <= AT_BOUND;
    let falls = |before: f64, after: f64| (before > 0.0 && after <= 0.0) || (at_bound(before) && after < -AT_BOUND);
    let mut bracket = *brackets(points, falls).first()?;
    if at_bound(bracket.0 .1) && bracket.1 .1 < -AT_BOUND {
        bracket.0 .1 = 0.0;
    }
    Some(bracket)
}

/// More transitions than this with no whole step between them end the run ([`SimulationError::Zeno`]): impacts that
/// come ever closer together without coming to rest.
pub const TRANSITIONS_IN_A_ROW: usize = 10_000;

/// Limit `index`'s transition at `time` ([`Dynamics::limit_transition`]) on `state`, recorded in `transitions`.
pub(super) fn transition<A: Algebra, D: Dynamics<A> + ?Sized>(
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

/// The one-sided constraints at the run's start, whose values go into `limits`: an error for one beyond its bound by
/// more than [`AT_BOUND`], and the transition of each that starts on its bound, in order (each may change others: a
/// contact's impact holds every contact touching, so the values are read anew).
pub(super) fn start_on_bounds<A: Algebra, D: Dynamics<A> + ?Sized>(
    stepper: &mut Stepper<'_, A, D>,
    start: f64,
    state: &mut [State<A>],
    limits: &mut [f64],
    transitions: &mut Vec<LimitTransition>,
) -> Result<(), SimulationError> {
    if limits.is_empty() {
        return Ok(());
    }
    limit_values(stepper, start, state, limits)?;
    if let Some((index, gap)) = (limits.iter().enumerate()).find(|(_, &gap)| gap < -AT_BOUND) {
        return Err(SimulationError::BeyondLimit {
            constraint: stepper.dynamics().limit_name(index).unwrap_or_default().to_owned(),
            depth: -gap,
        });
    }
    for index in 0..limits.len() {
        if limits[index] <= AT_BOUND {
            transition(stepper, (index, start), state, transitions)?;
            limit_values(stepper, start, state, limits)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Falls to the bound: a plain crossing; a value starting at +0 that passes −AT_BOUND; one that leaves the bound
    /// by round-off inside the step and passes −AT_BOUND between two later points (located from +0); not round-off
    /// about zero, nor a value that stays above.
    #[test]
    fn values_falling_to_their_bound_are_bracketed() {
        assert_eq!(
            first_fall(&[(0.0, 1e-3), (1.0, -1e-9)]),
            Some(((0.0, 1e-3), (1.0, -1e-9)))
        );
        assert_eq!(
            first_fall(&[(0.0, 0.0), (1.0, -4e-12)]),
            Some(((0.0, 0.0), (1.0, -4e-12)))
        );
        assert_eq!(
            first_fall(&[(0.0, 0.0), (0.5, -2e-13), (1.0, -4e-12)]),
            Some(((0.5, 0.0), (1.0, -4e-12)))
        );
        assert_eq!(first_fall(&[(0.0, 0.0), (0.5, -2e-13), (1.0, -9e-13)]), None);
        assert_eq!(first_fall(&[(0.0, 1e-3), (0.5, 2e-3), (1.0, 1e-9)]), None);
    }
}
