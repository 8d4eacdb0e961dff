//! Joint coordinates of a mechanism (docs/mechanisms.md §M7): the joint models and the free roots, their positions
//! and velocities in and out of the bodies' states, and the joint-space quantities a controller needs — the mass
//! matrix M(q), the bias forces h(q, v) and the inverse dynamics `τ = M q̈ + h` — computed from the bodies' own
//! states (the maximal coordinates), in world axes about one reference point so that nothing moves between frames.
//!
//! The coordinates come in groups: first every free root (a body no joint model holds), named after the body, with
//! the pose and twist of its reference frame (7 positions: x, y, z, qw, qx, qy, qz; 6 velocities: the frame origin's
//! velocity and the angular velocity, both in the frame's axes — Pinocchio's free flyer); then every joint model in
//! the order the joints were added. A group's generalised force pairs with its velocities by the power: a revolute
//! joint's torque, a prismatic joint's force, a free root's force then moment about its frame origin, in its axes.

use nalgebra::{DMatrix, DVector, Isometry3, Matrix3, Vector3, Vector6};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::{ConstraintError, Kinematics};
use crate::joints::{JointKind, JointModel, Side};
use crate::limits::Bound;
use crate::mechanism::articulated::{axis_column, axis_rate};
use crate::mechanism::spatial::{force_cross, motion_cross, spatial_body, Inertia6, SpatialBody};
use crate::mechanism::{BodyId, JointId, Mechanism, MechanismError, MechanismWorkspace};
use crate::motor;
use crate::state::State;

/// One group of coordinates: a joint model, or a free root.
#[derive(Clone, Debug)]
pub struct CoordinateGroup {
    name: String,
    model: JointModel,
    body: usize,
    parent: Option<usize>,
    joint: Option<JointId>,
    position_offset: usize,
    velocity_offset: usize,
}

impl CoordinateGroup {
    /// The joint's name, or the root body's.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The joint model (a free joint to the world for a root).
    pub fn model(&self) -> &JointModel {
        &self.model
    }

    /// The body the coordinates place (the joint's child, or the root).
    pub fn body(&self) -> BodyId {
        BodyId(self.body)
    }

    /// The joint, or `None` for a free root.
    pub fn joint(&self) -> Option<JointId> {
        self.joint
    }

    /// The body the joint attaches its child to, or `None` for the world (and for a free root).
    pub fn parent(&self) -> Option<BodyId> {
        self.parent.map(BodyId)
    }

    /// Where the group's positions start in the position vector.
    pub fn position_offset(&self) -> usize {
        self.position_offset
    }

    /// Where the group's velocities start in the velocity vector.
    pub fn velocity_offset(&self) -> usize {
        self.velocity_offset
    }

    fn positions(&self) -> std::ops::Range<usize> {
        self.position_offset..self.position_offset + self.model.kind().position_count()
    }

    fn velocities(&self) -> std::ops::Range<usize> {
        self.velocity_offset..self.velocity_offset + self.model.kind().velocity_count()
    }
}

/// The layout of a mechanism's joint coordinates (see the module docs).
#[derive(Clone, Debug)]
pub struct JointSpace {
    groups: Vec<CoordinateGroup>,
    /// Group indices, parents before children.
    order: Vec<usize>,
    /// Per body: its group.
    group_of_body: Vec<usize>,
    /// Per joint of the mechanism: its group, for joint models.
    group_of_joint: Vec<Option<usize>>,
    positions: usize,
    velocities: usize,
}

impl JointSpace {
    /// The coordinates of `mechanism`, if its joint models form a forest.
    pub(crate) fn new<A: Algebra>(mechanism: &Mechanism<A>) -> Option<Self> {
        let bodies = mechanism.bodies.len();
        let mut parent_joint = vec![None; bodies];
        for (j, joint) in mechanism.joints.iter().enumerate() {
            if joint.model.is_some() {
                parent_joint[joint.body] = Some(j);
            }
        }
        let mut groups = Vec::new();
        let mut group_of_body = vec![usize::MAX; bodies];
        for (b, entry) in mechanism.bodies.iter().enumerate() {
            if parent_joint[b].is_none() {
                let model =
                    JointModel::new(entry.name.clone(), JointKind::Free, Isometry3::identity(), entry.frame).ok()?;
                group_of_body[b] = groups.len();
                groups.push(CoordinateGroup {
                    name: entry.name.clone(),
                    model,
                    body: b,
                    parent: None,
                    joint: None,
                    position_offset: 0,
                    velocity_offset: 0,
                });
            }
        }
        for (j, joint) in mechanism.joints.iter().enumerate() {
            if let Some(model) = &joint.model {
                group_of_body[joint.body] = groups.len();
                groups.push(CoordinateGroup {
                    name: model.name().to_owned(),
                    model: model.clone(),
                    body: joint.body,
                    parent: joint.reference,
                    joint: Some(JointId(j)),
                    position_offset: 0,
                    velocity_offset: 0,
                });
            }
        }
        let (mut positions, mut velocities) = (0, 0);
        for group in &mut groups {
            group.position_offset = positions;
            group.velocity_offset = velocities;
            positions += group.model.kind().position_count();
            velocities += group.model.kind().velocity_count();
        }
        // Parents first: breadth-first from the groups whose parent is the world.
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); bodies];
        let mut order = Vec::with_capacity(groups.len());
        for (g, group) in groups.iter().enumerate() {
            match group.parent {
                Some(p) => children[p].push(g),
                None => order.push(g),
            }
        }
        let mut next = 0;
        while next < order.len() {
            let body = groups[order[next]].body;
            order.extend(children[body].iter().copied());
            next += 1;
        }
        let mut group_of_joint = vec![None; mechanism.joints.len()];
        for (g, group) in groups.iter().enumerate() {
            if let Some(joint) = group.joint {
                group_of_joint[joint.0] = Some(g);
            }
        }
        (order.len() == groups.len()).then_some(JointSpace {
            groups,
            order,
            group_of_body,
            group_of_joint,
            positions,
            velocities,
        })
    }

    /// The coordinate groups: free roots first, then the joint models in the order they were added.
    pub fn groups(&self) -> &[CoordinateGroup] {
        &self.groups
    }

    /// The coordinate group of joint index `joint`, if it is a joint model.
    pub(super) fn group_of_joint(&self, joint: usize) -> Option<&CoordinateGroup> {
        self.group_of_joint
            .get(joint)
            .copied()
            .flatten()
            .map(|g| &self.groups[g])
    }

    /// The group of this name (a joint's, or a free root body's).
    pub fn group(&self, name: &str) -> Option<&CoordinateGroup> {
        self.groups.iter().find(|g| g.name == name)
    }

    /// The number of position coordinates (nq).
    pub fn position_count(&self) -> usize {
        self.positions
    }

    /// The number of velocity coordinates (nv, the degrees of freedom without constraints between them).
    pub fn velocity_count(&self) -> usize {
        self.velocities
    }

    /// The positions' names: a one-coordinate joint's name, else `name.suffix` (`base.qw`, `wrist.1`).
    pub fn position_names(&self) -> Vec<String> {
        self.groups
            .iter()
            .flat_map(|g| {
                g.model.kind().position_names().iter().map(move |suffix| {
                    if suffix.is_empty() {
                        g.name.clone()
                    } else {
                        format!("{}.{suffix}", g.name)
                    }
                })
            })
            .collect()
    }

    /// The coordinates by kind, for the methods that step in them (`joint_integration`).
    pub(crate) fn layout(&self) -> crate::joint_integration::JointLayout {
        let mut layout = crate::joint_integration::JointLayout {
            positions: self.positions,
            velocities: self.velocities,
            ..Default::default()
        };
        for group in &self.groups {
            let (p, v) = (group.position_offset, group.velocity_offset);
            match group.model.kind() {
                JointKind::Spherical => layout.rotations.push((p, v)),
                JointKind::Free => {
                    layout.translations.push((p, v, p + 3));
                    layout.rotations.push((p + 3, v + 3));
                }
                kind => layout
                    .vectors
                    .extend((0..kind.velocity_count()).map(|k| (p + k, v + k))),
            }
        }
        layout
    }

    /// The neutral positions: zero, with identity quaternions.
    pub fn neutral_positions(&self) -> Vec<f64> {
        let mut q = vec![0.0; self.positions];
        for group in &self.groups {
            let at = group.position_offset;
            match group.model.kind() {
                JointKind::Spherical => q[at] = 1.0,
                JointKind::Free => q[at + 3] = 1.0,
                _ => {}
            }
        }
        q
    }
}

/// A body's pose and velocity in world terms.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WorldBody {
    pose: Isometry3<f64>,
    /// The pose's rotation as a matrix (body → world), computed once.
    rotation: Matrix3<f64>,
    /// Angular velocity and centre-of-mass velocity, world axes.
    angular: Vector3<f64>,
    linear: Vector3<f64>,
}

impl WorldBody {
    pub(crate) fn world() -> WorldBody {
        WorldBody {
            pose: Isometry3::identity(),
            rotation: Matrix3::identity(),
            angular: Vector3::zeros(),
            linear: Vector3::zeros(),
        }
    }

    /// The velocity of the body point at `x` (world).
    fn velocity_at(&self, x: &Vector3<f64>) -> Vector3<f64> {
        self.linear + self.angular.cross(&(x - self.pose.translation.vector))
    }
}

impl<A: Algebra> Mechanism<A> {
    /// The coordinates, built on first use after a change.
    pub(crate) fn coordinates(&self) -> Option<&JointSpace> {
        self.joint_space.get_or_init(|| JointSpace::new(self)).as_ref()
    }

    /// The joint coordinates' layout, if the joint models form a forest (always, for models added by
    /// [`Mechanism::connect`] alone).
    pub fn joint_space(&self) -> Result<&JointSpace, MechanismError> {
        self.coordinates()
            .ok_or_else(|| MechanismError::NoJointSpace("its joint models do not form a forest".to_owned()))
    }

    fn check_states(&self, states: &[State<A>]) -> Result<(), MechanismError> {
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

    fn parent_of(&self, group: &CoordinateGroup, bodies: &[WorldBody]) -> WorldBody {
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
    /// use dynamics::joints::{JointKind, JointModel};
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
    fn place_at(
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
                crate::joints::Motion::Rotation => angular += d * *rate,
                crate::joints::Motion::Translation => at_joint += d * *rate,
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

    /// Every body's world kinematics (from its state) for the joint-space algorithms.
    fn kinematics_of(&self, t: f64, states: &[State<A>]) -> Vec<Kinematics<A>> {
        states
            .iter()
            .enumerate()
            .map(|(i, s)| Kinematics::new(t, s.motor, s.body_velocity(&self.bodies[i].body)))
            .collect()
    }

    /// The joint-space mass matrix M(q) at `states` (nv × nv, symmetric positive definite), so that the kinetic
    /// energy is `½ vᵀ M v`: by the composite-rigid-body recursion on the bodies' inertias in world axes about one
    /// point (docs/mechanisms.md §M7), `M_jk = S_jᵀ I^c S_k` with `I^c` the composite inertia of the subtree below
    /// the later of the two joints.
    pub fn mass_matrix(&self, states: &[State<A>]) -> Result<DMatrix<f64>, MechanismError> {
        let space = self.joint_space()?;
        self.check_states(states)?;
        let WorldTerms { columns, spatial, .. } = self.world_terms(space, 0.0, states);
        let mut composite: Vec<Inertia6> = spatial.iter().map(|s| s.inertia).collect();
        for &g in space.order.iter().rev() {
            let group = &space.groups[g];
            if let Some(p) = group.parent {
                let below = composite[group.body];
                composite[p].add(&below);
            }
        }
        let n = space.velocities;
        let mut mass = DMatrix::zeros(n, n);
        for group in &space.groups {
            let inertia = &composite[group.body];
            for (k, column) in columns[group.velocities()].iter().enumerate() {
                let force = inertia.apply(column);
                let row = group.velocity_offset + k;
                // This joint and every joint above it on the way to the root.
                let mut above = Some(group);
                while let Some(h) = above {
                    for (l, other) in columns[h.velocities()].iter().enumerate() {
                        let value = other.dot(&force);
                        mass[(row, h.velocity_offset + l)] = value;
                        mass[(h.velocity_offset + l, row)] = value;
                    }
                    above = h.parent.map(|p| &space.groups[space.group_of_body[p]]);
                }
            }
        }
        Ok(mass)
    }

    /// Per `(body, world point, world direction n)`: the joint-space row c with `c · v = n · v_p` at joint velocities
    /// v, the point's velocity along n: each column S on the way from the body to its root paired with the unit
    /// force along n through the point, `c_k = S_k · (r × n; n)` (docs/contacts.md "Rows").
    pub(crate) fn point_jacobian(
        &self,
        states: &[State<A>],
        points: &[(usize, Vector3<f64>, Vector3<f64>)],
    ) -> Result<DMatrix<f64>, MechanismError> {
        let space = self.joint_space()?;
        self.check_states(states)?;
        let WorldTerms { columns, origin, .. } = self.world_terms(space, 0.0, states);
        let mut rows = DMatrix::zeros(points.len(), space.velocities);
        for (r, (body, point, normal)) in points.iter().enumerate() {
            let wrench = join((point - origin).cross(normal), *normal);
            let mut group = Some(&space.groups[space.group_of_body[*body]]);
            while let Some(g) = group {
                for (k, column) in columns[g.velocities()].iter().enumerate() {
                    rows[(r, g.velocity_offset + k)] = column.dot(&wrench);
                }
                group = g.parent.map(|p| &space.groups[space.group_of_body[p]]);
            }
        }
        Ok(rows)
    }

    /// The bodies' kinematics at `states` and their screws in world axes about one point, the first body's position.
    fn world_terms(&self, space: &JointSpace, t: f64, states: &[State<A>]) -> WorldTerms<A> {
        let kinematics = self.kinematics_of(t, states);
        let origin = kinematics.first().map_or_else(Vector3::zeros, |k| k.frame.position);
        let columns = self.columns(space, &kinematics, &origin);
        let spatial = kinematics
            .iter()
            .enumerate()
            .map(|(i, k)| spatial_body(&self.bodies[i].body, k, &origin))
            .collect();
        WorldTerms {
            kinematics,
            origin,
            columns,
            spatial,
        }
    }

    /// Every velocity coordinate's unit motion (world, about `origin`), in velocity order.
    fn columns(&self, space: &JointSpace, kinematics: &[Kinematics<A>], origin: &Vector3<f64>) -> Vec<Vector6<f64>> {
        let mut columns = vec![Vector6::zeros(); space.velocities];
        for group in &space.groups {
            let child = &kinematics[group.body];
            let through =
                child.frame.position + child.frame.rotation * group.model.child_frame().translation.vector - origin;
            for (k, axis) in group.model.axes().iter().enumerate() {
                let rotation = match (axis.side, group.parent) {
                    (Side::Child, _) => *child.frame.rotation.matrix(),
                    (Side::Parent, Some(p)) => *kinematics[p].frame.rotation.matrix(),
                    (Side::Parent, None) => Matrix3::identity(),
                };
                columns[group.velocity_offset + k] = axis_column(axis, &rotation, &through);
            }
        }
        columns
    }

    /// The bias forces h(q, v) at `states` and time `t`: the generalised forces that hold the joints at zero
    /// acceleration against gravity, the velocity products and the external forces on the bodies, so that
    /// `M(q) q̈ + h(q, v) = τ`. By the recursive Newton–Euler algorithm in world axes (docs/mechanisms.md §M7).
    pub fn bias_forces(&self, t: f64, states: &[State<A>]) -> Result<DVector<f64>, MechanismError> {
        let space = self.joint_space()?;
        self.inverse_dynamics(t, states, &vec![0.0; space.velocities])
    }

    /// The generalised forces `τ = M(q) q̈ + h(q, v)` that give the joint accelerations `accelerations` at `states`
    /// and time `t` (inverse dynamics, by the recursive Newton–Euler algorithm: each body's acceleration from its
    /// parent's and its joint's, the forces that produce them summed up the tree, each joint's share of its
    /// subtree's force). Constraints other than the joint models (loops) are not part of it.
    pub fn inverse_dynamics(
        &self,
        t: f64,
        states: &[State<A>],
        accelerations: &[f64],
    ) -> Result<DVector<f64>, MechanismError> {
        let space = self.joint_space()?;
        self.check_states(states)?;
        if accelerations.len() != space.velocities {
            return Err(MechanismError::Count {
                what: "joint accelerations",
                expected: space.velocities,
                got: accelerations.len(),
            });
        }
        if let Some(index) = accelerations
            .iter()
            .position(|a| !(a.is_finite() && a.abs() <= crate::state::MAX_COORDINATE))
        {
            return Err(MechanismError::NotFinite {
                what: "joint acceleration",
                index,
            });
        }
        let WorldTerms {
            kinematics,
            origin,
            columns,
            spatial,
        } = self.world_terms(space, t, states);
        let mut acceleration = vec![Vector6::zeros(); self.bodies.len()];
        for &g in &space.order {
            let group = &space.groups[g];
            let parent = group.parent.map_or_else(Vector6::zeros, |p| acceleration[p]);
            let bias = self.joint_bias(group, &spatial, &columns, &kinematics, &origin);
            let mut a = parent + bias;
            for (column, rate) in columns[group.velocities()]
                .iter()
                .zip(&accelerations[group.velocities()])
            {
                a += column * *rate;
            }
            acceleration[group.body] = a;
        }
        // The external wrenches: the bodies' forces and the force elements that are not actuators.
        let mut external: Vec<ScrewCoordinates> = (0..self.bodies.len())
            .map(|i| {
                self.external_body_wrench(i, &kinematics[i], kinematics[i].to_body(states[i].momentum))
                    .0
            })
            .collect();
        self.apply_elements(t, &|i: usize| &kinematics[i], &mut external, false)?;
        let mut force: Vec<Vector6<f64>> = (0..self.bodies.len())
            .map(|i| {
                let s = &spatial[i];
                let external = &external[i];
                let rotation = kinematics[i].frame.rotation.matrix();
                let f = rotation * external.l;
                let n = rotation * external.t + s.offset.cross(&f);
                s.inertia.apply(&acceleration[i]) + force_cross(&s.velocity, &s.momentum) - join(n, f)
            })
            .collect();
        let mut tau = DVector::zeros(space.velocities);
        for &g in space.order.iter().rev() {
            let group = &space.groups[g];
            let total = force[group.body];
            for (k, column) in columns[group.velocities()].iter().enumerate() {
                tau[group.velocity_offset + k] = column.dot(&total);
            }
            if let Some(p) = group.parent {
                force[p] += total;
            }
        }
        Ok(tau)
    }

    /// `Ṡ q̇` of a group's joint: the child's acceleration relative to its parent's with the joint rates held.
    fn joint_bias(
        &self,
        group: &CoordinateGroup,
        spatial: &[SpatialBody],
        columns: &[Vector6<f64>],
        kinematics: &[Kinematics<A>],
        origin: &Vector3<f64>,
    ) -> Vector6<f64> {
        let parent = group.parent.map_or_else(Vector6::zeros, |p| spatial[p].velocity);
        let child = spatial[group.body].velocity;
        let mut bias = motion_cross(&parent, &child);
        let child_kinematics = &kinematics[group.body];
        let through = child_kinematics.frame.position
            + child_kinematics.frame.rotation * group.model.child_frame().translation.vector
            - origin;
        for (axis, column) in group.model.axes().iter().zip(&columns[group.velocities()]) {
            if axis.side == Side::Parent {
                let rate = axis_rate(column, axis.motion, &(child - parent), &through);
                bias += motion_cross(&(parent - child), column) * rate;
            }
        }
        bias
    }

    /// The joint accelerations q̈ at `states` and time `t`: the mechanism's equations of motion (the same solve the
    /// integrators step), read in joint coordinates.
    pub fn joint_accelerations(&self, t: f64, states: &[State<A>]) -> Result<Vec<f64>, MechanismError> {
        let space = self.joint_space()?;
        self.check_states(states)?;
        let rates = self.rates_at(t, states)?;
        let WorldTerms {
            kinematics,
            origin,
            columns,
            spatial,
        } = self.world_terms(space, t, states);
        // Each body's spatial acceleration about o from its momentum rate: a_c = F/m, and about the centre of mass
        // n_c = Ī ω̇ + ω × Ī ω; then a_o = a_c − ω̇ × r − ω × v_c.
        let acceleration: Vec<Vector6<f64>> = rates
            .iter()
            .enumerate()
            .map(|(i, rate)| {
                let body = &self.bodies[i].body;
                let k = &kinematics[i];
                let wrench = A::screw_coordinates(rate.momentum_rate);
                let centre = k.frame.position;
                let force = wrench.l;
                let moment = wrench.t - centre.cross(&force);
                let rotation = k.frame.rotation.matrix();
                let omega_body = rotation.tr_mul(&k.angular_velocity);
                let moments = body.moments();
                let spin = rotation * omega_body.cross(&moments.component_mul(&omega_body));
                let omega_rate = rotation * (rotation.tr_mul(&(moment - spin))).component_div(&moments);
                let a_centre = force / body.mass();
                let offset = spatial[i].offset;
                join(
                    omega_rate,
                    a_centre - omega_rate.cross(&offset) - k.angular_velocity.cross(&k.linear_velocity),
                )
            })
            .collect();
        let mut q_ddot = vec![0.0; space.velocities];
        for group in &space.groups {
            let parent = group.parent.map_or_else(Vector6::zeros, |p| acceleration[p]);
            let relative =
                acceleration[group.body] - parent - self.joint_bias(group, &spatial, &columns, &kinematics, &origin);
            let child = &kinematics[group.body];
            let through =
                child.frame.position + child.frame.rotation * group.model.child_frame().translation.vector - origin;
            for (k, axis) in group.model.axes().iter().enumerate() {
                let column = &columns[group.velocity_offset + k];
                q_ddot[group.velocity_offset + k] = axis_rate(column, axis.motion, &relative, &through);
            }
        }
        Ok(q_ddot)
    }
}

/// What the joint-space algorithms (mass matrix, inverse dynamics, joint accelerations) start from: the bodies'
/// kinematics, and in world axes about `origin` every velocity coordinate's unit motion and every body's spatial
/// terms (docs/mechanisms.md §M7).
struct WorldTerms<A: Algebra> {
    kinematics: Vec<Kinematics<A>>,
    origin: Vector3<f64>,
    columns: Vec<Vector6<f64>>,
    spatial: Vec<SpatialBody>,
}

/// An error unless slices of `positions` and `velocities` entries fit `space`.
fn check_coordinate_counts(space: &JointSpace, positions: usize, velocities: usize) -> Result<(), ConstraintError> {
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

fn join(top: Vector3<f64>, bottom: Vector3<f64>) -> Vector6<f64> {
    Vector6::new(top.x, top.y, top.z, bottom.x, bottom.y, bottom.z)
}

impl<A: Algebra> Mechanism<A> {
    /// The joint accelerations q̈ at joint positions `q` and velocities `v` (the layout of [`JointSpace`]) and time
    /// `t`: the bodies placed by forward kinematics, their forces, the articulated solve, and each joint's shares of
    /// the accelerations (docs/mechanisms.md §M7). The evaluation of the methods that step in joint coordinates;
    /// it needs the articulated solve. `workspace.power` gets the force elements' power.
    pub(crate) fn joint_rates_at(
        &self,
        t: f64,
        q: &[f64],
        v: &[f64],
        accelerations: &mut [f64],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        let (Some(space), Some(articulation)) = (self.coordinates(), &self.articulation) else {
            return Err(ConstraintError::InvalidParameter {
                name: "joint coordinates".to_owned(),
                reason: "stepping in joint coordinates needs every joint a joint model, in a tree".to_owned(),
            });
        };
        check_coordinate_counts(space, q.len(), v.len())?;
        if accelerations.len() != space.velocities {
            return Err(ConstraintError::Count {
                what: "joint accelerations",
                expected: space.velocities,
                got: accelerations.len(),
            });
        }
        // Forward kinematics: every body's pose and velocity, then its kinematics and body momentum.
        let mut placed = std::mem::take(&mut workspace.placed);
        placed.resize(self.bodies.len(), WorldBody::world());
        for &g in &space.order {
            let group = &space.groups[g];
            let parent = self.parent_of(group, &placed);
            placed[group.body] = self.place_at(t, group, &parent, &q[group.positions()], &v[group.velocities()])?;
        }
        // The motors only where a force reads them (gravity and the articulated solve do not); elsewhere NaN, so
        // that a reader left out here shows as an error, not a wrong answer.
        let motors = !self.elements.is_empty()
            || self.bodies.iter().any(|b| {
                b.forces
                    .iter()
                    .any(|f| !matches!(f, crate::forces::Force::Gravity { .. }))
            });
        let unused = A::motor(crate::algebra::MotorCoordinates {
            scalar: f64::NAN,
            l: Vector3::repeat(f64::NAN),
            t: Vector3::repeat(f64::NAN),
            pseudoscalar: f64::NAN,
        });
        for (i, body) in placed.iter().enumerate() {
            let rotation = nalgebra::Rotation3::from_matrix_unchecked(body.rotation);
            let (omega, linear) = (
                rotation.inverse_transform_vector(&body.angular),
                rotation.inverse_transform_vector(&body.linear),
            );
            let velocity = A::screw(ScrewCoordinates { l: omega, t: linear });
            let position = body.pose.translation.vector;
            let motor = if motors {
                motor::from_pose::<A>(position, &body.pose.rotation)
            } else {
                unused
            };
            // The kinematics from what forward kinematics already holds (world velocities included).
            workspace.bodies[i].kinematics = Kinematics {
                t,
                motor,
                reverse: if motors { A::reverse(motor) } else { unused },
                body_velocity: velocity,
                velocity: nalgebra::Vector6::new(omega.x, omega.y, omega.z, linear.x, linear.y, linear.z),
                world_velocity: A::screw(ScrewCoordinates {
                    l: body.angular,
                    t: body.linear + position.cross(&body.angular),
                }),
                frame: motor::ScrewFrame { rotation, position },
                angular_velocity: body.angular,
                linear_velocity: body.linear,
            };
            workspace.momenta[i] = self.bodies[i].body.momentum::<A>(velocity);
        }
        workspace.placed = placed;
        let momenta = std::mem::take(&mut workspace.momenta);
        let forces = self.body_forces(t, &momenta, workspace, super::BodyTerms::Forces);
        workspace.momenta = momenta;
        forces?;
        // The reactions only for the drives' power: the other joints' is zero.
        let driven = self
            .joints
            .iter()
            .any(|j| j.model.as_ref().is_some_and(JointModel::is_driven));
        self.solve_articulated(articulation, t, workspace, driven)
            .map_err(|body| ConstraintError::NonFinite {
                name: self.bodies[body].name.clone(),
                t,
            })?;
        if driven {
            workspace.power += self.reaction_power(workspace);
        }
        let super::MechanismWorkspace {
            bodies, articulated, ..
        } = workspace;
        let origin = articulated.origin();
        for group in &space.groups {
            let out = &mut accelerations[group.velocities()];
            let child = &bodies[group.body].kinematics;
            let through = child.world_point(&group.model.child_frame().translation.vector) - origin;
            match group.joint {
                Some(joint) => {
                    let entry = &self.joints[joint.0];
                    articulated.joint_accelerations(
                        joint.0,
                        entry.body,
                        entry.reference,
                        group.model.axes(),
                        &through,
                        out,
                    );
                }
                None => {
                    // A free root: its velocity coordinates are turns and slides along its frame's axes.
                    let a = articulated.acceleration(group.body);
                    for (axis, value) in group.model.axes().iter().zip(out.iter_mut()) {
                        let column = axis_column(axis, child.frame.rotation.matrix(), &through);
                        *value = axis_rate(&column, axis.motion, a, &through);
                    }
                }
            }
        }
        if !accelerations.iter().all(|a| a.is_finite()) {
            return Err(ConstraintError::NonFinite {
                name: self.names(0..self.joints.len()),
                t,
            });
        }
        Ok(())
    }

    /// The joint positions and velocities of `states` into the slices, angles unwrapped from `previous` (when it
    /// has the right length), which then holds these positions.
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
