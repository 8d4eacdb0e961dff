//! The joint-space mass matrix M(q) (docs/mechanisms.md §M7), from the bodies' spatial inertias about one reference
//! point and every velocity coordinate's unit motion in world axes, and a body point's Jacobian.

use nalgebra::{DMatrix, Matrix3, Vector3, Vector6};

use crate::algebra::Algebra;
use crate::constraints::Kinematics;
use crate::joint_models::Side;
use crate::mechanism::articulated::axis_column;
use crate::mechanism::error::MechanismError;
use crate::mechanism::joint_space::JointSpace;
use crate::mechanism::model::Mechanism;
use crate::mechanism::parts::PointDirection;
use crate::mechanism::spatial::{join, spatial_body, Inertia6, SpatialBody};
use crate::state::State;

/// What the joint-space algorithms (mass matrix, inverse dynamics, joint accelerations) start from: the bodies'
/// kinematics, and in world axes about `origin` every velocity coordinate's unit motion and every body's spatial
/// terms (docs/mechanisms.md §M7).
pub(super) struct WorldTerms<A: Algebra> {
    pub(super) kinematics: Vec<Kinematics<A>>,
    pub(super) origin: Vector3<f64>,
    pub(super) columns: Vec<Vector6<f64>>,
    pub(super) spatial: Vec<SpatialBody>,
}

impl<A: Algebra> Mechanism<A> {
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

    /// Per point: the joint-space row c with `c · v = n · (v_p − v'_p)` at joint velocities v, the speed along the
    /// direction n of the body's material point at the world point p less the other body's (if any): each column S on
    /// the way from the body to its root paired with the unit force along n through p, `c_k = S_k · (r × n; n)`, less
    /// the same on the other body's way (docs/contacts.md "Rows").
    pub(crate) fn point_jacobian(
        &self,
        states: &[State<A>],
        points: &[PointDirection],
    ) -> Result<DMatrix<f64>, MechanismError> {
        let space = self.joint_space()?;
        self.check_states(states)?;
        let WorldTerms { columns, origin, .. } = self.world_terms(space, 0.0, states);
        let mut rows = DMatrix::zeros(points.len(), space.velocities);
        for (r, point) in points.iter().enumerate() {
            let wrench = join((point.point - origin).cross(&point.direction), point.direction);
            let sides = [(Some(point.body), 1.0), (point.other, -1.0)];
            for (body, sign) in sides {
                let mut group = body.map(|b| &space.groups[space.group_of_body[b]]);
                while let Some(g) = group {
                    for (k, column) in columns[g.velocities()].iter().enumerate() {
                        rows[(r, g.velocity_offset + k)] += sign * column.dot(&wrench);
                    }
                    group = g.parent.map(|p| &space.groups[space.group_of_body[p]]);
                }
            }
        }
        Ok(rows)
    }

    /// The bodies' kinematics at `states` and their screws in world axes about one point, the first body's position.
    pub(super) fn world_terms(&self, space: &JointSpace, t: f64, states: &[State<A>]) -> WorldTerms<A> {
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
}
