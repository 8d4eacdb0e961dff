//! Steps of one integrator on one system: the buffers made once, the step with its checks and diagnosis of a
//! failure, the error estimate of an embedded pair and the continuous extension inside the last step.

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::exponential::exp;
use crate::integrate::error::{SplittingError, StepError, MAX_FEEDBACK_STEP, MAX_ROTOR_NORM_ERROR};
use crate::integrate::joint_coordinates::{self, JointBuffers};
use crate::integrate::lie_group::{
    check_turn, rk4, rkmk4, rkmk4_body_momentum, rkmk_body_momentum, rkmk_stage, weighted_slopes, Buffers,
};
use crate::integrate::methods::{Integrator, JointMethod, Method, SplittingMethod};
use crate::integrate::splitting::{step_splitting, KineticSplitting};
use crate::integrate::tableaux::{
    dop853_dense_weights, dormand_prince_5_dense_weights, BUTCHER_6, COOPER_VERNER_8, DOP853, DOP853_EXTENDED_STAGES,
    DOP853_EXTENSION, DORMAND_PRINCE_5, RK4, RK4_WEIGHTS,
};
use crate::motion::Dynamics;
use crate::motor;
use crate::state::{State, MAX_DISTANCE_IN_GYRATION_RADII};

/// Steps of one integrator on one system. It owns the buffers of the stages and the system's workspace, so a
/// step allocates nothing; make one per run (or per thread).
pub struct Stepper<'a, A: Algebra, D: Dynamics<A> + ?Sized> {
    pub(super) dynamics: &'a D,
    pub(super) integrator: Integrator,
    splitting: Option<KineticSplitting<'a, A>>,
    workspace: D::Workspace,
    pub(super) buffers: Buffers<A>,
    /// The buffers of a method stepping in joint coordinates.
    pub(super) joints: Option<JointBuffers<A>>,
    /// The work done by the non-conservative forces over the last successful step (J).
    last_work: f64,
    /// The start and the length of the last successful step (s), if its stages are still in the buffers (for the
    /// error estimate and the dense output).
    pub(super) last_step: Option<(f64, f64)>,
    /// Whether the last successful step's extra stages for the continuous extension have been evaluated
    /// ([`Method::Dop853Body`] makes them only in steps that need them).
    extended: bool,
    /// Evaluations of the equations of motion so far.
    evaluations: usize,
}

impl<'a, A: Algebra, D: Dynamics<A> + ?Sized> Stepper<'a, A, D> {
    /// A stepper of `integrator` on `dynamics`; splitting methods need a single free body with forces of the
    /// configuration only.
    ///
    /// Steps by hand (what [`crate::simulate()`] does): a body coasting at 2 m/s moves 2 cm in ten steps of 1 ms.
    /// A splitting method is refused for a mechanism.
    ///
    /// ```
    /// use dynamics::integrate::SplittingError;
    /// use dynamics::{Body, FreeBody, Mechanism, Method, Pga, SplittingMethod, State, StepError, Stepper};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.1)?;
    /// let system = FreeBody::<Pga>::new(ball);
    /// let mut stepper = Stepper::new(&system, Method::Rkmk4)?;
    /// let still = UnitQuaternion::identity();
    /// let mut states = [State::new(&ball, Vector3::zeros(), &still, Vector3::zeros(), Vector3::x() * 2.0)]; // m/s
    /// for k in 0..10 {
    ///     stepper.step(k as f64 * 1e-3, &mut states, 1e-3)?;
    /// }
    /// assert!((states[0].pose().0 - Vector3::new(0.02, 0.0, 0.0)).norm() < 1e-15); // m
    ///
    /// let mechanism = Mechanism::<Pga>::single(ball);
    /// let refused = Stepper::new(&mechanism, SplittingMethod::Strang).err();
    /// assert_eq!(refused, Some(StepError::Splitting(SplittingError::NotAFreeBody)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(dynamics: &'a D, integrator: impl Into<Integrator>) -> Result<Self, StepError> {
        let integrator = integrator.into();
        let joints = match integrator {
            Integrator::Joint(method) => {
                let layout = dynamics
                    .joint_layout()
                    .ok_or(StepError::NoJointCoordinates { method: method.name() })?;
                Some(JointBuffers::new(layout, DOP853_EXTENDED_STAGES))
            }
            _ => None,
        };
        let splitting = match integrator {
            Integrator::General(_) | Integrator::Joint(_) => None,
            Integrator::Splitting(_) => {
                let free = dynamics.as_free_body().ok_or(SplittingError::NotAFreeBody)?;
                Some(KineticSplitting::new(free)?)
            }
        };
        Ok(Stepper {
            dynamics,
            integrator,
            splitting,
            workspace: dynamics.workspace(),
            buffers: Buffers::new(dynamics.body_count()),
            joints,
            last_work: 0.0,
            last_step: None,
            extended: false,
            evaluations: 0,
        })
    }

    /// The integrator this stepper takes steps of.
    pub fn integrator(&self) -> Integrator {
        self.integrator
    }

    /// The system being integrated.
    pub fn dynamics(&self) -> &'a D {
        self.dynamics
    }

    /// The work (J) the system's non-conservative forces (force elements other than springs: dampers, actuators,
    /// controllers, couples) did over the last successful step, integrated with the method's own weights from the
    /// power at each stage ([`Dynamics::power`]); zero before any step.
    pub fn last_work(&self) -> f64 {
        self.last_work
    }

    /// The system's workspace, for evaluations between steps.
    pub fn workspace(&mut self) -> &mut D::Workspace {
        &mut self.workspace
    }

    /// Evaluations of the equations of motion by this stepper's steps so far: every stage of every step tried,
    /// including failed and partial ones (a splitting method's force evaluations).
    pub fn evaluations(&self) -> usize {
        self.evaluations
    }

    /// The state at the fraction `theta` ∈ [0, 1] of the last successful step, from the method's continuous
    /// extension, into `out`; returns the work done from the step's start to there. `None` for a method without
    /// one, or when the last step's stages are gone (after a failed or partial step). [`Method::Dop853Body`]
    /// evaluates its extension's four stages on the first call in a step, which can fail as a stage can.
    pub(crate) fn dense_output(&mut self, theta: f64, out: &mut [State<A>]) -> Result<Option<f64>, StepError> {
        let Some((t, dt)) = self.last_step else {
            return Ok(None);
        };
        let (dormand_prince, dop853);
        let weights: &[f64] = match self.integrator {
            Integrator::General(Method::Dopri5Body) => {
                dormand_prince = dormand_prince_5_dense_weights(theta);
                &dormand_prince
            }
            Integrator::General(Method::Dop853Body) => {
                self.extend_dop853(t, dt)?;
                dop853 = dop853_dense_weights(theta);
                &dop853
            }
            Integrator::Joint(JointMethod::Dop853) => {
                self.extend_dop853(t, dt)?;
                let weights = dop853_dense_weights(theta);
                let joints = self.joints.as_mut().expect("made with the stepper");
                (joints.dense(self.dynamics, (&weights, dt, t + theta * dt), out, &mut self.workspace))
                    .map_err(|error| StepError::Constraint { t, error })?;
                return Ok(Some(work_over(dt, &weights, &self.buffers.powers)));
            }
            _ => return Ok(None),
        };
        let buffers = &self.buffers;
        for (b, state) in out.iter_mut().enumerate() {
            let (sigma, momentum) = weighted_slopes(buffers, weights, b, (dt, buffers.start_momenta[b]));
            let motor = A::compose(buffers.start_motors[b], exp::<A>(sigma));
            *state = State {
                motor,
                central_momentum: motor::central_from_body::<A>(motor, momentum),
            };
        }
        Ok(Some(work_over(dt, weights, &buffers.powers)))
    }

    /// The four stages DOP853's continuous extension adds to the last step from `t` of length `dt`, once per step.
    fn extend_dop853(&mut self, t: f64, dt: f64) -> Result<(), StepError> {
        if self.extended {
            return Ok(());
        }
        self.evaluations += DOP853_EXTENSION.len();
        if let Some(joints) = self.joints.as_mut() {
            let stages = (DOP853.b.len(), DOP853_EXTENSION.as_slice());
            (joints.extend(
                self.dynamics,
                (t, dt, DOP853.order),
                stages,
                &mut self.buffers.powers,
                &mut self.workspace,
            ))
            .map_err(|error| StepError::Constraint { t, error })?;
            self.extended = true;
            return Ok(());
        }
        for (k, (row, node)) in DOP853_EXTENSION.iter().enumerate() {
            let at = (DOP853.b.len() + k, t + node * dt, dt);
            rkmk_stage(
                self.dynamics,
                at,
                row,
                DOP853.order,
                &mut self.buffers,
                &mut self.workspace,
            )
            .map_err(|error| StepError::Constraint { t, error })?;
        }
        self.extended = true;
        Ok(())
    }

    /// The weights of `integrator`'s stages (none for a splitting, whose sub-steps are exact flows).
    fn stage_weights(integrator: Integrator) -> &'static [f64] {
        match integrator {
            Integrator::General(Method::Rk4 | Method::Rkmk4 | Method::Rkmk4Body) => &RK4_WEIGHTS,
            Integrator::General(Method::Rkmk6Body) => &BUTCHER_6.b,
            Integrator::General(Method::Dopri5Body) => &DORMAND_PRINCE_5.b,
            Integrator::General(Method::Dop853Body) | Integrator::Joint(JointMethod::Dop853) => &DOP853.b,
            Integrator::General(Method::Rkmk8Body) | Integrator::Joint(JointMethod::Rkmk8) => &COOPER_VERNER_8.b,
            Integrator::Joint(JointMethod::Rkmk4) => &RK4.b,
            Integrator::Joint(JointMethod::Rkmk6) => &BUTCHER_6.b,
            Integrator::Splitting(_) => &[],
        }
    }

    /// The evaluations of the equations of motion one step of `integrator` takes: one per stage, or a splitting's
    /// force kicks (two per Strang step, three Strang steps per Yoshida step).
    fn evaluations_per_step(integrator: Integrator) -> usize {
        match integrator {
            Integrator::Splitting(SplittingMethod::Strang) => 2,
            Integrator::Splitting(SplittingMethod::Yoshida4) => 6,
            _ => Self::stage_weights(integrator).len(),
        }
    }

    /// One step from `(t, states)` to `t + dt`, followed by [`Dynamics::after_step`]. On an error the states are
    /// left as they were before the step.
    pub fn step(&mut self, t: f64, states: &mut [State<A>], dt: f64) -> Result<(), StepError> {
        let expected = self.dynamics.body_count();
        if states.len() != expected {
            return Err(StepError::BodyCount {
                expected,
                got: states.len(),
            });
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err(StepError::InvalidStep { dt });
        }
        if !t.is_finite() {
            return Err(StepError::InvalidTime { t });
        }
        if let Some(body) = states.iter().position(|state| !state.is_representable()) {
            return Err(StepError::NonFiniteInput { t, body });
        }
        for (body, state) in states.iter().enumerate() {
            let distance = motor::position_of::<A>(state.motor).norm();
            let limit = MAX_DISTANCE_IN_GYRATION_RADII * self.dynamics.body(body).smallest_gyration_radius();
            if distance > limit {
                return Err(StepError::TooFarFromOrigin {
                    t,
                    body,
                    distance,
                    limit,
                });
            }
        }
        let rotor_norms = states.iter().map(State::rotor_norm_squared).enumerate();
        if let Some((body, norm_squared)) = rotor_norms
            .into_iter()
            .find(|(_, n)| (n - 1.0).abs() > MAX_ROTOR_NORM_ERROR)
        {
            return Err(StepError::NotARigidMotion { t, body, norm_squared });
        }
        let rate = self.dynamics.feedback_rate();
        if dt * rate > MAX_FEEDBACK_STEP && matches!(self.integrator, Integrator::General(_)) {
            return Err(StepError::FeedbackStepTooLarge { t, dt, rate });
        }
        self.dynamics.begin_step(t, states, &mut self.workspace);
        let result = match self.attempt(t, states, dt) {
            Err(StepError::Constraint { error, .. }) => Err(self.diagnose(t, states, dt, error)),
            result => result,
        };
        self.last_step = result.is_ok().then_some((t, dt));
        if result.is_ok() {
            states.copy_from_slice(&self.buffers.next);
            let weights = Self::stage_weights(self.integrator);
            self.last_work = work_over(dt, weights, &self.buffers.powers);
        }
        result
    }

    /// Why a step that failed in the constraints failed: a body turning more than [`MAX_TURN_PER_STEP`] in it
    /// ([`StepError::StepTooLarge`]); else, from a state on the constraints (within
    /// [`MAX_DRIFT_FOR_STEP_DIAGNOSIS`]) from which a shorter step succeeds, the step's size
    /// ([`StepError::ConstraintStepTooLarge`], with the longest of dt/2, dt/4, … that does); else the constraints'
    /// own error.
    fn diagnose(&mut self, t: f64, states: &[State<A>], dt: f64, error: ConstraintError) -> StepError {
        let start_slopes: Vec<A::Screw> = (states.iter().enumerate())
            .map(|(index, state)| state.body_velocity(self.dynamics.body(index)) * (-0.5 * dt))
            .collect();
        if let Err(too_large) = check_turn::<A>(&start_slopes, t, dt) {
            return too_large;
        }
        // Off the constraints already, a shorter step only postpones the failure.
        if self.dynamics.drift(t, states) > MAX_DRIFT_FOR_STEP_DIAGNOSIS {
            return StepError::Constraint { t, error };
        }
        let mut shorter = dt;
        for _ in 0..MAX_STEP_HALVINGS {
            shorter *= 0.5;
            if self.attempt(t, states, shorter).is_ok() {
                return StepError::ConstraintStepTooLarge {
                    t,
                    dt,
                    error,
                    works: shorter,
                };
            }
        }
        StepError::Constraint { t, error }
    }

    /// One step from `(t, states)` to `t + dt` into `self.buffers.next`, with its checks; `states` are the
    /// validated start.
    fn attempt(&mut self, t: f64, states: &[State<A>], dt: f64) -> Result<(), StepError> {
        self.evaluations += Self::evaluations_per_step(self.integrator);
        self.extended = false;
        let expected = self.dynamics.body_count();
        let dynamics = self.dynamics;
        let workspace = &mut self.workspace;
        let buffers = &mut self.buffers;
        let mut next = std::mem::take(&mut buffers.next);
        next.copy_from_slice(states);
        let result = match (self.integrator, &self.splitting) {
            (Integrator::General(Method::Rk4), _) => rk4(dynamics, t, &mut next, dt, buffers, workspace),
            (Integrator::General(Method::Rkmk4), _) => rkmk4(dynamics, t, &mut next, dt, buffers, workspace),
            (Integrator::General(Method::Rkmk4Body), _) => {
                rkmk4_body_momentum(dynamics, t, &mut next, dt, buffers, workspace)
            }
            (Integrator::General(Method::Rkmk6Body), _) => {
                rkmk_body_momentum(&BUTCHER_6, dynamics, t, &mut next, dt, buffers, workspace)
            }
            (Integrator::General(Method::Rkmk8Body), _) => {
                rkmk_body_momentum(&COOPER_VERNER_8, dynamics, t, &mut next, dt, buffers, workspace)
            }
            (Integrator::General(Method::Dopri5Body), _) => {
                rkmk_body_momentum(&DORMAND_PRINCE_5, dynamics, t, &mut next, dt, buffers, workspace)
            }
            (Integrator::General(Method::Dop853Body), _) => {
                rkmk_body_momentum(&DOP853, dynamics, t, &mut next, dt, buffers, workspace)
            }
            (Integrator::Splitting(method), Some(splitting)) => {
                buffers.slopes[0] = next[0].body_velocity(dynamics.body(0)) * (-0.5 * dt);
                next[0] = step_splitting(method, splitting, t, &next[0], dt);
                Ok(())
            }
            (Integrator::Splitting(_), None) => {
                buffers.next = next;
                return Err(SplittingError::NotAFreeBody.into());
            }
            (Integrator::Joint(method), _) => {
                // The turn check reads the start's body velocities, as every method's first stage stores them.
                for (index, (slope, state)) in buffers.slopes.iter_mut().zip(next.iter()).enumerate() {
                    *slope = state.body_velocity(dynamics.body(index)) * (-0.5 * dt);
                }
                let joints = self.joints.as_mut().expect("made with the stepper");
                let powers = &mut buffers.powers;
                match method {
                    JointMethod::Rkmk4 => {
                        let tableau = (&RK4.a, &RK4.b, &RK4.c, RK4.order);
                        joint_coordinates::step(tableau, dynamics, t, &mut next, dt, joints, powers, workspace)
                    }
                    JointMethod::Rkmk6 => {
                        let tableau = (&BUTCHER_6.a, &BUTCHER_6.b, &BUTCHER_6.c, BUTCHER_6.order);
                        joint_coordinates::step(tableau, dynamics, t, &mut next, dt, joints, powers, workspace)
                    }
                    JointMethod::Rkmk8 => {
                        let tableau = (
                            &COOPER_VERNER_8.a,
                            &COOPER_VERNER_8.b,
                            &COOPER_VERNER_8.c,
                            COOPER_VERNER_8.order,
                        );
                        joint_coordinates::step(tableau, dynamics, t, &mut next, dt, joints, powers, workspace)
                    }
                    JointMethod::Dop853 => {
                        let tableau = (&DOP853.a, &DOP853.b, &DOP853.c, DOP853.order);
                        joint_coordinates::step(tableau, dynamics, t, &mut next, dt, joints, powers, workspace)
                    }
                }
            }
        }
        // Stepping in joint coordinates ends on the joints (forward kinematics): no projection but the held
        // contacts'.
        .and_then(|()| match self.integrator {
            Integrator::Joint(_) => dynamics.after_joint_step(t + dt, &mut next, workspace),
            _ => dynamics.after_step(t + dt, &mut next, workspace),
        });
        let result = result
            .map_err(|error| StepError::Constraint { t, error })
            .and_then(|()| check_turn::<A>(&buffers.slopes[..expected], t, dt))
            .and_then(|()| match next.iter().position(|state| !state.is_representable()) {
                Some(body) => Err(StepError::NonFinite { t: t + dt, body }),
                None => Ok(()),
            });
        buffers.next = next;
        result
    }
}

/// The work over a step of length `dt` (or a part of it) from the stages' powers and the method's weights for its end:
/// the power integrated by the same method, exactly as an extra state `ẇ = P` would be.
fn work_over(dt: f64, weights: &[f64], powers: &[f64]) -> f64 {
    dt * weights.iter().zip(powers).map(|(w, p)| w * p).sum::<f64>()
}

/// The largest drift off the constraints ([`Dynamics::drift`], m or rad) at which [`Stepper::step`] still blames a
/// failed step on its size: projected runs stay within 1e-14 of their constraints, and a state a micrometre off
/// them fails for its drift, which a shorter step does not remove.
const MAX_DRIFT_FOR_STEP_DIAGNOSIS: f64 = 1e-6;

/// How many times [`Stepper::step`] halves a step that failed in the constraints to tell whether the step's size
/// is the cause (2⁻²⁰ ≈ 1e-6 of the step).
const MAX_STEP_HALVINGS: usize = 20;
