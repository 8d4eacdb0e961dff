//! The mechanism as a system the integrators step ([`crate::Dynamics`]).

use crate::algebra::Algebra;
use crate::body::Body;
use crate::constraints::{ConstraintError, Stabilisation};
use crate::limits::LimitChange;
use crate::mechanism::joint_rows::wrench_screw;
use crate::mechanism::joint_space::JointSpace;
use crate::mechanism::model::{Mechanism, MechanismWorkspace};
use crate::motion::{BodyRates, Dynamics, Rates};
use crate::motor;
use crate::state::State;

impl<A: Algebra> Dynamics<A> for Mechanism<A> {
    type Workspace = MechanismWorkspace<A>;

    fn feedback_rate(&self) -> f64 {
        self.stabilisation.feedback_rate()
    }

    fn drift(&self, t: f64, states: &[State<A>]) -> f64 {
        self.violation(t, states)
            .map_or(f64::INFINITY, |violation| violation.position)
    }

    fn workspace(&self) -> MechanismWorkspace<A> {
        self.new_workspace()
    }

    fn body_count(&self) -> usize {
        self.bodies.len()
    }

    fn body(&self, index: usize) -> &Body {
        &self.bodies[index].body
    }

    /// In the body frames; the momentum rate is the external wrench about the centre of mass (as for an
    /// unconstrained body) plus the reaction turned to world axes.
    #[inline]
    fn rates(
        &self,
        t: f64,
        states: &[State<A>],
        rates: &mut [Rates<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        self.check_count("rates", rates.len())?;
        self.evaluate_states(t, states, workspace)?;
        for (i, (rate, state)) in rates.iter_mut().zip(states).enumerate() {
            let kinematics = &workspace.bodies[i].kinematics;
            // The reactions and the force elements' wrenches, body frame, turned to world axes together (their
            // moments stay about the centre of mass, as the momentum rate's are).
            let mut internal = wrench_screw(&workspace.reactions[i]);
            if !self.elements.is_empty() {
                internal = internal + workspace.element_wrenches[i];
            }
            let reaction = A::screw(kinematics.frame.turn_to_world(&internal));
            *rate = Rates {
                body_velocity: kinematics.body_velocity,
                momentum_rate: self.external_wrench(i, t, state, kinematics) + reaction,
            };
        }
        Ok(())
    }

    /// Renews which switching contacts are watched and the directions the sliding contacts' slips are watched along.
    fn begin_step(&self, _t: f64, states: &[State<A>], workspace: &mut MechanismWorkspace<A>) {
        self.renew_switches(states, workspace);
        if !self.frictional.is_empty() {
            self.renew_slip_references(states, workspace);
        }
    }

    /// In the body frames throughout: no world momentum is built (unless a custom force asks for it) and the
    /// reactions are not moved to the world and back.
    #[inline]
    fn body_rates(
        &self,
        t: f64,
        motors: &[A::Motor],
        body_momenta: &[A::Screw],
        rates: &mut [BodyRates<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("motors", motors.len())?;
        self.check_count("body momenta", body_momenta.len())?;
        self.check_count("rates", rates.len())?;
        self.evaluate(t, motors, body_momenta, workspace)?;
        for (i, rate) in rates.iter_mut().enumerate() {
            let total = workspace.external[i] + wrench_screw(&workspace.reactions[i]);
            *rate = BodyRates {
                body_velocity: workspace.bodies[i].kinematics.body_velocity,
                body_wrench: A::screw(total),
            };
        }
        Ok(())
    }

    fn after_joint_step(
        &self,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        match self.stabilisation {
            Stabilisation::Projection { .. } => self.place_held_contacts(t, states, workspace),
            _ => Ok(()),
        }
    }

    #[inline]
    fn after_step(
        &self,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        match self.stabilisation {
            Stabilisation::Projection { position_iterations } => {
                self.project_with(t, states, position_iterations, workspace)
            }
            _ => {
                for state in states.iter_mut() {
                    state.motor = motor::normalise::<A>(state.motor);
                }
                Ok(())
            }
        }
    }

    #[inline]
    fn energy(&self, states: &[State<A>]) -> f64 {
        self.total_energy(states)
    }

    #[inline]
    fn power(&self, workspace: &MechanismWorkspace<A>) -> f64 {
        workspace.power
    }

    fn conserves_world_momenta(&self) -> bool {
        self.joints.is_empty()
            && self.contacts.is_empty()
            && self.elements.is_empty()
            && self.bodies.iter().all(|body| body.forces.is_empty())
    }

    fn joint_layout(&self) -> Option<crate::joint_layout::JointLayout> {
        self.articulation.as_ref()?;
        self.coordinates().map(JointSpace::layout)
    }

    #[inline]
    fn read_joints(
        &self,
        states: &[State<A>],
        positions: &mut [f64],
        velocities: &mut [f64],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        self.read_joints_into(states, positions, velocities, &mut workspace.previous_positions)
    }

    #[inline]
    fn write_joints(
        &self,
        t: f64,
        positions: &[f64],
        velocities: &[f64],
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.check_count("states", states.len())?;
        self.write_joints_into(t, positions, velocities, states, &mut workspace.placed)
    }

    #[inline]
    fn joint_rates(
        &self,
        t: f64,
        positions: &[f64],
        velocities: &[f64],
        accelerations: &mut [f64],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<(), ConstraintError> {
        self.joint_rates_at(t, positions, velocities, accelerations, workspace)
    }

    fn limit_count(&self) -> usize {
        Mechanism::limit_count(self)
    }

    fn limit_name(&self, index: usize) -> Option<&str> {
        Mechanism::limit_name(self, index)
    }

    fn limit_values(
        &self,
        t: f64,
        states: &[State<A>],
        workspace: &mut MechanismWorkspace<A>,
        values: &mut [f64],
    ) -> Result<(), ConstraintError> {
        Mechanism::limit_values(self, t, states, workspace, values)
    }

    fn limit_transition(
        &self,
        index: usize,
        t: f64,
        states: &mut [State<A>],
        workspace: &mut MechanismWorkspace<A>,
    ) -> Result<Vec<(usize, LimitChange)>, ConstraintError> {
        Mechanism::limit_transition(self, index, t, states, workspace)
    }
}
