//! A mechanism's one-sided constraints — its joint limits (docs/limits.md), then its contacts (docs/contacts.md) —
//! as [`crate::simulate()`] sees them: the values it watches, and the transitions it makes at their crossings (the
//! impact through the kinetic metric, the hold by a row of the articulated solve, the release).

use nalgebra::{DMatrix, DVector};

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::contacts::TOUCHING;
use crate::limits::{Bound, LimitChange, REST_SPEED};
use crate::mechanism::articulated::{Row, REPEATED_ROW};
use crate::mechanism::joint_space::{JointSpace, WorldBody};
use crate::mechanism::model::{Mechanism, MechanismWorkspace};
use crate::state::State;

/// The relative size below which an impulse counts as zero in the contacts' complementarity (pushes are ≥ 0, speeds
/// after an impact ≥ their targets).
const COMPLEMENTARITY: f64 = 1e-12;

impl<A: Algebra> Mechanism<A> {
    /// The number of one-sided constraints: limited joints, then contacts.
    pub(crate) fn limit_count(&self) -> usize {
        self.limits.len() + self.contacts.len()
    }

    /// The name of one-sided constraint `index`: its joint's for a limit, the contact's.
    pub(crate) fn limit_name(&self, index: usize) -> Option<&str> {
        match index.checked_sub(self.limits.len()) {
            None => Some(self.joints[self.limits[index].joint].name()),
            Some(contact) => self.contacts.get(contact).map(|c| c.name.as_str()),
        }
    }

    /// An error naming the one-sided constraints unless the mechanism has joint coordinates (its joint models form a
    /// forest).
    pub(super) fn limited_space(&self) -> Result<&JointSpace, ConstraintError> {
        self.coordinates().ok_or_else(|| ConstraintError::InvalidParameter {
            name: self.unilateral_names(),
            reason: "joint limits and contacts need joint coordinates: joint models forming a tree".to_owned(),
        })
    }

    fn unilateral_names(&self) -> String {
        (0..self.limit_count())
            .filter_map(|index| self.limit_name(index))
            .collect::<Vec<_>>()
            .join(" + ")
    }

    /// Per one-sided constraint, what [`crate::simulate()`] watches (docs/limits.md "The three states of a limit"):
    /// while free the gap to a limit's nearer bound (rad or m; angles unwrapped from the last positions read) or a
    /// contact point's height above its plane (m); while held the reaction pushing onto the bound or the plane (N m
    /// or N; an evaluation of the equations of motion at `(t, states)`).
    pub(crate) fn limit_values(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
        values: &mut [f64],
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        if values.len() != self.limit_count() {
            return Err(ConstraintError::Count {
                what: "limit values",
                expected: self.limit_count(),
                got: values.len(),
            });
        }
        let space = self.limited_space()?;
        if workspace.held.iter().any(Option::is_some) {
            self.evaluate_states(t, states, workspace)?;
        }
        let bodies: Vec<WorldBody> = states.iter().enumerate().map(|(i, s)| self.world_body(i, s)).collect();
        let previous =
            (workspace.previous_positions.len() == space.position_count()).then_some(&workspace.previous_positions);
        let mut row = self.coupling_rows.len();
        for (index, (held, value)) in workspace.held.iter().zip(values.iter_mut()).enumerate() {
            *value = match (held, index.checked_sub(self.limits.len())) {
                (Some(bound), _) => {
                    row += 1;
                    bound.inward() * workspace.articulated.multipliers()[row - 1]
                }
                (None, None) => {
                    let limit = &self.limits[index];
                    let group = space
                        .group_of_joint(limit.joint)
                        .expect("limited joints are joint models");
                    let offset = group.position_offset();
                    let mut q = [0.0];
                    self.read_positions(group, &bodies, previous.map(|p| &p[offset..offset + 1]), &mut q);
                    limit.range.gap(q[0])
                }
                (None, Some(contact)) => self.contact_motion(contact, states).0,
            };
        }
        Ok(())
    }

    /// One-sided constraint `index`'s transition at `(t, states)`, where its watched value has fallen to zero
    /// (docs/limits.md, docs/contacts.md): a held one is released; a free one that is not moving away meets its
    /// bound or plane in an impact, held there if it does not leave at [`REST_SPEED`] or faster, and released at
    /// once where the hold would pull. Returns what changed, in order, by constraint index: a contact's impact may
    /// change every contact it touches.
    pub(crate) fn limit_transition(
        &self,
        index: usize,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        self.check_count("states", states.len())?;
        if index >= self.limit_count() {
            return Err(ConstraintError::InvalidParameter {
                name: "joint limits and contacts".to_owned(),
                reason: format!(
                    "there is no one-sided constraint {index}: the mechanism has {}",
                    self.limit_count()
                ),
            });
        }
        if let Some(bound) = workspace.held[index].take() {
            self.hold_rows(workspace);
            return Ok(vec![(index, LimitChange::Released { bound })]);
        }
        let mut changes = match index.checked_sub(self.limits.len()) {
            None => self.limit_impact(index, t, states, workspace)?,
            Some(contact) => self.contact_impact(contact, t, states, workspace)?,
        };
        self.hold_rows(workspace);
        self.release_pulling(t, states, workspace, &mut changes)?;
        Ok(changes)
    }

    /// A limit's impact: the joint placed on its nearer bound and its rate reversed times the restitution by an
    /// impulse through the joint-space mass matrix that leaves every other held relation as it was.
    fn limit_impact(
        &self,
        index: usize,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        let space = self.limited_space()?;
        let (mut q, mut v) = (vec![0.0; space.position_count()], vec![0.0; space.velocity_count()]);
        self.read_joints_into(states, &mut q, &mut v, &mut workspace.previous_positions)?;
        let limit = self.limits[index];
        let group = space
            .group_of_joint(limit.joint)
            .expect("limited joints are joint models");
        let (position, velocity) = (group.position_offset(), group.velocity_offset());
        let bound = limit.range.nearer(q[position]);
        let speed_before = -bound.inward() * v[velocity];
        if speed_before < 0.0 {
            return Ok(Vec::new());
        }
        q[position] = limit.range.at(bound);
        let bounce = limit.range.restitution() * speed_before;
        let resting = bounce < REST_SPEED;
        let target = if resting { 0.0 } else { bound.inward() * bounce };
        let mut row = DMatrix::zeros(1, space.velocity_count());
        row[(0, velocity)] = 1.0;
        let equalities = self.equality_rows(&workspace.held);
        let mut residual = DVector::zeros(1 + equalities.nrows());
        residual[0] = target - v[velocity];
        let change = self.metric_correction(t, states, &row, &equalities, &residual)?;
        v.iter_mut().zip(change.iter()).for_each(|(v, dv)| *v += dv);
        self.write_joints_into(t, &q, &v, states, &mut workspace.placed)?;
        workspace.previous_positions.clone_from(&q);
        if !resting {
            return Ok(vec![(
                index,
                LimitChange::Bounced {
                    bound,
                    speed_before,
                    speed_after: bounce,
                },
            )]);
        }
        workspace.held[index] = Some(bound);
        Ok(vec![(index, LimitChange::Held { bound, speed_before })])
    }

    /// A contact's impact (docs/contacts.md "Impact"): every free contact touching its plane ([`TOUCHING`]) and not
    /// moving away from it, with contact `contact`, and every held contact, take impulses along their normals
    /// through the kinetic metric, the other held relations kept: each pushes (≥ 0) and leaves at `e` times the speed
    /// it met the plane with, or pushes nothing and leaves faster (complementarity, by active sets). Contacts leaving
    /// slower than [`REST_SPEED`] are held; held ones that stop pushing are released.
    fn contact_impact(
        &self,
        contact: usize,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        let first = self.limits.len();
        if self.contact_motion(contact, states).1 > 0.0 {
            return Ok(Vec::new());
        }
        // The contacts in the impact: (contact index, was held).
        let mut involved = Vec::new();
        for c in 0..self.contacts.len() {
            let held = workspace.held[first + c].is_some();
            let (height, speed) = self.contact_motion(c, states);
            if held || c == contact || (height <= TOUCHING && speed <= 0.0) {
                involved.push((c, held));
            }
        }
        let indices: Vec<usize> = involved.iter().map(|&(c, _)| c).collect();
        // On their planes first, as a limited joint is put on its bound: the crossing was located a round-off past it.
        let equalities = self.equality_rows(&workspace.held);
        self.place_contacts(
            t,
            states,
            (&indices, false),
            &equalities,
            &mut workspace.previous_positions,
        )?;
        let space = self.limited_space()?;
        let (mut q, mut v) = (vec![0.0; space.position_count()], vec![0.0; space.velocity_count()]);
        self.read_joints_into(states, &mut q, &mut v, &mut workspace.previous_positions)?;
        let rows = self.contact_rows(states, &indices)?;
        let before = &rows * DVector::from_column_slice(&v);
        // Each contact's target speed after the impact: e times its speed before, or 0 below REST_SPEED.
        let targets: Vec<f64> = (indices.iter().zip(before.iter()))
            .map(|(&c, &u)| {
                let bounce = -self.contacts[c].contact.restitution() * u.min(0.0);
                if bounce < REST_SPEED {
                    0.0
                } else {
                    bounce
                }
            })
            .collect();
        let change = self.complementary_impulse(t, states, (&rows, &before), &targets, &equalities)?;
        v.iter_mut().zip(change.iter()).for_each(|(v, dv)| *v += dv);
        self.write_joints_into(t, &q, &v, states, &mut workspace.placed)?;
        let after = &rows * DVector::from_column_slice(&v);
        let mut changes = Vec::new();
        for (k, &(c, was_held)) in involved.iter().enumerate() {
            let (speed_before, speed_after) = (-before[k], after[k]);
            let resting = speed_after < REST_SPEED;
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
        self.place_held_contacts(t, states, workspace)?;
        Ok(changes)
    }

    /// The velocity change of a contact impact: impulses p along the contact `rows` (speeds `before`) reaching the
    /// `targets` on an active set — `p ≥ 0` on it, speeds at or above their targets off it — with the `equalities`
    /// kept. The set starts with every contact; the most negative push leaves it, or the most violated speed joins
    /// it, until both hold (at most 4 passes per contact).
    fn complementary_impulse(
        &self,
        t: f64,
        states: &[State<A>],
        (rows, before): (&DMatrix<f64>, &DVector<f64>),
        targets: &[f64],
        equalities: &DMatrix<f64>,
    ) -> Result<DVector<f64>, ConstraintError> {
        let count = targets.len();
        let scale = before.amax().max(targets.iter().fold(0.0, |m: f64, x| m.max(x.abs())));
        // The responses of every contact and equality row, once: an active set takes its block of them.
        let (response, gram) = self.responses(t, states, &stack(rows, equalities))?;
        let equality_rows = count..count + equalities.nrows();
        let mut active = vec![true; count];
        for _ in 0..4 * count + 1 {
            let chosen: Vec<usize> = (0..count).filter(|&k| active[k]).collect();
            let block: Vec<usize> = chosen.iter().copied().chain(equality_rows.clone()).collect();
            let mut residual = DVector::zeros(block.len());
            for (r, &k) in chosen.iter().enumerate() {
                residual[r] = targets[k] - before[k];
            }
            let sub_gram = gram.select_rows(&block).select_columns(&block);
            let all = self.least_norm(t, &sub_gram, &residual)?;
            let change = response.select_columns(&block) * &all;
            let pushes = all.rows(0, chosen.len());
            let after = before + rows * &change;
            let pulling = (chosen.iter().zip(pushes.iter()))
                .filter(|(_, &p)| p < -COMPLEMENTARITY * pushes.amax().max(f64::MIN_POSITIVE))
                .min_by(|a, b| a.1.total_cmp(b.1));
            if let Some((&k, _)) = pulling {
                active[k] = false;
                continue;
            }
            let sinking = (0..count)
                .filter(|&k| !active[k] && after[k] < targets[k] - COMPLEMENTARITY * scale)
                .min_by(|&a, &b| (after[a] - targets[a]).total_cmp(&(after[b] - targets[b])));
            if let Some(k) = sinking {
                active[k] = true;
                continue;
            }
            return Ok(change);
        }
        Err(ConstraintError::InvalidParameter {
            name: self.unilateral_names(),
            reason: format!("the contact impact at t = {t}: no set of pushing contacts was found"),
        })
    }

    /// Held contacts that pull are released, the most pulling first, until every held one pushes (a hold and its
    /// release at the same instant: the constraint rests where its bound or plane does not press it).
    fn release_pulling(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
        changes: &mut Vec<(usize, LimitChange)>,
    ) -> Result<(), ConstraintError> {
        let mut values = vec![0.0; self.limit_count()];
        while workspace.held.iter().any(Option::is_some) {
            self.limit_values(t, states, workspace, &mut values)?;
            let pulling = (workspace.held.iter().zip(&values).enumerate())
                .filter(|(_, (held, &value))| held.is_some() && value <= 0.0)
                .min_by(|a, b| a.1 .1.total_cmp(b.1 .1));
            let Some((index, _)) = pulling else {
                break;
            };
            let bound = workspace.held[index].take().expect("chosen held");
            self.hold_rows(workspace);
            changes.push((index, LimitChange::Released { bound }));
        }
        Ok(())
    }

    /// The workspace's rows of the articulated solve: the couplings', then one per held limit (`q̈ = 0`) and per
    /// held contact (`n · a_p = 0`).
    pub(super) fn hold_rows(&self, workspace: &mut MechanismWorkspace<A>) {
        workspace.rows.clone_from(&self.coupling_rows);
        for (index, held) in workspace.held.iter().enumerate() {
            if held.is_none() {
                continue;
            }
            workspace.rows.push(match index.checked_sub(self.limits.len()) {
                None => Row::Joints {
                    follower: self.limits[index].joint,
                    leader: self.limits[index].joint,
                    multiplier: 0.0,
                },
                Some(contact) => self.contact_row(contact),
            });
        }
    }

    /// The held contacts placed on their planes and stopped there ([`Mechanism::place_contacts`]), the other held
    /// relations kept.
    pub(super) fn place_held_contacts(
        &self,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        let first = self.limits.len();
        // After every step: nothing to do, and nothing allocated, unless a contact is held.
        if workspace.held[first..].iter().all(Option::is_none) {
            return Ok(());
        }
        let held: Vec<usize> = (0..self.contacts.len())
            .filter(|&c| workspace.held[first + c].is_some())
            .collect();
        let equalities = self.equality_rows(&workspace.held);
        self.place_contacts(t, states, (&held, true), &equalities, &mut workspace.previous_positions)
    }

    /// The joint-space rows that an impact or a projection keeps at their values: the couplings `v_f − m v_l`, the
    /// driven joints' and the held limits' rates.
    fn equality_rows(&self, held: &[Option<Bound>]) -> DMatrix<f64> {
        let Some(space) = self.coordinates() else {
            return DMatrix::zeros(0, 0);
        };
        let velocity_of = |joint: usize| {
            space
                .group_of_joint(joint)
                .expect("coupled, driven and limited joints are joint models")
                .velocity_offset()
        };
        let mut rows: Vec<Vec<(usize, f64)>> = Vec::new();
        for coupling in &self.coupling_rows {
            if let Row::Joints {
                follower,
                leader,
                multiplier,
            } = *coupling
            {
                rows.push(vec![(velocity_of(follower), 1.0), (velocity_of(leader), -multiplier)]);
            }
        }
        for (j, joint) in self.joints.iter().enumerate() {
            if joint.model.as_ref().is_some_and(|model| model.is_driven()) {
                rows.push(vec![(velocity_of(j), 1.0)]);
            }
        }
        for (limit, bound) in self.limits.iter().zip(held) {
            if bound.is_some() {
                rows.push(vec![(velocity_of(limit.joint), 1.0)]);
            }
        }
        let mut matrix = DMatrix::zeros(rows.len(), space.velocity_count());
        for (r, coefficients) in rows.iter().enumerate() {
            for &(k, value) in coefficients {
                matrix[(r, k)] += value;
            }
        }
        matrix
    }

    /// The least change `Δ = M⁻¹Cᵀ(CM⁻¹Cᵀ)⁺ r` in the kinetic metric M (the joint-space mass matrix) that changes
    /// the rows C (`rows` above `equalities`) by `r` (docs/limits.md "Impact").
    pub(super) fn metric_correction(
        &self,
        t: f64,
        states: &[State<A>],
        rows: &DMatrix<f64>,
        equalities: &DMatrix<f64>,
        r: &DVector<f64>,
    ) -> Result<DVector<f64>, ConstraintError> {
        self.impulses(t, states, rows, equalities, r).map(|(change, _)| change)
    }

    /// [`Mechanism::metric_correction`] with the impulses `p = (CM⁻¹Cᵀ)⁺ r` on the rows.
    fn impulses(
        &self,
        t: f64,
        states: &[State<A>],
        rows: &DMatrix<f64>,
        equalities: &DMatrix<f64>,
        r: &DVector<f64>,
    ) -> Result<(DVector<f64>, DVector<f64>), ConstraintError> {
        let (response, gram) = self.responses(t, states, &stack(rows, equalities))?;
        let p = self.least_norm(t, &gram, r)?;
        let change = &response * &p;
        Ok((change, p.rows(0, rows.nrows()).into_owned()))
    }

    /// For joint-space rows C at `states`: `M⁻¹Cᵀ` and the Gram matrix `C M⁻¹ Cᵀ`, M the joint-space mass matrix.
    fn responses(
        &self,
        t: f64,
        states: &[State<A>],
        stacked: &DMatrix<f64>,
    ) -> Result<(DMatrix<f64>, DMatrix<f64>), ConstraintError> {
        let mass = (self.mass_matrix(states)).map_err(|error| self.impact_failed(t, error.to_string()))?;
        let factors = mass
            .cholesky()
            .ok_or_else(|| self.impact_failed(t, "the joint-space mass matrix is not positive definite".to_owned()))?;
        let response = factors.solve(&stacked.transpose());
        let gram = stacked * &response;
        Ok((response, gram))
    }

    /// The impulses `G⁺ r` of a Gram matrix G: rows that repeat others (a held limit on a coupled pair, a fourth corner
    /// on a plane) share by the least-norm solution.
    fn least_norm(&self, t: f64, gram: &DMatrix<f64>, r: &DVector<f64>) -> Result<DVector<f64>, ConstraintError> {
        let largest = gram.diagonal().amax();
        let p = (gram.clone().svd(true, true))
            .solve(r, REPEATED_ROW * largest)
            .map_err(|error| self.impact_failed(t, error.to_owned()))?;
        if !p.iter().all(|x| x.is_finite()) {
            return Err(self.impact_failed(t, "the impulse is not finite".to_owned()));
        }
        Ok(p)
    }

    /// An impact at `t` that could not be solved, naming the one-sided constraints.
    fn impact_failed(&self, t: f64, reason: String) -> ConstraintError {
        ConstraintError::InvalidParameter {
            name: self.unilateral_names(),
            reason: format!("the impact at t = {t}: {reason}"),
        }
    }
}

/// `rows` above `equalities`, one matrix.
fn stack(rows: &DMatrix<f64>, equalities: &DMatrix<f64>) -> DMatrix<f64> {
    let mut stacked = DMatrix::zeros(rows.nrows() + equalities.nrows(), rows.ncols());
    stacked.rows_mut(0, rows.nrows()).copy_from(rows);
    if equalities.nrows() > 0 {
        stacked.rows_mut(rows.nrows(), equalities.nrows()).copy_from(equalities);
    }
    stacked
}
