//! Force elements: forces between two bodies, or a body and the world, that see both bodies' states
//! (docs/mechanisms.md §M8) — a spring-damper between two body points, a couple between two bodies, a joint's
//! actuator force or torque, viscous joint damping, a controller of the joint-space state, or any wrench the user
//! computes from both states. Each acts on its two bodies with equal and opposite wrenches along the same line
//! (Newton's third law), so it changes no total momentum of its own.
//!
//! Energy: a conservative element (the spring) reports its potential, which [`crate::Mechanism::energy`] adds; every
//! other element reports the power it puts into the system, which the integrators integrate with the method's own
//! weights into the work done ([`crate::Simulation`]'s samples), so that `energy(t) − energy(0) = work(t)` up to
//! the integration error.

use std::fmt;
use std::sync::Arc;

use nalgebra::{DMatrix, DVector, Vector3};

use crate::algebra::Algebra;
use crate::constraints::ConstraintError;
use crate::mechanism::error::MechanismError;
use crate::mechanism::parts::{BodyId, JointId, Reference};
use crate::state::State;

/// A value that may change with time: a constant, or a function of time.
#[derive(Clone)]
pub enum OfTime<T> {
    /// The same value throughout.
    Constant(T),
    /// A function of time (s).
    Function(Arc<dyn Fn(f64) -> T + Send + Sync>),
}

impl<T: Copy> OfTime<T> {
    /// The value at time `t`.
    #[inline]
    pub fn at(&self, t: f64) -> T {
        match self {
            OfTime::Constant(value) => *value,
            OfTime::Function(function) => function(t),
        }
    }
}

impl<T: fmt::Debug> fmt::Debug for OfTime<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OfTime::Constant(value) => write!(f, "Constant({value:?})"),
            OfTime::Function(_) => f.write_str("Function(..)"),
        }
    }
}

/// What a controller sees: the time, the joint positions and velocities (in the layout of
/// [`crate::JointSpace`]), the bodies' states, and the mechanism, for the joint-space quantities a controller may
/// want (the mass matrix and the bias forces of computed torque).
pub struct JointState<'a, A: Algebra> {
    /// The time (s).
    pub t: f64,
    /// The joint positions.
    pub positions: &'a [f64],
    /// The joint velocities.
    pub velocities: &'a [f64],
    /// Every body's state.
    pub states: &'a [State<A>],
    pub(crate) mechanism: &'a dyn JointSpaceQueries<A>,
}

/// The joint-space quantities a controller may ask of the mechanism it acts in, at a state; the mechanism answers
/// them (`mechanism::elements`).
pub(crate) trait JointSpaceQueries<A: Algebra>: Sync {
    /// M(q).
    fn mass_matrix(&self, states: &[State<A>]) -> Result<DMatrix<f64>, MechanismError>;
    /// h(q, v) at time `t`.
    fn bias_forces(&self, t: f64, states: &[State<A>]) -> Result<DVector<f64>, MechanismError>;
}

impl<A: Algebra> JointState<'_, A> {
    /// M(q) at this state ([`crate::Mechanism::mass_matrix`]).
    pub fn mass_matrix(&self) -> Result<DMatrix<f64>, MechanismError> {
        self.mechanism.mass_matrix(self.states)
    }

    /// h(q, v) at this state ([`crate::Mechanism::bias_forces`]: everything but the actuators — joint forces and
    /// controllers).
    pub fn bias_forces(&self) -> Result<DVector<f64>, MechanismError> {
        self.mechanism.bias_forces(self.t, self.states)
    }
}

/// A controller: the generalised forces on every joint coordinate (a vector of the joint space's velocity count;
/// zero where a coordinate is not actuated) from the joint-space state.
pub type ControlLaw<A> = Arc<dyn Fn(&JointState<'_, A>) -> DVector<f64> + Send + Sync>;

/// A user wrench between two bodies: the world wrench on the first body, from the time and the two bodies' states
/// (the second is `None` for the world); the second body receives the opposite.
pub type WrenchBetween<A> = Arc<dyn Fn(f64, &State<A>, Option<&State<A>>) -> <A as Algebra>::Screw + Send + Sync>;

#[derive(Clone)]
pub(crate) enum ElementKind<A: Algebra> {
    SpringDamper {
        first: (usize, Vector3<f64>),
        second: (Option<usize>, Vector3<f64>),
        stiffness: f64,
        damping: f64,
        rest_length: f64,
    },
    Couple {
        first: usize,
        second: Option<usize>,
        moment: OfTime<Vector3<f64>>,
    },
    JointForce {
        joint: usize,
        force: OfTime<f64>,
    },
    JointDamping {
        joint: usize,
        coefficient: f64,
    },
    Controller(ControlLaw<A>),
    Between {
        first: usize,
        second: Option<usize>,
        wrench: WrenchBetween<A>,
    },
}

/// A force element (see the module docs).
#[derive(Clone)]
pub struct ForceElement<A: Algebra> {
    pub(crate) name: String,
    pub(crate) kind: ElementKind<A>,
}

impl<A: Algebra> fmt::Debug for ForceElement<A> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match &self.kind {
            ElementKind::SpringDamper { .. } => "spring-damper",
            ElementKind::Couple { .. } => "couple",
            ElementKind::JointForce { .. } => "joint force",
            ElementKind::JointDamping { .. } => "joint damping",
            ElementKind::Controller(_) => "controller",
            ElementKind::Between { .. } => "between",
        };
        write!(f, "ForceElement({:?}: {kind})", self.name)
    }
}

fn invalid(name: &str, reason: String) -> ConstraintError {
    ConstraintError::InvalidParameter {
        name: name.to_owned(),
        reason,
    }
}

fn finite(v: &Vector3<f64>) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The largest stiffness, damping or rest length accepted (as the mass bound of [`crate::body`]): beyond it the
/// forces overflow long before any physical element.
const MAX_PARAMETER: f64 = 1e50;

fn reference_index(reference: Reference) -> Option<usize> {
    match reference {
        Reference::World => None,
        Reference::Body(body) => Some(body.index()),
    }
}

impl<A: Algebra> ForceElement<A> {
    /// A linear spring and viscous damper between the body point `first.1` of body `first.0` (body coordinates) and
    /// the point `second.1` of `second.0` (its body coordinates, or a world point): along the line joining them, the
    /// force `k (l − l₀) + c l̇` pulls them together when positive. Potential `½ k (l − l₀)²`; the damper's power
    /// `−c l̇²`. Stiffness (N/m) and damping (N s/m) must be finite and non-negative, the rest length (m) finite and
    /// non-negative; with a rest length above zero the two points must not meet (an error at that evaluation names
    /// the element).
    ///
    /// A 1 kg ball hanging from a spring of 100 N/m and rest length 0.5 m rests 0.5981 m below its anchor:
    ///
    /// ```
    /// use dynamics::mechanism::force_elements::ForceElement;
    /// use dynamics::{Algebra, Body, Force, Mechanism, Pga, Reference, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.05)?;
    /// let mut hanging = Mechanism::<Pga>::new();
    /// let id = hanging.add_body("ball", ball)?;
    /// hanging.add_force(id, Force::gravity())?;
    /// let spring = ForceElement::spring_damper("spring", (id, Vector3::zeros()), (Reference::World, Vector3::z()), 100.0, 2.0, 0.5)?;
    /// hanging.add_force_element(spring)?;
    /// let rest = Vector3::z() * (1.0 - 0.5 - 9.81 / 100.0); // m
    /// let state = State::new(&ball, rest, &UnitQuaternion::identity(), Vector3::zeros(), Vector3::zeros());
    /// let rate = Pga::screw_coordinates(hanging.rates_at(0.0, &[state])?[0].momentum_rate);
    /// assert!(rate.l.norm() < 1e-12); // N: in equilibrium
    /// let stretched = 0.5f64 + 9.81 / 100.0;
    /// let potential = 9.81 * rest.z + 0.5 * 100.0 * (stretched - 0.5).powi(2);
    /// assert!((hanging.energy(&[state])? - potential).abs() < 1e-12); // J
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn spring_damper(
        name: impl Into<String>,
        (first, first_point): (BodyId, Vector3<f64>),
        (second, second_point): (Reference, Vector3<f64>),
        stiffness: f64,
        damping: f64,
        rest_length: f64,
    ) -> Result<Self, ConstraintError> {
        let name = name.into();
        for (what, value) in [
            ("stiffness", stiffness),
            ("damping", damping),
            ("rest length", rest_length),
        ] {
            if !(value.is_finite() && (0.0..=MAX_PARAMETER).contains(&value)) {
                return Err(invalid(
                    &name,
                    format!("{what} must be finite, non-negative and at most 1e50, got {value}"),
                ));
            }
        }
        for (what, point) in [("first point", first_point), ("second point", second_point)] {
            if !finite(&point) {
                return Err(invalid(
                    &name,
                    format!("{what} must be finite, got {:?}", [point.x, point.y, point.z]),
                ));
            }
        }
        Ok(ForceElement {
            name,
            kind: ElementKind::SpringDamper {
                first: (first.index(), first_point),
                second: (reference_index(second), second_point),
                stiffness,
                damping,
                rest_length,
            },
        })
    }

    /// A couple `moment(t)` (N m, world axes) on `first`, and its opposite on `second` (the world takes nothing).
    ///
    /// Two balls, a couple between them: each one's angular momentum changes by the couple, in opposite senses.
    ///
    /// ```
    /// use dynamics::mechanism::force_elements::{ForceElement, OfTime};
    /// use dynamics::{Algebra, Body, Mechanism, Pga, Reference, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.1)?;
    /// let mut pair = Mechanism::<Pga>::new();
    /// let (a, b) = (pair.add_body("a", ball)?, pair.add_body("b", ball)?);
    /// let moment = Vector3::new(0.0, 0.0, 0.2); // N m
    /// pair.add_force_element(ForceElement::couple("twist", a, Reference::Body(b), OfTime::Constant(moment)))?;
    /// let at = |x: f64| State::new(&ball, Vector3::new(x, 0.0, 0.0), &UnitQuaternion::identity(), Vector3::zeros(),
    ///     Vector3::zeros());
    /// let rates = pair.rates_at(0.0, &[at(0.0), at(1.0)])?;
    /// let (on_a, on_b) = (Pga::screw_coordinates(rates[0].momentum_rate), Pga::screw_coordinates(rates[1].momentum_rate));
    /// assert!((on_a.t - moment).norm() < 1e-15 && (on_b.t + moment).norm() < 1e-15); // N m
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn couple(name: impl Into<String>, first: BodyId, second: Reference, moment: OfTime<Vector3<f64>>) -> Self {
        ForceElement {
            name: name.into(),
            kind: ElementKind::Couple {
                first: first.index(),
                second: reference_index(second),
                moment,
            },
        }
    }

    /// A generalised force on a one-coordinate joint model: a torque about a revolute joint's axis (N m), a force
    /// along a prismatic joint's (N), `force(t)`; the child receives it, the parent its opposite (an actuator
    /// between them). Its power `τ q̇` is the work it does.
    ///
    /// A ball on a vertical axle (moment of inertia 0.1 kg m²) under 0.5 N m turns up at 5 rad/s²:
    ///
    /// ```
    /// use dynamics::mechanism::force_elements::{ForceElement, OfTime};
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use dynamics::{Body, Mechanism, Pga, Reference};
    /// use nalgebra::{Isometry3, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.5)?; // I = 2/5 m r² = 0.1 kg m²
    /// let mut wheel = Mechanism::<Pga>::new();
    /// let id = wheel.add_body("ball", ball)?;
    /// let axle = JointModel::new("axle", JointKind::Revolute { axis: Vector3::z() }, Isometry3::identity(),
    ///     Isometry3::identity())?;
    /// let joint = wheel.connect(id, Reference::World, axle)?;
    /// wheel.add_force_element(ForceElement::joint_force("motor", joint, OfTime::Constant(0.5)))?;
    /// let states = wheel.states_from_joints(&[0.0], &[0.0])?;
    /// assert!((wheel.joint_accelerations(0.0, &states)?[0] - 5.0).abs() < 1e-12); // rad/s²
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn joint_force(name: impl Into<String>, joint: JointId, force: OfTime<f64>) -> Self {
        ForceElement {
            name: name.into(),
            kind: ElementKind::JointForce {
                joint: joint.index(),
                force,
            },
        }
    }

    /// Viscous damping on every coordinate of a joint model, `τ = −c q̇` (c in N m s/rad or N s/m, finite and
    /// non-negative): the URDF `<dynamics damping>`.
    ///
    /// The ball on its axle (0.1 kg m²) spinning at 2 rad/s, damped by 0.1 N m s/rad, slows at 2 rad/s²:
    ///
    /// ```
    /// use dynamics::mechanism::force_elements::ForceElement;
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use dynamics::{Body, Mechanism, Pga, Reference};
    /// use nalgebra::{Isometry3, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.5)?;
    /// let mut wheel = Mechanism::<Pga>::new();
    /// let id = wheel.add_body("ball", ball)?;
    /// let axle = JointModel::new("axle", JointKind::Revolute { axis: Vector3::z() }, Isometry3::identity(),
    ///     Isometry3::identity())?;
    /// let joint = wheel.connect(id, Reference::World, axle)?;
    /// wheel.add_force_element(ForceElement::joint_damping("bearing", joint, 0.1)?)?;
    /// let states = wheel.states_from_joints(&[0.0], &[2.0])?;
    /// assert!((wheel.joint_accelerations(0.0, &states)?[0] + 2.0).abs() < 1e-12); // rad/s²
    /// assert!(ForceElement::<Pga>::joint_damping("bearing", joint, -0.1).is_err());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn joint_damping(name: impl Into<String>, joint: JointId, coefficient: f64) -> Result<Self, ConstraintError> {
        let name = name.into();
        if !(coefficient.is_finite() && (0.0..=MAX_PARAMETER).contains(&coefficient)) {
            return Err(invalid(
                &name,
                format!("damping must be finite, non-negative and at most 1e50, got {coefficient}"),
            ));
        }
        Ok(ForceElement {
            name,
            kind: ElementKind::JointDamping {
                joint: joint.index(),
                coefficient,
            },
        })
    }

    /// A controller: generalised forces on every joint coordinate from the joint-space state (a PD controller,
    /// computed torque). The law returns one number per velocity coordinate of [`crate::JointSpace`]; a wrong count
    /// or a value that is not finite is an error naming the controller at that evaluation.
    ///
    /// A pendulum held at 0.5 rad by a PD controller with gravity compensation:
    ///
    /// ```
    /// use std::sync::Arc;
    /// use dynamics::mechanism::force_elements::{ForceElement, JointState};
    /// use dynamics::joint_models::{JointKind, JointModel};
    /// use dynamics::{Body, Force, Mechanism, Pga, Reference};
    /// use nalgebra::{DVector, Isometry3, Vector3};
    ///
    /// let rod = Body::rod(1.0, 1.0, 1e-3)?;
    /// let mut arm = Mechanism::<Pga>::new();
    /// let link = arm.add_body("link", rod)?;
    /// arm.add_force(link, Force::gravity())?;
    /// let hinge = JointModel::new("shoulder", JointKind::Revolute { axis: Vector3::x() }, Isometry3::identity(),
    ///     Isometry3::translation(0.0, 0.0, 0.5))?;
    /// arm.connect(link, Reference::World, hinge)?;
    /// let hold = move |state: &JointState<'_, Pga>| {
    ///     let gravity = state.bias_forces().expect("bias forces");
    ///     DVector::from_element(1, gravity[0] + 50.0 * (0.5 - state.positions[0]) - 10.0 * state.velocities[0])
    /// };
    /// arm.add_force_element(ForceElement::controller("hold", Arc::new(hold)))?;
    /// let at_target = arm.states_from_joints(&[0.5], &[0.0])?;
    /// assert!(arm.joint_accelerations(0.0, &at_target)?[0].abs() < 1e-12); // rad/s²: held
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn controller(name: impl Into<String>, law: ControlLaw<A>) -> Self {
        ForceElement {
            name: name.into(),
            kind: ElementKind::Controller(law),
        }
    }

    /// Any wrench between two bodies: `wrench(t, first state, second state)` is the world wrench on `first`, the
    /// second (`None`: the world) receives the opposite. Its power is the work it does.
    ///
    /// A force of 3 N along the line from one ball to the other, pulling them together:
    ///
    /// ```
    /// use std::sync::Arc;
    /// use dynamics::mechanism::force_elements::ForceElement;
    /// use dynamics::{Algebra, Body, Mechanism, Pga, Reference, ScrewCoordinates, State};
    /// use nalgebra::{UnitQuaternion, Vector3};
    ///
    /// let ball = Body::sphere(1.0, 0.1)?;
    /// let mut pair = Mechanism::<Pga>::new();
    /// let (a, b) = (pair.add_body("a", ball)?, pair.add_body("b", ball)?);
    /// let pull = Arc::new(|_t: f64, first: &State<Pga>, second: Option<&State<Pga>>| {
    ///     let (p, q) = (first.pose().0, second.expect("a body").pose().0);
    ///     let force = (q - p).normalize() * 3.0; // N, along the line through both centres
    ///     Pga::screw(ScrewCoordinates { l: force, t: p.cross(&force) })
    /// });
    /// pair.add_force_element(ForceElement::between("pull", a, Reference::Body(b), pull))?;
    /// let at = |x: f64| State::new(&ball, Vector3::new(x, 0.0, 0.0), &UnitQuaternion::identity(), Vector3::zeros(),
    ///     Vector3::zeros());
    /// let rates = pair.rates_at(0.0, &[at(0.0), at(2.0)])?;
    /// let (on_a, on_b) = (Pga::screw_coordinates(rates[0].momentum_rate), Pga::screw_coordinates(rates[1].momentum_rate));
    /// assert!((on_a.l - Vector3::new(3.0, 0.0, 0.0)).norm() < 1e-15 && (on_a.l + on_b.l).norm() < 1e-15); // N
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn between(name: impl Into<String>, first: BodyId, second: Reference, wrench: WrenchBetween<A>) -> Self {
        ForceElement {
            name: name.into(),
            kind: ElementKind::Between {
                first: first.index(),
                second: reference_index(second),
                wrench,
            },
        }
    }

    /// The element's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Whether it is an actuator (a joint force or a controller), which the bias forces h leave out.
    pub fn is_actuator(&self) -> bool {
        matches!(self.kind, ElementKind::JointForce { .. } | ElementKind::Controller(_))
    }
}
