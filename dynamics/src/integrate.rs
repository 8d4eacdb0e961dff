//! Fixed-step integrators over any [`Dynamics`]. Adaptive stepping would wrap [`step`] with an
//! embedded error estimate (e.g. RK4 step doubling) and choose `dt` per step; it is not needed by the
//! reference scenes, whose work-precision sweeps fix `dt`.

use crate::algebra::Algebra;
use crate::motion::{Dynamics, Rates};
use crate::state::State;

/// The integration method, chosen per simulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Classic RK4 on (R, Ω) treated as vectors, then renormalisation of R (the paper's method).
    Rk4,
}

impl Method {
    pub const ALL: [Method; 1] = [Method::Rk4];

    pub fn name(self) -> &'static str {
        match self {
            Method::Rk4 => "RK4",
        }
    }
}

/// The time derivative `(dR/dt, dΩ/dt)` of `(R, Ω)` at one state.
struct Derivative<A: Algebra> {
    motor: A::Motor,
    momentum: A::Screw,
}

fn derivative<A: Algebra, D: Dynamics<A> + ?Sized>(dynamics: &D, t: f64, state: &State<A>) -> Derivative<A> {
    let rates: Rates<A> = dynamics.rates(t, state);
    Derivative {
        motor: rates.motor_rate(state.motor),
        momentum: rates.momentum_rate,
    }
}

/// `y + h·k`.
fn advance<A: Algebra>(state: &State<A>, slope: &Derivative<A>, h: f64) -> State<A> {
    State {
        motor: state.motor + slope.motor * h,
        momentum: state.momentum + slope.momentum * h,
    }
}

fn rk4<A: Algebra, D: Dynamics<A> + ?Sized>(dynamics: &D, t: f64, y: &State<A>, dt: f64) -> State<A> {
    let half = 0.5 * dt;
    let k1 = derivative(dynamics, t, y);
    let k2 = derivative(dynamics, t + half, &advance(y, &k1, half));
    let k3 = derivative(dynamics, t + half, &advance(y, &k2, half));
    let k4 = derivative(dynamics, t + dt, &advance(y, &k3, dt));
    let sixth = dt / 6.0;
    State {
        motor: y.motor + (k1.motor + k2.motor * 2.0 + k3.motor * 2.0 + k4.motor) * sixth,
        momentum: y.momentum + (k1.momentum + k2.momentum * 2.0 + k3.momentum * 2.0 + k4.momentum) * sixth,
    }
}

/// One step of `method` from `(t, state)` to `t + dt`, followed by [`Dynamics::after_step`].
pub fn step<A: Algebra, D: Dynamics<A> + ?Sized>(
    method: Method,
    dynamics: &D,
    t: f64,
    state: &State<A>,
    dt: f64,
) -> State<A> {
    let next = match method {
        Method::Rk4 => rk4(dynamics, t, state, dt),
    };
    dynamics.after_step(t + dt, next)
}
