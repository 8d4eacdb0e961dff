//! The bias forces h(q, v) and the inverse dynamics `τ = M q̈ + h` (docs/mechanisms.md §M7), by a recursion over
//! the joint tree in world axes about one reference point.

use nalgebra::{DVector, Vector3, Vector6};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::Kinematics;
use crate::joint_models::Side;
use crate::mechanism::articulated::axis_rate;
use crate::mechanism::error::MechanismError;
use crate::mechanism::joint_space::CoordinateGroup;
use crate::mechanism::mass_matrix::WorldTerms;
use crate::mechanism::model::Mechanism;
use crate::mechanism::spatial::{force_cross, join, motion_cross, SpatialBody};
use crate::state::State;

impl<A: Algebra> Mechanism<A> {
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
                self.external_body_wrench(
                    i,
                    &kinematics[i],
                    A::screw(
                        kinematics[i]
                            .frame
                            .turn_to_body(&A::screw_coordinates(states[i].central_momentum)),
                    ),
                )
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
    pub(super) fn joint_bias(
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
}
