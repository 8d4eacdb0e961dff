//! Evaluating a mechanism at a state: the bodies' kinematics and forces, the joints' rows, and the reactions by
//! the articulated solve or the constraint-space solve (docs/mechanisms.md §M4, §M7); energy, momentum, violation.

use nalgebra::Vector3;

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::{ConstraintError, Kinematics, Stabilisation};
use crate::forces::Force;
use crate::mechanism::articulated::Articulation;
use crate::mechanism::joint_rows::{wrench_coordinates, wrench_screw, JointContext, Rows};
use crate::mechanism::model::{BodyTerms, Condition, Mechanism, MechanismWorkspace};
use crate::mechanism::solve::{dot6, Consistency, SolveFailure};
use crate::mechanism::topology::{Side, Slot};
use crate::motion::{Dynamics, Rates};
use crate::state::State;

/// The largest residuals over the joints at one state: `max |e|` (rows with a position residual) and `max |ė|`.
/// Units are those of each constraint's residual (metres for a force-line row, multivector coefficients for
/// pins).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Violation {
    /// `max |e|` over the joints' rows that have a position residual.
    pub position: f64,
    /// `max |ė|` over all the joints' rows.
    pub velocity: f64,
}

impl<A: Algebra> Mechanism<A> {
    fn failure(&self, failure: SolveFailure) -> ConstraintError {
        match failure {
            SolveFailure::TreeRank {
                joint,
                singular_value,
                largest,
            } => ConstraintError::RankDeficient {
                names: self.names([joint]),
                rank: Self::joint_rank(&self.joints[joint]),
                singular_value,
                largest,
            },
            SolveFailure::Inconsistent {
                joint,
                relative_residual,
            } => ConstraintError::Inconsistent {
                names: self.names(std::iter::once(joint).chain(self.topology.cycles[joint].iter().copied())),
                relative_residual,
            },
        }
    }

    /// The wrench of the external forces on body `index` about its centre of mass, world axes (the momentum rate
    /// of [`crate::motion::Rates`]).
    #[inline]
    pub(super) fn external_wrench(
        &self,
        index: usize,
        t: f64,
        state: &State<A>,
        kinematics: &Kinematics<A>,
    ) -> A::Screw {
        let body = &self.bodies[index];
        body.forces.iter().fold(A::screw(Default::default()), |total, force| {
            total + force.central_wrench_at(&body.body, t, kinematics.motor, || state.central_momentum)
        })
    }

    /// The external wrench on body `index` in its own frame (gravity rotated into it directly), and the power of
    /// its forces other than gravity (gravity's is the rate of its potential, in the energy).
    #[inline]
    pub(super) fn external_body_wrench(
        &self,
        index: usize,
        kinematics: &Kinematics<A>,
        body_momentum: A::Screw,
    ) -> (ScrewCoordinates, f64) {
        let body = &self.bodies[index];
        body.forces.iter().fold(
            (ScrewCoordinates::default(), 0.0),
            |(total, power), force| match force {
                Force::Gravity { acceleration } => {
                    let weight = ScrewCoordinates {
                        l: kinematics
                            .frame
                            .rotation
                            .inverse_transform_vector(&(body.body.mass() * acceleration)),
                        t: Vector3::zeros(),
                    };
                    (total + weight, power)
                }
                _ => {
                    let central = force.central_wrench_at(&body.body, kinematics.t, kinematics.motor, || {
                        crate::motor::central_from_body::<A>(kinematics.motor, body_momentum)
                    });
                    let wrench = kinematics.frame.turn_to_body(&A::screw_coordinates(central));
                    (
                        total + wrench,
                        power + wrench_power(&wrench_coordinates(&wrench), &kinematics.velocity),
                    )
                }
            },
        )
    }

    /// The power of the joints' reactions in `workspace` (`Σ yᵢ·xᵢ`, body frames): a drive's work, and for the
    /// joints that prescribe nothing zero up to the constraint drift (docs/mechanisms.md §M8).
    #[inline]
    pub(crate) fn reaction_power(&self, workspace: &MechanismWorkspace<A>) -> f64 {
        workspace
            .reactions
            .iter()
            .zip(&workspace.bodies)
            .map(|(reaction, body)| wrench_power(reaction, &body.kinematics.velocity))
            .sum()
    }

    /// Every body's kinematics from its motor and body momentum; with `dynamics`, also its external wrench and
    /// free acceleration `H⁻¹(Ḃ × Ω_b + S_b)` (theory §5).
    #[inline]
    pub(super) fn body_kinematics(
        &self,
        t: f64,
        motors: &[A::Motor],
        body_momenta: &[A::Screw],
        workspace: &mut MechanismWorkspace<A>,
        terms: BodyTerms,
    ) -> Result<(), ConstraintError> {
        for (i, entry) in self.bodies.iter().enumerate() {
            let velocity = entry.body.velocity::<A>(body_momenta[i]);
            // Written in place (the kinematics are a few hundred bytes, built for every body at every evaluation).
            workspace.bodies[i].kinematics = Kinematics::new(t, motors[i], velocity);
        }
        self.body_forces(t, body_momenta, workspace, terms)
    }

    /// Every body's external wrench (its forces and the force elements'; `workspace.power` the elements' power) and,
    /// for the constraint-space solve, its free acceleration, at the kinematics in `workspace`.
    #[inline]
    pub(super) fn body_forces(
        &self,
        t: f64,
        body_momenta: &[A::Screw],
        workspace: &mut MechanismWorkspace<A>,
        terms: BodyTerms,
    ) -> Result<(), ConstraintError> {
        workspace.power = 0.0;
        for body in workspace.bodies.iter_mut() {
            body.free_acceleration = [0.0; 6];
        }
        if terms == BodyTerms::Kinematics {
            return Ok(());
        }
        for (i, body) in workspace.bodies.iter().enumerate() {
            let (wrench, power) = self.external_body_wrench(i, &body.kinematics, body_momenta[i]);
            workspace.external[i] = wrench;
            workspace.power += power;
        }
        if !self.elements.is_empty() {
            let MechanismWorkspace {
                bodies,
                external,
                element_wrenches,
                ..
            } = workspace;
            element_wrenches
                .iter_mut()
                .for_each(|w| *w = ScrewCoordinates::default());
            let kinematics = |i: usize| &bodies[i].kinematics;
            workspace.power += self.apply_elements(t, &kinematics, element_wrenches, true)?;
            for (total, element) in external.iter_mut().zip(element_wrenches.iter()) {
                *total = *total + *element;
            }
        }
        if terms == BodyTerms::FreeAccelerations {
            for (i, body) in workspace.bodies.iter_mut().enumerate() {
                let drive = A::screw_coordinates(A::commutator(body.kinematics.body_velocity, body_momenta[i]))
                    + workspace.external[i];
                let g = wrench_coordinates(&drive);
                body.free_acceleration = std::array::from_fn(|k| g[k] * workspace.inverse_metric[i][k]);
            }
        }
        Ok(())
    }

    /// Every joint's reduced rows at the bodies' kinematics.
    /// Every joint's rows for `purpose` at the bodies' kinematics in `workspace`.
    #[inline]
    pub(super) fn joint_rows(
        &self,
        t: f64,
        workspace: &mut MechanismWorkspace<A>,
        purpose: Rows,
    ) -> Result<(), ConstraintError> {
        let context = JointContext {
            t,
            stabilisation: if purpose == Rows::Dynamics {
                self.stabilisation
            } else {
                Stabilisation::None
            },
            settings: &self.settings,
            inverse_metric: &workspace.inverse_metric,
            loops: self.topology.loop_size > 0,
            purpose,
        };
        for (joint, rows) in self.joints.iter().zip(workspace.joints.iter_mut()) {
            joint.evaluate(&context, &workspace.bodies, &mut workspace.raw, rows)?;
        }
        Ok(())
    }

    /// Assembles and factors `K`, solves it for `condition`'s right-hand sides and accumulates the reactions
    /// `Jᵀλ` per body (wrench coordinates, body frames) into `workspace.reactions`.
    #[inline]
    pub(super) fn solve_reactions(
        &self,
        workspace: &mut MechanismWorkspace<A>,
        condition: Condition,
        consistency: Consistency,
    ) -> Result<(), ConstraintError> {
        self.factor_system(workspace)?;
        self.solve_factored(workspace, condition, consistency)
    }

    /// Assembles and factors `K` at the joints' current rows.
    #[inline]
    pub(super) fn factor_system(&self, workspace: &mut MechanismWorkspace<A>) -> Result<(), ConstraintError> {
        workspace.stage_factors = false;
        let MechanismWorkspace {
            joints,
            matrix,
            inverse_metric,
            ..
        } = workspace;
        let rows = |joint: usize, side: Side| -> &[[f64; 6]] {
            let rows = &joints[joint];
            match side {
                Side::Body => &rows.reduced.rows[..rows.reduced.rank],
                Side::Reference => &rows.reference_rows[..rows.reduced.rank],
            }
        };
        matrix.assemble(&self.topology, inverse_metric, rows);
        matrix
            .factor(&self.topology, &self.settings)
            .map_err(|f| self.failure(f))
    }

    /// Solves the factored `K` for `condition`'s right-hand sides and accumulates the reactions `Jᵀλ` per body
    /// into `workspace.reactions`.
    #[inline]
    pub(super) fn solve_factored(
        &self,
        workspace: &mut MechanismWorkspace<A>,
        condition: Condition,
        consistency: Consistency,
    ) -> Result<(), ConstraintError> {
        let MechanismWorkspace {
            joints,
            matrix,
            tree,
            loops,
            reactions,
            ..
        } = workspace;
        for (j, rows) in joints.iter().enumerate() {
            let values = &rows.reduced.values[condition as usize][..rows.reduced.rank];
            let target = match self.topology.slots[j] {
                Slot::Tree { offset, .. } => &mut tree[offset..offset + values.len()],
                Slot::Loop { offset } => &mut loops[offset..offset + values.len()],
            };
            target.copy_from_slice(values);
        }
        matrix
            .solve(&self.topology, tree, loops, consistency, &self.settings)
            .map_err(|f| self.failure(f))?;
        reactions.iter_mut().for_each(|y| *y = [0.0; 6]);
        for (j, (joint, rows)) in self.joints.iter().zip(joints.iter()).enumerate() {
            let (on_body, on_reference) = rows.reactions(self.multipliers(j, rows.reduced.rank, tree, loops));
            add(&mut reactions[joint.body], &on_body);
            if let Some(r) = joint.reference {
                add(&mut reactions[r], &on_reference);
            }
        }
        Ok(())
    }

    /// The equations of motion at the given motors and body momenta: every body's kinematics and reaction
    /// (docs/mechanisms.md §M4: `K λ = z`, reactions `Jᵀλ`).
    #[inline]
    pub(super) fn evaluate(
        &self,
        t: f64,
        motors: &[A::Motor],
        body_momenta: &[A::Screw],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        let terms = if self.articulation.is_some() {
            BodyTerms::Forces
        } else {
            BodyTerms::FreeAccelerations
        };
        self.body_kinematics(t, motors, body_momenta, workspace, terms)?;
        // Free bodies with nothing held need no solve; with contacts they get one all the same, as the transitions read
        // the accelerations of touching points from it.
        if self.joints.is_empty() && workspace.rows.is_empty() && self.contacts.is_empty() {
            workspace.reactions.iter_mut().for_each(|y| *y = [0.0; 6]);
            return Ok(());
        }
        if self.articulation.is_none() {
            self.keep_joint_space_rows("the general solve")?;
        }
        if let Some(articulation) = &self.articulation {
            self.solve_articulated(articulation, t, workspace, true)
                .map_err(|body| ConstraintError::NonFinite {
                    name: self.names(self.topology.incidences[body].iter().map(|incidence| incidence.joint)),
                    t,
                })?;
            self.check_reactions(t, workspace)?;
            workspace.power += self.reaction_power(workspace);
            return Ok(());
        }
        self.joint_rows(t, workspace, Rows::Dynamics)?;
        // The round-off floor of the loop consistency check: the size of the terms in the joints' conditions.
        let scale = workspace
            .joints
            .iter()
            .map(|rows| rows.acceleration_scale.powi(2))
            .sum::<f64>()
            .sqrt();
        self.solve_reactions(workspace, Condition::Acceleration, Consistency::Check { scale })?;
        workspace.stage_factors = workspace.joints.iter().all(|rows| rows.reduced.direct);
        self.check_reactions(t, workspace)?;
        workspace.power += self.reaction_power(workspace);
        Ok(())
    }

    /// [`Mechanism::evaluate`] at the bodies' states.
    #[inline]
    pub(super) fn evaluate_states(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        let (mut motors, mut momenta) = (
            std::mem::take(&mut workspace.motors),
            std::mem::take(&mut workspace.momenta),
        );
        for (i, state) in states.iter().enumerate() {
            motors[i] = state.motor;
            // The sandwich `~RΩR`, as the paper's RK4 has it: its stage motors are not unit, and the sandwich
            // scales by ⟨R~R⟩₀ (the frame map would divide it out and change the method).
            momenta[i] = state.body_momentum();
        }
        let result = self.evaluate(t, &motors, &momenta, workspace);
        workspace.motors = motors;
        workspace.momenta = momenta;
        result
    }

    /// The articulated solve (docs/mechanisms.md §M7) on the workspace's body kinematics and external wrenches,
    /// with the joints' reactions when `reactions` is set; fails with the body whose articulated inertia is not
    /// positive definite.
    #[inline]
    pub(super) fn solve_articulated(
        &self,
        articulation: &Articulation,
        t: f64,
        workspace: &mut MechanismWorkspace<A>,
        reactions: bool,
    ) -> Result<(), usize> {
        if !self.contacts.is_empty() {
            let origin = articulation.origin(&workspace.bodies);
            self.resolve_contact_rows(&origin, workspace);
        }
        let MechanismWorkspace {
            bodies,
            external,
            reactions: reaction_wrenches,
            articulated,
            rows,
            ..
        } = workspace;
        articulation.solve(
            t,
            &self.joints,
            &self.bodies,
            bodies,
            external,
            rows,
            articulated,
            reactions.then_some(reaction_wrenches.as_mut_slice()),
        )
    }

    /// An error naming the joints at the first body whose reaction is not finite.
    #[inline]
    fn check_reactions(&self, t: f64, workspace: &MechanismWorkspace<A>) -> Result<(), ConstraintError> {
        for (i, reaction) in workspace.reactions.iter().enumerate() {
            if !reaction.iter().all(|y| y.is_finite()) {
                let names = self.names(self.topology.incidences[i].iter().map(|incidence| incidence.joint));
                return Err(ConstraintError::NonFinite { name: names, t });
            }
        }
        Ok(())
    }

    /// Joint j's multipliers in the solved tree and loop vectors.
    #[inline]
    fn multipliers<'v>(&self, joint: usize, rank: usize, tree: &'v [f64], loops: &'v [f64]) -> &'v [f64] {
        match self.topology.slots[joint] {
            Slot::Tree { offset, .. } => &tree[offset..offset + rank],
            Slot::Loop { offset } => &loops[offset..offset + rank],
        }
    }

    /// An error unless `got` (the length of a slice of states) is the number of bodies.
    #[inline]
    pub(super) fn check_count(&self, what: &'static str, got: usize) -> Result<(), ConstraintError> {
        if got == self.bodies.len() {
            Ok(())
        } else {
            Err(ConstraintError::Count {
                what,
                expected: self.bodies.len(),
                got,
            })
        }
    }

    /// The kinetic plus potential energy of the system: the bodies' kinetic energies, their forces' potentials
    /// (gravity) and the conservative force elements' (springs). An error unless there is one state per body.
    pub fn energy(&self, states: &[State<A>]) -> Result<f64, ConstraintError> {
        self.check_count("states", states.len())?;
        Ok(self.total_energy(states))
    }

    /// [`Mechanism::energy`] of states already counted.
    pub(super) fn total_energy(&self, states: &[State<A>]) -> f64 {
        let bodies: f64 = self
            .bodies
            .iter()
            .zip(states)
            .map(|(entry, state)| {
                state.kinetic_energy(&entry.body)
                    + entry
                        .forces
                        .iter()
                        .map(|f| f.potential_energy(&entry.body, state))
                        .sum::<f64>()
            })
            .sum();
        if self.elements.is_empty() {
            return bodies;
        }
        bodies + self.elements_potential(states)
    }

    /// The total momentum `Σ Ωᵢ` (world frame): linear momentum in the l-part, angular momentum about the world
    /// origin in the t-part (theory §3). An error unless there is one state per body.
    pub fn momentum(&self, states: &[State<A>]) -> Result<A::Screw, ConstraintError> {
        self.check_count("states", states.len())?;
        Ok(states.iter().fold(A::screw(ScrewCoordinates::default()), |total, s| {
            total + s.momentum_about_origin()
        }))
    }

    /// The largest position and velocity residuals over the joints at this state; a contact's depth below its plane
    /// counts as a position residual (m).
    pub fn violation(&self, t: f64, states: &[State<A>]) -> Result<Violation, ConstraintError> {
        self.check_count("states", states.len())?;
        let mut workspace = self.new_workspace();
        self.position_rows(t, states, &mut workspace, Rows::Residuals)?;
        let (mut position, velocity) = self.coupling_violation(states);
        for contact in 0..self.contacts.len() {
            position = position.max(-self.contact_height(contact, states));
        }
        Ok(workspace
            .joints
            .iter()
            .fold(Violation { position, velocity }, |v, rows| Violation {
                position: v.position.max(rows.position_residual),
                velocity: v.velocity.max(rows.velocity_residual),
            }))
    }

    /// The rates of every body at this state (Ḃ and dΩ/dt), or why the reactions could not be found: the
    /// evaluation the integrators make, for diagnostics (it allocates a workspace).
    pub fn rates_at(&self, t: f64, states: &[State<A>]) -> Result<Vec<Rates<A>>, ConstraintError> {
        self.check_count("states", states.len())?;
        let mut workspace = self.new_workspace();
        let zero = A::screw(ScrewCoordinates::default());
        let mut rates = vec![
            Rates {
                body_velocity: zero,
                momentum_rate: zero,
            };
            states.len()
        ];
        Dynamics::rates(self, t, states, &mut rates, &mut workspace)?;
        Ok(rates)
    }

    /// The world wrench each joint exerts on its body (its reference receives the opposite), at this state.
    pub fn reactions(&self, t: f64, states: &[State<A>]) -> Result<Vec<A::Screw>, ConstraintError> {
        self.check_count("states", states.len())?;
        let mut workspace = self.new_workspace();
        for (i, state) in states.iter().enumerate() {
            workspace.motors[i] = state.motor;
            workspace.momenta[i] = state.body_momentum();
        }
        let (motors, momenta) = (workspace.motors.clone(), workspace.momenta.clone());
        self.evaluate(t, &motors, &momenta, &mut workspace)?;
        Ok(self
            .joints
            .iter()
            .enumerate()
            .map(|(j, joint)| {
                let rows = &workspace.joints[j];
                let lambda = self.multipliers(j, rows.reduced.rank, &workspace.tree, &workspace.loops);
                let (y, _) = rows.reactions(lambda);
                let kinematics = &workspace.bodies[joint.body].kinematics;
                A::screw(kinematics.to_world_coordinates(&wrench_screw(&y)))
            })
            .collect())
    }
}

/// `total += y` over six coordinates.
/// The power `y·x` of a wrench `y = (τ; f)` on a body moving with velocity `x = (ω; v)` (the same axes and point).
fn wrench_power(y: &[f64; 6], x: &nalgebra::Vector6<f64>) -> f64 {
    dot6(y, &(*x).into())
}

fn add(total: &mut [f64; 6], y: &[f64; 6]) {
    total.iter_mut().zip(y).for_each(|(t, y)| *t += y);
}
