//! The joint accelerations q̈ (docs/mechanisms.md §M7): at the bodies' states, and at joint positions and velocities
//! by forward kinematics and the articulated solve, the evaluation of the methods that step in joint coordinates.

use nalgebra::{Vector3, Vector6};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::{ConstraintError, Kinematics};
use crate::joint_models::JointModel;
use crate::mechanism::articulated::{axis_column, axis_rate};
use crate::mechanism::configuration::check_coordinate_counts;
use crate::mechanism::error::MechanismError;
use crate::mechanism::joint_space::WorldBody;
use crate::mechanism::mass_matrix::WorldTerms;
use crate::mechanism::model::{BodyTerms, Mechanism, MechanismWorkspace};
use crate::mechanism::parts::Slip;
use crate::mechanism::spatial::join;
use crate::motor;
use crate::state::State;

impl<A: Algebra> Mechanism<A> {
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
                let (force, moment) = (wrench.l, wrench.t);
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

    /// The joint accelerations q̈ at joint positions `q` and velocities `v` (the layout of [`JointSpace`]) and time
    /// `t`: the bodies placed by forward kinematics, their forces, the articulated solve, and each joint's shares of
    /// the accelerations (docs/mechanisms.md §M7). The evaluation of the methods that step in joint coordinates;
    /// it needs the articulated solve. `workspace.power` gets the force elements' power.
    #[inline]
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
        let forces = self.body_forces(t, &momenta, workspace, BodyTerms::Forces);
        workspace.momenta = momenta;
        forces?;
        // The reactions only for the power of the drives and of sliding friction: the other joints' and contacts'
        // is zero.
        let driven = self
            .joints
            .iter()
            .any(|j| j.model.as_ref().is_some_and(JointModel::is_driven));
        let first = self.limits.len();
        let sliding = (self.frictional.iter())
            .any(|&c| workspace.held[first + c].is_some() && matches!(workspace.slips[c], Slip::Sliding { .. }));
        self.solve_articulated(articulation, t, workspace, driven || sliding)
            .map_err(|body| ConstraintError::NonFinite {
                name: self.bodies[body].name.clone(),
                t,
            })?;
        if driven || sliding {
            workspace.power += self.reaction_power(workspace);
        }
        let MechanismWorkspace {
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
}
