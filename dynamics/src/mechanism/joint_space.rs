//! The joint coordinates of a mechanism (docs/mechanisms.md §M7): the joint models and the free roots as groups of
//! coordinates, and where each group's positions and velocities are. The algorithms on them work from the bodies'
//! own states (the maximal coordinates), in world axes about one reference point so that nothing moves between
//! frames: `configuration` (positions and velocities in and out of the states), `mass_matrix`, `forward_dynamics`
//! and `inverse_dynamics` (the joint-space quantities a controller needs: M(q), q̈, h(q, v) and `τ = M q̈ + h`).
//!
//! The coordinates come in groups: first every free root (a body no joint model holds), named after the body, with
//! the pose and twist of its reference frame (7 positions: x, y, z, qw, qx, qy, qz; 6 velocities: the frame origin's
//! velocity and the angular velocity, both in the frame's axes — Pinocchio's free flyer); then every joint model in
//! the order the joints were added. A group's generalised force pairs with its velocities by the power: a revolute
//! joint's torque, a prismatic joint's force, a free root's force then moment about its frame origin, in its axes.

use nalgebra::{Isometry3, Matrix3, Vector3};

use crate::algebra::Algebra;
use crate::joint_models::{JointKind, JointModel};
use crate::mechanism::joint_rows::Joint;
use crate::mechanism::parts::{BodyId, JointId, MechanismBody};

/// One group of coordinates: a joint model, or a free root.
#[derive(Clone, Debug)]
pub struct CoordinateGroup {
    pub(super) name: String,
    pub(super) model: JointModel,
    pub(super) body: usize,
    pub(super) parent: Option<usize>,
    pub(super) joint: Option<JointId>,
    pub(super) position_offset: usize,
    pub(super) velocity_offset: usize,
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

    pub(super) fn positions(&self) -> std::ops::Range<usize> {
        self.position_offset..self.position_offset + self.model.kind().position_count()
    }

    pub(super) fn velocities(&self) -> std::ops::Range<usize> {
        self.velocity_offset..self.velocity_offset + self.model.kind().velocity_count()
    }
}

/// The layout of a mechanism's joint coordinates (see the module docs).
#[derive(Clone, Debug)]
pub struct JointSpace {
    pub(super) groups: Vec<CoordinateGroup>,
    /// Group indices, parents before children.
    pub(super) order: Vec<usize>,
    /// Per body: its group.
    pub(super) group_of_body: Vec<usize>,
    /// Per joint of the mechanism: its group, for joint models.
    pub(super) group_of_joint: Vec<Option<usize>>,
    pub(super) positions: usize,
    pub(super) velocities: usize,
}

impl JointSpace {
    /// The coordinates of `mechanism`, if its joint models form a forest.
    pub(super) fn new<A: Algebra>(bodies: &[MechanismBody<A>], joints: &[Joint<A>]) -> Option<Self> {
        let (entries, bodies) = (bodies, bodies.len());
        let mut parent_joint = vec![None; bodies];
        for (j, joint) in joints.iter().enumerate() {
            if joint.model.is_some() {
                parent_joint[joint.body] = Some(j);
            }
        }
        let mut groups = Vec::new();
        let mut group_of_body = vec![usize::MAX; bodies];
        for (b, entry) in entries.iter().enumerate() {
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
        for (j, joint) in joints.iter().enumerate() {
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
        let mut group_of_joint = vec![None; joints.len()];
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
    pub(crate) fn layout(&self) -> crate::joint_layout::JointLayout {
        let mut layout = crate::joint_layout::JointLayout {
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
    pub(super) pose: Isometry3<f64>,
    /// The pose's rotation as a matrix (body → world), computed once.
    pub(super) rotation: Matrix3<f64>,
    /// Angular velocity and centre-of-mass velocity, world axes.
    pub(super) angular: Vector3<f64>,
    pub(super) linear: Vector3<f64>,
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
    pub(super) fn velocity_at(&self, x: &Vector3<f64>) -> Vector3<f64> {
        self.linear + self.angular.cross(&(x - self.pose.translation.vector))
    }
}
