//! The equations of motion (`docs/theory.md` §5) and the interface the integrators step: a system of N rigid bodies.
//!
//! ```text
//! Ω_b = ~R Ω R,  Ḃ = M⁻¹[Ω_b],  dR/dt = −½ R Ḃ,  dΩ/dt = W_world (+ R F ~R for a reaction F)
//! ```
//!
//! A system's state is one [`State`] per body; the integrators advance every body with the same method, so
//! the state lives on the product of the bodies' motor groups (each motor stays an exact motor in the
//! Lie-group methods).

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::body::Body;
use crate::constraints::ConstraintError;
use crate::forces::Force;
use crate::joint_layout::JointLayout;
use crate::motor;
use crate::state::State;

/// What the integrators need of one body at one state: the body-frame velocity Ḃ (so `dR/dt = −½RḂ`, and Lie
/// group methods can use Ḃ directly) and the rate of the momentum about the centre of mass `dΩ_c/dt`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rates<A: Algebra> {
    /// `Ḃ = M⁻¹[Ω_b]`, body frame.
    pub body_velocity: A::Screw,
    /// dΩ_c/dt: the resultant wrench (external forces and reactions) about the centre of mass, world axes. The
    /// centre's velocity is parallel to the linear momentum, so its motion adds nothing to the rate (docs/dynamics.md,
    /// "Momentum about the centre of mass").
    pub momentum_rate: A::Screw,
}

impl<A: Algebra> Rates<A> {
    /// `dR/dt = −½ R Ḃ`.
    #[inline]
    pub fn motor_rate(&self, motor: A::Motor) -> A::Motor {
        A::motor_times_screw(motor, self.body_velocity) * -0.5
    }
}

/// The rates of one body in its own frame, for integrators that carry the body momentum `Ω_b = ~RΩR` within a
/// step: `dΩ_b/dt = Ḃ × Ω_b + W_b` (theory §5) with `W_b = ~R W R` the body view of the resultant wrench.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyRates<A: Algebra> {
    /// `Ḃ = M⁻¹[Ω_b]`, body frame.
    pub body_velocity: A::Screw,
    /// `W_b = ~R W R`: the resultant wrench (external forces and reactions), body frame.
    pub body_wrench: A::Screw,
}

/// A system of rigid bodies the integrators can step: its rates, and what to do after each step. Every slice
/// holds one entry per body, in the system's body order.
pub trait Dynamics<A: Algebra> {
    /// Scratch memory of an evaluation (the reaction solve's buffers), made once per run so that steps do not
    /// allocate.
    type Workspace: Send;

    /// A fresh workspace for this system.
    fn workspace(&self) -> Self::Workspace;

    /// The number of bodies.
    fn body_count(&self) -> usize;

    /// The mass properties of body `index`.
    fn body(&self, index: usize) -> &Body;

    /// Ḃ and dΩ/dt of every body at time `t`, or why the reaction could not be found.
    fn rates(
        &self,
        t: f64,
        states: &[State<A>],
        rates: &mut [Rates<A>],
        workspace: &mut Self::Workspace,
    ) -> Result<(), ConstraintError>;

    /// Ḃ and `W_b` of every body at time `t`, from the motors and the body momenta `Ω_b`.
    fn body_rates(
        &self,
        t: f64,
        motors: &[A::Motor],
        body_momenta: &[A::Screw],
        rates: &mut [BodyRates<A>],
        workspace: &mut Self::Workspace,
    ) -> Result<(), ConstraintError>;

    /// Called before every step from `states` (each attempt and each partial step, all from the same start): by
    /// default nothing. A mechanism renews the direction its sliding contacts' slips are watched along here
    /// (docs/contacts.md "Friction").
    fn begin_step(&self, _t: f64, _states: &[State<A>], _workspace: &mut Self::Workspace) {}

    /// Called after every step: by default, renormalise the motors (theory §2, §10). Constrained systems also
    /// project onto the constraint manifold here.
    fn after_step(
        &self,
        _t: f64,
        states: &mut [State<A>],
        _workspace: &mut Self::Workspace,
    ) -> Result<(), ConstraintError> {
        for state in states {
            state.motor = motor::normalise::<A>(state.motor);
        }
        Ok(())
    }

    /// Called after every step in joint coordinates, which ends on the joints (forward kinematics): by default
    /// nothing. A mechanism stabilised by projection puts its held contacts back on their planes here
    /// (docs/contacts.md "Projection").
    fn after_joint_step(
        &self,
        _t: f64,
        _states: &mut [State<A>],
        _workspace: &mut Self::Workspace,
    ) -> Result<(), ConstraintError> {
        Ok(())
    }

    /// Total energy (kinetic + potential), for diagnostics.
    fn energy(&self, states: &[State<A>]) -> f64;

    /// The fastest rate (1/s) at which the system's constraint feedback (Baumgarte) pulls a residual back, which an
    /// explicit step must resolve ([`crate::StepError::FeedbackStepTooLarge`]); zero (the default) without feedback.
    fn feedback_rate(&self) -> f64 {
        0.0
    }

    /// How far `states` are off the system's constraints: the largest position residual (m or rad), infinite if it
    /// cannot be evaluated; zero (the default) for a system without constraints. A failed step from a state this far
    /// off is blamed on the drift, not on the step's size ([`crate::StepError::ConstraintStepTooLarge`]).
    fn drift(&self, _t: f64, _states: &[State<A>]) -> f64 {
        0.0
    }

    /// Where the system's joint coordinates are, for the methods that step in them
    /// ([`crate::JointMethod`]); `None` (the default) for a system without them.
    fn joint_layout(&self) -> Option<JointLayout> {
        None
    }

    /// The joint positions and velocities of `states` (for [`Dynamics::joint_layout`]'s systems).
    fn read_joints(
        &self,
        _states: &[State<A>],
        _positions: &mut [f64],
        _velocities: &mut [f64],
        _workspace: &mut Self::Workspace,
    ) -> Result<(), ConstraintError> {
        Err(no_joint_coordinates())
    }

    /// The bodies' states at joint positions and velocities, at time `t` (a driven joint at its drive then, whatever
    /// its entries hold).
    fn write_joints(
        &self,
        _t: f64,
        _positions: &[f64],
        _velocities: &[f64],
        _states: &mut [State<A>],
        _workspace: &mut Self::Workspace,
    ) -> Result<(), ConstraintError> {
        Err(no_joint_coordinates())
    }

    /// The joint accelerations at joint positions and velocities, at time `t`.
    fn joint_rates(
        &self,
        _t: f64,
        _positions: &[f64],
        _velocities: &[f64],
        _accelerations: &mut [f64],
        _workspace: &mut Self::Workspace,
    ) -> Result<(), ConstraintError> {
        Err(no_joint_coordinates())
    }

    /// The number of one-sided constraints the system enforces: joint limits ([`crate::limits`]), then contacts
    /// ([`crate::contacts`]); zero (the default) without them.
    fn limit_count(&self) -> usize {
        0
    }

    /// The name of one-sided constraint `index` (a limit's joint, or the contact), if there is that constraint.
    fn limit_name(&self, _index: usize) -> Option<&str> {
        None
    }

    /// Per one-sided constraint, the value whose fall to zero or below is its next transition, at `(t, states)`:
    /// while free a limited joint's gap to its nearer bound (rad or m) or a contact point's height above its plane
    /// (m), while held the reaction pushing it onto the bound or plane (N m or N).
    fn limit_values(
        &self,
        _t: f64,
        _states: &[State<A>],
        _workspace: &mut Self::Workspace,
        _values: &mut [f64],
    ) -> Result<(), ConstraintError> {
        Ok(())
    }

    /// One-sided constraint `index`'s transition at `(t, states)`, where its value has fallen to zero: an impact at
    /// its bound or plane (the velocities in `states` change), a hold, or a release. Returns what changed, in order,
    /// with the index of the constraint each change is of (a contact's impact changes every contact it touches).
    fn limit_transition(
        &self,
        _index: usize,
        _t: f64,
        _states: &mut [State<A>],
        _workspace: &mut Self::Workspace,
    ) -> Result<Vec<(usize, crate::limits::LimitChange)>, ConstraintError> {
        Ok(Vec::new())
    }

    /// The power (W) the system's non-conservative forces put in at the last evaluation in `workspace`, which the
    /// integrators integrate into the work done ([`crate::integrate::Stepper::last_work`]); zero by default.
    fn power(&self, _workspace: &Self::Workspace) -> f64 {
        0.0
    }

    /// Whether [`Dynamics::body_rates`] reads the motors. A force-free body's rates do not, so the body-momentum
    /// integrators skip computing the motors of their stages (an exponential and a motor product each).
    fn rates_depend_on_motors(&self) -> bool {
        true
    }

    /// Whether no force and no joint acts on any body, so that each body's world momentum is a constant of the
    /// motion. The body-momentum integrators then keep it exactly ([`crate::integrate`]).
    fn conserves_world_momenta(&self) -> bool {
        false
    }

    /// The system as a single free body, if it is one (the splitting integrators need its structure).
    fn as_free_body(&self) -> Option<&FreeBody<A>> {
        None
    }
}

fn no_joint_coordinates() -> ConstraintError {
    ConstraintError::InvalidParameter {
        name: "joint coordinates".to_owned(),
        reason: "this system has no joint coordinates to step in".to_owned(),
    }
}

/// One rigid body under external forces, no constraints.
#[derive(Clone, Debug)]
pub struct FreeBody<A: Algebra> {
    /// The body's mass properties.
    pub body: Body,
    /// The external forces on it.
    pub forces: Vec<Force<A>>,
}

impl<A: Algebra> FreeBody<A> {
    /// The body with no forces.
    ///
    /// Without forces a tumbling body keeps its world momentum (here exactly: the body-momentum integrators
    /// project onto it) and its energy.
    ///
    /// ```
    /// use dynamics::{simulate, Body, FreeBody, Method, Pga, Schedule, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let brick = Body::cuboid(1.0, Vector3::new(0.1, 0.2, 0.3))?;
    /// let system = FreeBody::<Pga>::new(brick);
    /// let spin = Vector3::new(0.1, 5.0, 0.1); // rad/s about the unstable middle axis
    /// let start = State::new(&brick, Vector3::zeros(), &UnitQuaternion::identity(), spin, Vector3::x());
    /// let run = simulate(&system, &[start], Method::Rkmk4Body, &Schedule::new(1e-3, 1.0)?)?;
    /// assert_eq!(run.final_state[0].central_momentum, start.central_momentum);
    /// assert!((run.body(0)[100].energy - run.body(0)[0].energy).abs() < 1e-9); // J
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(body: Body) -> Self {
        FreeBody {
            body,
            forces: Vec::new(),
        }
    }

    /// Adds a force, builder style.
    pub fn with_force(mut self, force: Force<A>) -> Self {
        self.forces.push(force);
        self
    }

    /// The resultant external wrench about the centre of mass, world axes.
    pub fn central_wrench(&self, t: f64, state: &State<A>) -> A::Screw {
        self.forces.iter().fold(A::screw(Default::default()), |total, force| {
            total + force.central_wrench_at(&self.body, t, state.motor, || state.central_momentum)
        })
    }

    /// The rates of the body at one state (a free body's cannot fail).
    #[inline]
    pub fn rates_at(&self, t: f64, state: &State<A>) -> Rates<A> {
        Rates {
            body_velocity: state.body_velocity(&self.body),
            momentum_rate: self.central_wrench(t, state),
        }
    }

    /// `Ḃ = M⁻¹[Ω_b]` straight from the body momentum, and a force-free body's zero wrench without a sandwich.
    #[inline]
    fn body_rates_of(&self, t: f64, motor: A::Motor, body_momentum: A::Screw) -> BodyRates<A> {
        let body_velocity = self.body.velocity::<A>(body_momentum);
        if self.forces.is_empty() {
            return BodyRates {
                body_velocity,
                body_wrench: A::screw(ScrewCoordinates::default()),
            };
        }
        // One frame turns the momentum out (for forces that read it) and the wrench back.
        let frame = motor::ScrewFrame::of::<A>(motor);
        let world = State {
            motor,
            central_momentum: A::screw(frame.turn_to_world(&A::screw_coordinates(body_momentum))),
        };
        let wrench = A::screw_coordinates(self.central_wrench(t, &world));
        BodyRates {
            body_velocity,
            body_wrench: A::screw(frame.turn_to_body(&wrench)),
        }
    }

    /// The power of the forces other than gravity (gravity's is the rate of its potential, in the energy): each
    /// wrench `(f; m_c)` about the centre of mass on the body moving with centre-of-mass velocity v and angular
    /// velocity ω, `f·v + m_c·ω`.
    fn power_at(&self, t: f64, state: &State<A>) -> f64 {
        let mut forces = self
            .forces
            .iter()
            .filter(|force| !matches!(force, Force::Gravity { .. }))
            .peekable();
        if forces.peek().is_none() {
            return 0.0;
        }
        let velocity = state.world_velocity(&self.body);
        forces
            .map(|force| {
                let w = A::screw_coordinates(
                    force.central_wrench_at(&self.body, t, state.motor, || state.central_momentum),
                );
                w.l.dot(&velocity.linear) + w.t.dot(&velocity.angular)
            })
            .sum()
    }

    fn state_energy(&self, state: &State<A>) -> f64 {
        state.kinetic_energy(&self.body)
            + self
                .forces
                .iter()
                .map(|f| f.potential_energy(&self.body, state))
                .sum::<f64>()
    }
}

/// An error unless each slice given to a free body holds exactly its one entry.
fn one_each(counts: &[(&'static str, usize)]) -> Result<(), ConstraintError> {
    match counts.iter().find(|&&(_, got)| got != 1) {
        Some(&(what, got)) => Err(ConstraintError::Count { what, expected: 1, got }),
        None => Ok(()),
    }
}

/// A free body's workspace: the power of its forces at the last evaluation.
#[derive(Clone, Copy, Debug, Default)]
pub struct FreeBodyWorkspace {
    power: f64,
}

impl<A: Algebra> Dynamics<A> for FreeBody<A> {
    type Workspace = FreeBodyWorkspace;

    fn workspace(&self) -> FreeBodyWorkspace {
        FreeBodyWorkspace::default()
    }

    fn body_count(&self) -> usize {
        1
    }

    fn body(&self, _index: usize) -> &Body {
        &self.body
    }

    #[inline]
    fn rates(
        &self,
        t: f64,
        states: &[State<A>],
        rates: &mut [Rates<A>],
        workspace: &mut FreeBodyWorkspace,
    ) -> Result<(), ConstraintError> {
        one_each(&[("states", states.len()), ("rates", rates.len())])?;
        workspace.power = 0.0;
        for (rate, state) in rates.iter_mut().zip(states) {
            *rate = self.rates_at(t, state);
            workspace.power += self.power_at(t, state);
        }
        Ok(())
    }

    #[inline]
    fn body_rates(
        &self,
        t: f64,
        motors: &[A::Motor],
        body_momenta: &[A::Screw],
        rates: &mut [BodyRates<A>],
        workspace: &mut FreeBodyWorkspace,
    ) -> Result<(), ConstraintError> {
        one_each(&[
            ("motors", motors.len()),
            ("body momenta", body_momenta.len()),
            ("rates", rates.len()),
        ])?;
        workspace.power = 0.0;
        for ((rate, &motor), &momentum) in rates.iter_mut().zip(motors).zip(body_momenta) {
            *rate = self.body_rates_of(t, motor, momentum);
            if self.forces.iter().any(|force| !matches!(force, Force::Gravity { .. })) {
                let state = State {
                    motor,
                    central_momentum: motor::central_from_body::<A>(motor, momentum),
                };
                workspace.power += self.power_at(t, &state);
            }
        }
        Ok(())
    }

    fn power(&self, workspace: &FreeBodyWorkspace) -> f64 {
        workspace.power
    }

    fn energy(&self, states: &[State<A>]) -> f64 {
        states.iter().map(|state| self.state_energy(state)).sum()
    }

    fn rates_depend_on_motors(&self) -> bool {
        !self.forces.is_empty()
    }

    fn conserves_world_momenta(&self) -> bool {
        self.forces.is_empty()
    }

    fn as_free_body(&self) -> Option<&FreeBody<A>> {
        Some(self)
    }
}
