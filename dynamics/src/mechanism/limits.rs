//! A mechanism's joint limits (docs/limits.md): the values [`crate::simulate()`] watches, and the transitions it
//! makes at their crossings — the impact through the kinetic metric, the hold by a joint-space row, the release.

use nalgebra::{DMatrix, DVector};

use super::articulated::CouplingRow;
use super::joint_space::WorldBody;
use super::{Mechanism, MechanismWorkspace};
use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::limits::{Bound, LimitChange, REST_SPEED};
use crate::state::State;

/// Singular values of the impact's row Gram matrix below this, relative to the largest, belong to rows that repeat
/// others (a held limit on a coupled pair): their share of the impulse is left to the others.
const REDUNDANT_ROW: f64 = 1e-12;

impl<A: Algebra> Mechanism<A> {
    /// The number of limited joints.
    pub(crate) fn limit_count(&self) -> usize {
        self.limits.len()
    }

    /// The name of limit `index`'s joint, if there is that limit.
    pub(crate) fn limit_name(&self, index: usize) -> Option<&str> {
        self.limits.get(index).map(|limit| self.joints[limit.joint].name())
    }

    /// An error naming the limited joints unless the mechanism has joint coordinates (its joint models form a
    /// forest).
    fn limited_space(&self) -> Result<&super::JointSpace, ConstraintError> {
        self.coordinates().ok_or_else(|| ConstraintError::InvalidParameter {
            name: self.names(self.limits.iter().map(|limit| limit.joint)),
            reason: "joint limits need joint coordinates: joint models forming a tree".to_owned(),
        })
    }

    /// Per limit, what [`crate::simulate()`] watches (docs/limits.md "The three states of a limit"): while free the gap to its nearer
    /// bound (rad or m; angles unwrapped from the last positions read), while held the reaction pushing the joint onto
    /// the bound (N m or N; an evaluation of the equations of motion at `(t, states)`).
    pub(crate) fn limit_values(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
        values: &mut [f64],
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        if values.len() != self.limits.len() {
            return Err(ConstraintError::Count {
                what: "limit values",
                expected: self.limits.len(),
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
        for ((limit, held), value) in self.limits.iter().zip(&workspace.held).zip(values.iter_mut()) {
            *value = match held {
                Some(bound) => {
                    row += 1;
                    bound.inward() * workspace.articulated.multipliers()[row - 1]
                }
                None => {
                    let group = space
                        .group_of_joint(limit.joint)
                        .expect("limited joints are joint models");
                    let offset = group.position_offset();
                    let mut q = [0.0];
                    self.read_positions(group, &bodies, previous.map(|p| &p[offset..offset + 1]), &mut q);
                    limit.range.gap(q[0])
                }
            };
        }
        Ok(())
    }

    /// Limit `index`'s transition at `(t, states)`, where its watched value has fallen to zero (docs/limits.md):
    /// a held limit is released; a free one meets its nearer bound in an impact, its joint placed on the bound and
    /// its rate reversed times the restitution by an impulse through the joint-space mass matrix that leaves every
    /// other held relation (couplings, drives, held limits) as it was. A joint that does not leave the bound at
    /// [`REST_SPEED`] or faster is held there, and released at once if the bound would pull. A joint moving away
    /// from the bound is left alone. Returns what changed, in order.
    pub(crate) fn limit_transition(
        &self,
        index: usize,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<LimitChange>, ConstraintError> {
        self.check_count("states", states.len())?;
        if index >= self.limits.len() {
            return Err(ConstraintError::InvalidParameter {
                name: "joint limits".to_owned(),
                reason: format!("there is no limit {index}: the mechanism has {}", self.limits.len()),
            });
        }
        if let Some(bound) = workspace.held[index].take() {
            self.hold_rows(workspace);
            return Ok(vec![LimitChange::Released { bound }]);
        }
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
        self.impulse(t, states, (velocity, target), &workspace.held, &mut v)?;
        self.write_joints_into(t, &q, &v, states, &mut workspace.placed)?;
        workspace.previous_positions.clone_from(&q);
        if !resting {
            return Ok(vec![LimitChange::Bounced {
                bound,
                speed_before,
                speed_after: bounce,
            }]);
        }
        workspace.held[index] = Some(bound);
        self.hold_rows(workspace);
        let mut changes = vec![LimitChange::Held { bound, speed_before }];
        let mut values = vec![0.0; self.limits.len()];
        self.limit_values(t, states, workspace, &mut values)?;
        if values[index] <= 0.0 {
            workspace.held[index] = None;
            self.hold_rows(workspace);
            changes.push(LimitChange::Released { bound });
        }
        Ok(changes)
    }

    /// The workspace's joint-space rows: the couplings', then `q̈ = 0` for each held limit.
    fn hold_rows(&self, workspace: &mut MechanismWorkspace<A>) {
        workspace.rows.clone_from(&self.coupling_rows);
        for (limit, held) in self.limits.iter().zip(&workspace.held) {
            if held.is_some() {
                workspace.rows.push(CouplingRow {
                    follower: limit.joint,
                    leader: limit.joint,
                    multiplier: 0.0,
                });
            }
        }
    }

    /// The impact (docs/limits.md "Impact"): the joint velocities `v` of the bodies at `states` changed
    /// by `Δv = M⁻¹Cᵀp` so that velocity coordinate `index` becomes `target` and every other held row keeps its
    /// value — the couplings `v_f − m v_l`, the driven joints, the held limits. M is the joint-space mass matrix, the
    /// kinetic metric; the impulse p solves `(C M⁻¹ Cᵀ) p = target − C v` on those rows.
    fn impulse(
        &self,
        t: f64,
        states: &[State<A>],
        (index, target): (usize, f64),
        held: &[Option<Bound>],
        v: &mut [f64],
    ) -> Result<(), ConstraintError> {
        let space = self.limited_space()?;
        let failed = |reason: String| ConstraintError::InvalidParameter {
            name: self.names(self.limits.iter().map(|limit| limit.joint)),
            reason: format!("the impact at t = {t}: {reason}"),
        };
        let velocity_of = |joint: usize| {
            space
                .group_of_joint(joint)
                .expect("coupled, driven and limited joints are joint models")
                .velocity_offset()
        };
        // The rows, each (coefficients by velocity coordinate, its target).
        let mut rows: Vec<(Vec<(usize, f64)>, f64)> = vec![(vec![(index, 1.0)], target)];
        for coupling in &self.coupling_rows {
            let (f, l) = (velocity_of(coupling.follower), velocity_of(coupling.leader));
            rows.push((
                vec![(f, 1.0), (l, -coupling.multiplier)],
                v[f] - coupling.multiplier * v[l],
            ));
        }
        for (j, joint) in self.joints.iter().enumerate() {
            if joint.model.as_ref().is_some_and(|model| model.is_driven()) {
                let k = velocity_of(j);
                rows.push((vec![(k, 1.0)], v[k]));
            }
        }
        for (limit, bound) in self.limits.iter().zip(held) {
            if bound.is_some() {
                let k = velocity_of(limit.joint);
                rows.push((vec![(k, 1.0)], v[k]));
            }
        }
        let n = space.velocity_count();
        let mut c = DMatrix::zeros(rows.len(), n);
        let mut rhs = DVector::zeros(rows.len());
        for (r, (coefficients, goal)) in rows.iter().enumerate() {
            let mut now = 0.0;
            for &(k, value) in coefficients {
                c[(r, k)] += value;
                now += value * v[k];
            }
            rhs[r] = goal - now;
        }
        let mass = self.mass_matrix(states).map_err(|error| failed(error.to_string()))?;
        let factors = mass
            .cholesky()
            .ok_or_else(|| failed("the joint-space mass matrix is not positive definite".to_owned()))?;
        let response = factors.solve(&c.transpose());
        let gram = &c * &response;
        let largest = gram.diagonal().amax();
        let p = gram
            .svd(true, true)
            .solve(&rhs, REDUNDANT_ROW * largest)
            .map_err(|error| failed(error.to_owned()))?;
        let change = response * p;
        if !change.iter().all(|x| x.is_finite()) {
            return Err(failed("the impulse is not finite".to_owned()));
        }
        v.iter_mut().zip(change.iter()).for_each(|(v, dv)| *v += dv);
        Ok(())
    }
}
