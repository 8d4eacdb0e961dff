//! A mechanism's one-sided constraints — its joint limits (docs/limits.md), then its contacts (docs/contacts.md) —
//! as [`crate::simulate()`] sees them: the values it watches, and the transitions it makes at their crossings (the
//! impact through the kinetic metric, the hold by a row of the articulated solve, the release).

use nalgebra::{DMatrix, DVector, Vector3};

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::contacts::OUTSIDE_FACE;
use crate::eigen::least_norm_by_blocks;
use crate::limits::{Bound, LimitChange, REST_SPEED};
use crate::mechanism::articulated::{Row, REPEATED_ROW};
use crate::mechanism::contact_impacts::AT_REST;
use crate::mechanism::contacts::stack;
use crate::mechanism::error::listed;
use crate::mechanism::friction::{tangent_basis, NOT_WATCHED, STOP_SPEED};
use crate::mechanism::joint_space::{JointSpace, WorldBody};
use crate::mechanism::model::{Mechanism, MechanismWorkspace};
use crate::mechanism::parts::Slip;
use crate::state::State;

impl<A: Algebra> Mechanism<A> {
    /// The number of one-sided constraints [`crate::simulate()`] watches: limited joints, then contacts, then the
    /// friction of each contact that has it.
    pub(crate) fn limit_count(&self) -> usize {
        self.limits.len() + self.contacts.len() + self.frictional.len()
    }

    /// The name of one-sided constraint `index`: its joint's for a limit, the contact's for a contact and for its
    /// friction.
    pub(crate) fn limit_name(&self, index: usize) -> Option<&str> {
        let bounded = self.limits.len() + self.contacts.len();
        if index < self.limits.len() {
            Some(self.joints[self.limits[index].joint].name())
        } else if index < bounded {
            Some(self.contacts[index - self.limits.len()].name.as_str())
        } else {
            let contact = *self.frictional.get(index - bounded)?;
            Some(self.contacts[contact].name.as_str())
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
        listed((0..self.limits.len() + self.contacts.len()).filter_map(|index| self.limit_name(index)))
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
        if !workspace.switches_renewed {
            self.renew_switches(states, workspace);
        }
        self.check_features(t, states, &workspace.held)?;
        if workspace.held.iter().any(Option::is_some) {
            self.evaluate_states(t, states, workspace)?;
        }
        let bodies: Vec<WorldBody> = states.iter().enumerate().map(|(i, s)| self.world_body(i, s)).collect();
        let previous =
            (workspace.previous_positions.len() == space.position_count()).then_some(&workspace.previous_positions);
        let multipliers = self.held_multipliers(workspace);
        let motions = vec![std::cell::OnceCell::new(); states.len()];
        let (bounded, friction) = values.split_at_mut(workspace.held.len());
        for (index, (held, value)) in workspace.held.iter().zip(bounded.iter_mut()).enumerate() {
            *value = match (held, index.checked_sub(self.limits.len())) {
                (Some(bound), contact) => {
                    let row = workspace.held_rows[index].expect("a held constraint has its row");
                    let push = bound.inward() * multipliers[row];
                    // A switching contact also lets go where its touching point leaves its face or edges.
                    match contact {
                        Some(c) if self.contacts[c].switching => {
                            push.min(OUTSIDE_FACE - self.frame_among(c, states, &motions).outside)
                        }
                        _ => push,
                    }
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
                (None, Some(contact)) if workspace.repeats[contact].is_some() => NOT_WATCHED,
                (None, Some(contact)) if self.contacts[contact].switching && !workspace.watched[contact] => NOT_WATCHED,
                (None, Some(contact)) => self.frame_among(contact, states, &motions).gap,
            };
        }
        for (&contact, value) in self.frictional.iter().zip(friction) {
            *value = self.friction_value(contact, states, workspace, &multipliers);
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
        let bounded = workspace.held.len();
        let mut changes = if index >= bounded {
            self.friction_transition(self.frictional[index - bounded], t, states, workspace)?
        } else if workspace.held[index].is_some() {
            self.release(index, t, states, workspace)?
        } else {
            match index.checked_sub(self.limits.len()) {
                None => self.limit_impact(index, t, states, workspace)?,
                // Not a contact; but another may meet at the same instant, a round-off later.
                Some(contact) if self.lets_go(contact, states, workspace) => {
                    self.hand_over(AT_REST, t, states, workspace)?
                }
                Some(contact) => self.contact_impact((contact, AT_REST), t, states, workspace)?,
            }
        };
        self.hold_rows(workspace);
        self.settle(t, states, workspace, &mut changes)?;
        Ok(changes)
    }

    /// One-sided constraint `index`, held, released: its bound or plane stopped pushing. A sliding contact whose push
    /// turned to a pull and that, released, would sink into its plane has no consistent state: Painlevé's paradox, an
    /// error naming it (docs/contacts.md "Friction").
    fn release(
        &self,
        index: usize,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        let bound = workspace.held[index].take().expect("a released constraint is held");
        self.hold_rows(workspace);
        let mut changes = vec![(index, LimitChange::Released { bound })];
        if let Some(contact) = index.checked_sub(self.limits.len()) {
            if self.lets_go(contact, states, workspace) {
                // A switching contact leaving its face goes beyond the plane's edge, where it may sink (no paradox),
                // and hands over to the features that meet there (a ball's face contact to the edge it rolls over),
                // at once rather than a round-off of sinking later.
                changes.extend(self.hand_over(REST_SPEED, t, states, workspace)?);
            } else {
                self.check_release(contact, t, states, workspace)?;
            }
        }
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

    /// Every held constraint made consistent after a transition at `(t, states)`, one change at a time: a held one
    /// that pulls is released (the most pulling first), else a sticking contact whose friction force has left its
    /// cone starts to slide (the furthest out first), until every held one pushes and every sticking one holds (a hold
    /// and its release at the same instant: the constraint rests where its bound or plane does not press it).
    fn settle(
        &self,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
        changes: &mut Vec<(usize, LimitChange)>,
    ) -> Result<(), ConstraintError> {
        let mut values = vec![0.0; self.limit_count()];
        let bounded = workspace.held.len();
        for _ in 0..=2 * self.limit_count() {
            if workspace.held.iter().all(Option::is_none) {
                return Ok(());
            }
            self.limit_values(t, states, workspace, &mut values)?;
            let pulling = (workspace.held.iter().zip(&values).enumerate())
                .filter(|(_, (held, &value))| held.is_some() && value <= 0.0)
                .min_by(|a, b| a.1 .1.total_cmp(b.1 .1));
            if let Some((index, _)) = pulling {
                changes.extend(self.release(index, t, states, workspace)?);
                continue;
            }
            let slipping = (self.frictional.iter().zip(&values[bounded..]))
                .filter(|&(&c, &margin)| {
                    workspace.held[self.limits.len() + c].is_some()
                        && workspace.slips[c] == Slip::Sticking
                        && margin < 0.0
                })
                .min_by(|a, b| a.1.total_cmp(b.1));
            let Some((&contact, _)) = slipping else {
                return Ok(());
            };
            changes.extend(self.start_slide(contact, t, states, workspace)?);
        }
        Err(ConstraintError::InvalidParameter {
            name: self.unilateral_names(),
            reason: format!("at t = {t} no consistent set of held, sliding and sticking constraints was found"),
        })
    }

    /// A held contact with friction at a transition of its friction value (docs/contacts.md "Friction"): a slide
    /// whose slip along its starting direction reached zero has stopped, and sticks if the cone can hold it, else
    /// slides on in the direction of maximal dissipation (a slide that only turned renews its direction); a stick
    /// whose friction force reached the cone starts to slide.
    fn friction_transition(
        &self,
        contact: usize,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        if workspace.held[self.limits.len() + contact].is_none() {
            return Ok(Vec::new());
        }
        if workspace.slips[contact] == Slip::Sticking {
            return self.start_slide(contact, t, states, workspace);
        }
        let slip = self.contact_slip(contact, states);
        let speed = slip.norm();
        if speed > STOP_SPEED {
            workspace.slips[contact] = Slip::Sliding {
                reference: slip / speed,
            };
            return Ok(Vec::new());
        }
        // A slide just begun (from rest, at the slip's +0) speeds up along its direction: no stop.
        let Slip::Sliding { reference } = workspace.slips[contact] else {
            unreachable!("a sticking contact was handled above")
        };
        self.evaluate_states(t, states, workspace)?;
        if self.touching_acceleration(contact, workspace).dot(&reference) > 0.0 {
            return Ok(Vec::new());
        }
        // Every held slide with no slip left stops with it: the contacts of one rigid motion stop together (a block's
        // corners), and a slide whose direction is round-off would push the others. Those the cone cannot hold slide
        // on when the mechanism settles.
        let mut changes = Vec::new();
        for &c in &self.frictional {
            let held = workspace.held[self.limits.len() + c].is_some();
            if !held || workspace.slips[c] == Slip::Sticking {
                continue;
            }
            let slip = self.contact_slip(c, states).norm();
            if c == contact || slip <= STOP_SPEED {
                workspace.slips[c] = Slip::Sticking;
                let index = self.friction_index(c).expect("a contact with friction");
                changes.push((index, LimitChange::Stuck { slip_before: slip }));
            }
        }
        self.hold_rows(workspace);
        self.place_held_contacts(t, states, workspace)?;
        Ok(changes)
    }

    /// The sticking contacts that slide when sticking contact `contact`'s friction leaves its cone: those whose margin
    /// at the widest split is at its least (within round-off of contact `contact`'s), which leave together (a block's
    /// corners), each along the direction of maximal dissipation from the one opposite its sticking force.
    fn start_slide(
        &self,
        contact: usize,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        self.evaluate_states(t, states, workspace)?;
        let multipliers = self.held_multipliers(workspace);
        let mut values = vec![0.0; self.limit_count()];
        let bounded = workspace.held.len();
        for (&c, value) in self.frictional.iter().zip(&mut values[bounded..]) {
            *value = self.friction_value(c, states, workspace, &multipliers);
        }
        let margin = |c: usize| values[self.friction_index(c).expect("a contact with friction")];
        let scale = multipliers.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let leaving: Vec<usize> = (self.frictional.iter().copied())
            .filter(|&c| {
                workspace.held[self.limits.len() + c].is_some()
                    && workspace.slips[c] == Slip::Sticking
                    && (c == contact || margin(c) <= margin(contact) + SAME_MARGIN * scale)
            })
            .collect();
        let guesses: Vec<Vector3<f64>> = leaving
            .iter()
            .map(|&c| {
                let row = workspace.held_rows[self.limits.len() + c].expect("a sticking contact is held");
                let [first, second] = tangent_basis(&self.contact_frame(c, states).normal);
                let force = first * multipliers[row + 1] + second * multipliers[row + 2];
                if force.norm() > 0.0 {
                    -force.normalize()
                } else {
                    first
                }
            })
            .collect();
        let directions = self.slide_from_rest(&leaving, t, states, workspace, &guesses)?;
        Ok((leaving.iter().zip(directions))
            .map(|(&c, direction)| {
                let index = self.friction_index(c).expect("a contact with friction");
                (index, LimitChange::Slipped { direction })
            })
            .collect())
    }

    /// An error unless contact `contact`, just released, moves off its plane or along it: one that sinks into it
    /// (sliding with a friction that turned its push into a pull) has no consistent state, Painlevé's paradox.
    fn check_release(
        &self,
        contact: usize,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        if !matches!(workspace.slips[contact], Slip::Sliding { .. }) || !self.contacts[contact].friction.is_some() {
            return Ok(());
        }
        self.evaluate_states(t, states, workspace)?;
        let normal = self.workspace_frame(contact, workspace).normal;
        let acceleration = normal.dot(&self.touching_acceleration(contact, workspace));
        let scale = self
            .touching_acceleration(contact, workspace)
            .norm()
            .max(f64::MIN_POSITIVE);
        if acceleration < -PAINLEVE_TOLERANCE * scale {
            return Err(ConstraintError::InvalidParameter {
                name: self.contacts[contact].name.clone(),
                reason: format!(
                    "at t = {t} the sliding contact has no consistent state (Painlevé's paradox): with friction {} its \
                     plane would have to pull to hold it, and released it accelerates into the plane at {:e} m/s²",
                    self.contacts[contact].friction.kinetic(),
                    -acceleration
                ),
            });
        }
        Ok(())
    }

    /// The workspace's rows of the articulated solve: the couplings', then one per held limit (`q̈ = 0`) and per
    /// held contact (`n · a_p = 0`), with two tangential ones per sticking contact ([`Mechanism::contact_hold_rows`]).
    pub(super) fn hold_rows(&self, workspace: &mut MechanismWorkspace<A>) {
        workspace.rows.clone_from(&self.coupling_rows);
        for (index, held) in workspace.held.iter().enumerate() {
            workspace.held_rows[index] = None;
            if held.is_none() {
                continue;
            }
            workspace.held_rows[index] = Some(workspace.rows.len());
            match index.checked_sub(self.limits.len()) {
                None => workspace.rows.push(Row::Joints {
                    follower: self.limits[index].joint,
                    leader: self.limits[index].joint,
                    multiplier: 0.0,
                }),
                Some(contact) => {
                    let slip = self.contacts[contact]
                        .friction
                        .is_some()
                        .then_some(workspace.slips[contact]);
                    self.contact_hold_rows(contact, slip, &mut workspace.rows);
                }
            }
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
        let sticking: Vec<usize> = (held.iter().copied())
            .filter(|&c| self.contacts[c].friction.is_some() && workspace.slips[c] == Slip::Sticking)
            .collect();
        let equalities = self.equality_rows(&workspace.held);
        self.place_contacts(
            t,
            states,
            (&held, &sticking, true),
            &equalities,
            &mut workspace.previous_positions,
        )
    }

    /// The joint-space rows that an impact or a projection keeps at their values: the couplings `v_f − m v_l`, the
    /// driven joints' and the held limits' rates.
    pub(super) fn equality_rows(&self, held: &[Option<Bound>]) -> DMatrix<f64> {
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
        let (response, gram) = self.responses(t, states, &stack(&[rows, equalities]))?;
        let p = self.least_norm(t, &gram, r, true)?;
        let change = &response * &p;
        Ok((change, p.rows(0, rows.nrows()).into_owned()))
    }

    /// For joint-space rows C at `states`: `M⁻¹Cᵀ` and the Gram matrix `C M⁻¹ Cᵀ`, M the joint-space mass matrix.
    pub(super) fn responses(
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

    /// The impulses `G⁺ r` of a matrix G: rows that repeat others (a held limit on a coupled pair, a fourth corner on a
    /// plane) share by the least-norm solution. Block by block: a `symmetric` G (a Gram matrix `C M⁻¹ Cᵀ`) by the
    /// pivoted Cholesky least-norm solve, another (an impact's modes, sliding friction in its rows) by the SVD.
    pub(super) fn least_norm(
        &self,
        t: f64,
        gram: &DMatrix<f64>,
        r: &DVector<f64>,
        symmetric: bool,
    ) -> Result<DVector<f64>, ConstraintError> {
        let largest = gram.diagonal().amax();
        let p = least_norm_by_blocks(gram, r, REPEATED_ROW * largest, |_| !symmetric);
        if !p.iter().all(|x| x.is_finite()) {
            return Err(self.impact_failed(t, "the impulse is not finite".to_owned()));
        }
        Ok(p)
    }

    /// An impact at `t` that could not be solved, naming the one-sided constraints.
    pub(super) fn impact_failed(&self, t: f64, reason: String) -> ConstraintError {
        ConstraintError::InvalidParameter {
            name: self.unilateral_names(),
            reason: format!("the impact at t = {t}: {reason}"),
        }
    }
}

/// Sticking contacts whose margins to their cones differ by less than this, relative to the loads, leave together.
const SAME_MARGIN: f64 = 1e-9;

/// A released sliding contact accelerating into its plane faster than this, relative to its touching point's whole
/// acceleration, has no consistent state (Painlevé's paradox); below it the acceleration is round-off.
const PAINLEVE_TOLERANCE: f64 = 1e-9;
