//! Integrators for the state of N rigid bodies, one `[R, Ω]` per body (`docs/theory.md` §5, §10), one step of
//! a length the caller chooses.
//!
//! Two families:
//! * [`Method`]: general methods, valid for any [`Dynamics`] (free bodies, constrained bodies, mechanisms):
//!   the paper's RK4 on `(R, Ω)` as vectors plus renormalisation, and Runge–Kutta–Munthe-Kaas (RKMK) methods
//!   that move each R only by motor products with exponentials of screws, with the momentum in the world
//!   frame (RKMK4) or in the body frame (RKMK4-body, RKMK6-body). Every body takes the same stages, so a
//!   mechanism advances on the product of its bodies' motor groups and each motor stays an exact motor.
//! * [`SplittingMethod`]: Hamiltonian splittings of a free body ([`KineticSplitting`], built from a
//!   [`FreeBody`] whose forces allow it). Every sub-step is the exact flow of one piece of the Hamiltonian,
//!   so for a free or gravitating body the energy error stays bounded over long times instead of drifting.
//!
//! [`Integrator`] names any of them; a [`Stepper`] takes steps of one integrator on one system, with its
//! buffers made once (a step allocates nothing).
//!
//! A step's length is the caller's: [`crate::simulate()`] takes it from a fixed schedule, or from the step-size
//! controller of an adaptive one ([`crate::step_control`]), which reads the error estimate of an embedded pair
//! ([`Method::Dopri5Body`], [`Method::Dop853Body`]) and takes samples and events from its continuous extension.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::constraints::ConstraintError;
use crate::exponential::exp;
use crate::forces::Force;
use crate::joint_integration::{self, JointBuffers, JointMethod};
use crate::motion::{to_body, to_world, BodyRates, Dynamics, FreeBody, Rates};
use crate::motor;
use crate::state::{State, MAX_COORDINATE, MAX_DISTANCE_IN_GYRATION_RADII};
use crate::step_control::{self, Tolerance};

/// A general integration method: valid for any [`Dynamics`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Classic RK4 on (R, Ω) treated as vectors, then renormalisation of R (the paper's method, theory §10).
    Rk4,
    /// Runge–Kutta–Munthe-Kaas of order 4: R is advanced as `R₀ exp(σ)` with σ from the RK4 tableau,
    /// corrected by the commutators that truncate `dexp⁻¹` at order 4. R stays an exact motor; the world
    /// momentum Ω (a vector) follows classic RK4, so a free body keeps Ω exactly.
    Rkmk4,
    /// RKMK4 with the momentum carried in the body frame during the step, `Ω_b = ~RΩR` with
    /// `dΩ_b/dt = Ḃ × Ω_b + ~R W R` (theory §5). For a free body the body momentum then obeys Euler's equations
    /// on their own, and the error of R no longer feeds back into `Ḃ = M⁻¹[Ω_b]`; with world Ω (the other two
    /// methods) `Ḃ = M⁻¹[~RΩR]` inherits R's error, which the Dzhanibekov flips amplify: on scene 1 at
    /// dt = 1e-3 this method's orientation error is about 100× smaller than RK4's or RKMK4's (see
    /// `scenarios/examples/free_body_accuracy.rs`). A system without forces and joints keeps each body's world
    /// momentum exactly: the step ends with a projection onto it (see `end_of_body_step`).
    /// A force-free body skips the stages' motors ([`Dynamics::rates_depend_on_motors`]).
    Rkmk4Body,
    /// The body-momentum scheme of [`Method::Rkmk4Body`] on Butcher's 7-stage explicit Runge–Kutta method of
    /// order 6 (J. C. Butcher, 1964), with `dexp⁻¹` truncated after its `ad⁴` term: 7 evaluations per step
    /// instead of 4, for an error that falls as dt⁶. At the accuracy of RK4 at dt = 1e-3 it takes steps
    /// 5–10× longer (measured on the reference scenes, see docs/dynamics.md).
    Rkmk6Body,
    /// The same scheme on Cooper and Verner's 11-stage explicit method of order 8 (1972), with `dexp⁻¹` truncated
    /// after its `ad⁶` term: 11 evaluations per step for an error that falls as dt⁸, so at tight tolerances
    /// (MuJoCo's accuracy on the double pendulum, 2.2e-10 rad) it takes steps about three times as long as
    /// RKMK6-body's and needs fewer evaluations per simulated second.
    Rkmk8Body,
    /// The same scheme on Dormand and Prince's 7-stage pair of orders 5 and 4 (J. R. Dormand and P. J. Prince,
    /// "A family of embedded Runge–Kutta formulae", J. Comp. Appl. Math. 6(1), 1980), with `dexp⁻¹` truncated after
    /// its `ad⁴` term. The 5th-order solution is kept; the difference from the embedded 4th-order one, taken in the
    /// Lie algebra, estimates the step's error, which an adaptive [`crate::Schedule`] turns into step sizes
    /// ([`crate::step_control`]). Its continuous extension of order 4 (Shampine's, in Hairer, Nørsett & Wanner,
    /// *Solving ODEs I*, §II.6) gives the state anywhere inside a step without another evaluation, so samples and
    /// events never shorten a step.
    Dopri5Body,
    /// The same scheme on Dormand and Prince's 12-stage pair of order 8 with embedded solutions of orders 5 and 3
    /// (DOP853: P. J. Prince and J. R. Dormand, J. Comp. Appl. Math. 7(1), 1981, as published with Hairer's code),
    /// with `dexp⁻¹` truncated after its `ad⁶` term: the 8th-order solution is kept, and Hairer's combination of
    /// the two embedded differences, `e₅²/√(e₅² + 0.01 e₃²)`, estimates the error with a step-size law of order 8.
    /// Its continuous extension of order 7 costs four more evaluations, made only in steps that hold a sample or
    /// an event. For tight tolerances: 12 evaluations per step for an error that falls as dt⁸.
    Dop853Body,
}

impl Method {
    /// Every general method, in the order of the enum.
    pub const ALL: [Method; 7] = [
        Method::Rk4,
        Method::Rkmk4,
        Method::Rkmk4Body,
        Method::Rkmk6Body,
        Method::Rkmk8Body,
        Method::Dopri5Body,
        Method::Dop853Body,
    ];

    /// The method's name in reports and tables ("RK4", "RKMK4", "RKMK4-body", "RKMK6-body", "RKMK8-body",
    /// "DP5(4)-body", "DOP853-body").
    pub fn name(self) -> &'static str {
        match self {
            Method::Rk4 => "RK4",
            Method::Rkmk4 => "RKMK4",
            Method::Rkmk4Body => "RKMK4-body",
            Method::Rkmk6Body => "RKMK6-body",
            Method::Rkmk8Body => "RKMK8-body",
            Method::Dopri5Body => "DP5(4)-body",
            Method::Dop853Body => "DOP853-body",
        }
    }

    /// The order of the global error.
    pub fn order(self) -> u32 {
        match self {
            Method::Rk4 | Method::Rkmk4 | Method::Rkmk4Body => 4,
            Method::Dopri5Body => 5,
            Method::Rkmk6Body => 6,
            Method::Rkmk8Body | Method::Dop853Body => 8,
        }
    }

    /// For an embedded pair, the order `k` of its error estimate's step-size law (the estimate of a step of
    /// length h falls as h^k, so the controller scales steps by `(1/err)^(1/k)`); `None` for a method without an
    /// estimate, which an adaptive schedule refuses.
    pub fn estimate_order(self) -> Option<u32> {
        match self {
            Method::Dopri5Body => Some(5),
            Method::Dop853Body => Some(8),
            Method::Rk4 | Method::Rkmk4 | Method::Rkmk4Body | Method::Rkmk6Body | Method::Rkmk8Body => None,
        }
    }
}

/// A splitting method for a free body ([`KineticSplitting`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SplittingMethod {
    /// Strang (symmetric, 2nd order): kick ½h, drift h, kick ½h, where the drift is the symmetric
    /// composition of the exact rotations about the body axes and the exact translation.
    Strang,
    /// Yoshida's 4th-order triple jump: three Strang steps of `w₁h, w₀h, w₁h`.
    Yoshida4,
}

impl SplittingMethod {
    /// Every splitting method, in the order of the enum.
    pub const ALL: [SplittingMethod; 2] = [SplittingMethod::Strang, SplittingMethod::Yoshida4];

    /// The method's name in reports and tables ("Strang", "Yoshida4").
    pub fn name(self) -> &'static str {
        match self {
            SplittingMethod::Strang => "Strang",
            SplittingMethod::Yoshida4 => "Yoshida4",
        }
    }

    /// The order of the global error.
    pub fn order(self) -> u32 {
        match self {
            SplittingMethod::Strang => 2,
            SplittingMethod::Yoshida4 => 4,
        }
    }
}

/// Any integrator: a general [`Method`], a [`SplittingMethod`] (free bodies only) or a [`JointMethod`]
/// (mechanisms of joint models in a tree).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Integrator {
    /// A general method, for any system.
    General(Method),
    /// A splitting method, for a single free body whose forces depend on the configuration only.
    Splitting(SplittingMethod),
    /// A method that steps in joint coordinates, for a mechanism whose joints are joint models in a tree
    /// (`crate::joint_integration`).
    Joint(JointMethod),
}

impl Integrator {
    /// Every integrator: the general methods, then the splittings.
    pub const ALL: [Integrator; 9] = [
        Integrator::General(Method::Rk4),
        Integrator::General(Method::Rkmk4),
        Integrator::General(Method::Rkmk4Body),
        Integrator::General(Method::Rkmk6Body),
        Integrator::General(Method::Rkmk8Body),
        Integrator::General(Method::Dopri5Body),
        Integrator::General(Method::Dop853Body),
        Integrator::Splitting(SplittingMethod::Strang),
        Integrator::Splitting(SplittingMethod::Yoshida4),
    ];

    /// The name of the method.
    pub fn name(self) -> &'static str {
        match self {
            Integrator::General(method) => method.name(),
            Integrator::Splitting(method) => method.name(),
            Integrator::Joint(method) => method.name(),
        }
    }

    /// The order of the global error.
    pub fn order(self) -> u32 {
        match self {
            Integrator::General(method) => method.order(),
            Integrator::Splitting(method) => method.order(),
            Integrator::Joint(method) => method.order(),
        }
    }

    /// The order of the error estimate of an embedded pair ([`Method::estimate_order`]); `None` for the others.
    pub fn estimate_order(self) -> Option<u32> {
        match self {
            Integrator::General(method) => method.estimate_order(),
            Integrator::Splitting(_) | Integrator::Joint(_) => None,
        }
    }
}

impl From<Method> for Integrator {
    fn from(method: Method) -> Self {
        Integrator::General(method)
    }
}

impl From<SplittingMethod> for Integrator {
    fn from(method: SplittingMethod) -> Self {
        Integrator::Splitting(method)
    }
}

impl From<JointMethod> for Integrator {
    fn from(method: JointMethod) -> Self {
        Integrator::Joint(method)
    }
}

/// Why a system cannot be integrated by splitting.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SplittingError {
    /// A kick `Ω ← Ω + h W` is the exact flow of `dΩ/dt = W` only if W does not depend on Ω (nor on
    /// time within the step); a custom force may depend on both.
    #[error("force {index} is a custom force, which may depend on the momentum; splitting needs forces of the configuration only")]
    CustomForce {
        /// The index of the custom force in the body's list of forces.
        index: usize,
    },
    /// The splittings are written for one free body (its kinetic energy splits into exact rotations).
    #[error("splitting methods integrate a single free body, not a constrained body or a mechanism")]
    NotAFreeBody,
}

/// The largest angle (rad) a body may turn through in one step, judged from its angular velocity at the start
/// of the step ([`StepError::StepTooLarge`]). The reference scenes turn at most 0.2 rad per step at their
/// largest step (the heavy top, 20 rad/s at dt = 1e-2).
pub const MAX_TURN_PER_STEP: f64 = 1.0;

/// Why a step failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StepError {
    /// The state does not have one entry per body of the system.
    #[error("the state has {got} bodies, the system has {expected}")]
    BodyCount {
        /// The number of bodies of the system.
        expected: usize,
        /// The number of states given.
        got: usize,
    },
    /// A splitting method was asked of a system it cannot integrate (when the stepper is made).
    #[error(transparent)]
    Splitting(#[from] SplittingError),
    /// A method stepping in joint coordinates was asked of a system without them (when the stepper is made).
    #[error(
        "{method} steps in joint coordinates: it needs a mechanism whose joints are all joint models (Mechanism::connect) in a tree, without Baumgarte stabilisation"
    )]
    NoJointCoordinates {
        /// The method's name.
        method: &'static str,
    },
    /// An evaluation of the equations of motion (or the projection after the step) failed; the error names the
    /// joints or constraints involved.
    #[error("at t = {t}: {error}")]
    Constraint {
        /// The time the failing step started at (s).
        t: f64,
        /// What went wrong.
        error: ConstraintError,
    },
    /// The step size is zero, negative, NaN or infinite.
    #[error("the step must be positive and finite, got dt = {dt}")]
    InvalidStep {
        /// The step that was refused (s).
        dt: f64,
    },
    /// The time the step starts at is NaN or infinite.
    #[error("the time must be finite, got t = {t}")]
    InvalidTime {
        /// The start time that was refused.
        t: f64,
    },
    /// A body is farther from the world origin than [`MAX_DISTANCE_IN_GYRATION_RADII`] of its radii of gyration,
    /// where its momentum about the origin no longer carries its spin to 1e-9 of its points' velocities.
    #[error(
        "at t = {t}: body {body} is {distance:.3e} m from the world origin, farther than {limit:.3e} m (4.5e6 of its \
         radii of gyration), where its momentum about the origin no longer carries its spin to 1e-9 of its \
         points' velocities; put the scene's origin near the bodies"
    )]
    TooFarFromOrigin {
        /// The time the step was to start at (s).
        t: f64,
        /// The index of the first body that is too far.
        body: usize,
        /// Its distance from the origin (m).
        distance: f64,
        /// The farthest it may be (m).
        limit: f64,
    },
    /// A state given to the step has a motor that is not a rigid motion: its rotor part's squared norm is off 1 by
    /// more than [`MAX_ROTOR_NORM_ERROR`] (a zero motor, or one written field by field without normalising).
    #[error(
        "the state given at t = {t} has a motor that is not a rigid motion (body {body}): its rotor part's squared \
         norm is {norm_squared:e}, not 1"
    )]
    NotARigidMotion {
        /// The time the step was to start at (s).
        t: f64,
        /// The index of the first body whose motor is not rigid.
        body: usize,
        /// Its rotor part's squared norm ([`State::rotor_norm_squared`]).
        norm_squared: f64,
    },
    /// A state given to the step has a NaN or infinite coordinate, or one beyond [`MAX_COORDINATE`].
    #[error("the state given at t = {t} is not finite or has a coordinate beyond {MAX_COORDINATE:e} (body {body})")]
    NonFiniteInput {
        /// The time the step was to start at (s).
        t: f64,
        /// The index of the first body whose state is not representable.
        body: usize,
    },
    /// At the start of the step, a body turns by more than [`MAX_TURN_PER_STEP`] within it: no method here
    /// resolves that (RK4's local error is already ~1% of the motion at one radian per step, and beyond its
    /// stability bound of 2.8 the result is noise, finite or not). The states are left as they were.
    #[error(
        "at t = {t}: body {body} turns {turn:.3} rad in the step dt = {dt} (angular velocity {angular_speed:.4e} \
         rad/s), more than {MAX_TURN_PER_STEP} rad per step; take a step below {limit:.3e}",
        limit = MAX_TURN_PER_STEP / angular_speed
    )]
    StepTooLarge {
        /// The time the refused step started at (s).
        t: f64,
        /// The refused step (s).
        dt: f64,
        /// The index of the first body that turns too far.
        body: usize,
        /// The angle it would turn through, `|ω| dt` (rad).
        turn: f64,
        /// Its angular speed `|ω|` at the start of the step (rad/s).
        angular_speed: f64,
    },
    /// A step failed in the constraints (they could not be solved or held together at a stage, or after the
    /// step) where a shorter step from the same state succeeds: the step is too large for the motion of the
    /// joints, or for stiff Baumgarte gains. The states are left as they were.
    #[error(
        "at t = {t}: the step dt = {dt} is too large for the constraints ({error}); a step of {works:.3e} succeeds"
    )]
    ConstraintStepTooLarge {
        /// The time the refused step started at (s).
        t: f64,
        /// The refused step (s).
        dt: f64,
        /// What went wrong in the constraints at the refused step.
        error: ConstraintError,
        /// The longest of dt/2, dt/4, … that succeeds from the same state (s).
        works: f64,
    },
    /// The step is too long for the Baumgarte feedback: its residuals decay at up to `rate` 1/s, which an explicit
    /// step longer than [`MAX_FEEDBACK_STEP`]`/rate` amplifies instead of damping (when the step is made).
    #[error(
        "at t = {t}: the step dt = {dt} is too large for the Baumgarte feedback, whose residuals decay at up to \
         {rate:.4e} 1/s; take a step below {limit:.3e} or lower the gains",
        limit = MAX_FEEDBACK_STEP / rate
    )]
    FeedbackStepTooLarge {
        /// The time the refused step started at (s).
        t: f64,
        /// The refused step (s).
        dt: f64,
        /// The feedback's fastest rate (1/s).
        rate: f64,
    },
    /// The step produced a NaN or infinite state: the step is too large for the motion, or a force or path
    /// returned NaN. The states are left as they were before the step.
    #[error(
        "the state is no longer finite (or beyond {MAX_COORDINATE:e}) at t = {t} (body {body}): the step is too large \
         for this system, or a force is not finite"
    )]
    NonFinite {
        /// The time the step was to reach (s).
        t: f64,
        /// The index of the first body whose state is not representable.
        body: usize,
    },
}

/// Steps of one integrator on one system. It owns the buffers of the stages and the system's workspace, so a
/// step allocates nothing; make one per run (or per thread).
pub struct Stepper<'a, A: Algebra, D: Dynamics<A> + ?Sized> {
    dynamics: &'a D,
    integrator: Integrator,
    splitting: Option<KineticSplitting<'a, A>>,
    workspace: D::Workspace,
    buffers: Buffers<A>,
    /// The buffers of a method stepping in joint coordinates.
    joints: Option<JointBuffers<A>>,
    /// The work done by the non-conservative forces over the last successful step (J).
    last_work: f64,
    /// The start and the length of the last successful step (s), if its stages are still in the buffers (for the
    /// error estimate and the dense output).
    last_step: Option<(f64, f64)>,
    /// Whether the last successful step's extra stages for the continuous extension have been evaluated
    /// ([`Method::Dop853Body`] makes them only in steps that need them).
    extended: bool,
    /// Evaluations of the equations of motion so far.
    evaluations: usize,
}

/// The per-body buffers of a step, sized once for the system.
struct Buffers<A: Algebra> {
    /// The state being advanced (copied back into the caller's slice only if the step succeeds).
    next: Vec<State<A>>,
    /// A stage's states (world-momentum methods).
    stage: Vec<State<A>>,
    rates: Vec<Rates<A>>,
    body_rates: Vec<BodyRates<A>>,
    /// A stage's motors and body momenta (body-momentum methods).
    motors: Vec<A::Motor>,
    momenta: Vec<A::Screw>,
    /// The body momenta and the motors at the start of the step (the dense output starts from them).
    start_momenta: Vec<A::Screw>,
    start_motors: Vec<A::Motor>,
    /// A stage's Lie-algebra offsets σ (the stage motors are `R₀ exp(σ)`).
    sigmas: Vec<A::Screw>,
    /// Per stage and body, stage-major: `(dR/dt, dΩ/dt)` (RK4), or the Lie-algebra slopes σ-increments and
    /// momentum slopes (RKMK).
    derivatives: Vec<Derivative<A>>,
    slopes: Vec<A::Screw>,
    momentum_slopes: Vec<A::Screw>,
    /// Per stage: the system's non-conservative power ([`Dynamics::power`]), which the method's weights integrate
    /// into the step's work, exactly as an extra state `ẇ = P` integrated by the same method.
    powers: Vec<f64>,
}

impl<A: Algebra> Buffers<A> {
    fn new(bodies: usize) -> Self {
        let zero_screw = A::screw(ScrewCoordinates::default());
        let zero_motor = A::motor(Default::default());
        let state = State {
            motor: zero_motor,
            momentum: zero_screw,
        };
        let stages = DOP853_EXTENDED_STAGES;
        Buffers {
            next: vec![state; bodies],
            stage: vec![state; bodies],
            rates: vec![
                Rates {
                    body_velocity: zero_screw,
                    momentum_rate: zero_screw,
                };
                bodies
            ],
            body_rates: vec![
                BodyRates {
                    body_velocity: zero_screw,
                    body_wrench: zero_screw,
                };
                bodies
            ],
            motors: vec![zero_motor; bodies],
            momenta: vec![zero_screw; bodies],
            start_momenta: vec![zero_screw; bodies],
            start_motors: vec![zero_motor; bodies],
            sigmas: vec![zero_screw; bodies],
            derivatives: vec![
                Derivative {
                    motor: zero_motor,
                    momentum: zero_screw,
                };
                4 * bodies
            ],
            slopes: vec![zero_screw; stages * bodies],
            momentum_slopes: vec![zero_screw; stages * bodies],
            powers: vec![0.0; stages],
        }
    }
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
                Some(JointBuffers::new(layout, COOPER_VERNER_8.b.len()))
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

    /// The error norm ([`crate::step_control`]) of the last successful step from `start` to `end`, for a method with
    /// an error estimate ([`Integrator::estimate_order`]); `None` for the others, or before a step. An embedded
    /// difference is the pair's two solutions apart in the Lie algebra, per body: the motor's `Σ eᵢKᵢ` and the body
    /// momentum's `h Σ eᵢ dΩ_b/dt` (`eᵢ` the difference of the two weights).
    pub(crate) fn error_norm(&self, tolerance: &Tolerance, start: &[State<A>], end: &[State<A>]) -> Option<f64> {
        let (_, dt) = self.last_step?;
        let zero = A::screw(ScrewCoordinates::default());
        let difference = |weights: &[f64]| {
            let estimates = (0..start.len()).map(|b| weighted_slopes(&self.buffers, weights, b, (dt, zero)));
            step_control::error_norm(tolerance, self.dynamics, (start, end), estimates)
        };
        match self.integrator {
            Integrator::General(Method::Dopri5Body) => Some(difference(&DORMAND_PRINCE_5_ERROR)),
            Integrator::General(Method::Dop853Body) => {
                // Hairer's combination: the 5th-order difference, damped where the 3rd-order one says the
                // asymptotic regime is not reached; it falls as h⁸. A NaN stays a NaN (the step is refused).
                let (fifth, third) = (difference(&DOP853_ERROR_5), difference(&DOP853_ERROR_3));
                let scale = (fifth * fifth + 0.01 * third * third).sqrt();
                Some(if scale == 0.0 { 0.0 } else { fifth * fifth / scale })
            }
            _ => None,
        }
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
            _ => return Ok(None),
        };
        let buffers = &self.buffers;
        for (b, state) in out.iter_mut().enumerate() {
            let (sigma, momentum) = weighted_slopes(buffers, weights, b, (dt, buffers.start_momenta[b]));
            let motor = A::compose(buffers.start_motors[b], exp::<A>(sigma));
            *state = State {
                motor,
                momentum: to_world::<A>(motor, momentum),
            };
        }
        Ok(Some(
            dt * weights.iter().zip(&buffers.powers).map(|(w, p)| w * p).sum::<f64>(),
        ))
    }

    /// The four stages DOP853's continuous extension adds to the last step from `t` of length `dt`, once per step.
    fn extend_dop853(&mut self, t: f64, dt: f64) -> Result<(), StepError> {
        if self.extended {
            return Ok(());
        }
        self.evaluations += DOP853_EXTENSION.len();
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
            Integrator::General(Method::Dop853Body) => &DOP853.b,
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
        let result = match self.attempt(t, states, dt) {
            Err(StepError::Constraint { error, .. }) => Err(self.diagnose(t, states, dt, error)),
            result => result,
        };
        self.last_step = result.is_ok().then_some((t, dt));
        if result.is_ok() {
            states.copy_from_slice(&self.buffers.next);
            let weights = Self::stage_weights(self.integrator);
            self.last_work = dt
                * weights
                    .iter()
                    .zip(&self.buffers.powers)
                    .map(|(w, p)| w * p)
                    .sum::<f64>();
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
                        joint_integration::step(tableau, dynamics, t, &mut next, dt, joints, powers, workspace)
                    }
                    JointMethod::Rkmk6 => {
                        let tableau = (&BUTCHER_6.a, &BUTCHER_6.b, &BUTCHER_6.c, BUTCHER_6.order);
                        joint_integration::step(tableau, dynamics, t, &mut next, dt, joints, powers, workspace)
                    }
                    JointMethod::Rkmk8 => {
                        let tableau = (
                            &COOPER_VERNER_8.a,
                            &COOPER_VERNER_8.b,
                            &COOPER_VERNER_8.c,
                            COOPER_VERNER_8.order,
                        );
                        joint_integration::step(tableau, dynamics, t, &mut next, dt, joints, powers, workspace)
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

/// How far from 1 a start motor's rotor norm squared may be ([`StepError::NotARigidMotion`]): every step
/// renormalises to round-off, so a larger error is a motor the user wrote, not drift.
pub const MAX_ROTOR_NORM_ERROR: f64 = 1e-6;

/// The largest step, in units of the inverse feedback rate ([`Dynamics::feedback_rate`]), at which the explicit
/// methods still damp the Baumgarte feedback: RK4's stability region reaches 2.79 on the negative real axis and
/// 2.83 on the imaginary one, the higher-order tableaux a little further.
pub const MAX_FEEDBACK_STEP: f64 = 2.5;

/// The largest drift off the constraints ([`Dynamics::drift`], m or rad) at which [`Stepper::step`] still blames a
/// failed step on its size: projected runs stay within 1e-14 of their constraints, and a state a micrometre off
/// them fails for its drift, which a shorter step does not remove.
const MAX_DRIFT_FOR_STEP_DIAGNOSIS: f64 = 1e-6;

/// How many times [`Stepper::step`] halves a step that failed in the constraints to tell whether the step's size
/// is the cause (2⁻²⁰ ≈ 1e-6 of the step).
const MAX_STEP_HALVINGS: usize = 20;

/// The weights of the classic fourth-order stages (RK4 and the RKMK4 methods).
const RK4_WEIGHTS: [f64; 4] = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];

/// Refuses a step in which a body turns by more than [`MAX_TURN_PER_STEP`]: `start_slopes` are the first
/// stage's `−½ dt Ḃ` of every body (every method stores them), whose angular part has length `½ |ω| dt`.
fn check_turn<A: Algebra>(start_slopes: &[A::Screw], t: f64, dt: f64) -> Result<(), StepError> {
    for (body, slope) in start_slopes.iter().enumerate() {
        let turn = 2.0 * A::screw_coordinates(*slope).l.norm();
        // Written so that a NaN turn passes to the finiteness check, which names it.
        if turn > MAX_TURN_PER_STEP {
            return Err(StepError::StepTooLarge {
                t,
                dt,
                body,
                turn,
                angular_speed: turn / dt,
            });
        }
    }
    Ok(())
}

/// The time derivative `(dR/dt, dΩ/dt)` of `(R, Ω)` of one body at one state.
#[derive(Clone, Copy)]
struct Derivative<A: Algebra> {
    motor: A::Motor,
    momentum: A::Screw,
}

/// `(dR/dt, dΩ/dt)` of every body at `states`, into `out`.
fn derivatives<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    t: f64,
    states: &[State<A>],
    rates: &mut [Rates<A>],
    out: &mut [Derivative<A>],
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    dynamics.rates(t, states, rates, workspace)?;
    for ((slope, rate), state) in out.iter_mut().zip(rates.iter()).zip(states) {
        *slope = Derivative {
            motor: rate.motor_rate(state.motor),
            momentum: rate.momentum_rate,
        };
    }
    Ok(())
}

/// `stage = y + h·k` for every body.
fn advance<A: Algebra>(stage: &mut [State<A>], y: &[State<A>], slopes: &[Derivative<A>], h: f64) {
    for ((stage, state), slope) in stage.iter_mut().zip(y).zip(slopes) {
        *stage = State {
            motor: state.motor + slope.motor * h,
            momentum: state.momentum + slope.momentum * h,
        };
    }
}

/// Classic RK4 on every body's (R, Ω) as vectors.
fn rk4<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    t: f64,
    y: &mut [State<A>],
    dt: f64,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = y.len();
    let half = 0.5 * dt;
    let Buffers {
        stage,
        rates,
        derivatives: k,
        ..
    } = buffers;
    let (k1, rest) = k.split_at_mut(n);
    let (k2, rest) = rest.split_at_mut(n);
    let (k3, k4) = rest.split_at_mut(n);
    let powers = &mut buffers.powers;
    derivatives(dynamics, t, y, rates, k1, workspace)?;
    powers[0] = dynamics.power(workspace);
    for (slope, rate) in buffers.slopes.iter_mut().zip(rates.iter()) {
        *slope = rate.body_velocity * (-0.5 * dt);
    }
    advance(stage, y, k1, half);
    derivatives(dynamics, t + half, stage, rates, k2, workspace)?;
    powers[1] = dynamics.power(workspace);
    advance(stage, y, k2, half);
    derivatives(dynamics, t + half, stage, rates, k3, workspace)?;
    powers[2] = dynamics.power(workspace);
    advance(stage, y, k3, dt);
    derivatives(dynamics, t + dt, stage, rates, k4, workspace)?;
    powers[3] = dynamics.power(workspace);
    let sixth = dt / 6.0;
    for (i, state) in y.iter_mut().enumerate() {
        *state = State {
            motor: state.motor + (k1[i].motor + k2[i].motor * 2.0 + k3[i].motor * 2.0 + k4[i].motor) * sixth,
            momentum: state.momentum
                + (k1[i].momentum + k2[i].momentum * 2.0 + k3[i].momentum * 2.0 + k4[i].momentum) * sixth,
        };
    }
    Ok(())
}

/// The Lie bracket `[X, Y] = XY − YX`, twice the commutator product of theory §1.1.
#[inline]
fn bracket<A: Algebra>(x: A::Screw, y: A::Screw) -> A::Screw {
    A::commutator(x, y) * 2.0
}

/// RKMK4 for `dR/dt = R ξ` with `ξ = −½Ḃ` (theory §3) and `dΩ/dt = W`, body by body.
///
/// With `R = R₀ exp(σ)`, σ obeys `dσ/dt = dexp⁻¹_{−σ}(ξ) = ξ + ½[σ, ξ] + …` (`[X, Y] = XY − YX`, twice the
/// commutator product of theory §1.1). Classic RK4 on σ, with `dexp⁻¹` truncated to the terms that matter at
/// order 4, leaves two commutators (Munthe-Kaas' RKMK4, here for the right action `R ξ`, which flips the sign
/// of the odd terms relative to the usual left-action form):
///
/// ```text
/// kᵢ = h ξ(Rᵢ, Ωᵢ)      R₂ = R₀ exp(½k₁)   R₃ = R₀ exp(½k₂ + ⅛[k₁, k₂])   R₄ = R₀ exp(k₃)
/// R₁ = R₀ exp(⅙(k₁ + 2k₂ + 2k₃ + k₄) + ¹⁄₁₂[k₁, k₄])
/// ```
///
/// Ω lives in a vector space, where the commutators vanish and the stages are classic RK4's.
fn rkmk4<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    t: f64,
    y: &mut [State<A>],
    dt: f64,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = y.len();
    let half = 0.5 * dt;
    // Stage s: rates at `stage`, then kₛ = −½hḂ and the momentum rate, stored at [s n + i].
    let evaluate = |s: usize, at: f64, buffers: &mut Buffers<A>, workspace: &mut D::Workspace, first: bool| {
        let Buffers {
            stage,
            rates,
            slopes,
            momentum_slopes,
            powers,
            ..
        } = buffers;
        dynamics.rates(at, if first { &*y } else { &*stage }, rates, workspace)?;
        powers[s] = dynamics.power(workspace);
        for (i, rate) in rates.iter().enumerate() {
            slopes[s * n + i] = rate.body_velocity * (-0.5 * dt);
            momentum_slopes[s * n + i] = rate.momentum_rate;
        }
        Ok::<(), ConstraintError>(())
    };
    // The stage `R₀ exp(σ)`, `Ω₀ + h dΩ` from the σ buffer and momentum slope s.
    let set_stage = |buffers: &mut Buffers<A>, s: usize, h: f64| {
        let slopes = &buffers.momentum_slopes[s * n..(s + 1) * n];
        for (((stage, start), &sigma), &slope) in
            buffers.stage.iter_mut().zip(y.iter()).zip(&buffers.sigmas).zip(slopes)
        {
            *stage = State {
                motor: A::compose(start.motor, exp::<A>(sigma)),
                momentum: start.momentum + slope * h,
            };
        }
    };
    evaluate(0, t, buffers, workspace, true)?;
    for i in 0..n {
        buffers.sigmas[i] = buffers.slopes[i] * 0.5;
    }
    set_stage(buffers, 0, half);
    evaluate(1, t + half, buffers, workspace, false)?;
    for i in 0..n {
        let (k1, k2) = (buffers.slopes[i], buffers.slopes[n + i]);
        buffers.sigmas[i] = k2 * 0.5 + bracket::<A>(k1, k2) * 0.125;
    }
    set_stage(buffers, 1, half);
    evaluate(2, t + half, buffers, workspace, false)?;
    for i in 0..n {
        buffers.sigmas[i] = buffers.slopes[2 * n + i];
    }
    set_stage(buffers, 2, dt);
    evaluate(3, t + dt, buffers, workspace, false)?;
    let (k, m) = (&buffers.slopes, &buffers.momentum_slopes);
    for (i, state) in y.iter_mut().enumerate() {
        let (k1, k2, k3, k4) = (k[i], k[n + i], k[2 * n + i], k[3 * n + i]);
        let sigma = (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (1.0 / 6.0) + bracket::<A>(k1, k4) * (1.0 / 12.0);
        let momentum_rate = m[i] + m[n + i] * 2.0 + m[2 * n + i] * 2.0 + m[3 * n + i];
        *state = State {
            motor: A::compose(state.motor, exp::<A>(sigma)),
            momentum: state.momentum + momentum_rate * (dt / 6.0),
        };
    }
    Ok(())
}

/// One stage of a body-momentum method: the body rates at the stage motors `R₀ exp(σᵢ)` (σ from
/// `buffers.sigmas`; the start motors for the first stage, and for systems whose rates do not depend on the
/// motors, which skips an exponential and a motor product per body) and the body momenta `buffers.momenta`;
/// stores `k = −½hḂ` and `dΩ_b/dt = Ḃ × Ω_b + W_b` (theory §5) of body i at `[s n + i]`.
fn body_stage<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    (s, at, dt): (usize, f64, f64),
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = buffers.motors.len();
    let skip_motors = s == 0 || !dynamics.rates_depend_on_motors();
    for ((motor, &start), &sigma) in buffers
        .motors
        .iter_mut()
        .zip(&buffers.start_motors)
        .zip(&buffers.sigmas)
    {
        *motor = if skip_motors {
            start
        } else {
            A::compose(start, exp::<A>(sigma))
        };
    }
    dynamics.body_rates(
        at,
        &buffers.motors,
        &buffers.momenta,
        &mut buffers.body_rates,
        workspace,
    )?;
    buffers.powers[s] = dynamics.power(workspace);
    for (i, (rates, &momentum)) in buffers.body_rates.iter().zip(&buffers.momenta).enumerate() {
        let velocity = rates.body_velocity;
        buffers.slopes[s * n + i] = velocity * (-0.5 * dt);
        buffers.momentum_slopes[s * n + i] = A::commutator(velocity, momentum) + rates.body_wrench;
    }
    Ok(())
}

/// [`Method::Rkmk4Body`]: the RKMK4 stages of [`rkmk4`] for every R, classic RK4 stages for the body momenta
/// `Ω_b`, with `dΩ_b/dt = Ḃ × Ω_b + W_b` (theory §5). The stages' R are exact motors, so any system can be
/// handed the world state `(R, RΩ_b~R)`.
///
/// The state carries the world momentum, so every step converts it to the body frame and back, through the
/// motor's map on screw coordinates ([`crate::motor::ScrewFrame`]). That map is the sandwich divided by
/// `⟨R~R⟩₀`, which [`crate::motor::normalise`] leaves about 1.3e-16 above 1 on average: an undivided sandwich
/// would grow the momentum by ~5e-16 per round trip, a systematic energy drift (5e-11 relative after 1e5
/// steps, measured on scene 1). In CGA the map also avoids the sandwiches' `½|x|²` round-off: at 100 m the
/// orientation error of this method on scene 1 fell from 4.7e-6 to 2.1e-9 rad, and at 1e4 m from total loss
/// to 1.6e-4 rad (`scenarios/tests/integration/hard_cases.rs`).
fn rkmk4_body_momentum<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    t: f64,
    y: &mut [State<A>],
    dt: f64,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = y.len();
    let half = 0.5 * dt;
    let conserving = dynamics.conserves_world_momenta();
    for ((start, motor), state) in (buffers.start_momenta.iter_mut())
        .zip(&mut buffers.start_motors)
        .zip(y.iter())
    {
        *start = to_body::<A>(state.motor, state.momentum);
        *motor = state.motor;
    }
    // Stage s + 1 starts from momentum slope s over h, with σ from `sigma(k₁, k₂, k₃)` of body i.
    let prepare = |buffers: &mut Buffers<A>, s: usize, h: f64, sigma: fn(&[A::Screw], usize, usize) -> A::Screw| {
        for i in 0..n {
            buffers.momenta[i] = buffers.start_momenta[i] + buffers.momentum_slopes[s * n + i] * h;
            buffers.sigmas[i] = sigma(&buffers.slopes, n, i);
        }
    };
    buffers.momenta.copy_from_slice(&buffers.start_momenta);
    body_stage(dynamics, (0, t, dt), buffers, workspace)?;
    prepare(buffers, 0, half, |k, _, i| k[i] * 0.5);
    body_stage(dynamics, (1, t + half, dt), buffers, workspace)?;
    prepare(buffers, 1, half, |k, n, i| {
        k[n + i] * 0.5 + bracket::<A>(k[i], k[n + i]) * 0.125
    });
    body_stage(dynamics, (2, t + half, dt), buffers, workspace)?;
    prepare(buffers, 2, dt, |k, n, i| k[2 * n + i]);
    body_stage(dynamics, (3, t + dt, dt), buffers, workspace)?;

    let (k, m) = (&buffers.slopes, &buffers.momentum_slopes);
    for (i, state) in y.iter_mut().enumerate() {
        let (k1, k2, k3, k4) = (k[i], k[n + i], k[2 * n + i], k[3 * n + i]);
        let sigma = (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (1.0 / 6.0) + bracket::<A>(k1, k4) * (1.0 / 12.0);
        let motor = A::compose(state.motor, exp::<A>(sigma));
        let momentum =
            buffers.start_momenta[i] + (m[i] + m[n + i] * 2.0 + m[2 * n + i] * 2.0 + m[3 * n + i]) * (dt / 6.0);
        *state = end_of_body_step(conserving, state, motor, momentum);
    }
    Ok(())
}
/// An explicit Runge–Kutta tableau with `S` stages: `a` strictly lower triangular, weights `b`, nodes `c`.
struct Tableau<const S: usize> {
    a: [[f64; S]; S],
    b: [f64; S],
    c: [f64; S],
    /// The order of the method, which sets where `dexp⁻¹` may be truncated.
    order: u32,
}

/// The classic fourth-order tableau (for [`JointMethod::Rkmk4`]; the body methods write its stages out).
const RK4: Tableau<4> = Tableau {
    a: [
        [0.0; 4],
        [0.5, 0.0, 0.0, 0.0],
        [0.0, 0.5, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ],
    b: RK4_WEIGHTS,
    c: [0.0, 0.5, 0.5, 1.0],
    order: 4,
};

/// Butcher's 7-stage method of order 6 (J. C. Butcher, "On Runge–Kutta processes of high order", J. Austral.
/// Math. Soc. 4, 1964; the tableau as printed in his "Numerical Methods for Ordinary Differential Equations").
/// `integrate::tests::butcher_6_satisfies_the_order_conditions` checks all 37 order conditions up to order 6.
const BUTCHER_6: Tableau<7> = Tableau {
    a: [
        [0.0; 7],
        [1.0 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 2.0 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1.0 / 12.0, 1.0 / 3.0, -1.0 / 12.0, 0.0, 0.0, 0.0, 0.0],
        [-1.0 / 16.0, 9.0 / 8.0, -3.0 / 16.0, -3.0 / 8.0, 0.0, 0.0, 0.0],
        [0.0, 9.0 / 8.0, -3.0 / 8.0, -3.0 / 4.0, 1.0 / 2.0, 0.0, 0.0],
        [
            9.0 / 44.0,
            -9.0 / 11.0,
            63.0 / 44.0,
            18.0 / 11.0,
            0.0,
            -16.0 / 11.0,
            0.0,
        ],
    ],
    b: [
        11.0 / 120.0,
        0.0,
        27.0 / 40.0,
        27.0 / 40.0,
        -4.0 / 15.0,
        -4.0 / 15.0,
        11.0 / 120.0,
    ],
    c: [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0 / 3.0, 1.0 / 2.0, 1.0 / 2.0, 1.0],
    order: 6,
};

/// √21, to the last bit of an f64 (`const` arithmetic has no square root): 4.582575694955840006588047193728…
const SQRT_21: f64 = 4.582_575_694_955_84;

/// Cooper and Verner's 11-stage method of order 8 (G. J. Cooper and J. H. Verner, "Some explicit Runge–Kutta
/// methods of high order", SIAM J. Numer. Anal. 9(3), 1972), whose nodes are those of the Lobatto quadrature
/// of order 8 (½ and ½ ± √21/14). `integrate::tests::cooper_verner_8_satisfies_the_order_conditions` checks all
/// 200 order conditions up to order 8.
const COOPER_VERNER_8: Tableau<11> = {
    const R: f64 = SQRT_21;
    const HIGH: f64 = (7.0 + R) / 14.0;
    const LOW: f64 = (7.0 - R) / 14.0;
    Tableau {
        a: [
            row(&[]),
            row(&[0.5]),
            row(&[0.25, 0.25]),
            row(&[1.0 / 7.0, (-7.0 - 3.0 * R) / 98.0, (21.0 + 5.0 * R) / 49.0]),
            row(&[(11.0 + R) / 84.0, 0.0, (18.0 + 4.0 * R) / 63.0, (21.0 - R) / 252.0]),
            row(&[
                (5.0 + R) / 48.0,
                0.0,
                (9.0 + R) / 36.0,
                (-231.0 + 14.0 * R) / 360.0,
                (63.0 - 7.0 * R) / 80.0,
            ]),
            row(&[
                (10.0 - R) / 42.0,
                0.0,
                (-432.0 + 92.0 * R) / 315.0,
                (633.0 - 145.0 * R) / 90.0,
                (-504.0 + 115.0 * R) / 70.0,
                (63.0 - 13.0 * R) / 35.0,
            ]),
            row(&[
                1.0 / 14.0,
                0.0,
                0.0,
                0.0,
                (14.0 - 3.0 * R) / 126.0,
                (13.0 - 3.0 * R) / 63.0,
                1.0 / 9.0,
            ]),
            row(&[
                1.0 / 32.0,
                0.0,
                0.0,
                0.0,
                (91.0 - 21.0 * R) / 576.0,
                11.0 / 72.0,
                (-385.0 - 75.0 * R) / 1152.0,
                (63.0 + 13.0 * R) / 128.0,
            ]),
            row(&[
                1.0 / 14.0,
                0.0,
                0.0,
                0.0,
                1.0 / 9.0,
                (-733.0 - 147.0 * R) / 2205.0,
                (515.0 + 111.0 * R) / 504.0,
                (-51.0 - 11.0 * R) / 56.0,
                (132.0 + 28.0 * R) / 245.0,
            ]),
            row(&[
                0.0,
                0.0,
                0.0,
                0.0,
                (-42.0 + 7.0 * R) / 18.0,
                (-18.0 + 28.0 * R) / 45.0,
                (-273.0 - 53.0 * R) / 72.0,
                (301.0 + 53.0 * R) / 72.0,
                (28.0 - 28.0 * R) / 45.0,
                (49.0 - 7.0 * R) / 18.0,
            ]),
        ],
        b: [
            1.0 / 20.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            49.0 / 180.0,
            16.0 / 45.0,
            49.0 / 180.0,
            1.0 / 20.0,
        ],
        c: [0.0, 0.5, 0.5, HIGH, HIGH, 0.5, LOW, LOW, 0.5, HIGH, 1.0],
        order: 8,
    }
};

/// Dormand and Prince's 7-stage pair (J. R. Dormand and P. J. Prince, J. Comp. Appl. Math. 6(1), 1980): the weights
/// of the 5th-order solution, which is kept, equal the last row (the last stage is the next step's first in the
/// classical method; here the step's end is projected or turned afterwards, so it is evaluated anew).
/// `integrate::tests::dormand_prince_5_satisfies_the_order_conditions` checks the 17 conditions up to order 5, the
/// embedded solution's 8 up to order 4, and the continuous extension's 8 at several points of the step.
const DORMAND_PRINCE_5: Tableau<7> = Tableau {
    a: [
        row(&[]),
        row(&[1.0 / 5.0]),
        row(&[3.0 / 40.0, 9.0 / 40.0]),
        row(&[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0]),
        row(&[19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0]),
        row(&[
            9017.0 / 3168.0,
            -355.0 / 33.0,
            46732.0 / 5247.0,
            49.0 / 176.0,
            -5103.0 / 18656.0,
        ]),
        row(&DORMAND_PRINCE_5_WEIGHTS),
    ],
    b: row(&DORMAND_PRINCE_5_WEIGHTS),
    c: [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0],
    order: 5,
};

/// The weights of Dormand and Prince's 5th-order solution (stages 1–6; the 7th weighs 0).
const DORMAND_PRINCE_5_WEIGHTS: [f64; 6] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];

/// `b − b̂`: the 5th-order weights minus those of the embedded 4th-order solution (5179/57600, 0, 7571/16695,
/// 393/640, −92097/339200, 187/2100, 1/40).
const DORMAND_PRINCE_5_ERROR: [f64; 7] = [
    35.0 / 384.0 - 5179.0 / 57600.0,
    0.0,
    500.0 / 1113.0 - 7571.0 / 16695.0,
    125.0 / 192.0 - 393.0 / 640.0,
    -2187.0 / 6784.0 + 92097.0 / 339200.0,
    11.0 / 84.0 - 187.0 / 2100.0,
    -1.0 / 40.0,
];

/// The continuous extension of order 4 (Shampine, "Some practical Runge–Kutta formulas", Math. Comp. 46, 1986; as
/// tabulated in Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.6): the weight of stage i at the fraction θ of the
/// step is `Σₖ P[i][k] θ^(k+1)`, which equals the 5th-order weight at θ = 1.
const DORMAND_PRINCE_5_DENSE: [[f64; 4]; 7] = [
    [
        1.0,
        -8048581381.0 / 2820520608.0,
        8663915743.0 / 2820520608.0,
        -12715105075.0 / 11282082432.0,
    ],
    [0.0; 4],
    [
        0.0,
        131558114200.0 / 32700410799.0,
        -68118460800.0 / 10900136933.0,
        87487479700.0 / 32700410799.0,
    ],
    [
        0.0,
        -1754552775.0 / 470086768.0,
        14199869525.0 / 1410260304.0,
        -10690763975.0 / 1880347072.0,
    ],
    [
        0.0,
        127303824393.0 / 49829197408.0,
        -318862633887.0 / 49829197408.0,
        701980252875.0 / 199316789632.0,
    ],
    [
        0.0,
        -282668133.0 / 205662961.0,
        2019193451.0 / 616988883.0,
        -1453857185.0 / 822651844.0,
    ],
    [
        0.0,
        40617522.0 / 29380423.0,
        -110615467.0 / 29380423.0,
        69997945.0 / 29380423.0,
    ],
];

/// The dense-output weights of [`DORMAND_PRINCE_5_DENSE`] at the fraction `theta` of the step.
fn dormand_prince_5_dense_weights(theta: f64) -> [f64; 7] {
    DORMAND_PRINCE_5_DENSE.map(|p| theta * (p[0] + theta * (p[1] + theta * (p[2] + theta * p[3]))))
}

/// Dormand and Prince's 12-stage method of order 8 with embedded solutions of orders 5 and 3 (P. J. Prince and
/// J. R. Dormand, "High order embedded Runge–Kutta formulae", J. Comp. Appl. Math. 7(1), 1981; the coefficients as
/// published with Hairer's DOP853, in Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.10, to 30 digits).
/// `integrate::tests::dop853_satisfies_the_order_conditions` checks the 200 conditions up to order 8, the embedded
/// solutions' up to orders 5 and 3, and the continuous extension's up to order 7 at several points of the step.
#[allow(clippy::excessive_precision)] // the coefficients as published; each rounds to the nearest f64
const DOP853: Tableau<12> = Tableau {
    a: [
        row(&[]),
        row(&[5.26001519587677318785587544488e-2]),
        row(&[1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2]),
        row(&[
            2.95875854768068491816892993775e-2,
            0.0,
            8.87627564304205475450678981324e-2,
        ]),
        row(&[
            2.41365134159266685502369798665e-1,
            0.0,
            -8.84549479328286085344864962717e-1,
            9.24834003261792003115737966543e-1,
        ]),
        row(&[
            3.7037037037037037037037037037e-2,
            0.0,
            0.0,
            1.70828608729473871279604482173e-1,
            1.25467687566822425016691814123e-1,
        ]),
        row(&[
            3.7109375e-2,
            0.0,
            0.0,
            1.70252211019544039314978060272e-1,
            6.02165389804559606850219397283e-2,
            -1.7578125e-2,
        ]),
        row(&[
            3.70920001185047927108779319836e-2,
            0.0,
            0.0,
            1.70383925712239993810214054705e-1,
            1.07262030446373284651809199168e-1,
            -1.53194377486244017527936158236e-2,
            8.27378916381402288758473766002e-3,
        ]),
        row(&[
            6.24110958716075717114429577812e-1,
            0.0,
            0.0,
            -3.36089262944694129406857109825,
            -8.68219346841726006818189891453e-1,
            2.75920996994467083049415600797e1,
            2.01540675504778934086186788979e1,
            -4.34898841810699588477366255144e1,
        ]),
        row(&[
            4.77662536438264365890433908527e-1,
            0.0,
            0.0,
            -2.48811461997166764192642586468,
            -5.90290826836842996371446475743e-1,
            2.12300514481811942347288949897e1,
            1.52792336328824235832596922938e1,
            -3.32882109689848629194453265587e1,
            -2.03312017085086261358222928593e-2,
        ]),
        row(&[
            -9.3714243008598732571704021658e-1,
            0.0,
            0.0,
            5.18637242884406370830023853209,
            1.09143734899672957818500254654,
            -8.14978701074692612513997267357,
            -1.85200656599969598641566180701e1,
            2.27394870993505042818970056734e1,
            2.49360555267965238987089396762,
            -3.0467644718982195003823669022,
        ]),
        row(&[
            2.27331014751653820792359768449,
            0.0,
            0.0,
            -1.05344954667372501984066689879e1,
            -2.00087205822486249909675718444,
            -1.79589318631187989172765950534e1,
            2.79488845294199600508499808837e1,
            -2.85899827713502369474065508674,
            -8.87285693353062954433549289258,
            1.23605671757943030647266201528e1,
            6.43392746015763530355970484046e-1,
        ]),
    ],
    b: DOP853_WEIGHTS,
    c: [
        0.0,
        0.526001519587677318785587544488e-1,
        0.789002279381515978178381316732e-1,
        0.118350341907227396726757197510,
        0.281649658092772603273242802490,
        1.0 / 3.0,
        0.25,
        4.0 / 13.0,
        127.0 / 195.0,
        0.6,
        6.0 / 7.0,
        1.0,
    ],
    order: 8,
};

/// The weights of DOP853's 8th-order solution.
#[allow(clippy::excessive_precision)]
const DOP853_WEIGHTS: [f64; 12] = [
    5.42937341165687622380535766363e-2,
    0.0,
    0.0,
    0.0,
    0.0,
    4.45031289275240888144113950566,
    1.89151789931450038304281599044,
    -5.8012039600105847814672114227,
    3.1116436695781989440891606237e-1,
    -1.52160949662516078556178806805e-1,
    2.01365400804030348374776537501e-1,
    4.47106157277725905176885569043e-2,
];

/// `b − b̂₅`: the 8th-order weights minus those of the embedded 5th-order solution.
#[allow(clippy::excessive_precision)]
const DOP853_ERROR_5: [f64; 12] = [
    0.1312004499419488073250102996e-1,
    0.0,
    0.0,
    0.0,
    0.0,
    -0.1225156446376204440720569753e1,
    -0.4957589496572501915214079952,
    0.1664377182454986536961530415e1,
    -0.3503288487499736816886487290,
    0.3341791187130174790297318841,
    0.8192320648511571246570742613e-1,
    -0.2235530786388629525884427845e-1,
];

/// `b − b̂₃`: the 8th-order weights minus those of the embedded 3rd-order solution, whose only weights are on
/// stages 1, 9 and 12 (0.244094488188976377952755905512, 0.733846688281611857341361741547,
/// 0.220588235294117647058823529412e-1).
#[allow(clippy::excessive_precision)]
const DOP853_ERROR_3: [f64; 12] = {
    let mut e = DOP853_WEIGHTS;
    e[0] -= 0.244094488188976377952755905512;
    e[8] -= 0.733846688281611857341361741547;
    e[11] -= 0.220588235294117647058823529412e-1;
    e
};

/// The stages of all of DOP853's steps and of its continuous extension.
const DOP853_EXTENDED_STAGES: usize = 16;

/// The four stages the continuous extension adds, with their rows over the 16 stages and their nodes: the first is
/// at the step's end (before any projection), the others at 0.1, 0.2 and 7/9 of the step.
#[allow(clippy::excessive_precision)]
const DOP853_EXTENSION: [([f64; DOP853_EXTENDED_STAGES], f64); 4] = [
    (row(&DOP853_WEIGHTS), 1.0),
    (
        row(&[
            5.61675022830479523392909219681e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            2.53500210216624811088794765333e-1,
            -2.46239037470802489917441475441e-1,
            -1.24191423263816360469010140626e-1,
            1.5329179827876569731206322685e-1,
            8.20105229563468988491666602057e-3,
            7.56789766054569976138603589584e-3,
            -8.298e-3,
        ]),
        0.1,
    ),
    (
        row(&[
            3.18346481635021405060768473261e-2,
            0.0,
            0.0,
            0.0,
            0.0,
            2.83009096723667755288322961402e-2,
            5.35419883074385676223797384372e-2,
            -5.49237485713909884646569340306e-2,
            0.0,
            0.0,
            -1.08347328697249322858509316994e-4,
            3.82571090835658412954920192323e-4,
            -3.40465008687404560802977114492e-4,
            1.41312443674632500278074618366e-1,
        ]),
        0.2,
    ),
    (
        row(&[
            -4.28896301583791923408573538692e-1,
            0.0,
            0.0,
            0.0,
            0.0,
            -4.69762141536116384314449447206,
            7.68342119606259904184240953878,
            4.06898981839711007970213554331,
            3.56727187455281109270669543021e-1,
            0.0,
            0.0,
            0.0,
            -1.39902416515901462129418009734e-3,
            2.9475147891527723389556272149,
            -9.15095847217987001081870187138,
        ]),
        7.0 / 9.0,
    ),
];

/// The continuous extension's last four coefficient rows, over the 16 stages (Hairer's `d` coefficients; see
/// [`dop853_dense_weights`]).
#[allow(clippy::excessive_precision)]
const DOP853_DENSE: [[f64; DOP853_EXTENDED_STAGES]; 4] = [
    [
        -0.84289382761090128651353491142e1,
        0.0,
        0.0,
        0.0,
        0.0,
        0.56671495351937776962531783590,
        -0.30689499459498916912797304727e1,
        0.23846676565120698287728149680e1,
        0.21170345824450282767155149946e1,
        -0.87139158377797299206789907490,
        0.22404374302607882758541771650e1,
        0.63157877876946881815570249290,
        -0.88990336451333310820698117400e-1,
        0.18148505520854727256656404962e2,
        -0.91946323924783554000451984436e1,
        -0.44360363875948939664310572000e1,
    ],
    [
        0.10427508642579134603413151009e2,
        0.0,
        0.0,
        0.0,
        0.0,
        0.24228349177525818288430175319e3,
        0.16520045171727028198505394887e3,
        -0.37454675472269020279518312152e3,
        -0.22113666853125306036270938578e2,
        0.77334326684722638389603898808e1,
        -0.30674084731089398182061213626e2,
        -0.93321305264302278729567221706e1,
        0.15697238121770843886131091075e2,
        -0.31139403219565177677282850411e2,
        -0.93529243588444783865713862664e1,
        0.35816841486394083752465898540e2,
    ],
    [
        0.19985053242002433820987653617e2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.38703730874935176555105901742e3,
        -0.18917813819516756882830838328e3,
        0.52780815920542364900561016686e3,
        -0.11573902539959630126141871134e2,
        0.68812326946963000169666922661e1,
        -0.10006050966910838403183860980e1,
        0.77771377980534432092869265740,
        -0.27782057523535084065932004339e1,
        -0.60196695231264120758267380846e2,
        0.84320405506677161018159903784e2,
        0.11992291136182789328035130030e2,
    ],
    [
        -0.25693933462703749003312586129e2,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.15418974869023643374053993627e3,
        -0.23152937917604549567536039109e3,
        0.35763911791061412378285349910e3,
        0.93405324183624310003907691704e2,
        -0.37458323136451633156875139351e2,
        0.10409964950896230045147246184e3,
        0.29840293426660503123344363579e2,
        -0.43533456590011143754432175058e2,
        0.96324553959188282948394950600e2,
        -0.39177261675615439165231486172e2,
        -0.14972683625798562581422125276e3,
    ],
];

/// The dense-output weights of DOP853 over its 16 stages at the fraction `theta` of the step, from Hairer's
/// form of the order-7 extension, `y(θ) = y₀ + θ(r₂ + θ'(r₃ + θ(r₄ + θ'(r₅ + θ(r₆ + θ'(r₇ + θr₈))))))` with
/// `θ' = 1 − θ`: `r₂` the step's increment `Σ bᵢKᵢ`, `r₃ = K₁ − r₂`, `r₄ = r₂ − K₁₃ − r₃` (K₁₃ the slope at the
/// step's end), `r₅…r₈` the rows of [`DOP853_DENSE`]. Every `r` is linear in the stages, so the extension is a set of
/// weights, the increment's at θ = 1.
fn dop853_dense_weights(theta: f64) -> [f64; DOP853_EXTENDED_STAGES] {
    let increment: [f64; DOP853_EXTENDED_STAGES] = row(&DOP853_WEIGHTS);
    let unit = |i: usize| -> [f64; DOP853_EXTENDED_STAGES] { std::array::from_fn(|j| if j == i { 1.0 } else { 0.0 }) };
    let (first, end) = (unit(0), unit(DOP853.b.len()));
    let r3: [f64; DOP853_EXTENDED_STAGES] = std::array::from_fn(|j| first[j] - increment[j]);
    let r4: [f64; DOP853_EXTENDED_STAGES] = std::array::from_fn(|j| increment[j] - end[j] - r3[j]);
    let after = 1.0 - theta;
    let [r5, r6, r7, r8] = DOP853_DENSE;
    std::array::from_fn(|j| {
        let inner = r5[j] + theta * (r6[j] + after * (r7[j] + theta * r8[j]));
        theta * (increment[j] + after * (r3[j] + theta * (r4[j] + after * inner)))
    })
}

/// A row of a strictly lower triangular tableau: its leading entries, then zeros.
const fn row<const S: usize>(leading: &[f64]) -> [f64; S] {
    let mut row = [0.0; S];
    let mut j = 0;
    while j < leading.len() {
        row[j] = leading[j];
        j += 1;
    }
    row
}

/// `dexp⁻¹_{−σ}(k) = k + ½[σ, k] + ¹⁄₁₂[σ, [σ, k]] − ¹⁄₇₂₀ ad⁴_σ k + ¹⁄₃₀₂₄₀ ad⁶_σ k − …` (the Bernoulli numbers
/// Bₙ/n!, with the odd terms' sign flipped for the right action, see [`rkmk4`]), truncated for a method of
/// `order`: with σ = O(h) the term ad^n_σ k is O(hⁿ⁺¹), so the terms n ≤ order − 1 are kept (the odd ones
/// beyond n = 1 vanish).
fn dexp_inverse<A: Algebra>(sigma: A::Screw, k: A::Screw, order: u32) -> A::Screw {
    let bracket = |x: A::Screw, y: A::Screw| A::commutator(x, y) * 2.0;
    let first = bracket(sigma, k);
    let second = bracket(sigma, first);
    let mut result = k + first * 0.5 + second * (1.0 / 12.0);
    if order > 4 {
        let fourth = bracket(sigma, bracket(sigma, second));
        result = result + fourth * (-1.0 / 720.0);
        if order > 6 {
            let sixth = bracket(sigma, bracket(sigma, fourth));
            result = result + sixth * (1.0 / 30240.0);
        }
    }
    result
}

/// A body-momentum Runge–Kutta–Munthe-Kaas step ([`Method::Rkmk6Body`]) on any explicit tableau, body by body
/// ([`rkmk_stage`]). The step ends at `R₀ exp(Σ bᵢKᵢ)` with the world momentum of the new motor; the stages stay in
/// `buffers` for an embedded pair's error estimate and continuous extension.
fn rkmk_body_momentum<A: Algebra, D: Dynamics<A> + ?Sized, const S: usize>(
    tableau: &Tableau<S>,
    dynamics: &D,
    t: f64,
    y: &mut [State<A>],
    dt: f64,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let conserving = dynamics.conserves_world_momenta();
    for ((start, motor), state) in buffers
        .start_momenta
        .iter_mut()
        .zip(&mut buffers.start_motors)
        .zip(y.iter())
    {
        *start = to_body::<A>(state.motor, state.momentum);
        *motor = state.motor;
    }
    for s in 0..S {
        let at = (s, t + tableau.c[s] * dt, dt);
        rkmk_stage(dynamics, at, &tableau.a[s], tableau.order, buffers, workspace)?;
    }
    for (b, state) in y.iter_mut().enumerate() {
        let (sigma, momentum) = weighted_slopes(buffers, &tableau.b, b, (dt, buffers.start_momenta[b]));
        let motor = A::compose(state.motor, exp::<A>(sigma));
        *state = end_of_body_step(conserving, state, motor, momentum);
    }
    Ok(())
}

/// Stage `s` at time `at` of a body-momentum RKMK step of `order`, with coefficients `row` on the earlier stages:
/// it evaluates the rates at `R₀ exp(σₛ)`, `σₛ = Σⱼ aₛⱼ Kⱼ`, and turns `kₛ = −½hḂₛ` into `Kₛ = dexp⁻¹_{−σₛ}(kₛ)`
/// (see [`rkmk4`] for the right-action form); the body momentum `Ω_b` takes the classic stages of
/// `dΩ_b/dt = Ḃ × Ω_b + W_b` (theory §5).
fn rkmk_stage<A: Algebra, D: Dynamics<A> + ?Sized>(
    dynamics: &D,
    (s, at, dt): (usize, f64, f64),
    row: &[f64],
    order: u32,
    buffers: &mut Buffers<A>,
    workspace: &mut D::Workspace,
) -> Result<(), ConstraintError> {
    let n = buffers.motors.len();
    for b in 0..n {
        // The high-order tableaux are sparse: `weighted_slopes` skips a zero coefficient.
        (buffers.sigmas[b], buffers.momenta[b]) =
            weighted_slopes(buffers, &row[..s], b, (dt, buffers.start_momenta[b]));
    }
    body_stage(dynamics, (s, at, dt), buffers, workspace)?;
    if s > 0 {
        for b in 0..n {
            let slope = &mut buffers.slopes[s * n + b];
            *slope = dexp_inverse::<A>(buffers.sigmas[b], *slope, order);
        }
    }
    Ok(())
}

/// `(Σ wₛKₛ, m₀ + h Σ wₛ dΩ_b/dtₛ)` of body `b` from the stages in `buffers` (zero weights skipped).
fn weighted_slopes<A: Algebra>(
    buffers: &Buffers<A>,
    weights: &[f64],
    b: usize,
    (dt, start_momentum): (f64, A::Screw),
) -> (A::Screw, A::Screw) {
    let n = buffers.start_momenta.len();
    let zero = A::screw(ScrewCoordinates::default());
    (0..weights.len())
        .filter(|&s| weights[s] != 0.0)
        .fold((zero, start_momentum), |(sigma, m), s| {
            (
                sigma + buffers.slopes[s * n + b] * weights[s],
                m + buffers.momentum_slopes[s * n + b] * (weights[s] * dt),
            )
        })
}

/// The state at the end of a body-momentum step from `start`: the step's motor with the world view of the step's
/// body momentum `Ω_b`.
///
/// Unless the world momentum is a constant of the motion (`conserving`: no force, no joint). The stages integrate
/// Euler's equations for `Ω_b`, which keep `R Ω_b ~R` only to the truncation error, so a torque-free body's world
/// momentum would wander (7e-9 relative over 10⁶ steps at dt = 1e-3, flipping about its middle axis). Then the
/// end state is projected onto that invariant (Hairer, Lubich & Wanner, *Geometric Numerical Integration*,
/// §IV.4): the world momentum is kept exactly, and the motor turned about the centre of mass by the shortest arc
/// that makes the kept angular momentum, seen from the body, point along the step's (the `t` part of momentum
/// coordinates, `Iω`). That keeps what the body-frame methods are for: the direction of the body's angular
/// momentum, which sets its angular velocity, comes from Euler's equations, not from the motor's error. The turn
/// about that axis stays the step's own, and the body's linear momentum is the world one seen from the body. The
/// correction is the size of the local error, so the method's order is kept.
fn end_of_body_step<A: Algebra>(
    conserving: bool,
    start: &State<A>,
    motor: A::Motor,
    body_momentum: A::Screw,
) -> State<A> {
    if !conserving {
        return State {
            motor,
            momentum: to_world::<A>(motor, body_momentum),
        };
    }
    let seen = A::screw_coordinates(to_body::<A>(motor, start.momentum)).t;
    let stepped = A::screw_coordinates(body_momentum).t;
    // The body frame turned by Q sees the world momentum as Q⁻¹ applied to what the step's frame sees: Q takes the
    // stepped direction to the seen one.
    let turn = motor::from_pose::<A>(Vector3::zeros(), &shortest_arc(&stepped, &seen));
    State {
        motor: A::compose(motor, turn),
        momentum: start.momentum,
    }
}

/// The rotation by the smallest angle taking the direction of `from` to that of `to`: the quaternion
/// `(1 + u·v, u⨯v)` of the unit vectors, normalised, which is exact for the tiny angles met here (nalgebra's
/// `rotation_between`, an arccosine of u·v, resolves only 1.5e-8 rad). The identity where a vector vanishes or
/// the two are more than 90° apart (not a correction of a step's error).
fn shortest_arc(from: &Vector3<f64>, to: &Vector3<f64>) -> UnitQuaternion<f64> {
    let (Some(from), Some(to)) = (from.try_normalize(0.0), to.try_normalize(0.0)) else {
        return UnitQuaternion::identity();
    };
    let cosine = 1.0 + from.dot(&to);
    if cosine.is_nan() || cosine <= 1.0 {
        return UnitQuaternion::identity();
    }
    let axis = from.cross(&to);
    UnitQuaternion::new_normalize(Quaternion::new(cosine, axis.x, axis.y, axis.z))
}

/// A [`FreeBody`] checked to admit a splitting integrator: its Hamiltonian is the kinetic energy
/// `Σ Lᵢ²/2Iᵢ + |p|²/2m` (body-frame angular momentum about the centre of mass, linear momentum) plus
/// forces that depend on the configuration only.
///
/// The kinetic pieces have exact flows that leave the world momentum Ω unchanged: `Lᵢ²/2Iᵢ` turns the body
/// about its axis i at the constant rate `Lᵢ/Iᵢ`, and `|p|²/2m` translates it at the constant body velocity
/// `p/m`. Each is applied as `R ← R exp(−½ h Ḃₖ)` (theory §3). The translation commutes with the rotations
/// (|p| is invariant under rotations, and a translation along p keeps L about the centre of mass), so it is
/// applied once per drift. The forces enter as kicks `Ω ← Ω + h W(R)`, the exact flow of `dΩ/dt = W` at fixed
/// R. For conservative forces (gravity) every piece is a Hamiltonian flow, so the method is symplectic and
/// the energy error stays bounded; for a constant wrench along a fixed world line or a constant couple (not
/// conservative under rotations) it is still a valid splitting of that order.
#[derive(Clone, Copy, Debug)]
pub struct KineticSplitting<'a, A: Algebra> {
    system: &'a FreeBody<A>,
    /// The body axes in the order of the rotation sequence `a(½h) b(½h) c(h) b(½h) a(½h)`: by increasing
    /// principal moment. Of the six orders this one measured the smallest Strang error on the Dzhanibekov
    /// cuboid (scene 1, dt = 1e-3, orientation at T = 10 s: 6.8e-6 rad; the other orders 2.6e-5 to 5.6e-4)
    /// and the third smallest for Yoshida4 (6.9e-9 rad; best 4.3e-9, worst 9.6e-8).
    axis_order: [usize; 3],
}

impl<'a, A: Algebra> KineticSplitting<'a, A> {
    /// Checks that every force depends on the configuration only.
    ///
    /// Gravity depends on the configuration only; a custom force may depend on the momentum, so a body with one
    /// is refused (naming the force).
    ///
    /// ```
    /// use std::sync::Arc;
    /// use dynamics::integrate::SplittingError;
    /// use dynamics::{Body, Force, FreeBody, KineticSplitting, Pga};
    ///
    /// let top = FreeBody::<Pga>::new(Body::solid_cone(0.5, 0.4, 0.1)?).with_force(Force::gravity());
    /// assert!(KineticSplitting::new(&top).is_ok());
    /// let drag = Force::Custom(Arc::new(|_t, state: &dynamics::State<Pga>| state.momentum * -0.1));
    /// let dragged = top.clone().with_force(drag);
    /// assert_eq!(KineticSplitting::new(&dragged).err(), Some(SplittingError::CustomForce { index: 1 }));
    /// # Ok::<(), dynamics::BodyError>(())
    /// ```
    pub fn new(system: &'a FreeBody<A>) -> Result<Self, SplittingError> {
        match system.forces.iter().position(|force| matches!(force, Force::Custom(_))) {
            Some(index) => Err(SplittingError::CustomForce { index }),
            None => {
                let moments = system.body.moments();
                let mut axis_order = [0, 1, 2];
                axis_order.sort_by(|&i, &j| moments[i].total_cmp(&moments[j]));
                Ok(KineticSplitting { system, axis_order })
            }
        }
    }

    /// The free body being split.
    pub fn system(&self) -> &'a FreeBody<A> {
        self.system
    }
}

/// One step of a splitting method from `(t, state)` to `t + dt` (the stepper then calls [`Dynamics::after_step`]).
fn step_splitting<A: Algebra>(
    method: SplittingMethod,
    splitting: &KineticSplitting<'_, A>,
    t: f64,
    state: &State<A>,
    dt: f64,
) -> State<A> {
    match method {
        SplittingMethod::Strang => strang(splitting, t, *state, dt),
        SplittingMethod::Yoshida4 => {
            // w₁ = 1/(2 − ∛2), w₀ = 1 − 2w₁ (Yoshida 1990): the order-3 error terms of the three
            // symmetric sub-steps cancel.
            let cube_root = 2f64.cbrt();
            let outer = 1.0 / (2.0 - cube_root);
            let inner = 1.0 - 2.0 * outer;
            let first = strang(splitting, t, *state, outer * dt);
            let second = strang(splitting, t + outer * dt, first, inner * dt);
            strang(splitting, t + (outer + inner) * dt, second, outer * dt)
        }
    }
}

/// Kick ½h, drift h, kick ½h. The forces are time-independent (custom forces are excluded), so the kicks'
/// times only matter for the record.
fn strang<A: Algebra>(splitting: &KineticSplitting<'_, A>, t: f64, state: State<A>, h: f64) -> State<A> {
    let system = splitting.system;
    let kick = |state: State<A>, at: f64| {
        if system.forces.is_empty() {
            state
        } else {
            State {
                momentum: state.momentum + system.external_wrench(at, &state) * (0.5 * h),
                ..state
            }
        }
    };
    let drifted = drift(system, splitting.axis_order, kick(state, t), h);
    kick(drifted, t + h)
}

/// The kinetic flow over `h`: `a(½h) b(½h) c(h) b(½h) a(½h)` rotations about body axes, then the translation.
fn drift<A: Algebra>(system: &FreeBody<A>, axis_order: [usize; 3], state: State<A>, h: f64) -> State<A> {
    let [a, b, c] = axis_order;
    let mut motor = state.motor;
    for (axis, fraction) in [(a, 0.5), (b, 0.5), (c, 1.0), (b, 0.5), (a, 0.5)] {
        let body_momentum = A::screw_coordinates(A::transform_screw(A::reverse(motor), state.momentum));
        let mut angular = nalgebra::Vector3::zeros();
        angular[axis] = body_momentum.t[axis] / system.body.moments()[axis];
        let velocity = A::screw(ScrewCoordinates {
            l: angular,
            t: nalgebra::Vector3::zeros(),
        });
        motor = A::compose(motor, exp::<A>(velocity * (-0.5 * fraction * h)));
    }
    let body_momentum = A::screw_coordinates(A::transform_screw(A::reverse(motor), state.momentum));
    let velocity = A::screw(ScrewCoordinates {
        l: nalgebra::Vector3::zeros(),
        t: body_momentum.l / system.body.mass(),
    });
    State {
        motor: A::compose(motor, exp::<A>(velocity * (-0.5 * h))),
        momentum: state.momentum,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every rooted tree with at most `max_order` vertices, as the list of its root's subtrees (indices of
    /// earlier trees, non-decreasing), with its order.
    fn rooted_trees(max_order: usize) -> Vec<(Vec<usize>, usize)> {
        let mut trees: Vec<(Vec<usize>, usize)> = vec![(Vec::new(), 1)];
        for order in 2..=max_order {
            // Multisets of earlier trees whose orders sum to order − 1, built with non-decreasing indices.
            let mut stack: Vec<(Vec<usize>, usize)> = vec![(Vec::new(), 0)];
            let existing = trees.len();
            while let Some((children, size)) = stack.pop() {
                if size == order - 1 {
                    trees.push((children, order));
                    continue;
                }
                let from = children.last().copied().unwrap_or(0);
                for (index, (_, child_order)) in trees.iter().enumerate().take(existing).skip(from) {
                    if size + child_order < order {
                        let mut next = children.clone();
                        next.push(index);
                        stack.push((next, size + child_order));
                    }
                }
            }
        }
        trees
    }

    /// The order conditions `Σ bᵢ Φᵢ(τ) = 1/γ(τ)` for every tree τ up to the tableau's order (Butcher), where
    /// `Φᵢ(τ) = Πₖ Σⱼ aᵢⱼ Φⱼ(τₖ)` over the root's subtrees τₖ and `γ(τ) = |τ| Πₖ γ(τₖ)`.
    fn order_condition_defects<const S: usize>(tableau: &Tableau<S>, theta: f64) -> Vec<f64> {
        let trees = rooted_trees(tableau.order as usize);
        let mut weights: Vec<[f64; S]> = Vec::new();
        let mut densities: Vec<f64> = Vec::new();
        for (children, order) in &trees {
            let mut phi = [1.0; S];
            let mut gamma = *order as f64;
            for &child in children {
                for (i, p) in phi.iter_mut().enumerate() {
                    *p *= (0..S).map(|j| tableau.a[i][j] * weights[child][j]).sum::<f64>();
                }
                gamma *= densities[child];
            }
            weights.push(phi);
            densities.push(gamma);
        }
        weights
            .iter()
            .zip(&densities)
            .zip(&trees)
            .map(|((phi, gamma), (_, order))| {
                ((0..S).map(|i| tableau.b[i] * phi[i]).sum::<f64>() - theta.powi(*order as i32) / gamma).abs()
            })
            .collect()
    }

    #[test]
    fn rooted_trees_are_counted_right() {
        // 1, 1, 2, 4, 9, 20 trees of orders 1..6 (OEIS A000081).
        let trees = rooted_trees(6);
        let counts: Vec<usize> = (1..=6).map(|n| trees.iter().filter(|t| t.1 == n).count()).collect();
        assert_eq!(counts, [1, 1, 2, 4, 9, 20]);
    }

    #[test]
    fn cooper_verner_8_satisfies_the_order_conditions() {
        assert_eq!(SQRT_21 * SQRT_21, 21.0);
        for (i, row) in COOPER_VERNER_8.a.iter().enumerate() {
            let sum = row.iter().sum::<f64>();
            assert!(
                (sum - COOPER_VERNER_8.c[i]).abs() < 1e-14,
                "c{i} is not the row sum: {sum}"
            );
        }
        let defects = order_condition_defects(&COOPER_VERNER_8, 1.0);
        assert_eq!(defects.len(), 200);
        let worst = defects.iter().copied().fold(0.0, f64::max);
        assert!(worst < 1e-13, "largest order-condition defect {worst:e}");
        let ninth = Tableau {
            order: 9,
            ..COOPER_VERNER_8
        };
        assert!(order_condition_defects(&ninth, 1.0).iter().any(|&d| d > 1e-6));
    }

    #[test]
    fn butcher_6_satisfies_the_order_conditions() {
        for (i, row) in BUTCHER_6.a.iter().enumerate() {
            assert!(
                (row.iter().sum::<f64>() - BUTCHER_6.c[i]).abs() < 1e-15,
                "c{i} is not the row sum"
            );
        }
        let defects = order_condition_defects(&BUTCHER_6, 1.0);
        assert_eq!(defects.len(), 37);
        let worst = defects.iter().copied().fold(0.0, f64::max);
        assert!(worst < 1e-15, "largest order-condition defect {worst:e}");
        // And it is not of order 7: some order-7 condition fails.
        let seventh = Tableau { order: 7, ..BUTCHER_6 };
        assert!(order_condition_defects(&seventh, 1.0).iter().any(|&d| d > 1e-6));
    }

    #[test]
    fn dormand_prince_5_satisfies_the_order_conditions() {
        let pair = &DORMAND_PRINCE_5;
        for (i, row) in pair.a.iter().enumerate() {
            assert!(
                (row.iter().sum::<f64>() - pair.c[i]).abs() < 1e-14,
                "c{i} is not the row sum"
            );
        }
        let worst = |defects: Vec<f64>| defects.iter().copied().fold(0.0, f64::max);
        let defects = order_condition_defects(pair, 1.0);
        assert_eq!(defects.len(), 17);
        assert!(worst(defects) < 1e-14);
        assert!(order_condition_defects(&Tableau { order: 6, ..*pair }, 1.0)
            .iter()
            .any(|&d| d > 1e-6));
        // The embedded solution, b̂ = b − e: order 4, not 5.
        let embedded = Tableau {
            b: std::array::from_fn(|i| pair.b[i] - DORMAND_PRINCE_5_ERROR[i]),
            order: 4,
            ..*pair
        };
        assert!(worst(order_condition_defects(&embedded, 1.0)) < 1e-14);
        assert!(order_condition_defects(&Tableau { order: 5, ..embedded }, 1.0)
            .iter()
            .any(|&d| d > 1e-6));
        // The continuous extension: order 4 at every fraction of the step, the kept solution at its end.
        for theta in [0.1, 1.0 / 3.0, 0.5, 0.8, 1.0] {
            let dense = Tableau {
                b: dormand_prince_5_dense_weights(theta),
                order: 4,
                ..*pair
            };
            assert!(worst(order_condition_defects(&dense, theta)) < 1e-14, "θ = {theta}");
        }
        let at_end = dormand_prince_5_dense_weights(1.0);
        assert!(at_end.iter().zip(&pair.b).all(|(d, b)| (d - b).abs() < 1e-15));
    }

    #[test]
    fn dop853_satisfies_the_order_conditions() {
        let worst = |defects: Vec<f64>| defects.iter().copied().fold(0.0, f64::max);
        let pair = &DOP853;
        for (i, row) in pair.a.iter().enumerate() {
            let sum = row.iter().sum::<f64>();
            assert!((sum - pair.c[i]).abs() < 1e-14, "c{i} is not the row sum: {sum}");
        }
        let defects = order_condition_defects(pair, 1.0);
        assert_eq!(defects.len(), 200);
        assert!(worst(defects) < 1e-13);
        assert!(order_condition_defects(&Tableau { order: 9, ..*pair }, 1.0)
            .iter()
            .any(|&d| d > 1e-6));
        // The embedded solutions b̂ = b − e: orders 5 and 3, not higher.
        for (error, order) in [(&DOP853_ERROR_5, 5), (&DOP853_ERROR_3, 3)] {
            let embedded = Tableau {
                b: std::array::from_fn(|i| pair.b[i] - error[i]),
                order,
                ..*pair
            };
            assert!(worst(order_condition_defects(&embedded, 1.0)) < 1e-13, "order {order}");
            assert!(order_condition_defects(
                &Tableau {
                    order: order + 1,
                    ..embedded
                },
                1.0
            )
            .iter()
            .any(|&d| d > 1e-6));
        }
        // The extension's stages on top of the step's, and the continuous extension: order 7 at every fraction of
        // the step, the kept solution at its end.
        let mut a = [[0.0; DOP853_EXTENDED_STAGES]; DOP853_EXTENDED_STAGES];
        let mut c = [0.0; DOP853_EXTENDED_STAGES];
        for (i, step_row) in pair.a.iter().enumerate() {
            a[i] = row(step_row);
            c[i] = pair.c[i];
        }
        for (k, (extension_row, node)) in DOP853_EXTENSION.iter().enumerate() {
            let i = pair.b.len() + k;
            (a[i], c[i]) = (*extension_row, *node);
            let sum = extension_row.iter().sum::<f64>();
            assert!((sum - node).abs() < 1e-14, "c{i} is not the row sum");
        }
        for theta in [0.1, 1.0 / 3.0, 0.5, 0.8, 1.0] {
            let dense = Tableau {
                a,
                b: dop853_dense_weights(theta),
                c,
                order: 7,
            };
            assert!(worst(order_condition_defects(&dense, theta)) < 1e-13, "θ = {theta}");
            // Inside the step it is of order 7 only (at its end it is the 8th-order solution).
            let eighth = Tableau { order: 8, ..dense };
            let defects = order_condition_defects(&eighth, theta);
            assert!(theta == 1.0 || defects.iter().any(|&d| d > 1e-9), "θ = {theta}");
        }
        let at_end = dop853_dense_weights(1.0);
        assert!(at_end
            .iter()
            .zip(&row::<DOP853_EXTENDED_STAGES>(&pair.b))
            .all(|(d, b)| (d - b).abs() < 1e-15));
    }
}
