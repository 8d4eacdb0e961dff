//! The exponential of a screw and the principal logarithm of a motor, for either algebra.
//!
//! Both come from the compiler: each algebra declares `fn exp_line(b: Line) -> Motor = exp(b);` and
//! `fn log_motor(m: Motor) -> Line = log(m);` in its `algebra!` block, which emits them in closed form
//! (`ga_codegen::transcendental`: with λ = ⟨B²⟩₀ = −θ², `exp(B) = c + s B + s ½(B∧B) + d ½⟨(B∧B)B⟩₂`,
//! c = cos θ, s = sin θ / θ, d = (c − s)/λ, by series near θ = 0, so pure translations are exact). What is
//! left here is the choice of branch: a motor and its negative are the same rigid motion, and the dynamics
//! wants the logarithm with the smaller rotation.

use crate::algebra::{Algebra, MotorCoordinates};

/// `exp(B)` for a screw `B = a·l + b·t` ([`Algebra::exp`]).
#[inline]
pub fn exp<A: Algebra>(screw: A::Screw) -> A::Motor {
    A::exp(screw)
}

/// The principal `log(M)` of a unit motor: the screw B with `exp(B) = ±M` and rotation part
/// `|a| ≤ π/2` (M or −M, whichever has the non-negative scalar part, through [`Algebra::log`]).
pub fn log<A: Algebra>(motor: A::Motor) -> A::Screw {
    let m = A::motor_coordinates(motor);
    if m.scalar < 0.0 {
        let negated = MotorCoordinates {
            scalar: -m.scalar,
            l: -m.l,
            t: -m.t,
            pseudoscalar: -m.pseudoscalar,
        };
        return A::log(A::motor(negated));
    }
    A::log(motor)
}
