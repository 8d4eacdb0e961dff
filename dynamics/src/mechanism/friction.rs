//! Coulomb friction at a mechanism's held contacts (docs/contacts.md "Friction"): the slip of a contact's touching
//! point, the direction a sliding contact's friction takes, the rows of the articulated solve that carry it (a sliding
//! contact's push tilted by `−μ ŝ`, a sticking contact's two tangential rows), and the friction values
//! [`crate::simulate()`] watches (the slip along the step's starting direction while sliding, the margin to the cone
//! while sticking).

use nalgebra::Vector3;

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::eigen::SingularValues;
use crate::mechanism::articulated::{Row, REPEATED_ROW};
use crate::mechanism::load_split::{least_margin, widest_split, Held};
use crate::mechanism::model::{Mechanism, MechanismWorkspace};
use crate::mechanism::parts::Slip;
use crate::state::State;

/// The value a contact's friction shows while the contact is free: positive, so never a transition.
pub(super) const NOT_WATCHED: f64 = 1.0;

/// Slips below this (m/s) where a slide's slip along its starting direction reaches zero are a stop; a larger one
/// is a slide that turned by a right angle within a step, which only renews the direction it is watched along. A
/// located stop leaves a few ulps of the time times the slip's rate (1e-14 m/s under 10 m/s²).
pub(super) const STOP_SPEED: f64 = 1e-9;

/// Two unit vectors completing the unit `normal` to a right-handed frame `(t₁, t₂, n)`, the same for the same normal.
pub(super) fn tangent_basis(normal: &Vector3<f64>) -> [Vector3<f64>; 2] {
    // The coordinate axis least aligned with n, made orthogonal to it.
    let axis = if normal.x.abs() <= normal.y.abs() && normal.x.abs() <= normal.z.abs() {
        Vector3::x()
    } else if normal.y.abs() <= normal.z.abs() {
        Vector3::y()
    } else {
        Vector3::z()
    };
    let first = (axis - normal * normal.dot(&axis)).normalize();
    [first, normal.cross(&first)]
}

/// The direction `±s/|s|` of a slide's friction: the slip's own direction while it points along `reference` (its
/// direction at the step's start), the opposite once it has passed through zero, and the reference itself for a slip
/// below [`STOP_SPEED`], whose direction is round-off (a slide just begun, or just stopped).
pub(super) fn sliding_direction(slip: &Vector3<f64>, reference: &Vector3<f64>) -> Vector3<f64> {
    let speed = slip.norm();
    if speed <= STOP_SPEED {
        return *reference;
    }
    if slip.dot(reference) >= 0.0 {
        slip / speed
    } else {
        -slip / speed
    }
}

impl<A: Algebra> Mechanism<A> {
    /// The one-sided index of contact `contact`'s friction value, if it has friction.
    pub(super) fn friction_index(&self, contact: usize) -> Option<usize> {
        let rank = self.frictional.iter().position(|&c| c == contact)?;
        Some(self.limits.len() + self.contacts.len() + rank)
    }

    /// Contact `index`'s slip (world, m/s) at `states`.
    pub(super) fn contact_slip(&self, index: usize, states: &[State<A>]) -> Vector3<f64> {
        self.contact_frame(index, states).slip()
    }

    /// The rows that hold contact `index` (held, with slip mode `slip`): its normal row, whose unit multiplier is the
    /// push, tilted to `n − μ ŝ` while sliding (the direction filled in at each evaluation), and while sticking two
    /// tangential rows at the touching point, whose multipliers are the friction force's components.
    pub(super) fn contact_hold_rows(&self, index: usize, slip: Option<Slip>, rows: &mut Vec<Row>) {
        let contact = &self.contacts[index];
        let count = if slip == Some(Slip::Sticking) { 3 } else { 1 };
        rows.extend((0..count).map(|_| Row::Point {
            body: contact.body,
            other: contact.against.body(),
            lever: Vector3::zeros(),
            moving: Vector3::zeros(),
            direction: Vector3::zeros(),
            force: Vector3::zeros(),
            extra: 0.0,
        }));
    }

    /// Every held contact's rows filled in at the kinematics in the workspace, with `origin` the solve's reference
    /// point: the normal row along n with the rate `ṅ · w` of its turning, its force the push with the friction a
    /// slide brings, `n − μ ŝ`, ŝ the slip's direction (continued through a stop: [`sliding_direction`]); a sticking
    /// contact's tangential rows along the tangent basis of n, whose `ṫ · w` vanishes while the slip is held at zero
    /// (docs/contacts.md "Friction" and "Between bodies").
    pub(super) fn resolve_contact_rows(&self, origin: &Vector3<f64>, workspace: &mut MechanismWorkspace<A>) {
        for c in 0..self.contacts.len() {
            let Some(row) = workspace.held_rows[self.limits.len() + c] else {
                continue;
            };
            let frame = self.workspace_frame(c, workspace);
            let lever = frame.touching - origin;
            let moving = frame.touching_rate;
            let force = match (self.contacts[c].friction.is_some(), workspace.slips[c]) {
                (true, Slip::Sliding { reference }) => {
                    let direction = sliding_direction(&frame.slip(), &reference);
                    frame.normal - direction * self.contacts[c].friction.kinetic()
                }
                _ => frame.normal,
            };
            let fill = |row: &mut Row, along: Vector3<f64>, pushed: Vector3<f64>, turning: f64| {
                if let Row::Point {
                    lever: l,
                    moving: m,
                    direction,
                    force,
                    extra,
                    ..
                } = row
                {
                    (*l, *m, *direction, *force, *extra) = (lever, moving, along, pushed, turning);
                }
            };
            fill(
                &mut workspace.rows[row],
                frame.normal,
                force,
                frame.normal_rate.dot(&frame.relative),
            );
            if self.contacts[c].friction.is_some() && workspace.slips[c] == Slip::Sticking {
                for (k, tangent) in tangent_basis(&frame.normal).into_iter().enumerate() {
                    fill(&mut workspace.rows[row + 1 + k], tangent, tangent, 0.0);
                }
            }
        }
    }

    /// Every sliding held contact's reference direction renewed to its slip's at `states`, the start of a step
    /// ([`crate::Dynamics::begin_step`]); a slip too small to have a direction keeps the one it has (that of a
    /// slide just begun).
    pub(super) fn renew_slip_references(&self, states: &[State<A>], workspace: &mut MechanismWorkspace<A>) {
        for &c in &self.frictional {
            if workspace.held_rows[self.limits.len() + c].is_none() {
                continue;
            }
            if let Slip::Sliding { reference } = &mut workspace.slips[c] {
                let slip = self.contact_slip(c, states);
                let speed = slip.norm();
                if speed > STOP_SPEED {
                    *reference = slip / speed;
                }
            }
        }
    }

    /// The multipliers of the held rows at the last evaluation in `workspace`: the articulated solve's, moved by a
    /// load the rows balance among themselves (one that changes no body's acceleration) to the split with the widest
    /// margin ([`widest_split`]) where the held rows repeat each other.
    pub(super) fn held_multipliers(&self, workspace: &MechanismWorkspace<A>) -> Vec<f64> {
        let least_norm = workspace.articulated.multipliers();
        if least_norm.is_empty() || workspace.held.iter().all(Option::is_none) {
            return least_norm.to_vec();
        }
        let held: Vec<Held> = (workspace.held.iter().enumerate())
            .filter_map(|(index, bound)| {
                let (bound, row) = ((*bound)?, workspace.held_rows[index]?);
                let friction = index.checked_sub(self.limits.len()).and_then(|c| {
                    let friction = self.contacts[c].friction;
                    (friction.is_some() && workspace.slips[c] == Slip::Sticking)
                        .then_some((row + 1, friction.stiction()))
                });
                Some(Held {
                    push: (row, bound.inward()),
                    friction,
                })
            })
            .collect();
        let base = nalgebra::DVector::from_column_slice(least_norm);
        // Every push and stick inside its cone at the least-norm split already (a body at rest on its corners):
        // no other split is needed, nor the null space that would give it.
        if least_margin(&base, &held) > 0.0 {
            return least_norm.to_vec();
        }
        let svd = SingularValues::of(&workspace.articulated.responses());
        // The loads that move nothing: the right singular vectors of (near) zero singular values.
        let null = svd.null_vectors(REPEATED_ROW * svd.largest());
        if null.is_empty() {
            return least_norm.to_vec();
        }
        let null = nalgebra::DMatrix::from_columns(&null);
        let base = nalgebra::DVector::from_column_slice(least_norm);
        widest_split(&base, &null, &held).0.as_slice().to_vec()
    }

    /// Contact `index`'s friction value at `states` with the held rows' multipliers `multipliers`
    /// ([`Mechanism::held_multipliers`]): while free [`NOT_WATCHED`]; while sliding the slip along the reference
    /// direction (m/s); while sticking the margin `μ_s N − |F_t|` to the cone (N).
    pub(super) fn friction_value(
        &self,
        index: usize,
        states: &[State<A>],
        workspace: &MechanismWorkspace<A>,
        multipliers: &[f64],
    ) -> f64 {
        let Some(row) = workspace.held_rows[self.limits.len() + index] else {
            return NOT_WATCHED;
        };
        match workspace.slips[index] {
            Slip::Sliding { reference } => self.contact_slip(index, states).dot(&reference),
            Slip::Sticking => {
                let push = multipliers[row];
                let tangential = multipliers[row + 1].hypot(multipliers[row + 2]);
                self.contacts[index].friction.stiction() * push - tangential
            }
        }
    }

    /// The directions held contacts at rest (no slip), `contacts`, start to slide in, by maximal dissipation: each
    /// the direction ŝ of its slip's acceleration under the kinetic friction `−μ N ŝ` they all bring, found together
    /// by fixed-point iteration from `guesses` (the directions opposite their sticking forces). They are left sliding
    /// along them; `states` and the other constraints' modes are those of the transition.
    pub(super) fn slide_from_rest(
        &self,
        contacts: &[usize],
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
        guesses: &[Vector3<f64>],
    ) -> Result<Vec<Vector3<f64>>, ConstraintError> {
        let mut directions = guesses.to_vec();
        // With μ_s = μ the friction force is continuous at the onset: the slip starts from zero acceleration, opposite
        // the sticking force (the guess); the tangential acceleration there is the round-off of the located time,
        // whose direction means nothing.
        let continuous = (contacts.iter()).all(|&c| {
            let friction = self.contacts[c].friction;
            friction.stiction() == friction.kinetic()
        });
        if continuous {
            for (&c, &direction) in contacts.iter().zip(&directions) {
                workspace.slips[c] = Slip::Sliding { reference: direction };
            }
            self.hold_rows(workspace);
            return Ok(directions);
        }
        // Damped where it does not contract: each direction moves a fraction of the way to its acceleration's, the
        // fraction halved whenever the largest turn fails to shrink.
        let (mut damping, mut previous_turn): (f64, f64) = (1.0, f64::INFINITY);
        for _ in 0..MAX_DIRECTION_ITERATIONS {
            for (&c, &direction) in contacts.iter().zip(&directions) {
                workspace.slips[c] = Slip::Sliding { reference: direction };
            }
            self.hold_rows(workspace);
            self.evaluate_states(t, states, workspace)?;
            let mut targets = directions.clone();
            let mut turned: f64 = 0.0;
            for (&c, (direction, target)) in contacts.iter().zip(directions.iter().zip(targets.iter_mut())) {
                let acceleration = self.touching_acceleration(c, workspace);
                let normal = self.workspace_frame(c, workspace).normal;
                let tangential = acceleration - normal * normal.dot(&acceleration);
                let size = tangential.norm();
                // No tangential acceleration (the cone just reached with μ_s = μ, or the contact held in place by
                // others still sticking): the slip starts along the guess.
                if size > REST_ACCELERATION {
                    *target = tangential / size;
                    turned = turned.max((*target - *direction).norm());
                }
            }
            if turned <= DIRECTION_TOLERANCE {
                for (&c, &direction) in contacts.iter().zip(&directions) {
                    workspace.slips[c] = Slip::Sliding { reference: direction };
                }
                self.hold_rows(workspace);
                return Ok(directions);
            }
            if turned >= previous_turn {
                damping = (0.5 * damping).max(MIN_DAMPING);
            }
            previous_turn = turned;
            for (direction, target) in directions.iter_mut().zip(&targets) {
                let moved = *direction + (target - *direction) * damping;
                *direction = if moved.norm() > 0.0 { moved.normalize() } else { *target };
            }
        }
        Err(ConstraintError::InvalidParameter {
            name: contacts
                .iter()
                .map(|&c| self.contacts[c].name.as_str())
                .collect::<Vec<_>>()
                .join(" + "),
            reason: format!(
                "at t = {t} the contacts start to slide, but no directions of maximal dissipation were found in \
                 {MAX_DIRECTION_ITERATIONS} iterations"
            ),
        })
    }

    /// The rate of contact `index`'s relative velocity at its touching point, from the last articulated solve: `ẇ`
    /// with the normal's turning added along n, so that its normal part is the gap's acceleration and its tangential
    /// part the slip's (at zero slip). Each body's part is `a_o + α × l + ω × ṗ`, l the touching point's offset from
    /// o and ṗ its velocity (docs/contacts.md "Friction" and "Between bodies").
    pub(super) fn touching_acceleration(&self, index: usize, workspace: &MechanismWorkspace<A>) -> Vector3<f64> {
        let frame = self.workspace_frame(index, workspace);
        let lever = frame.touching - workspace.articulated.origin();
        let side = |body: usize| {
            let a = workspace.articulated.acceleration(body);
            let (alpha, linear) = (a.fixed_rows::<3>(0).into_owned(), a.fixed_rows::<3>(3).into_owned());
            let omega = workspace.bodies[body].kinematics.angular_velocity;
            linear + alpha.cross(&lever) + omega.cross(&frame.touching_rate)
        };
        let contact = &self.contacts[index];
        let own = side(contact.body);
        let other = contact.against.body().map_or_else(Vector3::zeros, side);
        own - other + frame.normal * frame.normal_rate.dot(&frame.relative)
    }
}

/// A slip acceleration below this (m/s²) is none: round-off of a contact held in place.
const REST_ACCELERATION: f64 = 1e-9;

/// Fixed-point iterations at most for a slide's starting direction.
const MAX_DIRECTION_ITERATIONS: usize = 400;

/// The smallest fraction of the way to its acceleration's direction a slide's direction moves in one iteration.
const MIN_DAMPING: f64 = 1.0 / 64.0;

/// Successive directions closer than this (rad) have converged.
const DIRECTION_TOLERANCE: f64 = 1e-13;
