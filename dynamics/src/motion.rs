//! The equations of motion (SPEC §5), and the interface integrators step through.
//!
//! ```text
//! Ω_b = ~R Ω R,  Ḃ = M⁻¹[Ω_b],  dR/dt = −½ R Ḃ,  dΩ/dt = W_world (+ R F ~R for a reaction F)
//! ```

use crate::algebra::Algebra;
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

/// A system the integrators can step: its rates, and what to do after each step.
pub trait Dynamics<A: Algebra> {
    /// Ḃ and dΩ/dt at time `t`.
    fn rates(&self, t: f64, state: &State<A>) -> Rates<A>;

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

    fn energy(&self, state: &State<A>) -> f64 {
        state.kinetic_energy(&self.body)
            + self
                .forces
                .iter()
                .map(|f| f.potential_energy(&self.body, state))
                .sum::<f64>()
    }
}
