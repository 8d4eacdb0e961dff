//! A mechanism's joint coordinates in and out of the bodies' states (docs/mechanisms.md §M7): the joint positions
//! and velocities read off the states, the states placed by forward kinematics from joint positions and
//! velocities, and the projection of a state onto its joint coordinates and couplings.

use nalgebra::{Isometry3, Matrix3, Vector3};

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::joint_models::Side;
use crate::limits::Bound;
use crate::mechanism::articulated::{axis_column, axis_rate};
use crate::mechanism::error::MechanismError;
use crate::mechanism::joint_space::{CoordinateGroup, JointSpace, WorldBody};
use crate::mechanism::model::Mechanism;
use crate::mechanism::spatial::join;
use crate::motor;
use crate::state::State;

impl<A: Algebra> Mechanism<A> {
    /// The coordinates, built on first use after a change.
    #[inline]
    pub(crate) fn coordinates(&self) -> Option<&JointSpace> {
        self.joint_space
            .get_or_init(|| JointSpace::new(&self.bodies, &self.joints))
            .as_ref()
    }

    /// The joint coordinates' layout, if the joint models form a forest (always, for models added by
    /// [`Mechanism::connect`] alone).
    pub fn joint_space(&self) -> Result<&JointSpace, MechanismError> {
        self.coordinates()
            .ok_or_else(|| MechanismError::NoJointSpace("its joint models do not form a forest".to_owned()))
    }

    pub(super) fn check_states(&self, states: &[State<A>]) -> Result<(), MechanismError> {
        if states.len() != self.bodies.len() {
            return Err(MechanismError::Count {
                what: "states",
                expected: self.bodies.len(),
                got: states.len(),
            });
        }
        if let Some(index) = states.iter().position(|s| !s.is_representable()) {
            return Err(MechanismError::NotFinite { what: "state", index });
        }
        Ok(())
    }

    #[inline]
    pub(super) fn world_body(&self, index: usize, state: &State<A>) -> WorldBody {
        let (position, rotation) = state.pose();
        let velocity = state.world_velocity(&self.bodies[index].body);
        WorldBody {
            pose: Isometry3::from_parts(position.into(), rotation),
            rotation: *rotation.to_rotation_matrix().matrix(),
            angular: velocity.angular,
            linear: velocity.linear,
        }
    }

    #[inline]
    pub(super) fn parent_of(&self, group: &CoordinateGroup, bodies: &[WorldBody]) -> WorldBody {
        group.parent.map_or(WorldBody::world(), |p| bodies[p])
    }

    /// The joint positions at `states` (see [`JointSpace`] for their order). Angles are taken nearest `previous`
    /// (a position vector, e.g. the last sample's), so continuous joints unwrap across turns and quaternions stay
    /// continuous; without it angles are in (−π, π]. Off the joints (drift), each joint's own reading of the
    /// relative pose: a revolute joint's turn about its axis.
    ///
    /// A hinge turned 4 rad reads −2.28 rad alone, 4 rad next to a previous reading of 3.9:
    ///
    /// ```
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use dynamics::{Body, Mechanism, Pga, Reference};
    /// use nalgebra::{Isometry3, Vector3};
    ///
    /// let wheel = Body::cylinder(1.0, 0.3, 0.05)?;
    /// let mut axle = Mechanism::<Pga>::new();
    /// let body = axle.add_body("wheel", wheel)?;
    /// let joint = JointModel::new("axle", JointKind::Revolute { axis: Vector3::z() }, Isometry3::identity(),
    ///     Isometry3::identity())?;
    /// axle.connect(body, Reference::World, joint)?;
    /// let states = axle.states_from_joints(&[4.0], &[0.0])?;
    /// assert!((axle.joint_positions(&states, None)?[0] - (4.0 - std::f64::consts::TAU)).abs() < 1e-14);
    /// assert!((axle.joint_positions(&states, Some(&[3.9]))?[0] - 4.0).abs() < 1e-14);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn joint_positions(&self, states: &[State<A>], previous: Option<&[f64]>) -> Result<Vec<f64>, MechanismError> {
        let space = self.joint_space()?;
        self.check_states(states)?;
        if let Some(previous) = previous {
            if previous.len() != space.positions {
                return Err(MechanismError::Count {
                    what: "previous joint positions",
                    expected: space.positions,
                    got: previous.len(),
                });
            }
        }
        let bodies: Vec<WorldBody> = states.iter().enumerate().map(|(i, s)| self.world_body(i, s)).collect();
        let mut q = vec![0.0; space.positions];
        for group in &space.groups {
            let range = group.positions();
            self.read_positions(group, &bodies, previous.map(|p| &p[range.clone()]), &mut q[range]);
        }
        Ok(q)
    }

    #[inline]
    pub(super) fn read_positions(
        &self,
        group: &CoordinateGroup,
        bodies: &[WorldBody],
        previous: Option<&[f64]>,
        out: &mut [f64],
    ) {
        let parent = self.parent_of(group, bodies);
        let child = &bodies[group.body];
        let relative = parent.pose.inverse() * child.pose;
        let joint_pose = group.model.parent_frame().inverse() * relative * group.model.child_frame();
        group.model.coordinates_of(&joint_pose, previous, out);
    }

    /// The joint velocities at `states` (see [`JointSpace`]): each joint's rates in the relative motion of its child
    /// and parent, read at the joint origin.
    pub fn joint_velocities(&self, states: &[State<A>]) -> Result<Vec<f64>, MechanismError> {
        let space = self.joint_space()?;
        self.check_states(states)?;
        let bodies: Vec<WorldBody> = states.iter().enumerate().map(|(i, s)| self.world_body(i, s)).collect();
        let mut v = vec![0.0; space.velocities];
        for group in &space.groups {
            let range = group.velocities();
            self.read_velocities(group, &bodies, &mut v[range]);
        }
        Ok(v)
    }

    #[inline]
    pub(super) fn read_velocities(&self, group: &CoordinateGroup, bodies: &[WorldBody], out: &mut [f64]) {
        let parent = self.parent_of(group, bodies);
        let child = &bodies[group.body];
        let x = child
            .pose
            .transform_point(&group.model.child_frame().translation.vector.into())
            .coords;
        let relative = join(
            child.angular - parent.angular,
            child.velocity_at(&x) - parent.velocity_at(&x),
        );
        for (k, axis) in group.model.axes().iter().enumerate() {
            let column = axis_column(axis, &side_rotation(axis.side, &parent, child), &Vector3::zeros());
            out[k] = axis_rate(&column, axis.motion, &relative, &Vector3::zeros());
        }
    }

    /// The bodies' states at joint positions `q` and velocities `v` (see [`JointSpace`]), by exact forward
    /// kinematics: each child at `parent · parent_frame · J(q) · child_frame⁻¹`, moving with its parent's velocity
    /// plus the joint's motions. Errors: wrong counts, non-finite or out-of-range coordinates (the joint named), a
    /// quaternion of zero length.
    pub fn states_from_joints(&self, q: &[f64], v: &[f64]) -> Result<Vec<State<A>>, MechanismError> {
        let space = self.joint_space()?;
        for (what, slice, expected) in [
            ("joint positions", q, space.positions),
            ("joint velocities", v, space.velocities),
        ] {
            if slice.len() != expected {
                return Err(MechanismError::Count {
                    what,
                    expected,
                    got: slice.len(),
                });
            }
        }
        if let Some(group) = space.groups.iter().find(|g| {
            !v[g.velocities()]
                .iter()
                .all(|x| x.is_finite() && x.abs() <= crate::state::MAX_COORDINATE)
        }) {
            return Err(ConstraintError::InvalidParameter {
                name: group.name.clone(),
                reason: format!(
                    "joint velocities must be finite and at most 1e50, got {:?}",
                    &v[group.velocities()]
                ),
            }
            .into());
        }
        let mut bodies = vec![WorldBody::world(); self.bodies.len()];
        for &g in &space.order {
            let group = &space.groups[g];
            let parent = self.parent_of(group, &bodies);
            bodies[group.body] = self.place(group, &parent, &q[group.positions()], &v[group.velocities()])?;
        }
        let states: Vec<State<A>> = bodies
            .iter()
            .enumerate()
            .map(|(i, b)| {
                State::from_world_twist(
                    &self.bodies[i].body,
                    b.pose.translation.vector,
                    &b.pose.rotation,
                    b.angular,
                    b.linear,
                )
            })
            .collect();
        // Coordinates each within range can still add up beyond it (a chain of long slides).
        if let Some(index) = states.iter().position(|s| !s.is_representable()) {
            return Err(MechanismError::NotFinite { what: "state", index });
        }
        Ok(states)
    }

    /// [`Self::place`] at time `t`: a driven joint at its drive's value and rate then, whatever `q` and `v` hold
    /// (an integrator's copy of a driven coordinate carries its truncation error; the drive is exact).
    #[inline]
    pub(super) fn place_at(
        &self,
        t: f64,
        group: &CoordinateGroup,
        parent: &WorldBody,
        q: &[f64],
        v: &[f64],
    ) -> Result<WorldBody, ConstraintError> {
        match group.model.drive_at(t) {
            Some(drive) => self.place(group, parent, &[drive.value], &[drive.rate]),
            None => self.place(group, parent, q, v),
        }
    }

    /// The child of `group` placed by its joint positions and velocities relative to `parent`.
    #[inline]
    fn place(
        &self,
        group: &CoordinateGroup,
        parent: &WorldBody,
        q: &[f64],
        v: &[f64],
    ) -> Result<WorldBody, ConstraintError> {
        let pose = parent.pose * group.model.relative_pose(q)?;
        let rotation = *pose.rotation.to_rotation_matrix().matrix();
        let x = pose.translation.vector + rotation * group.model.child_frame().translation.vector;
        let (mut angular, mut at_joint) = (parent.angular, parent.velocity_at(&x));
        for (axis, rate) in group.model.axes().iter().zip(v) {
            let d = match axis.side {
                Side::Parent => parent.rotation * axis.direction,
                Side::Child => rotation * axis.direction,
            };
            match axis.motion {
                crate::joint_models::Motion::Rotation => angular += d * *rate,
                crate::joint_models::Motion::Translation => at_joint += d * *rate,
            }
        }
        // Every turn is about an axis through the child's joint origin x, so x moves with the slides alone.
        Ok(WorldBody {
            pose,
            rotation,
            angular,
            linear: at_joint + angular.cross(&(pose.translation.vector - x)),
        })
    }

    /// Projects states onto the joint models by their coordinates (docs/mechanisms.md §M7): the roots keep their
    /// states; every other body is placed by its joint's positions and velocities read from the states (taken
    /// nearest `previous` positions, if any, which it updates), a driven joint's its drive's at `t`, the couplings
    /// imposed on them and the held limits at their bounds (per limit, `held`), from its parent as placed. Exact on
    /// the joints to round-off, in O(N).
    pub(crate) fn project_coordinates(
        &self,
        t: f64,
        states: &mut [State<A>],
        previous: &mut Vec<f64>,
        held: &[Option<Bound>],
    ) -> Result<(), ConstraintError> {
        let Some(space) = self.coordinates() else {
            return Ok(());
        };
        let read: Vec<WorldBody> = states.iter().enumerate().map(|(i, s)| self.world_body(i, s)).collect();
        let mut q = vec![0.0; space.positions];
        let mut v = vec![0.0; space.velocities];
        let before = (previous.len() == space.positions).then_some(previous.as_slice());
        for group in &space.groups {
            let range = group.positions();
            self.read_positions(group, &read, before.map(|p| &p[range.clone()]), &mut q[range]);
            self.read_velocities(group, &read, &mut v[group.velocities()]);
            if let Some(drive) = group.model.drive_at(t) {
                q[group.position_offset] = drive.value;
                v[group.velocity_offset] = drive.rate;
            }
        }
        for coupling in &self.couplings {
            let at =
                |joint: usize| &space.groups[space.group_of_joint[joint].expect("coupled joints are joint models")];
            let (follower, leader) = (at(coupling.follower), at(coupling.leader));
            q[follower.position_offset] = coupling.multiplier * q[leader.position_offset] + coupling.offset;
            v[follower.velocity_offset] = coupling.multiplier * v[leader.velocity_offset];
        }
        for (limit, bound) in self.limits.iter().zip(held) {
            if let Some(bound) = bound {
                let group = &space.groups[space.group_of_joint[limit.joint].expect("limited joints are joint models")];
                q[group.position_offset] = limit.range.at(*bound);
                v[group.velocity_offset] = 0.0;
            }
        }
        let mut placed = read;
        for &g in &space.order {
            let group = &space.groups[g];
            if group.joint.is_none() {
                states[group.body].motor = motor::normalise::<A>(states[group.body].motor);
                continue;
            }
            let parent = self.parent_of(group, &placed);
            let child = self.place(group, &parent, &q[group.positions()], &v[group.velocities()])?;
            placed[group.body] = child;
            states[group.body] = State::from_world_twist(
                &self.bodies[group.body].body,
                child.pose.translation.vector,
                &child.pose.rotation,
                child.angular,
                child.linear,
            );
        }
        *previous = q;
        Ok(())
    }

    /// The couplings' largest position and velocity residuals, `|q_f − m q_l − offset|` and `|q̇_f − m q̇_l|`.
    pub(crate) fn coupling_violation(&self, states: &[State<A>]) -> (f64, f64) {
        let (Some(space), false) = (self.coordinates(), self.couplings.is_empty()) else {
            return (0.0, 0.0);
        };
        let bodies: Vec<WorldBody> = states.iter().enumerate().map(|(i, s)| self.world_body(i, s)).collect();
        let (mut position, mut velocity) = (0.0f64, 0.0f64);
        for coupling in &self.couplings {
            let read = |joint: usize| {
                let group = &space.groups[space.group_of_joint[joint].expect("coupled joints are joint models")];
                let (mut q, mut v) = ([0.0], [0.0]);
                self.read_positions(group, &bodies, None, &mut q);
                self.read_velocities(group, &bodies, &mut v);
                (q[0], v[0])
            };
            let ((qf, vf), (ql, vl)) = (read(coupling.follower), read(coupling.leader));
            position = position.max((qf - coupling.multiplier * ql - coupling.offset).abs());
            velocity = velocity.max((vf - coupling.multiplier * vl).abs());
        }
        (position, velocity)
    }

    /// The joint positions and velocities of `states` into the slices, angles unwrapped from `previous` (when it
    /// has the right length), which then holds these positions.
    #[inline]
    pub(crate) fn read_joints_into(
        &self,
        states: &[State<A>],
        positions: &mut [f64],
        velocities: &mut [f64],
        previous: &mut Vec<f64>,
    ) -> Result<(), ConstraintError> {
        let Some(space) = self.coordinates() else {
            return Err(ConstraintError::InvalidParameter {
                name: "joint coordinates".to_owned(),
                reason: "the joint models do not form a forest".to_owned(),
            });
        };
        check_coordinate_counts(space, positions.len(), velocities.len())?;
        let bodies: Vec<WorldBody> = states.iter().enumerate().map(|(i, s)| self.world_body(i, s)).collect();
        let before = (previous.len() == space.positions).then_some(previous.as_slice());
        for group in &space.groups {
            let range = group.positions();
            self.read_positions(group, &bodies, before.map(|p| &p[range.clone()]), &mut positions[range]);
            self.read_velocities(group, &bodies, &mut velocities[group.velocities()]);
        }
        previous.clear();
        previous.extend_from_slice(positions);
        Ok(())
    }

    /// The bodies' states at joint positions and velocities, the driven joints at their drives at `t`, into
    /// `states` (`placed` is scratch).
    #[inline]
    pub(crate) fn write_joints_into(
        &self,
        t: f64,
        positions: &[f64],
        velocities: &[f64],
        states: &mut [State<A>],
        placed: &mut Vec<WorldBody>,
    ) -> Result<(), ConstraintError> {
        let Some(space) = self.coordinates() else {
            return Err(ConstraintError::InvalidParameter {
                name: "joint coordinates".to_owned(),
                reason: "the joint models do not form a forest".to_owned(),
            });
        };
        check_coordinate_counts(space, positions.len(), velocities.len())?;
        placed.clear();
        placed.resize(self.bodies.len(), WorldBody::world());
        for &g in &space.order {
            let group = &space.groups[g];
            let parent = self.parent_of(group, placed);
            placed[group.body] = self.place_at(
                t,
                group,
                &parent,
                &positions[group.positions()],
                &velocities[group.velocities()],
            )?;
        }
        for (i, (state, body)) in states.iter_mut().zip(placed.iter()).enumerate() {
            *state = State::from_world_twist(
                &self.bodies[i].body,
                body.pose.translation.vector,
                &body.pose.rotation,
                body.angular,
                body.linear,
            );
        }
        Ok(())
    }
}

/// An error unless slices of `positions` and `velocities` entries fit `space`.
pub(super) fn check_coordinate_counts(
    space: &JointSpace,
    positions: usize,
    velocities: usize,
) -> Result<(), ConstraintError> {
    for (what, expected, got) in [
        ("joint positions", space.positions, positions),
        ("joint velocities", space.velocities, velocities),
    ] {
        if got != expected {
            return Err(ConstraintError::Count { what, expected, got });
        }
    }
    Ok(())
}

/// The rotation of the body a joint axis is fixed in.
fn side_rotation(side: Side, parent: &WorldBody, child: &WorldBody) -> Matrix3<f64> {
    match side {
        Side::Parent => parent.rotation,
        Side::Child => child.rotation,
    }
}
