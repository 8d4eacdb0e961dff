//! The equations of motion (SPEC §5), and the interface integrators step through.
//!
//! ```text
//! Ω_b = ~R Ω R,  Ḃ = M⁻¹[Ω_b],  dR/dt = −½ R Ḃ,  dΩ/dt = W_world (+ R F ~R for a reaction F)
//! ```

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::body::Body;
use crate::forces::Force;
use crate::motor;
use crate::state::State;

/// What the integrators need at one state: the body-frame velocity Ḃ (so `dR/dt = −½RḂ`, and Lie
/// group methods can use Ḃ directly) and the world momentum rate `dΩ/dt`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rates<A: Algebra> {
    pub body_velocity: A::Screw,
    pub momentum_rate: A::Screw,
}

impl<A: Algebra> Rates<A> {
    /// `dR/dt = −½ R Ḃ`.
    #[inline]
    pub fn motor_rate(&self, motor: A::Motor) -> A::Motor {
        A::motor_times_screw(motor, self.body_velocity) * -0.5
    }
}

/// The rates in the body frame, for integrators that carry the body momentum `Ω_b = ~RΩR` within a step:
/// `dΩ_b/dt = Ḃ × Ω_b + W_b` (SPEC §5) with `W_b = ~R W R` the body view of the resultant wrench.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyRates<A: Algebra> {
    pub body_velocity: A::Screw,
    pub body_wrench: A::Screw,
}

/// A system the integrators can step: its rates, and what to do after each step.
pub trait Dynamics<A: Algebra> {
    /// Ḃ and dΩ/dt at time `t`.
    fn rates(&self, t: f64, state: &State<A>) -> Rates<A>;

    /// Ḃ and `W_b` at time `t` for the motor R and body momentum `Ω_b`. By default the world state
    /// `(R, RΩ_b~R)` goes through [`Dynamics::rates`] and the wrench comes back to the body frame (two
    /// sandwiches); systems that work in the body frame anyway override it.
    fn body_rates(&self, t: f64, motor: A::Motor, body_momentum: A::Screw) -> BodyRates<A> {
        let world = State {
            motor,
            momentum: to_world::<A>(motor, body_momentum),
        };
        let rates = self.rates(t, &world);
        BodyRates {
            body_velocity: rates.body_velocity,
            body_wrench: body_wrench::<A>(motor, rates.momentum_rate),
        }
    }

    /// Called after every step: by default, renormalise the motor (SPEC §2, §10). Constrained
    /// systems also project onto the constraint manifold here.
    fn after_step(&self, _t: f64, state: State<A>) -> State<A> {
        State {
            motor: motor::normalise::<A>(state.motor),
            momentum: state.momentum,
        }
    }

    /// Total energy (kinetic + potential), for diagnostics.
    fn energy(&self, state: &State<A>) -> f64;
}

/// The body view `~RΩR` of a world screw, through the motor's rigid map on screw coordinates
/// ([`motor::ScrewFrame`]).
pub(crate) fn to_body<A: Algebra>(motor: A::Motor, world: A::Screw) -> A::Screw {
    A::screw(motor::ScrewFrame::of::<A>(motor).to_body(&A::screw_coordinates(world)))
}

/// The world view `RΩ_b~R` of a body screw.
pub(crate) fn to_world<A: Algebra>(motor: A::Motor, body: A::Screw) -> A::Screw {
    A::screw(motor::ScrewFrame::of::<A>(motor).to_world(&A::screw_coordinates(body)))
}

/// The body view `~RWR` of a world wrench; a free body's wrench is exactly zero, and skipping its sandwich
/// saves four sandwiches per generic step.
pub(crate) fn body_wrench<A: Algebra>(motor: A::Motor, world: A::Screw) -> A::Screw {
    let zero = A::screw(ScrewCoordinates::default());
    if world == zero {
        zero
    } else {
        to_body::<A>(motor, world)
    }
}

/// One rigid body under external forces, no constraints.
#[derive(Clone, Debug)]
pub struct FreeBody<A: Algebra> {
    pub body: Body,
    pub forces: Vec<Force<A>>,
}

impl<A: Algebra> FreeBody<A> {
    pub fn new(body: Body) -> Self {
        FreeBody {
            body,
            forces: Vec::new(),
        }
    }

    pub fn with_force(mut self, force: Force<A>) -> Self {
        self.forces.push(force);
        self
    }

    /// The resultant external wrench, world frame.
    pub fn external_wrench(&self, t: f64, state: &State<A>) -> A::Screw {
        self.forces.iter().fold(A::screw(Default::default()), |total, force| {
            total + force.wrench(&self.body, t, state)
        })
    }
}

impl<A: Algebra> Dynamics<A> for FreeBody<A> {
    #[inline]
    fn rates(&self, t: f64, state: &State<A>) -> Rates<A> {
        Rates {
            body_velocity: state.body_velocity(&self.body),
            momentum_rate: self.external_wrench(t, state),
        }
    }

    /// `Ḃ = M⁻¹[Ω_b]` straight from the body momentum, and a force-free body's zero wrench without a sandwich.
    fn body_rates(&self, t: f64, motor: A::Motor, body_momentum: A::Screw) -> BodyRates<A> {
        let body_velocity = self.body.velocity::<A>(body_momentum);
        if self.forces.is_empty() {
            return BodyRates {
                body_velocity,
                body_wrench: A::screw(ScrewCoordinates::default()),
            };
        }
        let world = State {
            motor,
            momentum: to_world::<A>(motor, body_momentum),
        };
        BodyRates {
            body_velocity,
            body_wrench: body_wrench::<A>(motor, self.external_wrench(t, &world)),
        }
    }

    fn energy(&self, state: &State<A>) -> f64 {
        state.kinetic_energy(&self.body)
            + self
                .forces
                .iter()
                .map(|f| f.potential_energy(&self.body, state))
                .sum::<f64>()
    }
}
