//! Hamiltonian splittings of a free body (`docs/theory.md` §10): every sub-step the exact flow of one piece of the
//! Hamiltonian, so the energy error of a free or gravitating body stays bounded over long times.

use crate::algebra::{Algebra, ScrewCoordinates};
use crate::exponential::exp;
use crate::forces::Force;
use crate::integrate::error::SplittingError;
use crate::integrate::methods::SplittingMethod;
use crate::motion::FreeBody;
use crate::motor::body_from_central;
use crate::state::State;

/// A [`FreeBody`] checked to admit a splitting integrator: its Hamiltonian is the kinetic energy
/// `Σ Lᵢ²/2Iᵢ + |p|²/2m` (body-frame angular momentum about the centre of mass, linear momentum) plus
/// forces that depend on the configuration only.
///
/// The kinetic pieces have exact flows that leave the momentum Ω_c unchanged: `Lᵢ²/2Iᵢ` turns the body
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
    /// let drag = Force::Custom(Arc::new(|_t, state: &dynamics::State<Pga>| state.momentum_about_origin() * -0.1));
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
pub(super) fn step_splitting<A: Algebra>(
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
pub(super) fn strang<A: Algebra>(splitting: &KineticSplitting<'_, A>, t: f64, state: State<A>, h: f64) -> State<A> {
    let system = splitting.system;
    let kick = |state: State<A>, at: f64| {
        if system.forces.is_empty() {
            state
        } else {
            State {
                central_momentum: state.central_momentum + system.central_wrench(at, &state) * (0.5 * h),
                ..state
            }
        }
    };
    let drifted = drift(system, splitting.axis_order, kick(state, t), h);
    kick(drifted, t + h)
}

/// The kinetic flow over `h`: `a(½h) b(½h) c(h) b(½h) a(½h)` rotations about body axes, then the translation.
pub(super) fn drift<A: Algebra>(system: &FreeBody<A>, axis_order: [usize; 3], state: State<A>, h: f64) -> State<A> {
    let [a, b, c] = axis_order;
    let mut motor = state.motor;
    for (axis, fraction) in [(a, 0.5), (b, 0.5), (c, 1.0), (b, 0.5), (a, 0.5)] {
        let body_momentum = A::screw_coordinates(body_from_central::<A>(motor, state.central_momentum));
        let mut angular = nalgebra::Vector3::zeros();
        angular[axis] = body_momentum.t[axis] / system.body.moments()[axis];
        let velocity = A::screw(ScrewCoordinates {
            l: angular,
            t: nalgebra::Vector3::zeros(),
        });
        motor = A::compose(motor, exp::<A>(velocity * (-0.5 * fraction * h)));
    }
    let body_momentum = A::screw_coordinates(body_from_central::<A>(motor, state.central_momentum));
    let velocity = A::screw(ScrewCoordinates {
        l: nalgebra::Vector3::zeros(),
        t: body_momentum.l / system.body.mass(),
    });
    State {
        motor: A::compose(motor, exp::<A>(velocity * (-0.5 * h))),
        central_momentum: state.central_momentum,
    }
}
