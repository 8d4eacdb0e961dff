//! A contact's impact (docs/contacts.md "Impact" and "Friction"): every contact touching its plane takes an impulse
//! through the kinetic metric, the other held relations kept. Along the normal Newton's law with complementarity:
//! each pushes (≥ 0) and leaves at `e` times the speed it met the plane with, or pushes nothing and leaves faster.
//! Along the plane Coulomb's law: a contact sticks (its slip after is zero) while its friction impulse is inside the
//! cone `|P_t| ≤ μ_s P_n`, else slides, its friction impulse `−μ P_n ŝ` opposing the slip ŝ the impact meets (or,
//! for a contact that meets the plane without slip, the sticking impulse the cone could not hold), and sticks if that
//! would reverse its slip. The modes are found by active sets; an impact whose restitution with friction would add
//! energy has its restitution lowered until it adds none.

use nalgebra::{DMatrix, DVector, Vector3};

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::contacts::{Friction, TOUCHING};
use crate::eigen::SingularValues;
use crate::limits::{Bound, LimitChange, REST_SPEED};
use crate::mechanism::articulated::REPEATED_ROW;
use crate::mechanism::contacts::stack;
use crate::mechanism::friction::{tangent_basis, STOP_SPEED};
use crate::mechanism::model::{Mechanism, MechanismWorkspace};
use crate::mechanism::parts::{PointDirection, Slip};
use crate::mechanism::polyhedra::outside;
use crate::state::State;

/// The relative size below which an impulse counts as zero in the contacts' complementarity (pushes are ≥ 0, speeds
/// after an impact ≥ their targets, friction inside its cone).
const COMPLEMENTARITY: f64 = 1e-12;

/// An impact may add energy up to this, relative to the energy its impulses move, before its restitution is lowered:
/// round-off of an elastic impact.
const ENERGY_ROUND_OFF: f64 = 1e-10;

/// A contact on its plane moving off it slower than this (m/s) is at rest on it: round-off of a motion along the
/// plane (a block started sliding on a floor).
pub(super) const AT_REST: f64 = 1e-12;

/// Contacts in one impact at most: the active sets cost the cube of their number per pass.
pub const MAX_CONTACTS_PER_IMPACT: usize = 256;

/// A contact's mode in an impact.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    /// No impulse.
    Out,
    /// A normal impulse, and a friction impulse opposing the slip along `direction` (zero without friction).
    Sliding { direction: Vector3<f64> },
    /// A normal impulse and a friction impulse that stops the slip.
    Sticking,
}

/// A contact's part in an impact: its normal row's index among the rows, its tangential rows' if it has friction, its
/// friction, its plane's tangent basis and its speed target after.
struct Participant {
    normal: usize,
    tangential: Option<usize>,
    friction: Friction,
    basis: [Vector3<f64>; 2],
    target: f64,
}

impl Participant {
    /// The mode impulses `p` show: none pushing, out; inside the cone, sticking; on it, sliding against its friction.
    fn mode_of(&self, p: &DVector<f64>) -> Mode {
        let push = p[self.normal];
        if push <= 0.0 {
            return Mode::Out;
        }
        let Some(row) = self.tangential else {
            return Mode::Sliding {
                direction: Vector3::zeros(),
            };
        };
        let friction = self.basis[0] * p[row] + self.basis[1] * p[row + 1];
        if friction.norm() < self.friction.stiction() * push * (1.0 - CONE_EDGE) {
            Mode::Sticking
        } else {
            Mode::Sliding {
                direction: -friction.normalize(),
            }
        }
    }

    /// The mode a contact takes when it enters the impact's active set. Friction opposes the slip the impact meets: a
    /// contact slipping before slides along its slip, one at rest sticks. (Started sticking, a box landing flat while
    /// moving along the floor would need pulls to hold its corners' friction, and the pulling ones would leave first;
    /// a corner joining a tumbling box's impact sticking can pull where sliding it pushes.)
    fn entering(&self, rows: &ImpactRows<'_>) -> Mode {
        let Some(row) = self.tangential else {
            return Mode::Sliding {
                direction: Vector3::zeros(),
            };
        };
        let slip = self.basis[0] * rows.before[row] + self.basis[1] * rows.before[row + 1];
        let speed = slip.norm();
        if speed > STOP_SPEED {
            Mode::Sliding {
                direction: slip / speed,
            }
        } else {
            Mode::Sticking
        }
    }
}

/// An impact's rows: the Gram matrix `S M⁻¹ Sᵀ` and the speeds before, for the stacked rows S (normal rows,
/// tangential rows, equalities).
struct ImpactRows<'r> {
    gram: &'r DMatrix<f64>,
    before: &'r DVector<f64>,
    /// The first equality row.
    equalities: usize,
}

/// The impulses of an impact on every row and the speeds after.
struct Outcome {
    impulses: DVector<f64>,
    after: DVector<f64>,
}

impl<A: Algebra> Mechanism<A> {
    /// A contact's impact: contact `contact`, every free contact within [`TOUCHING`] of its plane and not moving away
    /// from it, and every held contact take impulses (see the module docs). Contacts leaving slower than
    /// [`REST_SPEED`] are held, sticking if their slip after is below the stop speed, else sliding; held ones that
    /// leave are released. None, if contact `contact` leaves its plane faster than `leaving` (m/s): [`AT_REST`] for
    /// a located crossing, [`REST_SPEED`] for a contact handed a load at rest ([`Mechanism::hand_over`]), which may
    /// leave its plane at a round-off.
    pub(super) fn contact_impact(
        &self,
        (contact, leaving): (usize, f64),
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        let contact = workspace.repeats[contact].unwrap_or(contact);
        if self.contact_motion(contact, states).1 > leaving {
            return Ok(Vec::new());
        }
        let first = self.limits.len();
        // The contacts in the impact: (contact index, was held).
        let mut involved = Vec::new();
        for c in 0..self.contacts.len() {
            let held = workspace.held[first + c].is_some();
            let repeat = workspace.repeats[c].is_some();
            if repeat || (!held && c != contact && self.contacts[c].switching && !workspace.watched[c]) {
                continue;
            }
            let (height, speed) = self.contact_motion(c, states);
            // A switching contact's gap may have jumped below zero (docs/contacts.md "Edges"): that is no touch.
            let below = self.contacts[c].switching && height < -TOUCHING;
            let touching = height <= TOUCHING && speed <= AT_REST && !below;
            // A switching contact touching outside its face or edges is not a contact (docs/contacts.md "Edges").
            if held || c == contact || (touching && !self.lets_go(c, states, workspace)) {
                involved.push((c, held));
            }
        }
        if involved.len() > MAX_CONTACTS_PER_IMPACT {
            return Err(self.impact_failed(
                t,
                format!(
                    "{} contacts meet at once, more than one impact takes ({MAX_CONTACTS_PER_IMPACT})",
                    involved.len()
                ),
            ));
        }
        let indices: Vec<usize> = involved.iter().map(|&(c, _)| c).collect();
        // On their planes first, as a limited joint is put on its bound: the crossing was located a round-off past it.
        let equalities = self.equality_rows(&workspace.held);
        self.place_contacts(
            t,
            states,
            (&indices, &[], false),
            &equalities,
            &mut workspace.previous_positions,
        )?;
        let space = self.limited_space()?;
        let (mut q, mut v) = (vec![0.0; space.position_count()], vec![0.0; space.velocity_count()]);
        self.read_joints_into(states, &mut q, &mut v, &mut workspace.previous_positions)?;
        let normals = self.contact_rows(states, &indices)?;
        let frictional: Vec<usize> = (indices.iter().copied())
            .filter(|&c| self.contacts[c].friction.is_some())
            .collect();
        let tangential = self.slip_rows(states, &frictional)?;
        let stacked = stack(&[&normals, &tangential, &equalities]);
        let before = &stacked * DVector::from_column_slice(&v);
        let participants: Vec<Participant> = (indices.iter().enumerate())
            .map(|(k, &c)| {
                let contact = &self.contacts[c];
                let bounce = -contact.restitution * before[k].min(0.0);
                Participant {
                    normal: k,
                    tangential: frictional.iter().position(|&f| f == c).map(|f| indices.len() + 2 * f),
                    friction: contact.friction,
                    basis: tangent_basis(&self.contact_frame(c, states).normal),
                    target: if bounce < REST_SPEED { 0.0 } else { bounce },
                }
            })
            .collect();
        let (response, gram) = self.responses(t, states, &stacked)?;
        let rows = ImpactRows {
            gram: &gram,
            before: &before,
            equalities: indices.len() + tangential.nrows(),
        };
        let outcome = self.dissipative_impulses(t, &rows, &participants)?;
        let change = &response * &outcome.impulses;
        v.iter_mut().zip(change.iter()).for_each(|(v, dv)| *v += dv);
        self.write_joints_into(t, &q, &v, states, &mut workspace.placed)?;
        let mut changes = Vec::new();
        for (k, (&(c, was_held), participant)) in involved.iter().zip(&participants).enumerate() {
            let (speed_before, speed_after) = (-before[k], outcome.after[k]);
            let resting = speed_after < REST_SPEED;
            if resting {
                workspace.slips[c] = match participant.tangential {
                    Some(row) => {
                        let slip =
                            participant.basis[0] * outcome.after[row] + participant.basis[1] * outcome.after[row + 1];
                        let speed = slip.norm();
                        if speed <= STOP_SPEED {
                            Slip::Sticking
                        } else {
                            Slip::Sliding {
                                reference: slip / speed,
                            }
                        }
                    }
                    None => Slip::Sticking,
                };
            }
            let change = match (was_held, resting) {
                (true, true) => continue,
                (true, false) => {
                    workspace.held[first + c] = None;
                    LimitChange::Released { bound: Bound::Lower }
                }
                (false, true) => {
                    workspace.held[first + c] = Some(Bound::Lower);
                    LimitChange::Held {
                        bound: Bound::Lower,
                        speed_before,
                    }
                }
                (false, false) => LimitChange::Bounced {
                    bound: Bound::Lower,
                    speed_before,
                    speed_after,
                },
            };
            changes.push((first + c, change));
        }
        self.hold_rows(workspace);
        self.place_held_contacts(t, states, workspace)?;
        Ok(changes)
    }

    /// The impact of the first free contact that is watched, touching (within [`TOUCHING`]), moving away slower than
    /// `leaving` (m/s), and (switching) inside its face or edges at `states`, if any (docs/contacts.md "Edges"). Where
    /// a switching contact let go at its face's edge, the features that meet there take the load at once, by an
    /// impact at rest (`leaving` = [`REST_SPEED`]: a ball's face contact hands it to the edge it rolls over, whose gap
    /// opens only at second order); at a switching contact's false crossing, one meeting its plane there, whose own
    /// crossing is a round-off later, meets it now (`leaving` = [`AT_REST`]).
    pub(super) fn hand_over(
        &self,
        leaving: f64,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        let first = self.limits.len();
        let meeting = (0..self.contacts.len()).find(|&c| {
            let switching = self.contacts[c].switching;
            if workspace.held[first + c].is_some()
                || workspace.repeats[c].is_some()
                || (switching && !workspace.watched[c])
            {
                return false;
            }
            let frame = self.contact_frame(c, states);
            frame.gap.abs() <= TOUCHING && frame.normal_speed() <= leaving && !(switching && outside(&frame))
        });
        match meeting {
            Some(meeting) => self.contact_impact((meeting, leaving), t, states, workspace),
            None => Ok(Vec::new()),
        }
    }

    /// The rows of the slips of contacts `indices` in joint space at `states`: per contact two rows, the speeds of its
    /// touching point along its plane's tangent basis (the unit forces along the tangents through the touching point).
    pub(super) fn slip_rows(&self, states: &[State<A>], indices: &[usize]) -> Result<DMatrix<f64>, ConstraintError> {
        let points: Vec<PointDirection> = indices
            .iter()
            .flat_map(|&i| {
                let frame = self.contact_frame(i, states);
                tangent_basis(&frame.normal).map(|tangent| self.point_direction(i, frame.touching, tangent))
            })
            .collect();
        self.contact_jacobian(states, &points)
    }

    /// The impulses of an impact by Newton's law and Coulomb's (see the module docs). If they would add energy (a
    /// restitution with friction can, where a slip reverses), the targets are scaled down, by bisection, to the
    /// largest fraction of the restitution that adds none; at zero restitution an impact always dissipates.
    fn dissipative_impulses(
        &self,
        t: f64,
        rows: &ImpactRows<'_>,
        participants: &[Participant],
    ) -> Result<Outcome, ConstraintError> {
        let full = self.impact_outcome(t, rows, participants, 1.0)?;
        if energy_added(rows, &full) <= 0.0 {
            return Ok(full);
        }
        let (mut lower, mut upper) = (0.0, 1.0);
        let mut best = self.impact_outcome(t, rows, participants, 0.0)?;
        for _ in 0..RESTITUTION_BISECTIONS {
            let middle = 0.5 * (lower + upper);
            let outcome = self.impact_outcome(t, rows, participants, middle)?;
            if energy_added(rows, &outcome) <= 0.0 {
                (lower, best) = (middle, outcome);
            } else {
                upper = middle;
            }
        }
        Ok(best)
    }

    /// The impulses of an impact whose speed targets are scaled by `fraction`: by active sets ([`Mechanism::impact_modes`])
    /// where they settle; where they cycle (a contact that pulls while sticking, sinks while out and reverses its slip
    /// while sliding), by Gauss–Seidel iteration on Coulomb's law with each slide opposing its slip after
    /// ([`coulomb_iteration`]), whose modes, where consistent, are solved again exactly; an error naming the contacts
    /// if neither the exact solve nor the iterated impulses satisfy both laws.
    fn impact_outcome(
        &self,
        t: f64,
        rows: &ImpactRows<'_>,
        participants: &[Participant],
        fraction: f64,
    ) -> Result<Outcome, ConstraintError> {
        let error = match self.impact_modes(t, rows, participants, fraction) {
            Ok(outcome) => return Ok(outcome),
            Err(error) => error,
        };
        if participants.iter().all(|p| !p.friction.is_some()) {
            return frictionless_impulses(rows, participants, fraction).ok_or(error);
        }
        let Some(iterated) = coulomb_iteration(rows, participants, fraction) else {
            return Err(error);
        };
        let modes: Vec<Mode> = participants.iter().map(|p| p.mode_of(&iterated.impulses)).collect();
        let exact = self.impulses_for(t, rows, participants, &modes, fraction)?;
        if consistent(rows, participants, &modes, &exact, fraction) {
            Ok(exact)
        } else if consistent(rows, participants, &modes, &iterated, fraction) {
            Ok(iterated)
        } else {
            Err(error)
        }
    }

    /// The active sets of an impact whose speed targets are scaled by `fraction` (1 for the restitution asked): every
    /// contact starts in, sliding along its slip before if it has friction and slips, else sticking; a pulling one
    /// leaves, a free one sinking below its target joins, a sticking one whose friction leaves the cone slides, a
    /// sliding one whose slip would reverse sticks, until all hold; an error naming the contacts if the sets cycle.
    fn impact_modes(
        &self,
        t: f64,
        rows: &ImpactRows<'_>,
        participants: &[Participant],
        fraction: f64,
    ) -> Result<Outcome, ConstraintError> {
        let count = participants.len();
        let scale = rows.before.amax().max(f64::MIN_POSITIVE);
        let mut modes: Vec<Mode> = participants.iter().map(|p| p.entering(rows)).collect();
        for _ in 0..MAX_IMPACT_PASSES * (count + 1) {
            let outcome = self.impulses_for(t, rows, participants, &modes, fraction)?;
            let (p, after) = (&outcome.impulses, &outcome.after);
            let largest_push = participants.iter().fold(0.0f64, |m, q| m.max(p[q.normal].abs()));
            let pulling = (0..count)
                .filter(|&k| modes[k] != Mode::Out && p[participants[k].normal] < -COMPLEMENTARITY * largest_push)
                .min_by(|&a, &b| p[participants[a].normal].total_cmp(&p[participants[b].normal]));
            if let Some(k) = pulling {
                modes[k] = Mode::Out;
                continue;
            }
            let target = |k: usize| participants[k].target * fraction;
            let sinking = (0..count)
                .filter(|&k| {
                    modes[k] == Mode::Out && after[participants[k].normal] < target(k) - COMPLEMENTARITY * scale
                })
                .min_by(|&a, &b| {
                    (after[participants[a].normal] - target(a)).total_cmp(&(after[participants[b].normal] - target(b)))
                });
            if let Some(k) = sinking {
                modes[k] = participants[k].entering(rows);
                continue;
            }
            if let Some((k, mode)) = friction_change(participants, &modes, &outcome) {
                modes[k] = mode;
                continue;
            }
            return Ok(outcome);
        }
        Err(self.impact_failed(
            t,
            "no set of pushing, sticking and sliding contacts was found".to_owned(),
        ))
    }

    /// The impulses for fixed modes: unknowns the pushes of the contacts in, the friction impulses of the sticking ones
    /// and the equalities'; equations the normal speeds after at their targets (scaled by `fraction`), the sticking
    /// slips after at zero, the equalities unchanged. A sliding contact's friction impulse is `−μ P_n ŝ`. Solved in
    /// the least-norm sense, so that contacts repeating others share.
    fn impulses_for(
        &self,
        t: f64,
        rows: &ImpactRows<'_>,
        participants: &[Participant],
        modes: &[Mode],
        fraction: f64,
    ) -> Result<Outcome, ConstraintError> {
        let total = rows.gram.nrows();
        // Each unknown as a combination of row impulses, and each equation's row with its value.
        let mut unknowns: Vec<Vec<(usize, f64)>> = Vec::new();
        let mut equations: Vec<(usize, f64)> = Vec::new();
        for (participant, mode) in participants.iter().zip(modes) {
            let n = participant.normal;
            match (*mode, participant.tangential) {
                (Mode::Out, _) => continue,
                (Mode::Sliding { direction }, Some(row)) => {
                    let mu = participant.friction.kinetic();
                    let [first, second] = participant.basis;
                    unknowns.push(vec![
                        (n, 1.0),
                        (row, -mu * direction.dot(&first)),
                        (row + 1, -mu * direction.dot(&second)),
                    ]);
                }
                (Mode::Sticking, Some(row)) => {
                    unknowns.push(vec![(n, 1.0)]);
                    unknowns.push(vec![(row, 1.0)]);
                    unknowns.push(vec![(row + 1, 1.0)]);
                    equations.push((row, 0.0));
                    equations.push((row + 1, 0.0));
                }
                (_, None) => unknowns.push(vec![(n, 1.0)]),
            }
            equations.push((n, participant.target * fraction));
        }
        for e in rows.equalities..total {
            unknowns.push(vec![(e, 1.0)]);
            equations.push((e, rows.before[e]));
        }
        if unknowns.is_empty() {
            return Ok(Outcome {
                impulses: DVector::zeros(total),
                after: rows.before.clone(),
            });
        }
        let mut matrix = DMatrix::zeros(equations.len(), unknowns.len());
        let mut rhs = DVector::zeros(equations.len());
        for (i, &(row, value)) in equations.iter().enumerate() {
            rhs[i] = value - rows.before[row];
            for (j, combination) in unknowns.iter().enumerate() {
                matrix[(i, j)] = combination.iter().map(|&(r, w)| w * rows.gram[(row, r)]).sum();
            }
        }
        let solution = self.least_norm(t, &matrix, &rhs, false)?;
        let mut impulses = DVector::zeros(total);
        for (combination, &x) in unknowns.iter().zip(solution.iter()) {
            for &(r, w) in combination {
                impulses[r] += w * x;
            }
        }
        let after = rows.before + rows.gram * &impulses;
        Ok(Outcome { impulses, after })
    }
}

/// The first contact whose friction mode does not hold with `outcome`, and the mode it takes: a sticking one whose
/// friction impulse leaves the cone slides against it; a sliding one whose slip after reversed sticks.
fn friction_change(participants: &[Participant], modes: &[Mode], outcome: &Outcome) -> Option<(usize, Mode)> {
    let (p, after) = (&outcome.impulses, &outcome.after);
    for (k, (participant, mode)) in participants.iter().zip(modes).enumerate() {
        let Some(row) = participant.tangential else {
            continue;
        };
        let [first, second] = participant.basis;
        let push = p[participant.normal];
        match *mode {
            Mode::Out => {}
            Mode::Sticking => {
                let friction = first * p[row] + second * p[row + 1];
                let bound = participant.friction.stiction() * push;
                if friction.norm() > bound + COMPLEMENTARITY * push.abs().max(friction.norm()) {
                    let direction = -friction.normalize();
                    return Some((k, Mode::Sliding { direction }));
                }
            }
            Mode::Sliding { direction } => {
                // The slide keeps its direction through the impact; one whose slip it would reverse (beyond
                // round-off) needed less than the cone's friction: it sticks.
                let slip = first * after[row] + second * after[row + 1];
                if slip.dot(&direction) < -STOP_SPEED {
                    return Some((k, Mode::Sticking));
                }
            }
        }
    }
    None
}

/// Whether `outcome`, solved for `modes`, satisfies Newton's and Coulomb's laws: every contact in pushes, every one
/// out leaves at its target or faster, every sticking one's friction is inside its cone, every sliding one slips along
/// its friction's opposite (or not at all).
fn consistent(
    rows: &ImpactRows<'_>,
    participants: &[Participant],
    modes: &[Mode],
    outcome: &Outcome,
    fraction: f64,
) -> bool {
    let (p, after) = (&outcome.impulses, &outcome.after);
    let largest_push = participants.iter().fold(0.0f64, |m, q| m.max(p[q.normal].abs()));
    let scale = rows.before.amax().max(f64::MIN_POSITIVE);
    participants.iter().zip(modes).all(|(participant, mode)| {
        let push = p[participant.normal];
        match (*mode, participant.tangential) {
            (Mode::Out, _) => after[participant.normal] >= participant.target * fraction - COMPLEMENTARITY * scale,
            (_, None) => push >= -COMPLEMENTARITY * largest_push,
            (Mode::Sticking, Some(row)) => {
                let friction = participant.basis[0] * p[row] + participant.basis[1] * p[row + 1];
                push >= -COMPLEMENTARITY * largest_push
                    && friction.norm() <= participant.friction.stiction() * push + COMPLEMENTARITY * largest_push
            }
            (Mode::Sliding { direction }, Some(row)) => {
                let slip = participant.basis[0] * after[row] + participant.basis[1] * after[row + 1];
                push >= -COMPLEMENTARITY * largest_push
                    && slip.dot(&direction) >= -STOP_SPEED
                    && slip.cross(&direction).norm() <= STOP_SPEED.max(COMPLEMENTARITY * scale)
            }
        }
    })
}

/// A frictionless impact's impulses where the active sets cycle (contacts whose rows depend on each other, their
/// targets not all met by one rigid motion: points along an edge, some slower than [`REST_SPEED`] and held, the others
/// bouncing): the pushes `p ≥ 0` minimising `½ pᵀ G p + pᵀ (u⁻ − t)`, the equalities' impulses free, whose optimum is
/// Newton's law with complementarity (its gradient is the speeds after less their targets; docs/contacts.md
/// "Repeated and dependent contacts"). Primal active sets, as Lawson and Hanson's for non-negative least squares:
/// each pass minimises over the free impulses (least norm where G repeats rows; along a null direction of G that
/// lowers the objective where its equations have no solution), steps back to the first push reaching zero and fixes
/// it, and frees the fixed push whose gradient is most negative, until none is. Each pass lowers the objective, so
/// no set returns. `None` if the passes run out.
fn frictionless_impulses(rows: &ImpactRows<'_>, participants: &[Participant], fraction: f64) -> Option<Outcome> {
    let (gram, total) = (rows.gram, rows.gram.nrows());
    let pushes: Vec<usize> = participants.iter().map(|p| p.normal).collect();
    let mut linear = DVector::zeros(total);
    for participant in participants {
        linear[participant.normal] = rows.before[participant.normal] - participant.target * fraction;
    }
    let scale = rows.before.amax().max(f64::MIN_POSITIVE);
    let threshold = REPEATED_ROW * gram.diagonal().amax();
    let mut free: Vec<bool> = (0..total).map(|r| r >= rows.equalities).collect();
    let mut x = DVector::zeros(total);
    for _ in 0..MAX_IMPACT_PASSES * (pushes.len() + 1) {
        let subset: Vec<usize> = (0..total).filter(|&r| free[r]).collect();
        let block = DMatrix::from_fn(subset.len(), subset.len(), |i, j| gram[(subset[i], subset[j])]);
        let rhs = DVector::from_iterator(subset.len(), subset.iter().map(|&r| -linear[r]));
        let solution = SingularValues::of(&block).solve(&rhs, threshold);
        let residual = &block * &solution - &rhs;
        let current = DVector::from_iterator(subset.len(), subset.iter().map(|&r| x[r]));
        // To the subset's optimum, or along the descent its equations' residual gives where they have no solution.
        let (direction, reaches) = if residual.amax() <= COMPLEMENTARITY * scale {
            (solution - &current, 1.0)
        } else {
            (-residual, f64::INFINITY)
        };
        let (step, stop) = (subset.iter().enumerate())
            .filter(|&(k, &r)| r < rows.equalities && direction[k] < 0.0)
            .map(|(k, &r)| (current[k] / -direction[k], r))
            .fold(
                (reaches, None),
                |best, (s, r)| if s < best.0 { (s, Some(r)) } else { best },
            );
        if step.is_infinite() {
            return None;
        }
        for (k, &r) in subset.iter().enumerate() {
            x[r] = current[k] + step * direction[k];
        }
        if let Some(r) = stop {
            x[r] = 0.0;
            free[r] = false;
            continue;
        }
        let gradient = gram * &x + &linear;
        let entering = (pushes.iter().copied())
            .filter(|&r| !free[r] && gradient[r] < -COMPLEMENTARITY * scale)
            .min_by(|&a, &b| gradient[a].total_cmp(&gradient[b]));
        match entering {
            Some(r) => free[r] = true,
            None => {
                let after = rows.before + gram * &x;
                return Some(Outcome { impulses: x, after });
            }
        }
    }
    None
}

/// Coulomb's and Newton's laws on an impact by projected Gauss–Seidel: each contact's impulse in turn solved exactly
/// against the others' (out; sticking if its sticking impulse pushes and is inside the cone; else sliding, its
/// friction `−μ P_n ŝ` opposing its slip after, ŝ found on the circle of directions), the equalities' in turn held,
/// sweeping until no impulse changes by more than round-off. `None` if it does not settle in [`MAX_SWEEPS`].
fn coulomb_iteration(rows: &ImpactRows<'_>, participants: &[Participant], fraction: f64) -> Option<Outcome> {
    let gram = rows.gram;
    let total = gram.nrows();
    let mut p = DVector::zeros(total);
    let mut after = rows.before.clone();
    // The rows' speeds after with the impulses of the other rows of a block only: u − G[:, own] p_own.
    let without = |after: &DVector<f64>, p: &DVector<f64>, own: &[usize], of: usize| {
        after[of] - own.iter().map(|&j| gram[(of, j)] * p[j]).sum::<f64>()
    };
    for _ in 0..MAX_SWEEPS {
        let mut change: f64 = 0.0;
        let mut size: f64 = 0.0;
        for participant in participants {
            let n = participant.normal;
            let own: Vec<usize> = match participant.tangential {
                Some(row) => vec![n, row, row + 1],
                None => vec![n],
            };
            let local: Vec<f64> = own.iter().map(|&i| without(&after, &p, &own, i)).collect();
            let block = DMatrix::from_fn(own.len(), own.len(), |i, j| gram[(own[i], own[j])]);
            let target = participant.target * fraction;
            let next = local_coulomb(&block, &local, target, participant.friction);
            for (k, &i) in own.iter().enumerate() {
                let delta = next[k] - p[i];
                if delta != 0.0 {
                    after.axpy(delta, &gram.column(i), 1.0);
                    p[i] = next[k];
                }
                change = change.max(delta.abs());
                size = size.max(next[k].abs());
            }
        }
        for e in rows.equalities..total {
            if gram[(e, e)] > 0.0 {
                let delta = (rows.before[e] - after[e]) / gram[(e, e)];
                after.axpy(delta, &gram.column(e), 1.0);
                p[e] += delta;
                change = change.max(delta.abs());
                size = size.max(p[e].abs());
            }
        }
        if change <= SWEEP_TOLERANCE * size.max(f64::MIN_POSITIVE) {
            let after = rows.before + gram * &p;
            return Some(Outcome { impulses: p, after });
        }
    }
    None
}

/// One contact's impulse `(P_n, P_t₁, P_t₂)` (or `(P_n)` without friction) against the speeds `local` its rows have
/// without it, `block` its rows' Gram block: out if it leaves at `target` or faster without one; else sticking if the
/// sticking impulse pushes and is inside the static cone; else sliding, the direction ŝ (angle θ on the plane) the
/// root of `ŝ × u_t(θ) = 0` with `ŝ · u_t ≥ 0`, u_t the slip after with the friction `−μ P_n ŝ` and P_n holding the
/// normal speed at `target`; on no root (a slide at the cone's edge), the sticking impulse moved onto the cone.
fn local_coulomb(block: &DMatrix<f64>, local: &[f64], target: f64, friction: Friction) -> Vec<f64> {
    if local[0] >= target {
        return vec![0.0; local.len()];
    }
    if local.len() == 1 || !friction.is_some() {
        let mut out = vec![0.0; local.len()];
        out[0] = if block[(0, 0)] > 0.0 {
            (target - local[0]) / block[(0, 0)]
        } else {
            0.0
        };
        return out;
    }
    let rhs = nalgebra::Vector3::new(target - local[0], -local[1], -local[2]);
    let block3 = nalgebra::Matrix3::from_fn(|i, j| block[(i, j)]);
    let stick = block3.lu().solve(&rhs);
    if let Some(stick) = stick {
        let tangential = stick[1].hypot(stick[2]);
        if stick[0] >= 0.0 && tangential <= friction.stiction() * stick[0] {
            return vec![stick[0], stick[1], stick[2]];
        }
    }
    let mu = friction.kinetic();
    // The slide at angle θ: its push, its slip after, and the slip's turn from ŝ (zero at a solution).
    let slide = |theta: f64| {
        let (d1, d2) = (theta.cos(), theta.sin());
        let denominator = block[(0, 0)] - mu * (block[(0, 1)] * d1 + block[(0, 2)] * d2);
        let push = if denominator > 0.0 {
            (target - local[0]) / denominator
        } else {
            f64::NAN
        };
        let slip = |k: usize| local[k] + block[(k, 0)] * push - mu * push * (block[(k, 1)] * d1 + block[(k, 2)] * d2);
        let (s1, s2) = (slip(1), slip(2));
        (push, d1 * s2 - d2 * s1, d1 * s1 + d2 * s2)
    };
    let mut best: Option<(f64, f64)> = None;
    let steps = DIRECTION_SAMPLES;
    for k in 0..steps {
        let (a, b) = (
            std::f64::consts::TAU * k as f64 / steps as f64,
            std::f64::consts::TAU * (k + 1) as f64 / steps as f64,
        );
        let (fa, fb) = (slide(a).1, slide(b).1);
        if !(fa.is_finite() && fb.is_finite()) || fa.signum() == fb.signum() {
            continue;
        }
        let (mut low, mut high, mut f_low) = (a, b, fa);
        for _ in 0..BISECTIONS {
            let middle = 0.5 * (low + high);
            let f_middle = slide(middle).1;
            if f_middle.signum() == f_low.signum() {
                (low, f_low) = (middle, f_middle);
            } else {
                high = middle;
            }
        }
        let theta = 0.5 * (low + high);
        let (push, _, along) = slide(theta);
        if push >= 0.0 && along >= 0.0 && best.is_none_or(|(_, p)| push < p) {
            best = Some((theta, push));
        }
    }
    match best {
        Some((theta, push)) => vec![push, -mu * push * theta.cos(), -mu * push * theta.sin()],
        None => {
            let stick = stick.unwrap_or_else(|| nalgebra::Vector3::new(0.0, 0.0, 0.0));
            let push = stick[0].max(0.0);
            let tangential = stick[1].hypot(stick[2]);
            let scale = if tangential > 0.0 { mu * push / tangential } else { 0.0 };
            vec![push, stick[1] * scale, stick[2] * scale]
        }
    }
}

/// The kinetic energy an impact's contact impulses add (J), less round-off: `P·u⁺ − ½ PᵀGP` over the contact rows, the
/// equalities' work (a drive's) left out. Positive means energy added.
fn energy_added(rows: &ImpactRows<'_>, outcome: &Outcome) -> f64 {
    let p = &outcome.impulses;
    let quadratic = 0.5 * p.dot(&(rows.gram * p));
    let equalities = rows.equalities..p.len();
    let work: f64 = (0..p.len())
        .filter(|r| !equalities.contains(r))
        .map(|r| p[r] * outcome.after[r])
        .sum();
    let size = quadratic.abs() + (0..p.len()).map(|r| (p[r] * outcome.after[r]).abs()).sum::<f64>();
    work - quadratic - ENERGY_ROUND_OFF * size
}

/// Gauss–Seidel sweeps at most for an impact the active sets do not settle.
const MAX_SWEEPS: usize = 100_000;

/// A sweep that changes no impulse by more than this, relative to the largest, has converged.
const SWEEP_TOLERANCE: f64 = 1e-15;

/// Directions sampled on the circle for a slide's root, each bracket then bisected.
const DIRECTION_SAMPLES: usize = 256;

/// Bisections of a slide's direction: to the double's resolution of an angle.
const BISECTIONS: usize = 60;

/// A friction impulse within this of its cone's edge (relative) counts as on it: sliding.
const CONE_EDGE: f64 = 1e-9;

/// Passes of the active sets per contact at most (each contact may leave, join, stick and slide).
const MAX_IMPACT_PASSES: usize = 8;

/// Bisections of the restitution of an impact that would add energy: 2⁻⁴⁰ of it.
const RESTITUTION_BISECTIONS: usize = 40;
